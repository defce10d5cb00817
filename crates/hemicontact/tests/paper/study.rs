//! Convergence studies on small meshes.
//!
//! 1. A smooth problem whose P1 energy-norm error order is known: a square clamped on its
//!    whole boundary under a constant body force has an H² solution (convex domain, one
//!    boundary-condition type), so the energy-norm error is O(edge) — order 1 in the edge
//!    length, 1/2 in the element area h. Levels 8, 16, 32 (n = 4 is pre-asymptotic: order 0.88) against a reference at 128.
//! 2. Nested iteration does not change the results beyond the solver tolerance.
//! 3. A scenario without load (zero reference solution) is refused: nothing to measure.
//!
//! The paper's study against its committed table is the regression test
//! `paper_study_regression.rs`.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::scenario::{builtin, Scenario};
use hemicontact::study::{run, Study, StudySettings};

fn study(text: &str, levels: &[usize], reference: usize, nested: bool) -> Study {
    let scenario = Scenario::from_str(text, "test").unwrap();
    let settings = StudySettings {
        levels: levels.to_vec(),
        reference,
        nested_iteration: nested,
    };
    run(&scenario, "test", &settings, &mut |_| {}).unwrap()
}

#[test]
fn smooth_clamped_square_converges_with_order_one_in_edge_length() {
    let text = r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [4, 4]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "bottom"
[[dirichlet]]
part = "right"
[[dirichlet]]
part = "top"
[[dirichlet]]
part = "left"
[loads]
body_force = [100.0, -50.0]
"#;
    let s = study(text, &[8, 16, 32], 128, true);
    for l in &s.levels[1..] {
        let o = l.order_edge.unwrap();
        eprintln!("n = {}: error {:.4e}, order in edge {o:.3}", l.n, l.error);
        assert!((o - 1.0).abs() < 0.1, "order in edge {o}");
        assert!((l.order_area.unwrap() - 0.5 * o).abs() < 1e-12);
    }
}

#[test]
fn nested_iteration_does_not_change_the_result() {
    let text = builtin::paper(8, 1.0e4);
    let a = study(&text, &[4, 8, 16], 32, true);
    let b = study(&text, &[4, 8, 16], 32, false);
    for (x, y) in a.levels.iter().zip(&b.levels) {
        assert!(
            (x.error - y.error).abs() <= 1e-7 * y.error,
            "n = {}: {} vs {}",
            x.n,
            x.error,
            y.error
        );
    }
}

/// A scenario without load has the zero solution at every level: the relative error
/// `‖u_ref − u^h‖_E / ‖u_ref‖_E` is 0/0, so the study is refused instead of reporting NaN.
#[test]
fn zero_load_has_nothing_to_measure() {
    let text = r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [4, 4]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "bottom"
"#;
    let scenario = Scenario::from_str(text, "zero-load.toml").unwrap();
    let settings = StudySettings {
        levels: vec![2, 4],
        reference: 8,
        nested_iteration: true,
    };
    let e = run(&scenario, "zero load", &settings, &mut |_| {})
        .unwrap_err()
        .to_string();
    for part in ["zero-load.toml", "loads", "nothing to measure"] {
        assert!(e.contains(part), "`{part}` missing from: {e}");
    }
}
