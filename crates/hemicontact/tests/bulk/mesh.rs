//! # Verification: meshes (generated rectangles and validation on construction)
//!
//! What is verified, and why it must hold:
//!
//! - **Generated rectangles tile the domain.** `nx × ny` rectangles cut in two give
//!   `(nx+1)(ny+1)` nodes and `2 nx ny` triangles, all positively oriented, whose areas sum
//!   to `lx · ly`; every cell has area `lx ly / (2 nx ny)`; the sides are parts `bottom`,
//!   `right`, `top`, `left` with `nx`, `ny`, `nx`, `ny` facets whose lengths sum to the side
//!   length and whose normals are the outward unit normals.
//! - **Cut patterns are nested under refinement**, and the symmetric pattern is
//!   mirror-symmetric about the vertical centre line.
//! - **Invalid meshes are rejected with an `Error::Mesh` naming the culprit.** An inverted
//!   (clockwise) triangle, a degenerate (zero-area) triangle, a boundary facet that belongs
//!   to no part, a tagged facet inside the domain, an out-of-range vertex index, and an odd
//!   `nx` with the mirror-symmetric pattern.
//! - **Node adjacency** lists, for every node, exactly the other nodes it shares a cell
//!   with, sorted and once each (against sets built cell by cell), in 2D and 3D.

use hemicontact::geometry::simplex;
use hemicontact::mesh::generate::{rectangle, CutPattern, Rectangle};
use hemicontact::mesh::Mesh;
use hemicontact::Error;

#[test]
fn generated_rectangles_tile_the_domain() {
    let cases = [
        ([0.0, 0.0], [4.0, 4.0], [8, 8], CutPattern::Symmetric),
        ([-1.5, 2.0], [3.0, 0.7], [5, 3], CutPattern::Uniform),
        ([0.25, -0.5], [1.0, 10.0], [2, 17], CutPattern::Symmetric),
        ([0.0, 0.0], [1.0, 1.0], [1, 1], CutPattern::Uniform),
    ];
    for (origin, size, n, pattern) in cases {
        let mesh = rectangle(&Rectangle {
            origin,
            size,
            n,
            pattern,
            progression: [1.0; 2],
        })
        .unwrap();
        let (lx, ly) = (size[0], size[1]);
        assert_eq!(mesh.dim(), 2);
        assert_eq!(mesh.n_nodes(), (n[0] + 1) * (n[1] + 1));
        assert_eq!(mesh.n_cells(), 2 * n[0] * n[1]);
        assert!((mesh.measure() - lx * ly).abs() <= 1e-12 * lx * ly);
        let cell_area = lx * ly / (2 * n[0] * n[1]) as f64;
        for c in 0..mesh.n_cells() {
            let a = simplex::signed_measure(2, &mesh.cell_coords(c));
            assert!(
                (a - cell_area).abs() <= 1e-12 * cell_area,
                "cell {c}: area {a}"
            );
        }
        let (lo, hi) = mesh.bounding_box();
        assert!((lo[0] - origin[0]).abs() < 1e-14 && (lo[1] - origin[1]).abs() < 1e-14);
        assert!((hi[0] - origin[0] - lx).abs() < 1e-12 && (hi[1] - origin[1] - ly).abs() < 1e-12);
        let sides = [
            ("bottom", n[0], lx, [0.0, -1.0]),
            ("right", n[1], ly, [1.0, 0.0]),
            ("top", n[0], lx, [0.0, 1.0]),
            ("left", n[1], ly, [-1.0, 0.0]),
        ];
        assert_eq!(mesh.n_facets(), 2 * (n[0] + n[1]));
        for (name, count, length, normal) in sides {
            let p = mesh.part_index(name).unwrap();
            assert_eq!(mesh.part_facets(p).count(), count, "{name}");
            assert_eq!(mesh.part_nodes(p).len(), count + 1, "{name}");
            let mut total = 0.0;
            for f in mesh.part_facets(p) {
                let (m, nrm) = mesh.facet_measure_normal(f);
                total += m;
                assert!((nrm[0] - normal[0]).abs() < 1e-14 && (nrm[1] - normal[1]).abs() < 1e-14);
            }
            assert!((total - length).abs() < 1e-12, "{name}: length {total}");
        }
    }
}

/// Cut patterns must be nested under refinement, so that coarse P1 fields are
/// exactly representable on finer meshes: every triangle of the `2n × 2n` mesh must lie in
/// one triangle of the `n × n` mesh (all its vertices have barycentric coordinates ≥ 0 in
/// it). Mirror symmetry of the symmetric pattern is checked the same way: the image of
/// every cell under `x ↦ lx − x` is a cell.
#[test]
fn cut_patterns_are_nested_and_symmetric_pattern_is_mirror_symmetric() {
    let bary = |x: &[[f64; 3]; 4], p: &[f64]| {
        let det =
            (x[1][0] - x[0][0]) * (x[2][1] - x[0][1]) - (x[2][0] - x[0][0]) * (x[1][1] - x[0][1]);
        let l1 =
            ((p[0] - x[0][0]) * (x[2][1] - x[0][1]) - (x[2][0] - x[0][0]) * (p[1] - x[0][1])) / det;
        let l2 =
            ((x[1][0] - x[0][0]) * (p[1] - x[0][1]) - (p[0] - x[0][0]) * (x[1][1] - x[0][1])) / det;
        [1.0 - l1 - l2, l1, l2]
    };
    for pattern in [CutPattern::Uniform, CutPattern::Symmetric] {
        let make = |n: usize| {
            rectangle(&Rectangle {
                origin: [0.0, 0.0],
                size: [4.0, 4.0],
                n: [n, n],
                pattern,
                progression: [1.0; 2],
            })
            .unwrap()
        };
        let (coarse, fine) = (make(4), make(8));
        for c in 0..fine.n_cells() {
            let xf = fine.cell_coords(c);
            let inside = (0..coarse.n_cells()).any(|k| {
                let xc = coarse.cell_coords(k);
                (0..3).all(|a| bary(&xc, &xf[a][..2]).iter().all(|&l| l >= -1e-12))
            });
            assert!(
                inside,
                "{pattern:?}: fine cell {c} is not inside a coarse cell"
            );
        }
    }
    let mesh = rectangle(&Rectangle {
        origin: [0.0, 0.0],
        size: [4.0, 2.0],
        n: [6, 3],
        pattern: CutPattern::Symmetric,
        progression: [1.0; 2],
    })
    .unwrap();
    let key = |pts: [[f64; 2]; 3]| {
        let mut k: Vec<(i64, i64)> = pts
            .iter()
            .map(|p| ((p[0] * 1e6).round() as i64, (p[1] * 1e6).round() as i64))
            .collect();
        k.sort_unstable();
        k
    };
    let mut cells: Vec<_> = (0..mesh.n_cells())
        .map(|c| {
            let x = mesh.cell_coords(c);
            key([[x[0][0], x[0][1]], [x[1][0], x[1][1]], [x[2][0], x[2][1]]])
        })
        .collect();
    cells.sort();
    for c in 0..mesh.n_cells() {
        let x = mesh.cell_coords(c);
        let mirrored = key([
            [4.0 - x[0][0], x[0][1]],
            [4.0 - x[1][0], x[1][1]],
            [4.0 - x[2][0], x[2][1]],
        ]);
        assert!(
            cells.binary_search(&mirrored).is_ok(),
            "mirror of cell {c} is not a cell"
        );
    }
}

/// The arrays of `Mesh::try_new`: coordinates, cells, facets, facet parts, part names.
type MeshArrays = (Vec<f64>, Vec<u32>, Vec<u32>, Vec<u16>, Vec<String>);

/// The unit square `(0,0) (1,0) (1,1) (0,1)` cut along the diagonal 0–2, with its four
/// sides tagged.
fn unit_square() -> MeshArrays {
    let coords = vec![0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
    let cells = vec![0, 1, 2, 0, 2, 3];
    let facets = vec![0, 1, 1, 2, 2, 3, 3, 0];
    let parts = vec![0, 1, 2, 3];
    let names = ["bottom", "right", "top", "left"]
        .map(String::from)
        .to_vec();
    (coords, cells, facets, parts, names)
}

#[track_caller]
fn mesh_error(r: hemicontact::Result<Mesh>) -> String {
    match r {
        Err(Error::Mesh(msg)) => msg,
        Err(other) => panic!("expected Error::Mesh, got {other:?}"),
        Ok(_) => panic!("an invalid mesh was accepted"),
    }
}

#[test]
fn the_reference_square_is_valid() {
    let (coords, cells, facets, parts, names) = unit_square();
    let mesh = Mesh::try_new(2, coords, cells, facets, parts, names).unwrap();
    assert!((mesh.measure() - 1.0).abs() < 1e-15);
    assert_eq!(mesh.facet_cell(0), 0);
    assert_eq!(mesh.facet_cell(3), 1);
}

#[test]
fn inverted_triangle_is_rejected() {
    let (coords, _, facets, parts, names) = unit_square();
    // Cell 1 listed clockwise.
    let cells = vec![0, 1, 2, 0, 3, 2];
    let msg = mesh_error(Mesh::try_new(2, coords, cells, facets, parts, names));
    assert!(
        msg.contains("cell 1"),
        "message does not name the cell: {msg}"
    );
    assert!(msg.contains("inverted"), "{msg}");
}

#[test]
fn degenerate_triangle_is_rejected() {
    let (mut coords, _, facets, parts, names) = unit_square();
    // Node 4 = (2, 2) is collinear with nodes 0 and 2: cell 1 = (0, 2, 4) has zero area.
    coords.extend_from_slice(&[2.0, 2.0]);
    let cells = vec![0, 1, 2, 0, 2, 4];
    let msg = mesh_error(Mesh::try_new(2, coords, cells, facets, parts, names));
    assert!(
        msg.contains("cell 1"),
        "message does not name the cell: {msg}"
    );
    assert!(msg.contains("degenerate"), "{msg}");
    // A sliver with area 1e-15 relative to its size is degenerate too.
    let coords = vec![0.0, 0.0, 1.0, 0.0, 0.5, 1e-15];
    let msg = mesh_error(Mesh::try_new(
        2,
        coords,
        vec![0, 1, 2],
        vec![0, 1, 1, 2, 2, 0],
        vec![0, 0, 0],
        vec!["all".into()],
    ));
    assert!(
        msg.contains("cell 0") && msg.contains("degenerate"),
        "{msg}"
    );
}

#[test]
fn boundary_facet_without_part_is_rejected() {
    let (coords, cells, mut facets, mut parts, names) = unit_square();
    // Drop the left side (facet 3–0).
    facets.truncate(6);
    parts.truncate(3);
    let msg = mesh_error(Mesh::try_new(2, coords, cells, facets, parts, names));
    assert!(
        msg.contains("[0, 3]"),
        "message does not name the facet: {msg}"
    );
    assert!(msg.contains("no boundary part"), "{msg}");
}

#[test]
fn tagged_interior_facet_is_rejected() {
    let (coords, cells, mut facets, mut parts, names) = unit_square();
    // The diagonal 0–2 is shared by both cells.
    facets.extend_from_slice(&[0, 2]);
    parts.push(1);
    let msg = mesh_error(Mesh::try_new(2, coords, cells, facets, parts, names));
    assert!(
        msg.contains("[0, 2]"),
        "message does not name the facet: {msg}"
    );
    assert!(msg.contains("not on the boundary"), "{msg}");
}

#[test]
fn out_of_range_vertex_and_bad_dimension_are_rejected() {
    let (coords, _, facets, parts, names) = unit_square();
    let cells = vec![0, 1, 2, 0, 2, 7];
    let msg = mesh_error(Mesh::try_new(
        2,
        coords.clone(),
        cells,
        facets.clone(),
        parts.clone(),
        names.clone(),
    ));
    assert!(msg.contains('7'), "{msg}");
    let msg = mesh_error(Mesh::try_new(4, coords, vec![], facets, parts, names));
    assert!(msg.contains('4'), "{msg}");
}

#[test]
fn symmetric_pattern_needs_even_nx() {
    let r = Rectangle {
        origin: [0.0, 0.0],
        size: [1.0, 1.0],
        n: [5, 4],
        pattern: CutPattern::Symmetric,
        progression: [1.0; 2],
    };
    let msg = mesh_error(rectangle(&r));
    assert!(msg.contains('5') && msg.contains("even"), "{msg}");
}

#[test]
fn node_adjacency_lists_the_nodes_sharing_a_cell_sorted_and_once() {
    use hemicontact::mesh::generate::{cuboid, BoxSpec};
    use std::collections::BTreeSet;
    let meshes = [
        rectangle(&Rectangle {
            origin: [0.0, 0.0],
            size: [2.0, 1.0],
            n: [6, 5],
            pattern: CutPattern::Symmetric,
            progression: [1.0, 1.2],
        })
        .unwrap(),
        cuboid(&BoxSpec {
            origin: [0.0; 3],
            size: [1.0, 2.0, 1.0],
            n: [3, 4, 2],
            pattern: CutPattern::Uniform,
            progression: [1.0; 3],
        })
        .unwrap(),
    ];
    for mesh in meshes {
        let mut sets = vec![BTreeSet::new(); mesh.n_nodes()];
        for c in 0..mesh.n_cells() {
            for &a in mesh.cell(c) {
                for &b in mesh.cell(c) {
                    if a != b {
                        sets[a as usize].insert(b);
                    }
                }
            }
        }
        let (ptr, adj) = mesh.node_adjacency();
        assert_eq!(ptr.len(), mesh.n_nodes() + 1);
        for (v, set) in sets.iter().enumerate() {
            let expected: Vec<u32> = set.iter().copied().collect();
            assert_eq!(adj[ptr[v]..ptr[v + 1]], expected[..], "node {v}");
        }
    }
}
