//! Sparse linear algebra of the Newton systems: one linear-solver abstraction
//! ([`SpdSolver`], chosen and prepared by the setting [`LinearSolver`]) with a direct
//! implementation (sparse Cholesky with fill-reducing orderings, symbolic analysis once
//! per pattern, numeric refactorization when the matrix changed) and an iterative one
//! (conjugate gradients preconditioned by geometric multigrid, for large 3D systems), both
//! built on one preconditioned conjugate-gradient routine ([`pcg`]).

pub mod choice;
pub mod cholesky;
pub mod csr;
pub mod direct;
pub mod iterative;
pub mod lanczos;
mod llt;
pub mod multigrid;
pub mod ordering;
pub mod pcg;
#[cfg(feature = "petsc")]
pub mod petsc;
pub mod solver;
pub mod substructures;

pub use choice::{PetscSettings, PrepareOptions, HAS_PETSC};
pub use cholesky::{Cholesky, Layout};
pub use direct::DirectSolver;
pub use iterative::{MultigridCg, ITERATIVE_MAX_ITERATIONS};
pub use multigrid::Multigrid;
pub use ordering::Ordering;
pub use solver::{LinearSolver, SolveRequest, SolveStats, SpdSolver};
