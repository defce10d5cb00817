//! # Verification: notes on inputs and results that make no sense, through the program
//!
//! - **Small deformation broken**: a block whose bottom must reach a rigid plane 2 m up
//!   while its top is clamped at y = 1 (so its bottom moves by at least 2 m and its cells
//!   turn inside out) is solved, and `solve` says so on standard error and in
//!   `summary.json` (`notes` and `small_deformation`); along a load path, the first step
//!   noted is printed with the count of later ones, and each step's `summary.json` has its
//!   notes. A block pressed by 1 % of its modulus has no such note.
//! - **An obstacle smaller than the mesh** (a circle of radius 1 mm poking 0.5 mm into the
//!   block between two nodes 0.125 m apart) is noted by `check` and `solve`, and recorded
//!   in `summary.json`.

use crate::common::{assert_success, run, text};
use std::path::Path;

const DEEP: &str = r#"
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

/// `summary.json` of the folder `dir`.
fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

fn notes(summary: &serde_json::Value) -> Vec<String> {
    summary["notes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap().to_string())
        .collect()
}

#[test]
fn a_deformation_too_large_for_the_model_is_noted() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("deep.toml"), DEEP).unwrap();
    let out = run(tmp.path(), &["solve", "deep.toml", "--out", "r"]);
    assert_success(&out);
    let stderr = text(&out.stderr);
    for what in [
        "note: small deformation: the largest strain",
        "note: small deformation: the largest displacement",
        "note: small deformation: the displacement turns",
    ] {
        assert!(stderr.contains(what), "{what}: {stderr}");
    }
    let s = summary(&tmp.path().join("r"));
    let n = notes(&s);
    assert_eq!(
        n.iter()
            .filter(|n| n.starts_with("small deformation"))
            .count(),
        3,
        "{n:?}"
    );
    // The bottom nodes end at y ≥ 2: displaced by at least 2 m, 2/√2 of the diagonal.
    let ratio = s["small_deformation"]["max_displacement_ratio"]
        .as_f64()
        .unwrap();
    assert!(ratio >= 2f64.sqrt() * (1.0 - 1e-6), "{ratio}");
    assert!(s["small_deformation"]["inverted_cells"].as_u64().unwrap() > 0);
}

#[test]
fn a_load_path_prints_the_first_step_noted() {
    let tmp = tempfile::tempdir().unwrap();
    // The plane's position is not a load: every step is as deep.
    std::fs::write(
        tmp.path().join("deep.toml"),
        format!("{DEEP}[loading]\nsteps = 3\n"),
    )
    .unwrap();
    let out = run(tmp.path(), &["solve", "deep.toml", "--out", "r"]);
    assert_success(&out);
    let stderr = text(&out.stderr);
    assert!(
        stderr.contains("note: step 1/3 (load factor 0.333333): small deformation")
            && stderr.contains("note: 2 later step(s) have such notes too, the last at step 3/3"),
        "{stderr}"
    );
    for step in ["step-001", "step-002", "step-003"] {
        let n = notes(&summary(&tmp.path().join("r").join(step)));
        assert!(
            n.iter().any(|n| n.starts_with("small deformation")),
            "{step}: {n:?}"
        );
    }
}

#[test]
fn a_small_deformation_has_no_such_note() {
    let tmp = tempfile::tempdir().unwrap();
    // E = 1000 Pa pressed by 10 Pa: strains about 1 %.
    std::fs::write(
        tmp.path().join("small.toml"),
        DEEP.replace(
            "obstacle = { kind = \"plane\", point = [0.0, 2.0], normal = [0.0, 1.0] }",
            "obstacle = { kind = \"plane\", point = [0.0, 0.0], normal = [0.0, 1.0] }\n\
             [[loads.traction]]\npart = \"right\"\nvalue = [-10.0, 0.0]",
        ),
    )
    .unwrap();
    let out = run(tmp.path(), &["solve", "small.toml", "--out", "r"]);
    assert_success(&out);
    assert!(
        !text(&out.stderr).contains("small deformation"),
        "{}",
        text(&out.stderr)
    );
    let s = summary(&tmp.path().join("r"));
    assert!(notes(&s).is_empty(), "{s}");
    assert!(s["small_deformation"]["max_strain"].as_f64().unwrap() < 0.1);
}

#[test]
fn an_obstacle_smaller_than_the_mesh_is_noted() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(
        tmp.path().join("tiny.toml"),
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
value = [0.0, 0.0]
[[contact]]
part = "bottom"
law = "signorini"
obstacle = { kind = "circle", center = [0.5625, -0.0005], radius = 0.001 }
"#,
    )
    .unwrap();
    let check = run(tmp.path(), &["check", "tiny.toml"]);
    assert_success(&check);
    let out = run(tmp.path(), &["solve", "tiny.toml", "--out", "r"]);
    assert_success(&out);
    for stderr in [text(&check.stderr), text(&out.stderr)] {
        assert!(
            stderr.contains(
                "note: contact[0] (part `bottom`): the obstacle's radius of curvature R = 0.001 m"
            ) && stderr.contains("the obstacle reaches 0.0005 m into the body between"),
            "{stderr}"
        );
    }
    let n = notes(&summary(&tmp.path().join("r")));
    assert_eq!(
        n.iter().filter(|n| n.starts_with("contact[0]")).count(),
        2,
        "{n:?}"
    );
}
