//! Wall-clock time per phase of a solve ([`Timings`]), which the set-up, the Newton steps
//! and the linear solves add to and the report carries.

use serde::Serialize;

/// Wall-clock time per phase (s).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Timings {
    /// Sparsity pattern and DOF map.
    pub pattern: f64,
    /// Fill-reducing ordering and symbolic factorization (iterative linear solver: the
    /// multigrid grids and prolongations).
    pub symbolic: f64,
    /// Assembly of energy, gradient and Hessian (all Newton steps).
    pub assembly: f64,
    /// Numeric factorizations (all Newton steps); with the iterative linear solver, the
    /// multigrid set-ups (Galerkin operators, smoother intervals, coarsest factor).
    pub factorization: f64,
    /// Triangular solves and PCG iterations (all Newton steps).
    pub solve: f64,
    /// Number of numeric factorizations (iterative linear solver: multigrid set-ups).
    pub n_factorizations: usize,
    /// Line searches (energy evaluations).
    pub line_search: f64,
    /// Whole solve, end to end.
    pub total: f64,
}
