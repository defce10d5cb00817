//! Sparse Cholesky `A = L Lᵀ` with the symbolic analysis done once per pattern.
//!
//! [`Cholesky::analyze`] computes the fill-reducing ordering (see [`super::ordering`]) and
//! faer's symbolic factorization (elimination tree, supernodes, factor pattern), and
//! allocates the factor values and all workspace. [`Cholesky::factorize`] then refills the
//! numeric factor for new matrix values on the same pattern without allocating, and
//! [`Cholesky::solve_in_place`] solves with it. The matrix is given by its upper triangle
//! on a [`SystemPattern`].
//!
//! With the nested-dissection ordering, a large 2D system is factorized as two
//! substructures in parallel and a dense Schur complement on their separator
//! ([`super::substructures`]) when that adds little work and two threads are there to run
//! them; otherwise as one matrix by faer's supernodal Cholesky.

use super::llt::{factor_storage, numeric_llt};
use super::ordering::{top_bisection, Ordering};
use super::substructures::Substructured;
use crate::assembly::SystemPattern;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LltRef, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

/// How [`Cholesky::analyze_with`] lays out the factorization.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Layout {
    /// Substructures where they add little work and rayon's pool has two threads or more
    /// (see the module documentation), else the whole matrix.
    #[default]
    Auto,
    /// The whole matrix, by faer's supernodal Cholesky.
    Whole,
    /// Two substructures and their separator wherever the nested dissection splits the
    /// nodes, whatever the extra work (for tests); the whole matrix where it does not.
    Substructures,
}

/// A sparse Cholesky factorization on a fixed pattern; see the module documentation.
pub struct Cholesky {
    factor: Factor,
    n: usize,
    factorized: bool,
}

/// The two layouts of the factor.
enum Factor {
    Whole(Box<Whole>),
    Substructured(Box<Substructured>),
}

/// The whole matrix factorized by faer, in the fill-reducing order.
struct Whole {
    symbolic: SymbolicCholesky<usize>,
    l_values: Vec<f64>,
    par: Par,
    factor_stack: MemBuffer,
    solve_stack: MemBuffer,
}

impl std::fmt::Debug for Cholesky {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut d = f.debug_struct("Cholesky");
        d.field("n", &self.n)
            .field("nnz_factor", &self.nnz_factor());
        if let Factor::Substructured(s) = &self.factor {
            d.field("substructures", s);
        }
        d.finish()
    }
}

/// Equation permutation (`perm[new] = old`) from a node order of a mesh of dimension `d`:
/// each node's free equations, in component order, at the node's position.
fn equation_permutation(
    d: usize,
    equations: &[u32],
    pattern: &SystemPattern,
    node_order: &[u32],
) -> Vec<usize> {
    let mut perm = Vec::with_capacity(pattern.n());
    for &v in node_order {
        for i in 0..d {
            let e = equations[d * v as usize + i];
            if e != u32::MAX {
                perm.push(e as usize);
            }
        }
    }
    debug_assert_eq!(perm.len(), pattern.n());
    perm
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
    /// using `par` for the numeric factorization and solves; the layout is chosen
    /// ([`Layout::Auto`]).
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
        Self::analyze_with(mesh, equations, pattern, ordering, par, Layout::Auto)
    }

    /// [`Cholesky::analyze`] with the layout `layout`.
    ///
    /// # Errors
    /// [`Error::OutOfMemory`] if the factor or its workspace cannot be allocated.
    pub fn analyze_with(
        mesh: &Mesh,
        equations: &[u32],
        pattern: &SystemPattern,
        ordering: Ordering,
        par: Par,
        layout: Layout,
    ) -> Result<Self> {
        let n = pattern.n();
        let wanted = match layout {
            Layout::Auto => rayon::current_num_threads() >= 2,
            Layout::Whole => false,
            Layout::Substructures => true,
        };
        // The fill-reducing node order; with nested dissection, its first bisection is
        // also where the substructures split.
        let d = mesh.dim();
        let (ptr, adj) = mesh.node_adjacency();
        let free = free_nodes(mesh, equations);
        let node_order = match ordering {
            Ordering::NestedDissection => {
                match top_bisection(mesh.coords(), d, &ptr, &adj, free.clone()) {
                    None => free,
                    Some(bisection) => {
                        if wanted {
                            let forced = layout == Layout::Substructures;
                            if let Some(sub) =
                                Substructured::new(pattern, equations, d, &bisection, par, forced)?
                            {
                                return Ok(Cholesky {
                                    factor: Factor::Substructured(Box::new(sub)),
                                    n,
                                    factorized: false,
                                });
                            }
                        }
                        bisection.into_order()
                    }
                }
            }
            Ordering::Amd => amd_nodes(&ptr, &adj, &free)?,
        };
        let perm = equation_permutation(d, equations, pattern, &node_order);
        Ok(Cholesky {
            factor: Factor::Whole(Box::new(Whole::analyze(pattern, &perm, par)?)),
            n,
            factorized: false,
        })
    }

    /// Whether the factorization is laid out as two substructures and their separator.
    pub fn is_substructured(&self) -> bool {
        matches!(self.factor, Factor::Substructured(_))
    }

    /// Number of stored entries of the factor L (with substructures: both substructures'
    /// factors and the dense blocks of the separator).
    pub fn nnz_factor(&self) -> usize {
        match &self.factor {
            Factor::Whole(w) => w.l_values.len(),
            Factor::Substructured(s) => s.nnz_factor(),
        }
    }

    /// Number of equations.
    pub fn n(&self) -> usize {
        self.n
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
        match &mut self.factor {
            Factor::Whole(w) => w.factorize(pattern, values)?,
            Factor::Substructured(s) => s.factorize(values)?,
        }
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
        assert_eq!(rhs.len(), self.n);
        match &mut self.factor {
            Factor::Whole(w) => w.solve_in_place(rhs),
            Factor::Substructured(s) => s.solve_in_place(rhs),
        }
    }
}

/// The nodes of `mesh` with at least one free equation.
fn free_nodes(mesh: &Mesh, equations: &[u32]) -> Vec<u32> {
    let d = mesh.dim();
    (0..mesh.n_nodes() as u32)
        .filter(|&v| (0..d).any(|i| equations[d * v as usize + i] != u32::MAX))
        .collect()
}

impl Whole {
    /// The symbolic analysis of `pattern` in the equation order `perm` (`perm[new] = old`).
    fn analyze(pattern: &SystemPattern, perm: &[usize], par: Par) -> Result<Self> {
        let n = pattern.n();
        let mut perm_inv = vec![0usize; n];
        for (new, &old) in perm.iter().enumerate() {
            perm_inv[old] = new;
        }
        let a =
            SymbolicSparseColMatRef::new_checked(n, n, pattern.col_ptr(), None, pattern.row_idx());
        let p = faer::perm::PermRef::new_checked(perm, &perm_inv, n);
        let symbolic = factorize_symbolic_cholesky(
            a,
            Side::Upper,
            SymmetricOrdering::Custom(p),
            Default::default(),
        )
        .map_err(|e| Error::OutOfMemory(format!("symbolic Cholesky analysis: {e:?}")))?;
        let (l_values, factor_stack) = factor_storage(&symbolic, par)?;
        let solve_stack = MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, par))
            .map_err(|_| Error::OutOfMemory("Cholesky solve workspace".into()))?;
        Ok(Whole {
            symbolic,
            l_values,
            par,
            factor_stack,
            solve_stack,
        })
    }

    fn factorize(&mut self, pattern: &SystemPattern, values: &[f64]) -> Result<()> {
        let n = pattern.n();
        let sym =
            SymbolicSparseColMatRef::new_checked(n, n, pattern.col_ptr(), None, pattern.row_idx());
        numeric_llt(
            &self.symbolic,
            &mut self.l_values,
            SparseColMatRef::new(sym, values),
            self.par,
            &mut self.factor_stack,
        )
    }

    fn solve_in_place(&mut self, rhs: &mut [f64]) {
        let n = rhs.len();
        let llt = LltRef::<'_, usize, f64>::new(&self.symbolic, &self.l_values);
        llt.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(rhs, n, 1),
            self.par,
            MemStack::new(&mut self.solve_stack),
        );
    }
}
