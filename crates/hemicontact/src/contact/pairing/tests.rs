//! Unit tests of the pairing: projections, the edge of the master surface, corners, and
//! the grid search against the scan of every facet.
#![allow(clippy::unwrap_used, clippy::expect_used)]
use super::*;

/// Two unit squares (2D) side by side along y, separated by `gap`, each of two
/// triangles, with the parts `lower_top` (the lower square's top) and `upper_bottom`.
fn two_squares(gap: f64, shift: f64) -> Mesh {
    let coords = vec![
        0.0,
        0.0,
        1.0,
        0.0,
        1.0,
        1.0,
        0.0,
        1.0, // lower
        shift,
        1.0 + gap,
        1.0 + shift,
        1.0 + gap,
        1.0 + shift,
        2.0 + gap,
        shift,
        2.0 + gap,
    ];
    let cells = vec![0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7];
    Mesh::from_parts(
        2,
        coords,
        cells,
        &[
            ("lower_top".into(), vec![2, 3]),
            ("upper_bottom".into(), vec![4, 5]),
        ],
    )
    .unwrap()
}

fn facets_of(m: &Mesh, part: &str) -> Vec<usize> {
    m.part_facets(m.part_index(part).unwrap()).collect()
}

#[test]
fn a_node_above_a_facet_gets_its_gap_normal_and_shape_functions() {
    let m = two_squares(0.1, 0.25);
    let master = facets_of(&m, "lower_top");
    // Slave node 4 at (0.25, 1.1): above the lower square's top, a quarter along it.
    let Pairing::Paired(p) = pair(&m, &master, 4).unwrap() else {
        panic!("separated")
    };
    assert!((p.gap - 0.1).abs() < 1e-14, "gap {}", p.gap);
    assert!((p.normal[1] + 1.0).abs() < 1e-14 && p.normal[0].abs() < 1e-14);
    // Facet nodes (2, 3) at x = 1 and x = 0: N = (0.25, 0.75).
    let n_of = |v: u32| p.shape[p.nodes.iter().position(|&w| w == v).unwrap()];
    assert!((n_of(2) - 0.25).abs() < 1e-14 && (n_of(3) - 0.75).abs() < 1e-14);
}

#[test]
fn a_node_beyond_the_edge_of_the_master_surface_is_separated() {
    let m = two_squares(0.1, 0.25);
    let master = facets_of(&m, "lower_top");
    // Slave node 5 at (1.25, 1.1): beyond the master's right end.
    assert_eq!(pair(&m, &master, 5).unwrap(), Pairing::Separated);
}

#[test]
fn a_penetrating_node_has_a_negative_gap() {
    let m = two_squares(-0.05, 0.5);
    let master = facets_of(&m, "lower_top");
    let Pairing::Paired(p) = pair(&m, &master, 4).unwrap() else {
        panic!("separated")
    };
    assert!((p.gap + 0.05).abs() < 1e-14, "gap {}", p.gap);
}

/// A lower body of `coords`/`cells` with its top facets in the part `master`, and a
/// slave triangle `slave` (its first node the one paired).
fn with_slave(
    mut coords: Vec<f64>,
    mut cells: Vec<u32>,
    master: Vec<u32>,
    slave: [f64; 6],
) -> (Mesh, u32) {
    let first = (coords.len() / 2) as u32;
    coords.extend_from_slice(&slave);
    cells.extend_from_slice(&[first, first + 1, first + 2]);
    let m = Mesh::from_parts(2, coords, cells, &[("master".into(), master)]).unwrap();
    (m, first)
}

#[test]
fn a_node_above_a_convex_corner_is_paired_with_the_corner() {
    // A roof: the triangle (0, 0), (2, 0), (1, 1), its apex a convex corner.
    let (m, node) = with_slave(
        vec![0.0, 0.0, 2.0, 0.0, 1.0, 1.0],
        vec![0, 1, 2],
        vec![1, 2, 2, 0],
        [1.0, 1.5, 1.5, 2.0, 0.5, 2.0],
    );
    let Pairing::Paired(p) = pair(&m, &facets_of(&m, "master"), node).unwrap() else {
        panic!("separated")
    };
    assert!((p.gap - 0.5).abs() < 1e-14, "gap {}", p.gap);
    assert!(p.normal[0].abs() < 1e-14 && (p.normal[1] + 1.0).abs() < 1e-14);
    let at_apex = p.nodes.iter().position(|&v| v == 2).unwrap();
    assert!((p.shape[at_apex] - 1.0).abs() < 1e-14);
}

#[test]
fn a_node_equally_near_two_facets_of_a_notch_is_refused_naming_it() {
    // A pentagon with a V notch at its top, the notch's two facets the master part.
    let (m, node) = with_slave(
        vec![0.0, -1.0, 2.0, -1.0, 2.0, 1.0, 1.0, 0.0, 0.0, 1.0],
        vec![0, 1, 3, 1, 2, 3, 0, 3, 4],
        vec![2, 3, 3, 4],
        [1.0, 0.8, 1.2, 1.5, 0.8, 1.5],
    );
    let e = pair(&m, &facets_of(&m, "master"), node).unwrap_err();
    assert!(
        e.contains(&format!("node {node}")) && e.contains("ambiguous"),
        "{e}"
    );
}

/// The tolerance outside a facet reaches a symmetry plane, not a node beside the
/// master body: a master body whose top facet C–D is tilted by 0.02 over its length 1
/// and whose left side D–A lies on the plane x = 0. A slave node on that plane at
/// (0, 0.1) projects just outside the top facet (by 0.2 % of it), onto the plane of the
/// side, and is paired with D; the same node 1 % of the facet beyond the plane,
/// at (−0.01, 0.1), projects outside by 1.2 %, still within the 5 %, but stands beside
/// the master body: separated.
#[test]
fn the_tolerance_outside_a_facet_reaches_a_symmetry_plane_but_not_a_node_beside_it() {
    let body = vec![0.0, -1.0, 1.0, -1.0, 1.0, 0.0, 0.0, 0.02];
    let cells = vec![0, 1, 2, 0, 2, 3];
    for (x, paired) in [(0.0, true), (-0.01, false)] {
        let (m, node) = with_slave(
            body.clone(),
            cells.clone(),
            vec![2, 3],
            [x, 0.1, x + 0.3, 0.3, x - 0.2, 0.3],
        );
        let out = pair(&m, &facets_of(&m, "master"), node).unwrap();
        match out {
            Pairing::Paired(p) => {
                assert!(paired, "x = {x}: paired {p:?}");
                let at_d = p.nodes.iter().position(|&v| v == 3).unwrap();
                assert!((p.shape[at_d] - 1.0).abs() < 1e-14, "{p:?}");
            }
            Pairing::Separated => assert!(!paired, "x = {x}: separated"),
        }
    }
}

/// One face of a slave corner at a concave corner of the master surface (the slave
/// node at the vertex of a V notch, both notch facets at distance 0 with the same
/// closest point): paired with the notch facet that faces it head-on, whichever of the
/// two facets it faces; the node's whole boundary (no face given) takes the lower facet
/// index.
#[test]
fn a_face_of_a_slave_corner_is_paired_with_the_master_facet_it_faces() {
    let (m, node) = with_slave(
        vec![0.0, -1.0, 2.0, -1.0, 2.0, 1.0, 1.0, 0.0, 0.0, 1.0],
        vec![0, 1, 3, 1, 2, 3, 0, 3, 4],
        vec![2, 3, 3, 4],
        [1.0, 0.0, 1.6, 0.7, 0.4, 0.7],
    );
    let surface = MasterSurface::new(&m, &facets_of(&m, "master"));
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let facet_with = |p: Pairing| match p {
        Pairing::Paired(p) => {
            let mut v = [p.nodes[0], p.nodes[1]];
            v.sort_unstable();
            (v, p.gap)
        }
        Pairing::Separated => panic!("separated"),
    };
    for (facing, expected) in [([h, -h, 0.0], [2, 3]), ([-h, -h, 0.0], [3, 4])] {
        let (v, gap) = facet_with(surface.pair_facing(node, Some(facing)).unwrap());
        assert_eq!(v, expected, "facing {facing:?}");
        assert!(gap.abs() < 1e-15, "{gap}");
    }
    let first = facet_with(surface.pair(node).unwrap()).0;
    assert!(first == [2, 3] || first == [3, 4], "{first:?}");
}

#[test]
fn a_node_above_a_triangle_gets_its_barycentric_shape_functions() {
    // The lower tetrahedron's face z = 0 is the master; the slave tetrahedron's first
    // node is at (0.2, 0.3, 0.1).
    let coords = vec![
        0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -1.0, //
        0.2, 0.3, 0.1, 1.2, 0.3, 0.1, 0.2, 1.3, 0.1, 0.2, 0.3, 1.1,
    ];
    let m = Mesh::from_parts(
        3,
        coords,
        vec![0, 1, 2, 3, 4, 5, 6, 7],
        &[("master".into(), vec![0, 1, 2])],
    )
    .unwrap();
    let Pairing::Paired(p) = pair(&m, &facets_of(&m, "master"), 4).unwrap() else {
        panic!("separated")
    };
    assert!((p.gap - 0.1).abs() < 1e-14, "gap {}", p.gap);
    assert!((p.normal[2] + 1.0).abs() < 1e-14);
    let n_of = |v: u32| p.shape[p.nodes.iter().position(|&w| w == v).unwrap()];
    for (v, exact) in [(0, 0.5), (1, 0.3), (2, 0.2)] {
        assert!(
            (n_of(v) - exact).abs() < 1e-14,
            "N at node {v}: {}",
            n_of(v)
        );
    }
}

/// The grid search decides every slave node as examining every facet does: a curved
/// 3D master surface (a box's top lifted onto a sphere) under a finer, shifted and
/// wider slave surface (some of its nodes beyond the master's edge, some above it far
/// from its facets), each slave node paired through [`MasterSurface::pair`] and through
/// [`decide`] over all facets.
#[test]
fn the_grid_search_pairs_as_the_scan_of_every_facet() {
    use crate::mesh::generate::{cuboid, BoxSpec, CutPattern};
    let block = |origin: [f64; 3], size: [f64; 3], n: usize| {
        cuboid(&BoxSpec {
            origin,
            size,
            n: [n, n, 2],
            pattern: CutPattern::Uniform,
            progression: [1.0; 3],
        })
        .unwrap()
    };
    let lower = block([0.0, 0.0, -0.5], [1.0, 1.0, 0.5], 7);
    let upper = block([-0.2, -0.1, 0.05], [1.5, 1.3, 0.5], 11);
    let offset = lower.n_nodes() as u32;
    let mut coords = lower.coords().to_vec();
    for x in coords.chunks_exact_mut(3) {
        x[2] -= 0.1 * (x[0] * x[0] + x[1] * x[1]) * (1.0 + 2.0 * x[2]);
    }
    coords.extend_from_slice(upper.coords());
    let mut cells = lower.cells().to_vec();
    cells.extend(upper.cells().iter().map(|&v| v + offset));
    let part = |m: &Mesh, name: &str, shift: u32| -> Vec<u32> {
        let p = m.part_index(name).unwrap();
        m.part_facets(p)
            .flat_map(|f| m.facet(f).iter().map(move |&v| v + shift))
            .collect()
    };
    let mesh = Mesh::from_parts(
        3,
        coords,
        cells,
        &[
            ("lower_top".into(), part(&lower, "top", 0)),
            ("upper_bottom".into(), part(&upper, "bottom", offset)),
        ],
    )
    .unwrap();
    let master = facets_of(&mesh, "lower_top");
    let surface = MasterSurface::new(&mesh, &master);
    let slaves = mesh.part_nodes(mesh.part_index("upper_bottom").unwrap());
    let (mut paired, mut separated) = (0, 0);
    for &v in &slaves {
        let mut x = [0.0; 3];
        x.copy_from_slice(mesh.node(v as usize));
        let tol = TOLERANCE * surface.size;
        let all: Vec<Candidate> = (0..master.len())
            .map(|pos| surface.candidate(pos, &x))
            .collect();
        let scan = decide(&mesh, v, &x, &all, tol, None);
        let grid = surface.pair(v);
        assert_eq!(grid, scan, "node {v}");
        match grid {
            Ok(Pairing::Paired(_)) => paired += 1,
            _ => separated += 1,
        }
    }
    // Both outcomes were exercised.
    assert!(
        paired > 50 && separated > 10,
        "{paired} paired, {separated} separated"
    );
}
