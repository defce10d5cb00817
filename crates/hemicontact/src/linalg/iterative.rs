//! The iterative linear solver: conjugate gradients preconditioned by the geometric
//! multigrid V-cycle of [`Multigrid`], to the requested relative residual. No factorization
//! of the fine system is ever formed, so memory stays proportional to the matrix.
//!
//! The multigrid operators are rebuilt from the matrix when its values changed (beyond
//! 1e-12 relative to the largest entry of the last set-up); the set-up counts as a
//! "factorization" in [`SolveStats`].

use super::direct::UNCHANGED;
use super::solver::{SolveRequest, SolveStats, SpdSolver};
use super::Multigrid;
use crate::assembly::SystemPattern;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use std::time::Instant;

/// Iteration cap of multigrid-preconditioned CG. Measured counts are far below (tens at
/// most); reaching the cap means the preconditioner failed.
pub const ITERATIVE_MAX_ITERATIONS: usize = 500;

/// Multigrid-preconditioned conjugate gradients; see the module documentation.
#[derive(Debug)]
pub struct MultigridCg {
    /// Grids, prolongations and operators.
    multigrid: Multigrid,
    /// Matrix values of the current operators (empty: none yet).
    factored: Vec<f64>,
}

impl MultigridCg {
    /// Builds the grids and prolongations for `pattern`, the reduced system of `mesh` with
    /// equation numbers `equations` (no operators yet: the first solve sets them up).
    pub fn new(mesh: &Mesh, equations: &[u32], pattern: &SystemPattern) -> Self {
        MultigridCg {
            multigrid: Multigrid::new(mesh, equations, pattern),
            factored: Vec::new(),
        }
    }

    /// Estimated peak memory (bytes) of a solve with the iterative solver on a mesh of
    /// dimension `dim` with `nodes` nodes and `cells` cells:
    /// [`crate::resources::estimate_tetrahedra_iterative`] for tetrahedra. For triangles no
    /// iterative model is calibrated; the direct solver's model, which adds a Cholesky
    /// factor, bounds it.
    pub fn memory_estimate(dim: usize, nodes: u64, cells: u64) -> u64 {
        if dim == 3 {
            crate::resources::estimate_tetrahedra_iterative(nodes as f64, cells as f64)
        } else {
            crate::resources::estimate_mesh(dim, nodes, cells)
        }
    }
}

impl SpdSolver for MultigridCg {
    fn kind(&self) -> super::LinearSolver {
        super::LinearSolver::Iterative
    }

    /// # Errors
    /// [`Error::Breakdown`] if CG does not reach `request.eta` within
    /// [`ITERATIVE_MAX_ITERATIONS`] iterations or breaks down, and the errors of
    /// [`Multigrid::update`].
    fn solve(
        &mut self,
        _pattern: &SystemPattern,
        values: &[f64],
        b: &[f64],
        x: &mut [f64],
        request: &SolveRequest,
    ) -> Result<SolveStats> {
        let mut stats = SolveStats::default();
        let scale = self.factored.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let unchanged = !self.factored.is_empty()
            && values
                .iter()
                .zip(&self.factored)
                .all(|(a, c)| (a - c).abs() <= UNCHANGED * scale);
        if !unchanged {
            let t = Instant::now();
            self.factored.clear();
            self.multigrid.update(values)?;
            self.factored.extend_from_slice(values);
            stats.factorization_time = t.elapsed().as_secs_f64();
            stats.refactorized = true;
        }
        let t = Instant::now();
        let eta = request.eta;
        let outcome = self.multigrid.solve(b, x, eta, ITERATIVE_MAX_ITERATIONS)?;
        stats.solve_time = t.elapsed().as_secs_f64();
        if !outcome.converged {
            return Err(Error::Breakdown(format!(
                "multigrid-preconditioned CG did not reach the relative residual {eta:e} in \
                 {} iterations (reached {:e}); try [solver] linear_solver = \"direct\"",
                outcome.iterations, outcome.relative_residual
            )));
        }
        stats.iterations = outcome.iterations;
        Ok(stats)
    }

    fn level_sizes(&self) -> Vec<usize> {
        self.multigrid.level_sizes()
    }
}
