//! Convergence study: solve a scenario on a sequence of meshes and measure the
//! relative energy-norm error against a reference solution on a fine mesh.
//!
//! For each level, the solution `u^h` is carried onto the reference mesh by P1
//! interpolation ([`crate::fem::transfer`]: exact for nested meshes) and the error
//! `‖u_ref − u^h‖_E / ‖u_ref‖_E` is computed with the energy norm of the paper's example
//! ([`crate::assembly::norms::energy_norm`], the small-strain Hooke operator of the
//! material). The paper's mesh parameter `h` is the element *area*; the element edge
//! (square side) is reported too, with the observed orders between consecutive levels in
//! both.
//!
//! With nested iteration, a level starts from the previous level's solution interpolated
//! onto its mesh (the result does not depend on the start beyond the solver tolerance).
//!
//! The tables of a study (Markdown and CSV) are written by [`crate::io::study_table`].

use crate::assembly::norms::energy_norm_by_cell;
use crate::error::{Error, Result};
use crate::fem::transfer::interpolate;
use crate::problem::Problem;
use crate::scenario::Scenario;
use crate::solver::{solve_observed, OuterProgress, Solution};
use serde::Serialize;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

/// One level of a study.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Level {
    /// Squares along x.
    pub n: usize,
    /// Element area (the paper's h; the element volume in 3D); on a graded mesh the mean
    /// over the cells.
    pub h_area: f64,
    /// Element edge (square side along x); on a graded mesh the mean, side / n.
    pub h_edge: f64,
    /// Number of DOFs.
    pub dofs: usize,
    /// Relative energy-norm error against the reference.
    pub error: f64,
    /// Observed order in h (area) from the previous level (None for the first, and where
    /// an error is zero).
    pub order_area: Option<f64>,
    /// Observed order in the edge length from the previous level.
    pub order_edge: Option<f64>,
    /// Outer iterations.
    pub outer: usize,
    /// Newton steps.
    pub newton: usize,
    /// Whether the solve converged.
    pub converged: bool,
    /// Solve time (s).
    pub seconds: f64,
}

/// A study of one scenario.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Study {
    /// Label of the case.
    pub label: String,
    /// Reference resolution (squares along x).
    pub reference_n: usize,
    /// DOFs of the reference.
    pub reference_dofs: usize,
    /// Whether the reference solve converged.
    pub reference_converged: bool,
    /// Reference solve time (s).
    pub reference_seconds: f64,
    /// Energy norm of the reference solution.
    pub reference_norm: f64,
    /// The levels.
    pub levels: Vec<Level>,
}

/// Progress events of a study, for a progress display.
#[derive(Clone, Debug, PartialEq)]
pub enum Progress {
    /// Solving a level (`None`: the reference) of the case `label`.
    Solving {
        /// The case.
        label: String,
        /// Squares along x.
        n: usize,
        /// Whether it is the reference.
        reference: bool,
    },
    /// A solve finished.
    Solved {
        /// Seconds.
        seconds: f64,
    },
}

/// Settings of a study.
#[derive(Clone, Debug, PartialEq)]
pub struct StudySettings {
    /// Levels (squares along x), increasing.
    pub levels: Vec<usize>,
    /// Reference resolution, larger than every level.
    pub reference: usize,
    /// Start each level from the previous one's solution.
    pub nested_iteration: bool,
}

impl Default for StudySettings {
    fn default() -> Self {
        StudySettings {
            levels: vec![4, 8, 16, 32, 64, 128],
            reference: 512,
            nested_iteration: true,
        }
    }
}

/// Observed order `ln(e₀/e₁) / ln(h₀/h₁)` between two levels; `None` where it is undefined
/// (an error of zero: the level is exact to rounding, there is no rate to observe).
fn order(e0: f64, e1: f64, h0: f64, h1: f64) -> Option<f64> {
    let p = (e0 / e1).ln() / (h0 / h1).ln();
    (e0 > 0.0 && e1 > 0.0 && p.is_finite()).then_some(p)
}

/// Runs the study of `scenario` (a generated rectangle) under the label `label`.
///
/// # Errors
/// [`Error::Scenario`] if the scenario is not a generated rectangle, a level is invalid, or
/// the reference solution is zero (no load: the relative error is undefined, nothing to
/// measure); any error of the solves.
pub fn run(
    scenario: &Scenario,
    label: &str,
    settings: &StudySettings,
    progress: &mut dyn FnMut(Progress),
) -> Result<Study> {
    run_interruptible(scenario, label, settings, progress, &AtomicBool::new(false))
}

/// [`run`], interrupted once another thread raises `stop`: the solve under way returns
/// [`Error::Interrupted`] within one Newton step (see
/// [`crate::solver::solve_interruptible`]), and so does the study.
///
/// # Errors
/// As [`run`], and [`Error::Interrupted`].
pub fn run_interruptible(
    scenario: &Scenario,
    label: &str,
    settings: &StudySettings,
    progress: &mut dyn FnMut(Progress),
    stop: &AtomicBool,
) -> Result<Study> {
    run_observed(scenario, label, settings, progress, stop, &|_| {})
}

/// [`run_interruptible`] that hands every outer iteration of every solve to `observe`
/// (see [`crate::solver::solve_observed`]), for a progress display within a solve.
///
/// # Errors
/// As [`run_interruptible`].
pub fn run_observed(
    scenario: &Scenario,
    label: &str,
    settings: &StudySettings,
    progress: &mut dyn FnMut(Progress),
    stop: &AtomicBool,
    observe: &dyn Fn(&OuterProgress),
) -> Result<Study> {
    if settings.levels.is_empty() {
        return Err(Error::Scenario {
            file: scenario.source.clone(),
            field: "levels".into(),
            value: "[]".into(),
            allowed: "at least one level".into(),
        });
    }
    if settings.levels.windows(2).any(|w| w[1] <= w[0])
        || settings.levels.iter().any(|&n| n >= settings.reference)
    {
        return Err(Error::Scenario {
            file: scenario.source.clone(),
            field: "levels".into(),
            value: format!("{:?} (reference {})", settings.levels, settings.reference),
            allowed: "strictly increasing levels, all below the reference".into(),
        });
    }
    progress(Progress::Solving {
        label: label.into(),
        n: settings.reference,
        reference: true,
    });
    let solver = scenario.settings()?;
    let reference = scenario
        .with_resolution(settings.reference)?
        .into_problem()?;
    let t = Instant::now();
    let ref_sol = solve_observed(
        &reference,
        &solver,
        reference.initial_displacement(),
        stop,
        observe,
    )?;
    let reference_seconds = t.elapsed().as_secs_f64();
    progress(Progress::Solved {
        seconds: reference_seconds,
    });
    let hookes: Vec<_> = reference
        .materials
        .iter()
        .map(|m| m.elasticity.small_strain_hooke(reference.mesh.dim()))
        .collect();
    let hooke = |c: usize| hookes[reference.cell_material(c)];
    let reference_norm = energy_norm_by_cell(&reference.mesh, &hooke, &ref_sol.u);
    if !(reference_norm > 0.0 && reference_norm.is_finite()) {
        return Err(Error::Scenario {
            file: scenario.source.clone(),
            field: "loads".into(),
            value: format!("‖u_ref‖_E = {reference_norm} (the reference solution)"),
            allowed: "a scenario that deforms the body (a load, a body force or a non-zero \
                      prescribed displacement): with a zero reference solution the relative \
                      error ‖u_ref − u^h‖_E / ‖u_ref‖_E and its orders are undefined, so there \
                      is nothing to measure"
                .into(),
        });
    }
    let mut levels: Vec<Level> = Vec::new();
    let mut previous: Option<(Problem, Solution)> = None;
    for &n in &settings.levels {
        progress(Progress::Solving {
            label: label.into(),
            n,
            reference: false,
        });
        let problem = scenario.with_resolution(n)?.into_problem()?;
        let start = match (&previous, settings.nested_iteration) {
            (Some((p, s)), true) => interpolate(&p.mesh, &s.u, &problem.mesh),
            _ => problem.initial_displacement(),
        };
        let t = Instant::now();
        let sol = solve_observed(&problem, &solver, start, stop, observe)?;
        let seconds = t.elapsed().as_secs_f64();
        progress(Progress::Solved { seconds });
        let on_ref = interpolate(&problem.mesh, &sol.u, &reference.mesh);
        let diff: Vec<f64> = ref_sol.u.iter().zip(&on_ref).map(|(a, b)| a - b).collect();
        let error = energy_norm_by_cell(&reference.mesh, &hooke, &diff)
            / reference_norm.max(f64::MIN_POSITIVE);
        let (lo, hi) = problem.mesh.bounding_box();
        let h_edge = (hi[0] - lo[0]) / n as f64;
        // Element measure (area in 2D, volume in 3D): all cells of a uniform generated mesh
        // are equal; on a graded one this is the mean, which refinement scales the same way.
        let h_area = problem.mesh.measure() / problem.mesh.n_cells() as f64;
        let (order_area, order_edge) = match levels.last() {
            Some(p) => (
                order(p.error, error, p.h_area, h_area),
                order(p.error, error, p.h_edge, h_edge),
            ),
            None => (None, None),
        };
        levels.push(Level {
            n,
            h_area,
            h_edge,
            dofs: sol.report.n_dofs,
            error,
            order_area,
            order_edge,
            outer: sol.report.outer.len(),
            newton: sol.report.newton.len(),
            converged: sol.report.converged,
            seconds,
        });
        previous = Some((problem, sol));
    }
    Ok(Study {
        label: label.into(),
        reference_n: settings.reference,
        reference_dofs: ref_sol.report.n_dofs,
        reference_converged: ref_sol.report.converged,
        reference_seconds,
        reference_norm,
        levels,
    })
}
