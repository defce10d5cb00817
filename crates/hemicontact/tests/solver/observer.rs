//! Observing a solve: `solve_observed` hands every outer iteration to an observer (for a
//! progress display) and changes nothing in the solve.
//!
//! - The observer is called once per outer iteration of the report, with the iterations
//!   numbered 0, 1, … in order, the report's change and fixed-point residual of that
//!   iteration, the Newton steps so far (ending at the report's total) and the outer
//!   tolerance of the settings.
//! - The solution is bitwise the one of `solve` without an observer.
//! - The residual shown is the larger of the two relative residuals, the fixed-point
//!   residual alone at the first iteration (where the change is ∞).

#![allow(clippy::expect_used, clippy::unwrap_used)]

use hemicontact::scenario::{builtin, Scenario};
use hemicontact::solver::{solve, solve_observed, OuterProgress};
use std::cell::RefCell;
use std::sync::atomic::AtomicBool;

#[test]
fn observer_sees_every_outer_iteration_and_changes_nothing() {
    let s = Scenario::from_str(&builtin::paper(16, 1e4), "paper").expect("scenario");
    let (p, settings) = (s.into_problem().unwrap(), s.settings().unwrap());
    let seen: RefCell<Vec<OuterProgress>> = RefCell::new(Vec::new());
    let observed = solve_observed(
        &p,
        &settings,
        p.prescribed_displacement(),
        &AtomicBool::new(false),
        &|o| seen.borrow_mut().push(*o),
    )
    .unwrap();
    let plain = solve(&p, &settings).unwrap();
    assert!(observed.report.converged);
    assert_eq!(observed.u, plain.u, "an observer changed the solution");
    assert_eq!(observed.reactions, plain.reactions);
    let seen = seen.into_inner();
    let outer = &observed.report.outer;
    assert!(outer.len() > 1, "the paper example needs outer iterations");
    assert_eq!(seen.len(), outer.len());
    let mut steps = 0;
    for (k, (o, step)) in seen.iter().zip(outer).enumerate() {
        assert_eq!(o.iteration, k);
        assert_eq!(o.change.to_bits(), step.change.to_bits());
        assert_eq!(
            o.fixed_point_residual.to_bits(),
            step.fixed_point_residual.to_bits()
        );
        steps += step.newton_steps;
        assert_eq!(o.newton_steps, steps);
        assert_eq!(o.tolerance, settings.outer.tolerance);
        let expected = if k == 0 {
            o.fixed_point_residual
        } else {
            o.change.max(o.fixed_point_residual)
        };
        assert_eq!(o.residual(), expected);
    }
    assert!(seen[0].change.is_infinite());
    assert_eq!(steps, observed.report.newton.len());
    // The last iteration met the tolerance it reports.
    let last = seen.last().unwrap();
    assert!(last.residual() <= last.tolerance, "{last:?}");
}
