//! The totals over each contact part (`contact_totals` of `summary.json`) against
//! independent facts: a block pressed by a uniform pressure q onto a frictionless
//! foundation carries, by equilibrium, the total normal force q × (loaded length or area)
//! through its contact face, entirely in contact, with the pressure q everywhere on it; a
//! body that does not reach its foundation carries no contact force.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use hemicontact::io::contact_totals::{contact_totals, ContactTotals};
use hemicontact::io::summary::Summary;
use hemicontact::problem::Problem;
use hemicontact::solver::{solve, SolverSettings};

/// Relative tolerance of the equilibrium checks.
const TOL: f64 = 1e-8;

/// Solves a scenario text and returns its problem, settings and the totals (checked to
/// be certified).
fn totals_of(text: &str) -> (Problem, SolverSettings, Vec<ContactTotals>) {
    let (problem, settings) = common::setup(text);
    let s = solve(&problem, &settings).unwrap();
    common::assert_certified(&s, TOL);
    let t = contact_totals(&problem, &s.contact);
    (problem, settings, t)
}

/// A 2D block `a` × 1 on a `n` × 4 grid, rollers on its sides, pressed by `q` on its
/// top onto a frictionless foundation under its bottom (gap 0) with the law `law`.
fn block_2d(a: f64, n: usize, q: f64, law: &str) -> String {
    format!(
        r#"
[mesh]
kind = "rectangle"
size = [{a:?}, 1.0]
n = [{n}, 4]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "left"
components = ["x"]
[[dirichlet]]
part = "right"
components = ["x"]
[[loads.traction]]
part = "top"
value = [0.0, {mq:?}]
[[contact]]
part = "bottom"
gap = 0.0
{law}
"#,
        mq = -q
    )
}

/// Checks the totals of the pressed block: force q·measure upwards (the outward normal
/// of the bottom is −y, so `Σ R·ν = −q·measure`), no tangential force, every point in
/// contact over the whole face, peak pressure q on the face.
fn assert_pressed(t: &ContactTotals, q: f64, measure: f64, points: usize, d: usize) {
    let load = q * measure;
    assert_eq!(t.part, "bottom");
    assert_eq!(t.points, points);
    assert_eq!(t.n_contact, points, "the whole face is in contact");
    assert_eq!((t.n_stick, t.n_slip), (0, 0), "frictionless");
    assert_eq!(t.force.len(), d);
    assert_eq!(t.force_tangential.len(), d);
    assert!(
        common::rel(t.force[d - 1], load, load) < TOL,
        "vertical force {} vs q × measure = {load}",
        t.force[d - 1]
    );
    assert!(
        common::rel(t.force_normal, -load, load) < TOL,
        "normal force {} vs −{load}",
        t.force_normal
    );
    for k in 0..d - 1 {
        assert!(
            t.force[k].abs() < TOL * load,
            "horizontal force {k}: {}",
            t.force[k]
        );
    }
    for k in 0..d {
        assert!(
            t.force_tangential[k].abs() < TOL * load,
            "tangential force {k}: {}",
            t.force_tangential[k]
        );
    }
    assert!(
        common::rel(t.contact_measure, measure, measure) < 1e-12,
        "contact measure {} vs the face's {measure}",
        t.contact_measure
    );
    assert!(
        common::rel(t.max_pressure, q, q) < TOL,
        "peak pressure {} vs q = {q}",
        t.max_pressure
    );
    let at = t.max_pressure_at.as_ref().expect("a point is in contact");
    assert_eq!(at.len(), d);
    assert_eq!(at[d - 1], 0.0, "the peak is on the bottom face: {at:?}");
    assert!(t.max_pressure_node.is_some());
}

#[test]
fn block_on_a_compliant_foundation_carries_the_pressure_times_the_length() {
    let (a, n, q) = (2.0, 8, 50.0);
    let (_, _, t) = totals_of(&block_2d(a, n, q, "c_nu = 2.0e4"));
    assert_eq!(t.len(), 1);
    assert_pressed(&t[0], q, a, n + 1, 2);
}

#[test]
fn block_on_a_signorini_foundation_carries_the_pressure_times_the_length() {
    let (a, n, q) = (1.5, 6, 80.0);
    let (_, _, t) = totals_of(&block_2d(a, n, q, "law = \"signorini\""));
    assert_eq!(t.len(), 1);
    assert_pressed(&t[0], q, a, n + 1, 2);
}

#[test]
fn box_on_a_compliant_foundation_carries_the_pressure_times_the_area() {
    let (a, b, q) = (2.0, 1.5, 40.0);
    let text = format!(
        r#"
[mesh]
kind = "box"
size = [{a:?}, {b:?}, 1.0]
n = [4, 3, 2]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "left"
components = ["x"]
[[dirichlet]]
part = "right"
components = ["x"]
[[dirichlet]]
part = "front"
components = ["y"]
[[dirichlet]]
part = "back"
components = ["y"]
[[loads.traction]]
part = "top"
value = [0.0, 0.0, {mq:?}]
[[contact]]
part = "bottom"
gap = 0.0
c_nu = 2.0e4
"#,
        mq = -q
    );
    let (_, _, t) = totals_of(&text);
    assert_eq!(t.len(), 1);
    assert_pressed(&t[0], q, a * b, 5 * 4, 3);
}

/// A 1 × 1 block hanging from its top under its weight `f` (N/m³) above a foundation at
/// gap 0.1: uniaxial strain sags its bottom by f/(2(λ+2G)) ≈ 0.004 m, short of the gap.
#[test]
fn a_block_short_of_its_foundation_carries_no_contact_force() {
    let f = 10.0;
    let text = format!(
        r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [4, 4]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "top"
[[dirichlet]]
part = "left"
components = ["x"]
[[dirichlet]]
part = "right"
components = ["x"]
[loads]
body_force = [0.0, {mf:?}]
[[contact]]
part = "bottom"
gap = 0.1
c_nu = 2.0e4
"#,
        mf = -f
    );
    let (_, _, t) = totals_of(&text);
    assert_eq!(t.len(), 1);
    let t = &t[0];
    let weight = f * 1.0;
    assert_eq!(t.points, 5);
    assert_eq!((t.n_contact, t.n_stick, t.n_slip), (0, 0, 0));
    for k in 0..2 {
        assert!(t.force[k].abs() < TOL * weight, "force {:?}", t.force);
        assert!(
            t.force_tangential[k].abs() < TOL * weight,
            "{:?}",
            t.force_tangential
        );
    }
    assert!(t.force_normal.abs() < TOL * weight, "{}", t.force_normal);
    assert_eq!(t.contact_measure, 0.0);
    assert_eq!(t.max_pressure, 0.0);
    assert_eq!(
        (t.max_pressure_node, t.max_pressure_at.as_ref()),
        (None, None)
    );
}

/// The summary carries the totals, one entry per `[[contact]]` boundary in the file's
/// order, under the documented keys.
#[test]
fn summary_json_lists_the_totals_of_each_contact_boundary() {
    let (a, n, q) = (2.0, 4, 50.0);
    let text = block_2d(a, n, q, "c_nu = 2.0e4")
        + r#"
[[contact]]
part = "top"
gap = 0.5
c_nu = 2.0e4
"#;
    let (problem, settings) = common::setup(&text);
    let s = solve(&problem, &settings).unwrap();
    common::assert_certified(&s, TOL);
    let summary = Summary::new(&problem, &settings, &s, None, "<test>");
    let json = serde_json::to_value(&summary).unwrap();
    let parts = json["contact_totals"].as_array().expect("a list");
    assert_eq!(parts.len(), 2);
    assert_eq!(parts[0]["part"], "bottom");
    assert_eq!(parts[1]["part"], "top");
    let keys = [
        "part",
        "points",
        "n_contact",
        "n_stick",
        "n_slip",
        "force",
        "force_normal",
        "force_tangential",
        "contact_measure",
        "max_pressure",
        "max_pressure_node",
        "max_pressure_at",
    ];
    for p in parts {
        let mut found: Vec<&str> = p.as_object().unwrap().keys().map(|k| k.as_str()).collect();
        let mut expected = keys.to_vec();
        found.sort_unstable();
        expected.sort_unstable();
        assert_eq!(found, expected);
    }
    let load = q * a;
    let fy = parts[0]["force"][1].as_f64().unwrap();
    assert!(common::rel(fy, load, load) < TOL, "{fy} vs {load}");
    let measure = parts[0]["contact_measure"].as_f64().unwrap();
    assert!(common::rel(measure, a, a) < 1e-12, "{measure} vs {a}");
    // The top is loaded, not pressed: out of contact, no measure, no peak.
    assert_eq!(parts[1]["n_contact"], 0);
    assert_eq!(parts[1]["contact_measure"].as_f64().unwrap(), 0.0);
    assert!(parts[1]["max_pressure_at"].is_null());
    // The totals' counts add up to the summary's.
    let sum = |key: &str| parts.iter().map(|p| p[key].as_u64().unwrap()).sum::<u64>();
    assert_eq!(sum("points"), json["contact_points"].as_u64().unwrap());
    assert_eq!(sum("n_contact"), json["contact_active"].as_u64().unwrap());
    assert_eq!(sum("n_stick"), json["contact_stick"].as_u64().unwrap());
    assert_eq!(sum("n_slip"), json["contact_slip"].as_u64().unwrap());
}
