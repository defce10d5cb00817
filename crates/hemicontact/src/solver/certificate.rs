//! The certificate of a solve: residuals that let a user trust the answer without trusting
//! the code (SPEC §4).
//!
//! The interface force at contact point i is recovered from *equilibrium of the body*:
//! the node's balance `f_i − ∇W_i(u) + R_i = 0` gives the force the foundation exerts on
//! it, `R_i = ∇W_i(u) − f_i` (internal minus external nodal forces). It is then checked against the contact laws evaluated at
//! the final displacement — with the *actual* friction bound `F(u)`, not the frozen one, so
//! the certificate also certifies that the outer fixed point was reached:
//!
//! - normal law: `R_i·ν_i = −w_i p(u_ν,i)`;
//! - friction law: with slip `r = ‖u_τ,i‖` and bound `F = F(u)`: if `r > r_stick` (slip),
//!   `R_τ,i = −w_i F j'(r) u_τ/r` (the force opposes the slip and equals the bound);
//!   otherwise (stick) `‖R_τ,i‖ ≤ w_i F j'(0)`; for the smooth law (19) always
//!   `R_τ,i = −w_i F ∇j(u_τ)`.
//!
//! Status: *separated* when the pressure is zero (for Coulomb-type bounds and frictionless
//! contact; a Tresca-type bound acts regardless of the pressure, so its points are stick or
//! slip), *slip* when in contact with `r > r_stick` (or frictionless), *stick* otherwise.
//!
//! On a roller node (some components prescribed), a law is only checked along directions
//! that involve free components only: along a prescribed one the force is a support
//! reaction.
//!
//! At a node shared by several contact boundaries (an edge or corner between walls), the
//! equilibrium force is one vector for several points: the force attributed to a point is
//! what remains after subtracting the model forces of the node's other points.
//!
//! Residuals are forces (N, or N/m in 2D), reported relative to the force scale `S` =
//! the largest nodal external force or contact force, at least the force unit of the
//! prescribed displacements ([`super::System::force_floor`]). `r_stick = 10³ ρ_num`.

use super::constraints::KktCertificate;
use crate::assembly::contact::{ContactAssembler, Frozen};
use crate::contact::{FrictionBound, FrictionPotential};
use serde::Serialize;

/// Contact status of a point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Status {
    /// Not touching the foundation (u_ν < g): no force.
    Separated,
    /// In contact, tangential force below the bound, no slip.
    Stick,
    /// In contact and slipping: the tangential force equals the bound.
    Slip,
}

impl Status {
    /// Integer code for VTK/CSV output: 0 separated, 1 stick, 2 slip.
    pub fn code(self) -> i32 {
        match self {
            Status::Separated => 0,
            Status::Stick => 1,
            Status::Slip => 2,
        }
    }
}

/// Results at one contact point.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ContactResult {
    /// Mesh node.
    pub node: u32,
    /// Contact boundary index.
    pub boundary: usize,
    /// Lumped weight w_i.
    pub weight: f64,
    /// Normal displacement u_ν (m).
    pub u_nu: f64,
    /// Current gap `g − u_ν` (m; negative: penetration of the asperities).
    pub gap: f64,
    /// Tangential displacement coordinates (m).
    pub u_tau: [f64; 2],
    /// Slip ‖u_τ‖ (m).
    pub slip: f64,
    /// Contact pressure p (Pa, N/m in 2D) = −σ_ν.
    pub pressure: f64,
    /// Friction bound F(u).
    pub bound: f64,
    /// Interface force on the body from equilibrium, normal part `R·ν` (N).
    pub force_normal: f64,
    /// Interface force, tangential coordinates (N).
    pub force_tangential: [f64; 2],
    /// Interface force in global coordinates (N).
    pub force: [f64; 3],
    /// Friction traction `−σ_τ = −R_τ / w` in global coordinates (Pa, N/m in 2D): the
    /// friction multiplier of exact friction, recovered from equilibrium.
    pub friction_traction: [f64; 3],
    /// Status.
    pub status: Status,
    /// Normal-law residual (N).
    pub normal_residual: f64,
    /// Friction-law residual (N).
    pub friction_residual: f64,
}

/// The certificate; see the module documentation.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Certificate {
    /// Relative equilibrium residual of the last convex problem (‖∇E_k‖ / force scale of
    /// the Newton criterion).
    pub equilibrium: f64,
    /// Largest normal-law residual, relative to the force scale.
    pub normal_law: f64,
    /// Largest friction-law residual, relative to the force scale.
    pub friction_law: f64,
    /// Node with the largest friction-law residual, if any.
    pub worst_friction_node: Option<u32>,
    /// The force scale S (N).
    pub force_scale: f64,
    /// Slip below which a point counts as sticking (m).
    pub stick_threshold: f64,
    /// Number of points in contact.
    pub n_contact: usize,
    /// Number of slipping points.
    pub n_slip: usize,
    /// KKT residuals of the exact constraints, if the problem has any.
    pub kkt: Option<KktCertificate>,
}

/// Evaluates the contact results and the certificate at `u`. `grad_bulk` is `∇W(u) − f`
/// (DOF order, so it is the interface force at contact nodes) and `f_ext` the external
/// forces; `frozen` the quantities of the last convex problem (its multipliers give the
/// pressure at Signorini points and the stick/slip classification of exact friction:
/// stick where `‖τ + r u_τ‖ ≤ F`, i.e. the projection defining the friction force is
/// inactive).
pub fn evaluate(
    ca: &ContactAssembler<'_>,
    u: &[f64],
    grad_bulk: &[f64],
    f_ext: &[f64],
    fixed: &dyn Fn(usize) -> bool,
    equilibrium: f64,
    frozen: &Frozen,
    force_floor: f64,
) -> (Vec<ContactResult>, Certificate) {
    let d = ca.dim;
    let m = d - 1;
    let stick_threshold = 1e3 * ca.rho_num;
    let u_scale = u
        .chunks(d)
        .map(|c| c.iter().map(|x| x * x).sum::<f64>().sqrt())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let mut kkt = KktCertificate::default();
    // The other points on the node of point i (points are ordered by boundary, so they are
    // found through a node → points map).
    let mut by_node: std::collections::BTreeMap<u32, Vec<usize>> = Default::default();
    for (i, &v) in ca.nodes.node.iter().enumerate() {
        by_node.entry(v).or_default().push(i);
    }
    let shared = |i: usize| -> Vec<usize> {
        by_node
            .get(&ca.nodes.node[i])
            .map(|pts| pts.iter().copied().filter(|&j| j != i).collect())
            .unwrap_or_default()
    };
    let mut max_pressure = 0.0f64;
    let mut min_pressure = f64::INFINITY;
    let mut exact_any = false;
    let mut results = Vec::with_capacity(ca.nodes.len());
    let mut scale = f_ext
        .chunks(d)
        .map(|c| c.iter().map(|x| x * x).sum::<f64>().sqrt())
        .fold(0.0, f64::max);
    for i in 0..ca.nodes.len() {
        let s = ca.state(u, i, frozen);
        let cb = &ca.boundaries[ca.nodes.boundary[i] as usize];
        let w = ca.nodes.weight[i];
        let v = ca.nodes.node[i] as usize;
        let mut force = [0.0; 3];
        for k in 0..d {
            force[k] = grad_bulk[d * v + k];
        }
        // A node on several contact boundaries (an edge between two walls) has one
        // equilibrium force for all its points: attribute to this point what remains after
        // the model forces of the node's other points.
        for j in shared(i) {
            let g = ca.point(u, frozen, j).gradient;
            for k in 0..d {
                force[k] += g[k];
            }
        }
        let n = &ca.nodes.normal[i];
        let t = &ca.nodes.tangent[i];
        let fn_ = (0..d).map(|k| force[k] * n[k]).sum::<f64>();
        let mut ft = [0.0; 2];
        for a in 0..m {
            ft[a] = (0..d).map(|k| force[k] * t[a][k]).sum();
        }
        // On a roller, the force along a prescribed component is a support reaction, not a
        // contact force: a law is checked only along directions made of free components.
        let free = |dir: &[f64; 3]| (0..d).all(|k| dir[k].abs() < 1e-12 || !fixed(d * v + k));
        let normal_checked = free(n);
        let tangent_checked = (0..m).all(|a| free(&t[a]));
        let normal_residual = if normal_checked {
            (fn_ + w * s.pressure).abs()
        } else {
            0.0
        };
        let ft_norm = (ft[0] * ft[0] + ft[1] * ft[1]).sqrt();
        let in_contact = s.pressure > 0.0;
        let (status, friction_residual) = match &cb.friction {
            None => (
                if in_contact {
                    Status::Slip
                } else {
                    Status::Separated
                },
                ft_norm,
            ),
            Some(fr) if !in_contact && fr.bound == FrictionBound::Coulomb => {
                (Status::Separated, ft_norm)
            }
            Some(fr) => {
                let smooth = matches!(fr.potential, FrictionPotential::Regularized { .. });
                let wf = w * s.bound;
                let slipping = if fr.exact {
                    let (r, tau) = (ca.penalty[i], frozen.traction[i]);
                    let z = [tau[0] + r * s.u_tau[0], tau[1] + r * s.u_tau[1]];
                    let stick = frozen.bound[i] > 0.0
                        && crate::assembly::contact::project_ball(&z, m, frozen.bound[i]).1;
                    if stick {
                        kkt.stick_slip = kkt.stick_slip.max(s.slip / u_scale);
                    }
                    kkt.n_constraints.2 += 1;
                    !stick && s.slip > 0.0
                } else {
                    s.slip > stick_threshold
                };
                if slipping || smooth {
                    // R_τ = −w F j'(r) u_τ/r.
                    let slope = if s.slip > 0.0 {
                        fr.potential.slope(s.slip) / s.slip
                    } else {
                        0.0
                    };
                    let r2: f64 = (0..m)
                        .map(|a| (ft[a] + wf * slope * s.u_tau[a]).powi(2))
                        .sum();
                    let st = if slipping {
                        Status::Slip
                    } else {
                        Status::Stick
                    };
                    (st, r2.sqrt())
                } else {
                    (
                        Status::Stick,
                        (ft_norm - wf * fr.potential.slope(0.0)).max(0.0),
                    )
                }
            }
        };
        let friction_residual = if tangent_checked {
            friction_residual
        } else {
            0.0
        };
        let mut friction_traction = [0.0; 3];
        for a in 0..m {
            for k in 0..d {
                friction_traction[k] -= ft[a] * t[a][k] / w;
            }
        }
        scale = scale.max(w * s.pressure).max(w * s.bound);
        if cb.normal.is_exact() {
            exact_any = true;
            kkt.n_constraints.1 += 1;
            max_pressure = max_pressure.max(s.pressure);
            min_pressure = min_pressure.min(s.pressure);
            kkt.contact_violation = kkt
                .contact_violation
                .max((s.u_nu - cb.gap).max(0.0) / u_scale);
        }
        exact_any |= cb.friction.as_ref().is_some_and(|f| f.exact);
        results.push(ContactResult {
            node: ca.nodes.node[i],
            boundary: ca.nodes.boundary[i] as usize,
            weight: w,
            u_nu: s.u_nu,
            gap: cb.gap - s.u_nu,
            u_tau: s.u_tau,
            slip: s.slip,
            pressure: s.pressure,
            bound: s.bound,
            force_normal: fn_,
            force_tangential: ft,
            force,
            friction_traction,
            status,
            normal_residual,
            friction_residual,
        });
    }
    let scale = scale.max(force_floor).max(f64::MIN_POSITIVE);
    if max_pressure > 0.0 {
        kkt.contact_min_multiplier = min_pressure / max_pressure;
        for (r, cb) in results
            .iter()
            .map(|r| (r, &ca.boundaries[r.boundary]))
            .filter(|(_, cb)| cb.normal.is_exact())
        {
            kkt.contact_complementarity = kkt
                .contact_complementarity
                .max(r.pressure * (cb.gap - r.u_nu).abs() / (max_pressure * u_scale));
        }
    }
    let mut cert = Certificate {
        kkt: exact_any.then_some(kkt),
        equilibrium,
        force_scale: scale,
        stick_threshold,
        ..Certificate::default()
    };
    for r in &results {
        cert.normal_law = cert.normal_law.max(r.normal_residual / scale);
        if r.friction_residual / scale > cert.friction_law {
            cert.friction_law = r.friction_residual / scale;
            cert.worst_friction_node = Some(r.node);
        }
        if r.status != Status::Separated {
            cert.n_contact += 1;
        }
        if r.status == Status::Slip {
            cert.n_slip += 1;
        }
    }
    (results, cert)
}
