//! `solve` of a scenario with `[loading]`: one result folder per step, the ParaView
//! collection listing them in step order with the load factors as time values, one row of
//! `load_path.csv` per step, and a step that does not converge ending the path with exit
//! code 3.

use std::path::Path;

use crate::common::{assert_success, run, text};

const BLOCK: &str = r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [4, 4]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "bottom"
[[loads.traction]]
part = "top"
value = [0.0, -300.0]
[[contact]]
part = "right"
gap = 0.01
c_nu = 1.0e4
"#;

fn solve(dir: &Path, content: &str) -> (std::process::Output, std::path::PathBuf) {
    let path = dir.join("path.toml");
    std::fs::write(&path, content).unwrap();
    let out_dir = dir.join("out");
    let out = run(
        dir,
        &[
            "solve",
            path.to_str().unwrap(),
            "--out",
            out_dir.to_str().unwrap(),
        ],
    );
    (out, out_dir)
}

fn summary(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn load_path_writes_each_step_a_collection_and_a_table() {
    let tmp = tempfile::tempdir().unwrap();
    let (out, dir) = solve(
        tmp.path(),
        &format!("{BLOCK}[loading]\nfactors = [0.25, 0.5, 1.0]\n"),
    );
    assert_success(&out);
    for step in ["step-001", "step-002", "step-003"] {
        for file in ["solution.vtu", "contact.csv", "summary.json"] {
            assert!(dir.join(step).join(file).is_file(), "{step}/{file}");
        }
        let s = summary(&dir.join(step).join("summary.json"));
        assert_eq!(s["converged"], serde_json::Value::Bool(true));
    }
    assert!(!dir.join("step-004").exists());
    // No single-solve results at the root: the steps are the results.
    assert!(!dir.join("solution.vtu").exists());
    let pvd = std::fs::read_to_string(dir.join("solution.pvd")).unwrap();
    let datasets: Vec<&str> = pvd.lines().filter(|l| l.contains("<DataSet")).collect();
    assert_eq!(datasets.len(), 3, "{pvd}");
    for (line, (t, step)) in datasets.iter().zip([
        ("0.25", "step-001"),
        ("0.5", "step-002"),
        ("1.0", "step-003"),
    ]) {
        assert!(line.contains(&format!("timestep=\"{t}\"")), "{line}");
        assert!(
            line.contains(&format!("file=\"{step}/solution.vtu\"")),
            "{line}"
        );
    }
    // Each step's VTU carries its load factor as TimeValue.
    let vtu = std::fs::read(dir.join("step-002/solution.vtu")).unwrap();
    assert!(
        vtu.windows(9).any(|w| w == b"TimeValue"),
        "TimeValue in the step's FieldData"
    );
    let csv = std::fs::read_to_string(dir.join("load_path.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 4, "header and one row per step: {csv}");
    assert!(lines[0].starts_with("load_factor,contact_force_x,contact_force_y,"));
    let factors: Vec<f64> = lines[1..]
        .iter()
        .map(|l| l.split(',').next().unwrap().parse().unwrap())
        .collect();
    assert_eq!(factors, vec![0.25, 0.5, 1.0]);
    assert!(lines[1..].iter().all(|l| l.ends_with(",true")), "{csv}");
}

#[test]
fn the_figures_are_drawn_for_the_last_step_only() {
    // 100 steps: 100 step folders (over 300 files, flushed in one go at the commit).
    let tmp = tempfile::tempdir().unwrap();
    let (out, dir) = solve(tmp.path(), &format!("{BLOCK}[loading]\nsteps = 100\n"));
    assert_success(&out);
    let figures = [
        "deformed.svg",
        "deformed.png",
        "interface.svg",
        "interface.png",
    ];
    for k in 1..=100 {
        let step = dir.join(format!("step-{k:03}"));
        for file in ["solution.vtu", "contact.csv", "summary.json"] {
            assert!(step.join(file).is_file(), "step {k}: {file}");
        }
        for figure in figures {
            assert_eq!(step.join(figure).is_file(), k == 100, "step {k}: {figure}");
        }
        // The summary lists exactly the files of its folder.
        let listed = summary(&step.join("summary.json"))["files"]
            .as_array()
            .unwrap()
            .len();
        assert_eq!(
            listed,
            std::fs::read_dir(&step).unwrap().count(),
            "step {k}"
        );
    }
    // The last step's figures are those of a plain solve of the full load.
    std::fs::create_dir(tmp.path().join("plain")).unwrap();
    let (plain, plain_dir) = solve(&tmp.path().join("plain"), BLOCK);
    assert_success(&plain);
    let svg = |d: &Path| std::fs::read_to_string(d.join("interface.svg")).unwrap();
    assert_eq!(
        svg(&dir.join("step-100")).lines().count(),
        svg(&plain_dir).lines().count()
    );
}

#[test]
fn a_step_that_does_not_converge_ends_the_path_with_code_3() {
    let tmp = tempfile::tempdir().unwrap();
    let (out, dir) = solve(
        tmp.path(),
        &format!(
            "{BLOCK}[loading]\nsteps = 3\n[solver.newton]\nresidual_tolerance = 1e-300\n\
             max_iterations = 2\n"
        ),
    );
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(stderr.contains("did not converge"), "{stderr}");
    let s = summary(&dir.join("step-001/summary.json"));
    assert_eq!(s["converged"], serde_json::Value::Bool(false));
    assert!(!dir.join("step-002").exists(), "the path stops at step 1");
    // The step that ends the path is the last one: it has the figures.
    assert!(dir.join("step-001/deformed.png").is_file());
    let csv = std::fs::read_to_string(dir.join("load_path.csv")).unwrap();
    assert_eq!(csv.lines().count(), 2, "{csv}");
    assert!(csv.lines().nth(1).unwrap().ends_with(",false"), "{csv}");
}

#[test]
fn bad_loading_is_rejected_naming_the_field() {
    let tmp = tempfile::tempdir().unwrap();
    let (out, dir) = solve(
        tmp.path(),
        &format!("{BLOCK}[loading]\nfactors = [0.5, 0.25]\n"),
    );
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("loading.factors[1]"), "{stderr}");
    assert!(!dir.join("load_path.csv").exists());
}
