//! Sparse linear algebra: fill-reducing orderings and the Cholesky factorization with the
//! symbolic analysis done once per pattern and numeric refactorization per solve.

pub mod cholesky;
pub mod ordering;

pub use cholesky::Cholesky;
pub use ordering::Ordering;
