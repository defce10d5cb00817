//! How a rigid obstacle sits against its contact part (`contact::placement`), against
//! elementary geometry worked out here:
//!
//! 1. **Facing**: an obstacle on the wrong side of its part is refused, naming
//!    `contact[k].obstacle` and the side the body is on — a plane whose normal points out
//!    of the body (the whole block then lies in the half-space), a paraboloid whose axis
//!    points into the body, a circle inside the body. The same shapes turned the right way
//!    are accepted, and so are a displacement-driven indentation (negative gaps) and a
//!    contact part around a whole round body whose far side faces away from a plane below.
//! 2. **Resolution**: a circle (sphere) smaller than the part's elements poking into the
//!    body between two nodes, every node apart from it, is noted twice: its radius is below
//!    the element size, and it reaches into the body by its radius minus the distance from
//!    its centre to the face (the depth the note states); a large circle crossing the face
//!    between nodes is noted for the penetration only; a circle just apart from the face,
//!    or touching it at a node, raises no penetration note.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::contact::{ContactBoundary, ContactObstacle, NormalLaw, Obstacle, ObstacleSpec};
use hemicontact::material::{Elasticity, Hooke, Material};
use hemicontact::mesh::Mesh;
use hemicontact::problem::{Dirichlet, Problem};
use hemicontact::scenario::Scenario;
use hemicontact::Error;

/// A block `[0, 1] × [0, 0.5]` (8 × 4 squares), its top pushed down by 2 cm, its bottom in
/// Signorini contact with the obstacle `obstacle` (an inline TOML table).
fn block(obstacle: &str) -> String {
    block_with_top(obstacle, "[0.0, -0.02]")
}

/// [`block`] with its top moved by `top` (a TOML array): a body its support carries by
/// that translation, which meets the obstacle where the translation puts it.
fn block_with_top(obstacle: &str, top: &str) -> String {
    format!(
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
value = {top}
[[contact]]
part = "bottom"
law = "signorini"
obstacle = {obstacle}
"#
    )
}

/// The unit cube (2 × 2 × 2 cuboids), its top clamped, its bottom (z = 0) in Signorini
/// contact with `obstacle`.
fn cube(obstacle: &str) -> String {
    format!(
        r#"
[mesh]
kind = "box"
size = [1.0, 1.0, 1.0]
n = [2, 2, 2]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "top"
[[contact]]
part = "bottom"
law = "signorini"
obstacle = {obstacle}
"#
    )
}

/// The notes of a valid scenario.
#[track_caller]
fn notes(text: &str) -> Vec<String> {
    let scenario = Scenario::from_str(text, "block.toml").unwrap();
    match scenario.into_problem_with_notes() {
        Ok((_, notes)) => notes,
        Err(e) => panic!("refused: {e}"),
    }
}

/// The field and message of a refused scenario.
#[track_caller]
fn refused(text: &str) -> (String, String) {
    let scenario = Scenario::from_str(text, "block.toml").unwrap();
    match scenario.into_problem() {
        Err(e @ Error::Scenario { .. }) => {
            let message = e.to_string();
            let Error::Scenario { field, .. } = e else {
                unreachable!()
            };
            (field, message)
        }
        Err(e) => panic!("expected a scenario error, got {e}"),
        Ok(_) => panic!("accepted"),
    }
}

#[test]
fn a_plane_whose_normal_points_out_of_the_body_is_refused() {
    // The plane y = −0.01 with its normal pointing down, away from the block above it: the
    // obstacle is the half-space y > −0.01, which holds the whole block (45 nodes).
    let (field, message) = refused(&block(
        "{ kind = \"plane\", point = [0.0, -0.01], normal = [0.0, -1.0] }",
    ));
    assert_eq!(field, "contact[0].obstacle");
    assert!(
        message.contains("the body lies inside the obstacle (45 of its 45 nodes are)")
            && message.contains("mean ν·n = 1,")
            && message.contains("`normal`"),
        "{message}"
    );
    // Turned the right way, the same plane is accepted.
    notes(&block(
        "{ kind = \"plane\", point = [0.0, -0.01], normal = [0.0, 1.0] }",
    ));
    // So is the plane 1 cm up into the block, pointing into it: a displacement-driven
    // indentation, every gap −0.01.
    notes(&block(
        "{ kind = \"plane\", point = [0.0, 0.01], normal = [0.0, 1.0] }",
    ));
}

#[test]
fn a_paraboloid_whose_axis_points_into_the_body_is_refused() {
    // The indenter below the block has its axis pointing down, away from the body.
    notes(&block(
        "{ kind = \"paraboloid\", apex = [0.5, 0.0], axis = [0.0, -1.0], radius = 0.5 }",
    ));
    let (field, message) = refused(&block(
        "{ kind = \"paraboloid\", apex = [0.5, 0.0], axis = [0.0, 1.0], radius = 0.5 }",
    ));
    assert_eq!(field, "contact[0].obstacle");
    assert!(
        message.contains("wrong side") && message.contains("`axis`"),
        "{message}"
    );
    // Pressed 1 cm into the block, the right way round: accepted (negative gaps).
    notes(&block(
        "{ kind = \"paraboloid\", apex = [0.5, 0.01], axis = [0.0, -1.0], radius = 0.5 }",
    ));
}

#[test]
fn a_circle_inside_the_body_is_refused_and_one_below_it_accepted() {
    // A circle of radius 1 cm centred 5 cm above the bottom, inside the block: at the
    // bottom nodes its outward normal points down, as the part's does.
    let (field, message) = refused(&block(
        "{ kind = \"circle\", center = [0.53, 0.05], radius = 0.01 }",
    ));
    assert_eq!(field, "contact[0].obstacle");
    assert!(
        message.contains("the obstacle lies behind the part, on the body's side of it")
            && message.contains("(0 of the body's 45 nodes are inside the obstacle)"),
        "{message}"
    );
    // The same circle 5 cm below the bottom.
    notes(&block(
        "{ kind = \"circle\", center = [0.53, -0.06], radius = 0.01 }",
    ));
}

/// A disc of radius 1 as a fan of 24 triangles around its centre (node 0), its rim in two
/// parts: `rim` (22 edges, from the top going round through the bottom) and `top` (the 2
/// edges around the top point), with Signorini contact on `rim` against the plane
/// `y = −1 − gap` below it and `top` clamped.
fn disc_on_a_plane(gap: f64) -> Result<Problem, Error> {
    let n = 24;
    let mut coords = vec![0.0, 0.0];
    for k in 0..n {
        // Node k + 1 at angle 90° + 15° k: node 1 is the top point.
        let a = std::f64::consts::FRAC_PI_2 + 2.0 * std::f64::consts::PI * k as f64 / n as f64;
        coords.extend([a.cos(), a.sin()]);
    }
    let rim_node = |k: usize| (k % n + 1) as u32;
    let cells: Vec<u32> = (0..n)
        .flat_map(|k| [0, rim_node(k), rim_node(k + 1)])
        .collect();
    let edge = |k: usize| [rim_node(k), rim_node(k + 1)];
    let top: Vec<u32> = [n - 1, 0].iter().flat_map(|&k| edge(k)).collect();
    let rim: Vec<u32> = (1..n - 1).flat_map(edge).collect();
    let mesh = Mesh::from_parts(
        2,
        coords,
        cells,
        &[("rim".to_string(), rim), ("top".to_string(), top)],
    )?;
    let (rim, top) = (
        mesh.part_index("rim").unwrap(),
        mesh.part_index("top").unwrap(),
    );
    let material = Material::elastic(Elasticity::Hooke(Hooke {
        lambda: 1.0,
        mu: 1.0,
    }));
    let plane = ObstacleSpec {
        shape: Obstacle::Plane {
            point: vec![0.0, -1.0 - gap],
            normal: vec![0.0, 1.0],
        },
        displacement: None,
    };
    Problem::builder(mesh, material)
        .dirichlet(Dirichlet {
            part: top,
            components: [true, true, false],
            value: [0.0; 3],
        })
        .contact(ContactBoundary {
            against: None,
            part: rim,
            gap: 0.0,
            obstacle: Some(ContactObstacle::new(plane)),
            normal: NormalLaw::Signorini,
            friction: None,
        })
        .build()
}

#[test]
fn a_contact_part_around_a_round_body_may_turn_its_far_side_away() {
    // The upper rim nodes face away from the plane (their outward normals point up, as the
    // plane's does), 2 m from it; the nodes nearest to it face it.
    for gap in [0.01, 0.0, -0.005] {
        let problem = disc_on_a_plane(gap).unwrap_or_else(|e| panic!("gap {gap}: {e}"));
        let points = problem.contact_nodes().unwrap();
        let away = (0..points.len())
            .filter(|&i| {
                let x = problem.mesh().node(points.node[i] as usize);
                x[1] > 0.1
            })
            .count();
        assert!(away >= 8, "{away} rim points on the upper half");
    }
}

/// [`block`] held at its top: the obstacle's notes describe it where it stands.
fn held_block(obstacle: &str) -> String {
    block_with_top(obstacle, "[0.0, 0.0]")
}

/// The note of `notes` containing `what`, if any.
fn note<'a>(notes: &'a [String], what: &str) -> Option<&'a String> {
    notes.iter().find(|n| n.contains(what))
}

#[test]
fn a_circle_smaller_than_the_elements_between_two_nodes_is_noted() {
    // Radius 1 mm, centre 0.5 mm below the bottom, midway between the nodes at x = 0.5 and
    // 0.625 (elements 0.125 m wide): the circle reaches R − 0.0005 = 0.5 mm into the block,
    // while the nearest nodes are 62.5 mm from its centre.
    let n = notes(&held_block(
        "{ kind = \"circle\", center = [0.5625, -0.0005], radius = 0.001 }",
    ));
    let size = note(&n, "radius of curvature").unwrap_or_else(|| panic!("{n:?}"));
    assert!(
        size.contains("contact[0] (part `bottom`)")
            && size.contains("R = 0.001 m")
            && size.contains("(0.125 m across"),
        "{size}"
    );
    let between = note(&n, "between the part's nodes").unwrap_or_else(|| panic!("{n:?}"));
    assert!(
        between.contains("reaches 0.0005 m into the body") && between.contains("at [0.5625, 0] m"),
        "{between}"
    );
    // The same circle 1.5 mm below the face: still too small, but apart from the body.
    let n = notes(&held_block(
        "{ kind = \"circle\", center = [0.5625, -0.0025], radius = 0.001 }",
    ));
    assert!(note(&n, "radius of curvature").is_some(), "{n:?}");
    assert!(note(&n, "between the part's nodes").is_none(), "{n:?}");
}

#[test]
fn a_large_circle_crossing_the_face_between_nodes_is_noted() {
    // Radius 0.5, its top 0.1 mm above the bottom face at x = 0.5625, between two nodes:
    // the nodes at x = 0.5 and 0.625 are √(0.0625² + 0.4999²) − 0.5 ≈ 3.8 mm from it.
    let n = notes(&held_block(
        "{ kind = \"circle\", center = [0.5625, -0.4999], radius = 0.5 }",
    ));
    assert!(note(&n, "radius of curvature").is_none(), "{n:?}");
    let between = note(&n, "between the part's nodes").unwrap_or_else(|| panic!("{n:?}"));
    assert!(
        between.contains("reaches 0.0001 m into the body"),
        "{between}"
    );
    // Touching the face at the node x = 0.5: no penetration between nodes.
    let n = notes(&held_block(
        "{ kind = \"circle\", center = [0.5, -0.5], radius = 0.5 }",
    ));
    assert!(note(&n, "between the part's nodes").is_none(), "{n:?}");
    // 0.1 mm apart from the face: no note either.
    let n = notes(&held_block(
        "{ kind = \"circle\", center = [0.5625, -0.5001], radius = 0.5 }",
    ));
    assert!(n.iter().all(|n| !n.contains("obstacle")), "{n:?}");
}

/// The notes describe the body where its support carries it: the large circle 0.1 mm
/// below the bottom face is apart from the held block, but the block whose top is moved
/// down by 0.2 mm meets it 0.1 mm inside, between two nodes (which stay 3.8 mm from it).
#[test]
fn the_notes_describe_the_body_where_its_support_carries_it() {
    let circle = "{ kind = \"circle\", center = [0.5625, -0.5001], radius = 0.5 }";
    let n = notes(&held_block(circle));
    assert!(note(&n, "between the part's nodes").is_none(), "{n:?}");
    let n = notes(&block_with_top(circle, "[0.0, -0.0002]"));
    let between = note(&n, "between the part's nodes").unwrap_or_else(|| panic!("{n:?}"));
    assert!(
        between.contains("reaches 0.0001 m into the body"),
        "{between}"
    );
}

#[test]
fn a_sphere_poking_into_a_triangle_of_the_face_is_noted() {
    // Radius 2 mm, centre 1 mm below the bottom face at (0.3, 0.1), inside one of its
    // triangles (the face's nodes are 0.5 m apart): it reaches 1 mm into the cube.
    let n = notes(&cube(
        "{ kind = \"sphere\", center = [0.3, 0.1, -0.001], radius = 0.002 }",
    ));
    let between = note(&n, "between the part's nodes").unwrap_or_else(|| panic!("{n:?}"));
    assert!(
        between.contains("reaches 0.001 m into the body") && between.contains("at [0.3, 0.1, 0] m"),
        "{between}"
    );
    assert!(note(&n, "radius of curvature").is_some(), "{n:?}");
}
