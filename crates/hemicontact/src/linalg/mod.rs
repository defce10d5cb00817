//! Sparse linear algebra: fill-reducing orderings and the Cholesky factorization with the
//! symbolic analysis done once per pattern and numeric refactorization per solve, and a
//! geometric multigrid preconditioner for conjugate gradients (large 3D systems).

pub mod cholesky;
pub mod multigrid;
pub mod ordering;

pub use cholesky::Cholesky;
pub use multigrid::Multigrid;
pub use ordering::Ordering;
