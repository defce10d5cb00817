//! The `PETSC_OPTIONS` environment variable reaches the PETSc linear solver and wins over
//! `[solver.petsc] options`, as PETSc's command line wins over its option files. (A test
//! file of its own: the variable is the process's, and this is its only test.)
#![cfg(feature = "petsc")]
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::scenario::Scenario;
use hemicontact::solver::{solve, LinearSolver};
use std::path::Path;

#[test]
fn petsc_options_variable_wins_over_the_scenario() {
    // Set before PETSc is initialized and before any thread reads the environment.
    std::env::set_var("PETSC_OPTIONS", "-ksp_type preonly -pc_type cholesky");
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/paper3d.toml");
    let scenario = Scenario::from_file(&path)
        .unwrap()
        .with_resolution(6)
        .unwrap();
    let problem = scenario.into_problem().unwrap();
    let mut settings = scenario.settings().unwrap();
    settings.linear_solver = LinearSolver::Petsc;
    settings.petsc.options = "-pc_type hypre".into();
    let petsc = solve(&problem, &settings).unwrap();
    assert!(petsc.report.converged, "{}", petsc.report.message);
    assert!(
        petsc
            .report
            .linear_solver
            .starts_with("petsc (ksp preonly, pc cholesky"),
        "{}",
        petsc.report.linear_solver
    );
    settings.linear_solver = LinearSolver::Direct;
    let direct = solve(&problem, &settings).unwrap();
    let d = petsc
        .u
        .iter()
        .zip(&direct.u)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let scale = direct.u.iter().map(|v| v.abs()).fold(0.0, f64::max);
    assert!(d <= 1e-8 * scale, "{d:e} against {scale:e}");
}
