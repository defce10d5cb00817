//! The small dense symmetric matrices of the rigid-motion analysis: normal matrices `Σ r rᵀ`
//! and their null spaces, and symmetric positive semidefinite solves, by the cyclic Jacobi
//! eigenvalue method. Their size is the number of rigid-motion coefficients of one body (at
//! most 6) or of a group of bodies coupled through contact pairs (6 per body); they are
//! stored row by row in a `Vec` of `k × k` entries.

/// Relative tolerance on the eigenvalues of the normal matrices: an eigenvalue at most
/// `NULL_TOLERANCE · tr N` spans a free motion (see the module documentation).
pub const NULL_TOLERANCE: f64 = 1e-10;

/// Accumulated normal matrix `Σ r rᵀ` (k × k) with its trace reference.
pub(super) struct Normal {
    k: usize,
    a: Vec<f64>,
    /// Sum of the squared norms of the rows in the full coefficient space (the trace
    /// reference of the tolerance: restricted rows can be shorter).
    scale: f64,
}

impl Normal {
    /// The zero k × k normal matrix.
    pub(super) fn new(k: usize) -> Self {
        Normal {
            k,
            a: vec![0.0; k * k],
            scale: 0.0,
        }
    }

    /// Adds the row `r` (k entries), counting its own squared norm in the trace reference.
    pub(super) fn add(&mut self, r: &[f64]) {
        let n2 = r[..self.k].iter().map(|x| x * x).sum();
        self.add_weighted(r, n2);
    }

    /// Adds the row `r` (k entries), counting `full_norm2` in the trace reference.
    pub(super) fn add_weighted(&mut self, r: &[f64], full_norm2: f64) {
        for i in 0..self.k {
            for j in 0..self.k {
                self.a[i * self.k + j] += r[i] * r[j];
            }
        }
        self.scale += full_norm2;
    }

    /// Orthonormal basis (k coefficients each) of the eigenvectors with eigenvalue at most
    /// `NULL_TOLERANCE · scale`; all of them without any row.
    pub(super) fn null_space(&self) -> Vec<Vec<f64>> {
        self.split().0
    }

    /// The orthonormal eigenvectors (k coefficients each) split into the null space (as
    /// [`Normal::null_space`]) and its orthogonal complement, the range.
    pub(super) fn split(&self) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
        let k = self.k;
        let (values, vectors) = jacobi_eigen(self.a.clone(), k);
        let tol = NULL_TOLERANCE * self.scale;
        let column = |j: usize| (0..k).map(|l| vectors[l * k + j]).collect::<Vec<f64>>();
        let null = (0..k).filter(|&j| values[j] <= tol).map(column);
        let range = (0..k).filter(|&j| values[j] > tol).map(column);
        (null.collect(), range.collect())
    }
}

/// Eigenvalues and eigenvectors (column j: entries `l·k + j`) of the symmetric `k × k`
/// matrix `a` (row by row) by the cyclic Jacobi method (converges quadratically; at most 50
/// sweeps).
fn jacobi_eigen(mut a: Vec<f64>, k: usize) -> (Vec<f64>, Vec<f64>) {
    let mut v = vec![0.0; k * k];
    for i in 0..k {
        v[i * k + i] = 1.0;
    }
    for _ in 0..50 {
        let off: f64 = (0..k)
            .flat_map(|i| (0..k).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[i * k + j] * a[i * k + j])
            .sum();
        let diag: f64 = (0..k).map(|i| a[i * k + i] * a[i * k + i]).sum();
        if off <= 1e-32 * diag || off == 0.0 {
            break;
        }
        for p in 0..k {
            for q in p + 1..k {
                if a[p * k + q] == 0.0 {
                    continue;
                }
                // Rotation annihilating a[p][q] (Golub–Van Loan, Algorithm 8.4.1).
                let theta = (a[q * k + q] - a[p * k + p]) / (2.0 * a[p * k + q]);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for r in 0..k {
                    let (arp, arq) = (a[r * k + p], a[r * k + q]);
                    a[r * k + p] = c * arp - s * arq;
                    a[r * k + q] = s * arp + c * arq;
                }
                for r in 0..k {
                    let (apr, aqr) = (a[p * k + r], a[q * k + r]);
                    a[p * k + r] = c * apr - s * aqr;
                    a[q * k + r] = s * apr + c * aqr;
                }
                for row in 0..k {
                    let (vp, vq) = (v[row * k + p], v[row * k + q]);
                    v[row * k + p] = c * vp - s * vq;
                    v[row * k + q] = s * vp + c * vq;
                }
            }
        }
    }
    let values = (0..k).map(|i| a[i * k + i]).collect();
    (values, v)
}

/// The solution of the `k × k` symmetric positive semidefinite system `a y = b` (a row by
/// row, k = `b.len()`) by its eigendecomposition, eigenvalues below `10⁻¹²` of the largest
/// treated as zero (the least-squares solution of least norm).
pub fn solve_symmetric(a: &[f64], b: &[f64]) -> Vec<f64> {
    let k = b.len();
    let (values, vectors) = jacobi_eigen(a[..k * k].to_vec(), k);
    let largest = values[..k].iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let mut y = vec![0.0; k];
    for j in 0..k {
        if values[j] <= 1e-12 * largest || values[j] <= 0.0 {
            continue;
        }
        let proj: f64 = (0..k).map(|l| vectors[l * k + j] * b[l]).sum::<f64>() / values[j];
        for (l, yl) in y.iter_mut().enumerate() {
            *yl += proj * vectors[l * k + j];
        }
    }
    y
}

/// [`solve_symmetric`] for the leading `k × k` block of `a` and the first k entries of `b`
/// (k ≤ 6); the other entries of the answer are zero.
pub fn solve_small(a: &[[f64; 6]; 6], b: &[f64; 6], k: usize) -> [f64; 6] {
    let flat: Vec<f64> = (0..k).flat_map(|i| a[i][..k].iter().copied()).collect();
    let y = solve_symmetric(&flat, &b[..k]);
    let mut out = [0.0; 6];
    out[..k].copy_from_slice(&y);
    out
}
