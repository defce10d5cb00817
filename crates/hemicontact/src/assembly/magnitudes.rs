//! The magnitudes of the terms that each entry of the gradient sums: the scale of its
//! round-off.
//!
//! An entry of `∇E` is a sum of terms that may cancel: the element forces of the cells
//! around a node, each `|T| Bᵀσ` with `σ = C ε` and `ε = B u_e` a sum over the cell's
//! nodes; the contact force of a point, `w p(u_ν − g)` with `u_ν` a sum over its stencil.
//! Where a stiff part is moved as a whole, the terms `B u_e` are large and cancel to a
//! small strain, and the entry is known only to about the machine epsilon times the sum of
//! their magnitudes. This module computes that sum, entry by entry, with the same
//! operations as the assembly, every product and sum taken in absolute value:
//!
//! - a cell T has, at its local DOF p, `|T| Σ_m |B_mp| (Σ_n |C_mn| e_n + |σ_m|)` with
//!   `e_n = Σ_q |B_nq| |u_q|` (the cell's tangent C and stress σ, ideal locking included),
//!   and, for sums along a rigid motion in which its terms cancel, `|T| Σ_m |B_mp| |σ_m|`
//!   ([`CellMagnitudes`]);
//! - a contact point adds, at each DOF of its stencil's node a, `|c_a| (‖g‖₁ + w (|p| + F +
//!   ‖b‖₁) + k_ν m_ν + k_τ m_τ)` with g its force, p its pressure, F and b its frozen bound
//!   and linear term, `k_ν` and `k_τ` the stiffness of its Hessian block along the normal
//!   and in the tangent plane, and `m_ν`, `m_τ` the magnitudes of the normal and
//!   tangential kinematics it is evaluated at, term by term (`Σ_a |c_a| Σ_k |ν_k u_k(v_a)|`
//!   and the gap; the same along the tangents, the foundation's motion and the placement;
//!   each with its frozen multiplier over the penalty).

use super::contact::{ContactAssembler, ContactData};
use super::element;
use super::global::BulkAssembler;
use crate::geometry::simplex;
use crate::material::StrainEnergy;
use crate::mesh::Mesh;
use crate::tensor::{mandel_len, Sym};

/// The magnitudes of one cell's terms of the gradient
/// ([`BulkAssembler::cell_magnitudes`]), per local DOF `p = d·a + i` (vertex a, component
/// i; the first `d(d+1)` entries).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CellMagnitudes {
    /// `|T| Σ_m |B_mp| (Σ_n |C_mn| e_n + |σ_m|)`: the magnitude of the cell's term at
    /// DOF p, its strain taken term by term (N).
    pub term: [f64; 12],
    /// `|T| Σ_m |B_mp| |σ_m|`: the magnitude of the same term for the cell's stress as
    /// computed. The cell's terms sum to zero along a rigid motion whatever the round-off of
    /// its stress, so a sum of all of them along one is known to about ε times these (N).
    pub rigid: [f64; 12],
}

impl<M: StrainEnergy> BulkAssembler<'_, M> {
    /// Calls `visit(c, magnitudes)` for every cell c of the mesh with the magnitudes of its
    /// terms of the bulk gradient at displacement `u` (see the module documentation).
    ///
    /// # Panics
    /// If `u` is not of length `d · n_nodes`.
    pub fn cell_magnitudes(&self, u: &[f64], visit: impl FnMut(usize, &CellMagnitudes)) {
        assert_eq!(u.len(), self.mesh.dim() * self.mesh.n_nodes());
        if self.mesh.dim() == 2 {
            self.cell_magnitudes_of::<6>(u, visit);
        } else {
            self.cell_magnitudes_of::<12>(u, visit);
        }
    }

    /// [`BulkAssembler::cell_magnitudes`] for cells with `LD` local DOFs.
    fn cell_magnitudes_of<const LD: usize>(
        &self,
        u: &[f64],
        mut visit: impl FnMut(usize, &CellMagnitudes),
    ) {
        let mesh = self.mesh;
        let d = element::dim_of(LD);
        let nm = mandel_len(d);
        let mut out = CellMagnitudes {
            term: [0.0; 12],
            rigid: [0.0; 12],
        };
        for c in 0..mesh.n_cells() {
            let geo = simplex::geometry(d, &mesh.cell_coords(c));
            let b = element::b_matrix::<LD>(&geo);
            let u_e = element::gather::<LD>(mesh, u, c);
            let eps = element::strain(&b, &u_e);
            let k = self.material_index(c);
            let material = &self.materials[k];
            let mut sigma = material.stress(&eps);
            let mut tangent = material.tangent(&eps);
            if let Some(al) = self.ideal.and_then(|l| l.cell(c, k)) {
                sigma = sigma.add_scaled(1.0, &al.stress(&eps));
                if al.multiplier(&eps) > 0.0 {
                    let t = al.tangent(&eps);
                    for (row, trow) in tangent.iter_mut().zip(t.iter()) {
                        for (a, b) in row.iter_mut().zip(trow.iter()) {
                            *a += b;
                        }
                    }
                }
            }
            let mut strain = [0.0; 6];
            for (m, e) in strain.iter_mut().enumerate().take(nm) {
                *e = (0..LD).map(|q| (b[m][q] * u_e[q]).abs()).sum();
            }
            let mut stress = [0.0; 6];
            for (m, s) in stress.iter_mut().enumerate().take(nm) {
                *s = (0..nm)
                    .map(|n| (tangent[m][n] * strain[n]).abs())
                    .sum::<f64>()
                    + sigma.c[m].abs();
            }
            let w = geo.measure.abs();
            for p in 0..LD {
                out.term[p] = w * (0..nm).map(|m| (b[m][p] * stress[m]).abs()).sum::<f64>();
                out.rigid[p] = w * (0..nm).map(|m| (b[m][p] * sigma.c[m]).abs()).sum::<f64>();
            }
            visit(c, &out);
        }
    }
}

/// The measure of cell `c` of `mesh` and the magnitudes of the terms of its strain for the
/// displacement `u`: `Σ_q |B_mq| |u_q|` for every Mandel component m, the scale of the
/// strain's round-off.
pub fn strain_magnitudes(mesh: &Mesh, u: &[f64], c: usize) -> (f64, Sym) {
    fn inner<const LD: usize>(mesh: &Mesh, u: &[f64], c: usize) -> (f64, Sym) {
        let d = element::dim_of(LD);
        let geo = simplex::geometry(d, &mesh.cell_coords(c));
        let b = element::b_matrix::<LD>(&geo);
        let u_e = element::gather::<LD>(mesh, u, c);
        let mut e = Sym::zero(d);
        for m in 0..mandel_len(d) {
            e.c[m] = (0..LD).map(|q| (b[m][q] * u_e[q]).abs()).sum();
        }
        (geo.measure.abs(), e)
    }
    if mesh.dim() == 2 {
        inner::<6>(mesh, u, c)
    } else {
        inner::<12>(mesh, u, c)
    }
}

impl ContactAssembler<'_> {
    /// Adds the magnitudes of the contact points' terms of the gradient at displacement
    /// `u` for the frozen data `frozen` to `out` (DOF order; see the module
    /// documentation), over every point held here (a process's ghost points complete its
    /// master nodes' entries). The responses of user-defined compliance laws must be those
    /// at `u`.
    pub fn term_magnitudes(&self, u: &[f64], frozen: &ContactData<'_>, out: &mut [f64]) {
        let d = self.dim;
        let nodes = self.nodes;
        for i in 0..nodes.len() {
            let term = self.point(u, frozen, i);
            let s = self.state(u, i, frozen);
            let cb = &self.boundaries[nodes.boundary[i] as usize];
            let (n, stencil, coef) = nodes.stencil(d, i);
            let (normal, tangent) = (&nodes.normal[i], &nodes.tangent[i]);
            // The magnitudes of the normal and tangential kinematics the law is evaluated
            // at, term by term.
            let along = |e: &[f64; 3]| -> f64 {
                (0..n)
                    .map(|a| {
                        let v = stencil[a] as usize;
                        let x = &u[d * v..d * v + d];
                        coef[a].abs() * (0..d).map(|k| (e[k] * x[k]).abs()).sum::<f64>()
                    })
                    .sum()
            };
            let r = self.penalty[i];
            let exact = |yes: bool, m: f64| if yes && r > 0.0 { m / r } else { 0.0 };
            let m_normal = along(normal)
                + nodes.gap[i].abs()
                + exact(cb.normal.is_exact(), frozen.pressure[i].abs());
            let mut m_tangent: f64 = tangent[..d - 1].iter().map(along).sum();
            m_tangent += nodes.foundation_motion[i]
                .iter()
                .map(|x| x.abs())
                .sum::<f64>();
            if let Some(placed) = nodes.placed_tangential.get(i) {
                m_tangent += placed.iter().map(|x| x.abs()).sum::<f64>();
            }
            let friction_exact = cb.friction.as_ref().is_some_and(|f| f.is_exact());
            m_tangent += exact(
                friction_exact,
                frozen.traction[i].iter().map(|x| x.abs()).sum(),
            );
            // The stiffness of the term along the normal and in the tangent plane.
            let h = &term.hessian;
            let quad = |a: &[f64; 3], b: &[f64; 3]| -> f64 {
                (0..d)
                    .map(|k| (0..d).map(|l| a[k] * h[k][l] * b[l]).sum::<f64>())
                    .sum::<f64>()
                    .abs()
            };
            let k_normal = quad(normal, normal);
            let k_tangent = tangent[..d - 1]
                .iter()
                .map(|ta| tangent[..d - 1].iter().map(|tb| quad(ta, tb)).sum::<f64>())
                .fold(0.0f64, f64::max);
            let w = nodes.weight[i].abs();
            let force = term.gradient[..d].iter().map(|x| x.abs()).sum::<f64>()
                + w * (s.pressure.abs()
                    + frozen.bound[i].abs()
                    + frozen.linear[i].iter().map(|x| x.abs()).sum::<f64>());
            let magnitude = force + k_normal * m_normal + k_tangent * m_tangent;
            for a in 0..n {
                let v = stencil[a] as usize;
                for k in 0..d {
                    out[d * v + k] += coef[a].abs() * magnitude;
                }
            }
        }
    }
}
