//! # Verification: a contact part that turns a corner
//!
//! What is verified, and why it must hold:
//!
//! - **The corner node of one part is one contact point per side**, with the normal and
//!   weight of that side's facets: for the unit square cut 4 × 4 whose bottom and right
//!   sides form one part, the corner (1, 0) carries the normal (0, −1) with weight h/2 and
//!   the normal (1, 0) with weight h/2, h = 1/4 (the hat function integrated over each
//!   side's facet); every other node of the part is one point with its side's normal and
//!   weight h (h/2 at the free end (0, 0); the end (1, 1) is on the prescribed top and is
//!   no contact node).
//! - **One part turning a corner gives the answer of two parts**: the same square pressed
//!   down and to the right by its top into the foundations of its bottom and its right
//!   side, once with `bottom` and `right` as two contact parts and once as one part: the
//!   displacements agree to 1e-12 relative, with Signorini contact and with normal
//!   compliance, in 2D and in 3D (a box whose bottom and side x = max form one part).
//! - **Signorini holds at the corner**: with one part, the corner node penetrates neither
//!   foundation beyond the gap, along either side's normal (up to the solver's tolerance,
//!   10⁻⁸ of the gap). Averaging the two normals let it penetrate far beyond the gap.
//! - **A smooth curved boundary stays one point per node**: the half-disc's arc
//!   (`scenarios/half-disc.toml`) has one contact point per contact node, and no note.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use hemicontact::contact::nodes::CORNER_ANGLE_DEG;
use hemicontact::mesh::Mesh;
use hemicontact::problem::Problem;
use hemicontact::scenario::Scenario;
use hemicontact::solver::SolverSettings;
use std::path::Path;

/// `mesh` with the facets of part `from` moved into part `into` (part names unchanged).
fn merge_parts(mesh: &Mesh, into: &str, from: &str) -> Mesh {
    let (a, b) = (
        mesh.part_index(into).unwrap(),
        mesh.part_index(from).unwrap(),
    );
    let facets: Vec<u32> = (0..mesh.n_facets())
        .flat_map(|f| mesh.facet(f).to_vec())
        .collect();
    let parts: Vec<u16> = (0..mesh.n_facets())
        .map(|f| {
            let p = mesh.facet_part(f);
            (if p == b { a } else { p }) as u16
        })
        .collect();
    Mesh::try_new(
        mesh.dim(),
        mesh.coords().to_vec(),
        mesh.cells().to_vec(),
        facets,
        parts,
        mesh.part_names().to_vec(),
    )
    .unwrap()
}

/// The scenario with contact on `bottom` and `right` (two parts), and the same problem with
/// the two sides merged into the one part `bottom`.
fn two_and_one(text: &str) -> (Problem, Problem) {
    let two = common::problem(text);
    let right = two.mesh().part_index("right").unwrap();
    let mut one = two
        .to_builder()
        .mesh(merge_parts(two.mesh(), "bottom", "right"))
        .without_contact();
    for c in two.contact().iter().filter(|c| c.part != right) {
        one = one.contact(c.clone());
    }
    let one = one.build().unwrap();
    assert_eq!((two.contact().len(), one.contact().len()), (2, 1));
    (two, one)
}

fn square(law: &str) -> String {
    format!(
        r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [8, 8]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "top"
value = [0.03, -0.03]
[[contact]]
part = "bottom"
gap = 0.01
{law}
[[contact]]
part = "right"
gap = 0.01
{law}
"#
    )
}

const SIGNORINI: &str = r#"law = "signorini""#;
const COMPLIANCE: &str = r#"law = "normal-compliance"
c_nu = 1.0e4"#;

#[test]
fn corner_node_is_one_point_per_side() {
    let text = square(SIGNORINI).replace("n = [8, 8]", "n = [4, 4]");
    let (_, one) = two_and_one(&text);
    let points = one.contact_nodes().unwrap();
    let h = 0.25;
    let corner = (0..one.mesh().n_nodes())
        .find(|&v| one.mesh().node(v) == [1.0, 0.0])
        .unwrap() as u32;
    let at: Vec<usize> = (0..points.len())
        .filter(|&i| points.node[i] == corner)
        .collect();
    assert_eq!(at.len(), 2, "the corner must be two points");
    let mut normals: Vec<[f64; 3]> = at.iter().map(|&i| points.normal[i]).collect();
    normals.sort_by(|a, b| a[0].total_cmp(&b[0]));
    assert_eq!(normals, [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0]]);
    for &i in &at {
        assert!((points.weight[i] - h / 2.0).abs() < 1e-15);
    }
    // The other nodes: one point each, 4 on the bottom and 3 on the right besides the
    // corner ((1, 1) is on the prescribed top: not a contact node). The free end (0, 0)
    // weighs h/2, the others h: in all the length of the part, 2, less the h/2 of (1, 1).
    assert_eq!(points.len(), 9);
    let total: f64 = points.weight.iter().sum();
    assert!((total - (2.0 - h / 2.0)).abs() < 1e-14, "{total}");
    for i in (0..points.len()).filter(|i| !at.contains(i)) {
        let x = one.mesh().node(points.node[i] as usize);
        let n = points.normal[i];
        let expected = if x[1] == 0.0 {
            [0.0, -1.0, 0.0]
        } else {
            [1.0, 0.0, 0.0]
        };
        assert_eq!(n, expected, "node at {x:?}");
        let w = if x == [0.0, 0.0] { h / 2.0 } else { h };
        assert!((points.weight[i] - w).abs() < 1e-15, "node at {x:?}");
    }
}

#[test]
fn corner_split_is_noted() {
    let (two, one) = two_and_one(&square(SIGNORINI));
    let corner = |notes: Vec<String>| notes.into_iter().filter(|n| n.contains("corner")).count();
    assert_eq!(corner(two.notes()), 0);
    let notes = one.notes();
    assert!(
        notes.iter().any(|n| n.contains("`bottom` turns corners")
            && n.contains(&format!("{CORNER_ANGLE_DEG}°"))
            && n.contains("at 1 node(s): they are 2 contact points")),
        "{notes:?}"
    );
}

/// Largest relative difference of the displacements of two solutions of `two` and `one`.
fn compare(two: &Problem, one: &Problem) -> (Vec<f64>, f64) {
    let a = hemicontact::solver::solve(two, &SolverSettings::default()).unwrap();
    let b = hemicontact::solver::solve(one, &SolverSettings::default()).unwrap();
    assert!(a.report.converged && b.report.converged);
    let scale = a.u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(scale > 0.0);
    let diff =
        a.u.iter()
            .zip(&b.u)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    (b.u, diff / scale)
}

#[test]
fn one_part_turning_a_corner_solves_like_two_parts_2d() {
    for law in [SIGNORINI, COMPLIANCE] {
        let (two, one) = two_and_one(&square(law));
        let (_, rel) = compare(&two, &one);
        assert!(rel <= 1e-12, "{law}: relative difference {rel:e}");
    }
}

#[test]
fn signorini_corner_does_not_penetrate_either_foundation() {
    let (_, one) = two_and_one(&square(SIGNORINI));
    let s = hemicontact::solver::solve(&one, &SolverSettings::default()).unwrap();
    assert!(s.report.converged);
    let corner = (0..one.mesh().n_nodes())
        .find(|&v| one.mesh().node(v) == [1.0, 0.0])
        .unwrap();
    let (ux, uy) = (s.u[2 * corner], s.u[2 * corner + 1]);
    let gap = 0.01;
    // Bottom foundation: normal (0, −1), u_ν = −u_y ≤ g; right: normal (1, 0), u_x ≤ g.
    assert!(
        -uy <= gap * (1.0 + 1e-8),
        "bottom: u_ν = {} > g = {gap}",
        -uy
    );
    assert!(ux <= gap * (1.0 + 1e-8), "right: u_ν = {ux} > g = {gap}");
    // The top is pushed 0.03 into both foundations 0.01 away: the corner touches both.
    assert!(-uy > 0.5 * gap && ux > 0.5 * gap, "({ux}, {uy})");
}

#[test]
fn one_part_turning_a_corner_solves_like_two_parts_3d() {
    for law in [SIGNORINI, COMPLIANCE] {
        let text = format!(
            r#"
[mesh]
kind = "box"
size = [1.0, 1.0, 1.0]
n = [4, 4, 4]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "top"
value = [0.03, 0.0, -0.03]
[[contact]]
part = "bottom"
gap = 0.01
{law}
[[contact]]
part = "right"
gap = 0.01
{law}
"#
        );
        let (two, one) = two_and_one(&text);
        // The edge x = 1, z = 0 is 5 nodes, one on the prescribed top, each two points.
        assert_eq!(
            two.contact_nodes().unwrap().len(),
            one.contact_nodes().unwrap().len()
        );
        let (_, rel) = compare(&two, &one);
        assert!(rel <= 1e-12, "{law}: relative difference {rel:e}");
    }
}

#[test]
fn half_disc_arc_is_one_point_per_node() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/half-disc.toml");
    let (problem, notes) = Scenario::from_file(&path)
        .unwrap()
        .into_problem_with_notes()
        .unwrap();
    assert!(notes.iter().all(|n| !n.contains("corner")), "{notes:?}");
    let points = problem.contact_nodes().unwrap();
    let part = problem.mesh().part_index("contact").unwrap();
    let excluded = problem.fully_prescribed();
    let nodes: Vec<u32> = problem
        .mesh()
        .part_nodes(part)
        .into_iter()
        .filter(|&v| !excluded[v as usize])
        .collect();
    assert!(nodes.len() > 20);
    assert_eq!(points.node, nodes);
}
