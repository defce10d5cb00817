//! The solution method: a fixed-pattern system prepared once, and a globalized Newton
//! method on the total energy.
//!
//! The program reads like the method: [`solve`] builds the DOF map and the sparsity pattern,
//! runs the symbolic analysis once, then Newton iterates (assemble, refactorize, solve,
//! line search) until the residual is small, and returns the solution with its report.

pub mod newton;
pub mod report;
pub mod system;

pub use newton::NewtonSettings;
pub use report::{NewtonStep, SolveReport, Timings};
pub use system::System;

use crate::error::Result;
use crate::linalg::Ordering;
use crate::problem::Problem;
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// Solver settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SolverSettings {
    /// Fill-reducing ordering of the sparse Cholesky factorization. Default: nested
    /// dissection, which gives the smallest factor on the meshes measured by
    /// `hemicontact bench`.
    pub ordering: Ordering,
    /// Threads for the factorization (0: all cores). Default 0.
    pub threads: usize,
    /// Newton method settings.
    pub newton: NewtonSettings,
}

impl Default for SolverSettings {
    fn default() -> Self {
        SolverSettings {
            ordering: Ordering::default(),
            threads: 0,
            newton: NewtonSettings::default(),
        }
    }
}

/// A solved (or not converged) problem: displacement, reactions, energy, and the report.
#[derive(Clone, Debug)]
pub struct Solution {
    /// Displacement at every DOF (m), DOF order, length `d · n_nodes`.
    pub u: Vec<f64>,
    /// Reaction forces at prescribed DOFs (N), zero at free DOFs; DOF order.
    pub reactions: Vec<f64>,
    /// Total potential energy at `u` (J).
    pub energy: f64,
    /// What the solver did; `report.converged` says whether `u` is a solution.
    pub report: SolveReport,
}

/// Solves the problem: prepares the system (pattern, symbolic analysis) and runs Newton.
///
/// # Errors
/// Invalid problem data ([`Problem::validate`]), a matrix that is not positive definite
/// (rigid motions not blocked), or memory exhaustion. Non-convergence is not an error: see
/// [`SolveReport::converged`].
pub fn solve(problem: &Problem) -> Result<Solution> {
    let start = Instant::now();
    problem.validate()?;
    let mut system = System::new(problem)?;
    let mut u = problem.prescribed_displacement();
    let mut report = SolveReport::new(&system);
    let outcome = newton::minimize(
        &mut system,
        problem,
        &mut u,
        &problem.solver.newton,
        &mut report,
    );
    report.timings.total = start.elapsed().as_secs_f64();
    outcome?;
    let (energy, reactions) = system.energy_and_reactions(problem, &u);
    Ok(Solution {
        u,
        reactions,
        energy,
        report,
    })
}

/// Builds the rayon parallelism for `threads` (0: all available cores).
pub fn parallelism(threads: usize) -> faer::Par {
    if threads == 1 {
        faer::Par::Seq
    } else {
        faer::Par::rayon(threads)
    }
}
