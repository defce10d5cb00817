//! Load stepping: scaled problems, the load path driver and `[loading]` input, against
//! facts known without the program: linearity without contact, the global equilibrium of
//! a body resting on its foundation, uniqueness of convex problems, and the identity of a
//! one-step path with the plain solve.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::loading::{for_each_step, load_path, LoadStep, PathRow};
use hemicontact::scenario::Scenario;
use hemicontact::solver::{solve, Solution};
use std::sync::atomic::AtomicBool;

mod common;

use common::setup;

/// Solves `text` along its `[loading]` path.
fn path_of(text: &str) -> Vec<LoadStep> {
    let scenario = Scenario::from_str(text, "<test>").unwrap();
    let (problem, settings) = (
        scenario.into_problem().unwrap(),
        scenario.settings().unwrap(),
    );
    let factors = scenario.load_factors().unwrap().expect("a [loading] table");
    load_path(
        &problem,
        &settings,
        &factors,
        &AtomicBool::new(false),
        &|_, _| {},
        &mut |_| Ok(()),
    )
    .unwrap()
}

/// A block clamped at the bottom, pressed down on top, bulging into a wall on the right
/// (normal compliance) with the friction `friction` (a `[contact.friction]` table or "").
fn bulging_block(friction: &str, loading: &str) -> String {
    format!(
        r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [6, 6]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "bottom"
[[loads.traction]]
part = "top"
value = [0.0, -300.0]
[[contact]]
part = "right"
gap = 0.01
c_nu = 1.0e4
{friction}
{loading}
"#
    )
}

fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

fn max_abs(a: &[f64]) -> f64 {
    a.iter().map(|x| x.abs()).fold(0.0, f64::max)
}

fn one_shot(text: &str) -> Solution {
    let (problem, settings) = setup(text);
    solve(&problem, &settings).unwrap()
}

/// Frictionless and Tresca contact with normal compliance and Hooke's law are strictly
/// convex minimizations: one solution, whatever the start. The last step of a path (λ = 1)
/// and the one-shot solve are two certified approximations of it: both stop with relative
/// residuals of at most the certificate tolerance 1e-6, and Newton's quadratic convergence
/// on a strictly convex energy puts both far below it, so the displacements agree to the
/// certificate tolerance relative to max |u| (they agree to round-off in practice).
#[test]
fn last_step_is_the_one_shot_solution_of_a_convex_problem() {
    let tresca = "[contact.friction]\nbound = \"tresca\"\nmu = 5.0\n";
    for friction in ["", tresca] {
        let plain = one_shot(&bulging_block(friction, ""));
        let path = path_of(&bulging_block(friction, "[loading]\nsteps = 4\n"));
        assert_eq!(path.len(), 4);
        let last = path.last().unwrap();
        assert!(last.solution.report.converged && plain.report.converged);
        assert_eq!(last.factor, 1.0);
        assert!(
            last.solution.report.certificate.n_contact > 0,
            "the block touches"
        );
        let scale = max_abs(&plain.u);
        let diff = max_abs_diff(&last.solution.u, &plain.u);
        assert!(
            diff <= 1e-6 * scale,
            "friction {friction:?}: |u_path - u| = {diff:e}, max |u| = {scale:e}"
        );
    }
}

/// One step at λ = 1 is the plain solve: same problem, same start, same arithmetic.
#[test]
fn one_step_is_the_plain_solve_bitwise() {
    let friction = "[contact.friction]\nbound = \"coulomb\"\n\
                    mu = { law = \"exponential\", a = 0.4, b = 0.1, beta = 100.0 }\n";
    let plain = one_shot(&bulging_block(friction, ""));
    let path = path_of(&bulging_block(friction, "[loading]\nsteps = 1\n"));
    assert_eq!(path.len(), 1);
    let s = &path[0].solution;
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&s.u), bits(&plain.u));
    assert_eq!(bits(&s.reactions), bits(&plain.reactions));
    assert_eq!(s.report.newton.len(), plain.report.newton.len());
}

/// Hooke's law without contact is linear: u(λ) = λ u(1) to round-off, including a
/// prescribed displacement, which scales with the loads.
#[test]
fn linear_elastic_problem_scales_exactly() {
    let text = r#"
[mesh]
kind = "rectangle"
size = [2.0, 1.0]
n = [8, 4]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "left"
[[dirichlet]]
part = "right"
components = ["x"]
value = [0.01, 0.0]
[[loads.traction]]
part = "top"
value = [5.0, -20.0]
[loads]
body_force = [0.0, -3.0]
[loading]
factors = [0.1, 0.3, 0.7, 1.0]
"#;
    let path = path_of(text);
    assert_eq!(path.len(), 4);
    let u1 = &path[3].solution.u;
    let scale = max_abs(u1);
    assert!(scale > 0.0);
    for step in &path {
        assert!(step.solution.report.converged);
        let scaled: Vec<f64> = u1.iter().map(|x| step.factor * x).collect();
        let diff = max_abs_diff(&step.solution.u, &scaled);
        assert!(
            diff <= 1e-10 * scale,
            "λ = {}: |u(λ) − λ u(1)| = {diff:e}, max |u(1)| = {scale:e}",
            step.factor
        );
    }
}

/// A block held only horizontally (a roller on the left) rests on a frictionless
/// compliant foundation and is pressed down by a uniform traction 300 N/m on its top of
/// width 1: vertical equilibrium makes the total contact force exactly λ · 300 N/m upward,
/// nondecreasing along the path, and the number of points in contact cannot decrease.
#[test]
fn frictionless_path_is_monotone_and_in_equilibrium() {
    let text = r#"
[mesh]
kind = "rectangle"
size = [1.0, 0.5]
n = [8, 4]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "left"
components = ["x"]
[[loads.traction]]
part = "top"
value = [0.0, -300.0]
[[contact]]
part = "bottom"
gap = 0.001
c_nu = 1.0e4
[loading]
steps = 5
"#;
    let path = path_of(text);
    assert_eq!(path.len(), 5);
    let rows: Vec<PathRow> = path.iter().map(PathRow::of).collect();
    for (k, r) in rows.iter().enumerate() {
        assert!(r.converged, "step {}", k + 1);
        let expected = r.factor * 300.0;
        assert!(
            (r.contact_force[1] - expected).abs() <= 1e-5 * expected,
            "λ = {}: total contact force {} against {expected}",
            r.factor,
            r.contact_force[1]
        );
        assert!(r.contact_force[0].abs() <= 1e-5 * expected, "frictionless");
        if k > 0 {
            assert!(r.contact_force[1] >= rows[k - 1].contact_force[1]);
            assert!(r.n_contact >= rows[k - 1].n_contact);
        }
    }
    assert!(rows[0].n_contact > 0);
}

/// `[loading]` errors name the field, the value and what is allowed.
#[test]
fn bad_loading_input_names_the_field() {
    let cases = [
        ("steps = 0", "loading.steps"),
        ("steps = 10001", "loading.steps"),
        ("factors = []", "loading.factors"),
        ("factors = [0.0, 1.0]", "loading.factors[0]"),
        ("factors = [-0.5]", "loading.factors[0]"),
        ("factors = [0.5, 0.5]", "loading.factors[1]"),
        ("factors = [0.5, 0.25]", "loading.factors[1]"),
        ("factors = [0.5, nan]", "loading.factors[1]"),
        ("factors = [0.5, inf]", "loading.factors[1]"),
        ("steps = 2\nfactors = [1.0]", "loading"),
        ("", "loading"),
    ];
    for (table, field) in cases {
        let text = bulging_block("", &format!("[loading]\n{table}\n"));
        let scenario = Scenario::from_str(&text, "<test>").unwrap();
        let e = scenario.into_problem().expect_err(table).to_string();
        assert!(
            e.contains(&format!("`{field}`")) || e.contains(&format!("{field} ")),
            "{table}: {e}"
        );
        let e2 = scenario.load_factors().expect_err(table).to_string();
        assert_eq!(e, e2);
    }
    // An unknown key is a parse error naming it.
    let text = bulging_block("", "[loading]\nstep = 2\n");
    let e = Scenario::from_str(&text, "<test>").unwrap_err().to_string();
    assert!(e.contains("step"), "{e}");
    // The library's own check.
    let (problem, _) = setup(&bulging_block("", ""));
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = problem.with_load_factor(bad).unwrap_err().to_string();
        assert!(e.contains("load_factor"), "{e}");
    }
}

/// `steps = N` gives k/N exactly, the last being 1.
#[test]
fn uniform_steps_are_k_over_n() {
    let f = hemicontact::loading::uniform_factors(8).unwrap();
    assert_eq!(f, vec![0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 1.0]);
    let f = hemicontact::loading::uniform_factors(3).unwrap();
    assert_eq!(f, vec![1.0 / 3.0, 2.0 / 3.0, 1.0]);
}

#[test]
fn steps_handed_over_one_by_one_are_the_steps_of_the_path_bitwise() {
    let text = bulging_block("", "[loading]\nsteps = 5\n");
    let kept = path_of(&text);
    let scenario = Scenario::from_str(&text, "<test>").unwrap();
    let (problem, settings) = (
        scenario.into_problem().unwrap(),
        scenario.settings().unwrap(),
    );
    let factors = scenario.load_factors().unwrap().unwrap();
    let mut handed = Vec::new();
    let n = for_each_step(
        &problem,
        &settings,
        &factors,
        &AtomicBool::new(false),
        &|_, _| {},
        &mut |step| {
            handed.push((step.step, step.factor, step.solution.u));
            Ok(())
        },
    )
    .unwrap();
    assert_eq!(n, 5);
    assert_eq!(handed.len(), kept.len());
    for ((k, factor, u), step) in handed.iter().zip(&kept) {
        assert_eq!((*k, *factor), (step.step, step.factor));
        assert_eq!(u, &step.solution.u, "step {k}");
    }
    // A step that does not converge ends the path there, and is handed over.
    let strict = bulging_block(
        "",
        "[loading]\nsteps = 3\n[solver.newton]\nresidual_tolerance = 1e-300\nmax_iterations = 2\n",
    );
    let scenario = Scenario::from_str(&strict, "<test>").unwrap();
    let (problem, settings) = (
        scenario.into_problem().unwrap(),
        scenario.settings().unwrap(),
    );
    let mut converged = Vec::new();
    let n = for_each_step(
        &problem,
        &settings,
        &[0.5, 1.0],
        &AtomicBool::new(false),
        &|_, _| {},
        &mut |step| {
            converged.push(step.solution.report.converged);
            Ok(())
        },
    )
    .unwrap();
    assert_eq!((n, converged), (1, vec![false]));
}
