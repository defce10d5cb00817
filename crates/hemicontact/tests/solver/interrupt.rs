//! Interrupting a solve: a caller (the Python package on Ctrl-C) raises a stop flag, and
//! the solve returns `Error::Interrupted` instead of a result, within one Newton step.

#![allow(clippy::expect_used)]

use hemicontact::scenario::{builtin, Scenario};
use hemicontact::solver::{solve_interruptible, SolverSettings};
use hemicontact::Error;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

fn paper(n: usize) -> (hemicontact::problem::Problem, SolverSettings) {
    let s = Scenario::from_str(&builtin::paper(n, 1e4), "paper").expect("scenario");
    (
        s.into_problem().expect("problem"),
        s.settings().expect("settings"),
    )
}

/// A flag raised before the solve stops it before the first Newton step.
#[test]
fn raised_flag_interrupts_before_any_step() {
    let (p, settings) = paper(8);
    let stop = AtomicBool::new(true);
    let r = solve_interruptible(&p, &settings, p.prescribed_displacement(), &stop);
    assert!(matches!(r, Err(Error::Interrupted)), "{r:?}");
}

/// A flag raised by another thread during the solve stops it: the paper example at
/// n = 128 (0.5 s in release, 9 outer iterations) is interrupted 20 ms after its start and
/// returns well before a full solve would.
#[test]
fn flag_raised_by_another_thread_interrupts_a_running_solve() {
    let (p, settings) = paper(128);
    let full = {
        let t = Instant::now();
        let never = AtomicBool::new(false);
        let r = solve_interruptible(&p, &settings, p.prescribed_displacement(), &never);
        assert!(r.expect("solve").report.converged);
        t.elapsed()
    };
    let stop = AtomicBool::new(false);
    let (r, took) = std::thread::scope(|scope| {
        scope.spawn(|| {
            std::thread::sleep(Duration::from_millis(20));
            stop.store(true, Ordering::Relaxed);
        });
        let t = Instant::now();
        let r = solve_interruptible(&p, &settings, p.prescribed_displacement(), &stop);
        (r, t.elapsed())
    });
    assert!(matches!(r, Err(Error::Interrupted)), "{r:?}");
    assert!(
        took < full,
        "interrupted after {took:?}, a full solve takes {full:?}"
    );
}
