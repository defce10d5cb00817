//! The scales every convergence test and every check of the certificate is relative to:
//! no part of a problem is decided by another part's scale.
//!
//! # Bodies
//!
//! A mesh may hold several bodies (connected components of its cells,
//! [`crate::rigid::bodies`]) whose forces and displacements differ by orders of
//! magnitude: a block barely loaded beside one pulled by metres. Every norm a stopping test
//! compares with a tolerance is therefore taken body by body, each relative to the body's
//! own scale, and the test holds when it holds on every body:
//!
//! - the Newton residual `‖∇E|_b‖` relative to the body's force scale
//!   `F_b = max(‖f_ext|_b‖, ‖∇W|_b‖, f_D,b)` (external forces, internal forces reactions
//!   included, and the force unit of the body's prescribed motions
//!   `f_D,b = max_k S_k |u_D,k − c_b,k| · diam_b^{d−2}` over the body's prescribed
//!   components k, `S_k` the P-wave modulus of the stiffest material around the node and
//!   `c_b` the translation the body's supports carry it by ([`crate::rigid::carry`]), so that
//!   a stress-free displacement-driven body is measured against the forces its data could
//!   cause, a soft body never against a stiff one's modulus, and a rigid translation, taken
//!   exactly, asks no force);
//! - the relative change of u in the energy norm, `‖Δu|_b‖_E / ‖u|_b‖_E`.
//!
//! On a mesh of one body each norm is the plain one, computed in the same order. A norm
//! beyond its tolerance that no longer falls is taken again over the entries above their
//! round-off floors, with the resultants of the body's regions ([`super::round_off`]).
//!
//! # Contact points
//!
//! Within a body, a contact region may carry forces far below the body's largest. Each
//! contact point i therefore has its own scales:
//!
//! - its **force scale** `f_i = max(w_i σ_i, η L_i, η_b F_b)` (N), with `σ_i = max(F_i,
//!   p_i)` its friction bound and pressure (Pa) and `w_i` its weight; a separated point has
//!   no force of its own, so the scale has a floor: a fraction η = [`FLOW_FLOOR`] of the
//!   force `L_i = Σ_T ‖f_T,v‖` that the stresses of the cells around its node v pass
//!   through it ([`crate::assembly::BulkAssembler::nodal_force_sum`]), and, where the body
//!   is stress-free around it, a fraction η_b = [`BODY_FLOOR`] of its body's force scale;
//! - its **stiffness** `k_i = S / h_i` ([`super::constraints::contact_stiffness`]), which
//!   turns the force scale into its **slip scale** `δ_i = f_i / (w_i k_i)`: element size
//!   times local strain.
//!
//! Newton's method converges at point i when the residual at its node is at most
//! `tol_N f_i`; the outer loop measures the change of the point's frozen bound and
//! multipliers against `f_i` and `δ_i`; the certificate checks its laws against `f_i` and
//! its stick state against `δ_i` ([`super::certificate`]).

//!
//! The bodies and their scales are here; the scales of the contact points
//! ([`super::System::point_scales`]), computed on the system, in `points`.

mod points;

use super::regions::Regions;
use crate::assembly::element;
use crate::material::{Hooke, StrainEnergy};
use crate::mesh::Mesh;
use crate::parallel::Share;
use crate::problem::Problem;
use crate::rigid::RigidMotions;

/// The floor η of the force scale of a contact point, as a fraction of the force its node
/// passes (see the module documentation): 1 %. Well above round-off (Newton resolves the
/// nodal forces to `tol_N η L_i`, 10⁻¹² of `L_i` at the default tolerance), and below the
/// contact force of any point that carries a share of its node's load.
pub const FLOW_FLOOR: f64 = 1e-2;

/// The last floor η_b of the force scale of a contact point, as a fraction of the force
/// scale `F_b` of its body, for a point without force in a stress-free neighbourhood (see
/// the module documentation): `10⁻⁴`, so that Newton resolves the residual at its node to
/// `tol_N η_b F_b` = 10⁻¹⁴ of the body's forces at the default tolerance, above round-off.
pub const BODY_FLOOR: f64 = 1e-4;

/// The body of every node and the per-body force floors; see the module documentation.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Bodies {
    /// The body of each node (`u32::MAX` for a node in no cell, which belongs to none).
    pub of_node: Vec<u32>,
    /// Number of bodies.
    pub count: usize,
    /// Force unit of the prescribed motions of each body, `f_D,b` (N): the largest
    /// prescribed displacement component on the body beyond its carried translation, each
    /// times the P-wave modulus S of the stiffest material around its node, times
    /// `diam_b^{d−2}`.
    pub force_floor: Vec<f64>,
    /// The regions of one material in the bodies, over which residuals are also summed
    /// ([`super::regions`]).
    pub regions: Regions,
}

impl Bodies {
    /// The bodies of `problem`, with the bodies of `rigid`.
    pub fn new(problem: &Problem, rigid: &RigidMotions) -> Self {
        let mesh = &problem.mesh;
        let d = mesh.dim();
        let count = rigid.bodies.len();
        let mut of_node = vec![u32::MAX; mesh.n_nodes()];
        for (b, body) in rigid.bodies.iter().enumerate() {
            for &v in &body.nodes {
                of_node[v as usize] = b as u32;
            }
        }
        // Largest prescribed motion per body beyond the translation its supports carry it
        // by (a rigid translation, taken exactly, asks no force of the body), each times the
        // stiffness of the material it moves (a soft body is not measured against a stiff
        // one's modulus).
        let stiffness = super::constraints::node_stiffness(problem);
        let mut motion = vec![0.0f64; count];
        let u_d = problem.prescribed_displacement();
        let carried = problem.carried_displacement();
        let dofs = problem.dof_map();
        for (k, x) in u_d.iter().enumerate() {
            let b = of_node[k / d];
            if dofs.is_fixed(k) && b != u32::MAX {
                let beyond = x - carried.as_ref().map_or(0.0, |c| c[k]);
                let m = &mut motion[b as usize];
                *m = m.max(stiffness[k / d] * beyond.abs());
            }
        }
        let force_floor = rigid
            .bodies
            .iter()
            .zip(&motion)
            .map(|(body, m)| {
                let (lo, hi) = body.bounding_box;
                let diam = (0..3).map(|i| (hi[i] - lo[i]).powi(2)).sum::<f64>().sqrt();
                m * diam.powi(d as i32 - 2)
            })
            .collect();
        let regions = Regions::new(mesh, |c| problem.cell_material(c), &of_node);
        Bodies {
            of_node,
            count,
            force_floor,
            regions,
        }
    }

    /// These bodies on a part `mesh` of the mesh whose node `l` is the whole mesh's
    /// `nodes[l]` and whose cell p is its `cells[p]`: [`Bodies::of_node`] and the regions'
    /// cells and nodes are the part's.
    pub fn restricted(&self, nodes: &[u32], mesh: &Mesh, cells: &[u32]) -> Bodies {
        Bodies {
            of_node: nodes.iter().map(|&v| self.of_node[v as usize]).collect(),
            count: self.count,
            force_floor: self.force_floor.clone(),
            regions: self.regions.restricted(mesh, cells),
        }
    }

    /// The Euclidean norm per body of the DOF vector whose entry `k` is `value(k)` (`n`
    /// entries, DOF order, dimension `d`; 0 for a DOF left out), into `out` (one per body),
    /// summed in DOF order over the DOFs `share` counts, then over the processes.
    pub fn norms(
        &self,
        share: &Share,
        d: usize,
        n: usize,
        value: impl Fn(usize) -> f64,
        out: &mut Vec<f64>,
    ) {
        out.clear();
        out.resize(self.count, 0.0);
        for k in 0..n {
            let b = self.of_node[k / d];
            if b != u32::MAX && share.counts_dof(k) {
                let x = value(k);
                out[b as usize] += x * x;
            }
        }
        share.sum(out);
        out.iter_mut().for_each(|s| *s = s.sqrt());
    }

    /// The equilibrium residual `‖∇E|_b‖` of every body over its free DOFs (`fixed(k)`: DOF
    /// k prescribed) for the gradient `grad` (DOF order), into `out` ([`Bodies::norms`]).
    pub fn residuals(
        &self,
        share: &Share,
        d: usize,
        grad: &[f64],
        fixed: impl Fn(usize) -> bool,
        out: &mut Vec<f64>,
    ) {
        self.norms(
            share,
            d,
            grad.len(),
            |k| if fixed(k) { 0.0 } else { grad[k] },
            out,
        );
    }

    /// The force scale `F_b = max(‖f_ext|_b‖, ‖∇W|_b‖, f_D,b)` of every body (N; at least
    /// the smallest positive number), for the external forces `f_ext` and the bulk gradient
    /// minus the external forces `grad_bulk = ∇W − f_ext` (DOF order), into `out`; `external`
    /// holds `‖f_ext|_b‖` ([`Bodies::norms`] of `f_ext`).
    pub fn force_scales(
        &self,
        share: &Share,
        d: usize,
        grad_bulk: &[f64],
        f_ext: &[f64],
        external: &[f64],
        out: &mut Vec<f64>,
    ) {
        // Internal forces ∇W over every DOF, reactions included.
        self.norms(share, d, grad_bulk.len(), |k| grad_bulk[k] + f_ext[k], out);
        for ((s, e), floor) in out.iter_mut().zip(external).zip(&self.force_floor) {
            *s = e.max(*s).max(*floor).max(f64::MIN_POSITIVE);
        }
    }

    /// The `(residual, scale)` of the body whose `residual` is largest relative to its
    /// `scale` (scales taken at least the smallest positive number; a NaN residual is the
    /// worst); `(0, f64::MIN_POSITIVE)` without bodies.
    pub fn worst(residual: &[f64], scale: &[f64]) -> (f64, f64) {
        let mut worst = (0.0, f64::MIN_POSITIVE);
        for (&r, &s) in residual.iter().zip(scale) {
            let s = s.max(f64::MIN_POSITIVE);
            if f64::is_nan(worst.0) {
                break;
            }
            if r.is_nan() || r / s > worst.0 / worst.1 || (r == 0.0 && worst.0 == 0.0) {
                worst = (r, s);
            }
        }
        worst
    }

    /// The energy norm `‖v|_b‖_E = (Σ_{T ∈ b} |T| A ε_T(v):ε_T(v))^{1/2}` of `v` on each body
    /// (Hooke law `hooke(c)` in cell `c`; the same sum as [`crate::assembly::norms::energy_norm`], cell by cell,
    /// scaled by a power of two against overflow), into `out`; the cells `share` counts,
    /// then over the processes.
    pub fn energy_norms(
        &self,
        share: &Share,
        mesh: &Mesh,
        hooke: &dyn Fn(usize) -> Hooke,
        v: &[f64],
        out: &mut Vec<f64>,
    ) {
        let d = mesh.dim();
        let mut scale = vec![0.0f64; self.count];
        for (k, x) in v.iter().enumerate() {
            let b = self.of_node[k / d];
            if b != u32::MAX && share.counts_dof(k) {
                scale[b as usize] = scale[b as usize].max(x.abs());
            }
        }
        share.max(&mut scale);
        for s in scale.iter_mut() {
            if *s != 0.0 && s.is_finite() {
                *s = s.log2().ceil().min(1023.0).exp2();
            }
        }
        out.clear();
        out.resize(self.count, 0.0);
        for c in 0..mesh.n_cells() {
            let b = self.of_node[mesh.cell(c)[0] as usize] as usize;
            let s = scale[b];
            if s == 0.0 || !s.is_finite() || !share.counts_cell(c) {
                continue;
            }
            let (measure, eps) = element::cell_strain(mesh, v, c);
            out[b] += measure * hooke(c).energy(&eps.scaled(1.0 / s));
        }
        share.sum(out);
        for (n, s) in out.iter_mut().zip(&scale) {
            *n = if *s == 0.0 {
                0.0
            } else if !s.is_finite() {
                f64::INFINITY
            } else {
                s * n.max(0.0).sqrt()
            };
        }
    }
}
