//! P1 element kernels: strain-displacement matrix, strain, and the element contributions
//! `|T| Bᵀσ` (gradient) and `|T| Bᵀ C B` (Hessian).
//!
//! Local DOFs of a cell are numbered `p = d·a + i` (vertex `a`, component `i`), so a cell has
//! `LD = d(d+1)` local DOFs: 6 for triangles, 12 for tetrahedra. The kernels are generic over
//! `LD` so that every loop has a compile-time bound and every local array its exact size
//! (the dimension is `d = 2` for `LD = 6` and `d = 3` for `LD = 12`).

use crate::geometry::simplex::{self, SimplexGeometry};
use crate::mesh::Mesh;
use crate::tensor::{mandel_len, Sym, Tangent, SQRT2};

/// Strain-displacement matrix `B[m][p]`: Mandel component `m` of the strain produced by a
/// unit value of local DOF `p` (rows beyond `mandel_len(d)` are zero).
pub type BMatrix<const LD: usize> = [[f64; LD]; 6];

/// Spatial dimension of a cell with `ld` local DOFs (6 → 2, 12 → 3).
#[inline]
pub const fn dim_of(ld: usize) -> usize {
    if ld == 6 {
        2
    } else {
        3
    }
}

/// Builds the strain-displacement matrix of a cell from its hat-function gradients.
#[inline]
pub fn b_matrix<const LD: usize>(geo: &SimplexGeometry) -> BMatrix<LD> {
    let dim = dim_of(LD);
    let mut b = [[0.0; LD]; 6];
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

/// Strain `ε = B u_e` from the local displacement vector `u_e`.
#[inline]
pub fn strain<const LD: usize>(b: &BMatrix<LD>, u_e: &[f64; LD]) -> Sym {
    let dim = dim_of(LD);
    let mut eps = Sym::zero(dim);
    for m in 0..mandel_len(dim) {
        eps.c[m] = (0..LD).map(|p| b[m][p] * u_e[p]).sum();
    }
    eps
}

/// Element gradient `g_e = w Bᵀσ`.
#[inline]
pub fn gradient<const LD: usize>(b: &BMatrix<LD>, sigma: &Sym, w: f64) -> [f64; LD] {
    let nm = mandel_len(dim_of(LD));
    let mut g = [0.0; LD];
    for p in 0..LD {
        g[p] = w * (0..nm).map(|m| b[m][p] * sigma.c[m]).sum::<f64>();
    }
    g
}

/// Element Hessian `K_e = w Bᵀ C B`; only the upper triangle `k[p][q]`, `p ≤ q`, is set.
#[inline]
pub fn hessian<const LD: usize>(b: &BMatrix<LD>, c: &Tangent, w: f64) -> [[f64; LD]; LD] {
    let nm = mandel_len(dim_of(LD));
    // CB[m][q] = w Σ_n C[m][n] B[n][q]
    let mut cb = [[0.0; LD]; 6];
    for m in 0..nm {
        for n in 0..nm {
            let cmn = w * c[m][n];
            for q in 0..LD {
                cb[m][q] += cmn * b[n][q];
            }
        }
    }
    let mut k = [[0.0; LD]; LD];
    for p in 0..LD {
        for q in p..LD {
            k[p][q] = (0..nm).map(|m| b[m][p] * cb[m][q]).sum();
        }
    }
    k
}

/// Local displacement vector of cell `c` from the global vector `u` (DOF order).
#[inline]
pub fn gather<const LD: usize>(mesh: &Mesh, u: &[f64], c: usize) -> [f64; LD] {
    let d = dim_of(LD);
    let mut ue = [0.0; LD];
    for (a, &v) in mesh.cell(c).iter().enumerate() {
        ue[d * a..d * a + d].copy_from_slice(&u[d * v as usize..d * v as usize + d]);
    }
    ue
}

/// Measure and constant strain of cell `c` of `mesh` for the displacement `u`.
#[inline]
pub fn cell_strain(mesh: &Mesh, u: &[f64], c: usize) -> (f64, Sym) {
    fn inner<const LD: usize>(mesh: &Mesh, u: &[f64], c: usize) -> (f64, Sym) {
        let geo = simplex::geometry(dim_of(LD), &mesh.cell_coords(c));
        let b = b_matrix::<LD>(&geo);
        (geo.measure, strain(&b, &gather::<LD>(mesh, u, c)))
    }
    if mesh.dim() == 2 {
        inner::<6>(mesh, u, c)
    } else {
        inner::<12>(mesh, u, c)
    }
}
