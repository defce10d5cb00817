//! The linear-solver abstraction of the Newton systems `H x = b`: a solver prepared once
//! on a [`SystemPattern`] (symbolic analysis, grids), then asked repeatedly to solve with
//! new matrix values on that pattern to a relative residual.
//!
//! The implementations are [`super::direct::DirectSolver`] (sparse Cholesky, reused while
//! the matrix changes little), [`super::iterative::MultigridCg`]
//! (multigrid-preconditioned conjugate gradients) and, with the cargo feature `petsc`,
//! `super::petsc::PetscSolver` (PETSc's KSP). [`LinearSolver`] (the setting, its values
//! here and its choice in [`super::choice`]) chooses and prepares one of them. A trait
//! object rather than an enum: a new backend is a new type implementing [`SpdSolver`] plus
//! one arm in the setting's `prepare` and `memory_estimate`, and the system holding it does
//! not change.

use super::Cholesky;
use crate::assembly::SystemPattern;
use crate::error::Result;
use serde::{Deserialize, Serialize};

/// How the Newton systems `H x = b` are solved.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LinearSolver {
    /// Sparse Cholesky factorization, reused and used as a PCG preconditioner while the
    /// Hessian changes little (see [`super::direct`]).
    Direct,
    /// Conjugate gradients preconditioned by geometric multigrid
    /// ([`super::multigrid`]) to the Newton forcing term; no factorization of the
    /// fine system is ever formed, so memory stays proportional to the matrix.
    Iterative,
    /// Direct in 2D and in 3D below [`LinearSolver::AUTO_ITERATIVE_EQUATIONS`] equations,
    /// iterative above.
    #[default]
    Auto,
    /// PETSc's Krylov solvers and preconditioners (conjugate gradients with GAMG by
    /// default, any other through [`super::PetscSettings::options`]); needs the cargo
    /// feature `petsc` (see `super::petsc`).
    Petsc,
}

/// What a Newton step asks of the linear solver.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolveRequest {
    /// Relative residual `‖b − H x‖ / ‖b‖` to reach where the solve is iterative (the
    /// forcing term of the inexact Newton method); exact solves ignore it.
    pub eta: f64,
    /// Cap on the conjugate-gradient iterations a solver may spend before giving up on a
    /// stale preconditioner and rebuilding it (the direct solver's reuse of an old factor);
    /// solvers without such a reuse path ignore it.
    pub reuse_iterations: usize,
}

/// How one system was solved, with the time spent (seconds, wall clock).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SolveStats {
    /// Whether the factorization (direct) or the multigrid operators (iterative) were
    /// rebuilt from the new matrix values.
    pub refactorized: bool,
    /// Conjugate-gradient iterations (0: a plain direct solve).
    pub iterations: usize,
    /// Seconds spent rebuilding (numeric factorization, multigrid set-up).
    pub factorization_time: f64,
    /// Seconds spent solving (triangular solves, CG iterations, the test whether the
    /// matrix changed).
    pub solve_time: f64,
}

/// A solver of symmetric positive definite systems on a fixed sparsity pattern.
pub trait SpdSolver: std::fmt::Debug + Send {
    /// Which solver this is: [`LinearSolver::Direct`],
    /// [`LinearSolver::Iterative`] or [`LinearSolver::Petsc`] (never `Auto`).
    fn kind(&self) -> LinearSolver;

    /// Solves `A x = b` for the matrix with upper-triangle `values` on `pattern` (the
    /// pattern the solver was prepared on), updating the solver's internal state
    /// (factor, multigrid operators) as the values require.
    ///
    /// # Errors
    /// [`crate::Error::NotPositiveDefinite`] or [`crate::Error::Breakdown`] when the matrix
    /// cannot be factorized or the iteration fails.
    fn solve(
        &mut self,
        pattern: &SystemPattern,
        values: &[f64],
        b: &[f64],
        x: &mut [f64],
        request: &SolveRequest,
    ) -> Result<SolveStats>;

    /// The solver in words: `direct`, `iterative`, or `petsc (ksp cg, pc gamg)` with the
    /// backend's own method and preconditioner.
    fn describe(&self) -> String {
        format!("{:?}", self.kind()).to_lowercase()
    }

    /// Stored entries of the Cholesky factor (0 without one).
    fn nnz_factor(&self) -> usize {
        0
    }

    /// Equations per multigrid level, finest first (empty without a hierarchy).
    fn level_sizes(&self) -> Vec<usize> {
        Vec::new()
    }

    /// The exact sparse Cholesky factorization, for callers that factorize a matrix of
    /// their own on the pattern (`None` for solvers without one).
    fn cholesky_mut(&mut self) -> Option<&mut Cholesky> {
        None
    }
}
