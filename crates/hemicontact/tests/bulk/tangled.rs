//! # Verification: inverted, tangled and overlapping meshes are refused
//!
//! What is verified, and why it must hold:
//!
//! - **A tangled Gmsh mesh is an error naming its inverted elements.** The Gmsh square of
//!   side 4 (`tests/data/gmsh/square.msh`), written back by `write_msh`, with the interior
//!   node nearest the centre moved past its nearest neighbour: some triangles around the
//!   node become clockwise while the others stay counterclockwise. The signed areas, computed
//!   here by the cross product, still sum to 16 (they always do), but their absolute values
//!   do not: reorienting the clockwise cells, as the reader once did, covered more than the
//!   domain. The error names the file and every clockwise element tag, and says what is
//!   allowed.
//! - **The same tangle with its clockwise cells written counterclockwise** (every cell then
//!   looks fine) is caught by the divergence theorem: the cell areas sum to more than the
//!   16 enclosed by the boundary, and the error names the overlapping elements.
//! - **A consistently clockwise mesh is repaired**: every triangle of the square written
//!   clockwise reads back into the very cells of the counterclockwise file, with a note that
//!   `check`/`solve` print, and the same contact problem has the same solution bit for bit.
//! - **One clockwise triangle among counterclockwise ones** is an error naming that element
//!   alone.
//! - **`Mesh::try_new` refuses overlapping cells that are each positively oriented**: two
//!   triangles (and two tetrahedra) on the same side of their common facet; the error names
//!   both cells, and gives Σ|T| and the boundary integral, both computed here by hand.
//! - **Overlapping cells under a tagged facet are named as an overlap**: the unit square as
//!   two triangles plus a third, (0,0),(1,0),(0,1), over half of each; its edges 0–1 and
//!   0–3 are then shared by two cells on the same side (both cells lie above y = 0, right
//!   of x = 0), so the tagged bottom edge is no longer on the boundary. The error says the
//!   cells overlap and names the pairs, cell 0 and cell 2, cell 1 and cell 2. A cell given
//!   twice makes its facets shared by three cells: the error names them and the repeat.
//! - **The round-off tolerance does not reject good meshes**: generated rectangles and boxes
//!   far from the origin (coordinates 10⁶ times the cell size) are accepted.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::io::msh::{write_msh, MshEncoding};
use hemicontact::mesh::generate::{cuboid, rectangle, BoxSpec, CutPattern, Rectangle};
use hemicontact::mesh::gmsh::{parse_msh, read_msh};
use hemicontact::mesh::Mesh;
use hemicontact::scenario::Scenario;
use hemicontact::solver::SolverSettings;
use hemicontact::Error;
use std::path::Path;

fn square() -> Mesh {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/gmsh/square.msh");
    read_msh(&path).unwrap().mesh
}

/// Signed area of the triangle `(a, b, c)`, by the cross product.
fn signed_area(a: &[f64], b: &[f64], c: &[f64]) -> f64 {
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
}

/// The ASCII `.msh` text of `mesh` as `write_msh` writes it (node tags `1..=N`, element
/// tags: the facets, then the cells), with the coordinates `coords` instead of the mesh's
/// and the last two vertices of the cells where `flip(cell)` swapped.
fn msh_text(mesh: &Mesh, coords: &[f64], flip: &dyn Fn(usize) -> bool) -> String {
    let text = String::from_utf8(write_msh(mesh, MshEncoding::Ascii)).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let n = mesh.n_nodes();
    let nodes = lines.iter().position(|l| l == "$Nodes").unwrap();
    // $Nodes, the section header, the block header, n tags, then n coordinate lines.
    for i in 0..n {
        lines[nodes + 3 + n + i] = format!("{:e} {:e} 0", coords[2 * i], coords[2 * i + 1]);
    }
    let end = lines.iter().position(|l| l == "$EndElements").unwrap();
    let first_cell = end - mesh.n_cells();
    for c in 0..mesh.n_cells() {
        if flip(c) {
            let mut w: Vec<&str> = lines[first_cell + c].split_whitespace().collect();
            w.swap(2, 3);
            lines[first_cell + c] = w.join(" ");
        }
    }
    lines.join("\n") + "\n"
}

/// Element tag of cell `c` in a file written by `write_msh`.
fn element_tag(mesh: &Mesh, c: usize) -> usize {
    mesh.n_facets() + c + 1
}

fn file_error(r: Result<hemicontact::mesh::gmsh::GmshMesh, Error>) -> String {
    match r {
        Err(e @ Error::MeshFile { .. }) => e.to_string(),
        Err(e) => panic!("expected a mesh file error, got {e}"),
        Ok(g) => panic!(
            "expected an error, the mesh was accepted with area {}",
            g.mesh.measure()
        ),
    }
}

/// The square with its interior node nearest the centre moved past its nearest
/// neighbour: the new coordinates and, per cell, the signed area there.
fn tangled_square(mesh: &Mesh) -> (Vec<f64>, Vec<f64>) {
    let n = mesh.n_nodes();
    let mut on_boundary = vec![false; n];
    for f in 0..mesh.n_facets() {
        for &v in mesh.facet(f) {
            on_boundary[v as usize] = true;
        }
    }
    let dist = |a: usize, b: &[f64]| {
        let x = mesh.node(a);
        ((x[0] - b[0]).powi(2) + (x[1] - b[1]).powi(2)).sqrt()
    };
    let p = (0..n)
        .filter(|&v| !on_boundary[v])
        .min_by(|&a, &b| dist(a, &[2.0, 2.0]).total_cmp(&dist(b, &[2.0, 2.0])))
        .unwrap();
    let (ptr, adj) = mesh.node_adjacency();
    let q = adj[ptr[p]..ptr[p + 1]]
        .iter()
        .map(|&v| v as usize)
        .min_by(|&a, &b| dist(a, mesh.node(p)).total_cmp(&dist(b, mesh.node(p))))
        .unwrap();
    let mut coords = mesh.coords().to_vec();
    // p goes to q + 0.3 (q − p): past its neighbour.
    for i in 0..2 {
        coords[2 * p + i] = mesh.node(q)[i] + 0.3 * (mesh.node(q)[i] - mesh.node(p)[i]);
    }
    let x = |v: u32| &coords[2 * v as usize..2 * v as usize + 2];
    let areas = (0..mesh.n_cells())
        .map(|c| {
            let t = mesh.cell(c);
            signed_area(x(t[0]), x(t[1]), x(t[2]))
        })
        .collect();
    (coords, areas)
}

#[test]
fn tangled_gmsh_mesh_is_an_error_naming_the_inverted_elements() {
    let mesh = square();
    let (coords, areas) = tangled_square(&mesh);
    let clockwise: Vec<usize> = (0..areas.len()).filter(|&c| areas[c] < 0.0).collect();
    // The premise: a real tangle, some cells of each orientation, none degenerate.
    assert!(!clockwise.is_empty() && clockwise.len() < areas.len() / 2);
    assert!(areas.iter().all(|a| a.abs() > 1e-3));
    let signed: f64 = areas.iter().sum();
    let absolute: f64 = areas.iter().map(|a| a.abs()).sum();
    assert!((signed - 16.0).abs() < 1e-12, "{signed}");
    assert!(absolute > 16.0 + 1e-3, "{absolute}");

    let text = msh_text(&mesh, &coords, &|_| false);
    let msg = file_error(parse_msh(text.as_bytes(), "tangled.msh"));
    assert!(msg.starts_with("tangled.msh:"), "{msg}");
    assert!(msg.contains("inverted"), "{msg}");
    assert!(msg.contains("clockwise"), "{msg}");
    assert!(
        msg.contains(&format!(
            "{} of the {} triangles",
            clockwise.len(),
            areas.len()
        )),
        "{msg}"
    );
    for &c in &clockwise {
        assert!(
            msg.contains(&format!("element {}", element_tag(&mesh, c))),
            "element {} not named: {msg}",
            element_tag(&mesh, c)
        );
    }
    // What is allowed.
    assert!(msg.contains("same orientation"), "{msg}");
}

#[test]
fn tangle_of_counterclockwise_cells_fails_the_divergence_check() {
    let mesh = square();
    let (coords, areas) = tangled_square(&mesh);
    // The clockwise cells written counterclockwise: every cell looks fine on its own.
    let text = msh_text(&mesh, &coords, &|c| areas[c] < 0.0);
    let absolute: f64 = areas.iter().map(|a| a.abs()).sum();
    let msg = file_error(parse_msh(text.as_bytes(), "folded.msh"));
    assert!(msg.starts_with("folded.msh:"), "{msg}");
    assert!(msg.contains("overlap"), "{msg}");
    // The two measures: Σ|T| (as computed here) and the 16 enclosed by the boundary.
    let (sum, enclosed) = measures(&msg);
    assert!(
        (sum - absolute).abs() < 1e-12 * absolute,
        "{absolute}: {msg}"
    );
    assert!((enclosed - 16.0).abs() < 1e-12, "{msg}");
    // The overlapping pairs name the reoriented cells.
    let first = (0..areas.len()).find(|&c| areas[c] < 0.0).unwrap();
    assert!(
        msg.contains(&format!("element {}", element_tag(&mesh, first))),
        "{msg}"
    );
}

#[test]
fn consistently_clockwise_mesh_is_repaired_with_a_note() {
    let mesh = square();
    let ccw = msh_text(&mesh, mesh.coords(), &|_| false);
    let cw = msh_text(&mesh, mesh.coords(), &|_| true);
    let a = parse_msh(ccw.as_bytes(), "ccw.msh").unwrap();
    let b = parse_msh(cw.as_bytes(), "cw.msh").unwrap();
    // Swapping the last two vertices back gives the very cells of the counterclockwise file.
    assert_eq!(a.mesh.cells(), b.mesh.cells());
    assert!(
        a.notes.iter().all(|n| !n.contains("reoriented")),
        "{:?}",
        a.notes
    );
    assert!(
        b.notes.iter().any(|n| n.contains("clockwise")
            && n.contains("reoriented")
            && n.contains(&format!("({} triangles)", mesh.n_cells()))),
        "{:?}",
        b.notes
    );

    // The note reaches the scenario's notes (printed by `check` and `solve`, written to
    // summary.json), and the solution is the same.
    let dir = std::env::temp_dir().join(format!("hemicontact-cw-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scenario = |file: &str| {
        format!(
            r#"
[mesh]
kind = "gmsh"
file = "{file}"
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "top"
value = [0.0, -0.05]
[[contact]]
part = "bottom"
gap = 0.01
c_nu = 1.0e4
"#
        )
    };
    let mut solutions = Vec::new();
    let mut all_notes = Vec::new();
    for (name, text) in [("ccw.msh", &ccw), ("cw.msh", &cw)] {
        std::fs::write(dir.join(name), text).unwrap();
        let path = dir.join(name.replace(".msh", ".toml"));
        std::fs::write(&path, scenario(name)).unwrap();
        let (problem, notes) = Scenario::from_file(&path)
            .unwrap()
            .into_problem_with_notes()
            .unwrap();
        solutions.push(hemicontact::solver::solve(&problem, &SolverSettings::default()).unwrap());
        all_notes.push(notes);
    }
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(
        all_notes[1].iter().any(|n| n.contains("reoriented")),
        "{:?}",
        all_notes[1]
    );
    assert!(solutions[0].report.converged);
    assert!(solutions[0].u.iter().any(|&x| x != 0.0));
    assert_eq!(solutions[0].u, solutions[1].u);
}

#[test]
fn one_clockwise_triangle_among_counterclockwise_ones_is_named() {
    let mesh = square();
    let odd = 17;
    let text = msh_text(&mesh, mesh.coords(), &|c| c == odd);
    let msg = file_error(parse_msh(text.as_bytes(), "one-inverted.msh"));
    assert!(msg.starts_with("one-inverted.msh:"), "{msg}");
    let tag = element_tag(&mesh, odd);
    assert!(
        msg.contains(&format!(
            "1 of the {} triangles of surface 1 is inverted: element {tag} is ordered clockwise",
            mesh.n_cells()
        )),
        "{msg}"
    );
    // No other element is named.
    assert_eq!(msg.matches("element ").count(), 1, "{msg}");
}

/// The two numbers of a divergence-check error: the sum of the cell measures and the
/// measure enclosed by the boundary.
fn measures(msg: &str) -> (f64, f64) {
    let after = |key: &str| -> f64 {
        let start = msg
            .find(key)
            .unwrap_or_else(|| panic!("no `{key}` in {msg}"))
            + key.len();
        let word = msg[start..].split_whitespace().next().unwrap();
        word.trim_end_matches([',', ';', ')']).parse().unwrap()
    };
    (after("sum to "), after(" of "))
}

fn mesh_error(r: Result<Mesh, Error>) -> String {
    match r {
        Err(e @ Error::Mesh(_)) => e.to_string(),
        Err(e) => panic!("expected a mesh error, got {e}"),
        Ok(m) => panic!("expected an error, accepted with measure {}", m.measure()),
    }
}

#[test]
fn overlapping_positive_triangles_are_refused() {
    // Two counterclockwise triangles above their common edge 0–1: T0 = (0,0),(1,0),(0,1)
    // of area 1/2 and T1 = (0,0),(1,0),(0.4,0.4) of area 1/5, inside T0. The boundary
    // integral (1/d) Σ_F (x_F − o)·n_F |F| (o the centre (½, ½) of the bounding box) counts
    // the edge 0–1 twice with the outward normal (0, −1) of both cells instead of cancelling:
    // it is Σ|T| − 2 · ½ · ½ · 1 = 0.7 − 0.5 = 0.2.
    let coords = vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.4, 0.4];
    let cells = vec![0, 1, 2, 0, 1, 3];
    let facets = vec![1, 2, 2, 0, 1, 3, 3, 0];
    let msg = mesh_error(Mesh::try_new(
        2,
        coords,
        cells,
        facets,
        vec![0; 4],
        vec!["all".into()],
    ));
    let (sum, enclosed) = measures(&msg);
    assert!((sum - 0.7).abs() < 1e-15, "{msg}");
    assert!((enclosed - 0.2).abs() < 1e-15, "{msg}");
    assert!(msg.contains("cell 0 and cell 1"), "{msg}");
}

#[test]
fn overlapping_positive_tetrahedra_are_refused() {
    // Two right-handed tetrahedra above their common face 0–1–2 (z = 0): the unit corner
    // tetrahedron (volume 1/6) and the one with apex (0.2, 0.2, 0.2) inside it (volume
    // 1/30). As for the triangles, the face z = 0 (area ½, normal (0, 0, −1), at distance ½
    // from the centre o of the bounding box) is counted twice: the boundary integral is
    // Σ|T| − 2 · ⅓ · ½ · ½ = 1/5 − 1/6 = 1/30.
    let coords = vec![
        0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.2, 0.2, 0.2,
    ];
    let cells = vec![0, 1, 2, 3, 0, 1, 2, 4];
    let facets = vec![0, 1, 3, 0, 2, 3, 1, 2, 3, 0, 1, 4, 0, 2, 4, 1, 2, 4];
    let msg = mesh_error(Mesh::try_new(
        3,
        coords,
        cells,
        facets,
        vec![0; 6],
        vec!["all".into()],
    ));
    let (sum, enclosed) = measures(&msg);
    assert!((sum - 0.2).abs() < 1e-15, "{msg}");
    assert!((enclosed - 1.0 / 30.0).abs() < 1e-15, "{msg}");
    assert!(msg.contains("cell 0 and cell 1"), "{msg}");
}

/// The unit square 0 (0,0), 1 (1,0), 2 (1,1), 3 (0,1) with the cells `cells` and its four
/// sides tagged.
fn tagged_square(cells: Vec<u32>) -> Result<Mesh, Error> {
    let coords = vec![0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
    let side = |name: &str, a: u32, b: u32| (name.to_string(), vec![a, b]);
    Mesh::from_parts(
        2,
        coords,
        cells,
        &[
            side("bottom", 0, 1),
            side("right", 1, 2),
            side("top", 2, 3),
            side("left", 3, 0),
        ],
    )
}

#[test]
fn overlapping_cells_under_a_tagged_facet_are_named_as_an_overlap() {
    tagged_square(vec![0, 1, 2, 0, 2, 3]).unwrap();
    let msg = mesh_error(tagged_square(vec![0, 1, 2, 0, 2, 3, 0, 1, 3]));
    assert!(
        msg.contains("tagged facet [0, 1] (part `bottom`) is not on the boundary")
            && msg.contains("cells overlap")
            && msg.contains("(they overlap): cell 0 and cell 2; cell 1 and cell 2"),
        "{msg}"
    );
    let msg = mesh_error(tagged_square(vec![0, 1, 2, 0, 2, 3, 1, 2, 0]));
    assert!(
        msg.contains("is shared by 3 cells")
            && msg.contains("cell 0, cell 1 and cell 2; cell 2 repeats cell 0 (the same nodes)"),
        "{msg}"
    );
}

#[test]
fn good_meshes_far_from_the_origin_pass_the_divergence_check() {
    for pattern in [CutPattern::Uniform, CutPattern::Symmetric] {
        let m = rectangle(&Rectangle {
            origin: [1.0e6, -3.0e6],
            size: [1.0, 0.5],
            n: [40, 20],
            pattern,
            progression: [1.0; 2],
        })
        .unwrap();
        assert!((m.measure() - 0.5).abs() < 1e-6);
    }
    let m = cuboid(&BoxSpec {
        origin: [-2.0e5, 1.0e5, 7.0e5],
        size: [0.3, 0.2, 0.1],
        n: [6, 4, 2],
        pattern: CutPattern::Uniform,
        progression: [1.0; 3],
    })
    .unwrap();
    assert!((m.measure() - 0.006).abs() < 1e-6);
}
