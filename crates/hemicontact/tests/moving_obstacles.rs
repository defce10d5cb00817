//! Friction against a moving obstacle: the slip is relative to the obstacle.
//!
//! 1. Galilean invariance: an obstacle translated by t gives the same answer as the
//!    problem seen from the obstacle, where every support is moved by −t and the obstacle
//!    is at rest: u = u' + t, with the same contact and friction states and the same
//!    interface forces. Against a plane, and a cylinder moved along its axis, the two
//!    problems are the same to round-off (1e-8 asserted), whatever the direction of t.
//!    Against a circle or a sphere of radius R they are not the same discrete problem: the
//!    small-deformation contact takes each point's gap and normal once, by projection onto
//!    the obstacle where it ends up (the moving obstacle at its final place, which a sliding
//!    indenter needs; the resting one at its own), and the normals at two points t apart
//!    differ by t/R. The two answers then differ by a first-order term in t/R: measured at
//!    t, t/2, t/4, asserted to fall linearly and to stay below t/R relative to u (where
//!    measuring the slip without the obstacle's motion errs by t/|u|, orders of magnitude
//!    more). In 2D and 3D, with exact and regularized friction, Tresca and Coulomb bounds
//!    and a slip-dependent μ.
//! 2. The sliding indenter: a rigid cylinder (2D) or sphere (3D) pressed into a block and
//!    slid along its surface in load steps; wherever every point in contact slips, the
//!    tangential force is μ times the normal force (Coulomb) to 1e-6.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use hemicontact::solver::{FrictionState, Solution};

/// One frame of a block pressed by its top onto an obstacle: the top moved by `top`, the
/// obstacle `obstacle` (a TOML inline table without its displacement) translated by `t`
/// (none if `None`), with the contact laws `laws`.
struct Frame<'a> {
    dim: usize,
    top: [f64; 3],
    obstacle: &'a str,
    t: Option<[f64; 3]>,
    laws: &'a str,
}

fn vector(v: &[f64; 3], d: usize) -> String {
    let parts: Vec<String> = v[..d].iter().map(|x| format!("{x:?}")).collect();
    format!("[{}]", parts.join(", "))
}

impl Frame<'_> {
    fn text(&self) -> String {
        let d = self.dim;
        let (size, n) = if d == 2 {
            ("[2.0, 1.0]", "[16, 8]")
        } else {
            ("[1.0, 1.0, 0.5]", "[6, 6, 3]")
        };
        let displacement = self.t.map_or(String::new(), |t| {
            format!(", displacement = {}", vector(&t, d))
        });
        let obstacle = format!("{}{displacement} }}", self.obstacle.trim_end_matches('}'));
        format!(
            r#"
[mesh]
kind = "{kind}"
size = {size}
n = {n}
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "top"
value = {top}
[[contact]]
part = "bottom"
obstacle = {obstacle}
{laws}
"#,
            kind = if d == 2 { "rectangle" } else { "box" },
            top = vector(&self.top, d),
            laws = self.laws,
        )
    }

    fn solve(&self) -> Solution {
        let s = common::solve_text(&self.text()).unwrap();
        assert!(s.report.converged, "{}", s.report.message);
        s
    }
}

/// The frame comparison of one set-up: the largest differences of u and of the interface
/// forces, relative to the largest of each, and whether the states agree.
struct Comparison {
    u: f64,
    force: f64,
    states_agree: bool,
    n_stick: usize,
    n_slip: usize,
}

/// Solves the problem with the obstacle `obstacle` moved by `t`, and the problem in the
/// obstacle's frame: the obstacle at rest and the top moved back by t; compares u with
/// u' + t.
fn galilean(dim: usize, obstacle: &str, t: [f64; 3], top: [f64; 3], laws: &str) -> Comparison {
    let moving = Frame {
        dim,
        top,
        obstacle,
        t: Some(t),
        laws,
    }
    .solve();
    let resting = Frame {
        dim,
        top: [top[0] - t[0], top[1] - t[1], top[2] - t[2]],
        obstacle,
        t: None,
        laws,
    }
    .solve();
    let scale = moving.u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let diff = moving
        .u
        .iter()
        .zip(&resting.u)
        .enumerate()
        .map(|(k, (a, b))| (a - (b + t[k % dim])).abs())
        .fold(0.0, f64::max);
    let states = |s: &Solution| -> Vec<_> {
        s.contact
            .iter()
            .map(|c| (c.normal_state, c.friction_state))
            .collect()
    };
    let count = |state| {
        moving
            .contact
            .iter()
            .filter(|c| c.friction_state == state)
            .count()
    };
    let force_scale = moving
        .contact
        .iter()
        .flat_map(|c| c.force)
        .fold(0.0f64, |m, f| m.max(f.abs()));
    let force_diff = moving
        .contact
        .iter()
        .zip(&resting.contact)
        .flat_map(|(a, b)| (0..3).map(move |k| (a.force[k] - b.force[k]).abs()))
        .fold(0.0, f64::max);
    let c = Comparison {
        u: diff / scale,
        force: force_diff / force_scale,
        states_agree: states(&moving) == states(&resting),
        n_stick: count(FrictionState::Stick),
        n_slip: count(FrictionState::Slip),
    };
    println!(
        "{dim}D {obstacle}, t = {t:?}, {}: {} stick, {} slip; u differs by {:.1e}, forces by \
         {:.1e}",
        laws.lines()
            .filter(|l| !l.starts_with('['))
            .collect::<Vec<_>>()
            .join(", "),
        c.n_stick,
        c.n_slip,
        c.u,
        c.force
    );
    c
}

/// The same problem in both frames, to round-off.
#[track_caller]
fn same(c: &Comparison) {
    assert!(c.n_slip > 0, "the obstacle's motion must make points slip");
    assert!(c.u <= 1e-8, "{}", c.u);
    assert!(c.force <= 1e-8, "{}", c.force);
    assert!(c.states_agree);
}

/// The two frames of an obstacle of radius `radius` agree to first order in t/R: the
/// differences at t, t/2 and t/4 fall with an observed order of at least 0.8 and stay below
/// |t|/R.
#[track_caller]
fn first_order(dim: usize, obstacle: &str, radius: f64, t: [f64; 3], top: [f64; 3], laws: &str) {
    let runs: Vec<(f64, Comparison)> = [1.0, 0.5, 0.25]
        .iter()
        .map(|&f| {
            let t = t.map(|x| f * x);
            let ratio = t.iter().map(|x| x * x).sum::<f64>().sqrt() / radius;
            (ratio, galilean(dim, obstacle, t, top, laws))
        })
        .collect();
    assert!(
        runs[0].1.n_slip > 0,
        "the obstacle's motion must make points slip"
    );
    for (ratio, c) in &runs {
        assert!(c.u <= *ratio, "{} > t/R = {ratio}", c.u);
    }
    for w in runs.windows(2) {
        let order = (w[0].1.u / w[1].1.u).log2();
        println!("  observed order {order:.2}");
        assert!(order >= 0.8, "order {order}");
    }
}

const PLANE_2D: &str = "{ kind = \"plane\", point = [0.0, 0.0], normal = [0.0, 1.0] }";
const CIRCLE_2D: &str = "{ kind = \"circle\", center = [1.0, -5.0], radius = 5.0 }";
const PLANE_3D: &str = "{ kind = \"plane\", point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }";
const SPHERE_3D: &str = "{ kind = \"sphere\", center = [0.5, 0.5, -3.0], radius = 3.0 }";
const CYLINDER_3D: &str =
    "{ kind = \"cylinder\", point = [0.5, 0.0, -3.0], axis = [0.0, 1.0, 0.0], radius = 3.0 }";
const COULOMB: &str = r#"law = "signorini"
[contact.friction]
bound = "coulomb"
mu = { law = "constant", mu = 0.3 }"#;
const COULOMB_EXACT: &str = r#"law = "signorini"
[contact.friction]
bound = "coulomb"
mu = { law = "constant", mu = 0.3 }
exact = true"#;
const TRESCA: &str = r#"law = "normal-compliance"
c_nu = 1.0e5
[contact.friction]
bound = "tresca"
mu = { law = "constant", mu = 2.0 }"#;
const SLIP_WEAKENING: &str = r#"law = "normal-compliance"
c_nu = 1.0e5
[contact.friction]
bound = "coulomb"
mu = { law = "exponential", a = 0.4, b = 0.1, beta = 100.0 }"#;

const DOWN_2D: [f64; 3] = [0.0, -0.01, 0.0];
const SIDE_2D: [f64; 3] = [0.004, 0.0, 0.0];
const DOWN_3D: [f64; 3] = [0.0, 0.0, -0.01];
const SIDE_3D: [f64; 3] = [0.003, 0.002, 0.0];

#[test]
fn a_plane_moved_in_2d_equals_the_supports_moved_back() {
    for laws in [COULOMB, COULOMB_EXACT, TRESCA, SLIP_WEAKENING] {
        same(&galilean(2, PLANE_2D, SIDE_2D, DOWN_2D, laws));
    }
    // Along and into the plane at once.
    same(&galilean(
        2,
        PLANE_2D,
        [0.004, 0.002, 0.0],
        DOWN_2D,
        COULOMB,
    ));
}

#[test]
fn a_plane_moved_in_3d_equals_the_supports_moved_back() {
    for laws in [COULOMB, COULOMB_EXACT, TRESCA] {
        same(&galilean(3, PLANE_3D, SIDE_3D, DOWN_3D, laws));
    }
    same(&galilean(
        3,
        PLANE_3D,
        [0.003, 0.002, 0.002],
        DOWN_3D,
        SLIP_WEAKENING,
    ));
}

#[test]
fn a_cylinder_moved_along_its_axis_equals_the_supports_moved_back() {
    for laws in [COULOMB, COULOMB_EXACT, TRESCA] {
        same(&galilean(3, CYLINDER_3D, [0.0, 0.003, 0.0], DOWN_3D, laws));
    }
}

#[test]
fn a_circle_moved_in_2d_agrees_with_its_frame_to_first_order_in_t_over_r() {
    for laws in [COULOMB, COULOMB_EXACT, TRESCA, SLIP_WEAKENING] {
        first_order(2, CIRCLE_2D, 5.0, [0.004, 0.0, 0.0], DOWN_2D, laws);
    }
}

#[test]
fn a_sphere_moved_in_3d_agrees_with_its_frame_to_first_order_in_t_over_r() {
    for laws in [COULOMB, COULOMB_EXACT, TRESCA, SLIP_WEAKENING] {
        first_order(3, SPHERE_3D, 3.0, [0.003, 0.002, 0.0], DOWN_3D, laws);
    }
}

/// Solves `text` along its `[loading]` path and checks every step: where every point in
/// contact slips, `Σ_i |R_τ,i| = μ Σ_i |R_i·ν_i|` to 1e-6; returns the number of such steps.
fn sliding_indenter(text: &str, mu: f64) -> usize {
    use hemicontact::scenario::Scenario;
    use std::sync::atomic::AtomicBool;
    let scenario = Scenario::from_str(text, "<test>").unwrap();
    let problem = scenario.into_problem().unwrap();
    let settings = scenario.settings().unwrap();
    let factors = scenario.load_factors().unwrap().expect("a [loading] table");
    let steps = hemicontact::loading::load_path(
        &problem,
        &settings,
        &factors,
        &AtomicBool::new(false),
        &|_, _| {},
        &mut |_| Ok(()),
    )
    .unwrap();
    assert_eq!(steps.len(), factors.len());
    let mut sliding = 0;
    for step in &steps {
        let s = &step.solution;
        assert!(
            s.report.converged,
            "step {}: {}",
            step.step, s.report.message
        );
        let touching: Vec<_> = s
            .contact
            .iter()
            .filter(|c| c.normal_state == hemicontact::solver::NormalState::Contact)
            .collect();
        let tangential: f64 = touching
            .iter()
            .map(|c| c.force_tangential[0].hypot(c.force_tangential[1]))
            .sum();
        let normal: f64 = touching.iter().map(|c| c.force_normal.abs()).sum();
        let all_slip = touching
            .iter()
            .all(|c| c.friction_state == FrictionState::Slip);
        println!(
            "step {} (λ = {}): {} points in contact, all slipping: {all_slip}; Σ|R_τ| / Σ|R_ν| = {:.10}",
            step.step,
            step.factor,
            touching.len(),
            tangential / normal
        );
        if all_slip && touching.len() > 1 {
            sliding += 1;
            assert!(
                (tangential - mu * normal).abs() <= 1e-6 * mu * normal,
                "step {}: {} vs μ = {mu}",
                step.step,
                tangential / normal
            );
        }
    }
    sliding
}

#[test]
fn a_sliding_cylinder_drags_with_mu_times_the_normal_force() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenarios/sliding-indenter.toml"
    ))
    .unwrap();
    assert_eq!(sliding_indenter(&text, 0.3), 5);
}

#[test]
fn a_sliding_sphere_drags_with_mu_times_the_normal_force() {
    let text = r#"
[mesh]
kind = "box"
origin = [-0.5, -0.5, -0.25]
size = [1.0, 1.0, 0.25]
n = [24, 24, 4]
[material]
young = 10.0
poisson = 0.3
[[dirichlet]]
part = "bottom"
[[contact]]
part = "top"
law = "signorini"
obstacle = { kind = "sphere", center = [0.0, 0.0, 0.5], radius = 0.5, displacement = [0.03, 0.01, -0.01] }
[contact.friction]
bound = "coulomb"
mu = { law = "constant", mu = 0.4 }
exact = true
[loading]
steps = 3
"#;
    assert_eq!(sliding_indenter(text, 0.4), 3);
}
