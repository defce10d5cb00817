//! Verification of user-defined normal compliance laws p(δ) ([`hemicontact::contact::compliance_law`])
//! and of friction bounds that vary along the interface, F(x)
//! ([`hemicontact::contact::field_law`]).
//!
//! Normal compliance:
//! 1. The energy quadrature `P(δ) = ∫₀^δ p` is exact (to round-off) for `p = δ^k`,
//!    k ≤ 15, and the responses are in the solver's units.
//! 2. A block of height H on a compliance foundation under a uniform pressure q, with
//!    rollers on its sides, is in a uniform uniaxial-strain state: the foundation pushes
//!    back with p(δ) = q, so the penetration is `δ = p⁻¹(q)`. For `p = c δ³`,
//!    `δ = (q/c)^{1/3}`; P1 elements represent the state exactly (patch test), so the
//!    computed bottom displacement equals the closed form to the solver's tolerance.
//! 3. A custom law `p = c_ν δ` gives the built-in compliance solution of the paper example to
//!    1e-12.
//! 4. The law is called with all points of a part at once, at most twice per energy
//!    evaluation.
//! 5. Validation samples the law: p(0) ≠ 0, a decreasing p, a dp that is not the slope of p,
//!    and a NaN are refused, naming the law; a failure during the solve ends it with
//!    `Error::Law`.
//!
//! Friction bound of the position:
//! 6. A constant F(x) = F₀ gives the built-in constant Tresca bound's solution.
//! 7. The bound written at each contact point is F at that point's coordinates (the
//!    positions reach the function in metres through the solver's scaling).
//! 8. The uniqueness check takes μ₀ as the largest value at the part's nodes; a negative
//!    value is refused at validation, naming the law and the point.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::contact::{
    ComplianceFunction, ContactBoundary, CustomCompliance, CustomField, FrictionCoefficient,
    NormalLaw, NormalResponse, PositionFunction,
};
use hemicontact::problem::Problem;
use hemicontact::scenario::{builtin, Scenario};
use hemicontact::solver::{solve, SolverSettings};
use hemicontact::Error;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

/// `p = c δ^m`, `p' = c m δ^(m−1)`, counting calls and recording batch sizes; `fault`
/// makes it misbehave.
#[derive(Debug, Default)]
struct Power {
    c: f64,
    m: i32,
    fault: Option<&'static str>,
    calls: AtomicUsize,
    batches: Mutex<Vec<usize>>,
}

impl Power {
    fn new(c: f64, m: i32) -> Self {
        Power {
            c,
            m,
            ..Power::default()
        }
    }
}

impl ComplianceFunction for Power {
    fn pressure(&self, x: &[f64], out: &mut [f64]) -> Result<(), String> {
        self.calls.fetch_add(1, Ordering::SeqCst);
        self.batches.lock().unwrap().push(x.len());
        for (p, &d) in out.iter_mut().zip(x) {
            *p = self.c * d.powi(self.m);
            match self.fault {
                Some("offset") => *p += 1.0,
                Some("decreasing") if d > 1e-3 => *p = self.c * 1e-9 / d,
                Some("nan") if d > 1e-3 => *p = f64::NAN,
                _ => {}
            }
        }
        if self.fault == Some("error") && x.len() < 300 {
            return Err("the asperity model diverged".into());
        }
        Ok(())
    }

    fn stiffness(&self, x: &[f64], out: &mut [f64]) -> Result<(), String> {
        self.calls.fetch_add(1, Ordering::SeqCst);
        self.batches.lock().unwrap().push(x.len());
        for (k, &d) in out.iter_mut().zip(x) {
            *k = self.c * f64::from(self.m) * d.powi(self.m - 1);
            if self.fault == Some("wrong-slope") {
                *k *= 2.0;
            }
        }
        Ok(())
    }
}

#[test]
fn the_energy_quadrature_is_exact_for_polynomials_up_to_degree_15() {
    for m in 1..=15 {
        let law = CustomCompliance::new("power", Arc::new(Power::new(3.0, m)));
        let delta = [0.0, -0.5, 0.25, 1.0, 1.7];
        let mut out = [NormalResponse::default(); 5];
        law.responses(&delta, true, &mut out).unwrap();
        for (d, r) in delta.iter().zip(&out) {
            let d = d.max(0.0);
            let mf = f64::from(m);
            let energy = 3.0 * d.powi(m + 1) / (mf + 1.0);
            assert!(
                (r.energy - energy).abs() <= 1e-14 * energy.max(1.0),
                "m = {m}, δ = {d}: {} vs {energy}",
                r.energy
            );
            assert_eq!(r.pressure, 3.0 * d.powi(m));
            assert_eq!(
                r.stiffness,
                if d > 0.0 {
                    3.0 * mf * d.powi(m - 1)
                } else {
                    0.0
                }
            );
        }
    }
    // Units: δ̂ in units of U, p̂ in units of T: P̂ = P/(T U), p̂ = p/T, p̂' = p' U/T.
    let (u, t) = (0.5, 8.0);
    let law = CustomCompliance::new("power", Arc::new(Power::new(3.0, 2))).nondimensional(u, t);
    let mut out = [NormalResponse::default()];
    law.responses(&[2.0], true, &mut out).unwrap();
    let d: f64 = 2.0 * u;
    assert!((out[0].energy - d.powi(3) / (t * u)).abs() <= 1e-15);
    assert_eq!(out[0].pressure, 3.0 * d * d / t);
    assert_eq!(out[0].stiffness, 6.0 * d * u / t);
}

/// A 1 × 1 block, rollers on its sides, a pressure `q` on its top, on a foundation with
/// the law `law` under its bottom (gap `gap`).
fn block(q: f64, gap: f64, law: NormalLaw) -> (Problem, SolverSettings) {
    let text = format!(
        r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [6, 6]
[material]
young = 1000.0
poisson = 0.3
plane = "strain"
[[dirichlet]]
part = "left"
components = ["x"]
[[dirichlet]]
part = "right"
components = ["x"]
[[loads.traction]]
part = "top"
value = [0.0, {}]
[[contact]]
part = "bottom"
gap = {gap:?}
law = "normal-compliance"
c_nu = 1.0
"#,
        -q
    );
    let mut scenario = Scenario::from_str(&text, "<block>").unwrap();
    scenario.given_normal = vec![(0, law)];
    (
        scenario.into_problem().unwrap(),
        scenario.settings().unwrap(),
    )
}

#[test]
fn a_block_on_a_cubic_foundation_sinks_by_the_closed_form_penetration() {
    let (c, q, gap) = (1e9, 50.0, 0.01);
    let law = NormalLaw::Custom(CustomCompliance::new("cubic", Arc::new(Power::new(c, 3))));
    let (problem, settings) = block(q, gap, law);
    let s = solve(&problem, &settings).unwrap();
    assert!(s.report.converged, "{}", s.report.message);
    assert!(
        s.report.certificate.failures().is_empty(),
        "{:?}",
        s.report.certificate
    );
    // δ = (q/c)^{1/3}: the bottom moves down by g + δ.
    let delta = (q / c).cbrt();
    for r in &s.contact {
        // The remaining gap is g − u_ν = −δ.
        assert!(
            (r.gap + delta).abs() <= 1e-9 * delta,
            "g − u_ν = {} vs −δ = {}",
            r.gap,
            -delta
        );
        assert!(
            (r.pressure - q).abs() <= 1e-8 * q,
            "p = {} vs q = {q}",
            r.pressure
        );
    }
}

#[test]
fn a_linear_custom_law_reproduces_the_built_in_compliance_on_the_paper_example() {
    let scenario = Scenario::from_str(&builtin::paper(16, 1e4), "<paper>").unwrap();
    let (problem, settings) = (
        scenario.into_problem().unwrap(),
        scenario.settings().unwrap(),
    );
    let NormalLaw::Compliance(c) = problem.contact()[0].normal.clone() else {
        panic!("the paper uses normal compliance");
    };
    let law = Arc::new(Power::new(c.c_nu, 1));
    let mut builder = problem.to_builder().without_contact();
    for cb in problem.contact() {
        builder = builder.contact(ContactBoundary {
            against: None,
            normal: NormalLaw::Custom(CustomCompliance::new("linear", law.clone())),
            ..cb.clone()
        });
    }
    let custom = builder.build().unwrap();
    law.calls.store(0, Ordering::SeqCst);
    law.batches.lock().unwrap().clear();
    let built_in = solve(&problem, &settings).unwrap();
    let user = solve(&custom, &settings).unwrap();
    assert!(built_in.report.converged && user.report.converged);
    assert!(user.report.certificate.failures().is_empty());
    let rel = |x: &[f64], y: &[f64]| {
        let d = x
            .iter()
            .zip(y)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        d / y.iter().fold(0.0f64, |m, b| m.max(b.abs()))
    };
    assert!(
        rel(&user.u, &built_in.u) <= 1e-12,
        "{}",
        rel(&user.u, &built_in.u)
    );
    let p = |s: &hemicontact::solver::Solution| -> Vec<f64> {
        s.contact.iter().map(|c| c.pressure).collect()
    };
    assert!(rel(&p(&user), &p(&built_in)) <= 1e-12);
    // Batches: every call has all the points of one part (16 per side), or 9 times as
    // many for the quadrature; never one point at a time.
    let batches = law.batches.lock().unwrap();
    assert!(!batches.is_empty());
    assert!(batches.iter().all(|&n| n > 0 && n <= 9 * 16), "{batches:?}");
    // At most two calls (p, dp) per part per energy evaluation: the evaluations are the
    // Newton steps plus line-search trials plus the outer iterations' and the final ones.
    let evaluations: usize = user.report.newton.len() * 3 + user.report.outer.len() * 2 + 4;
    assert!(law.calls.load(Ordering::SeqCst) <= 2 * 2 * evaluations);
}

/// The validation error of a block whose foundation law is `Power` with `fault`.
fn refused(fault: &'static str) -> String {
    let law = Power {
        fault: Some(fault),
        ..Power::new(1e9, 3)
    };
    let text = r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [2, 2]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "top"
[[contact]]
part = "bottom"
law = "normal-compliance"
c_nu = 1.0
"#;
    let mut scenario = Scenario::from_str(text, "<block>").unwrap();
    scenario.given_normal = vec![(
        0,
        NormalLaw::Custom(CustomCompliance::new("faulty", Arc::new(law))),
    )];
    match scenario.into_problem() {
        Err(e @ Error::Law { .. }) => e.to_string(),
        other => panic!("{fault}: expected a law error, got {other:?}"),
    }
}

#[test]
fn validation_refuses_a_law_that_is_not_a_monotone_compliance_naming_it() {
    let offset = refused("offset");
    assert!(
        offset.contains("contact[0].normal (faulty)") && offset.contains("p(0)"),
        "{offset}"
    );
    let decreasing = refused("decreasing");
    assert!(decreasing.contains("monotone"), "{decreasing}");
    let slope = refused("wrong-slope");
    assert!(slope.contains("derivative of p"), "{slope}");
    let nan = refused("nan");
    assert!(nan.contains("NaN") && nan.contains("finite"), "{nan}");
}

#[test]
fn a_law_that_fails_during_the_solve_ends_it_with_its_error() {
    // Validation calls p with 303 penetrations; the solve's batches are smaller, and fail.
    let law = Power {
        fault: Some("error"),
        ..Power::new(1e9, 3)
    };
    let (problem, settings) = block(
        50.0,
        0.0,
        NormalLaw::Custom(CustomCompliance::new("diverging", Arc::new(law))),
    );
    match solve(&problem, &settings) {
        Err(Error::Law { law, message }) => {
            assert_eq!(law, "contact[0].normal (diverging)");
            assert!(message.contains("the asperity model diverged"), "{message}");
        }
        other => panic!("expected a law error, got {other:?}"),
    }
}

/// `F(x) = f(x)` for a Rust closure, recording the positions it was called with.
struct Field<F: Fn(&[f64]) -> f64 + Send + Sync> {
    f: F,
    seen: Mutex<Vec<[f64; 3]>>,
}

impl<F: Fn(&[f64]) -> f64 + Send + Sync> std::fmt::Debug for Field<F> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "field")
    }
}

impl<F: Fn(&[f64]) -> f64 + Send + Sync> PositionFunction for Field<F> {
    fn evaluate(&self, points: &[[f64; 3]], dim: usize, out: &mut [f64]) -> Result<(), String> {
        self.seen.lock().unwrap().extend_from_slice(points);
        for (v, x) in out.iter_mut().zip(points) {
            *v = (self.f)(&x[..dim]);
        }
        Ok(())
    }
}

/// The paper example (n = 16) with Tresca friction of bound `mu` on both sides.
fn tresca(mu: FrictionCoefficient) -> Result<(Problem, SolverSettings), Error> {
    let text = builtin::paper(16, 1e4).replace(
        "bound = \"coulomb\"\npotential = { kind = \"norm\" }\nmu = { law = \"exponential\", a = 0.4, b = 0.1, beta = 100.0 }",
        "bound = \"tresca\"\npotential = { kind = \"norm\" }\nmu = { law = \"constant\", mu = 30.0 }",
    );
    assert!(text.contains("tresca"));
    let mut scenario = Scenario::from_str(&text, "<paper, Tresca>").unwrap();
    scenario.given_friction = vec![(0, mu.clone()), (1, mu)];
    Ok((scenario.into_problem()?, scenario.settings()?))
}

#[test]
fn a_constant_bound_of_the_position_gives_the_built_in_constant_bound() {
    let (built_in, settings) = tresca(FrictionCoefficient::Constant { mu: 30.0 }).unwrap();
    let field = Arc::new(Field {
        f: |_: &[f64]| 30.0,
        seen: Mutex::new(Vec::new()),
    });
    let (custom, _) = tresca(FrictionCoefficient::Field(CustomField::new(
        "thirty", field,
    )))
    .unwrap();
    let a = solve(&built_in, &settings).unwrap();
    let b = solve(&custom, &settings).unwrap();
    assert!(a.report.converged && b.report.converged);
    assert!(
        a.report.certificate.n_slip > 0,
        "some points slip: the bound matters"
    );
    assert!(a
        .u
        .iter()
        .zip(&b.u)
        .all(|(x, y)| x.to_bits() == y.to_bits()));
}

#[test]
fn the_bound_at_each_point_is_the_function_at_that_points_coordinates() {
    // F(x, y) = 10 + 5 y (Pa): a bound growing with height along the sides.
    let field = Arc::new(Field {
        f: |x: &[f64]| 10.0 + 5.0 * x[1],
        seen: Mutex::new(Vec::new()),
    });
    let (problem, settings) = tresca(FrictionCoefficient::Field(CustomField::new(
        "graded",
        field.clone(),
    )))
    .unwrap();
    let s = solve(&problem, &settings).unwrap();
    assert!(s.report.converged, "{}", s.report.message);
    let mesh = problem.mesh();
    for r in &s.contact {
        let y = mesh.node(r.node as usize)[1];
        assert!(
            (r.bound - (10.0 + 5.0 * y)).abs() <= 1e-12 * r.bound,
            "{} at y = {y}",
            r.bound
        );
    }
    // The function saw positions in metres on the sides x = 0 and x = 4 of the 4 × 4 body.
    assert!(field
        .seen
        .lock()
        .unwrap()
        .iter()
        .all(|p| (p[0] == 0.0 || p[0] == 4.0) && (0.0..=4.0).contains(&p[1])));
    // μ₀ of the uniqueness check: the largest value at the parts' nodes, F(·, 4) = 30 Pa.
    let u = hemicontact::solver::uniqueness::evaluate(&problem, &settings);
    assert_eq!(u.mu0, 30.0);
    assert_eq!(u.l_mu, 0.0);
}

#[test]
fn a_negative_bound_is_refused_at_validation_naming_the_point() {
    let field = Arc::new(Field {
        f: |x: &[f64]| 2.0 - x[1],
        seen: Mutex::new(Vec::new()),
    });
    let err = tresca(FrictionCoefficient::Field(CustomField::new(
        "sinking", field,
    )))
    .expect_err("refused");
    let text = err.to_string();
    assert!(matches!(err, Error::Law { .. }), "{text}");
    assert!(
        text.contains("contact[0].friction.mu (sinking)") && text.contains("finite and ≥ 0"),
        "{text}"
    );
}
