//! The certificate of a solve: residuals that let a user trust the answer without trusting
//! the code.
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
//! # Every point on its own scales
//!
//! No check of a point is decided by another part of the problem. Each contact point i has
//!
//! - a **force scale** `f_i = max(w_i max(F_i, p_i), η L_i)` (N): its own friction bound
//!   and pressure times its weight, but at least the fraction η = 1 % of the force `L_i`
//!   that the stresses of its cells pass through its node (a separated point has no force
//!   of its own; see [`super::local_scales`]); its residuals are relative to `f_i`;
//! - a **slip scale** `δ_i = f_i / (w_i k_i)` (m), with `k_i = S / h_i` its elastic
//!   stiffness per unit area ([`super::constraints::contact_stiffness`]): the slip that its
//!   force scale causes around it, element size times local strain. A point sticks when its
//!   slip is at most `tol · δ_i`.
//!
//! Both are independent of the loads and displacements of other bodies and other regions,
//! and of a rigid translation of the whole (the slip is relative to the foundation).
//!
//! States, one for each law (never mixed): the *normal state* is `contact` where the
//! pressure is positive and `separated` elsewhere; the *friction state* is `none` where no
//! friction force can act (frictionless contact, or a Coulomb-type bound at a separated
//! point), `stick` where the slip is at most `tol · δ_i` and `slip` elsewhere (exact
//! friction: where its multiplier's projection is inactive). A Tresca-type bound acts
//! regardless of the pressure, so a separated point may stick or slip.
//!
//! The law checks, each relative to the point's force scale with the certificate
//! tolerance `tol`:
//!
//! - stick: `‖R_τ‖ ≤ w F j'(0)` (the excess is the residual) — and the slip is below
//!   `tol · δ_i` by definition of the state;
//! - slip: `R_τ = −w F j'(r) u_τ/r` (the force equals the bound and opposes the slip);
//! - the smooth law (19) everywhere: `R_τ = −w F ∇j(u_τ)`;
//! - separated points under a Coulomb bound or without friction: `R_τ = 0`;
//! - the normal law `R·ν = −w p(u_ν)` (for Signorini with the multiplier as p; its sign,
//!   the constraint and complementarity are the KKT checks);
//! - equilibrium `∇W(u) − f = 0` at the free DOFs of the nodes without a contact point,
//!   body by body, relative to the body's force scale.
//!
//! A residual no larger than its round-off floor ([`super::round_off`]: machine epsilon
//! times the magnitudes of the terms summed at the node) counts as zero: an entry of
//! equilibrium, or a law residual against the floor of its node's force. The floor is per
//! node, so a stiff neighbour's round-off excuses nothing elsewhere.
//!
//! A certificate *passes* when every residual is at most `tol`; a solve whose certificate
//! fails is reported as not converged, naming the law, the contact part and the node.
//!
//! Support reactions are not contact forces: at a node on rollers that is also a contact
//! node, the force along a prescribed component is shared by the support and the
//! foundation, and equilibrium cannot tell them apart. There the contact force is the
//! model's (the law evaluated at the final state), and the support reaction is the rest
//! ([`crate::solver::System::reactions`]), so reactions and interface forces together
//! balance the loads.
//!
//! At a node shared by several contact points (an edge between two contact parts, or a
//! corner of one part, see [`crate::contact::nodes`]), the
//! equilibrium force is one vector for several points: the force attributed to a point is
//! what remains after subtracting the model forces of the node's other points.
//!
//! Residuals are forces (N, or N/m in 2D), reported relative to their point's force scale.

mod inputs;
mod point;
mod results;

pub use inputs::Inputs;

pub use results::{ContactResult, FrictionState, NormalState, Worst};

use super::frozen::Frozen;
use super::multipliers::KktCertificate;
use super::round_off::{body_residuals, Floors};
use super::system::Evaluation;
pub use super::whole::whole_results;
use super::System;
use crate::assembly::contact::{ContactAssembler, ContactData};
use crate::parallel::Share;
use crate::problem::Problem;
use serde::Serialize;

/// The certificate; see the module documentation.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Certificate {
    /// The tolerance every residual is compared with (dimensionless).
    pub tolerance: f64,
    /// Relative equilibrium residual: the largest over the bodies of `‖(∇W − f)|_b‖ / F_b`
    /// over the free DOFs of the nodes without a contact point ([`super::local_scales`]).
    pub equilibrium: f64,
    /// Largest normal-law residual, each relative to its point's force scale.
    pub normal_law: f64,
    /// Largest friction-law residual, each relative to its point's force scale.
    pub friction_law: f64,
    /// The point with the largest normal-law residual, if any point has one.
    pub worst_normal: Option<Worst>,
    /// The point with the largest friction-law residual, if any point has one.
    pub worst_friction: Option<Worst>,
    /// Number of points in contact (normal state).
    pub n_contact: usize,
    /// Number of sticking points (friction state).
    pub n_stick: usize,
    /// Number of slipping points (friction state).
    pub n_slip: usize,
    /// KKT residuals of the exact constraints, if the problem has any.
    pub kkt: Option<KktCertificate>,
}

/// One failed check of a certificate: which law, how far off, where.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Failure {
    /// The law or condition: `"equilibrium"`, `"normal law"`, `"friction law"` or
    /// `"KKT conditions of the exact constraints"`.
    pub law: &'static str,
    /// The residual (relative, as reported).
    pub residual: f64,
    /// The point where it is largest, for the contact laws.
    pub at: Option<Worst>,
}

impl Certificate {
    /// The checks above the tolerance, worst first; empty when the certificate passes. A
    /// residual that is not a number fails.
    pub fn failures(&self) -> Vec<Failure> {
        let tol = self.tolerance;
        let mut out: Vec<Failure> = [
            ("equilibrium", self.equilibrium, None),
            ("normal law", self.normal_law, self.worst_normal),
            ("friction law", self.friction_law, self.worst_friction),
            (
                "KKT conditions of the exact constraints",
                self.kkt.as_ref().map_or(0.0, KktCertificate::worst),
                None,
            ),
        ]
        .into_iter()
        .filter(|(_, r, _)| r.is_nan() || *r > tol)
        .map(|(law, residual, at)| Failure { law, residual, at })
        .collect();
        out.sort_by(|a, b| b.residual.total_cmp(&a.residual));
        out
    }

    /// Whether every residual is at most the tolerance.
    pub fn passes(&self) -> bool {
        self.failures().is_empty()
    }
}

/// Evaluates the contact results and the certificate; see the module documentation.
/// `frozen` holds the quantities of the last convex problem (its multipliers give the
/// pressure at Signorini points and the stick/slip classification of exact friction:
/// stick where `‖τ + r u_τ‖ ≤ F`, i.e. the projection defining the friction force is
/// inactive). The friction bound at each point is `F(μ_i, p_i)` with the coefficients
/// `mu` of the inputs.
pub fn evaluate(ca: &ContactAssembler<'_>, inp: &Inputs<'_>) -> (Vec<ContactResult>, Certificate) {
    let Inputs {
        u,
        grad_bulk,
        frozen,
        tolerance,
        share,
        ..
    } = *inp;
    // The points this process counts (all on one process; its ghost points' slave nodes,
    // and so their equilibrium forces, are another's).
    let owned = ca.nodes.owned();
    let with_reactions;
    let grad_bulk = match with_pair_reactions(ca, u, frozen, grad_bulk) {
        Some(g) => {
            with_reactions = g;
            with_reactions.as_slice()
        }
        None => grad_bulk,
    };
    let equilibrium = equilibrium(ca, inp, grad_bulk);
    let mut kkt = KktCertificate::default();
    // The other points on the node of point i (points are ordered by boundary, so they are
    // found through a node → points map).
    let mut by_node: std::collections::BTreeMap<u32, Vec<usize>> = Default::default();
    for (i, &v) in ca.nodes.node[..owned].iter().enumerate() {
        by_node.entry(v).or_default().push(i);
    }
    let shared = |i: usize| -> Vec<usize> {
        by_node
            .get(&ca.nodes.node[i])
            .map(|pts| pts.iter().copied().filter(|&j| j != i).collect())
            .unwrap_or_default()
    };
    let mut exact_any = false;
    let mut results = Vec::with_capacity(owned);
    for i in 0..owned {
        let cb = &ca.boundaries[ca.nodes.boundary[i] as usize];
        results.push(point::result(ca, inp, grad_bulk, i, &shared(i), &mut kkt));
        exact_any |= cb.normal.is_exact() || cb.friction.as_ref().is_some_and(|f| f.is_exact());
    }
    let cert = summary(&results, kkt, exact_any, equilibrium, tolerance, share);
    (results, cert)
}

/// Between two bodies, the force on a slave point acts back on its master facet's nodes
/// (action = reaction): `∇W − f` with the model force of each pair, spread with −N_j,
/// joined there, so that the master body's equilibrium checks that it balances; `None`
/// without pairs (`grad_bulk` as it is).
fn with_pair_reactions(
    ca: &ContactAssembler<'_>,
    u: &[f64],
    frozen: ContactData<'_>,
    grad_bulk: &[f64],
) -> Option<Vec<f64>> {
    let d = ca.dim;
    if !ca.nodes.has_pairs() {
        return None;
    }
    let mut g = grad_bulk.to_vec();
    for i in 0..ca.nodes.len() {
        let (n, nodes, coef) = ca.nodes.stencil(d, i);
        if n == 1 {
            continue;
        }
        let model = ca.point(u, &frozen, i).gradient;
        for a in 1..n {
            let v = nodes[a] as usize;
            for k in 0..d {
                g[d * v + k] += coef[a] * model[k];
            }
        }
    }
    Some(g)
}

/// The relative equilibrium residual ([`Certificate::equilibrium`]) of `grad_bulk` (`∇W −
/// f`, with the pairs' reactions): body by body, at the free DOFs of the nodes without a
/// contact point (at those, the interface force is what the laws check), relative to the
/// body's force scale; a body beyond the tolerance over its entries above their round-off
/// floors only.
fn equilibrium(ca: &ContactAssembler<'_>, inp: &Inputs<'_>, grad_bulk: &[f64]) -> f64 {
    let Inputs {
        u,
        f_ext,
        fixed,
        bodies,
        round_off,
        mesh,
        frozen,
        tolerance,
        share,
        ..
    } = *inp;
    let d = ca.dim;
    // Equilibrium, body by body, at the free DOFs of the nodes without a contact point (at
    // those, the interface force is what the laws check).
    let mut on_contact = vec![false; grad_bulk.len() / d];
    for &v in &ca.nodes.node {
        on_contact[v as usize] = true;
    }
    let (mut residual, mut external, mut scale) = (Vec::new(), Vec::new(), Vec::new());
    let excluded = |k: usize| fixed(k) || on_contact[k / d];
    bodies.residuals(share, d, grad_bulk, excluded, &mut residual);
    bodies.norms(share, d, f_ext.len(), |k| f_ext[k], &mut external);
    bodies.force_scales(share, d, grad_bulk, f_ext, &external, &mut scale);
    // A body beyond the tolerance may be so by round-off: then over the entries above their
    // floors, with the regions' resultants of the whole residual (the laws' at the contact
    // points).
    let mut whole = grad_bulk.to_vec();
    for i in 0..ca.nodes.len() {
        let (v, model) = (ca.nodes.node[i] as usize, ca.point(u, &frozen, i).gradient);
        for k in 0..d {
            whole[d * v + k] += model[k];
        }
    }
    let mut above = Vec::new();
    let row = |k: usize| if excluded(k) { 0.0 } else { grad_bulk[k] };
    let all = |k: usize| if fixed(k) { 0.0 } else { whole[k] };
    body_residuals(bodies, mesh, share, round_off, row, all, &mut above);
    for ((r, a), s) in residual.iter_mut().zip(&above).zip(&scale) {
        if *r > tolerance * s {
            *r = r.min(*a);
        }
    }
    residual.iter().zip(&scale).fold(
        0.0f64,
        |e, (r, s)| if r.is_nan() { f64::NAN } else { e.max(r / s) },
    )
}

/// The certificate of the points' `results` (this process's), with the KKT residuals
/// `kkt` of exact friction gathered at them, whether any point has an exact law
/// (`exact_any`), the relative residual of `equilibrium` and the tolerance: the worst law
/// residuals and the state counts, over the processes.
fn summary(
    results: &[ContactResult],
    mut kkt: KktCertificate,
    exact_any: bool,
    equilibrium: f64,
    tolerance: f64,
    share: &Share,
) -> Certificate {
    // Over the processes: whether any point has an exact law, the exact friction's
    // largest slip at a sticking point and its count.
    let exact_any = share.any(exact_any);
    let mut slip = [kkt.stick_slip];
    share.max(&mut slip);
    kkt.stick_slip = slip[0];
    kkt.n_constraints.2 = share.count(kkt.n_constraints.2);
    let mut cert = Certificate {
        kkt: exact_any.then_some(kkt),
        tolerance,
        equilibrium,
        ..Certificate::default()
    };
    let worse = |w: &mut Option<Worst>, value: &mut f64, r: &ContactResult, residual: f64| {
        let rel = residual / r.force_scale;
        // A NaN residual is the worst of all.
        if rel > *value || (rel.is_nan() && !value.is_nan()) || w.is_none() && rel > 0.0 {
            *value = rel;
            *w = Some(Worst {
                node: share.whole_node(r.node),
                boundary: r.boundary,
                residual: rel,
            });
        }
    };
    for r in results {
        worse(
            &mut cert.worst_normal,
            &mut cert.normal_law,
            r,
            r.normal_residual,
        );
        worse(
            &mut cert.worst_friction,
            &mut cert.friction_law,
            r,
            r.friction_residual,
        );
        cert.n_contact += usize::from(r.normal_state == NormalState::Contact);
        cert.n_stick += usize::from(r.friction_state == FrictionState::Stick);
        cert.n_slip += usize::from(r.friction_state == FrictionState::Slip);
    }
    // Over the processes; on one, the worst points and counts themselves (a worst point's
    // residual is the law's value, and no worst point leaves it 0).
    (cert.worst_normal, cert.normal_law) =
        super::whole::worst_of_all(share, cert.worst_normal, cert.normal_law);
    (cert.worst_friction, cert.friction_law) =
        super::whole::worst_of_all(share, cert.worst_friction, cert.friction_law);
    cert.n_contact = share.count(cert.n_contact);
    cert.n_stick = share.count(cert.n_stick);
    cert.n_slip = share.count(cert.n_slip);
    cert
}

impl System {
    /// The contact results and the certificate ([`evaluate`]) of `u` for
    /// the frozen quantities `frozen`, from the evaluation `eval` at `u` (its bulk gradient
    /// and the responses of user-defined compliance laws), the force scales of the bodies
    /// `body_scale`, the friction coefficients `mu` at `u` and the tolerance `tolerance`.
    #[allow(clippy::too_many_arguments)]
    pub fn certificate(
        &self,
        problem: &Problem,
        u: &[f64],
        frozen: &Frozen,
        eval: &Evaluation,
        body_scale: &[f64],
        mu: &[f64],
        tolerance: f64,
    ) -> (Vec<ContactResult>, Certificate) {
        let (mut point_force, mut floor) = (Vec::new(), Vec::new());
        self.point_scales(
            problem,
            u,
            frozen,
            &eval.normal,
            body_scale,
            &mut point_force,
            &mut floor,
        );
        let mut round_off = Floors::default();
        self.round_off_floors(problem, u, frozen, &eval.normal, &mut round_off);
        let mut ca = self.contact_assembler(problem);
        ca.responses = &eval.normal;
        evaluate(
            &ca,
            &Inputs {
                u,
                mu,
                grad_bulk: &eval.grad_bulk,
                f_ext: &self.f_ext,
                fixed: &|k| self.dofs.is_fixed(k),
                bodies: &self.bodies,
                floor: &floor,
                round_off: &round_off,
                mesh: &problem.mesh,
                frozen: frozen.contact(),
                tolerance,
                share: self.share(),
            },
        )
    }
}
