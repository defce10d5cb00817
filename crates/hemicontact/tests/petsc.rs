//! The PETSc linear solver (`[solver] linear_solver = "petsc"`, cargo feature `petsc`):
//! every committed scenario gives the direct solver's answer to 1e-8, certified; PETSc's
//! options choose the Krylov method and preconditioner (a factorization, hypre, MUMPS);
//! options PETSc refuses are reported naming the field; the preconditioner is kept across
//! changed matrices while it pays, and set up for every one when told to.
#![cfg(feature = "petsc")]
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::loading::load_path;
use hemicontact::scenario::Scenario;
use hemicontact::solver::{solve, LinearSolver, Solution, SolverSettings};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

fn scenarios_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios")
}

/// Solves `scenario` as `hemicontact solve` does (its load path when it has one: the last
/// step) with `settings`.
fn solve_scenario(scenario: &Scenario, settings: &SolverSettings) -> Solution {
    let problem = scenario.into_problem().unwrap();
    match scenario.load_factors().unwrap() {
        None => solve(&problem, settings).unwrap(),
        Some(factors) => {
            let stop = AtomicBool::new(false);
            let steps = load_path(&problem, settings, &factors, &stop, &|_, _| {}, &mut |_| {
                Ok(())
            })
            .unwrap();
            steps.into_iter().last().unwrap().solution
        }
    }
}

/// `max |a − b| / max |b|`.
fn max_rel_diff(a: &[f64], b: &[f64]) -> f64 {
    let d = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    d / b.iter().map(|y| y.abs()).fold(0.0, f64::max)
}

/// Direct and PETSc solves of a committed scenario: both certified, the same displacement
/// to 1e-8 (relative, maximum norm), the same reactions, and PETSc's Krylov iterations
/// reported per Newton step.
fn agrees_with_direct(file: &str) {
    let mut scenario = Scenario::from_file(&scenarios_dir().join(file)).unwrap();
    if file == "hertz3d-force.toml" {
        // Its committed 107k DOFs cost minutes on two cores; at n = 16 (15k DOFs) the
        // agreement is the same (its table in docs/distributed.md is at both).
        scenario = scenario.with_resolution(16).unwrap();
    }
    let mut settings = scenario.settings().unwrap();
    settings.linear_solver = LinearSolver::Direct;
    let direct = solve_scenario(&scenario, &settings);
    settings.linear_solver = LinearSolver::Petsc;
    let petsc = solve_scenario(&scenario, &settings);
    assert!(direct.report.converged, "{file}: {}", direct.report.message);
    assert!(petsc.report.converged, "{file}: {}", petsc.report.message);
    assert!(
        petsc
            .report
            .linear_solver
            .starts_with("petsc (ksp cg, pc gamg"),
        "{}",
        petsc.report.linear_solver
    );
    assert!(petsc.report.newton.iter().all(|s| s.pcg_iterations > 0));
    let e = max_rel_diff(&petsc.u, &direct.u);
    let r = max_rel_diff(&petsc.reactions, &direct.reactions);
    eprintln!(
        "{file}: {} equations, max relative difference u {e:.1e}, reactions {r:.1e}; \
         Newton steps {} / {}, set-ups {} / factorizations {}",
        petsc.report.n_equations,
        petsc.report.newton.len(),
        direct.report.newton.len(),
        petsc.report.timings.n_factorizations,
        direct.report.timings.n_factorizations
    );
    assert!(e <= 1e-8, "{file}: displacement differs by {e:e}");
    assert!(r <= 1e-8, "{file}: reactions differ by {r:e}");
}

/// The scenarios compared below: every file of `scenarios/`.
const SCENARIOS: [&str; 19] = [
    "cattaneo-mindlin.toml",
    "cattaneo-spheres.toml",
    "fault.toml",
    "half-disc.toml",
    "hertz2d.toml",
    "hertz3d-force.toml",
    "hertz3d.toml",
    "layered-block.toml",
    "paper-elastic.toml",
    "paper-ideal.toml",
    "paper-no-locking.toml",
    "paper-signorini.toml",
    "paper.toml",
    "paper3d-paper-gap.toml",
    "paper3d.toml",
    "punch-on-block.toml",
    "sliding-indenter.toml",
    "two-cylinders.toml",
    "two-spheres.toml",
];

#[test]
fn the_list_is_every_committed_scenario() {
    let mut files: Vec<String> = std::fs::read_dir(scenarios_dir())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|f| f.ends_with(".toml"))
        .collect();
    files.sort();
    assert_eq!(files, SCENARIOS);
}

macro_rules! agreement {
    ($($name:ident => $file:literal,)*) => {$(
        #[test]
        fn $name() {
            agrees_with_direct($file);
        }
    )*};
}

agreement! {
    cattaneo_mindlin => "cattaneo-mindlin.toml",
    cattaneo_spheres => "cattaneo-spheres.toml",
    fault => "fault.toml",
    half_disc => "half-disc.toml",
    hertz2d => "hertz2d.toml",
    hertz3d_force => "hertz3d-force.toml",
    hertz3d => "hertz3d.toml",
    layered_block => "layered-block.toml",
    punch_on_block => "punch-on-block.toml",
    paper_elastic => "paper-elastic.toml",
    paper_ideal => "paper-ideal.toml",
    paper_no_locking => "paper-no-locking.toml",
    paper_signorini => "paper-signorini.toml",
    paper => "paper.toml",
    paper3d_paper_gap => "paper3d-paper-gap.toml",
    paper3d => "paper3d.toml",
    sliding_indenter => "sliding-indenter.toml",
    two_cylinders => "two-cylinders.toml",
    two_spheres => "two-spheres.toml",
}

/// `scenarios/paper3d.toml` at a small resolution with `[solver.petsc] options`.
fn paper3d_with(options: &str, pcg_iterations: usize) -> (Solution, Solution) {
    let scenario = Scenario::from_file(&scenarios_dir().join("paper3d.toml"))
        .unwrap()
        .with_resolution(8)
        .unwrap();
    let problem = scenario.into_problem().unwrap();
    let mut settings = scenario.settings().unwrap();
    settings.linear_solver = LinearSolver::Direct;
    let direct = solve(&problem, &settings).unwrap();
    settings.linear_solver = LinearSolver::Petsc;
    settings.petsc.options = options.into();
    settings.newton.pcg_iterations = pcg_iterations;
    let petsc = solve(&problem, &settings).unwrap();
    assert!(direct.report.converged, "{}", direct.report.message);
    assert!(
        petsc.report.converged,
        "{options}: {}",
        petsc.report.message
    );
    let e = max_rel_diff(&petsc.u, &direct.u);
    assert!(e <= 1e-8, "{options}: displacement differs by {e:e}");
    (petsc, direct)
}

/// PETSc's own sparse Cholesky (`preonly`): one "iteration" and a set-up for every Newton
/// step (a kept factor would be a wrong solve, so it is never kept), and the direct answer.
#[test]
fn options_choose_a_factorization() {
    let (petsc, _) = paper3d_with("-ksp_type preonly -pc_type cholesky", 100);
    assert!(
        petsc
            .report
            .linear_solver
            .starts_with("petsc (ksp preonly, pc cholesky"),
        "{}",
        petsc.report.linear_solver
    );
    assert!(petsc.report.newton.iter().all(|s| s.refactorized));
    assert!(petsc.report.newton.iter().all(|s| s.pcg_iterations == 1));
}

/// MUMPS and hypre's BoomerAMG through the options, as a user of PETSc would choose them.
#[test]
fn options_reach_mumps_and_hypre() {
    let (mumps, _) = paper3d_with(
        "-ksp_type preonly -pc_type cholesky -pc_factor_mat_solver_type mumps",
        100,
    );
    assert!(mumps.report.linear_solver.ends_with("mumps)"));
    let (hypre, _) = paper3d_with("-pc_type hypre", 100);
    assert_eq!(hypre.report.linear_solver, "petsc (ksp cg, pc hypre)");
}

/// GAMG's set-up costs tens of CG iterations: it is kept across changed matrices while it
/// pays (fewer set-ups than Newton steps), and with `newton.pcg_iterations = 0` every
/// changed matrix is set up. The answer is the direct one in both cases.
#[test]
fn the_preconditioner_is_kept_while_it_pays() {
    let (kept, _) = paper3d_with("", 100);
    let steps = kept.report.newton.len();
    let setups = kept.report.timings.n_factorizations;
    assert!(
        setups * 3 <= steps,
        "{setups} set-ups in {steps} Newton steps"
    );
    let (fresh, _) = paper3d_with("", 0);
    assert!(fresh.report.newton.iter().all(|s| s.refactorized));
}

/// Options PETSc refuses end the solve with an error naming the field and quoting PETSc.
#[test]
fn refused_options_name_the_field() {
    let scenario = Scenario::from_file(&scenarios_dir().join("paper3d.toml"))
        .unwrap()
        .with_resolution(4)
        .unwrap();
    let problem = scenario.into_problem().unwrap();
    let mut settings = scenario.settings().unwrap();
    settings.linear_solver = LinearSolver::Petsc;
    settings.petsc.options = "-pc_type nonsense".into();
    let e = solve(&problem, &settings).unwrap_err().to_string();
    assert!(e.contains("petsc.options") && e.contains("nonsense"), "{e}");
}

/// Scotch, the partitioner `mpirun` splits the mesh with, on the node graph of the Gmsh
/// half-disc, whose own numbering divides badly (contiguous ranges of 4: one range's
/// cells, owned and ghost, are 2.26 times an even share): its 4 parts hold within 10 % of a
/// quarter of the nodes each, and the most cells around one part are at most 1.4 times an
/// even share (less than the ranges give); the same parts every call; malformed graphs are
/// refused, not handed to Scotch.
#[test]
fn scotch_splits_a_gmsh_mesh_into_compact_balanced_parts() {
    let problem = Scenario::from_file(&scenarios_dir().join("half-disc.toml"))
        .unwrap()
        .into_problem()
        .unwrap();
    let mesh = problem.mesh();
    let (ptr, adj) = mesh.node_adjacency();
    let adjncy: Vec<usize> = adj.iter().map(|&w| w as usize).collect();
    let n_parts = 4;
    let parts = hemicontact_petsc::partition(&ptr, &adjncy, n_parts).unwrap();
    let n = mesh.n_nodes();
    let mut sizes = vec![0usize; n_parts];
    for &p in &parts {
        sizes[p] += 1;
    }
    let share = n as f64 / n_parts as f64;
    assert!(
        sizes
            .iter()
            .all(|&s| (s as f64 - share).abs() <= 0.1 * share),
        "{sizes:?}"
    );
    // The most cells around one part's nodes, over an even share of the cells.
    let load = |part_of: &dyn Fn(usize) -> usize| {
        (0..n_parts)
            .map(|p| {
                (0..mesh.n_cells())
                    .filter(|&c| mesh.cell(c).iter().any(|&v| part_of(v as usize) == p))
                    .count()
            })
            .max()
            .unwrap() as f64
            * n_parts as f64
            / mesh.n_cells() as f64
    };
    let scotch = load(&|v| parts[v]);
    let ranges = load(&|v| v * n_parts / n);
    eprintln!(
        "half-disc in {n_parts}: Scotch parts {sizes:?} (checksum {}), most cells around a part \
         {scotch:.2} × an even share (contiguous ranges: {ranges:.2})",
        parts.iter().enumerate().map(|(v, &p)| v * p).sum::<usize>()
    );
    assert!(
        scotch <= 1.4 && scotch < ranges,
        "{scotch} against {ranges}"
    );
    assert_eq!(
        parts,
        hemicontact_petsc::partition(&ptr, &adjncy, n_parts).unwrap()
    );
    // A self-loop and a neighbour out of range.
    assert!(hemicontact_petsc::partition(&[0, 1], &[0], 2).is_err());
    assert!(hemicontact_petsc::partition(&[0, 1, 1], &[5], 2).is_err());
}
