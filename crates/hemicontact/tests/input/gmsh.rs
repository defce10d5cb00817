//! # Verification: the Gmsh reader and writer (`mesh::gmsh`)
//!
//! What is verified, and why it must hold:
//!
//! - **Committed Gmsh meshes read into the meshes Gmsh made** (files in `tests/data/gmsh/`,
//!   made by its `generate.py` with Gmsh 4.15): node, cell and facet counts as Gmsh reports
//!   them in the file headers; the parts named by the physical groups; the total measure of
//!   the polygonal domains (the square 16, the cube 1) to round-off, and the facet lengths or
//!   areas of each side; the half-disc's area is that of the polygon inscribed in the arc,
//!   `Σ ½ sin θ_k` over the arc's facets, to round-off, and below π/2 by at most the
//!   inscribed-polygon error `Σ (θ_k − sin θ_k)/2`.
//! - **ASCII and binary files of the same mesh give identical arrays** (cells, facets, parts,
//!   tags) for the square and the cube, and the same coordinates up to the last bit (Gmsh
//!   writes 16 significant digits in ASCII, the exact double in binary).
//! - **Gmsh's numbering is kept or mapped**: the hand-written `tiny.msh` (sparse node tags
//!   10…40, an unused geometry node 99) gives 4 nodes in file order, its cells as written,
//!   the unused node dropped with a note. (Orientation: see `tests/tangled.rs`.)
//! - **Every bad file gives its error**, naming the file and (ASCII) the line or (binary)
//!   the byte offset, and saying what is wrong: format 2.2, quadrangles, second-order
//!   elements, truncation, undefined or duplicate node tags, a degenerate triangle, a
//!   missing section, NaN coordinates, a huge claimed count (failing at once, without
//!   allocating), partitioned meshes, a facet in two groups, z ≠ 0 in 2D, counts that do not
//!   match, binary files with 4-byte size_t, big-endian or truncated data.
//! - **Round trip**: a generated rectangle (8 × 8) and box (3 × 3 × 3) written by
//!   `write_msh` (ASCII and binary) and read back give the same coordinates (bitwise) and
//!   cells, node tags `1..=N` in order, the same parts with the same facets (grouped by
//!   part), and the same solution of the same contact problem to 1e-12.
//! - **Scenarios** with `kind = "gmsh"` resolve the file relative to the scenario, reject
//!   the generator fields, refuse refinement (`with_resolution`), and note contact parts
//!   sharing nodes with Dirichlet parts; `scenarios/half-disc.toml` solves.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::io::msh::{write_msh, MshEncoding};
use hemicontact::mesh::generate::{cuboid, rectangle, BoxSpec, CutPattern, Rectangle};
use hemicontact::mesh::gmsh::{parse_msh, read_msh, GmshMesh, UNTAGGED};
use hemicontact::mesh::Mesh;
use hemicontact::scenario::Scenario;
use hemicontact::solver::SolverSettings;
use hemicontact::Error;
use std::path::{Path, PathBuf};

mod common;

use common::facet_set;

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/gmsh")
        .join(name)
}

fn repo(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(name)
}

fn read(name: &str) -> GmshMesh {
    read_msh(&data(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Sum of the measures of the facets of part `name`.
fn part_measure(mesh: &Mesh, name: &str) -> f64 {
    let p = mesh
        .part_index(name)
        .unwrap_or_else(|| panic!("no part {name}"));
    mesh.part_facets(p)
        .map(|f| mesh.facet_measure_normal(f).0)
        .sum()
}

/// Same nodes (coordinates within `tol`, relative to 1), same cells in the same order,
/// same parts with the same facets.
#[track_caller]
fn assert_same_mesh(a: &Mesh, b: &Mesh, tol: f64) {
    assert_eq!(a.dim(), b.dim());
    assert_eq!(a.n_nodes(), b.n_nodes());
    if tol == 0.0 {
        assert_eq!(a.coords(), b.coords());
    }
    for (x, y) in a.coords().iter().zip(b.coords()) {
        assert!((x - y).abs() <= tol * x.abs().max(1.0), "{x} vs {y}");
    }
    assert_eq!(a.cells(), b.cells());
    assert_eq!(a.part_names(), b.part_names());
    assert_eq!(facet_set(a), facet_set(b));
}

#[test]
fn square_reads_with_its_parts_and_area() {
    let g = read("square.msh");
    let m = &g.mesh;
    assert_eq!(m.dim(), 2);
    // The header says 30 nodes, all used by the triangles.
    assert_eq!(m.n_nodes(), 30);
    assert_eq!(g.node_tags, (1..=30).collect::<Vec<u64>>());
    assert_eq!(m.part_names(), ["bottom", "right", "top", "left"]);
    assert!((m.measure() - 16.0).abs() < 1e-12, "{}", m.measure());
    for side in ["bottom", "right", "top", "left"] {
        assert!((part_measure(m, side) - 4.0).abs() < 1e-12, "{side}");
    }
    // Euler: a triangulated disc has V − E + F = 1, with 3F = 2E − B.
    let b = m.n_facets();
    let e = (3 * m.n_cells() + b) / 2;
    assert_eq!(m.n_nodes() + m.n_cells(), e + 1);
    assert_eq!(g.region_names, ["domain"]);
    assert!(g.cell_region.iter().all(|&r| r == 0));
    assert_eq!(g.cell_region.len(), m.n_cells());
    assert_eq!(g.element_tags.len(), m.n_cells());
    assert!(g.notes.is_empty(), "{:?}", g.notes);
}

#[test]
fn cube_reads_with_its_parts_and_volume() {
    let g = read("cube.msh");
    let m = &g.mesh;
    assert_eq!(m.dim(), 3);
    assert_eq!(m.n_nodes(), 45);
    assert_eq!(
        m.part_names(),
        ["left", "right", "front", "back", "bottom", "top"]
    );
    assert!((m.measure() - 1.0).abs() < 1e-12, "{}", m.measure());
    for side in ["left", "right", "front", "back", "bottom", "top"] {
        assert!((part_measure(m, side) - 1.0).abs() < 1e-12, "{side}");
    }
    // Outward normals of the faces.
    let p = m.part_index("top").unwrap();
    for f in m.part_facets(p) {
        let n = m.facet_measure_normal(f).1;
        assert!((n[2] - 1.0).abs() < 1e-12, "{n:?}");
    }
    // The header's 184 elements are the 6 faces' triangles and the tetrahedra.
    assert_eq!(m.n_cells() + m.n_facets(), 184);
    assert_eq!(g.region_names, ["body"]);
}

#[test]
fn ascii_and_binary_files_give_identical_meshes() {
    for (ascii, binary) in [
        ("square.msh", "square-binary.msh"),
        ("cube.msh", "cube-binary.msh"),
    ] {
        let a = read(ascii);
        let b = read(binary);
        // Gmsh writes 16 significant digits in ASCII (`%.16g`): the last bit may differ.
        assert_same_mesh(&a.mesh, &b.mesh, 1e-15);
        let facets = |m: &Mesh| {
            (0..m.n_facets())
                .map(|f| m.facet(f).to_vec())
                .collect::<Vec<_>>()
        };
        assert_eq!(facets(&a.mesh), facets(&b.mesh));
        assert_eq!(a.node_tags, b.node_tags);
        assert_eq!(a.element_tags, b.element_tags);
        assert_eq!(a.cell_region, b.cell_region);
        assert_eq!(a.region_names, b.region_names);
    }
}

#[test]
fn half_disc_area_is_the_inscribed_polygon() {
    let g = read_msh(&repo("scenarios/meshes/half-disc.msh")).unwrap();
    let m = &g.mesh;
    assert_eq!(m.part_names(), ["contact", "top"]);
    assert!((part_measure(m, "top") - 2.0).abs() < 1e-12);
    // The arc's nodes are on the circle: the domain is the polygon inscribed in the arc,
    // a fan of triangles (centre, facet) of area ½ sin θ each.
    let centre = [0.0, 1.0];
    let p = m.part_index("contact").unwrap();
    let (mut polygon, mut error) = (0.0, 0.0);
    for f in m.part_facets(p) {
        let v = m.facet(f);
        let (a, b) = (m.node(v[0] as usize), m.node(v[1] as usize));
        let ra = [a[0] - centre[0], a[1] - centre[1]];
        let rb = [b[0] - centre[0], b[1] - centre[1]];
        assert!(
            ((ra[0].hypot(ra[1])) - 1.0).abs() < 1e-12,
            "{a:?} not on the arc"
        );
        let sin = (ra[0] * rb[1] - ra[1] * rb[0]).abs();
        let theta = (ra[0] * rb[0] + ra[1] * rb[1]).acos();
        polygon += 0.5 * sin;
        error += 0.5 * (theta - sin);
    }
    let area = m.measure();
    let half_pi = std::f64::consts::FRAC_PI_2;
    assert!((area - polygon).abs() < 1e-12, "{area} vs {polygon}");
    assert!(area < half_pi && half_pi - area <= error * (1.0 + 1e-9) + 1e-15);
    // The chord error of 0.05-long facets: θ³/12 per facet, about 1e-5 · π / 0.05 in all.
    assert!(half_pi - area < 1e-3, "{}", half_pi - area);
}

#[test]
fn tiny_file_keeps_file_order() {
    let g = read("tiny.msh");
    let m = &g.mesh;
    // Node 99 (a geometry point) is used by no triangle: dropped, with a note.
    assert_eq!(g.node_tags, [10, 20, 30, 40]);
    assert_eq!(m.coords(), [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0]);
    // Elements 5 and 6 are [10, 20, 30] and [10, 30, 40], counterclockwise: kept as they are.
    assert_eq!(m.cells(), [0, 1, 2, 0, 2, 3]);
    assert_eq!(g.element_tags, [5, 6]);
    assert_eq!(m.part_names(), ["bottom", "right", "top", "left"]);
    assert!((m.measure() - 1.0).abs() < 1e-15);
    assert!(
        g.notes.iter().any(|n| n.contains("1 nodes not used")),
        "{:?}",
        g.notes
    );
}

#[test]
fn untagged_boundary_facets_form_their_own_part() {
    // The left side's curve loses its physical group: its facet goes to `untagged`.
    let text = std::fs::read_to_string(data("tiny.msh"))
        .unwrap()
        .replace("4 0 0 0 0 1 0 1 4 0", "4 0 0 0 0 1 0 0 0");
    let g = parse_msh(text.as_bytes(), "tiny-untagged.msh").unwrap();
    assert_eq!(g.mesh.part_names(), ["bottom", "right", "top", UNTAGGED]);
    assert_eq!(g.mesh.part_nodes(3), [0, 3]);
    assert!(
        g.notes.iter().any(|n| n.contains("`untagged`")),
        "{:?}",
        g.notes
    );
}

#[test]
fn unnamed_groups_are_named_by_tag_and_regions_are_recorded() {
    // Without $PhysicalNames the parts are "1" … "4"; a second surface group makes two
    // cell regions (the triangles are in different surfaces).
    let text = std::fs::read_to_string(data("tiny.msh")).unwrap();
    let start = text.find("$PhysicalNames").unwrap();
    let end = text.find("$Entities").unwrap();
    let mut text = format!("{}{}", &text[..start], &text[end..]);
    text = text
        .replace("1 4 1 0\n", "1 4 2 0\n")
        .replace(
            "1 0 0 0 1 1 0 1 5 0\n",
            "1 0 0 0 1 1 0 1 5 0\n2 0 0 0 1 1 0 1 7 0\n",
        )
        .replace("5 6 1 6", "6 6 1 6")
        .replace(
            "2 1 2 2\n5 10 20 30\n6 10 30 40\n",
            "2 1 2 1\n5 10 20 30\n2 2 2 1\n6 10 30 40\n",
        );
    let g = parse_msh(text.as_bytes(), "tiny-unnamed.msh").unwrap();
    assert_eq!(g.mesh.part_names(), ["1", "2", "3", "4"]);
    assert_eq!(g.region_names, ["5", "7"]);
    assert_eq!(g.cell_region, [0, 1]);
    assert!(
        g.notes
            .iter()
            .any(|n| n.contains("a single `[material]` applies")),
        "{:?}",
        g.notes
    );
    // The mesh carries the regions, to which a scenario gives one material each.
    assert_eq!(g.mesh.region_names(), ["5", "7"]);
    assert_eq!((g.mesh.cell_region(0), g.mesh.cell_region(1)), (0, 1));
    let toml = r#"
[[material]]
part = "7"
young = 100.0
poisson = 0.3
[[material]]
part = "5"
young = 300.0
poisson = 0.3
[[dirichlet]]
part = "1"
"#;
    let mut s = hemicontact::scenario::Scenario::from_str(toml, "tiny.toml").unwrap();
    s.given_mesh = Some(g.mesh.clone());
    let p = s.into_problem().unwrap();
    assert_eq!(p.region_material(), [1, 0]);
    assert_eq!((p.cell_material(0), p.cell_material(1)), (1, 0));
}

#[test]
fn interior_facets_of_a_group_are_ignored_with_a_note() {
    // The diagonal 10–30 shared by both triangles, in the physical group of `top`.
    let text = std::fs::read_to_string(data("tiny.msh"))
        .unwrap()
        .replace("5 6 1 6", "5 7 1 7")
        .replace("1 3 1 1\n3 30 40\n", "1 3 1 2\n3 30 40\n7 10 30\n");
    let g = parse_msh(text.as_bytes(), "tiny-diagonal.msh").unwrap();
    assert_eq!(g.mesh.n_facets(), 4);
    assert!(
        g.notes
            .iter()
            .any(|n| n.contains("`top`: 1 facets lie inside")),
        "{:?}",
        g.notes
    );
}

/// The error of reading `name`, with the checks every error must pass: an
/// `Error::MeshFile` whose message names the file.
#[track_caller]
fn error_of(name: &str) -> String {
    let path = data(name);
    match read_msh(&path) {
        Ok(_) => panic!("{name}: read without error"),
        Err(e @ Error::MeshFile { .. }) => {
            let text = e.to_string();
            assert!(text.contains(name), "{name}: the file is not named: {text}");
            text
        }
        Err(e) => panic!("{name}: not a MeshFile error: {e:?}"),
    }
}

#[test]
fn bad_files_give_errors_that_say_what_is_wrong() {
    let cases: &[(&str, &[&str])] = &[
        (
            "bad-format-2.2.msh",
            &[
                ":2:",
                "format 2.2 is not supported",
                "export as 4.1 (gmsh -format msh41",
            ],
        ),
        (
            "bad-quadrangle.msh",
            &[
                ":46:",
                "element type 3 (Quadrilateral 4)",
                "only P1 simplices",
                "Mesh.ElementOrder = 1 and Mesh.RecombineAll = 0",
            ],
        ),
        (
            "bad-second-order.msh",
            &[
                "element type 8 (Line 3)",
                "only P1 simplices",
                "Mesh.ElementOrder = 1",
            ],
        ),
        (
            "bad-truncated.msh",
            &[
                ":48:",
                "unexpected end of file while reading `$EndElements`",
                "truncated",
            ],
        ),
        (
            "bad-truncated-nodes.msh",
            &[":26:", "claims 4 nodes in a block", "truncated or corrupt"],
        ),
        (
            "bad-unknown-node.msh",
            &[":48:", "element 6 refers to node tag 77", "does not define"],
        ),
        (
            "bad-degenerate.msh",
            &["element 6 (nodes [10, 40, 30]) is degenerate", "area"],
        ),
        ("bad-no-elements.msh", &["missing `$Elements` section"]),
        (
            "bad-duplicate-node.msh",
            &[":30:", "node tag 30 is defined twice"],
        ),
        (
            "bad-coincident-nodes.msh",
            &[
                "nodes 30 and 50 of one body are at the same point",
                "not merged",
            ],
        ),
        (
            "bad-nan.msh",
            &[":33:", "node tag 30 has a non-finite coordinate (NaN)"],
        ),
        (
            "bad-huge-count.msh",
            &[
                ":5:",
                "claims 1000000000000000000 nodes",
                "truncated or corrupt",
            ],
        ),
        (
            "bad-partitioned.msh",
            &[":21:", "partitioned meshes are not supported"],
        ),
        (
            "bad-two-groups.msh",
            &[
                "boundary facet with nodes [40, 10] (element 4)",
                "is in physical groups `left` and `bottom`",
                "a facet may belong to one boundary part",
            ],
        ),
        (
            "bad-z.msh",
            &["node tag 30 of triangle 5 has z = 0.5", "plane z = 0"],
        ),
        (
            "bad-count-mismatch.msh",
            &["header announces 6 nodes, its blocks hold 5"],
        ),
        (
            "bad-data-size-4.msh",
            &[":2:", "data size 4", "8-byte size_t"],
        ),
        ("bad-big-endian.msh", &["(byte 20)", "big-endian"]),
        (
            "bad-binary-truncated.msh",
            &["(byte 773)", "claims 30 nodes", "truncated or corrupt"],
        ),
    ];
    for (name, expected) in cases {
        let text = error_of(name);
        for e in *expected {
            assert!(text.contains(e), "{name}: `{e}` missing from: {text}");
        }
    }
}

/// A 50-byte file claiming 10¹⁸ nodes fails at once, without allocating for them.
#[test]
fn huge_counts_fail_fast() {
    for header in [
        "$Nodes\n1 1000000000000000000 1 1\n",
        "$Nodes\n18446744073709551615 1 1 1\n",
        "$Elements\n1 18446744073709551615 1 1\n",
        "$Entities\n18446744073709551615 0 0 0\n",
        "$PhysicalNames\n1000000000000\n",
    ] {
        let text = format!("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n{header}");
        let start = std::time::Instant::now();
        let e = parse_msh(text.as_bytes(), "huge.msh")
            .unwrap_err()
            .to_string();
        assert!(start.elapsed().as_millis() < 100);
        assert!(
            e.contains("truncated or corrupt") || e.contains("`$Elements` comes before"),
            "{e}"
        );
    }
}

fn rectangle_8x8() -> Mesh {
    rectangle(&Rectangle {
        origin: [0.0, 0.0],
        size: [4.0, 4.0],
        n: [8, 8],
        pattern: CutPattern::Symmetric,
        progression: [1.0; 2],
    })
    .unwrap()
}

fn cuboid_3x3x3() -> Mesh {
    cuboid(&BoxSpec {
        origin: [0.0, 0.0, 0.0],
        size: [1.0, 1.0, 1.0],
        n: [3, 3, 3],
        pattern: CutPattern::Uniform,
        progression: [1.0; 3],
    })
    .unwrap()
}

#[test]
fn written_meshes_read_back_identically() {
    for mesh in [rectangle_8x8(), cuboid_3x3x3()] {
        for encoding in [MshEncoding::Ascii, MshEncoding::Binary] {
            let bytes = write_msh(&mesh, encoding);
            let g = parse_msh(&bytes, "written.msh").unwrap();
            // The shortest round-trip text of each f64 (ASCII) or its bytes (binary).
            assert_same_mesh(&mesh, &g.mesh, 0.0);
            assert_eq!(g.node_tags, (1..=mesh.n_nodes() as u64).collect::<Vec<_>>());
            assert_eq!(g.region_names, ["domain"]);
            assert!(g.notes.is_empty(), "{:?}", g.notes);
        }
    }
}

const PAPER_LIKE_2D: &str = r#"
[mesh]
kind = "rectangle"
size = [4.0, 4.0]
n = [8, 8]
[material]
young = 2000.0
poisson = 0.3
[locking]
set = "limited-compressibility"
theta = 0.16
c_kappa = 10000.0
[[dirichlet]]
part = "bottom"
[[loads.traction]]
part = "top"
value = [0.0, -900.0]
[[contact]]
part = "left"
gap = 0.4
c_nu = 10000.0
friction = { bound = "coulomb", mu = { law = "exponential", a = 0.4, b = 0.1, beta = 100.0 } }
[[contact]]
part = "right"
gap = 0.4
c_nu = 10000.0
friction = { bound = "coulomb", mu = { law = "exponential", a = 0.4, b = 0.1, beta = 100.0 } }
"#;

const BOX_3D: &str = r#"
[mesh]
kind = "box"
size = [1.0, 1.0, 1.0]
n = [3, 3, 3]
pattern = "uniform"
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "bottom"
[[loads.traction]]
part = "top"
value = [0.0, 0.0, -200.0]
[[contact]]
part = "right"
gap = 0.001
c_nu = 1.0e5
friction = { bound = "tresca", mu = { law = "constant", mu = 0.3 } }
"#;

/// The same problem on a generated mesh and on the mesh written to `.msh` and read back:
/// the arrays are identical, so the solutions are too.
#[test]
fn round_trip_gives_the_same_solution() {
    for text in [PAPER_LIKE_2D, BOX_3D] {
        let generated = Scenario::from_str(text, "round-trip")
            .unwrap()
            .into_problem()
            .unwrap();
        let bytes = write_msh(generated.mesh(), MshEncoding::Ascii);
        let read = parse_msh(&bytes, "round-trip.msh").unwrap();
        let from_file = generated.to_builder().mesh(read.mesh).build().unwrap();
        let a = hemicontact::solver::solve(&generated, &SolverSettings::default()).unwrap();
        let b = hemicontact::solver::solve(&from_file, &SolverSettings::default()).unwrap();
        assert!(a.report.converged && b.report.converged);
        let scale = a.u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(scale > 0.0);
        for (x, y) in a.u.iter().zip(&b.u) {
            assert!((x - y).abs() <= 1e-12 * scale, "{x} vs {y}");
        }
    }
}

// ---------------------------------------------------------------------------------------
// Scenarios.
// ---------------------------------------------------------------------------------------

const SQUARE_SCENARIO: &str = r#"
[mesh]
kind = "gmsh"
file = "square.msh"
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "bottom"
[[loads.traction]]
part = "top"
value = [0.0, -100.0]
[[contact]]
part = "right"
gap = 0.01
c_nu = 1.0e4
"#;

/// A scenario whose relative paths resolve against `tests/data/gmsh`.
fn scenario_in_data(text: &str) -> Scenario {
    let mut s = Scenario::from_str(text, "gmsh-scenario").unwrap();
    s.dir = Some(data(""));
    s
}

#[test]
fn gmsh_scenario_resolves_the_file_next_to_the_scenario() {
    // A scenario file and its mesh in a folder that is not the working folder.
    let dir = std::env::temp_dir().join(format!("hemicontact-gmsh-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("meshes")).unwrap();
    std::fs::copy(data("square.msh"), dir.join("meshes/square.msh")).unwrap();
    let path = dir.join("square.toml");
    std::fs::write(
        &path,
        SQUARE_SCENARIO.replace("square.msh", "meshes/square.msh"),
    )
    .unwrap();
    let s = Scenario::from_file(&path).unwrap();
    let resolved = s.into_problem_with_notes();
    std::fs::remove_dir_all(&dir).unwrap();
    let (problem, notes) = resolved.unwrap();
    assert_eq!(problem.mesh().n_nodes(), 30);
    // The contact side `right` shares its lower corner with the clamped `bottom`.
    assert_eq!(notes.len(), 1, "{notes:?}");
    let solution = hemicontact::solver::solve(&problem, &SolverSettings::default()).unwrap();
    assert!(solution.report.converged);
}

#[test]
fn gmsh_scenario_rejects_generator_fields_and_refinement() {
    for (extra, field) in [
        ("size = [1.0, 1.0]", "mesh.size"),
        ("n = [2, 2]", "mesh.n"),
        ("origin = [0.0, 0.0]", "mesh.origin"),
        ("pattern = \"uniform\"", "mesh.pattern"),
    ] {
        let text = SQUARE_SCENARIO.replace(
            "file = \"square.msh\"",
            &format!("file = \"square.msh\"\n{extra}"),
        );
        let e = scenario_in_data(&text).into_problem().unwrap_err();
        let msg = e.to_string();
        assert!(
            matches!(e, Error::Scenario { .. }) && msg.contains(field) && msg.contains("gmsh"),
            "{msg}"
        );
    }
    let text = SQUARE_SCENARIO.replace("file = \"square.msh\"\n", "");
    let msg = scenario_in_data(&text)
        .into_problem()
        .unwrap_err()
        .to_string();
    assert!(msg.contains("mesh.file"), "{msg}");
    let msg = scenario_in_data(SQUARE_SCENARIO)
        .with_resolution(8)
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("a read mesh cannot be refined")
            && msg.contains("use a generated mesh for convergence studies"),
        "{msg}"
    );
    // The file field is for gmsh meshes only.
    let text = "[mesh]\nkind = \"rectangle\"\nsize = [1.0, 1.0]\nn = [2, 2]\nfile = \"a.msh\"\n\
                [material]\nyoung = 1.0\npoisson = 0.0\n[[dirichlet]]\npart = \"left\"\n";
    let msg = Scenario::from_str(text, "t")
        .unwrap()
        .into_problem()
        .unwrap_err()
        .to_string();
    assert!(msg.contains("mesh.file"), "{msg}");
}

#[test]
fn gmsh_scenario_errors_name_the_mesh_file() {
    let text = SQUARE_SCENARIO.replace("square.msh", "missing.msh");
    let msg = scenario_in_data(&text)
        .into_problem()
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("mesh.file") && msg.contains("missing.msh"),
        "{msg}"
    );
    let text = SQUARE_SCENARIO.replace("square.msh", "bad-quadrangle.msh");
    let msg = scenario_in_data(&text)
        .into_problem()
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("bad-quadrangle.msh:46:") && msg.contains("Quadrilateral"),
        "{msg}"
    );
}

#[test]
fn gmsh_scenario_honours_the_memory_limit() {
    let mut s = scenario_in_data(SQUARE_SCENARIO);
    s.memory_limit = Some(1000);
    let msg = s.into_problem().unwrap_err().to_string();
    assert!(
        msg.contains("mesh.file") && msg.contains("GiB") && msg.contains("--ignore-memory-limit"),
        "{msg}"
    );
}

#[test]
fn contact_sharing_nodes_with_dirichlet_gives_a_note() {
    let text = SQUARE_SCENARIO.replace("part = \"right\"", "part = \"left\"");
    let (problem, notes) = scenario_in_data(&text).into_problem_with_notes().unwrap();
    // The left side shares its bottom corner with the clamped bottom side.
    assert!(
        notes.iter().any(|n| n.contains("contact part `left`")
            && n.contains("Dirichlet part `bottom`")
            && n.contains("1 node")),
        "{notes:?}"
    );
    // That node is not a contact node.
    let left = problem.mesh().part_index("left").unwrap();
    assert_eq!(
        problem.contact_nodes().unwrap().len(),
        problem.mesh().part_nodes(left).len() - 1
    );
}

#[test]
fn half_disc_scenario_solves_with_contact_on_the_arc() {
    let s = Scenario::from_file(&repo("scenarios/half-disc.toml")).unwrap();
    let (problem, notes) = s.into_problem_with_notes().unwrap();
    assert!(
        notes.iter().any(|n| n.contains("contact part `contact`")),
        "{notes:?}"
    );
    let solution = hemicontact::solver::solve(&problem, &SolverSettings::default()).unwrap();
    let r = &solution.report;
    assert!(r.converged, "{}", r.message);
    assert!(r.certificate.n_contact > 10, "{}", r.certificate.n_contact);
    assert!(r.certificate.n_slip > 0);
    assert!(r.certificate.friction_law < 1e-8 && r.certificate.normal_law < 1e-8);
}

/// An entity in very many physical groups (here 20 000, all named `side`) costs time in
/// proportion to the file, not to groups × facets.
#[test]
fn many_physical_groups_per_entity_are_read_in_linear_time() {
    let mesh = rectangle(&Rectangle {
        origin: [0.0, 0.0],
        size: [1.0, 1.0],
        n: [2000, 1],
        pattern: CutPattern::Uniform,
        progression: [1.0; 2],
    })
    .unwrap();
    let text = String::from_utf8(write_msh(&mesh, MshEncoding::Ascii)).unwrap();
    let groups = 20_000;
    // Every group of dimension 1 is named `side`; the entity of part 1 (`bottom`) is in all.
    let mut names = format!("$PhysicalNames\n{}\n", groups + 1);
    for g in 1..=groups {
        names.push_str(&format!("1 {g} \"side\"\n"));
    }
    names.push_str(&format!("2 {} \"domain\"\n$EndPhysicalNames\n", groups + 1));
    let start = text.find("$PhysicalNames").unwrap();
    let end = text.find("$Entities").unwrap();
    let all: Vec<String> = (1..=groups).map(|g| g.to_string()).collect();
    let text = format!("{}{names}{}", &text[..start], &text[end..]).replacen(
        " 1 1 0\n",
        &format!(" {groups} {} 0\n", all.join(" ")),
        1,
    );
    assert!(
        text.contains(&format!(" {groups} 1 2 3 ")),
        "the entity line was not found"
    );
    let start = std::time::Instant::now();
    let g = parse_msh(text.as_bytes(), "many-groups.msh").unwrap();
    let elapsed = start.elapsed();
    assert_eq!(g.mesh.part_names(), ["side"]);
    assert!(elapsed.as_secs_f64() < 1.0, "{elapsed:?}");
}

/// A device or a folder is refused before reading (reading `/dev/zero` would not end).
#[test]
fn only_regular_files_are_read() {
    for path in ["/dev/zero", "/tmp"] {
        let path = Path::new(path);
        if path.exists() {
            let e = read_msh(path).unwrap_err();
            assert!(
                matches!(&e, Error::Io { .. }) && e.to_string().contains("not a regular file"),
                "{e}"
            );
        }
    }
    let text = SQUARE_SCENARIO.replace("square.msh", "/dev/zero");
    let msg = scenario_in_data(&text)
        .into_problem()
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("mesh.file") && msg.contains("not a regular file"),
        "{msg}"
    );
}
