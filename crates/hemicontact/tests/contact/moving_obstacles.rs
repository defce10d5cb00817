//! Friction against a moving obstacle: the slip is relative to the obstacle.
//!
//! 1. Galilean invariance: an obstacle translated by t gives the same answer as the
//!    problem seen from the obstacle, where every support is moved by −t and the obstacle
//!    is at rest: u = u' + t, with the same contact and friction states and the same
//!    interface forces. The supports' common translation carries the body
//!    (`hemicontact::rigid::carry`) and the contact points meet the obstacle where the
//!    carried body is, by the one relative translation `t − c`: the two frames are the same
//!    discrete problem, whatever t. Asserted to round-off (the forces bit for bit, the
//!    displacements to the round-off of adding t to them) against planes, a cylinder along
//!    its axis, and circles, spheres and paraboloids moved by up to 0.15 of their radius
//!    (where the contact zone has moved by several times its width), in 2D and 3D,
//!    frictionless and with exact and regularized friction, Tresca and Coulomb bounds and a slip-dependent μ,
//!    and along a load path.
//! 2. An obstacle moved far along a plane: 1 cm inside the body, slid by 1 m to 10⁶ m,
//!    every point in contact slips and the forces are the same at every distance (Coulomb
//!    with a constant μ does not see how far), the frames agree, and nothing is infinite; a
//!    translation beyond what double precision resolves against the body's size (10¹⁰ m
//!    for a 2 m block) is refused naming the obstacle's displacement.
//! 3. The sliding indenter: a rigid cylinder (2D) or sphere (3D) pressed into a block and
//!    slid along its surface in load steps; wherever every point in contact slips, the
//!    tangential force is μ times the normal force (Coulomb) to 1e-6.

use crate::common;
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
    same_without_friction(c);
}

/// The same problem in both frames, to round-off, whether or not points slip.
#[track_caller]
fn same_without_friction(c: &Comparison) {
    assert!(c.u <= 1e-12, "{}", c.u);
    assert!(c.force <= 1e-12, "{}", c.force);
    assert!(c.states_agree);
}

/// The two frames of an obstacle of radius `radius` moved by `t` times 0.05, 0.5 and 1
/// agree to round-off, however far the obstacle moves against its radius.
#[track_caller]
fn same_at_any_distance(
    dim: usize,
    obstacle: &str,
    radius: f64,
    t: [f64; 3],
    top: [f64; 3],
    laws: &str,
) {
    for f in [0.05, 0.5, 1.0] {
        let t = t.map(|x| f * x);
        let ratio = t.iter().map(|x| x * x).sum::<f64>().sqrt() / radius;
        println!("  t/R = {ratio:.3}");
        let c = galilean(dim, obstacle, t, top, laws);
        if laws.contains("friction") {
            same(&c);
        } else {
            same_without_friction(&c);
        }
    }
}

const PLANE_2D: &str = "{ kind = \"plane\", point = [0.0, 0.0], normal = [0.0, 1.0] }";
const CIRCLE_2D: &str = "{ kind = \"circle\", center = [1.0, -5.0], radius = 5.0 }";
const PARABOLOID_2D: &str =
    "{ kind = \"paraboloid\", apex = [1.0, 0.0], axis = [0.0, -1.0], radius = 5.0 }";
const PLANE_3D: &str = "{ kind = \"plane\", point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }";
const SPHERE_3D: &str = "{ kind = \"sphere\", center = [0.5, 0.5, -3.0], radius = 3.0 }";
const PARABOLOID_3D: &str =
    "{ kind = \"paraboloid\", apex = [0.5, 0.5, 0.0], axis = [0.0, 0.0, -1.0], radius = 3.0 }";
const CYLINDER_3D: &str =
    "{ kind = \"cylinder\", point = [0.5, 0.0, -3.0], axis = [0.0, 1.0, 0.0], radius = 3.0 }";
const FRICTIONLESS: &str = r#"law = "signorini""#;
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
fn a_circle_or_paraboloid_moved_in_2d_equals_the_supports_moved_back_at_any_t_over_r() {
    for laws in [FRICTIONLESS, COULOMB, COULOMB_EXACT, TRESCA, SLIP_WEAKENING] {
        same_at_any_distance(2, CIRCLE_2D, 5.0, [0.75, 0.0, 0.0], DOWN_2D, laws);
    }
    same_at_any_distance(2, PARABOLOID_2D, 5.0, [0.75, 0.0, 0.0], DOWN_2D, COULOMB);
}

#[test]
fn a_sphere_or_paraboloid_moved_in_3d_equals_the_supports_moved_back_at_any_t_over_r() {
    for laws in [FRICTIONLESS, COULOMB, COULOMB_EXACT, TRESCA, SLIP_WEAKENING] {
        same_at_any_distance(3, SPHERE_3D, 3.0, [0.3, 0.2, 0.0], DOWN_3D, laws);
    }
    same_at_any_distance(
        3,
        PARABOLOID_3D,
        3.0,
        [0.3, 0.2, 0.0],
        DOWN_3D,
        COULOMB_EXACT,
    );
}

/// Along a load path (the obstacle's translation and the supports' values ramped with the
/// load factor, each step warm-started from the last): the two frames agree at every step,
/// to round-off.
#[test]
fn the_frames_agree_along_a_load_path() {
    use hemicontact::scenario::Scenario;
    use std::sync::atomic::AtomicBool;
    let t = [0.6, 0.0, 0.0];
    let path = |frame: Frame| {
        let text = format!("{}\n[loading]\nsteps = 4\n", frame.text());
        let scenario = Scenario::from_str(&text, "<test>").unwrap();
        let problem = scenario.into_problem().unwrap();
        let factors = scenario.load_factors().unwrap().unwrap();
        hemicontact::loading::load_path(
            &problem,
            &scenario.settings().unwrap(),
            &factors,
            &AtomicBool::new(false),
            &|_, _| {},
            &mut |_| Ok(()),
        )
        .unwrap()
    };
    let moving = path(Frame {
        dim: 2,
        top: DOWN_2D,
        obstacle: CIRCLE_2D,
        t: Some(t),
        laws: COULOMB,
    });
    let resting = path(Frame {
        dim: 2,
        top: [-t[0], DOWN_2D[1], 0.0],
        obstacle: CIRCLE_2D,
        t: None,
        laws: COULOMB,
    });
    assert_eq!(moving.len(), 4);
    for (a, b) in moving.iter().zip(&resting) {
        assert!(a.solution.report.converged && b.solution.report.converged);
        let (u, v) = (&a.solution.u, &b.solution.u);
        let scale = u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let shift = a.factor * t[0];
        let du = (0..u.len())
            .map(|k| (u[k] - (v[k] + if k % 2 == 0 { shift } else { 0.0 })).abs())
            .fold(0.0, f64::max);
        let slips = a
            .solution
            .contact
            .iter()
            .filter(|c| c.friction_state == FrictionState::Slip)
            .count();
        let force_scale = a
            .solution
            .contact
            .iter()
            .flat_map(|c| c.force)
            .fold(0.0f64, |m, f| m.max(f.abs()));
        let df = a
            .solution
            .contact
            .iter()
            .zip(&b.solution.contact)
            .flat_map(|(p, q)| (0..3).map(move |k| (p.force[k] - q.force[k]).abs()))
            .fold(0.0, f64::max);
        println!(
            "step {} (t/R = {:.3}): {slips} slipping, u differs by {:.1e}, forces by {:.1e}",
            a.step,
            shift / 5.0,
            du / scale,
            df / force_scale
        );
        // Each step starts from the last, whose displacement beyond the carried
        // translation the two frames hold to round-off, not bit for bit.
        assert!(slips > 0 && du <= 1e-12 * scale && df <= 1e-12 * force_scale);
    }
}

/// An obstacle moved far along itself: a plane 1 cm inside the bottom of a 2 m block held
/// at its top, slid by t along x with exact Coulomb friction (μ = 0.3). Beyond the
/// slip of the stick limit every point slips in the direction of −t, so the contact forces
/// do not depend on t: the same at t = 1, 10³ and 10⁶ m to 1e-12, each equal to its frame
/// with the top moved by −t (the forces bit for bit, the displacements to the round-off of
/// t in them), every number written finite. A translation of 10¹⁰ m, at which double
/// precision places the nodes against the plane only to 2·10⁻⁶ m, is refused.
#[test]
fn an_obstacle_moved_far_along_a_plane_gives_the_same_forces_or_is_refused() {
    let plane = "{ kind = \"plane\", point = [0.0, 0.01], normal = [0.0, 1.0] }";
    let mut reference: Option<Vec<[f64; 3]>> = None;
    for t in [1.0, 1e3, 1e6] {
        let frame = |top: [f64; 3], t: Option<[f64; 3]>| Frame {
            dim: 2,
            top,
            obstacle: plane,
            t,
            laws: COULOMB_EXACT,
        };
        let moving = frame([0.0; 3], Some([t, 0.0, 0.0])).solve();
        let resting = frame([-t, 0.0, 0.0], None).solve();
        let forces: Vec<[f64; 3]> = moving.contact.iter().map(|c| c.force).collect();
        let finite = moving
            .contact
            .iter()
            .all(|c| c.slip.is_finite() && c.u_tau[0].is_finite() && c.pressure.is_finite());
        let all_slip = moving
            .contact
            .iter()
            .filter(|c| c.pressure > 0.0)
            .all(|c| c.friction_state == FrictionState::Slip);
        let scale = forces.iter().flatten().fold(0.0f64, |m, f| m.max(f.abs()));
        let du = moving
            .u
            .iter()
            .zip(&resting.u)
            .enumerate()
            .map(|(k, (a, b))| (a - (b + if k % 2 == 0 { t } else { 0.0 })).abs())
            .fold(0.0, f64::max);
        let same_forces = moving
            .contact
            .iter()
            .zip(&resting.contact)
            .all(|(p, q)| p.force == q.force);
        let moved = reference.as_ref().map_or(0.0, |r| {
            r.iter()
                .zip(&forces)
                .flat_map(|(a, b)| (0..3).map(move |k| (a[k] - b[k]).abs()))
                .fold(0.0, f64::max)
        });
        println!(
            "t = {t:e}: all slipping {all_slip}, forces moved by {:.1e} from t = 1, frames: \
             forces identical {same_forces}, u by {du:.1e} m; finite {finite}",
            moved / scale
        );
        assert!(all_slip && finite && same_forces);
        assert!(moved <= 1e-12 * scale, "{moved:e}");
        assert!(du <= 4.0 * f64::EPSILON * t, "{du:e}");
        reference.get_or_insert(forces);
    }
    let far = Frame {
        dim: 2,
        top: [0.0; 3],
        obstacle: plane,
        t: Some([1e10, 0.0, 0.0]),
        laws: COULOMB_EXACT,
    };
    let e = hemicontact::scenario::Scenario::from_str(&far.text(), "<test>")
        .unwrap()
        .into_problem()
        .unwrap_err()
        .to_string();
    println!("t = 1e10: {e}");
    assert!(
        e.contains("contact[0].obstacle") && e.contains("displacement") && e.contains("size"),
        "{e}"
    );
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
