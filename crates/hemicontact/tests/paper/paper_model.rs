//! Verification of the paper's model (nearly locking, normal compliance, slip-dependent
//! friction, convexification solver): hand-derived solutions, symmetry, the paper's
//! qualitative result, robustness of the outer loop, and the certificate of every solve.
//!
//! Every solve here is certified: `assert_certified` checks that the equilibrium residual
//! and the contact/friction law residuals of the solver's own certificate are below 1e-8
//! relative — the certificate is computed from equilibrium of the body, independently of
//! the frozen quantities the solver iterated on. (With a compliance c_ν = 10¹², whose
//! forces are known only to about 10⁻⁵, the certificate's own tolerance is checked
//! instead.)
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use hemicontact::contact::FrictionPotential;
use hemicontact::problem::Problem;
use hemicontact::scenario::builtin;
use hemicontact::solver::{solve, FrictionState, Mixing, NormalState, Solution, SolverSettings};

fn assert_certified(s: &Solution) {
    common::assert_certified(s, 1e-8);
}

const E: f64 = 1000.0;
const NU: f64 = 0.3;

/// Plane-strain Lamé constants `(λ, G)` of `E`, `ν`.
fn lame() -> (f64, f64) {
    common::lame(E, NU, false)
}

/// A unit block on rollers (left: x fixed, bottom: y fixed), pressed by `p` on top, expands
/// into a frictionless normal-compliance wall on the right at gap `g`. The stress is uniform:
/// `σ_yy = −p`, `σ_xx = −c_ν(ε_xx − g)` with `u_ν = ε_xx` on the right side, so
/// `(λ+2G+c_ν) ε_xx + λ ε_yy = c_ν g` and `λ ε_xx + (λ+2G) ε_yy = −p` (plane strain).
#[test]
fn block_pressed_against_normal_compliance_wall_matches_hand_solution() {
    let (p, g, c_nu) = (200.0, 0.02, 5.0e4);
    let text = format!(
        r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [6, 6]
[material]
young = {E}
poisson = {NU}
[[dirichlet]]
part = "left"
components = ["x"]
[[dirichlet]]
part = "bottom"
components = ["y"]
[[loads.traction]]
part = "top"
value = [0.0, -{p}]
[[contact]]
part = "right"
gap = {g}
c_nu = {c_nu}
"#
    );
    let (pr, settings) = common::setup(&text);
    let s = solve(&pr, &settings).unwrap();
    assert_certified(&s);
    let (l, mu) = lame();
    let (a11, a12, a22) = (l + 2.0 * mu + c_nu, l, l + 2.0 * mu);
    let det = a11 * a22 - a12 * a12;
    let exx = (c_nu * g * a22 + a12 * p) / det;
    let eyy = (-p * a11 - a12 * c_nu * g) / det;
    assert!(
        exx > g,
        "the hand solution must be in contact: ε_xx = {exx}, g = {g}"
    );
    let pressure = c_nu * (exx - g);
    for n in 0..pr.mesh().n_nodes() {
        let x = pr.mesh().node(n);
        let (ux, uy) = (s.u[2 * n], s.u[2 * n + 1]);
        assert!(
            (ux - exx * x[0]).abs() < 1e-10,
            "u_x at {x:?}: {ux} vs {}",
            exx * x[0]
        );
        assert!(
            (uy - eyy * x[1]).abs() < 1e-10,
            "u_y at {x:?}: {uy} vs {}",
            eyy * x[1]
        );
    }
    assert_eq!(
        s.contact.len(),
        7,
        "all right-side nodes, rollers included, are contact nodes"
    );
    for c in &s.contact {
        assert!(
            (c.pressure - pressure).abs() < 1e-8 * pressure,
            "pressure {} vs {pressure}",
            c.pressure
        );
        assert!((c.u_nu - exx).abs() < 1e-10);
    }
}

fn sheared_block(delta: f64, mu: f64) -> (Problem, Solution) {
    let text = format!(
        r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [4, 4]
[material]
young = {E}
poisson = {NU}
[[dirichlet]]
part = "top"
value = [{delta}, 0.0]
[[dirichlet]]
part = "left"
components = ["y"]
[[dirichlet]]
part = "right"
components = ["y"]
[[contact]]
part = "bottom"
gap = 0.0
c_nu = 1.0e4
[contact.friction]
bound = "tresca"
potential = "norm"
mu = {{ law = "constant", mu = {mu} }}
"#
    );
    let (pr, settings) = common::setup(&text);
    let s = solve(&pr, &settings).unwrap();
    (pr, s)
}

/// A unit block in simple shear: top displaced by δ, sides on y-rollers, bottom on a
/// Tresca foundation with constant bound μ (a traction). While the bottom sticks the shear
/// is uniform, `σ_xy = G δ`; it slips once `G δ > μ`, i.e. beyond `δ* = μ/G`, after which
/// `σ_xy = μ` and the bottom slips by `δ − δ*`.
#[test]
fn sheared_block_on_tresca_foundation_sticks_below_and_slips_above_the_threshold() {
    let mu = 5.0;
    let (_, g) = lame();
    let delta_star = mu / g;
    // Below the threshold: stick, uniform shear u_x = δ y.
    let (pr, s) = sheared_block(0.5 * delta_star, mu);
    assert_certified(&s);
    // The numerical regularization of ‖·‖ in the user's units: a fraction
    // (the friction law's `regularization`, 1e-8) of the displacement scale of the solve.
    let scales = s.report.scales.expect("scales");
    let regularization = pr
        .contact()
        .iter()
        .filter_map(|c| c.friction.as_ref()?.potential.regularization())
        .fold(0.0, f64::max);
    assert_eq!(regularization, 1e-8);
    let rho_num = regularization * scales.displacement;
    for c in &s.contact {
        assert_eq!(
            c.friction_state,
            FrictionState::Stick,
            "node {} should stick",
            c.node
        );
        assert!(c.slip < rho_num, "stick slip {}", c.slip);
        // Tangential traction G δ below the bound.
        assert!((c.force_tangential[0].abs() / c.weight - g * 0.5 * delta_star).abs() < 1e-6 * mu);
    }
    // Exact up to the numerical regularization of ‖·‖: a sticking node moves by less than
    // ρ_num.
    for n in 0..pr.mesh().n_nodes() {
        let y = pr.mesh().node(n)[1];
        assert!((s.u[2 * n] - 0.5 * delta_star * y).abs() < rho_num);
    }
    // Above the threshold: slip by δ − δ*, friction traction = μ.
    let delta = 2.0 * delta_star;
    let (pr, s) = sheared_block(delta, mu);
    assert_certified(&s);
    for c in &s.contact {
        assert_eq!(
            c.friction_state,
            FrictionState::Slip,
            "node {} should slip",
            c.node
        );
        assert!(
            (c.slip - (delta - delta_star)).abs() < 1e-8 * delta_star,
            "slip {}",
            c.slip
        );
        assert!((c.force_tangential[0].abs() / c.weight - mu).abs() < 1e-8 * mu);
    }
    for n in 0..pr.mesh().n_nodes() {
        let y = pr.mesh().node(n)[1];
        let exact = (delta - delta_star) + delta_star * y;
        assert!((s.u[2 * n] - exact).abs() < 1e-8 * delta_star);
    }
}

fn paper(n: usize, c_kappa: f64, extra: &str) -> (Problem, Solution) {
    let (pr, settings) = common::setup(&(builtin::paper(n, c_kappa) + extra));
    let s = solve(&pr, &settings).unwrap();
    (pr, s)
}

/// With the mirror-symmetric cut pattern the paper's problem is symmetric about x = 2:
/// `u_x(4 − x, y) = −u_x(x, y)`, `u_y(4 − x, y) = u_y(x, y)`.
#[test]
fn paper_solution_is_mirror_symmetric() {
    let n = 16;
    let (pr, s) = paper(n, 1.0e4, "");
    assert_certified(&s);
    let scale = s.u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for j in 0..=n {
        for i in 0..=n {
            let a = j * (n + 1) + i;
            let b = j * (n + 1) + (n - i);
            assert!((pr.mesh().node(a)[0] + pr.mesh().node(b)[0] - 4.0).abs() < 1e-14);
            assert!((s.u[2 * a] + s.u[2 * b]).abs() < 1e-10 * scale);
            assert!((s.u[2 * a + 1] - s.u[2 * b + 1]).abs() < 1e-10 * scale);
        }
    }
}

/// The paper's qualitative result (its Section 5): without locking nothing reaches the
/// foundations; with C_κ = 10 000 the body is quasi-incompressible, bulges, and nodes at the
/// top of both vertical sides are in contact, many of them slipping.
#[test]
fn paper_qualitative_result() {
    let (_, free) = paper(16, 0.0, "");
    assert_certified(&free);
    assert!(free
        .contact
        .iter()
        .all(|c| c.normal_state == NormalState::Separated));
    let (pr, locked) = paper(16, 1.0e4, "");
    assert_certified(&locked);
    let touching: Vec<_> = locked
        .contact
        .iter()
        .filter(|c| c.normal_state == NormalState::Contact)
        .collect();
    assert!(!touching.is_empty());
    for side in 0..2 {
        let on_side: Vec<_> = touching.iter().filter(|c| c.boundary == side).collect();
        assert!(!on_side.is_empty(), "side {side} touches");
        // The contact zone is at the top: every touching node is above mid-height, and
        // the top corner touches.
        assert!(on_side
            .iter()
            .all(|c| pr.mesh().node(c.node as usize)[1] > 2.0));
        assert!(on_side
            .iter()
            .any(|c| pr.mesh().node(c.node as usize)[1] == 4.0));
    }
    assert!(touching
        .iter()
        .any(|c| c.friction_state == FrictionState::Slip));
    // The locking penalty acts: some cell has |tr ε| > θ.
    let summary = hemicontact::io::summary::Summary::new(
        &pr,
        &SolverSettings::default(),
        &locked,
        None,
        "test",
    );
    assert!(summary.locked_cells > 0);
}

/// Newton's energy decreases monotonically within each convex solve (line search on a
/// convex energy), in every outer iteration of the paper example.
#[test]
fn energy_decreases_across_newton_steps() {
    let (_, s) = paper(16, 1.0e4, "");
    let steps = &s.report.newton;
    assert!(steps.len() >= 2);
    for w in steps.windows(2) {
        if w[0].outer == w[1].outer {
            assert!(
                w[1].energy <= w[0].energy + 1e-12 * w[0].energy.abs(),
                "{w:?}"
            );
        }
    }
}

/// The numerical regularization of ‖·‖ is invisible in the reported digits: shrinking it
/// tenfold changes neither the contact/slip counts nor max |u| to 8 significant digits.
#[test]
fn friction_regularization_does_not_change_reported_digits() {
    let maxu = |s: &Solution| s.u.chunks(2).map(|c| c[0].hypot(c[1])).fold(0.0, f64::max);
    let (_, a) = paper(16, 1.0e4, "");
    let (_, b) = paper(
        16,
        1.0e4,
        "\n[solver.outer]\nfriction_regularization = 1e-9\n",
    );
    assert_certified(&a);
    assert_certified(&b);
    assert_eq!(
        a.report.certificate.n_contact,
        b.report.certificate.n_contact
    );
    assert_eq!(a.report.certificate.n_slip, b.report.certificate.n_slip);
    let (ma, mb) = (maxu(&a), maxu(&b));
    assert!((ma - mb).abs() < 1e-8 * ma, "{ma} vs {mb}");
}

/// The nonconvex potential (17) through its difference-of-convex split: the solve converges
/// and the certificate checks the friction force against `F j'(‖u_τ‖)` of the exact law.
#[test]
fn nonconvex_friction_potential_run() {
    let text = builtin::paper(16, 1.0e4).replace(
        "potential = { kind = \"norm\" }",
        "potential = { kind = \"nonconvex\", a = 0.5 }",
    );
    let (pr, settings) = common::setup(&text);
    assert!(pr.contact().iter().all(|c| matches!(
        c.friction.as_ref().map(|f| f.potential),
        Some(FrictionPotential::Nonconvex { .. })
    )));
    let s = solve(&pr, &settings).unwrap();
    assert_certified(&s);
    assert!(s.report.outer.len() > 1);
    assert!(s
        .contact
        .iter()
        .any(|c| c.friction_state == FrictionState::Slip));
}

fn constant_mu(mu: f64, outer: &str) -> String {
    builtin::paper(16, 1.0e4).replace(
        "mu = { law = \"exponential\", a = 0.4, b = 0.1, beta = 100.0 }",
        &format!("mu = {{ law = \"constant\", mu = {mu} }}"),
    ) + "\n[solver.outer]\n"
        + outer
}

/// With a large friction coefficient (μ ≡ 2) the plain fixed point oscillates; the solver
/// detects it, relaxes, and converges; Anderson acceleration (the default) converges too,
/// in fewer outer iterations.
#[test]
fn oscillating_fixed_point_is_detected_and_cured() {
    let plain = common::solve_text(&constant_mu(2.0, "acceleration = \"none\"\n")).unwrap();
    assert_certified(&plain);
    assert!(
        plain
            .report
            .outer
            .iter()
            .any(|o| matches!(o.mixing, Mixing::Oscillation { .. })),
        "oscillation should be detected"
    );
    let anderson = common::solve_text(&constant_mu(2.0, "")).unwrap();
    assert_certified(&anderson);
    assert!(anderson.report.outer.len() < plain.report.outer.len());
    let maxu = |s: &Solution| s.u.chunks(2).map(|c| c[0].hypot(c[1])).fold(0.0, f64::max);
    assert!((maxu(&plain) - maxu(&anderson)).abs() < 1e-7 * maxu(&plain));
}

/// The non-convergence path: a cap of 5 outer iterations on a slowly converging problem
/// gives `converged = false`, a message saying so, and still the last iterate.
#[test]
fn iteration_cap_reports_non_convergence_with_last_iterate() {
    let s = common::solve_text(&constant_mu(
        5.0,
        "acceleration = \"none\"\nmax_iterations = 5\n",
    ))
    .unwrap();
    assert!(!s.report.converged);
    assert!(
        s.report.message.contains("not converged"),
        "{}",
        s.report.message
    );
    assert_eq!(s.report.outer.len(), 5);
    assert!(
        s.u.iter().any(|&x| x != 0.0),
        "the last iterate is returned"
    );
}

/// The paper's example with a normal compliance 10⁸ times stiffer, c_ν = 10¹²: the pressure
/// `c_ν (u_ν − g)` is a difference of the gap 0.4 and a displacement of nearly the same size
/// times 10¹², so the contact points' forces are known only to about `ε c_ν g` (10⁻⁵ of the
/// pressures), far above the Newton tolerance relative to them. The solve converges with a
/// passing certificate, the touching points penetrating by their pressure over c_ν.
#[test]
fn the_paper_example_with_a_stiff_compliance_converges() {
    let c_nu = 1.0e12;
    let text = builtin::paper(32, 1.0e4).replace("c_nu = 10000.0", &format!("c_nu = {c_nu:e}"));
    assert!(text.contains("c_nu = 1e12") && !text.contains("c_nu = 10000.0"));
    let (pr, settings) = common::setup(&text);
    let s = solve(&pr, &settings).unwrap();
    assert!(s.report.converged, "{}", s.report.message);
    assert!(s.report.certificate.passes(), "{:?}", s.report.certificate);
    let touching: Vec<_> = s.contact.iter().filter(|c| c.pressure > 0.0).collect();
    println!(
        "{} points touch; {} Newton steps",
        touching.len(),
        s.report.newton.len()
    );
    assert!(!touching.is_empty());
    for c in touching {
        assert!(
            (-c.gap - c.pressure / c_nu).abs() <= 1e-6 * c.pressure / c_nu + 1e-15,
            "node {}: penetration {:e}, pressure {:e}",
            c.node,
            -c.gap,
            c.pressure
        );
    }
}
