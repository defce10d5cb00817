//! Verification of user-defined friction coefficients μ(r) ([`hemicontact::contact::slip_law`]).
//!
//! 1. A custom Rust law that computes the paper's exponential slip weakening
//!    `μ(r) = (a − b) e^{−βr} + b` gives the built-in exponential law's solution of the paper
//!    example. The solver's scales are powers of two, so the dimensionless slip handed to the
//!    function, `r̂ · U`, is the user's slip exactly and `β (r̂ U)` equals the built-in
//!    `(β U) r̂` bit for bit: the two solutions are expected, and observed, to be bitwise
//!    identical (the 1e-12 relative bound is the requirement, the bitwise equality what is
//!    observed).
//! 2. The function is evaluated in batches: once per contact part at the starting
//!    displacement, once per outer iteration and once for the certificate, each call with
//!    the slips of all the part's points (counted with atomic counters).
//! 3. A function returning NaN, a negative value or an error stops the solve with
//!    `Error::Law`, naming the law and the slip.
//! 4. Validation samples the law at 0 and 10^(k/10) m, k = −100 … 20, and refuses a
//!    negative sample, naming the law and the first such slip; `sup μ` and `L_μ` of a custom
//!    law are estimates from those samples and the uniqueness check says so.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::contact::{ContactBoundary, CustomCoefficient, FrictionCoefficient, SlipFunction};
use hemicontact::problem::Problem;
use hemicontact::scenario::{builtin, Scenario};
use hemicontact::solver::{solve, SolverSettings};
use hemicontact::Error;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

/// The paper's law: a = μ(0), b = μ(∞), β (1/m).
const A: f64 = 0.4;
const B: f64 = 0.1;
const BETA: f64 = 100.0;

/// `(a − b) e^{−βr} + b`, written as the built-in law writes it, counting calls and
/// recording the batch sizes.
#[derive(Debug, Default)]
struct Exponential {
    calls: AtomicUsize,
    batches: Mutex<Vec<usize>>,
}

impl SlipFunction for Exponential {
    fn evaluate(&self, slips: &[f64], out: &mut [f64]) -> Result<(), String> {
        self.calls.fetch_add(1, Ordering::SeqCst);
        self.batches.lock().unwrap().push(slips.len());
        for (mu, &r) in out.iter_mut().zip(slips) {
            *mu = (A - B) * (-BETA * r).exp() + B;
        }
        Ok(())
    }
}

/// How a [`Faulty`] law fails once armed.
#[derive(Debug, Clone, Copy)]
enum Fault {
    Nan,
    Negative,
    Error,
}

/// The paper's law until armed; then it fails at the first positive slip of a call,
/// recording that slip.
#[derive(Debug)]
struct Faulty {
    fault: Fault,
    armed: AtomicBool,
    at: Mutex<Option<f64>>,
}

impl SlipFunction for Faulty {
    fn evaluate(&self, slips: &[f64], out: &mut [f64]) -> Result<(), String> {
        for (mu, &r) in out.iter_mut().zip(slips) {
            *mu = (A - B) * (-BETA * r).exp() + B;
        }
        if !self.armed.load(Ordering::SeqCst) {
            return Ok(());
        }
        let Some(k) = slips.iter().position(|&r| r > 0.0) else {
            return Ok(());
        };
        *self.at.lock().unwrap() = Some(slips[k]);
        match self.fault {
            Fault::Nan => out[k] = f64::NAN,
            Fault::Negative => out[k] = -0.25,
            Fault::Error => return Err("the table lookup failed".into()),
        }
        Ok(())
    }
}

/// The paper example with `n × n` squares and its solver settings.
fn paper(n: usize) -> (Problem, SolverSettings) {
    let scenario = Scenario::from_str(&builtin::paper(n, 1e4), "<paper>").unwrap();
    (
        scenario.into_problem().unwrap(),
        scenario.settings().unwrap(),
    )
}

/// `problem` with every friction coefficient replaced by the custom law `law` named
/// `name`.
fn with_law(
    problem: &Problem,
    name: &str,
    law: Arc<dyn SlipFunction>,
) -> hemicontact::Result<Problem> {
    let mut builder = problem.to_builder().without_contact();
    for c in problem.contact() {
        let mut friction = c.friction.clone().unwrap();
        friction.mu = FrictionCoefficient::Custom(CustomCoefficient::new(name, law.clone()));
        builder = builder.contact(ContactBoundary {
            against: None,
            friction: Some(friction),
            ..c.clone()
        });
    }
    builder.build()
}

/// Largest `|x − y|` over the largest `|y|`.
fn rel_max(x: &[f64], y: &[f64]) -> f64 {
    let d = x
        .iter()
        .zip(y)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    d / y.iter().fold(0.0f64, |m, b| m.max(b.abs()))
}

#[test]
fn custom_exponential_law_reproduces_the_built_in_law_on_the_paper_example() {
    let (problem, settings) = paper(16);
    assert_eq!(
        problem.contact()[0].friction.as_ref().unwrap().mu,
        FrictionCoefficient::Exponential {
            a: A,
            b: B,
            beta: BETA
        }
    );
    let custom = with_law(
        &problem,
        "exponential_in_rust",
        Arc::new(Exponential::default()),
    )
    .unwrap();
    let built_in = solve(&problem, &settings).unwrap();
    let user = solve(&custom, &settings).unwrap();
    assert!(built_in.report.converged && user.report.converged);
    // Some points slip, so μ really varies with the slip.
    assert!(user.report.certificate.n_slip > 0);
    assert!(rel_max(&user.u, &built_in.u) <= 1e-12);
    let bound = |s: &hemicontact::solver::Solution| -> Vec<f64> {
        s.contact.iter().map(|c| c.bound).collect()
    };
    assert!(rel_max(&bound(&user), &bound(&built_in)) <= 1e-12);
    // Observed: bitwise identical (see the module documentation for why).
    assert!(user
        .u
        .iter()
        .zip(&built_in.u)
        .all(|(a, b)| a.to_bits() == b.to_bits()));
    assert_eq!(user.report.outer.len(), built_in.report.outer.len());
}

#[test]
fn the_law_is_called_once_per_part_per_outer_iteration_with_all_the_parts_points() {
    let (problem, settings) = paper(16);
    let law = Arc::new(Exponential::default());
    let custom = with_law(&problem, "counted", law.clone()).unwrap();
    // Validation sampled the law once per contact part, with the 122 sample slips.
    assert_eq!(law.calls.load(Ordering::SeqCst), 2);
    assert!(law.batches.lock().unwrap().iter().all(|&n| n == 122));
    law.calls.store(0, Ordering::SeqCst);
    law.batches.lock().unwrap().clear();

    let solution = solve(&custom, &settings).unwrap();
    assert!(solution.report.converged);
    let outer = solution.report.outer.len();
    assert!(
        outer > 2,
        "the slip-dependent law needs several outer iterations"
    );
    // Per contact part: the starting displacement, each outer iteration, the certificate.
    let parts = custom.contact().len();
    assert_eq!(law.calls.load(Ordering::SeqCst), parts * (1 + outer + 1));
    // Each call receives all the points of one part: the 2D side of 16 squares has 16
    // nodes above the clamped bottom corner, each one contact point.
    let points = custom.contact_nodes().unwrap();
    for b in 0..parts {
        let n = points.boundary.iter().filter(|&&x| x as usize == b).count();
        assert_eq!(n, 16);
    }
    assert!(law.batches.lock().unwrap().iter().all(|&n| n == 16));
}

/// Solves the paper example with a [`Faulty`] law armed after validation; returns the error
/// and the slip where the law failed.
fn failing_solve(fault: Fault) -> (Error, f64) {
    let (problem, settings) = paper(8);
    let law = Arc::new(Faulty {
        fault,
        armed: AtomicBool::new(false),
        at: Mutex::new(None),
    });
    let custom = with_law(&problem, "my_law", law.clone()).unwrap();
    law.armed.store(true, Ordering::SeqCst);
    let error = solve(&custom, &settings).expect_err("a failing law stops the solve");
    let at = law.at.lock().unwrap().expect("the law failed at a slip");
    (error, at)
}

#[test]
fn a_law_returning_nan_stops_the_solve_naming_the_law_and_the_slip() {
    let (error, r) = failing_solve(Fault::Nan);
    let Error::Law { law, message } = &error else {
        panic!("expected Error::Law, got {error:?}");
    };
    // Points are ordered by contact part: the first part's call fails first.
    assert_eq!(law, "contact[0].friction.mu (my_law)");
    assert!(
        message.contains(&format!("μ(r = {r:e} m) = NaN")),
        "{message}"
    );
    assert!(error.to_string().contains("my_law"));
}

#[test]
fn a_law_returning_a_negative_value_stops_the_solve_naming_the_law_and_the_slip() {
    let (error, r) = failing_solve(Fault::Negative);
    let Error::Law { law, message } = &error else {
        panic!("expected Error::Law, got {error:?}");
    };
    assert_eq!(law, "contact[0].friction.mu (my_law)");
    assert!(
        message.contains(&format!("μ(r = {r:e} m) = -0.25")),
        "{message}"
    );
}

#[test]
fn a_law_returning_an_error_stops_the_solve_with_its_message() {
    let (error, _) = failing_solve(Fault::Error);
    let Error::Law { law, message } = &error else {
        panic!("expected Error::Law, got {error:?}");
    };
    assert_eq!(law, "contact[0].friction.mu (my_law)");
    assert!(message.contains("the table lookup failed"), "{message}");
    // The slips it was called with: all 8 points of the part's side.
    assert!(message.contains("slips of 8 points"), "{message}");
}

/// `μ(r) = 1 − r/8`: negative beyond r = 8 m.
#[derive(Debug)]
struct Falling;

impl SlipFunction for Falling {
    fn evaluate(&self, slips: &[f64], out: &mut [f64]) -> Result<(), String> {
        for (mu, &r) in out.iter_mut().zip(slips) {
            *mu = 1.0 - r / 8.0;
        }
        Ok(())
    }
}

#[test]
fn validation_refuses_a_law_negative_at_a_sampled_slip() {
    let (problem, _) = paper(8);
    let error = with_law(&problem, "falling", Arc::new(Falling)).unwrap_err();
    let Error::Invalid { field, allowed, .. } = &error else {
        panic!("expected Error::Invalid, got {error:?}");
    };
    assert_eq!(field, "contact[0].friction.mu");
    // The samples 10^0.9 ≈ 7.94 m and 10 m straddle r = 8 m: μ(10) = 1 − 10/8 = −0.25.
    assert!(allowed.contains("`falling`"), "{allowed}");
    assert!(allowed.contains("μ(r = 1e1 m) = -0.25"), "{allowed}");
}

#[test]
fn sup_and_lipschitz_of_a_custom_law_are_sample_estimates_and_reported_as_such() {
    let law = FrictionCoefficient::Custom(CustomCoefficient::new(
        "exponential_in_rust",
        Arc::new(Exponential::default()),
    ));
    // sup μ = μ(0) = a, sampled at r = 0 (to the round-off of (a − b) + b).
    assert!((law.sup() - A).abs() <= 1e-15, "sup μ = {}", law.sup());
    // L_μ = (a − b) β = 30 at r = 0; the secant over [0, 1e-10 m] misses it by about
    // β · 5e-11 = 5e-9 relative, plus the round-off of μ(1e-10) − μ(0) ≈ −3e-9, a
    // difference of two values near 0.4 each rounded to a few 5.5e-17: up to about 1e-7
    // relative (observed 1e-7).
    let l = law.lipschitz();
    assert!(
        (l - (A - B) * BETA).abs() <= 1e-6 * (A - B) * BETA,
        "L_μ = {l}"
    );
    assert!(law.is_slip_dependent());

    // The uniqueness check states that μ₀ and L_μ are estimates, for a custom law only.
    let (problem, settings) = paper(8);
    let built_in = hemicontact::solver::uniqueness::check(&problem, &settings).unwrap();
    assert!(built_in.estimated.is_none());
    let custom = with_law(
        &problem,
        "exponential_in_rust",
        Arc::new(Exponential::default()),
    )
    .unwrap();
    let u = hemicontact::solver::uniqueness::check(&custom, &settings).unwrap();
    let note = u.estimated.expect("the estimates are flagged");
    assert!(
        note.contains("estimates") && note.contains("exponential_in_rust"),
        "{note}"
    );
    assert!((u.mu0 - A).abs() <= 1e-15);
}

#[test]
fn the_dimensionless_rewrite_sets_the_units_and_leaves_the_function_untouched() {
    let law: Arc<dyn SlipFunction> = Arc::new(Exponential::default());
    let user = CustomCoefficient::new("exponential_in_rust", law.clone());
    // Slips in units of U = 2⁻¹⁰ m, values in units of 4 (a Tresca bound's traction unit).
    let (u, v) = (2f64.powi(-10), 4.0);
    let scaled = FrictionCoefficient::Custom(user.clone()).nondimensional(u, 1.0, v);
    let FrictionCoefficient::Custom(c) = &scaled else {
        panic!("still a custom law");
    };
    assert!(Arc::ptr_eq(&c.law, &law));
    assert_eq!((c.slip_unit, c.value_unit), (u, v));
    // μ̂(r̂) = μ(r̂ U)/v.
    let r_hat = [0.0, 1.0, 3.5, 100.0];
    let mut mu_hat = [0.0; 4];
    scaled
        .values(&r_hat, &[[0.0; 3]; 4], 2, &mut mu_hat)
        .unwrap();
    for (r, m) in r_hat.iter().zip(mu_hat) {
        let expected = ((A - B) * (-BETA * r * u).exp() + B) / v;
        assert!(
            (m - expected).abs() <= 1e-15 * expected,
            "{m} vs {expected}"
        );
    }
    // Equal only to itself with the same units.
    assert_ne!(scaled, FrictionCoefficient::Custom(user.clone()));
    assert_eq!(
        FrictionCoefficient::Custom(user.clone()),
        FrictionCoefficient::Custom(user)
    );
}
