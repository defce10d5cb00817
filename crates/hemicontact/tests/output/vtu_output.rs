//! # Verification: `solution.vtu` and `.pvd` collections
//!
//! What is verified, and why it must hold:
//!
//! - **Encoding.** The file declares `compressor="vtkZLibDataCompressor"` and
//!   `header_type="UInt64"`; every array decodes (VTK block layout, zlib) to exactly the
//!   values of the solution in memory: the points are the mesh nodes, `displacement` is u
//!   padded to 3 components, `contact_pressure` the pressure of each contact point. The
//!   same solution gives the same bytes twice.
//! - **Fields and FieldData.** The point and cell arrays are exactly the documented ones
//!   (no duplicate: `contact_multiplier` is gone), with their numbers of components; the
//!   `units` entry names every one of them; `TITLE`, `TimeValue` (the load factor given),
//!   `hemicontact_version` and the state `codes` are in `FieldData`; a non-finite load
//!   factor is an error naming it.
//! - **Signs of the contact forces.** A unit square on a frictional foundation (normal
//!   compliance, Tresca bound 0.5 Pa) is pressed down and pushed to the right by
//!   prescribing its top side, `u = (0.02, −0.01)` m. Its bottom slides to the right, so
//!   the foundation pulls it to the left and pushes it up: at every sliding contact node
//!   both the `friction_traction` and the `interface_force` point in −x, the force is
//!   upward, and the tangential force is the weight times the traction. Nothing else acts
//!   on the body, so the interface forces balance the reactions of the top side.
//! - **Independent readers.** `tests/python/check_vtk.py` reads a written file with VTK's
//!   own reader (`vtkXMLUnstructuredGridReader`) and compares the names, components,
//!   FieldData and values with those computed here; `tests/python/check_pvd.py` parses a
//!   `.pvd` of three load factors, checks that its files exist, are in increasing time and
//!   carry that time as `TimeValue`, and reads each with `vtkXMLGenericDataObjectReader`: the
//!   prescribed top displacement is the load factor times (0.02, −0.01). The interpreter is
//!   `$HEMICONTACT_PYTHON`, else `python3`; under `CI=true` a missing `vtk` fails the
//!   tests, elsewhere they are skipped with a loud line saying they are no evidence.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use common::vtu::{attr, f64s, i32s, text};
use hemicontact::io::{pvd, vtu::solution_vtu};
use hemicontact::problem::Problem;
use hemicontact::solver::{FrictionState, Solution};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Prescribed top displacement at load factor 1 (m).
const PUSH: [f64; 2] = [0.02, -0.01];

/// The unit square on a frictional foundation, its top side moved by `factor · PUSH`.
fn pushed_block(factor: f64) -> String {
    format!(
        r#"
title = "block pushed sideways"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [4, 4]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "top"
value = [{}, {}]
[[contact]]
part = "bottom"
gap = 0.0
law = "normal-compliance"
c_nu = 10000.0
[contact.friction]
bound = "tresca"
mu = {{ law = "constant", mu = 0.5 }}
"#,
        factor * PUSH[0],
        factor * PUSH[1]
    )
}

fn solved(factor: f64) -> (Problem, Solution) {
    let (problem, settings) = common::setup(&pushed_block(factor));
    let solution = hemicontact::solver::solve(&problem, &settings).unwrap();
    assert!(solution.report.converged, "{}", solution.report.message);
    (problem, solution)
}

/// The XML part of a `.vtu` (before the appended data).
fn header(bytes: &[u8]) -> String {
    let end = bytes
        .windows(14)
        .position(|w| w == b"<AppendedData ")
        .unwrap();
    String::from_utf8(bytes[..end].to_vec()).unwrap()
}

/// (name, components) of the arrays between `<tag>` and `</tag>`.
fn arrays(xml: &str, section: &str) -> Vec<(String, usize)> {
    let start = xml.find(&format!("<{section}>")).unwrap();
    let end = xml.find(&format!("</{section}>")).unwrap();
    xml[start..end]
        .lines()
        .filter(|l| l.starts_with("<DataArray"))
        .map(|l| {
            (
                attr(l, "Name").to_string(),
                attr(l, "NumberOfComponents").parse().unwrap(),
            )
        })
        .collect()
}

const POINT_FIELDS: [(&str, usize); 9] = [
    ("displacement", 3),
    ("reaction", 3),
    ("contact_normal_state", 1),
    ("contact_friction_state", 1),
    ("contact_pressure", 1),
    ("friction_traction", 3),
    ("slip", 1),
    ("interface_force", 3),
    ("contact_normal", 3),
];
const CELL_FIELDS: [(&str, usize); 7] = [
    ("strain", 9),
    ("stress", 9),
    ("von_mises", 1),
    ("trace_strain", 1),
    ("locking_active", 1),
    ("locking_q", 1),
    ("locking_multiplier", 1),
];

#[test]
fn encoding_fields_and_field_data() {
    let (problem, solution) = solved(1.0);
    let bytes = solution_vtu(&problem, &solution, "block pushed sideways", 0.75)
        .unwrap()
        .to_bytes();
    assert_eq!(
        bytes,
        solution_vtu(&problem, &solution, "block pushed sideways", 0.75)
            .unwrap()
            .to_bytes(),
        "the same solution gives the same bytes"
    );
    let xml = header(&bytes);
    let root = &xml[xml.find("<VTKFile").unwrap()..];
    let root = &root[..root.find('>').unwrap()];
    assert_eq!(attr(root, "compressor"), "vtkZLibDataCompressor");
    assert_eq!(attr(root, "header_type"), "UInt64");
    let expect = |list: &[(&str, usize)]| -> Vec<(String, usize)> {
        list.iter().map(|&(n, c)| (n.to_string(), c)).collect()
    };
    assert_eq!(arrays(&xml, "PointData"), expect(&POINT_FIELDS));
    assert_eq!(arrays(&xml, "CellData"), expect(&CELL_FIELDS));

    // FieldData.
    assert_eq!(text(&bytes, "TITLE"), "block pushed sideways");
    assert_eq!(f64s(&bytes, "TimeValue"), [0.75]);
    assert_eq!(
        text(&bytes, "hemicontact_version"),
        env!("CARGO_PKG_VERSION")
    );
    let units = text(&bytes, "units");
    let named: Vec<&str> = units
        .lines()
        .map(|l| l.split(':').next().unwrap())
        .collect();
    let all: Vec<&str> = POINT_FIELDS
        .iter()
        .chain(CELL_FIELDS.iter())
        .map(|f| f.0)
        .collect();
    assert_eq!(named, all, "units: {units}");
    assert!(
        units.contains("interface_force: N/m\n"),
        "2D forces per thickness: {units}"
    );
    assert!(units.contains("contact_pressure: Pa\n"), "{units}");
    let codes = text(&bytes, "codes");
    assert!(
        codes.contains("contact_friction_state: -1 not a contact node"),
        "{codes}"
    );
    assert!(codes.contains("2 slip"), "{codes}");

    // Values: decoded = computed.
    let mesh = problem.mesh();
    let points = {
        let (ty, data) = common::vtu::raw(&bytes, "Points");
        assert_eq!(ty, "Float64");
        data.chunks(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
            .collect::<Vec<f64>>()
    };
    assert_eq!(points.len(), 3 * mesh.n_nodes());
    let u = f64s(&bytes, "displacement");
    for n in 0..mesh.n_nodes() {
        let x = mesh.node(n);
        assert_eq!(points[3 * n..3 * n + 3], [x[0], x[1], 0.0], "node {n}");
        assert_eq!(
            u[3 * n..3 * n + 3],
            [solution.u[2 * n], solution.u[2 * n + 1], 0.0],
            "node {n}"
        );
    }
    let pressure = f64s(&bytes, "contact_pressure");
    let normal = i32s(&bytes, "contact_normal_state");
    for c in &solution.contact {
        assert_eq!(pressure[c.node as usize], c.pressure);
        assert_eq!(normal[c.node as usize], c.normal_state.code());
    }
    let contact_nodes = solution.contact.len();
    assert_eq!(normal.iter().filter(|&&s| s >= 0).count(), contact_nodes);

    let e = solution_vtu(&problem, &solution, "x", f64::NAN)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("load factor") && e.contains("NaN"), "{e}");
}

#[test]
fn friction_traction_and_interface_force_both_act_on_the_body() {
    let (problem, solution) = solved(1.0);
    let bytes = solution_vtu(&problem, &solution, "t", 1.0)
        .unwrap()
        .to_bytes();
    let traction = f64s(&bytes, "friction_traction");
    let force = f64s(&bytes, "interface_force");
    let state = i32s(&bytes, "contact_friction_state");
    let normal = f64s(&bytes, "contact_normal");
    let mut sliding = 0;
    for c in &solution.contact {
        let v = c.node as usize;
        // The bottom's outward normal.
        assert_eq!(&normal[3 * v..3 * v + 3], &[0.0, -1.0, 0.0], "node {v}");
        assert!(c.pressure > 0.0, "node {v} is pressed");
        assert!(force[3 * v + 1] > 0.0, "node {v}: the foundation pushes up");
        if c.friction_state == FrictionState::Slip {
            sliding += 1;
            assert_eq!(state[v], 2);
            assert!(solution.u[2 * v] > 0.0, "node {v} slides to the right");
            assert!(
                traction[3 * v] < 0.0,
                "node {v}: traction {}",
                traction[3 * v]
            );
            assert!(force[3 * v] < 0.0, "node {v}: force {}", force[3 * v]);
            // Tangential force = weight × tangential traction (same sign convention).
            let rel = (force[3 * v] - c.weight * traction[3 * v]).abs() / force[3 * v].abs();
            assert!(rel < 1e-12, "node {v}: {rel}");
        }
    }
    assert_eq!(sliding, solution.contact.len(), "all bottom nodes slide");
    // No load: interface forces and reactions balance.
    for k in 0..2 {
        let f: f64 = (0..problem.mesh().n_nodes())
            .map(|v| force[3 * v + k])
            .sum();
        let r: f64 = solution.reactions.iter().skip(k).step_by(2).sum();
        assert!(
            (f + r).abs() <= 1e-8 * f.abs().max(r.abs()),
            "component {k}: {f} + {r}"
        );
    }
}

/// The Python interpreter of the reader checks: `$HEMICONTACT_PYTHON`, else `python3`.
fn python() -> String {
    std::env::var("HEMICONTACT_PYTHON").unwrap_or_else(|_| "python3".to_string())
}

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hemicontact-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs `tests/python/SCRIPT` with `args`. Returns false (after announcing the skip, or
/// failing under `CI=true`) if the interpreter cannot import vtk; panics if a check fails.
fn run_check(script: &str, args: &[&Path]) -> bool {
    use std::io::Write as _;
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/python")
        .join(script);
    let out = Command::new(python())
        .arg(&path)
        .args(args)
        .output()
        .expect("the Python interpreter runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    if out.status.code() == Some(77) {
        assert!(
            std::env::var("CI").as_deref() != Ok("true"),
            "CI=true and `{}` cannot import vtk: {stderr}; .ci/run installs it with \
             scripts/install-test-deps.sh and sets HEMICONTACT_PYTHON",
            python()
        );
        let _ = writeln!(
            std::io::stderr().lock(),
            "\n*** SKIPPED {script}: `{}` cannot import vtk and numpy. This run is NO evidence \
             that VTK reads the files. Install the readers with `bash \
             scripts/install-test-deps.sh target/test-venv` and set \
             HEMICONTACT_PYTHON=$PWD/target/test-venv/bin/python (an absolute path). ***\n",
            python()
        );
        return false;
    }
    assert!(
        out.status.success(),
        "{script} failed (exit {:?}):\n{}{stderr}",
        out.status.code(),
        String::from_utf8_lossy(&out.stdout)
    );
    true
}

#[test]
fn vtk_reads_the_file_as_written() {
    let (problem, solution) = solved(1.0);
    let dir = scratch("vtk-read");
    let file = dir.join("solution.vtu");
    solution_vtu(&problem, &solution, "block pushed sideways", 0.75)
        .unwrap()
        .write(&file)
        .unwrap();
    let mesh = problem.mesh();
    let points: Vec<[f64; 3]> = (0..mesh.n_nodes())
        .map(|n| [mesh.node(n)[0], mesh.node(n)[1], 0.0])
        .collect();
    let u: Vec<[f64; 3]> = solution.u.chunks(2).map(|c| [c[0], c[1], 0.0]).collect();
    let expected = serde_json::json!({
        "points": points,
        "displacement": u,
        "cells": mesh.n_cells(),
        "point_fields": POINT_FIELDS,
        "cell_fields": CELL_FIELDS,
        "title": "block pushed sideways",
        "time": 0.75,
        "version": env!("CARGO_PKG_VERSION"),
    });
    let json = dir.join("expected.json");
    std::fs::write(&json, serde_json::to_string(&expected).unwrap()).unwrap();
    run_check("check_vtk.py", &[&file, &json]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn pvd_collection_of_load_factors_is_read_by_vtk() {
    let dir = scratch("pvd");
    let factors = [0.25, 0.5, 1.0];
    let mut entries = Vec::new();
    for (k, &t) in factors.iter().enumerate() {
        let (problem, solution) = solved(t);
        let rel = format!("step-{k}/solution.vtu");
        std::fs::create_dir_all(dir.join(format!("step-{k}"))).unwrap();
        solution_vtu(&problem, &solution, "block pushed sideways", t)
            .unwrap()
            .write(&dir.join(&rel))
            .unwrap();
        entries.push((t, rel));
    }
    let list: Vec<(f64, &str)> = entries.iter().map(|(t, f)| (*t, f.as_str())).collect();
    let file = dir.join("steps.pvd");
    pvd::write(&file, &list).unwrap();
    let (px, py) = (PUSH[0].to_string(), PUSH[1].to_string());
    run_check(
        "check_pvd.py",
        &[&file, Path::new("3"), Path::new(&px), Path::new(&py)],
    );
    let _ = std::fs::remove_dir_all(&dir);
}
