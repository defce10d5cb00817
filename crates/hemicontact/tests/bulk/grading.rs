//! Graded meshes: the geometric progression of the rectangle and box generators.
//!
//! Along an axis of side `L` cut into `n` cells with progression `r`, the cell sizes are
//! `h_k = h_0 r^k` and node `i` is at `x0 + L (r^i − 1)/(r^n − 1)` (Gmsh's transfinite
//! `Using Progression r`). Checked here against facts known without the program:
//!
//! - `r = 1` gives bitwise the nodes of the plain grid, `x0 + L (i/n)`;
//! - the nodes follow the closed form (evaluated here with `powi`), the ends are exact, the
//!   ratio of consecutive cell sizes is `r` (1e-12 relative), `r > 1` refines towards `x0`;
//! - the cells tile the rectangle (box): every cell is positively oriented and their areas
//!   (volumes), computed here by cross (triple) products, sum to `lx ly` (`lx ly lz`);
//! - patch test: P1 elements contain the affine fields, so an affine displacement
//!   prescribed on the boundary of a graded mesh is reproduced at every node and gives the
//!   same strain in every cell (as in `patch.rs`, on graded meshes, 2D and 3D);
//! - bad ratios are refused, by the generators and by the scenario loader naming
//!   `mesh.progression[k]` and the value; the symmetric pattern refuses a graded x axis;
//! - a scenario with `progression` survives a TOML round trip, and refinement
//!   (`with_resolution`) keeps `r^n`, so doubling `n` splits every cell in two (nested).
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use common::{problem, solve_with_prescribed_field};
use hemicontact::assembly::BulkAssembler;
use hemicontact::mesh::generate::{cuboid, rectangle, BoxSpec, CutPattern, Rectangle};
use hemicontact::mesh::Mesh;
use hemicontact::scenario::Scenario;
use hemicontact::Error;

fn rect(origin: [f64; 2], size: [f64; 2], n: [usize; 2], r: [f64; 2]) -> Rectangle {
    Rectangle {
        origin,
        size,
        n,
        pattern: CutPattern::Uniform,
        progression: r,
    }
}

fn cube(origin: [f64; 3], size: [f64; 3], n: [usize; 3], r: [f64; 3]) -> BoxSpec {
    BoxSpec {
        origin,
        size,
        n,
        pattern: CutPattern::Uniform,
        progression: r,
    }
}

/// Coordinate `axis` of the node with grid index `(i, j[, k])`: nodes are numbered with x
/// fastest, then y, then z.
fn coord(m: &Mesh, n: &[usize], idx: &[usize], axis: usize) -> f64 {
    let mut node = 0;
    for a in (0..n.len()).rev() {
        node = node * (n[a] + 1) + idx[a];
    }
    m.node(node)[axis]
}

/// The node coordinates along `axis` (the other indices zero).
fn axis_coords(m: &Mesh, n: &[usize], axis: usize) -> Vec<f64> {
    (0..=n[axis])
        .map(|i| {
            let mut idx = vec![0; n.len()];
            idx[axis] = i;
            coord(m, n, &idx, axis)
        })
        .collect()
}

/// Signed measure of cell `c` by hand: half the cross product (2D), a sixth of the triple
/// product (3D) of the edge vectors from the first vertex.
fn cell_measure(m: &Mesh, c: usize) -> f64 {
    let v: Vec<&[f64]> = m.cell(c).iter().map(|&n| m.node(n as usize)).collect();
    let e = |k: usize, a: usize| v[k][a] - v[0][a];
    if m.dim() == 2 {
        0.5 * (e(1, 0) * e(2, 1) - e(1, 1) * e(2, 0))
    } else {
        (e(1, 0) * (e(2, 1) * e(3, 2) - e(2, 2) * e(3, 1))
            - e(1, 1) * (e(2, 0) * e(3, 2) - e(2, 2) * e(3, 0))
            + e(1, 2) * (e(2, 0) * e(3, 1) - e(2, 1) * e(3, 0)))
            / 6.0
    }
}

#[test]
fn progression_one_gives_bitwise_the_plain_grid() {
    let (o, l, n) = ([0.3, -1.7], [2.9, 0.7], [7, 5]);
    let m = rectangle(&rect(o, l, n, [1.0, 1.0])).unwrap();
    for j in 0..=n[1] {
        for i in 0..=n[0] {
            let x = m.node(j * (n[0] + 1) + i);
            assert_eq!(x[0].to_bits(), (o[0] + l[0] * (i as f64 / 7.0)).to_bits());
            assert_eq!(x[1].to_bits(), (o[1] + l[1] * (j as f64 / 5.0)).to_bits());
        }
    }
    let (o, l, n) = ([0.1, 0.2, -0.3], [1.1, 0.3, 2.3], [4, 6, 5]);
    for pattern in [CutPattern::Uniform, CutPattern::Symmetric] {
        let mut b = cube(o, l, n, [1.0; 3]);
        b.pattern = pattern;
        let m = cuboid(&b).unwrap();
        for k in 0..=n[2] {
            for j in 0..=n[1] {
                for i in 0..=n[0] {
                    let idx = [i, j, k];
                    for a in 0..3 {
                        let old = o[a] + l[a] * (idx[a] as f64 / n[a] as f64);
                        assert_eq!(coord(&m, &n, &idx, a).to_bits(), old.to_bits());
                    }
                }
            }
        }
    }
}

/// Checks the nodes along `axis` against the closed form, the exact ends and the ratio of
/// consecutive cell sizes.
#[track_caller]
fn check_axis(m: &Mesh, n: &[usize], axis: usize, x0: f64, length: f64, r: f64) {
    let x = axis_coords(m, n, axis);
    let cells = n[axis] as i32;
    assert_eq!(x[0], x0, "first node");
    assert_eq!(x[n[axis]], x0 + length, "last node");
    for (i, &xi) in x.iter().enumerate() {
        let exact = x0 + length * (r.powi(i as i32) - 1.0) / (r.powi(cells) - 1.0);
        assert!(
            (xi - exact).abs() <= 1e-13 * length,
            "axis {axis}, node {i}: {xi} against {exact}"
        );
    }
    let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    for k in 1..h.len() {
        let ratio = h[k] / h[k - 1];
        assert!(
            (ratio - r).abs() <= 1e-12 * r,
            "axis {axis}: h[{k}]/h[{}] = {ratio}, r = {r}",
            k - 1
        );
    }
    // h_0 = L (r − 1)/(r^n − 1): the smallest cell at x0 for r > 1, the largest for r < 1.
    let h0 = length * (r - 1.0) / (r.powi(cells) - 1.0);
    assert!((h[0] - h0).abs() <= 1e-12 * h0);
    if r > 1.0 {
        assert!(h[0] < h[h.len() - 1]);
    } else {
        assert!(h[0] > h[h.len() - 1]);
    }
}

#[test]
fn graded_rectangle_follows_the_closed_form() {
    for (o, l, n, r) in [
        ([0.0, 0.0], [1.0, 1.0], [8, 6], [1.5, 0.7]),
        ([-2.0, 0.5], [3.0, 0.25], [10, 4], [0.9, 1.25]),
        ([1.0, 1.0], [2.0, 2.0], [5, 7], [1.001, 3.0]),
    ] {
        let m = rectangle(&rect(o, l, n, r)).unwrap();
        for a in 0..2 {
            check_axis(&m, &n, a, o[a], l[a], r[a]);
        }
        // The grid is a tensor product: node (i, j) is (x_i, y_j).
        let (xs, ys) = (axis_coords(&m, &n, 0), axis_coords(&m, &n, 1));
        for j in 0..=n[1] {
            for i in 0..=n[0] {
                assert_eq!(m.node(j * (n[0] + 1) + i), &[xs[i], ys[j]]);
            }
        }
    }
}

#[test]
fn graded_box_follows_the_closed_form() {
    let (o, l, n, r) = (
        [0.5, -1.0, 2.0],
        [1.0, 2.0, 0.5],
        [6, 5, 7],
        [1.3, 0.8, 1.1],
    );
    let m = cuboid(&cube(o, l, n, r)).unwrap();
    for a in 0..3 {
        check_axis(&m, &n, a, o[a], l[a], r[a]);
    }
    let xs: Vec<Vec<f64>> = (0..3).map(|a| axis_coords(&m, &n, a)).collect();
    for k in 0..=n[2] {
        for j in 0..=n[1] {
            for i in 0..=n[0] {
                let node = (k * (n[1] + 1) + j) * (n[0] + 1) + i;
                assert_eq!(m.node(node), &[xs[0][i], xs[1][j], xs[2][k]]);
            }
        }
    }
}

#[test]
fn graded_cells_tile_the_rectangle_and_the_box() {
    let m = rectangle(&rect([0.2, 0.1], [3.0, 2.0], [9, 7], [1.4, 0.6])).unwrap();
    let mut area = 0.0;
    for c in 0..m.n_cells() {
        let a = cell_measure(&m, c);
        assert!(a > 0.0, "cell {c} has area {a}");
        area += a;
    }
    assert!((area - 6.0).abs() <= 1e-12 * 6.0, "area {area}");
    let mut b = cube(
        [0.0, 1.0, -1.0],
        [2.0, 1.5, 0.5],
        [4, 6, 4],
        [1.0, 1.7, 0.5],
    );
    for pattern in [CutPattern::Uniform, CutPattern::Symmetric] {
        b.pattern = pattern;
        let m = cuboid(&b).unwrap();
        let mut volume = 0.0;
        for c in 0..m.n_cells() {
            let v = cell_measure(&m, c);
            assert!(v > 0.0, "{pattern:?}: cell {c} has volume {v}");
            volume += v;
        }
        assert!((volume - 1.5).abs() <= 1e-12 * 1.5, "volume {volume}");
        // The six faces keep their areas.
        for (part, face) in [("left", 0.75), ("front", 1.0), ("top", 3.0)] {
            let area: f64 = m
                .part_facets(m.part_index(part).unwrap())
                .map(|f| m.facet_measure_normal(f).0)
                .sum();
            assert!((area - face).abs() <= 1e-12 * face, "{part}: {area}");
        }
    }
}

/// An affine displacement `u = a + B x` prescribed on the whole boundary of a graded mesh
/// must be reproduced at every node, with the strain `sym(B)` in every cell.
#[test]
fn affine_displacement_is_reproduced_on_graded_meshes() {
    let b = [
        [0.010, -0.020, 0.004],
        [0.015, 0.005, -0.006],
        [0.002, 0.003, -0.008],
    ];
    let a = [1.0e-3, -2.0e-3, 0.5e-3];
    for (dim, mesh, parts) in [
        (
            2,
            "kind = \"rectangle\"\norigin = [0.3, -0.2]\nsize = [2.0, 1.5]\nn = [8, 6]\n\
             pattern = \"uniform\"\nprogression = [1.5, 0.6]",
            &["bottom", "right", "top", "left"][..],
        ),
        (
            3,
            "kind = \"box\"\nsize = [1.0, 1.0, 1.0]\nn = [4, 4, 4]\n\
             progression = [1.0, 1.6, 0.7]",
            &["left", "right", "front", "back", "bottom", "top"][..],
        ),
    ] {
        let mut text = format!("[mesh]\n{mesh}\n[material]\nyoung = 2000.0\npoisson = 0.3\n");
        for part in parts {
            text += &format!("[[dirichlet]]\npart = \"{part}\"\n");
        }
        let p = problem(&text);
        let exact = |x: &[f64]| -> Vec<f64> {
            (0..dim)
                .map(|i| a[i] + (0..dim).map(|j| b[i][j] * x[j]).sum::<f64>())
                .collect()
        };
        let (u, steps) = solve_with_prescribed_field(&p, exact);
        assert!(steps > 0, "{dim}D: the solver took no step");
        let mesh = p.mesh();
        // The mesh is graded: its cells are not all of one size.
        let sizes: Vec<f64> = (0..mesh.n_cells()).map(|c| cell_measure(mesh, c)).collect();
        let (small, large) = sizes
            .iter()
            .fold((f64::MAX, 0.0_f64), |(s, l), &v| (s.min(v), l.max(v)));
        assert!(large > 3.0 * small, "{dim}D: cells from {small} to {large}");
        let scale = 0.05;
        for n in 0..mesh.n_nodes() {
            let v = exact(mesh.node(n));
            for i in 0..dim {
                assert!(
                    (u[dim * n + i] - v[i]).abs() <= 1e-10 * scale,
                    "{dim}D node {n}: u[{i}] = {:e}, exact {:e}",
                    u[dim * n + i],
                    v[i]
                );
            }
        }
        let strain = |i: usize, j: usize| 0.5 * (b[i][j] + b[j][i]);
        let bulk = BulkAssembler::new(mesh, &p.materials()[0]);
        for (c, e) in bulk.cell_strains(&u).iter().enumerate() {
            // Mandel components: the diagonal, then √2 ε_ij (2D: xy; 3D: yz, xz, xy).
            let mut want = vec![strain(0, 0), strain(1, 1)];
            if dim == 2 {
                want.push(2f64.sqrt() * strain(0, 1));
            } else {
                want.extend([
                    strain(2, 2),
                    2f64.sqrt() * strain(1, 2),
                    2f64.sqrt() * strain(0, 2),
                    2f64.sqrt() * strain(0, 1),
                ]);
            }
            for (k, &w) in want.iter().enumerate() {
                assert!(
                    (e.c[k] - w).abs() <= 1e-10 * 0.02,
                    "{dim}D cell {c}: ε[{k}] = {:e}, exact {w:e}",
                    e.c[k]
                );
            }
        }
    }
}

#[test]
fn bad_progressions_are_refused_by_the_generators() {
    for (r, n) in [
        (0.0, 4),
        (-1.5, 4),
        (f64::NAN, 4),
        (f64::INFINITY, 4),
        (1.0e-4, 4),
        (2.0e3, 4),
        // Within the range, but the smallest cell is (r − 1)/(r^n − 1) ≈ 1e-15 of the side.
        (10.0, 16),
        (0.1, 16),
    ] {
        for axis in 0..2 {
            let mut p = [1.0, 1.0];
            p[axis] = r;
            let mut spec = rect([0.0, 0.0], [1.0, 1.0], [4, 4], p);
            spec.n[axis] = n;
            match rectangle(&spec) {
                Err(Error::Mesh(msg)) => {
                    assert!(
                        msg.contains("progression") && msg.contains(&r.to_string()),
                        "{msg}"
                    );
                    assert!(msg.contains(["along x", "along y"][axis]), "{msg}");
                }
                other => panic!("r = {r} along axis {axis} accepted: {other:?}"),
            }
        }
        let mut spec = cube([0.0; 3], [1.0; 3], [2, 2, n], [1.0, 1.0, r]);
        spec.pattern = CutPattern::Uniform;
        match cuboid(&spec) {
            Err(Error::Mesh(msg)) => assert!(msg.contains("along z"), "{msg}"),
            other => panic!("r = {r} along z accepted: {other:?}"),
        }
    }
    // The ends of the range are accepted when the cells stay large enough.
    for r in [1.0e-3, 1.0e3] {
        rectangle(&rect([0.0, 0.0], [1.0, 1.0], [2, 2], [r, 1.0])).unwrap();
    }
    // The symmetric pattern mirrors about the centre of x: a graded x axis is refused, a
    // graded y or z axis is not.
    let mut spec = rect([0.0, 0.0], [1.0, 1.0], [4, 4], [1.2, 1.0]);
    spec.pattern = CutPattern::Symmetric;
    assert!(matches!(rectangle(&spec), Err(Error::Mesh(m)) if m.contains("symmetric")));
    spec.progression = [1.0, 1.2];
    rectangle(&spec).unwrap();
    let mut spec = cube([0.0; 3], [1.0; 3], [2, 2, 2], [0.8, 1.0, 1.0]);
    spec.pattern = CutPattern::Symmetric;
    assert!(matches!(cuboid(&spec), Err(Error::Mesh(m)) if m.contains("symmetric")));
    spec.progression = [1.0, 0.8, 1.3];
    cuboid(&spec).unwrap();
}

fn scenario(mesh: &str) -> String {
    format!("[mesh]\n{mesh}\n[material]\nyoung = 1000.0\npoisson = 0.3\n[[dirichlet]]\npart = \"bottom\"\n")
}

/// The scenario error of `text`: its field and value.
#[track_caller]
fn refusal(text: &str) -> (String, String, String) {
    let err = Scenario::from_str(text, "<test>")
        .and_then(|s| s.into_problem().map(|_| ()))
        .expect_err("refused");
    match err {
        Error::Scenario {
            field,
            value,
            allowed,
            ..
        } => (field, value, allowed),
        other => panic!("not a scenario error: {other}"),
    }
}

#[test]
fn bad_progressions_are_refused_by_the_scenario_naming_the_field() {
    let base = "kind = \"rectangle\"\nsize = [1.0, 1.0]\nn = [4, 8]\npattern = \"uniform\"";
    for (given, field, value) in [
        ("[1.0, 0.0]", "mesh.progression[1]", "0"),
        ("[-2.0, 1.0]", "mesh.progression[0]", "-2"),
        ("[1.0, 5000.0]", "mesh.progression[1]", "5000"),
        ("[1.0, 100.0]", "mesh.progression[1]", "100"),
        ("[1.0, 1.0, 1.0]", "mesh.progression", "[1.0, 1.0, 1.0]"),
        ("[2.0]", "mesh.progression", "[2.0]"),
    ] {
        let (f, v, allowed) = refusal(&scenario(&format!("{base}\nprogression = {given}")));
        assert_eq!((f.as_str(), v.as_str()), (field, value), "{given}");
        if field != "mesh.progression" {
            assert!(
                allowed.contains("from 1e-3 to 1e3")
                    && allowed.contains("smallest cell is at least 1e-9 of the side"),
                "{allowed}"
            );
        }
    }
    // nan and inf are TOML floats too.
    let (f, v, _) = refusal(&scenario(&format!("{base}\nprogression = [nan, 1.0]")));
    assert_eq!((f.as_str(), v.as_str()), ("mesh.progression[0]", "NaN"));
    let (f, v, _) = refusal(&scenario(&format!("{base}\nprogression = [1.0, inf]")));
    assert_eq!((f.as_str(), v.as_str()), ("mesh.progression[1]", "inf"));
    // The default pattern is symmetric: a graded x axis needs pattern = "uniform".
    let text =
        scenario("kind = \"rectangle\"\nsize = [1.0, 1.0]\nn = [4, 4]\nprogression = [1.5, 1.0]");
    let (f, v, allowed) = refusal(&text);
    assert_eq!((f.as_str(), v.as_str()), ("mesh.progression[0]", "1.5"));
    assert!(allowed.contains("uniform"), "{allowed}");
    // A Gmsh mesh has no progression.
    let text = scenario("kind = \"gmsh\"\nfile = \"m.msh\"\nprogression = [1.5, 1.0]");
    let (f, _, _) = refusal(&text);
    assert_eq!(f, "mesh.progression");
}

#[test]
fn scenario_progression_round_trips_and_refines_nested() {
    let text = scenario(
        "kind = \"box\"\nsize = [1.0, 2.0, 1.0]\nn = [4, 8, 4]\n\
         pattern = \"uniform\"\nprogression = [1.44, 1.0, 0.64]",
    );
    let s = Scenario::from_str(&text, "<test>").unwrap();
    assert_eq!(
        s.mesh_spec().unwrap().progression.as_deref(),
        Some(&[1.44, 1.0, 0.64][..])
    );
    let again = Scenario::from_str(&toml::to_string(&s.file).unwrap(), "<again>").unwrap();
    assert_eq!(
        again.mesh_spec().unwrap().progression,
        s.mesh_spec().unwrap().progression
    );
    let coarse = s.into_problem().unwrap();
    assert_eq!(
        coarse.mesh().coords(),
        again.into_problem().unwrap().mesh().coords()
    );
    // Without the key every ratio is 1: the plain grid.
    let plain = Scenario::from_str(
        &text.replace("progression = [1.44, 1.0, 0.64]", ""),
        "<plain>",
    )
    .unwrap();
    assert!(plain.mesh_spec().unwrap().progression.is_none());
    let m = plain.into_problem().unwrap();
    let n = [4, 8, 4];
    for a in 0..3 {
        for (i, x) in axis_coords(m.mesh(), &n, a).into_iter().enumerate() {
            let side = [1.0, 2.0, 1.0][a];
            assert_eq!(x.to_bits(), (side * (i as f64 / n[a] as f64)).to_bits());
        }
    }

    // Doubling n takes r to √r (1.2, 1, 0.8): every coarse node is a fine node.
    let fine = s.with_resolution(8).unwrap();
    let spec = fine.mesh_spec().unwrap();
    assert_eq!(spec.n.as_deref(), Some(&[8, 16, 8][..]));
    let r = spec.progression.clone().unwrap();
    for (got, want) in r.iter().zip([1.2, 1.0, 0.8]) {
        assert!((got - want).abs() <= 1e-15, "{r:?}");
    }
    let fine = fine.into_problem().unwrap();
    let (cm, fm) = (coarse.mesh(), fine.mesh());
    for a in 0..3 {
        let c = axis_coords(cm, &[4, 8, 4], a);
        let f = axis_coords(fm, &[8, 16, 8], a);
        for (i, &x) in c.iter().enumerate() {
            assert!(
                (f[2 * i] - x).abs() <= 1e-14,
                "axis {a} node {i}: {} vs {x}",
                f[2 * i]
            );
        }
    }
    // The same resolution is the same scenario, bitwise.
    let same = s.with_resolution(4).unwrap();
    assert_eq!(
        same.mesh_spec().unwrap().progression,
        s.mesh_spec().unwrap().progression
    );
}
