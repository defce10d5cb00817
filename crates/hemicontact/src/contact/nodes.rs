//! Contact nodes (SPEC §3): the nodes of Γ_C with their lumped weights, averaged normals and
//! tangent bases.
//!
//! A *contact point* is a pair (node, contact boundary): a node on two contact boundaries
//! (an edge between two faces facing two foundations) is two points, one per foundation.
//! Nodes on Γ_D are never contact nodes. For point `i`:
//!
//! - weight `w_i = ∫_{Γ_C} φ_i = Σ_{F ∋ node} |F| / d` over the boundary's facets;
//! - normal `ν_i`: the weighted average `Σ |F| ν_F` of its facets' outward normals,
//!   normalized;
//! - tangents: 2D, `τ = (−ν_y, ν_x)` (counter-clockwise along the boundary); 3D,
//!   `τ₁ = e × ν / ‖e × ν‖` with `e` the axis least aligned with ν, `τ₂ = ν × τ₁`.
//!
//! Points are ordered by boundary, then by node number.

use super::ContactBoundary;
use crate::fem::simplex::cross;
use crate::mesh::Mesh;

/// The contact points of a mesh; see the module documentation.
#[derive(Clone, Debug, Default)]
pub struct ContactNodes {
    /// Mesh node of each point.
    pub node: Vec<u32>,
    /// Contact boundary (index into the problem's list) of each point.
    pub boundary: Vec<u16>,
    /// Lumped weight w_i (m² in 3D, m in 2D).
    pub weight: Vec<f64>,
    /// Outward unit normal ν_i.
    pub normal: Vec<[f64; 3]>,
    /// Orthonormal tangent basis (first d − 1 vectors used).
    pub tangent: Vec<[[f64; 3]; 2]>,
}

impl ContactNodes {
    /// Builds the contact points of `boundaries` on `mesh`, skipping nodes where
    /// `excluded[node]` is true (nodes with all components prescribed).
    pub fn new(mesh: &Mesh, boundaries: &[ContactBoundary], excluded: &[bool]) -> Self {
        let d = mesh.dim();
        let mut out = ContactNodes::default();
        let mut acc_w = vec![0.0; mesh.n_nodes()];
        let mut acc_n = vec![[0.0; 3]; mesh.n_nodes()];
        for (b, cb) in boundaries.iter().enumerate() {
            let nodes = mesh.part_nodes(cb.part);
            for &v in &nodes {
                acc_w[v as usize] = 0.0;
                acc_n[v as usize] = [0.0; 3];
            }
            for f in mesh.part_facets(cb.part) {
                let (measure, n) = mesh.facet_measure_normal(f);
                for &v in mesh.facet(f) {
                    acc_w[v as usize] += measure / d as f64;
                    for i in 0..3 {
                        acc_n[v as usize][i] += measure * n[i];
                    }
                }
            }
            for &v in &nodes {
                if excluded[v as usize] {
                    continue;
                }
                let mut n = acc_n[v as usize];
                let len = n.iter().map(|x| x * x).sum::<f64>().sqrt();
                for x in n.iter_mut() {
                    *x /= len;
                }
                out.node.push(v);
                out.boundary.push(b as u16);
                out.weight.push(acc_w[v as usize]);
                out.normal.push(n);
                out.tangent.push(tangent_basis(d, &n));
            }
        }
        out
    }

    /// Number of contact points.
    pub fn len(&self) -> usize {
        self.node.len()
    }

    /// Whether there are no contact points.
    pub fn is_empty(&self) -> bool {
        self.node.is_empty()
    }

    /// Normal displacement `u_ν = u·ν` and tangential coordinates `ξ_a = u·τ_a` of point `i`
    /// for the displacement `u` (DOF order).
    #[inline]
    pub fn kinematics(&self, dim: usize, u: &[f64], i: usize) -> (f64, [f64; 2]) {
        let v = self.node[i] as usize;
        let x = &u[dim * v..dim * v + dim];
        let dot = |a: &[f64; 3]| (0..dim).map(|k| a[k] * x[k]).sum::<f64>();
        let mut xi = [0.0; 2];
        for (a, t) in self.tangent[i].iter().enumerate().take(dim - 1) {
            xi[a] = dot(t);
        }
        (dot(&self.normal[i]), xi)
    }
}

/// Orthonormal tangent basis of the unit normal `n`; see the module documentation.
pub fn tangent_basis(dim: usize, n: &[f64; 3]) -> [[f64; 3]; 2] {
    if dim == 2 {
        return [[-n[1], n[0], 0.0], [0.0; 3]];
    }
    let k = (0..3)
        .min_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
        .unwrap_or(0);
    let mut e = [0.0; 3];
    e[k] = 1.0;
    let mut t1 = cross(&e, n);
    let len = t1.iter().map(|x| x * x).sum::<f64>().sqrt();
    for x in t1.iter_mut() {
        *x /= len;
    }
    let t2 = cross(n, &t1);
    [t1, t2]
}
