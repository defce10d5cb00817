//! The small-deformation check of a solution (`small_deformation`), against displacement
//! fields whose strains, displacements and orientations are known in closed form on the
//! unit square, and against a solve whose answer is known from its constraints:
//!
//! - a uniform stretch `u = (e x, 0)` has `ε = e e₁⊗e₁`, `‖ε‖ = e`, and its largest
//!   displacement e at x = 1: below the limits at e = 0.05, both limits exceeded at
//!   e = 0.2 (0.2 > 0.1 and 0.2/√2 > 0.1);
//! - a rigid rotation by θ = 0.3 rad strains only to second order,
//!   `‖ε‖ = √2 (1 − cos θ) ≈ 0.063`, but moves the corner (1, 1) by `2√2 sin(θ/2) ≈ 0.42`,
//!   0.30 of the diagonal: the displacement note alone;
//! - `u = −2x` maps x to −x, a point reflection, which in 2D is a rotation by π: no cell is
//!   inverted; `u = (−2x, 0)` mirrors x and turns every cell inside out, `u = (−0.9x, 0)`
//!   compresses it to a tenth, inverting none;
//! - a block whose bottom must reach a rigid plane 2 m up while its top stays at y = 1
//!   (Signorini: the bottom nodes end at y ≥ 2) is displaced by at least 2 m, 2/√2 of its
//!   size, and inverts cells: its summary has the three notes.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::assembly::BulkAssembler;
use hemicontact::io::summary::Summary;
use hemicontact::material::{Elasticity, Hooke, Material};
use hemicontact::mesh::generate::{rectangle, CutPattern, Rectangle};
use hemicontact::mesh::Mesh;
use hemicontact::scenario::Scenario;
use hemicontact::small_deformation::{SmallDeformation, DISPLACEMENT_LIMIT, STRAIN_LIMIT};
use hemicontact::solver::solve;

fn square() -> Mesh {
    rectangle(&Rectangle {
        origin: [0.0, 0.0],
        size: [1.0, 1.0],
        n: [4, 4],
        pattern: CutPattern::Uniform,
        progression: [1.0; 2],
    })
    .unwrap()
}

/// The check of the displacement `u(x)` interpolated at the nodes of the unit square.
fn check(u: impl Fn(f64, f64) -> [f64; 2]) -> SmallDeformation {
    let mesh = square();
    let values: Vec<f64> = (0..mesh.n_nodes())
        .flat_map(|v| {
            let x = mesh.node(v);
            u(x[0], x[1])
        })
        .collect();
    let material = Material::elastic(Elasticity::Hooke(Hooke {
        lambda: 1.0,
        mu: 1.0,
    }));
    let strains = BulkAssembler::new(&mesh, &material).cell_strains(&values);
    SmallDeformation::of(&mesh, &values, &strains, &[])
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs().max(1.0)
}

#[test]
fn the_limits_are_a_tenth() {
    assert_eq!((STRAIN_LIMIT, DISPLACEMENT_LIMIT), (0.1, 0.1));
}

#[test]
fn a_uniform_stretch_has_its_strain_and_displacement() {
    let small = check(|x, _| [0.05 * x, 0.0]);
    assert!(close(small.max_strain, 0.05), "{small:?}");
    assert!(close(small.max_displacement_ratio, 0.05 / 2f64.sqrt()));
    assert!(small.holds() && small.notes().is_empty(), "{small:?}");
    let large = check(|x, _| [0.2 * x, 0.0]);
    assert!(close(large.max_strain, 0.2));
    assert!(close(large.max_displacement_ratio, 0.2 / 2f64.sqrt()));
    let notes = large.notes();
    assert_eq!(notes.len(), 2, "{notes:?}");
    assert!(notes[0].contains("largest strain ‖ε‖ = 0.2 ") && notes[0].contains("exceeds 0.1"));
    assert!(
        notes[1].contains("largest displacement, 0.2 m"),
        "{}",
        notes[1]
    );
    assert!(!large.holds());
}

#[test]
fn a_rigid_rotation_is_caught_by_its_displacement_alone() {
    let t: f64 = 0.3;
    let (c, s) = (t.cos(), t.sin());
    let r = check(|x, y| [c * x - s * y - x, s * x + c * y - y]);
    assert!(close(r.max_strain, 2f64.sqrt() * (1.0 - c)), "{r:?}");
    let corner = 2.0 * 2f64.sqrt() * (t / 2.0).sin();
    assert!(
        close(r.max_displacement_ratio, corner / 2f64.sqrt()),
        "{r:?}"
    );
    assert_eq!(r.inverted_cells, 0);
    let notes = r.notes();
    assert_eq!(notes.len(), 1, "{notes:?}");
    assert!(notes[0].contains("largest displacement"), "{notes:?}");
}

#[test]
fn cells_turned_inside_out_are_counted() {
    // x ↦ −x is a rotation by π in the plane: orientation kept.
    assert_eq!(check(|x, y| [-2.0 * x, -2.0 * y]).inverted_cells, 0);
    // Mirrored in x: all 32 cells inverted, the first ten named.
    let mirrored = check(|x, _| [-2.0 * x, 0.0]);
    assert_eq!(mirrored.inverted_cells, 32);
    assert_eq!(mirrored.inverted, (0..10).collect::<Vec<_>>());
    let note = mirrored.notes().pop().unwrap();
    assert!(
        note.contains("turns 32 cell(s) inside out (cell 0, cell 1,") && note.contains("22 more"),
        "{note}"
    );
    // Compressed to a tenth: a large strain, no inverted cell.
    let squeezed = check(|x, _| [-0.9 * x, 0.0]);
    assert_eq!(squeezed.inverted_cells, 0);
    assert!(close(squeezed.max_strain, 0.9));
}

#[test]
fn a_block_pushed_through_a_plane_two_metres_up_is_noted() {
    let text = r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [4, 4]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "top"
[[contact]]
part = "bottom"
law = "signorini"
obstacle = { kind = "plane", point = [0.0, 2.0], normal = [0.0, 1.0] }
"#;
    let scenario = Scenario::from_str(text, "deep.toml").unwrap();
    let (problem, settings) = (
        scenario.into_problem().unwrap(),
        scenario.settings().unwrap(),
    );
    let solution = solve(&problem, &settings).unwrap();
    let summary = Summary::new(&problem, &settings, &solution, None, "deep.toml");
    let check = &summary.small_deformation;
    // The bottom nodes end at y ≥ 2 (to the certificate's tolerance): moved by ≥ 2 m.
    assert!(check.max_displacement_ratio >= 2.0 / 2f64.sqrt() * (1.0 - 1e-6));
    assert!(
        check.inverted_cells > 0 && check.max_strain > 1.0,
        "{check:?}"
    );
    assert_eq!(summary.notes, check.notes());
    assert_eq!(summary.notes.len(), 3, "{:?}", summary.notes);
    let json = serde_json::to_value(&summary).unwrap();
    assert_eq!(json["small_deformation"]["strain_limit"], 0.1);
    assert_eq!(json["notes"].as_array().unwrap().len(), 3);
    // A scenario's notes go first.
    let mut with = summary.clone();
    with.prepend_notes(vec!["from the scenario".to_string()]);
    assert_eq!(with.notes[0], "from the scenario");
    assert_eq!(with.notes[1..], summary.notes[..]);
}
