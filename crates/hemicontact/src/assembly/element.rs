//! P1 element kernels: strain-displacement matrix, strain, and the element contributions
//! `|T| Bᵀσ` (gradient) and `|T| Bᵀ C B` (Hessian).
//!
//! Local DOFs of a cell are numbered `p = d·a + i` (vertex `a`, component `i`), so a cell has
//! `ld = d(d+1)` local DOFs: 6 for triangles, 12 for tetrahedra.

use crate::fem::simplex::SimplexGeometry;
use crate::tensor::{mandel_len, Sym, Tangent, SQRT2};

/// Strain-displacement matrix `B[m][p]`: Mandel component `m` of the strain produced by a
/// unit value of local DOF `p` (shape `mandel_len(d) × d(d+1)`, padded to 6 × 12).
pub type BMatrix = [[f64; 12]; 6];

/// Builds the strain-displacement matrix of a cell from its hat-function gradients.
#[inline]
pub fn b_matrix(dim: usize, geo: &SimplexGeometry) -> BMatrix {
    let mut b = [[0.0; 12]; 6];
    let h = 1.0 / SQRT2;
    for a in 0..=dim {
        let g = &geo.grad[a];
        let p = dim * a;
        if dim == 2 {
            b[0][p] = g[0];
            b[2][p] = h * g[1];
            b[1][p + 1] = g[1];
            b[2][p + 1] = h * g[0];
        } else {
            // Mandel order [xx, yy, zz, yz, xz, xy].
            b[0][p] = g[0];
            b[4][p] = h * g[2];
            b[5][p] = h * g[1];
            b[1][p + 1] = g[1];
            b[3][p + 1] = h * g[2];
            b[5][p + 1] = h * g[0];
            b[2][p + 2] = g[2];
            b[3][p + 2] = h * g[1];
            b[4][p + 2] = h * g[0];
        }
    }
    b
}

/// Strain `ε = B u_e` from the local displacement vector `u_e` (length `d(d+1)`).
#[inline]
pub fn strain(dim: usize, b: &BMatrix, u_e: &[f64; 12]) -> Sym {
    let ld = dim * (dim + 1);
    let mut eps = Sym::zero(dim);
    for (m, row) in b.iter().enumerate().take(mandel_len(dim)) {
        eps.c[m] = (0..ld).map(|p| row[p] * u_e[p]).sum();
    }
    eps
}

/// Element gradient `g_e = w Bᵀσ` (length `d(d+1)`).
#[inline]
pub fn gradient(dim: usize, b: &BMatrix, sigma: &Sym, w: f64) -> [f64; 12] {
    let ld = dim * (dim + 1);
    let nm = mandel_len(dim);
    let mut g = [0.0; 12];
    for (p, gp) in g.iter_mut().enumerate().take(ld) {
        *gp = w * (0..nm).map(|m| b[m][p] * sigma.c[m]).sum::<f64>();
    }
    g
}

/// Element Hessian `K_e = w Bᵀ C B`, upper triangle in local order: entry `(p, q)` with
/// `p ≤ q` at `k[p][q]`.
#[inline]
pub fn hessian(dim: usize, b: &BMatrix, c: &Tangent, w: f64) -> [[f64; 12]; 12] {
    let ld = dim * (dim + 1);
    let nm = mandel_len(dim);
    // CB[m][q] = Σ_n C[m][n] B[n][q]
    let mut cb = [[0.0; 12]; 6];
    for m in 0..nm {
        for n in 0..nm {
            let cmn = w * c[m][n];
            if cmn != 0.0 {
                for q in 0..ld {
                    cb[m][q] += cmn * b[n][q];
                }
            }
        }
    }
    let mut k = [[0.0; 12]; 12];
    for p in 0..ld {
        for q in p..ld {
            k[p][q] = (0..nm).map(|m| b[m][p] * cb[m][q]).sum();
        }
    }
    k
}
