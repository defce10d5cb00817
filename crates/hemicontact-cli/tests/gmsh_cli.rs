//! # Verification: Gmsh meshes through the command-line program
//!
//! - **`check scenarios/half-disc.toml`** (a Gmsh mesh, resolved relative to the scenario
//!   file, from another working folder) succeeds, prints the sizes of the committed mesh
//!   (804 nodes) and the parts `contact` and `top`, and notes on standard error that the
//!   contact part shares its two end nodes with the Dirichlet part `top`.
//! - **`solve`** of it converges and writes the note into `summary.json`.
//! - **A bad mesh** makes `check` exit with code 1 (invalid input) and a message naming the
//!   mesh file, the line and the problem; a missing mesh file names the field `mesh.file`
//!   and the path; `convergence` refuses a read mesh (it cannot be refined).

use std::path::{Path, PathBuf};

use crate::common::{repo_root, run, text};

#[test]
fn check_half_disc_reads_the_mesh_next_to_the_scenario() {
    let tmp = tempfile::tempdir().unwrap();
    let scenario = repo_root().join("scenarios/half-disc.toml");
    let out = run(tmp.path(), &["check", scenario.to_str().unwrap()]);
    let (stdout, stderr) = (text(&out.stdout), text(&out.stderr));
    assert!(out.status.success(), "{stdout}\n{stderr}");
    assert!(stdout.contains("nodes      804"), "{stdout}");
    assert!(
        stdout.contains("contact") && stdout.contains("top"),
        "{stdout}"
    );
    assert!(
        stderr.contains("note: contact part `contact` shares 2 node(s) with Dirichlet part `top`"),
        "{stderr}"
    );
}

#[test]
fn solve_half_disc_converges_and_records_the_notes() {
    let tmp = tempfile::tempdir().unwrap();
    let scenario = repo_root().join("scenarios/half-disc.toml");
    let out_dir = tmp.path().join("out");
    let out = run(
        tmp.path(),
        &[
            "solve",
            scenario.to_str().unwrap(),
            "--out",
            out_dir.to_str().unwrap(),
        ],
    );
    assert!(
        out.status.success(),
        "{}\n{}",
        text(&out.stdout),
        text(&out.stderr)
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["converged"], serde_json::Value::Bool(true));
    assert_eq!(summary["sizes"]["nodes"].as_u64(), Some(804));
    let notes = summary["notes"].as_array().expect("notes");
    assert!(
        notes
            .iter()
            .any(|n| n.as_str().unwrap().contains("contact part `contact`")),
        "{notes:?}"
    );
    assert!(summary["contact_active"].as_u64().unwrap() > 10);
}

/// Writes a scenario using the mesh `mesh` (a path relative to the scenario's folder).
fn scenario_with_mesh(dir: &Path, mesh: &str) -> PathBuf {
    let path = dir.join("scenario.toml");
    std::fs::write(
        &path,
        format!(
            "[mesh]\nkind = \"gmsh\"\nfile = \"{mesh}\"\n[material]\nyoung = 1000.0\n\
             poisson = 0.3\n[[dirichlet]]\npart = \"bottom\"\n"
        ),
    )
    .unwrap();
    path
}

#[test]
fn check_with_a_bad_mesh_exits_1_naming_the_file() {
    let tmp = tempfile::tempdir().unwrap();
    let data = repo_root().join("crates/hemicontact/tests/data/gmsh");
    std::fs::copy(
        data.join("bad-quadrangle.msh"),
        tmp.path().join("quads.msh"),
    )
    .unwrap();
    let path = scenario_with_mesh(tmp.path(), "quads.msh");
    let out = run(tmp.path(), &["check", path.to_str().unwrap()]);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("quads.msh:46:") && stderr.contains("Quadrilateral 4"),
        "{stderr}"
    );
    assert!(stderr.contains("Mesh.ElementOrder = 1"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");

    let path = scenario_with_mesh(tmp.path(), "no-such.msh");
    let out = run(tmp.path(), &["check", path.to_str().unwrap()]);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("mesh.file") && stderr.contains("no-such.msh"),
        "{stderr}"
    );
}

#[test]
fn convergence_refuses_a_read_mesh() {
    let tmp = tempfile::tempdir().unwrap();
    let scenario = repo_root().join("scenarios/half-disc.toml");
    let out = run(
        tmp.path(),
        &["convergence", scenario.to_str().unwrap(), "--levels", "4,8"],
    );
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("a read mesh cannot be refined"), "{stderr}");
}
