//! The uniqueness check of the paper's Theorem 4: the discrete trace constant ‖γ‖ against
//! a hand bound and under mesh refinement, and the condition's bookkeeping.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::scenario::{builtin, Scenario};
use hemicontact::solver::uniqueness::{check, trace_constant};
use hemicontact::solver::SolverSettings;

mod common;

use common::problem;

/// The validated problem and `[solver]` settings of a scenario text.
fn setup(text: &str) -> (hemicontact::problem::Problem, SolverSettings) {
    let scenario = Scenario::from_str(text, "test").unwrap();
    let problem = scenario.into_problem().unwrap();
    (problem, scenario.settings().unwrap())
}

fn block_with_top_contact(n: usize) -> String {
    format!(
        r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [{n}, {n}]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "bottom"
[[contact]]
part = "top"
gap = 0.0
c_nu = 1.0e3
[contact.friction]
bound = "tresca"
mu = {{ law = "constant", mu = 1.0 }}
"#
    )
}

/// Unit square clamped at the bottom, Γ_C = top. The P1 field v = (y, 0) has
/// ‖ε(v)‖² = ∫ 2 (½)² = ½ and ‖v‖²_{Γ_C} = 1 (lumped weights integrate constants exactly),
/// so ‖γ‖² ≥ 2 on every mesh; the discrete constant also converges under refinement.
#[test]
fn trace_constant_respects_hand_bound_and_converges() {
    let mut values = Vec::new();
    for n in [4, 8, 16, 32] {
        let (g, it) = trace_constant(
            &problem(&block_with_top_contact(n)),
            &SolverSettings::default(),
        )
        .unwrap();
        assert!(it < 2000, "power iteration did not converge");
        assert!(
            g * g >= 2.0 - 1e-9,
            "n = {n}: ‖γ‖² = {} below the hand bound 2",
            g * g
        );
        values.push(g);
    }
    eprintln!("‖γ‖ for n = 4, 8, 16, 32: {values:?}");
    let d: Vec<f64> = values.windows(2).map(|w| (w[1] - w[0]).abs()).collect();
    assert!(d[1] < d[0] && d[2] < d[1], "differences must shrink: {d:?}");
    assert!(d[2] < 0.02 * values[3]);
}

/// The condition `(μ₀ α_j + c_j L_μ) ‖γ‖² < m_A` with the constants of the laws: for the
/// paper's slip-weakening μ (a = 0.4, b = 0.1, β = 100) with a Tresca-type bound and
/// j = ‖·‖, `α_j = 0`, `c_j = 1`, `L_μ = (a − b) β = 30`, `m_A = 2G` (λ ≥ 0).
#[test]
fn condition_uses_the_constants_of_the_laws() {
    let text = builtin::paper(8, 1.0e4).replace("bound = \"coulomb\"", "bound = \"tresca\"");
    let u = check(&problem(&text), &SolverSettings::default()).unwrap();
    assert!(u.applies);
    let g = 2000.0 / 2.6;
    assert!((u.m_a - 2.0 * g).abs() < 1e-9);
    assert!((u.l_mu - 30.0).abs() < 1e-12 && u.alpha_j == 0.0 && u.c_j == 1.0);
    let gamma = u.trace_constant.unwrap();
    assert!((u.lhs - 30.0 * gamma * gamma).abs() < 1e-9 * u.lhs);
    assert_eq!(u.holds, u.lhs < u.m_a);
    assert!((u.margin - (u.m_a - u.lhs)).abs() < 1e-9);
    // The nonconvex potential (17) adds μ₀ α_j with α_j = (1 − a)/a.
    let text = text.replace(
        "potential = { kind = \"norm\" }",
        "potential = { kind = \"nonconvex\", a = 0.5 }",
    );
    let u2 = check(&problem(&text), &SolverSettings::default()).unwrap();
    assert!((u2.alpha_j - 1.0).abs() < 1e-12);
    assert!((u2.lhs - (0.4 * 1.0 + 30.0) * gamma * gamma).abs() < 1e-9 * u2.lhs);
}

/// Coulomb-type bounds are outside the theorem: the check says so and computes nothing.
#[test]
fn coulomb_bound_is_reported_as_not_covered() {
    let u = check(
        &problem(&builtin::paper(8, 1.0e4)),
        &SolverSettings::default(),
    )
    .unwrap();
    assert!(!u.applies && !u.holds);
    assert!(u.note.unwrap().contains("Coulomb"));
    assert!(u.trace_constant.is_none());
}

/// The unit square clamped on `bottom` and `left`, cut by one "/" diagonal into two
/// triangles: the only free node is the corner (1, 1), a contact node of `top` with
/// lumped weight ½, pushed into the foundation by a traction on `right`. E = 1000 Pa,
/// ν = 0: m_A = 2G = 1000 Pa. Tresca-type bound, j = ‖·‖ (α_j = 0, c_j = 1),
/// μ(r) = 0.3 e^{−βr} + 0.1: L_μ = 0.3 β.
///
/// By hand, with `v = a φ` (φ the hat function of (1, 1): `y` on the lower triangle, `x`
/// on the upper one), `‖ε(v)‖² = ½ (a_y² + a_x²/2) + ½ (a_x² + a_y²/2) = ¾ |a|²` and
/// `‖v‖²_{Γ_C} = ½ |a|²`, so `‖γ‖² = 2/3` and the left-hand side is `0.3 β · 2/3 = 0.2 β`.
fn one_free_node(beta: f64, extra: &str) -> String {
    format!(
        r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [1, 1]
pattern = "uniform"
[material]
young = 1000.0
poisson = 0.0
[[dirichlet]]
part = "bottom"
[[dirichlet]]
part = "left"
[[loads.traction]]
part = "right"
value = [0.0, 10.0]
[[contact]]
part = "top"
gap = 0.0
c_nu = 1.0e3
[contact.friction]
bound = "tresca"
mu = {{ law = "exponential", a = 0.4, b = 0.1, beta = {beta:?} }}
{extra}
"#
    )
}

/// The `uniqueness` block of the summary of a solve of `text`, as written to JSON.
fn summary_uniqueness(text: &str) -> serde_json::Value {
    let (p, settings) = setup(text);
    let solution = hemicontact::solver::solve(&p, &settings).unwrap();
    let summary = hemicontact::io::summary::Summary::new(&p, &settings, &solution, None, "test");
    let json = serde_json::to_value(&summary).unwrap();
    json["uniqueness"].clone()
}

fn num(v: &serde_json::Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("`{key}` is not a number in {v}"))
}

/// β = 2000: L_μ = 600, lhs = 400 < m_A = 1000: the condition holds (margin 600).
#[test]
fn summary_carries_the_condition_where_it_holds() {
    let u = summary_uniqueness(&one_free_node(2000.0, ""));
    assert_eq!(u["applies"], true, "{u}");
    assert_eq!(u["holds"], true, "{u}");
    assert!(
        (num(&u, "trace_constant").powi(2) - 2.0 / 3.0).abs() < 1e-9,
        "{u}"
    );
    assert!((num(&u, "m_a") - 1000.0).abs() < 1e-9);
    assert!((num(&u, "lhs") - 400.0).abs() < 1e-6, "{u}");
    assert!((num(&u, "margin") - 600.0).abs() < 1e-6, "{u}");
}

/// β = 6000: L_μ = 1800, lhs = 1200 ≥ m_A = 1000: the condition fails (margin −200).
#[test]
fn summary_carries_the_condition_where_it_fails() {
    let u = summary_uniqueness(&one_free_node(6000.0, ""));
    assert_eq!(u["applies"], true, "{u}");
    assert_eq!(u["holds"], false, "{u}");
    assert!((num(&u, "lhs") - 1200.0).abs() < 1e-6, "{u}");
    assert!((num(&u, "margin") + 200.0).abs() < 1e-6, "{u}");
}

/// Where the condition is not evaluated, the summary says why: no contact boundary, a
/// Coulomb-type bound, the iterative linear solver.
#[test]
fn summary_gives_the_reason_where_the_condition_is_not_evaluated() {
    let no_contact = one_free_node(2000.0, "")
        .split("[[contact]]")
        .next()
        .unwrap()
        .to_string();
    let u = summary_uniqueness(&no_contact);
    assert_eq!(u["applies"], false, "{u}");
    assert!(u["note"].as_str().unwrap().contains("no contact"), "{u}");

    let u = summary_uniqueness(&builtin::paper(8, 1.0e4));
    assert_eq!(u["applies"], false, "{u}");
    assert!(u["note"].as_str().unwrap().contains("Coulomb"), "{u}");

    let iterative = one_free_node(2000.0, "[solver]\nlinear_solver = \"iterative\"")
        .replace("n = [1, 1]", "n = [4, 4]");
    let u = summary_uniqueness(&iterative);
    assert_eq!(u["applies"], false, "{u}");
    assert!(u["note"].as_str().unwrap().contains("iterative"), "{u}");
    assert!(u["trace_constant"].is_null() && u["lhs"].is_null(), "{u}");
    assert!((num(&u, "l_mu") - 600.0).abs() < 1e-9, "{u}");
}
