//! The certificate means what it says.
//!
//! - Support reactions are not contact forces: at a node on rollers that is also a contact
//!   node, the friction force stays within its bound, and reactions, interface forces and
//!   loads balance (Newton's third law over the whole body: Σ f + Σ R_contact + Σ R_support
//!   = Σ ∇W = 0, the internal forces of a body summing to zero).
//! - Normal and friction states are separate: with a Tresca bound, a point off its
//!   foundation is *separated* (and not counted in contact) whatever its friction state.
//! - A certificate above its tolerance is not a converged solve: a tolerance below what the
//!   equilibrium iteration delivers fails the run, naming the law.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use common::problem;
use hemicontact::solver::{solve, FrictionState, NormalState, SolverSettings};

/// A unit square on rollers at the bottom (u_y = 0) and at the right (u_x = 0), pushed to
/// the left and down by a traction on its top, bulging into a wall with Coulomb friction on
/// its left side (gap 0). The bottom-left corner is on rollers *and* on the contact side:
/// its tangential (vertical) component is prescribed.
fn rollers_and_wall(exact: bool) -> String {
    format!(
        r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [8, 8]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "bottom"
components = ["y"]
[[dirichlet]]
part = "right"
components = ["x"]
[[loads.traction]]
part = "top"
value = [-200.0, -300.0]
[[contact]]
part = "left"
gap = 0.0
law = "normal-compliance"
c_nu = 1.0e4
[contact.friction]
bound = "coulomb"
mu = {{ law = "constant", mu = 0.3 }}
exact = {exact}
"#
    )
}

#[test]
fn support_reactions_are_not_contact_forces() {
    for exact in [false, true] {
        let p = problem(&rollers_and_wall(exact));
        let s = solve(&p, &SolverSettings::default()).unwrap();
        assert!(s.report.converged, "{}", s.report.message);
        // The corner node (0, 0): on the bottom rollers and on the contact side.
        let corner = s
            .contact
            .iter()
            .find(|c| {
                let x = p.mesh().node(c.node as usize);
                x[0] == 0.0 && x[1] == 0.0
            })
            .expect("the corner is a contact point");
        assert_eq!(corner.normal_state, NormalState::Contact);
        let ft = corner.force_tangential[0].abs();
        assert!(
            ft <= corner.weight * corner.bound * (1.0 + 1e-9),
            "exact = {exact}: friction force {ft:e} above its bound {:e}",
            corner.weight * corner.bound
        );
        // Σ f + Σ R_contact + Σ R_support = 0, componentwise, relative to the load.
        let f = p.external_forces();
        let load: f64 = f.iter().map(|x| x.abs()).sum();
        for k in 0..2 {
            let external: f64 = f.iter().skip(k).step_by(2).sum();
            let support: f64 = s.reactions.iter().skip(k).step_by(2).sum();
            let contact: f64 = s.contact.iter().map(|c| c.force[k]).sum();
            let balance = external + support + contact;
            assert!(
                balance.abs() <= 1e-9 * load,
                "exact = {exact}, component {k}: loads {external:e} + supports {support:e} + \
                 contact {contact:e} = {balance:e}"
            );
        }
    }
}

/// A block on a Tresca foundation (gap 0), its top lifted: every bottom point separates.
/// Separated points are not in contact, though the Tresca bound acts on them (it does not
/// depend on the pressure); pressed down instead, every point is in contact.
#[test]
fn tresca_points_off_the_foundation_are_separated() {
    let text = r#"
[mesh]
kind = "rectangle"
size = [4.0, 1.0]
n = [16, 4]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "top"
value = [0.0, -0.01]
[[contact]]
part = "bottom"
gap = 0.0
law = "normal-compliance"
c_nu = 100.0
[contact.friction]
bound = "tresca"
mu = { law = "constant", mu = 0.5 }
"#;
    let lifted = text.replace("value = [0.0, -0.01]", "value = [0.0, 0.01]");
    let p = problem(&lifted);
    let s = solve(&p, &SolverSettings::default()).unwrap();
    assert!(s.report.converged, "{}", s.report.message);
    let cert = &s.report.certificate;
    assert_eq!(cert.n_contact, 0, "{cert:?}");
    assert!(s
        .contact
        .iter()
        .all(|c| c.normal_state == NormalState::Separated && c.pressure == 0.0));
    // The Tresca bound still acts on them: they stick (the top moves straight up).
    assert!(s
        .contact
        .iter()
        .all(|c| c.friction_state != FrictionState::None));
    assert_eq!(cert.n_stick + cert.n_slip, s.contact.len());
    // Pressed instead: all in contact.
    let p = problem(text);
    let s = solve(&p, &SolverSettings::default()).unwrap();
    assert!(s.report.converged, "{}", s.report.message);
    assert_eq!(s.report.certificate.n_contact, s.contact.len());
}

/// The certificate decides convergence: with a tolerance below the equilibrium residual
/// the iteration reaches (Newton stops at 1e-10 relative), the same solve is refused,
/// naming the law that fails.
#[test]
fn certificate_above_its_tolerance_is_not_converged() {
    let p = problem(&rollers_and_wall(false));
    let settings = SolverSettings {
        certificate_tolerance: 1e-14,
        ..SolverSettings::default()
    };
    let s = solve(&p, &settings).unwrap();
    assert!(!s.report.converged);
    assert!(
        s.report.message.contains("not certified") && s.report.message.contains("residual"),
        "{}",
        s.report.message
    );
    assert!(!s.report.certificate.passes());
}
