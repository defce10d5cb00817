//! Sparse matrices in compressed sparse row form, with the parallel products the multigrid
//! hierarchy needs: `y = A x` and the row-by-row (Gustavson) product `A B`.

use rayon::prelude::*;

/// Rows per parallel task of a sparse matrix–vector product.
const ROWS_PER_TASK: usize = 4096;

/// A sparse matrix in compressed sparse row form (all entries, both triangles for the
/// symmetric operators).
#[derive(Clone, Debug, Default)]
pub struct Csr {
    /// Number of columns.
    pub(super) n_cols: usize,
    /// Row start offsets into `col` and `val` (length rows + 1).
    pub(super) ptr: Vec<usize>,
    /// Column of every entry, sorted within each row.
    pub(super) col: Vec<u32>,
    /// Value of every entry.
    pub(super) val: Vec<f64>,
}

impl Csr {
    /// Number of rows.
    pub fn n_rows(&self) -> usize {
        self.ptr.len().saturating_sub(1)
    }

    /// Number of columns.
    pub fn n_cols(&self) -> usize {
        self.n_cols
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.col.len()
    }

    /// Entries `(column, value)` of row `i`.
    pub fn row(&self, i: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let r = self.ptr[i]..self.ptr[i + 1];
        self.col[r.clone()]
            .iter()
            .zip(&self.val[r])
            .map(|(&c, &v)| (c as usize, v))
    }

    /// `y = A x` (rows in parallel).
    ///
    /// # Panics
    /// If the lengths do not match.
    #[track_caller]
    pub fn matvec(&self, x: &[f64], y: &mut [f64]) {
        assert!(x.len() == self.n_cols && y.len() == self.n_rows());
        y.par_iter_mut()
            .with_min_len(ROWS_PER_TASK)
            .enumerate()
            .for_each(|(i, yi)| {
                let mut acc = 0.0;
                for k in self.ptr[i]..self.ptr[i + 1] {
                    acc += self.val[k] * x[self.col[k] as usize];
                }
                *yi = acc;
            });
    }

    /// The transpose.
    pub(super) fn transpose(&self) -> Csr {
        let mut count = vec![0usize; self.n_cols + 1];
        for &c in &self.col {
            count[c as usize + 1] += 1;
        }
        for j in 0..self.n_cols {
            count[j + 1] += count[j];
        }
        let ptr = count.clone();
        let mut next = count;
        let mut col = vec![0u32; self.nnz()];
        let mut val = vec![0.0; self.nnz()];
        for i in 0..self.n_rows() {
            for k in self.ptr[i]..self.ptr[i + 1] {
                let j = self.col[k] as usize;
                col[next[j]] = i as u32;
                val[next[j]] = self.val[k];
                next[j] += 1;
            }
        }
        Csr {
            n_cols: self.n_rows(),
            ptr,
            col,
            val,
        }
    }

    /// The diagonal entries (0 where none is stored).
    pub(super) fn diagonal(&self, out: &mut [f64]) {
        for (i, d) in out.iter_mut().enumerate() {
            *d = self.row(i).filter(|&(j, _)| j == i).map(|(_, v)| v).sum();
        }
    }
}

/// Sparse product `A B` by rows (Gustavson), blocks of rows in parallel. Every row is
/// computed by one task in a fixed order, so the result does not depend on the scheduling.
pub(super) fn multiply(a: &Csr, b: &Csr) -> Csr {
    let n = a.n_rows();
    let blocks: Vec<(Vec<usize>, Vec<u32>, Vec<f64>)> = (0..n.div_ceil(ROWS_PER_TASK))
        .into_par_iter()
        .map(|k| multiply_rows(a, b, k * ROWS_PER_TASK..((k + 1) * ROWS_PER_TASK).min(n)))
        .collect();
    let nnz = blocks.iter().map(|blk| blk.1.len()).sum();
    let mut ptr = Vec::with_capacity(n + 1);
    ptr.push(0);
    let mut col = Vec::with_capacity(nnz);
    let mut val = Vec::with_capacity(nnz);
    for (lengths, c, v) in blocks {
        for len in lengths {
            ptr.push(ptr[ptr.len() - 1] + len);
        }
        col.extend_from_slice(&c);
        val.extend_from_slice(&v);
    }
    Csr {
        n_cols: b.n_cols,
        ptr,
        col,
        val,
    }
}

/// Rows `rows` of `A B`: their lengths, columns (sorted per row) and values.
fn multiply_rows(
    a: &Csr,
    b: &Csr,
    rows: std::ops::Range<usize>,
) -> (Vec<usize>, Vec<u32>, Vec<f64>) {
    let mut acc = vec![0.0; b.n_cols];
    let mut mark = vec![usize::MAX; b.n_cols];
    let mut lengths = Vec::with_capacity(rows.len());
    let mut col = Vec::new();
    let mut val = Vec::new();
    for i in rows {
        let start = col.len();
        for (k, av) in a.row(i) {
            for (j, bv) in b.row(k) {
                if mark[j] != i {
                    mark[j] = i;
                    acc[j] = 0.0;
                    col.push(j as u32);
                }
                acc[j] += av * bv;
            }
        }
        col[start..].sort_unstable();
        val.extend(col[start..].iter().map(|&j| acc[j as usize]));
        lengths.push(col.len() - start);
    }
    (lengths, col, val)
}
