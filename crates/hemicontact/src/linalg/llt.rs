//! faer's numeric Cholesky factorization `L Lᵀ` on a symbolic analysis: the storage of the
//! factor and its workspace, and the refill for new matrix values. Shared by the
//! whole-matrix factorization ([`super::cholesky`]) and the two substructures
//! ([`super::substructures`]).

use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::SymbolicCholesky;
use faer::sparse::SparseColMatRef;
use faer::{Par, Side};

/// The values of the factor of `symbolic` and the workspace of its numeric factorization.
///
/// # Errors
/// [`Error::OutOfMemory`] if either cannot be allocated.
pub(super) fn factor_storage<I: faer::Index>(
    symbolic: &SymbolicCholesky<I>,
    par: Par,
) -> Result<(Vec<f64>, MemBuffer)> {
    let len = symbolic.len_val();
    let mut l_values = Vec::new();
    l_values
        .try_reserve_exact(len)
        .map_err(|_| Error::OutOfMemory(format!("Cholesky factor of {len} entries")))?;
    l_values.resize(len, 0.0);
    let stack =
        MemBuffer::try_new(symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()))
            .map_err(|_| Error::OutOfMemory("Cholesky workspace".into()))?;
    Ok((l_values, stack))
}

/// faer's numeric factorization `L Lᵀ` of the matrix `a` (upper triangle) into `l_values`
/// on the analysis `symbolic`, with its workspace `stack`.
///
/// # Errors
/// [`Error::NotPositiveDefinite`] if a pivot is not positive.
pub(super) fn numeric_llt<I: faer::Index>(
    symbolic: &SymbolicCholesky<I>,
    l_values: &mut [f64],
    a: SparseColMatRef<'_, I, f64>,
    par: Par,
    stack: &mut MemBuffer,
) -> Result<()> {
    symbolic
        .factorize_numeric_llt::<f64>(
            l_values,
            a,
            Side::Upper,
            Default::default(),
            par,
            MemStack::new(stack),
            Default::default(),
        )
        .map_err(|e| Error::NotPositiveDefinite {
            context: format!("{e:?}"),
        })?;
    Ok(())
}
