//! Sparse Cholesky `A = L Lᵀ` with the symbolic analysis done once per pattern.
//!
//! [`Cholesky::analyze`] computes the fill-reducing ordering (see [`super::ordering`]) and
//! faer's symbolic factorization (elimination tree, supernodes, factor pattern), and
//! allocates the factor values and all workspace. [`Cholesky::factorize`] then refills the
//! numeric factor for new matrix values on the same pattern without allocating, and
//! [`Cholesky::solve_in_place`] solves with it. The matrix is given by its upper triangle
//! on a [`SystemPattern`].

use super::ordering::{nested_dissection, Ordering};
use crate::assembly::SystemPattern;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LltRef, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

/// A sparse Cholesky factorization on a fixed pattern; see the module documentation.
pub struct Cholesky {
    symbolic: SymbolicCholesky<usize>,
    l_values: Vec<f64>,
    par: Par,
    factor_stack: MemBuffer,
    solve_stack: MemBuffer,
    factorized: bool,
}

impl std::fmt::Debug for Cholesky {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Cholesky")
            .field("n", &self.symbolic.nrows())
            .field("nnz_factor", &self.l_values.len())
            .finish()
    }
}

/// Equation permutation (`perm[new] = old`) from a node ordering of `mesh`: each node's free
/// equations, in component order, at the node's position.
fn equation_permutation(
    mesh: &Mesh,
    equations: &[u32],
    pattern: &SystemPattern,
    ordering: Ordering,
) -> Result<Vec<usize>> {
    let d = mesh.dim();
    let (ptr, adj) = mesh.node_adjacency();
    let free_nodes: Vec<u32> = (0..mesh.n_nodes() as u32)
        .filter(|&v| (0..d).any(|i| equations[d * v as usize + i] != u32::MAX))
        .collect();
    let node_order = match ordering {
        Ordering::NestedDissection => nested_dissection(mesh.coords(), d, &ptr, &adj, free_nodes),
        Ordering::Amd => amd_nodes(&ptr, &adj, &free_nodes)?,
    };
    let mut perm = Vec::with_capacity(pattern.n());
    for v in node_order {
        for i in 0..d {
            let e = equations[d * v as usize + i];
            if e != u32::MAX {
                perm.push(e as usize);
            }
        }
    }
    debug_assert_eq!(perm.len(), pattern.n());
    Ok(perm)
}

/// Approximate minimum degree ordering of the subgraph induced by `nodes`.
fn amd_nodes(ptr: &[usize], adj: &[u32], nodes: &[u32]) -> Result<Vec<u32>> {
    let mut local = vec![usize::MAX; ptr.len() - 1];
    for (k, &v) in nodes.iter().enumerate() {
        local[v as usize] = k;
    }
    let n = nodes.len();
    let mut col_ptr = Vec::with_capacity(n + 1);
    let mut row_idx = Vec::new();
    col_ptr.push(0usize);
    for &v in nodes {
        let j = local[v as usize];
        let mut rows: Vec<usize> = adj[ptr[v as usize]..ptr[v as usize + 1]]
            .iter()
            .map(|&w| local[w as usize])
            .filter(|&i| i < j)
            .collect();
        rows.push(j);
        rows.sort_unstable();
        row_idx.extend_from_slice(&rows);
        col_ptr.push(row_idx.len());
    }
    let a = SymbolicSparseColMatRef::new_checked(n, n, &col_ptr, None, &row_idx);
    let mut perm = vec![0usize; n];
    let mut perm_inv = vec![0usize; n];
    let mut mem = MemBuffer::try_new(faer::sparse::linalg::amd::order_scratch::<usize>(
        n,
        row_idx.len(),
    ))
    .map_err(|_| Error::OutOfMemory("AMD ordering workspace".into()))?;
    faer::sparse::linalg::amd::order(
        &mut perm,
        &mut perm_inv,
        a,
        Default::default(),
        MemStack::new(&mut mem),
    )
    .map_err(|e| Error::OutOfMemory(format!("AMD ordering: {e:?}")))?;
    Ok(perm.into_iter().map(|k| nodes[k]).collect())
}

impl Cholesky {
    /// Symbolic analysis of `pattern` (the reduced system of `mesh` with equation numbers
    /// `equations`, see [`crate::fem::dofs::DofMap::equations`]) with the given ordering,
    /// using `par` for the numeric factorization and solves.
    ///
    /// # Errors
    /// [`Error::OutOfMemory`] if the factor or its workspace cannot be allocated.
    pub fn analyze(
        mesh: &Mesh,
        equations: &[u32],
        pattern: &SystemPattern,
        ordering: Ordering,
        par: Par,
    ) -> Result<Self> {
        let n = pattern.n();
        let perm = equation_permutation(mesh, equations, pattern, ordering)?;
        let mut perm_inv = vec![0usize; n];
        for (new, &old) in perm.iter().enumerate() {
            perm_inv[old] = new;
        }
        let a =
            SymbolicSparseColMatRef::new_checked(n, n, pattern.col_ptr(), None, pattern.row_idx());
        let p = faer::perm::PermRef::new_checked(&perm, &perm_inv, n);
        let symbolic = factorize_symbolic_cholesky(
            a,
            Side::Upper,
            SymmetricOrdering::Custom(p),
            Default::default(),
        )
        .map_err(|e| Error::OutOfMemory(format!("symbolic Cholesky analysis: {e:?}")))?;
        let len = symbolic.len_val();
        let mut l_values = Vec::new();
        l_values
            .try_reserve_exact(len)
            .map_err(|_| Error::OutOfMemory(format!("Cholesky factor of {len} entries")))?;
        l_values.resize(len, 0.0);
        let factor_stack = MemBuffer::try_new(
            symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()),
        )
        .map_err(|_| Error::OutOfMemory("Cholesky workspace".into()))?;
        let solve_stack = MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, par))
            .map_err(|_| Error::OutOfMemory("Cholesky solve workspace".into()))?;
        Ok(Cholesky {
            symbolic,
            l_values,
            par,
            factor_stack,
            solve_stack,
            factorized: false,
        })
    }

    /// Number of stored entries of the factor L.
    pub fn nnz_factor(&self) -> usize {
        self.l_values.len()
    }

    /// Number of equations.
    pub fn n(&self) -> usize {
        self.symbolic.nrows()
    }

    /// Numeric factorization of the matrix with upper-triangle `values` on `pattern`
    /// (the pattern given to [`Cholesky::analyze`]).
    ///
    /// # Errors
    /// [`Error::NotPositiveDefinite`] if a pivot is not positive, [`Error::Breakdown`] if a
    /// value is not finite.
    ///
    /// # Panics
    /// If `values.len() != pattern.nnz()`.
    #[track_caller]
    pub fn factorize(&mut self, pattern: &SystemPattern, values: &[f64]) -> Result<()> {
        assert_eq!(values.len(), pattern.nnz());
        self.factorized = false;
        if let Some(k) = values.iter().position(|v| !v.is_finite()) {
            return Err(Error::Breakdown(format!(
                "matrix entry {k} is {}",
                values[k]
            )));
        }
        let n = pattern.n();
        let sym =
            SymbolicSparseColMatRef::new_checked(n, n, pattern.col_ptr(), None, pattern.row_idx());
        let a = SparseColMatRef::new(sym, values);
        self.symbolic
            .factorize_numeric_llt::<f64>(
                &mut self.l_values,
                a,
                Side::Upper,
                Default::default(),
                self.par,
                MemStack::new(&mut self.factor_stack),
                Default::default(),
            )
            .map_err(|e| Error::NotPositiveDefinite {
                context: format!("{e:?}"),
            })?;
        self.factorized = true;
        Ok(())
    }

    /// Solves `A x = b` in place (`rhs` holds b on entry, x on exit).
    ///
    /// # Panics
    /// If the matrix has not been factorized successfully, or `rhs.len() != n`.
    #[track_caller]
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) {
        assert!(self.factorized, "solve before a successful factorization");
        let n = self.n();
        assert_eq!(rhs.len(), n);
        let llt = LltRef::<'_, usize, f64>::new(&self.symbolic, &self.l_values);
        llt.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(rhs, n, 1),
            self.par,
            MemStack::new(&mut self.solve_stack),
        );
    }
}
