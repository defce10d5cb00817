//! Verification against Hertz's theory of contact, and of rigid obstacles in the solver.
//!
//! The analytic values are computed here from the data of the committed scenarios (read as
//! TOML), never pasted:
//!
//! 1. **2D, `scenarios/hertz2d.toml`**: a rigid cylinder of radius R pressed onto a block
//!    (plane strain, frictionless Signorini) by the force per unit thickness F, known from
//!    equilibrium with the traction on the block's bottom. With `E* = E/(1 − ν²)`:
//!    `a = √(4FR/(πE*))`, `p₀ = 2F/(πa)`. Checked: the contact half-width within one
//!    element size, the peak pressure within 5 %, and the resultant contact force equal
//!    to the applied load (equilibrium).
//! 2. **3D, `scenarios/hertz3d.toml`**, a published set-up: a rigid paraboloid indenting
//!    the unit block by d (quarter model, symmetry planes on rollers): `a = √(Rd)`,
//!    `F = (4/3) E* √R d^{3/2}`, `p₀ = (2/π) E* √(d/R)`, the published values recomputed.
//!    Checked: a within one element size, and the vertical contact force balanced by the
//!    clamped bottom's reaction alone (the rollers of the symmetry planes carry no vertical
//!    force, and their reactions are not counted as contact forces). The force and the peak
//!    pressure are measured, not asserted: this block departs from the half-space (see
//!    `docs/benchmarks.md`).
//! 3. **3D, force-driven, `scenarios/hertz3d-force.toml`**: a block 20 a across pushed
//!    by a known force onto a flat paraboloid (a/R = 0.02), Hertz's half-space:
//!    `a = (3FR/(4E*))^{1/3}`, `p₀ = 3F/(2πa²)`. Checked on a coarser mesh: the contact
//!    force equal to the load, a within one element, p₀ within 5 %.
//! 4. **Obstacles against the flat foundation**: a `plane` obstacle parallel to the
//!    contact part at distance g reproduces the flat foundation `gap = g`, directly or
//!    translated into place by its `displacement`; a plane facing the part at an angle
//!    gives every point the distance to it as gap and its normal.
//! 5. **Load stepping** scales the obstacle's translation: the last step of a path equals
//!    the one-shot solve, and a step at λ sees the translation λ t.
//! 6. **Refusals** naming the field: a node whose closest point is not unique, a
//!    degenerate obstacle, a shape of the wrong dimension, and a gap given with an
//!    obstacle.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::problem::Problem;
use hemicontact::scenario::Scenario;
use hemicontact::solver::{solve, Solution, SolverSettings};
use std::f64::consts::PI;
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A committed scenario: its text parsed as TOML (the data of the analytic values) and
/// the problem and settings it describes.
fn committed(name: &str) -> (toml::Value, Problem, SolverSettings) {
    let path = root().join("scenarios").join(name);
    let text = std::fs::read_to_string(&path).unwrap();
    let value: toml::Value = toml::from_str(&text).unwrap();
    let scenario = Scenario::from_file(&path).unwrap();
    (
        value,
        scenario.into_problem().unwrap(),
        scenario.settings().unwrap(),
    )
}

fn number(v: &toml::Value, path: &[&str]) -> f64 {
    let mut x = v;
    for key in path {
        x = match key.parse::<usize>() {
            Ok(i) => &x[i],
            Err(_) => &x[*key],
        };
    }
    x.as_float()
        .or_else(|| x.as_integer().map(|i| i as f64))
        .unwrap()
}

fn certified(s: &Solution) {
    assert!(s.report.converged, "not converged");
    let failures = s.report.certificate.failures();
    assert!(failures.is_empty(), "certificate failed: {failures:?}");
}

/// The spacing of the contact points' coordinate `k` (sorted, distinct) around `x`: the
/// size of the element edge along the surface that contains `x`.
fn spacing_at(mut coords: Vec<f64>, x: f64) -> f64 {
    coords.sort_by(f64::total_cmp);
    coords.dedup();
    coords
        .windows(2)
        .find(|w| w[0] <= x && x <= w[1])
        .map(|w| w[1] - w[0])
        .unwrap()
}

#[test]
fn hertz_2d_cylinder_half_width_and_peak_pressure() {
    let (v, problem, settings) = committed("hertz2d.toml");
    let (e, nu) = (
        number(&v, &["material", "young"]),
        number(&v, &["material", "poisson"]),
    );
    let radius = number(&v, &["contact", "0", "obstacle", "radius"]);
    let q = number(&v, &["loads", "traction", "0", "value", "1"]);
    let width = number(&v, &["mesh", "size", "0"]);
    // The half model carries half of the force on the cylinder.
    let force = 2.0 * q * width;
    let e_star = e / (1.0 - nu * nu);
    let a = (4.0 * force * radius / (PI * e_star)).sqrt();
    let p0 = 2.0 * force / (PI * a);

    let s = solve(&problem, &settings).unwrap();
    certified(&s);
    let mesh = problem.mesh();
    let x = |c: &hemicontact::solver::certificate::ContactResult| mesh.node(c.node as usize)[0];
    // Equilibrium: the contact force on the block balances the traction q on its bottom.
    let fy: f64 = s.contact.iter().map(|c| c.force[1]).sum();
    assert!((fy + q * width).abs() <= 1e-8 * q * width, "F_y = {fy}");
    // The obstacle's normals lean outwards: the horizontal contact force is balanced by the
    // reaction of the rollers on the symmetry line, and not counted in it.
    let fx: f64 = s.contact.iter().map(|c| c.force[0]).sum();
    let rollers: f64 = (0..mesh.n_nodes())
        .filter(|&n| mesh.node(n)[0] == 0.0)
        .map(|n| s.reactions[2 * n])
        .sum();
    assert!(
        fx > 0.0 && (fx + rollers).abs() <= 1e-8 * fx,
        "{fx} vs {rollers}"
    );
    let in_contact: Vec<_> = s.contact.iter().filter(|c| c.pressure > 0.0).collect();
    let a_fe = in_contact.iter().map(|c| x(c)).fold(0.0, f64::max);
    let h = spacing_at(s.contact.iter().map(x).collect(), a);
    assert!(
        (a_fe - a).abs() <= h,
        "half-width {a_fe} vs Hertz {a}: more than one element ({h}) apart"
    );
    let peak = s
        .contact
        .iter()
        .find(|c| x(c) == 0.0)
        .map(|c| c.pressure)
        .unwrap();
    assert!(
        (peak / p0 - 1.0).abs() <= 0.05,
        "peak pressure {peak} vs Hertz {p0}"
    );
}

#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "a 3D solve of this size takes minutes without optimizations: run with --release"
)]
fn hertz_3d_paraboloid_contact_radius_and_equilibrium() {
    let (v, problem, settings) = committed("hertz3d.toml");
    let (e, nu) = (
        number(&v, &["material", "young"]),
        number(&v, &["material", "poisson"]),
    );
    let obstacle = ["contact", "0", "obstacle"];
    let radius = number(&v, &[obstacle.as_slice(), &["radius"]].concat());
    let depth = -number(&v, &[obstacle.as_slice(), &["displacement", "2"]].concat());
    let e_star = e / (1.0 - nu * nu);
    let a = (radius * depth).sqrt();
    let force = 4.0 / 3.0 * e_star * radius.sqrt() * depth.powf(1.5);
    let p0 = 2.0 / PI * e_star * (depth / radius).sqrt();
    // The published values of this set-up.
    assert!((a - 0.1).abs() < 1e-12 && (force - 0.029304).abs() < 1e-6);
    assert!((p0 - 1.39916).abs() < 1e-5);

    let s = solve(&problem, &settings).unwrap();
    certified(&s);
    let mesh = problem.mesh();
    let fz: f64 = s.contact.iter().map(|c| c.force[2]).sum();
    // Not asserted: the force, 4 |fz|, and the peak pressure exceed Hertz's (by 14 % and
    // 6 % on this mesh) because this block is only 10 a deep with its bottom clamped and
    // a/R = 0.2; scripts/hertz.py measures them and docs/benchmarks.md explains them.
    // The vertical force reaches the clamped bottom: the rollers carry none of it.
    let d = 3;
    let bottom: f64 = (0..mesh.n_nodes())
        .filter(|&n| mesh.node(n)[2] == -1.0)
        .map(|n| s.reactions[d * n + 2])
        .sum();
    assert!(
        (bottom + fz).abs() <= 1e-6 * fz.abs(),
        "bottom reaction {bottom} vs contact force {fz}"
    );
    // Contact radius along the symmetry line y = 0.
    assert_radius_on_axis(mesh, &s, a);
}

/// Asserts that the contact radius of the 3D solution `s` on `mesh` along the symmetry
/// line y = 0 (its outermost point with a positive pressure) is within one element of
/// `a`; returns the pressure at the apex (x = y = 0).
#[track_caller]
fn assert_radius_on_axis(mesh: &hemicontact::mesh::Mesh, s: &Solution, a: f64) -> f64 {
    let at = |c: &hemicontact::solver::certificate::ContactResult| mesh.node(c.node as usize);
    let on_axis: Vec<_> = s.contact.iter().filter(|c| at(c)[1] == 0.0).collect();
    let a_fe = on_axis
        .iter()
        .filter(|c| c.pressure > 0.0)
        .map(|c| at(c)[0])
        .fold(0.0, f64::max);
    let h = spacing_at(on_axis.iter().map(|c| at(c)[0]).collect(), a);
    assert!(
        (a_fe - a).abs() <= h,
        "radius {a_fe} vs Hertz {a}: more than one element ({h}) apart"
    );
    on_axis
        .iter()
        .find(|c| at(c)[0] == 0.0)
        .map(|c| c.pressure)
        .unwrap()
}

/// The force-driven 3D set-up, `scenarios/hertz3d-force.toml`, on its mesh coarsened to
/// 16 cells per side (14 739 DOFs; the committed 32 is in `docs/benchmarks.md`): a block
/// 20 a across pushed by a known force F onto a flat paraboloid (a/R = 0.02), so that
/// Hertz's half-space holds: `a = (3FR/(4E*))^{1/3}`, `p₀ = 3F/(2πa²)`. Checked: the
/// contact force equals the applied load (equilibrium; the block's vertical translation is
/// carried by the contact alone), a within one element, p₀ within 5 %.
#[test]
fn hertz_3d_force_driven_radius_peak_pressure_and_force() {
    let path = root().join("scenarios/hertz3d-force.toml");
    let v: toml::Value = toml::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let (e, nu) = (
        number(&v, &["material", "young"]),
        number(&v, &["material", "poisson"]),
    );
    let radius = number(&v, &["contact", "0", "obstacle", "radius"]);
    let q = number(&v, &["loads", "traction", "0", "value", "2"]);
    let (lx, ly) = (
        number(&v, &["mesh", "size", "0"]),
        number(&v, &["mesh", "size", "1"]),
    );
    let force = 4.0 * q * lx * ly;
    let e_star = e / (1.0 - nu * nu);
    let a = (3.0 * force * radius / (4.0 * e_star)).cbrt();
    let p0 = 3.0 * force / (2.0 * PI * a * a);
    assert!((a - 0.1).abs() < 1e-9, "the scenario's load gives a = {a}");

    let scenario = Scenario::from_file(&path)
        .unwrap()
        .with_resolution(16)
        .unwrap();
    let problem = scenario.into_problem().unwrap();
    let s = solve(&problem, &scenario.settings().unwrap()).unwrap();
    certified(&s);
    let mesh = problem.mesh();
    let fz: f64 = s.contact.iter().map(|c| c.force[2]).sum();
    assert!(
        (4.0 * fz + force).abs() <= 1e-8 * force,
        "contact force {} vs the applied {force}",
        -4.0 * fz
    );
    let peak = assert_radius_on_axis(mesh, &s, a);
    assert!(
        (peak / p0 - 1.0).abs() <= 0.05,
        "peak pressure {peak} vs Hertz {p0}"
    );
}

/// A block `[0, 1] × [0, 0.5]` pressed down onto a foundation under its bottom, with
/// `contact` the text of the contact entry's foundation and `extra` more tables.
fn block(contact: &str, extra: &str) -> (Problem, SolverSettings) {
    let text = format!(
        r#"
[mesh]
kind = "rectangle"
size = [1.0, 0.5]
n = [8, 4]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "top"
value = [0.0, -0.02]
[[contact]]
part = "bottom"
law = "normal-compliance"
c_nu = 5000.0
{contact}
[contact.friction]
bound = "coulomb"
mu = 0.3
{extra}
"#
    );
    let scenario = Scenario::from_str(&text, "<block>").unwrap();
    (
        scenario.into_problem().unwrap(),
        scenario.settings().unwrap(),
    )
}

fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn plane_obstacle_reproduces_the_flat_foundation() {
    let g = 0.004;
    let (flat, settings) = block(&format!("gap = {g}"), "");
    let reference = solve(&flat, &settings).unwrap();
    certified(&reference);
    assert!(reference.report.certificate.n_contact > 0);
    let scale = reference.u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for obstacle in [
        format!(
            "obstacle = {{ kind = \"plane\", point = [0.3, {}], normal = [0.0, 2.0] }}",
            -g
        ),
        // The same plane, translated into place along its normal (a translation along it
        // would drag the block by friction: the slip is relative to the obstacle).
        format!(
            "obstacle = {{ kind = \"plane\", point = [0.0, 0.1], normal = [0.0, 1.0], \
             displacement = [0.0, {}] }}",
            -g - 0.1
        ),
    ] {
        let (problem, settings) = block(&obstacle, "");
        let s = solve(&problem, &settings).unwrap();
        certified(&s);
        // Where the top's support carries the block (down by 0.02), as for the flat
        // foundation: the gap g − 0.02.
        let points = problem.contact_nodes().unwrap();
        let foundation = flat.contact_nodes().unwrap();
        for i in 0..points.len() {
            assert!(
                (points.gap[i] - (g - 0.02)).abs() < 1e-15
                    && (points.gap[i] - foundation.gap[i]).abs() < 1e-15,
                "{obstacle}: gap {}",
                points.gap[i]
            );
            assert_eq!(points.normal[i], [0.0, -1.0, 0.0]);
        }
        assert!(
            max_difference(&s.u, &reference.u) <= 1e-9 * scale,
            "{obstacle}: {}",
            max_difference(&s.u, &reference.u)
        );
        for (c, r) in s.contact.iter().zip(&reference.contact) {
            assert_eq!(
                (c.normal_state, c.friction_state),
                (r.normal_state, r.friction_state)
            );
        }
    }
}

#[test]
fn inclined_plane_gives_each_point_its_distance_and_the_plane_normal() {
    // The plane through (0, −0.01) rising by 0.01 over the block's width.
    let n: [f64; 2] = [-0.01, 1.0];
    let (problem, settings) = block(
        "obstacle = { kind = \"plane\", point = [0.0, -0.01], normal = [-0.01, 1.0] }",
        "",
    );
    let points = problem.contact_nodes().unwrap();
    let len = (n[0] * n[0] + n[1] * n[1]).sqrt();
    for i in 0..points.len() {
        // The distance of the node where the top's support carries it, 0.02 lower.
        let x = problem.mesh().node(points.node[i] as usize);
        let expected = (x[0] * n[0] + (x[1] - 0.02 + 0.01) * n[1]) / len;
        assert!((points.gap[i] - expected).abs() < 1e-15);
        assert!((points.normal[i][0] + n[0] / len).abs() < 1e-15);
        assert!((points.normal[i][1] + n[1] / len).abs() < 1e-15);
        // Friction acts along the plane.
        let t = points.tangent[i][0];
        assert!((t[0] * n[0] + t[1] * n[1]).abs() < 1e-15);
    }
    let s = solve(&problem, &settings).unwrap();
    certified(&s);
    // The interface force of a point has its normal part along the plane's normal.
    for c in s.contact.iter().filter(|c| c.pressure > 0.0) {
        let along = (c.force[0] * n[0] + c.force[1] * n[1]) / len;
        assert!((along + c.force_normal).abs() <= 1e-12 * c.force_normal.abs());
    }
}

#[test]
fn load_steps_scale_the_obstacle_translation() {
    let obstacle = "obstacle = { kind = \"circle\", center = [0.5, -0.5], radius = 0.5, \
                    displacement = [0.0, 0.01] }";
    // Free top: the circle pushes the block up against rollers on its top.
    let text = format!(
        r#"
[mesh]
kind = "rectangle"
size = [1.0, 0.5]
n = [16, 8]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "top"
[[contact]]
part = "bottom"
law = "signorini"
{obstacle}
"#
    );
    let scenario = Scenario::from_str(&text, "<indent>").unwrap();
    let problem = scenario.into_problem().unwrap();
    let settings = scenario.settings().unwrap();
    let one_shot = solve(&problem, &settings).unwrap();
    certified(&one_shot);
    let path = hemicontact::loading::load_path(
        &problem,
        &settings,
        &[0.5, 1.0],
        &std::sync::atomic::AtomicBool::new(false),
        &|_, _| {},
        &mut |_| Ok(()),
    )
    .unwrap();
    let last = &path.last().unwrap().solution;
    let scale = one_shot.u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(max_difference(&last.u, &one_shot.u) <= 1e-9 * scale);
    // At λ = 1/2 the circle is translated by half as much: the same as a problem whose
    // translation is halved.
    let half = Scenario::from_str(&text.replace("0.01]", "0.005]"), "<half>")
        .unwrap()
        .into_problem()
        .unwrap();
    let direct = solve(&half, &settings).unwrap();
    assert_eq!(path[0].factor, 0.5);
    assert!(max_difference(&path[0].solution.u, &direct.u) <= 1e-9 * scale);
    // The centre point is pushed up by the full translation, less nothing: it is in contact.
    let centre = one_shot
        .contact
        .iter()
        .find(|c| problem.mesh().node(c.node as usize)[0] == 0.5)
        .unwrap();
    assert!(centre.pressure > 0.0);
}

fn refusal(contact: &str) -> String {
    let text = format!(
        r#"
[mesh]
kind = "rectangle"
size = [1.0, 0.5]
n = [8, 4]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "top"
[[contact]]
part = "bottom"
law = "signorini"
{contact}
"#
    );
    match Scenario::from_str(&text, "block.toml").and_then(|s| s.into_problem()) {
        Ok(_) => panic!("accepted: {contact}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn bad_obstacles_are_refused_naming_the_field() {
    // The centre of the circle is a node of the contact part (x = 0.5, y = 0).
    let e = refusal("obstacle = { kind = \"circle\", center = [0.5, 0.0], radius = 0.2 }");
    assert!(
        e.contains("contact[0].obstacle") && e.contains("node 4 at [0.5, 0]"),
        "{e}"
    );
    let e = refusal("obstacle = { kind = \"circle\", center = [0.5, -1.0], radius = 0.0 }");
    assert!(e.contains("contact[0].obstacle.radius"), "{e}");
    let e = refusal("obstacle = { kind = \"plane\", point = [0.0, -1.0], normal = [0.0, 0.0] }");
    assert!(e.contains("contact[0].obstacle.normal"), "{e}");
    let e = refusal("obstacle = { kind = \"sphere\", center = [0.5, -1.0], radius = 0.5 }");
    assert!(e.contains("contact[0].obstacle.kind"), "{e}");
    let e = refusal(
        "gap = 0.1\nobstacle = { kind = \"plane\", point = [0.0, -1.0], normal = [0.0, 1.0] }",
    );
    assert!(e.contains("contact[0].gap"), "{e}");
    let e = refusal("obstacle = { kind = \"circle\", centre = [0.5, -1.0], radius = 0.5 }");
    assert!(e.contains("centre"), "{e}");
}
