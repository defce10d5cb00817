//! Determinism: the same scenario gives bitwise-identical results run to run, and across
//! assembly thread counts: each parallel task of the assembly writes the entries of its own
//! nodes, adding the cells' terms in the serial loop's order.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::scenario::{builtin, Scenario};
use hemicontact::solver::solve;

fn run(threads: usize) -> hemicontact::solver::Solution {
    // n = 64: 8192 cells, enough for the assembly to run in two chunks.
    let text = builtin::paper(64, 1.0e4) + &format!("\n[solver]\nthreads = {threads}\n");
    let scenario = Scenario::from_str(&text, "test").unwrap();
    let p = scenario.into_problem().unwrap();
    solve(&p, &scenario.settings().unwrap()).unwrap()
}

#[test]
fn bitwise_identical_run_to_run() {
    let a = run(0);
    let b = run(0);
    assert!(a.report.converged);
    assert_eq!(
        a.u.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
        b.u.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
    );
    assert_eq!(a.report.newton.len(), b.report.newton.len());
}

#[test]
fn thread_counts_give_the_same_bits() {
    let a = run(1);
    let b = run(2);
    assert!(a.report.converged && b.report.converged);
    assert_eq!(
        a.u.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
        b.u.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
    );
    assert_eq!(a.report.newton, b.report.newton);
}
