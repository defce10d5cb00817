//! The iterative linear solver: conjugate gradients preconditioned by the geometric
//! multigrid V-cycle of [`Multigrid`], to the requested relative residual. No factorization
//! of the fine system is ever formed, so memory stays proportional to the matrix.
//!
//! When the matrix changed (beyond 1e-12 relative to the largest entry of the last
//! set-up), the multigrid operators are set up again, in one of two ways:
//! - **lagged** ([`Multigrid::update_fine`]): the fine operator and its smoother from the
//!   new matrix, the coarse operators kept. Between Newton steps the matrix changes only at
//!   contact nodes and locked cells, so the old coarse levels still correct well, and the
//!   Galerkin products, most of a set-up, are saved;
//! - **full** ([`Multigrid::update`]): every level, counted as a "factorization" in
//!   [`SolveStats`].
//!
//! The choice counts iterations, as the direct solver's reuse of a factor does (ski
//! rental): the first solve after a full set-up gives the iterations per decade of residual
//! reduction that a fresh hierarchy needs; each lagged solve pays the iterations beyond
//! that rate, and once they add up to the cost of a full set-up ([`SETUP_COST`] V-cycles)
//! the next changed matrix is set up fully. A lagged solve that does not converge within
//! twice the fresh rate is abandoned for a full set-up and solved again. Counts, not
//! timers, decide, so the results are deterministic.

use super::direct::matrix_unchanged;
use super::solver::{SolveRequest, SolveStats, SpdSolver};
use super::Multigrid;
use crate::assembly::SystemPattern;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use std::time::Instant;

/// Iteration cap of multigrid-preconditioned CG. Measured counts are far below (tens at
/// most); reaching the cap means the preconditioner failed.
pub const ITERATIVE_MAX_ITERATIONS: usize = 500;

/// Cost of a full multigrid set-up (Galerkin products, eigenvalue estimates on every level,
/// coarsest factor) in V-cycles (PCG iterations): measured 5.6 on `paper3d.toml` at n = 24
/// (0.131 s per set-up, 0.0236 s per iteration).
pub const SETUP_COST: f64 = 5.0;

/// Multigrid-preconditioned conjugate gradients; see the module documentation.
#[derive(Debug)]
pub struct MultigridCg {
    /// Grids, prolongations and operators.
    multigrid: Multigrid,
    /// Matrix values of the current operators (empty: none yet).
    factored: Vec<f64>,
    /// PCG iterations per decade of residual reduction of the first solve after the last
    /// full set-up (0: not measured yet).
    fresh_rate: f64,
    /// Iterations beyond that rate spent by lagged solves since the last full set-up.
    rent: f64,
    /// Whether the next changed matrix gets a full set-up.
    setup_next: bool,
}

impl MultigridCg {
    /// Builds the grids and prolongations for `pattern`, the reduced system of `mesh` with
    /// equation numbers `equations` (no operators yet: the first solve sets them up).
    pub fn new(mesh: &Mesh, equations: &[u32], pattern: &SystemPattern) -> Self {
        MultigridCg {
            multigrid: Multigrid::new(mesh, equations, pattern),
            factored: Vec::new(),
            fresh_rate: 0.0,
            rent: 0.0,
            setup_next: false,
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
        let unchanged = !self.factored.is_empty()
            && matrix_unchanged(values.iter().copied().zip(self.factored.iter().copied()));
        let eta = request.eta;
        // Decades of residual reduction asked for (at least one).
        let decades = (1.0 / eta).log10().max(1.0);
        let lagged =
            !unchanged && request.reuse_iterations > 0 && !self.setup_next && self.fresh_rate > 0.0;
        if lagged {
            let t = Instant::now();
            self.factored.clear();
            self.multigrid.update_fine(values)?;
            self.factored.extend_from_slice(values);
            stats.factorization_time = t.elapsed().as_secs_f64();
            let t = Instant::now();
            let expected = self.fresh_rate * decades;
            let cap = (2.0 * expected).ceil() as usize + 2;
            let outcome = self.multigrid.solve(b, x, eta, cap);
            stats.solve_time = t.elapsed().as_secs_f64();
            match outcome {
                Ok(o) if o.converged => {
                    self.rent += (o.iterations as f64 - expected).max(0.0);
                    self.setup_next = self.rent >= SETUP_COST;
                    stats.iterations = o.iterations;
                    return Ok(stats);
                }
                // Not converged, or a curvature breakdown (an indefinite V-cycle from
                // coarse levels too far from the new matrix): set up fully and solve again.
                // A breakdown's iterations are counted as the cap, an upper bound.
                Ok(o) => stats.iterations = o.iterations,
                Err(_) => stats.iterations = cap,
            }
        }
        if !unchanged {
            let t = Instant::now();
            self.factored.clear();
            self.multigrid.update(values)?;
            self.factored.extend_from_slice(values);
            stats.factorization_time += t.elapsed().as_secs_f64();
            stats.refactorized = true;
            self.rent = 0.0;
            self.setup_next = false;
        }
        let t = Instant::now();
        let outcome = self.multigrid.solve(b, x, eta, ITERATIVE_MAX_ITERATIONS)?;
        stats.solve_time += t.elapsed().as_secs_f64();
        if !outcome.converged {
            return Err(Error::Breakdown(format!(
                "multigrid-preconditioned CG did not reach the relative residual {eta:e} in \
                 {} iterations (reached {:e}); try [solver] linear_solver = \"direct\"",
                outcome.iterations, outcome.relative_residual
            )));
        }
        if stats.refactorized {
            self.fresh_rate = outcome.iterations.max(1) as f64 / decades;
        }
        stats.iterations += outcome.iterations;
        Ok(stats)
    }

    fn level_sizes(&self) -> Vec<usize> {
        self.multigrid.level_sizes()
    }
}
