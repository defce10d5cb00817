//! Contact terms of the convexified energy: for every contact point i,
//!
//! `w_i [ P(u_ν,i) + F_i^k j_cvx(u_τ,i) − b_i^k · u_τ,i ]`,
//!
//! with the *frozen* friction bound `F_i^k` and linear term `b_i^k = F_i^k ∇h(u_τ,i^k)` (the
//! difference-of-convex step) taken from the previous outer iterate (see [`ContactData`]).
//! `j_cvx` is the (regularized) convex part of the friction potential. The term is convex in
//! u whenever `F_i^k ≥ 0`.
//!
//! Exact constraints (see [`crate::solver::constraints`]) replace two of these terms by
//! their augmented Lagrangians, with multipliers frozen like F and b, and a penalty `r_i`:
//!
//! - Signorini (`u_ν ≤ g`, multiplier λ_i = contact pressure): `P` becomes
//!   `(1/2r) [(λ + r(u_ν − g))_+² − λ²]`, i.e. normal compliance of stiffness r at the gap
//!   `g − λ/r` ([`crate::contact::NormalLaw::effective`]);
//! - exact friction (multiplier τ_i = −σ_τ, the friction traction): `F j_cvx(ξ) = F‖ξ‖`
//!   becomes its Moreau envelope at τ + rξ.
//!
//! The tangential term, smoothed or exact, is the friction law's
//! ([`crate::contact::Friction::tangential_term`]); this module maps tangential and global
//! coordinates.

use super::pattern::{SystemPattern, FIXED_SLOT};
pub use crate::contact::friction::project_ball;
use crate::contact::{ContactBoundary, ContactNodes, NormalLaw, NormalResponse, TangentialData};
use crate::error::{Error, Result};

/// The per-point data of the contact terms held fixed over one convex problem: the friction
/// data of the convexification and the contact multipliers of the exact constraints. The
/// solver owns these vectors ([`crate::solver::Frozen`]); the assembler only reads them.
#[derive(Clone, Copy, Debug)]
pub struct ContactData<'a> {
    /// Friction bound F_i^k ≥ 0 per point (Pa, or N/m in 2D).
    pub bound: &'a [f64],
    /// Linear term `b_i^k = F_i^k ∇h(u_τ,i^k)` per point, tangential coordinates.
    pub linear: &'a [[f64; 2]],
    /// Signorini multiplier λ_i ≥ 0 (the contact pressure, Pa) per point; unused (zero) at
    /// normal-compliance points.
    pub pressure: &'a [f64],
    /// Exact-friction multiplier τ_i = −σ_τ per point (Pa, tangential coordinates);
    /// unused (zero) where friction is regularized.
    pub traction: &'a [[f64; 2]],
}

/// The friction data of the convexification (the difference-of-convex step) at one outer
/// iterate, per contact point.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FrictionData {
    /// Friction bound F_i^k ≥ 0 (Pa, or N/m in 2D).
    pub bound: Vec<f64>,
    /// Linear term `b_i^k = F_i^k ∇h(u_τ,i^k)`, tangential coordinates.
    pub linear: Vec<[f64; 2]>,
}

impl FrictionData {
    /// No friction at any of `n` points (the first outer iteration of a Coulomb problem
    /// from an unloaded contact zone).
    pub fn zero(n: usize) -> Self {
        FrictionData {
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
    /// Elastic stiffness per unit area k_i per point (Pa/m,
    /// [`crate::solver::constraints::contact_stiffness`]): with the bound, the slip scale
    /// `F_i / k_i` of the point's smoothed norm.
    pub stiffness: &'a [f64],
    /// Augmented-Lagrangian penalty r_i per point (Pa/m) of the exact constraints.
    pub penalty: &'a [f64],
    /// The responses of the points of user-defined compliance laws at the displacement
    /// being assembled ([`ContactAssembler::normal_responses`]), one per point; empty when
    /// no contact part has such a law.
    pub responses: &'a [NormalResponse],
}

impl<'a> ContactAssembler<'a> {
    /// State of point `i` at displacement `u` (kinematics and pressure; the friction
    /// coefficient is evaluated for all points at once by
    /// [`ContactAssembler::friction_coefficients`]). At a Signorini point the pressure is
    /// the updated multiplier `(λ_i + r_i (u_ν − g))_+` of the frozen multiplier λ_i in
    /// `frozen`.
    #[inline]
    pub fn state(&self, u: &[f64], i: usize, frozen: &ContactData<'_>) -> PointState {
        let cb = &self.boundaries[self.nodes.boundary[i] as usize];
        let (u_nu, u_tau) = self.nodes.kinematics(self.dim, u, i);
        let slip = (u_tau[0] * u_tau[0] + u_tau[1] * u_tau[1]).sqrt();
        let pressure = if cb.normal.is_custom() {
            self.custom_response(i).pressure
        } else {
            let (law, gap) =
                cb.normal
                    .effective(self.nodes.gap[i], frozen.pressure[i], self.penalty[i]);
            law.pressure(u_nu, gap)
        };
        PointState {
            u_nu,
            u_tau,
            slip,
            pressure,
        }
    }

    /// The response of point `i` of a user-defined compliance law from
    /// [`ContactAssembler::responses`]; NaN if they were not computed (an error that shows).
    #[inline]
    fn custom_response(&self, i: usize) -> NormalResponse {
        self.responses.get(i).copied().unwrap_or(NormalResponse {
            energy: f64::NAN,
            pressure: f64::NAN,
            stiffness: f64::NAN,
        })
    }

    /// Whether a contact part has a user-defined compliance law.
    pub fn has_custom_normal(&self) -> bool {
        self.boundaries.iter().any(|b| b.normal.is_custom())
    }

    /// The responses (energy, pressure and, if `stiffness`, the derivative) of the points of
    /// the parts with a user-defined compliance law at displacement `u`, into `out` (resized
    /// to one per point; zero elsewhere): one batch of the law per contact part
    /// ([`crate::contact::CustomCompliance::responses`]). Pass the result as [`ContactAssembler::responses`] to assemble at `u`. Nothing is
    /// done (and `out` is left empty) when no part has such a law.
    ///
    /// # Errors
    /// [`Error::Law`] naming the law (`contact[k].normal (name)`) and the penetration.
    pub fn normal_responses(
        &self,
        u: &[f64],
        stiffness: bool,
        out: &mut Vec<NormalResponse>,
    ) -> Result<()> {
        out.clear();
        if !self.has_custom_normal() {
            return Ok(());
        }
        let n = self.nodes.len();
        out.resize(n, NormalResponse::default());
        let mut start = 0;
        let (mut penetration, mut responses) = (Vec::new(), Vec::new());
        for run in self.nodes.boundary.chunk_by(|a, b| a == b) {
            let range = start..start + run.len();
            start = range.end;
            let b = run[0] as usize;
            let cb = &self.boundaries[b];
            let NormalLaw::Custom(law) = &cb.normal else {
                continue;
            };
            penetration.clear();
            penetration.extend(
                range
                    .clone()
                    .map(|i| self.nodes.kinematics(self.dim, u, i).0 - self.nodes.gap[i]),
            );
            responses.clear();
            responses.resize(range.len(), NormalResponse::default());
            law.responses(&penetration, stiffness, &mut responses)
                .map_err(|message| Error::Law {
                    law: format!("contact[{b}].normal ({})", law.name),
                    message,
                })?;
            out[range].copy_from_slice(&responses);
        }
        Ok(())
    }

    /// The friction coefficient `μ_i = μ(‖u_τ,i‖)` (or `μ(x_i)` for a law of the position)
    /// of every point at displacement `u`, 0 at frictionless points: the slips of the
    /// points, then one evaluation of each contact part's law over its
    /// points ([`crate::contact::FrictionCoefficient::values`]). Allocates vectors of the
    /// number of points; called once per outer iteration and once for the certificate.
    ///
    /// # Errors
    /// [`Error::Law`] if a user-defined law fails, naming the law
    /// (`contact[k].friction.mu (name)`) and the slip.
    pub fn friction_coefficients(&self, u: &[f64]) -> Result<Vec<f64>> {
        let n = self.nodes.len();
        let mut mu = vec![0.0; n];
        let (mut slips, mut positions, mut values) = (Vec::new(), Vec::new(), Vec::new());
        let mut start = 0;
        // Points are ordered by boundary: each run is one contact part.
        for run in self.nodes.boundary.chunk_by(|a, b| a == b) {
            let range = start..start + run.len();
            start = range.end;
            let b = run[0] as usize;
            let Some(fr) = &self.boundaries[b].friction else {
                continue;
            };
            slips.clear();
            slips.extend(range.clone().map(|i| {
                let (_, t) = self.nodes.kinematics(self.dim, u, i);
                (t[0] * t[0] + t[1] * t[1]).sqrt()
            }));
            positions.clear();
            positions.extend(range.clone().map(|i| self.nodes.position[i]));
            values.clear();
            values.resize(range.len(), 0.0);
            fr.mu
                .values(&slips, &positions, self.dim, &mut values)
                .map_err(|message| Error::Law {
                    law: format!("contact[{b}].friction.mu ({})", fr.mu.name()),
                    message,
                })?;
            mu[range].copy_from_slice(&values);
        }
        Ok(mu)
    }

    /// The friction data of the convexification at displacement `u`: the bound
    /// `F_i = F(‖u_τ,i‖, p_i)` and the linear term `b_i = F_i ∇h(u_τ,i)`, with the contact
    /// multipliers of `current`. At a Signorini point a Coulomb bound takes the pressure from
    /// the current multiplier λ_i, not from its update `(λ_i + r_i(u_ν − g))_+`: the two
    /// agree at the fixed point, but the update amplifies the error of an inexact solve by
    /// the large penalty r, which would put a floor under the fixed-point residual.
    ///
    /// # Errors
    /// As [`ContactAssembler::friction_coefficients`] and
    /// [`ContactAssembler::normal_responses`].
    pub fn convexify(&self, u: &[f64], current: &ContactData<'_>) -> Result<FrictionData> {
        let n = self.nodes.len();
        let mu = self.friction_coefficients(u)?;
        let mut responses = Vec::new();
        self.normal_responses(u, false, &mut responses)?;
        let at_u = ContactAssembler {
            responses: &responses,
            ..*self
        };
        let mut data = FrictionData::zero(n);
        for i in 0..n {
            let cb = &self.boundaries[self.nodes.boundary[i] as usize];
            let Some(fr) = &cb.friction else { continue };
            let s = at_u.state(u, i, current);
            let pressure = if cb.normal.is_exact() {
                current.pressure[i]
            } else {
                s.pressure
            };
            let bound = fr.bound_of(mu[i], pressure);
            data.bound[i] = bound;
            let hs = fr.potential.h_slope(s.slip);
            if hs != 0.0 && s.slip > 0.0 {
                for a in 0..2 {
                    data.linear[i][a] = bound * hs * s.u_tau[a] / s.slip;
                }
            }
        }
        Ok(data)
    }

    /// Contact energy at `u` of the points counted here ([`ContactNodes::owned`]; the
    /// responses of user-defined compliance laws, if any, must be those at `u`); adds the
    /// gradient of every point to `grad` (all DOFs, DOF order) and, if
    /// `hess` is given, its Hessian to the upper-triangular values using the per-point node
    /// block slots `slots` (see [`contact_slots`]).
    pub fn assemble(
        &self,
        u: &[f64],
        frozen: &ContactData<'_>,
        grad: &mut [f64],
        hess: Option<(&mut [f64], &[u32])>,
    ) -> f64 {
        let d = self.dim;
        let mut energy = 0.0;
        let mut hess = hess;
        let paired = self.nodes.has_pairs();
        let stride = slot_stride(d, paired);
        // A process's ghost points (the last ones) complete its rows; their energy is
        // their slave node's owner's.
        let owned = self.nodes.owned();
        for i in 0..self.nodes.len() {
            let term = self.point(u, frozen, i);
            if i < owned {
                energy += term.energy;
            }
            if paired {
                let (n, nodes, coef) = self.nodes.stencil(d, i);
                for a in 0..n {
                    let v = nodes[a] as usize;
                    for k in 0..d {
                        grad[d * v + k] += coef[a] * term.gradient[k];
                    }
                }
                if let Some((h, slots)) = hess.as_mut() {
                    Self::add_stencil(d, &term, &coef, &slots[i * stride..(i + 1) * stride], h);
                }
                continue;
            }
            let v = self.nodes.node[i] as usize;
            for k in 0..d {
                grad[d * v + k] += term.gradient[k];
            }
            if let Some((h, slots)) = hess.as_mut() {
                Self::add_block(d, &term, &slots[i * 6..i * 6 + 6], h);
            }
        }
        energy
    }

    /// Adds the Hessian of `term` spread over a point's stencil with coefficients `coef`
    /// ([`ContactNodes::stencil`]; zero past its length): the block of stencil nodes
    /// (a, b) is `c_a c_b H`. `slots` are the point's [`slot_stride`] slots of the local
    /// upper triangle (see [`contact_slots`]).
    pub fn add_stencil(
        d: usize,
        term: &PointTerm,
        coef: &[f64; 4],
        slots: &[u32],
        hess: &mut [f64],
    ) {
        let l = (d + 1) * d;
        let mut idx = 0;
        for p in 0..l {
            for q in p..l {
                let slot = slots[idx];
                idx += 1;
                if slot == FIXED_SLOT {
                    continue;
                }
                let (a, k, b, m) = (p / d, p % d, q / d, q % d);
                hess[slot as usize] += coef[a] * coef[b] * term.hessian[k][m];
            }
        }
    }

    /// Adds the Hessian node block of `term` (dimension `d`) to the upper-triangular values
    /// `hess` at its point's slots `slots` (6 of them, see [`contact_slots`]).
    pub fn add_block(d: usize, term: &PointTerm, slots: &[u32], hess: &mut [f64]) {
        let mut idx = 0;
        for k in 0..d {
            for l in k..d {
                if slots[idx] != FIXED_SLOT {
                    hess[slots[idx] as usize] += term.hessian[k][l];
                }
                idx += 1;
            }
        }
    }

    /// The contact term of point `i` at `u`: its energy, its gradient with respect to the
    /// node's displacement (the force the body exerts on the foundation, N) and its
    /// (generalized) Hessian node block.
    pub fn point(&self, u: &[f64], frozen: &ContactData<'_>, i: usize) -> PointTerm {
        let d = self.dim;
        let m = d - 1;
        let cb = &self.boundaries[self.nodes.boundary[i] as usize];
        let w = self.nodes.weight[i];
        let (u_nu, xi) = self.nodes.kinematics(d, u, i);
        let n = &self.nodes.normal[i];
        let t = &self.nodes.tangent[i];
        // Normal part: w P(u_ν), gradient w p ν, Hessian w p' ν νᵀ (for Signorini the
        // augmented Lagrangian, a compliance law at a shifted gap, minus λ²/2r).
        let r = self.penalty[i];
        let (mut energy, p, kn) = if cb.normal.is_custom() {
            let c = self.custom_response(i);
            (w * c.energy, c.pressure, c.stiffness)
        } else {
            let (law, gap) = cb
                .normal
                .effective(self.nodes.gap[i], frozen.pressure[i], r);
            (
                w * law.energy(u_nu, gap),
                law.pressure(u_nu, gap),
                law.stiffness(u_nu, gap),
            )
        };
        if cb.normal.is_exact() {
            energy -= w * frozen.pressure[i] * frozen.pressure[i] / (2.0 * r);
        }
        // Tangential part: w times the friction law's term.
        let mut gt = [0.0; 2];
        let mut ht = [[0.0; 2]; 2];
        if let Some(fr) = &cb.friction {
            let data = TangentialData {
                bound: frozen.bound[i],
                linear: frozen.linear[i],
                traction: frozen.traction[i],
                penalty: r,
                stiffness: self.stiffness[i],
            };
            let term = fr.tangential_term(&xi, m, &data);
            energy += w * term.energy;
            gt = term.gradient;
            ht = term.hessian;
        }
        let mut gradient = [0.0; 3];
        let mut hessian = [[0.0; 3]; 3];
        for k in 0..d {
            gradient[k] = w * (p * n[k] + (0..m).map(|a| gt[a] * t[a][k]).sum::<f64>());
            for l in 0..d {
                let mut val = kn * n[k] * n[l];
                for a in 0..m {
                    for c in 0..m {
                        val += ht[a][c] * t[a][k] * t[c][l];
                    }
                }
                hessian[k][l] = w * val;
            }
        }
        PointTerm {
            energy,
            gradient,
            hessian,
        }
    }
}

/// The contact term of one point; see [`ContactAssembler::point`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PointTerm {
    /// Energy (J, J/m in 2D).
    pub energy: f64,
    /// Gradient with respect to the node's displacement (N), first d entries.
    pub gradient: [f64; 3],
    /// Hessian node block (N/m), first d × d entries.
    pub hessian: [[f64; 3]; 3],
}

/// Slots of the node blocks of the contact points in `pattern`: 6 entries per point (the
/// upper triangle `(k, l)`, `k ≤ l < d`, row by row, padded), [`FIXED_SLOT`] where a DOF is
/// prescribed.
///
/// With contact pairs ([`ContactNodes::has_pairs`]) every point has instead
/// [`slot_stride`] entries: the upper triangle, row by row, of the local matrix of its
/// stencil's DOFs `(a, k)` (stencil node a ≤ d, component k; [`ContactNodes::stencil`]),
/// each the slot of the global pair of equations in upper-triangular order.
pub fn contact_slots(
    nodes: &ContactNodes,
    dim: usize,
    equations: &[u32],
    pattern: &SystemPattern,
) -> Vec<u32> {
    if !nodes.has_pairs() {
        return node_block_slots(&nodes.node, dim, equations, pattern);
    }
    let l = (dim + 1) * dim;
    let stride = slot_stride(dim, true);
    let mut slots = vec![FIXED_SLOT; stride * nodes.len()];
    for i in 0..nodes.len() {
        let (n, stencil, _) = nodes.stencil(dim, i);
        let equation = |p: usize| {
            let a = p / dim;
            if a < n {
                equations[dim * stencil[a] as usize + p % dim]
            } else {
                u32::MAX
            }
        };
        let mut idx = 0;
        for p in 0..l {
            for q in p..l {
                let (a, b) = (equation(p), equation(q));
                if a != u32::MAX && b != u32::MAX {
                    if let Some(s) = pattern.find(a.min(b) as usize, a.max(b) as usize) {
                        slots[stride * i + idx] = s as u32;
                    }
                }
                idx += 1;
            }
        }
    }
    slots
}

/// Number of Hessian slots per contact point in [`contact_slots`]: 6 (a node block) without
/// contact pairs, and the upper triangle of the `(d + 1) d` stencil DOFs with them (21 in
/// 2D, 78 in 3D).
pub fn slot_stride(dim: usize, paired: bool) -> usize {
    if paired {
        let l = (dim + 1) * dim;
        l * (l + 1) / 2
    } else {
        6
    }
}

/// Slots in `pattern` of the diagonal node blocks of the nodes `nodes`, as
/// [`contact_slots`] (6 per node).
pub fn node_block_slots(
    nodes: &[u32],
    dim: usize,
    equations: &[u32],
    pattern: &SystemPattern,
) -> Vec<u32> {
    let mut slots = vec![FIXED_SLOT; 6 * nodes.len()];
    for (i, &v) in nodes.iter().enumerate() {
        let v = v as usize;
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
