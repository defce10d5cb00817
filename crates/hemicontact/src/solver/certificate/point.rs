//! The certificate at one contact point: its interface force from equilibrium, its scales,
//! and the residuals of its normal and friction laws (see the module documentation of
//! [`super`]).

use super::inputs::Inputs;
use super::results::{ContactResult, FrictionState, NormalState};
use crate::assembly::contact::{ContactAssembler, PointState};
use crate::contact::{ContactBoundary, FrictionBound, FrictionPotential};
use crate::solver::multipliers::KktCertificate;
use crate::solver::round_off::{above_floor, point_floor};

/// The results at contact point `i` (one of this process's own points) from `grad_bulk`
/// (`∇W − f` with the pairs' reactions), the other points `others` on its node; the KKT
/// residual of exact friction at a sticking point goes to `kkt`.
pub(super) fn result(
    ca: &ContactAssembler<'_>,
    inp: &Inputs<'_>,
    grad_bulk: &[f64],
    i: usize,
    others: &[usize],
    kkt: &mut KktCertificate,
) -> ContactResult {
    let Inputs {
        u,
        mu,
        fixed,
        floor,
        round_off,
        frozen,
        tolerance,
        ..
    } = *inp;
    let d = ca.dim;
    let m = d - 1;
    let s = ca.state(u, i, &frozen);
    let cb = &ca.boundaries[ca.nodes.boundary[i] as usize];
    // The friction bound F at this state (not frozen).
    let bound = cb
        .friction
        .as_ref()
        .map_or(0.0, |f| f.bound_of(mu[i], s.pressure));
    let w = ca.nodes.weight[i];
    let v = ca.nodes.node[i] as usize;
    // The point's own scales: its force, at least a fraction of the force its node
    // passes, and the slip that force causes around it.
    let force_scale = (w * bound.max(s.pressure))
        .max(floor[i])
        .max(f64::MIN_POSITIVE);
    let slip_scale = force_scale / (w * ca.stiffness[i]);
    let force = interface_force(ca, inp, grad_bulk, i, others);
    let n = &ca.nodes.normal[i];
    let t = &ca.nodes.tangent[i];
    let fn_ = (0..d).map(|k| force[k] * n[k]).sum::<f64>();
    let mut ft = [0.0; 2];
    for a in 0..m {
        ft[a] = (0..d).map(|k| force[k] * t[a][k]).sum();
    }
    // The round-off of the force at the node, within which a residual is no residual.
    let noise = point_floor(&round_off.dof, d, v, fixed);
    // A residual within the tolerance stands as it is; one beyond it may be round-off.
    let law = |r: f64| {
        if r <= tolerance * force_scale {
            r
        } else {
            above_floor(r, noise).abs()
        }
    };
    let normal_residual = law((fn_ + w * s.pressure).abs());
    let normal_state = if s.pressure > 0.0 {
        NormalState::Contact
    } else {
        NormalState::Separated
    };
    let friction = FrictionAt {
        s: &s,
        bound,
        w,
        ft,
        slip_scale,
        stick_threshold: tolerance * slip_scale,
        normal_state,
    };
    let (friction_state, raw_friction_residual) = friction.check(ca, inp, cb, i, kkt);
    let friction_residual = law(raw_friction_residual);
    let mut friction_traction = [0.0; 3];
    for a in 0..m {
        for k in 0..d {
            friction_traction[k] += ft[a] * t[a][k] / w;
        }
    }
    ContactResult {
        node: ca.nodes.node[i],
        boundary: ca.nodes.boundary[i] as usize,
        weight: w,
        u_nu: s.u_nu,
        gap: ca.nodes.gap[i] - s.u_nu,
        u_tau: s.u_tau,
        slip: s.slip,
        pressure: s.pressure,
        bound,
        force_normal: fn_,
        force_tangential: ft,
        force,
        friction_traction,
        normal_state,
        friction_state,
        normal_residual,
        friction_residual,
        force_scale,
        slip_scale,
    }
}

/// The interface force on the body at contact point `i` (N, global coordinates) from
/// equilibrium: `∇W − f` at the free components of its node, the model force at the
/// prescribed ones (the support and the foundation share the force there); at a node with
/// other points `others`, what remains after their model forces.
fn interface_force(
    ca: &ContactAssembler<'_>,
    inp: &Inputs<'_>,
    grad_bulk: &[f64],
    i: usize,
    others: &[usize],
) -> [f64; 3] {
    let Inputs {
        u, fixed, frozen, ..
    } = *inp;
    let d = ca.dim;
    let v = ca.nodes.node[i] as usize;
    let model = ca.point(u, &frozen, i).gradient;
    let mut force = [0.0; 3];
    for k in 0..d {
        force[k] = if fixed(d * v + k) {
            // A prescribed component: the support and the foundation share the force,
            // so the contact force is the model's, the support reaction the rest.
            -model[k]
        } else {
            grad_bulk[d * v + k]
        };
    }
    // A node on several contact boundaries (an edge between two walls) has one
    // equilibrium force for all its points: attribute to this point what remains after
    // the model forces of the node's other points.
    for &j in others {
        let g = ca.point(u, &frozen, j).gradient;
        for k in 0..d {
            if !fixed(d * v + k) {
                force[k] += g[k];
            }
        }
    }
    force
}

/// What the friction check of a point needs of it.
struct FrictionAt<'s> {
    /// The point's state at the displacement.
    s: &'s PointState,
    /// The friction bound F at this state (not frozen).
    bound: f64,
    /// The point's weight w.
    w: f64,
    /// The tangential interface force (N, tangential coordinates).
    ft: [f64; 2],
    /// The point's slip scale (m).
    slip_scale: f64,
    /// The slip below which the point sticks (m): `tol` times its slip scale.
    stick_threshold: f64,
    /// The point's normal state.
    normal_state: NormalState,
}

impl FrictionAt<'_> {
    /// The friction state of point `i` (on boundary `cb`) and its friction-law residual
    /// (N, before the round-off discount): stick `‖R_τ‖ ≤ w F j'(0)`, slip (or the smooth
    /// law) `R_τ = −w F j'(r) u_τ/r`, no friction `R_τ = 0`. Exact friction sticks where
    /// its projection is inactive, its slip there going to `kkt`.
    fn check(
        &self,
        ca: &ContactAssembler<'_>,
        inp: &Inputs<'_>,
        cb: &ContactBoundary,
        i: usize,
        kkt: &mut KktCertificate,
    ) -> (FrictionState, f64) {
        let FrictionAt {
            s,
            bound,
            w,
            ft,
            slip_scale,
            stick_threshold,
            normal_state,
        } = *self;
        let frozen = inp.frozen;
        let m = ca.dim - 1;
        let ft_norm = (ft[0] * ft[0] + ft[1] * ft[1]).sqrt();
        match &cb.friction {
            None => (FrictionState::None, ft_norm),
            Some(fr)
                if normal_state == NormalState::Separated && fr.bound == FrictionBound::Coulomb =>
            {
                (FrictionState::None, ft_norm)
            }
            Some(fr) => {
                let smooth = matches!(fr.potential, FrictionPotential::Regularized { .. });
                let wf = w * bound;
                let slipping = if fr.is_exact() {
                    let (r, tau) = (ca.penalty[i], frozen.traction[i]);
                    let z = [tau[0] + r * s.u_tau[0], tau[1] + r * s.u_tau[1]];
                    let stick = frozen.bound[i] > 0.0
                        && crate::assembly::contact::project_ball(&z, m, frozen.bound[i]).1;
                    if stick {
                        kkt.stick_slip = kkt.stick_slip.max(s.slip / slip_scale);
                    }
                    kkt.n_constraints.2 += 1;
                    !stick && s.slip > 0.0
                } else {
                    s.slip > stick_threshold
                };
                let state = if slipping {
                    FrictionState::Slip
                } else {
                    FrictionState::Stick
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
                    (state, r2.sqrt())
                } else {
                    (state, (ft_norm - wf * fr.potential.slope(0.0)).max(0.0))
                }
            }
        }
    }
}
