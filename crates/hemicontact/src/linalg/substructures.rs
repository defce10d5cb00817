//! Sparse Cholesky by two substructures, factorized in parallel.
//!
//! The first bisection of the nested dissection ([`super::ordering::top_bisection`]) splits
//! the equations into two interiors `1` and `2` that no matrix entry joins, and the
//! separator `S` between them:
//!
//! ```text
//!     ⎡ A₁₁   0   A₁ₛ ⎤          ⎡ L₁₁   0    0  ⎤
//! A = ⎢  0   A₂₂  A₂ₛ ⎥ ,   L =  ⎢  0   L₂₂   0  ⎥ ,   Lₛᵢ = Aₛᵢ Lᵢᵢ⁻ᵀ,   Lₛ Lₛᵀ = S,
//!     ⎣ Aₛ₁  Aₛ₂  Aₛₛ ⎦          ⎣ Lₛ₁  Lₛ₂  Lₛ  ⎦
//! ```
//!
//! with the Schur complement `S = Aₛₛ − Aₛ₁ A₁₁⁻¹ A₁ₛ − Aₛ₂ A₂₂⁻¹ A₂ₛ`. Each substructure
//! `i` is factorized on its own, as the sparse matrix `Mᵢ = [Aᵢᵢ Aᵢₛ; Aₛᵢ Aₛₛ]` (its interior
//! in nested-dissection order, the separator last; a principal submatrix of A, so positive
//! definite when A is): its factor holds `Lᵢᵢ`, `Lₛᵢ`, and a last block `Kᵢ` with
//! `Kᵢ Kᵢᵀ = Aₛₛ − Aₛᵢ Aᵢᵢ⁻¹ Aᵢₛ`. The two are independent and run in parallel. Then
//!
//! `S = K₁ K₁ᵀ + K₂ K₂ᵀ − Aₛₛ`,
//!
//! a dense matrix of the separator's size, is factorized densely. The two substructures
//! run side by side on rayon's thread pool (`rayon::join`), whatever the factorization's
//! own thread setting, which governs only the dense blocks. A solve runs them in parallel
//! as well:
//! - forward: `Mᵢ [yᵢ; wᵢ] = …` by the forward substitution of `Mᵢ`'s factor on `[bᵢ; 0]`,
//!   which gives `Lᵢᵢ⁻¹ bᵢ = yᵢ` and `wᵢ = −Kᵢ⁻¹ Lₛᵢ yᵢ`; then `yₛ = Lₛ⁻¹ (bₛ + K₁w₁ + K₂w₂)`;
//! - backward: `xₛ = Lₛ⁻ᵀ yₛ`, and the back substitution of `Mᵢ`'s factor on
//!   `[yᵢ; Kᵢᵀ xₛ]` gives `xᵢ = Lᵢᵢ⁻ᵀ (yᵢ − Lₛᵢᵀ xₛ)`.
//!
//! This is the same factorization as the whole one in the same order, computed in a
//! different sequence: the separator's block is factorized once in each substructure
//! and once more in `S`. The extra work is about `s³` flops for `s` separator equations,
//! small in 2D (a separator of √n nodes) and large in 3D (n^⅔), so
//! [`super::Cholesky::analyze`] chooses substructures only when that work is under a tenth
//! of the factorization's ([`SUBSTRUCTURE_OVERHEAD`]) and rayon's pool has at least two
//! threads (on one, the extra work is all they add). For a given layout the results do not
//! depend on the number of threads; between the two layouts they differ at round-off, as
//! the assembly's sums do between thread counts.

use super::ordering::Bisection;
use crate::assembly::SystemPattern;
use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::sparse::linalg::cholesky::supernodal::{SupernodalLltRef, SymbolicSupernodalCholesky};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Accum, Conj, Mat, MatMut, Par, Side};

/// Largest ratio of the extra work of substructures (`s³` flops for a separator of `s`
/// equations) to the flops of the two substructures' factorizations at which
/// [`super::Cholesky::analyze`] chooses them.
pub const SUBSTRUCTURE_OVERHEAD: f64 = 0.1;

/// Which part of the bisection an equation belongs to.
const SEPARATOR: u8 = 2;

/// One substructure: its interior equations, the sparse factor of `Mᵢ = [Aᵢᵢ Aᵢₛ; Aₛᵢ Aₛₛ]`
/// and the dense last block `Kᵢ` of that factor.
struct Substructure {
    /// Equations of the interior (in the whole system's numbering), in elimination order.
    interior: Vec<usize>,
    /// faer's symbolic factorization of `Mᵢ` (identity ordering: `Mᵢ` is built in order).
    symbolic: SymbolicCholesky<u32>,
    /// Upper triangle of `Mᵢ`: column pointers and row indices (32-bit, as the factor's
    /// structure: half the memory of 64-bit indices).
    col_ptr: Vec<u32>,
    row_idx: Vec<u32>,
    /// For each entry of `Mᵢ`: its position in the whole matrix's values.
    gather: Vec<u32>,
    /// Values of `Mᵢ`.
    values: Vec<f64>,
    /// Values of the factor of `Mᵢ`.
    l_values: Vec<f64>,
    factor_stack: MemBuffer,
    solve_stack: MemBuffer,
    /// `Kᵢ`: the separator's block of the factor, dense lower triangular (`s × s`).
    k: Mat<f64>,
    /// Work vector of length `dim Mᵢ`: `[yᵢ; wᵢ]` between the substitutions.
    work: Vec<f64>,
    /// `Kᵢ wᵢ` after the forward substitution (length s).
    kw: Mat<f64>,
    par: Par,
}

/// The factorization by two substructures; see the module documentation.
pub struct Substructured {
    parts: [Substructure; 2],
    /// Equations of the separator, in elimination order.
    separator: Vec<usize>,
    /// `(row, column, value position)` of the stored entries of `Aₛₛ`'s lower triangle
    /// (dense numbering of the separator).
    separator_entries: Vec<(usize, usize, usize)>,
    /// `Lₛ`: the Cholesky factor of the Schur complement (dense, lower triangle).
    schur: Mat<f64>,
    schur_stack: MemBuffer,
    /// `yₛ`, then `xₛ` (length s).
    ys: Mat<f64>,
    par: Par,
}

impl std::fmt::Debug for Substructured {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Substructured")
            .field(
                "interiors",
                &[self.parts[0].interior.len(), self.parts[1].interior.len()],
            )
            .field("separator", &self.separator.len())
            .finish()
    }
}

/// Flops of a supernodal factorization, `Σ_j c_j²` over its columns with `c_j` the
/// column's entries.
fn factor_flops(symbolic: &SymbolicSupernodalCholesky<u32>) -> f64 {
    let (begin, end) = (symbolic.supernode_begin(), symbolic.supernode_end());
    let mut flops = 0.0;
    for s in 0..symbolic.n_supernodes() {
        let ncols = (end[s] - begin[s]) as usize;
        let below = symbolic.supernode(s).pattern().len();
        for k in 0..ncols {
            let c = (ncols - k + below) as f64;
            flops += c * c;
        }
    }
    flops
}

/// The supernodal analysis inside `symbolic` (a substructure's, which
/// [`Substructure::new`] checked to be supernodal).
fn supernodal(symbolic: &SymbolicCholesky<u32>) -> &SymbolicSupernodalCholesky<u32> {
    match symbolic.raw() {
        SymbolicCholeskyRaw::Supernodal(s) => s,
        SymbolicCholeskyRaw::Simplicial(_) => unreachable!("checked in Substructure::new"),
    }
}

fn out_of_memory(what: &str) -> Error {
    Error::OutOfMemory(what.into())
}

impl Substructure {
    /// The substructure of `interior` (equations, in order) and `separator` on the upper
    /// triangle `pattern` of the whole matrix; `part[e]` tells each equation's part (`me`
    /// for this interior, [`SEPARATOR`], or the other one's).
    fn new(
        pattern: &SystemPattern,
        part: &[u8],
        me: u8,
        interior: Vec<usize>,
        separator: &[usize],
        par: Par,
    ) -> Result<Self> {
        let n_interior = interior.len();
        let m = n_interior + separator.len();
        let mut local = vec![usize::MAX; pattern.n()];
        for (k, &e) in interior.iter().chain(separator).enumerate() {
            local[e] = k;
        }
        // Upper triangle of Mᵢ in its own numbering, by a counting sort on the columns.
        let (col_ptr, row_idx) = (pattern.col_ptr(), pattern.row_idx());
        let local = &local;
        let inside = move |e: usize| part[e] == me || part[e] == SEPARATOR;
        let entries = move || {
            (0..pattern.n())
                .filter(move |&c| inside(c))
                .flat_map(move |c| {
                    (col_ptr[c]..col_ptr[c + 1])
                        .filter(move |&k| inside(row_idx[k]))
                        .map(move |k| (local[row_idx[k]], local[c], k))
                })
        };
        let mut m_col_ptr = vec![0u32; m + 1];
        for (lr, lc, _) in entries() {
            m_col_ptr[lr.max(lc) + 1] += 1;
        }
        for j in 0..m {
            m_col_ptr[j + 1] += m_col_ptr[j];
        }
        let nnz = m_col_ptr[m] as usize;
        let mut next: Vec<usize> = m_col_ptr[..m].iter().map(|&p| p as usize).collect();
        let mut column = vec![(0u32, 0u32); nnz];
        for (lr, lc, k) in entries() {
            let c = lr.max(lc);
            column[next[c]] = (lr.min(lc) as u32, k as u32);
            next[c] += 1;
        }
        for j in 0..m {
            column[m_col_ptr[j] as usize..m_col_ptr[j + 1] as usize].sort_unstable();
        }
        let m_row_idx: Vec<u32> = column.iter().map(|e| e.0).collect();
        let gather: Vec<u32> = column.iter().map(|e| e.1).collect();
        drop(column);
        let sym = SymbolicSparseColMatRef::new_checked(m, m, &m_col_ptr, None, &m_row_idx);
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let symbolic =
            factorize_symbolic_cholesky(sym, Side::Upper, SymmetricOrdering::Identity, params)
                .map_err(|e| Error::OutOfMemory(format!("symbolic Cholesky analysis: {e:?}")))?;
        let SymbolicCholeskyRaw::Supernodal(supernodal) = symbolic.raw() else {
            return Err(Error::Breakdown(
                "a substructure's factorization is not supernodal".into(),
            ));
        };
        let (l_values, factor_stack) = super::llt::factor_storage(&symbolic, par)?;
        let solve_stack = MemBuffer::try_new(supernodal.solve_in_place_scratch::<f64>(1, par))
            .map_err(|_| out_of_memory("Cholesky solve workspace"))?;
        let s = separator.len();
        Ok(Substructure {
            interior,
            symbolic,
            col_ptr: m_col_ptr,
            row_idx: m_row_idx,
            values: vec![0.0; gather.len()],
            gather,
            l_values,
            factor_stack,
            solve_stack,
            k: Mat::zeros(s, s),
            work: vec![0.0; m],
            kw: Mat::zeros(s, 1),
            par,
        })
    }

    fn supernodal(&self) -> &SymbolicSupernodalCholesky<u32> {
        supernodal(&self.symbolic)
    }

    /// Factorizes `Mᵢ` from the whole matrix's `values` and copies out `Kᵢ`.
    fn factorize(&mut self, values: &[f64]) -> Result<()> {
        for (v, &k) in self.values.iter_mut().zip(&self.gather) {
            *v = values[k as usize];
        }
        let m = self.work.len();
        let sym = SymbolicSparseColMatRef::new_checked(m, m, &self.col_ptr, None, &self.row_idx);
        super::llt::numeric_llt(
            &self.symbolic,
            &mut self.l_values,
            SparseColMatRef::new(sym, &self.values),
            self.par,
            &mut self.factor_stack,
        )?;
        // Kᵢ: the columns of the factor at or after the first separator equation.
        let first = self.interior.len();
        let mut k = std::mem::replace(&mut self.k, Mat::new());
        k.fill(0.0);
        let llt = SupernodalLltRef::<'_, u32, f64>::new(self.supernodal(), &self.l_values);
        let symbolic = self.supernodal();
        for sn in 0..symbolic.n_supernodes() {
            let node = llt.supernode(sn);
            let (start, val) = (node.start(), node.val());
            let ncols = val.ncols();
            if start + ncols <= first {
                continue;
            }
            for c in start.max(first)..start + ncols {
                let jc = c - start;
                for r in jc..ncols {
                    k[(start + r - first, c - first)] = val[(r, jc)];
                }
                for (idx, &row) in node.pattern().iter().enumerate() {
                    k[(row as usize - first, c - first)] = val[(ncols + idx, jc)];
                }
            }
        }
        self.k = k;
        Ok(())
    }

    /// Forward substitution on `[bᵢ; 0]` (from the whole right-hand side `b`), leaving
    /// `[yᵢ; wᵢ]` in `work` and `Kᵢ wᵢ` in `kw`.
    fn forward(&mut self, b: &[f64]) {
        let first = self.interior.len();
        for (w, &e) in self.work.iter_mut().zip(&self.interior) {
            *w = b[e];
        }
        self.work[first..].fill(0.0);
        let m = self.work.len();
        let llt = SupernodalLltRef::<'_, u32, f64>::new(supernodal(&self.symbolic), &self.l_values);
        llt.l_solve_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(&mut self.work, m, 1),
            self.par,
            MemStack::new(&mut self.solve_stack),
        );
        let s = m - first;
        let w = faer::MatRef::from_column_major_slice(&self.work[first..], s, 1);
        triangular::matmul(
            self.kw.as_mut(),
            BlockStructure::Rectangular,
            Accum::Replace,
            self.k.as_ref(),
            BlockStructure::TriangularLower,
            w,
            BlockStructure::Rectangular,
            1.0,
            Par::Seq,
        );
    }

    /// Back substitution on `[yᵢ; Kᵢᵀ xₛ]`, leaving `xᵢ` in `work[..interior]`.
    fn backward(&mut self, xs: faer::MatRef<'_, f64>) {
        let first = self.interior.len();
        let m = self.work.len();
        let s = m - first;
        let v = MatMut::from_column_major_slice_mut(&mut self.work[first..], s, 1);
        triangular::matmul(
            v,
            BlockStructure::Rectangular,
            Accum::Replace,
            self.k.transpose(),
            BlockStructure::TriangularUpper,
            xs,
            BlockStructure::Rectangular,
            1.0,
            Par::Seq,
        );
        let llt = SupernodalLltRef::<'_, u32, f64>::new(supernodal(&self.symbolic), &self.l_values);
        llt.l_transpose_solve_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(&mut self.work, m, 1),
            self.par,
            MemStack::new(&mut self.solve_stack),
        );
    }
}

impl Substructured {
    /// The substructures of `bisection` (nodes) for the matrix with upper-triangle pattern
    /// `pattern` and node equations `equations` (`d` per node, `u32::MAX` where fixed).
    /// Returns `Ok(None)` when substructures cannot be used (an empty part, a matrix entry
    /// joining the two interiors, 2³² matrix entries or more) or, unless `forced`, would not pay (an extra work above
    /// [`SUBSTRUCTURE_OVERHEAD`] of the factorization's, see the module documentation).
    ///
    /// # Errors
    /// [`Error::OutOfMemory`] if a factor or its workspace cannot be allocated.
    pub fn new(
        pattern: &SystemPattern,
        equations: &[u32],
        d: usize,
        bisection: &Bisection,
        par: Par,
        forced: bool,
    ) -> Result<Option<Self>> {
        let node_equations = |nodes: &[u32]| -> Vec<usize> {
            let mut out = Vec::with_capacity(d * nodes.len());
            for &v in nodes {
                for i in 0..d {
                    let e = equations[d * v as usize + i];
                    if e != u32::MAX {
                        out.push(e as usize);
                    }
                }
            }
            out
        };
        // The substructures index their matrices with 32 bits.
        if pattern.nnz() >= u32::MAX as usize {
            return Ok(None);
        }
        let first = node_equations(&bisection.first);
        let second = node_equations(&bisection.second);
        let separator = node_equations(&bisection.separator);
        if first.is_empty() || second.is_empty() || separator.is_empty() {
            return Ok(None);
        }
        let mut part = vec![u8::MAX; pattern.n()];
        for (p, eqs) in [(0u8, &first), (1, &second), (SEPARATOR, &separator)] {
            for &e in eqs.iter() {
                part[e] = p;
            }
        }
        if part.contains(&u8::MAX) {
            return Ok(None);
        }
        let (col_ptr, row_idx) = (pattern.col_ptr(), pattern.row_idx());
        for c in 0..pattern.n() {
            for &r in &row_idx[col_ptr[c]..col_ptr[c + 1]] {
                if part[r] != part[c] && part[r] != SEPARATOR && part[c] != SEPARATOR {
                    return Ok(None);
                }
            }
        }
        // The two substructures run side by side on the thread pool (one after the other
        // on a pool of one thread); each uses half of `par`'s threads inside its dense
        // blocks.
        let inner = match par {
            Par::Rayon(t) if t.get() >= 4 => Par::rayon(t.get() / 2),
            _ => Par::Seq,
        };
        let (a, b) = rayon::join(
            || Substructure::new(pattern, &part, 0, first, &separator, inner),
            || Substructure::new(pattern, &part, 1, second, &separator, inner),
        );
        let parts = [a?, b?];
        let s = separator.len();
        let flops = factor_flops(parts[0].supernodal()) + factor_flops(parts[1].supernodal());
        if !forced && (s as f64).powi(3) > SUBSTRUCTURE_OVERHEAD * flops {
            return Ok(None);
        }
        let mut dense_of = vec![usize::MAX; pattern.n()];
        for (k, &e) in separator.iter().enumerate() {
            dense_of[e] = k;
        }
        let mut separator_entries = Vec::new();
        for c in 0..pattern.n() {
            if part[c] != SEPARATOR {
                continue;
            }
            for (k, &r) in row_idx
                .iter()
                .enumerate()
                .take(col_ptr[c + 1])
                .skip(col_ptr[c])
            {
                if part[r] == SEPARATOR {
                    let (i, j) = (dense_of[r].max(dense_of[c]), dense_of[r].min(dense_of[c]));
                    separator_entries.push((i, j, k));
                }
            }
        }
        let schur_stack = MemBuffer::try_new(
            faer::linalg::cholesky::llt::factor::cholesky_in_place_scratch::<f64>(
                s,
                par,
                Default::default(),
            ),
        )
        .map_err(|_| out_of_memory("dense Cholesky workspace"))?;
        Ok(Some(Substructured {
            parts,
            separator,
            separator_entries,
            schur: Mat::zeros(s, s),
            schur_stack,
            ys: Mat::zeros(s, 1),
            par,
        }))
    }

    /// Stored entries of the factor: the two substructures' sparse factors and the
    /// dense blocks `K₁`, `K₂` and `Lₛ`.
    pub fn nnz_factor(&self) -> usize {
        let s = self.separator.len();
        self.parts[0].l_values.len() + self.parts[1].l_values.len() + 3 * s * s
    }

    /// Numeric factorization of the matrix with upper-triangle `values` on the pattern
    /// given to [`Substructured::new`].
    ///
    /// # Errors
    /// [`Error::NotPositiveDefinite`] if a pivot is not positive.
    pub fn factorize(&mut self, values: &[f64]) -> Result<()> {
        let [a, b] = &mut self.parts;
        let (ra, rb) = rayon::join(|| a.factorize(values), || b.factorize(values));
        ra?;
        rb?;
        // S = K₁K₁ᵀ + K₂K₂ᵀ − Aₛₛ (lower triangle), then Lₛ Lₛᵀ = S.
        let s = self.separator.len();
        self.schur.fill(0.0);
        for &(i, j, k) in &self.separator_entries {
            self.schur[(i, j)] = -values[k];
        }
        for part in &self.parts {
            triangular::matmul(
                self.schur.as_mut(),
                BlockStructure::TriangularLower,
                Accum::Add,
                part.k.as_ref(),
                BlockStructure::TriangularLower,
                part.k.transpose(),
                BlockStructure::TriangularUpper,
                1.0,
                self.par,
            );
        }
        debug_assert_eq!(self.schur.nrows(), s);
        faer::linalg::cholesky::llt::factor::cholesky_in_place(
            self.schur.as_mut(),
            Default::default(),
            self.par,
            MemStack::new(&mut self.schur_stack),
            Default::default(),
        )
        .map_err(|e| Error::NotPositiveDefinite {
            context: format!("Schur complement on the separator: {e:?}"),
        })?;
        Ok(())
    }

    /// Solves `A x = b` in place (`rhs` holds b on entry, x on exit) with the last
    /// factorization.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) {
        let [a, b] = &mut self.parts;
        {
            let rhs: &[f64] = rhs;
            rayon::join(|| a.forward(rhs), || b.forward(rhs));
        }
        // yₛ = Lₛ⁻¹ (bₛ + K₁w₁ + K₂w₂), xₛ = Lₛ⁻ᵀ yₛ.
        for (k, &e) in self.separator.iter().enumerate() {
            self.ys[(k, 0)] = rhs[e] + a.kw[(k, 0)] + b.kw[(k, 0)];
        }
        faer::linalg::triangular_solve::solve_lower_triangular_in_place(
            self.schur.as_ref(),
            self.ys.as_mut(),
            Par::Seq,
        );
        faer::linalg::triangular_solve::solve_upper_triangular_in_place(
            self.schur.transpose(),
            self.ys.as_mut(),
            Par::Seq,
        );
        let xs = self.ys.as_ref();
        rayon::join(|| a.backward(xs), || b.backward(xs));
        for part in [&*a, &*b] {
            for (&e, &x) in part.interior.iter().zip(&part.work) {
                rhs[e] = x;
            }
        }
        for (k, &e) in self.separator.iter().enumerate() {
            rhs[e] = self.ys[(k, 0)];
        }
    }
}
