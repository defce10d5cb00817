//! Contact terms of the convexified energy (SPEC §4): for every contact point i,
//!
//! `w_i [ P(u_ν,i) + F_i^k j_cvx(u_τ,i) − b_i^k · u_τ,i ]`,
//!
//! with the *frozen* friction bound `F_i^k` and linear term `b_i^k = F_i^k ∇h(u_τ,i^k)` (the
//! difference-of-convex step) taken from the previous outer iterate (see [`Frozen`]).
//! `j_cvx` is the (regularized) convex part of the friction potential. The term is convex in
//! u whenever `F_i^k ≥ 0`.

use super::pattern::{SystemPattern, FIXED_SLOT};
use crate::contact::friction::regularized_norm;
use crate::contact::{ContactBoundary, ContactNodes};

/// The quantities frozen at the contact points for one convex subproblem.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frozen {
    /// Friction bound F_i^k ≥ 0 per point (Pa, or N/m in 2D).
    pub bound: Vec<f64>,
    /// Linear term `b_i^k = F_i^k ∇h(u_τ,i^k)` per point, tangential coordinates.
    pub linear: Vec<[f64; 2]>,
}

impl Frozen {
    /// No friction at any of `n` points (the first outer iteration of a Coulomb problem
    /// from an unloaded contact zone).
    pub fn zero(n: usize) -> Self {
        Frozen {
            bound: vec![0.0; n],
            linear: vec![[0.0; 2]; n],
        }
    }
}

/// The state of one contact point at a displacement u.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PointState {
    /// Normal displacement u_ν (m).
    pub u_nu: f64,
    /// Tangential displacement coordinates (m).
    pub u_tau: [f64; 2],
    /// Slip ‖u_τ‖ (m).
    pub slip: f64,
    /// Contact pressure p(u_ν) ≥ 0.
    pub pressure: f64,
    /// Friction bound F at this state (not frozen).
    pub bound: f64,
}

/// Contact terms over the contact points.
#[derive(Clone, Copy, Debug)]
pub struct ContactAssembler<'a> {
    /// Spatial dimension.
    pub dim: usize,
    /// The contact points.
    pub nodes: &'a ContactNodes,
    /// The contact boundaries (laws and gaps).
    pub boundaries: &'a [ContactBoundary],
    /// Numerical regularization ρ_num of the norm in j_cvx (m).
    pub rho_num: f64,
}

impl<'a> ContactAssembler<'a> {
    /// State of point `i` at displacement `u`, with the friction bound evaluated at that
    /// state (SPEC §1).
    #[inline]
    pub fn state(&self, u: &[f64], i: usize) -> PointState {
        let cb = &self.boundaries[self.nodes.boundary[i] as usize];
        let (u_nu, u_tau) = self.nodes.kinematics(self.dim, u, i);
        let slip = (u_tau[0] * u_tau[0] + u_tau[1] * u_tau[1]).sqrt();
        let pressure = cb.normal.pressure(u_nu, cb.gap);
        let bound = cb
            .friction
            .as_ref()
            .map_or(0.0, |f| f.bound_value(slip, pressure));
        PointState {
            u_nu,
            u_tau,
            slip,
            pressure,
            bound,
        }
    }

    /// The frozen quantities at displacement `u` (the convexification step of SPEC §4).
    pub fn freeze(&self, u: &[f64]) -> Frozen {
        let n = self.nodes.len();
        let mut frozen = Frozen::zero(n);
        for i in 0..n {
            let cb = &self.boundaries[self.nodes.boundary[i] as usize];
            let Some(fr) = &cb.friction else { continue };
            let s = self.state(u, i);
            frozen.bound[i] = s.bound;
            let hs = fr.potential.h_slope(s.slip);
            if hs != 0.0 && s.slip > 0.0 {
                for a in 0..2 {
                    frozen.linear[i][a] = s.bound * hs * s.u_tau[a] / s.slip;
                }
            }
        }
        frozen
    }

    /// Contact energy at `u`; adds its gradient to `grad` (all DOFs, DOF order) and, if
    /// `hess` is given, its Hessian to the upper-triangular values using the per-point node
    /// block slots `slots` (see [`contact_slots`]).
    pub fn assemble(
        &self,
        u: &[f64],
        frozen: &Frozen,
        grad: &mut [f64],
        hess: Option<(&mut [f64], &[u32])>,
    ) -> f64 {
        let d = self.dim;
        let m = d - 1;
        let mut energy = 0.0;
        let mut hess = hess;
        for i in 0..self.nodes.len() {
            let cb = &self.boundaries[self.nodes.boundary[i] as usize];
            let w = self.nodes.weight[i];
            let (u_nu, xi) = self.nodes.kinematics(d, u, i);
            let n = &self.nodes.normal[i];
            let t = &self.nodes.tangent[i];
            // Normal part: w P(u_ν), gradient w p ν, Hessian w p' ν νᵀ.
            energy += w * cb.normal.energy(u_nu, cb.gap);
            let p = cb.normal.pressure(u_nu, cb.gap);
            let kn = cb.normal.stiffness(u_nu, cb.gap);
            // Tangential part: w [F φ(ξ) − b·ξ].
            let mut gt = [0.0; 2];
            let mut ht = [[0.0; 2]; 2];
            if let Some(fr) = &cb.friction {
                let f = frozen.bound[i];
                let b = frozen.linear[i];
                let rho = fr.potential.convex_rho(self.rho_num);
                let (phi, g, h) = regularized_norm(&xi, m, rho);
                energy += w * (f * phi - (0..m).map(|a| b[a] * xi[a]).sum::<f64>());
                for a in 0..m {
                    gt[a] = f * g[a] - b[a];
                    for c in 0..m {
                        ht[a][c] = f * h[a][c];
                    }
                }
            }
            let v = self.nodes.node[i] as usize;
            let mut gnode = [0.0; 3];
            for k in 0..d {
                gnode[k] = w * (p * n[k] + (0..m).map(|a| gt[a] * t[a][k]).sum::<f64>());
                grad[d * v + k] += gnode[k];
            }
            if let Some((h, slots)) = hess.as_mut() {
                let s = &slots[i * 6..i * 6 + 6];
                let mut idx = 0;
                for k in 0..d {
                    for l in k..d {
                        let mut val = kn * n[k] * n[l];
                        for a in 0..m {
                            for c in 0..m {
                                val += ht[a][c] * t[a][k] * t[c][l];
                            }
                        }
                        if s[idx] != FIXED_SLOT {
                            h[s[idx] as usize] += w * val;
                        }
                        idx += 1;
                    }
                }
            }
        }
        energy
    }
}

/// Slots of the node blocks of the contact points in `pattern`: 6 entries per point (the
/// upper triangle `(k, l)`, `k ≤ l < d`, row by row, padded), [`FIXED_SLOT`] where a DOF is
/// prescribed.
pub fn contact_slots(
    nodes: &ContactNodes,
    dim: usize,
    equations: &[u32],
    pattern: &SystemPattern,
) -> Vec<u32> {
    let mut slots = vec![FIXED_SLOT; 6 * nodes.len()];
    for i in 0..nodes.len() {
        let v = nodes.node[i] as usize;
        let mut idx = 0;
        for k in 0..dim {
            for l in k..dim {
                let (a, b) = (equations[dim * v + k], equations[dim * v + l]);
                if a != u32::MAX && b != u32::MAX {
                    if let Some(s) = pattern.find(a as usize, b as usize) {
                        slots[6 * i + idx] = s as u32;
                    }
                }
                idx += 1;
            }
        }
    }
    slots
}
