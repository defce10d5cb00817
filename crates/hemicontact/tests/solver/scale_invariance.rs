//! Units must not matter: the solver works in dimensionless variables, so every tolerance,
//! regularization and threshold is relative to the problem's own scales.
//!
//! Verified here, on the paper's example (nearly locking, slip-weakening Coulomb friction,
//! normal compliance) and on a frictional block pressed and sheared on a foundation:
//!
//! - multiplying every stiffness by s (E, c_ν, C_κ) with the loads unchanged divides u by s
//!   and keeps the iteration counts and the contact and friction states — exactly the
//!   positively homogeneous rescaling, so the strain thresholds of the locking set are
//!   divided by s, the decay rate β of μ multiplied by s and the gap divided by s;
//! - multiplying loads, Tresca bounds and every stiffness by s together leaves u unchanged;
//! - both for s anywhere from 1e-250 to 1e250, and under a change of length unit;
//! - the regularized friction answer agrees with the exact-friction one (`exact = true`),
//!   stick and slip labels included;
//! - a regularization too coarse for the certificate is refused, naming the law and node.
//!
//! The scaled scenarios are written out here from the physics (which quantity has which
//! unit), independently of the library's own change of variables.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use common::{rel, solve_text};
use hemicontact::solver::{FrictionState, NormalState, Solution};
use proptest::prelude::*;

/// The paper's square (4 × 4 m, n × n cells, clamped bottom, traction on top, walls on the
/// left and right at the gap g with normal compliance and exponential slip weakening), with
/// every datum spelled out so that the tests can scale each by its unit.
#[allow(clippy::too_many_arguments)]
fn paper(
    n: usize,
    length: f64,
    young: f64,
    c_kappa: f64,
    theta: f64,
    traction: f64,
    c_nu: f64,
    gap: f64,
    beta: f64,
) -> String {
    let contact = |part: &str| {
        format!(
            r#"
[[contact]]
part = "{part}"
gap = {gap:e}
law = "normal-compliance"
c_nu = {c_nu:e}
[contact.friction]
bound = "coulomb"
potential = "norm"
mu = {{ law = "exponential", a = 0.4, b = 0.1, beta = {beta:e} }}
"#
        )
    };
    format!(
        r#"
[mesh]
kind = "rectangle"
size = [{length:e}, {length:e}]
n = [{n}, {n}]
pattern = "symmetric"
[material]
young = {young:e}
poisson = 0.3
plane = "strain"
[locking]
set = "limited-compressibility"
theta = {theta:e}
treatment = "penalty"
c_kappa = {c_kappa:e}
[[dirichlet]]
part = "bottom"
[[loads.traction]]
part = "top"
value = [0.0, {t:e}]
{left}{right}"#,
        t = -traction,
        left = contact("left"),
        right = contact("right"),
    )
}

/// The paper's data in SI units at n = 16.
fn paper_si(stiffness: f64, length: f64) -> String {
    // Stiffness × s, strains ÷ s (θ), slips ÷ s (β × s, g ÷ s); length × ℓ: coordinates,
    // gaps and slips × ℓ, the compliance stiffness (Pa/m) and β ÷ ℓ.
    let s = stiffness;
    paper(
        16,
        4.0 * length,
        2000.0 * s,
        1e4 * s,
        0.16 / s,
        900.0,
        1e4 * s / length,
        0.4 / s * length,
        100.0 * s / length,
    )
}

/// A 2 × 1 block on a foundation (normal compliance c_ν, gap 0), its top pressed down by δ
/// and moved sideways by `shift`; friction `friction` (a TOML table body). The corners slip
/// outward under the Poisson expansion and the centre sticks.
fn block(length: f64, young: f64, c_nu: f64, shift: f64, delta: f64, friction: &str) -> String {
    format!(
        r#"
[mesh]
kind = "rectangle"
size = [{w:e}, {length:e}]
n = [16, 8]
[material]
young = {young:e}
poisson = 0.3
plane = "strain"
[[dirichlet]]
part = "top"
value = [{shift:e}, {dy:e}]
[[contact]]
part = "bottom"
gap = 0.0
law = "normal-compliance"
c_nu = {c_nu:e}
[contact.friction]
{friction}
"#,
        w = 2.0 * length,
        dy = -delta,
    )
}

/// Largest nodal displacement difference `max|a − c·b|` relative to `max|a|`.
fn u_diff(a: &Solution, b: &Solution, c: f64) -> f64 {
    let scale = a.u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    a.u.iter()
        .zip(&b.u)
        .fold(0.0f64, |m, (x, y)| m.max((x - c * y).abs()))
        / scale
}

fn states(s: &Solution) -> Vec<(NormalState, FrictionState)> {
    s.contact
        .iter()
        .map(|c| (c.normal_state, c.friction_state))
        .collect()
}

fn iterations(s: &Solution) -> (usize, usize) {
    (s.report.outer.len(), s.report.newton.len())
}

fn certified(text: &str) -> Solution {
    let s = solve_text(text).expect("solves");
    assert!(s.report.converged, "{}", s.report.message);
    s
}

/// The reference answers, computed once per test binary.
fn paper_reference() -> &'static Solution {
    static R: std::sync::OnceLock<Solution> = std::sync::OnceLock::new();
    R.get_or_init(|| certified(&paper_si(1.0, 1.0)))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 10, .. ProptestConfig::default() })]

    /// Stiffness × s (loads unchanged) divides u by s, with the same iterations and states,
    /// for s log-uniform in [1e-250, 1e250].
    #[test]
    fn paper_stiffness_times_s_divides_u_by_s(exponent in -250.0f64..250.0) {
        let s = 10f64.powf(exponent);
        let reference = paper_reference();
        let scaled = certified(&paper_si(s, 1.0));
        prop_assert!(u_diff(reference, &scaled, s) < 1e-8, "s = {s:e}: {}", u_diff(reference, &scaled, s));
        prop_assert_eq!(iterations(reference), iterations(&scaled));
        prop_assert_eq!(states(reference), states(&scaled));
    }

    /// A change of length unit by ℓ multiplies u by ℓ.
    #[test]
    fn paper_length_unit_times_l_multiplies_u(exponent in -6.0f64..6.0) {
        let l = 10f64.powf(exponent);
        let reference = paper_reference();
        let scaled = certified(&paper_si(1.0, l));
        prop_assert!(u_diff(reference, &scaled, 1.0 / l) < 1e-8);
        prop_assert_eq!(iterations(reference), iterations(&scaled));
        prop_assert_eq!(states(reference), states(&scaled));
    }

    /// Loads (here prescribed displacements stay, so: stiffness and Tresca bound) × s
    /// together leave u unchanged — regularized and exact friction, Tresca and Coulomb.
    #[test]
    fn block_loads_bounds_and_stiffness_times_s_leave_u(exponent in -250.0f64..250.0, exact in any::<bool>()) {
        let s = 10f64.powf(exponent);
        let exact = if exact { "exact = true" } else { "" };
        for (bound, mu) in [("coulomb", 0.3), ("tresca", 2.0)] {
            let friction = |k: f64| format!(
                "bound = \"{bound}\"\nmu = {{ law = \"constant\", mu = {:e} }}\n{exact}",
                if bound == "tresca" { mu * k } else { mu }
            );
            let a = certified(&block(1.0, 1000.0, 1e4, 2e-3, 1e-2, &friction(1.0)));
            let b = certified(&block(1.0, 1000.0 * s, 1e4 * s, 2e-3, 1e-2, &friction(s)));
            prop_assert!(u_diff(&a, &b, 1.0) < 1e-8, "{bound} s = {s:e}");
            prop_assert_eq!(iterations(&a), iterations(&b));
            prop_assert_eq!(states(&a), states(&b));
        }
    }
}

/// The regularized friction answer against the exact one: the block has sticking and
/// slipping points, and both methods label them alike and agree on u.
#[test]
fn regularized_friction_agrees_with_exact_friction() {
    for bound in ["coulomb", "tresca"] {
        let mu = if bound == "tresca" { 2.0 } else { 0.3 };
        let law = format!("bound = \"{bound}\"\nmu = {{ law = \"constant\", mu = {mu} }}\n");
        let regularized = certified(&block(1.0, 1000.0, 1e4, 2e-3, 1e-2, &law));
        let exact = certified(&block(
            1.0,
            1000.0,
            1e4,
            2e-3,
            1e-2,
            &format!("{law}exact = true\n"),
        ));
        let cert = &exact.report.certificate;
        assert!(cert.n_stick > 0 && cert.n_slip > 0, "{bound}: {cert:?}");
        assert_eq!(states(&regularized), states(&exact), "{bound}");
        let d = u_diff(&exact, &regularized, 1.0);
        assert!(d < 1e-6, "{bound}: regularized vs exact {d:e}");
    }
}

/// The case that failed: the paper's square with steel-like stiffness (E = 2e11 Pa,
/// c_ν = 1e12 Pa/m, gap 0, constant μ = 0.3) slips exactly where the same problem in soft
/// units (every stiffness ÷ 1e8) slips, with the friction force at the bound. The slips are
/// about 1e-8 m, where a regularization tied to the domain size labelled them stick.
#[test]
fn steel_units_slip_like_soft_units() {
    let case = |s: f64| {
        paper(16, 4.0, 2e11 * s, 0.0, 0.16, 900.0, 1e12 * s, 0.0, 0.0).replace(
            "{ law = \"exponential\", a = 0.4, b = 0.1, beta = 0e0 }",
            "{ law = \"constant\", mu = 0.3 }",
        )
    };
    let steel = certified(&case(1.0));
    let soft = certified(&case(1e-8));
    assert!(steel.report.certificate.n_slip > 0);
    assert_eq!(states(&steel), states(&soft));
    assert!(u_diff(&soft, &steel, 1e8) < 1e-8);
    for c in steel
        .contact
        .iter()
        .filter(|c| c.friction_state == FrictionState::Slip)
    {
        // The friction force at the bound: |R_τ| = w F.
        let ft = c.force_tangential[0].abs();
        assert!(rel(ft, c.weight * c.bound, 0.0) < 1e-6, "node {}", c.node);
    }
}

/// Extreme units: E = 2e-297 Pa with a matching traction, and E = 1e299 Pa, give the
/// answer of ordinary units (not u = 0, not an overflow).
#[test]
fn extreme_units_give_the_ordinary_answer() {
    let reference = paper_reference();
    for s in [1e-300, 1e-157, 1e295] {
        let text = paper(
            16,
            4.0,
            2000.0 * s,
            1e4 * s,
            0.16,
            900.0 * s,
            1e4 * s,
            0.4,
            100.0,
        );
        let scaled = certified(&text);
        assert!(u_diff(reference, &scaled, 1.0) < 1e-8, "s = {s:e}");
        assert_eq!(states(reference), states(&scaled));
    }
}

/// A regularization far too coarse for the certificate (an elastic slip of 10⁻³ of each
/// point's slip scale) is refused: not converged, naming the friction law, the part and the
/// node. (The paper's square in soft units with zero gap and μ = 1, where points stick and
/// slip; the elastic slip of its sticking points exceeds the stick threshold, and there the
/// friction force is below the bound.)
#[test]
fn coarse_friction_regularization_is_refused_not_certified() {
    let base = paper(16, 4.0, 2000.0, 0.0, 0.16, 900.0, 1e4, 0.0, 0.0).replace(
        "{ law = \"exponential\", a = 0.4, b = 0.1, beta = 0e0 }",
        "{ law = \"constant\", mu = 1.0 }",
    );
    let fine = certified(&base);
    let c = &fine.report.certificate;
    assert!(
        c.n_slip > 0 && c.n_stick > 0,
        "{} stick, {} slip",
        c.n_stick,
        c.n_slip
    );
    let text = format!("{base}\n[solver.outer]\nfriction_regularization = 1e-3\n");
    let s = solve_text(&text).unwrap();
    assert!(!s.report.converged);
    let m = &s.report.message;
    assert!(
        m.contains("friction law") && m.contains("node") && m.contains("contact part"),
        "{m}"
    );
    assert!(s.report.certificate.friction_law > s.report.certificate.tolerance);
}

/// Data so far apart that the displacements they cause cannot be represented in double
/// precision (E = 1e-300 Pa under 1e300 Pa: u ≈ 1e600 m) are refused with an error naming
/// the displacement scale, not solved into infinities.
#[test]
fn unrepresentable_displacements_are_refused() {
    let text = r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [2, 2]
[material]
young = 1e-300
poisson = 0.3
[[dirichlet]]
part = "bottom"
[[loads.traction]]
part = "top"
value = [0.0, -1e300]
"#;
    let err = solve_text(text).unwrap_err().to_string();
    assert!(err.contains("displacement scale"), "{err}");
}
