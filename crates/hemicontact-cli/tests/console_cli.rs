//! # Verification: what the command-line program prints, and its small commands
//!
//! The binary runs with standard error captured (not a terminal), as in a log or CI.
//!
//! - **Off a terminal, one line per phase**: `solve` prints exactly three lines on standard
//!   error (what is solved, how the solve ended, where the results went) and no terminal
//!   control sequences; `-v` adds one line per outer iteration, numbered 1…N with N the
//!   outer iterations of `summary.json`; `--quiet` prints nothing at all on success and
//!   still writes the results.
//! - **`--levels`** accepts the space-separated form its help shows and the
//!   comma-separated one, with the same study (the levels solved, from `summary.json`).
//! - **`mu = 0.3`** is the constant coefficient `{ law = "constant", mu = 0.3 }`: both files
//!   give byte-identical `solution.vtu` and `contact.csv`.
//! - **A missing file** is reported on one line that names it once.
//! - **`check` prints the laws in words**: the paper's exponential law with its parameters
//!   and units, and the Lipschitz constant of μ(r) = (a − b) e^(−βr) + b, which is
//!   L_μ = (a − b) β = 0.3 · 100 = 30, printed as `30` (not `30.000000000000004`).
//! - **The `paper` header** gives both mesh sizes of n = 8 on the 4 × 4 square: element
//!   area 16 / (2 · 64) = 0.125 m² and square side 4 / 8 = 0.5 m.
//! - **`bench --paper`** says what it solves per mesh size and how each repetition went.
//! - **`completions`** prints a non-empty script naming the program and its commands for
//!   bash, zsh and fish; **`schema`** prints a JSON Schema (valid JSON, an object schema
//!   whose properties are the scenario's top-level tables).
//! - **`scenarios/paper3d.toml` reaches its walls** at its own resolution (contact points
//!   in contact), which its gap was chosen for.

use std::path::{Path, PathBuf};

use crate::common::{assert_success, repo_root, run, text};

/// A small scenario with frictional contact on the left side; `MU` is replaced by the
/// coefficient.
const WITH_CONTACT: &str = r#"title = "console test"

[mesh]
kind = "rectangle"
size = [4.0, 4.0]
n = [8, 8]

[material]
young = 2000.0
poisson = 0.3

[[dirichlet]]
part = "bottom"

[[loads.traction]]
part = "top"
value = [0.0, -900.0]

[[contact]]
part = "left"
gap = 0.0
c_nu = 10000.0
[contact.friction]
bound = "coulomb"
mu = MU
"#;

fn scenario(dir: &Path, name: &str, mu: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, WITH_CONTACT.replace("MU", mu)).unwrap();
    path
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

#[test]
fn solve_off_a_terminal_prints_one_line_per_phase() {
    let tmp = tempfile::tempdir().unwrap();
    let file = scenario(tmp.path(), "s.toml", "0.3");
    let out = run(tmp.path(), &["solve", file.to_str().unwrap(), "--out", "r"]);
    assert_success(&out);
    let stderr = text(&out.stderr);
    let lines: Vec<&str> = stderr.lines().filter(|l| !l.starts_with("note:")).collect();
    assert_eq!(lines.len(), 4, "{stderr}");
    assert!(lines[0].starts_with("solving ") && lines[0].contains("s.toml"));
    assert!(
        lines[0].contains("81 nodes, 128 triangles, 162 DOFs"),
        "{}",
        lines[0]
    );
    let outer = summary(&tmp.path().join("r"))["report"]["outer"]
        .as_array()
        .unwrap()
        .len();
    assert!(
        lines[1].starts_with(&format!("solved in {outer} outer iterations")),
        "{}",
        lines[1]
    );
    assert!(lines[2].starts_with("results written in "), "{}", lines[2]);
    assert!(lines[3].starts_with("written to r ("), "{}", lines[3]);
    assert!(
        !stderr.contains('\u{1b}'),
        "terminal control sequences:\n{stderr}"
    );
}

#[test]
fn verbose_prints_every_outer_iteration() {
    let tmp = tempfile::tempdir().unwrap();
    let file = scenario(tmp.path(), "s.toml", "0.3");
    let out = run(
        tmp.path(),
        &["-v", "solve", file.to_str().unwrap(), "--out", "r"],
    );
    assert_success(&out);
    let stderr = text(&out.stderr);
    let outer = summary(&tmp.path().join("r"))["report"]["outer"]
        .as_array()
        .unwrap()
        .len();
    assert!(outer > 1, "a friction problem needs outer iterations");
    let iterations: Vec<&str> = stderr
        .lines()
        .filter(|l| l.trim_start().starts_with("outer "))
        .collect();
    assert_eq!(iterations.len(), outer, "{stderr}");
    for (k, line) in iterations.iter().enumerate() {
        assert!(
            line.trim_start()
                .starts_with(&format!("outer {}: residual ", k + 1)),
            "{line}"
        );
    }
}

#[test]
fn quiet_prints_nothing_on_success() {
    let tmp = tempfile::tempdir().unwrap();
    let file = scenario(tmp.path(), "s.toml", "0.3");
    for args in [
        vec!["--quiet", "solve", file.to_str().unwrap(), "--out", "r"],
        vec!["check", "-q", file.to_str().unwrap()],
        vec!["-q", "paper", "--n", "4", "--out", "p"],
    ] {
        let out = run(tmp.path(), &args);
        assert_success(&out);
        assert!(out.stdout.is_empty(), "{args:?}: {}", text(&out.stdout));
        assert!(out.stderr.is_empty(), "{args:?}: {}", text(&out.stderr));
    }
    assert!(tmp.path().join("r/solution.vtu").is_file());
    assert!(tmp.path().join("p/comparison.png").is_file());
    // Errors are still printed.
    let out = run(tmp.path(), &["-q", "solve", "nope.toml"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(text(&out.stderr).contains("nope.toml"));
}

#[test]
fn levels_accept_spaces_and_commas() {
    let tmp = tempfile::tempdir().unwrap();
    let file = repo_root().join("scenarios/paper-elastic.toml");
    let file = file.to_str().unwrap();
    let mut tables = Vec::new();
    for (out_dir, levels) in [("a", vec!["2", "4"]), ("b", vec!["2,4"])] {
        let mut args = vec!["convergence", file, "--levels"];
        args.extend(&levels);
        args.extend(["--reference", "8", "--out", out_dir]);
        let out = run(tmp.path(), &args);
        assert_success(&out);
        let study = summary(&tmp.path().join(out_dir));
        let ns: Vec<u64> = study["studies"][0]["levels"]
            .as_array()
            .unwrap()
            .iter()
            .map(|l| l["n"].as_u64().unwrap())
            .collect();
        assert_eq!(ns, [2, 4], "{study:#}");
        assert_eq!(study["levels"], serde_json::json!([2, 4]));
        tables.push(ns);
    }
    assert_eq!(tables[0], tables[1]);
}

#[test]
fn a_number_for_mu_is_the_constant_law() {
    let tmp = tempfile::tempdir().unwrap();
    let short = scenario(tmp.path(), "short.toml", "0.3");
    let table = scenario(
        tmp.path(),
        "table.toml",
        r#"{ law = "constant", mu = 0.3 }"#,
    );
    for (file, out_dir) in [(&short, "short"), (&table, "table")] {
        assert_success(&run(
            tmp.path(),
            &["solve", file.to_str().unwrap(), "--out", out_dir],
        ));
    }
    // The friction law matters: points are in contact, and some slip.
    let s = summary(&tmp.path().join("short"));
    assert!(s["contact_active"].as_u64().unwrap() > 0, "{s:#}");
    assert!(s["contact_slip"].as_u64().unwrap() > 0, "{s:#}");
    for name in ["solution.vtu", "contact.csv"] {
        let a = std::fs::read(tmp.path().join("short").join(name)).unwrap();
        let b = std::fs::read(tmp.path().join("table").join(name)).unwrap();
        assert!(a == b, "{name} differs");
    }
    let check = run(tmp.path(), &["check", short.to_str().unwrap()]);
    assert_success(&check);
    assert!(text(&check.stdout).contains("constant μ = 0.3"));
    // A wrong value names both forms.
    let bad = scenario(tmp.path(), "bad.toml", r#""high""#);
    let out = run(tmp.path(), &["check", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = text(&out.stderr);
    assert!(
        stderr.contains("a number (a constant μ") && stderr.contains("law = \"exponential\""),
        "{stderr}"
    );
}

#[test]
fn missing_file_is_reported_once() {
    let tmp = tempfile::tempdir().unwrap();
    for cmd in ["check", "solve", "convergence"] {
        let out = run(tmp.path(), &[cmd, "nope.toml"]);
        assert_eq!(out.status.code(), Some(1));
        let stderr = text(&out.stderr);
        assert_eq!(stderr.lines().count(), 1, "{cmd}: {stderr}");
        assert_eq!(stderr.matches("nope.toml").count(), 1, "{cmd}: {stderr}");
        assert!(stderr.starts_with("error: "), "{cmd}: {stderr}");
    }
}

#[test]
fn check_prints_the_laws_in_words() {
    let tmp = tempfile::tempdir().unwrap();
    let file = repo_root().join("scenarios/paper.toml");
    let out = run(tmp.path(), &["check", file.to_str().unwrap()]);
    assert_success(&out);
    let stdout = text(&out.stdout);
    for expected in [
        "limited compressibility |tr ε| ≤ θ with θ = 0.16",
        "penalty C_κ = 10000 Pa",
        "normal compliance p = c_ν (u_ν − g)_+ with c_ν = 10000 Pa/m",
        "Coulomb-type bound",
        "exponential slip weakening μ(r) = (a − b) e^(−βr) + b with a = 0.4, b = 0.1, β = 100 1/m",
        "L_μ = 30,",
    ] {
        assert!(stdout.contains(expected), "`{expected}` not in:\n{stdout}");
    }
    for debug in [
        "Exponential {",
        "LimitedCompressibility",
        "30.000000000000004",
    ] {
        assert!(!stdout.contains(debug), "`{debug}` in:\n{stdout}");
    }
}

#[test]
fn missing_nonconvex_parameter_names_its_range() {
    let tmp = tempfile::tempdir().unwrap();
    let file = scenario(tmp.path(), "a.toml", "0.3");
    let text_in = std::fs::read_to_string(&file)
        .unwrap()
        .replace("mu = 0.3", "mu = 0.3\npotential = \"nonconvex\"");
    std::fs::write(&file, text_in).unwrap();
    let out = run(tmp.path(), &["check", file.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = text(&out.stderr);
    assert!(stderr.contains("0 < a < 1"), "{stderr}");
    assert!(!stderr.contains("> 0"), "{stderr}");
}

#[test]
fn paper_header_gives_area_and_edge() {
    let tmp = tempfile::tempdir().unwrap();
    let out = run(tmp.path(), &["paper", "--n", "8", "--out", "p"]);
    assert_success(&out);
    let stdout = text(&out.stdout);
    let header = stdout.lines().next().unwrap();
    assert!(
        header.contains("h = 0.125 m² (element area)") && header.contains("edge h = 0.5 m"),
        "{header}"
    );
    // Off a terminal: per case what is solved, how it ended and how long writing took,
    // then the comparison figure and where it all went.
    let stderr = text(&out.stderr);
    let phases: Vec<&str> = stderr.lines().filter(|l| !l.starts_with("note:")).collect();
    assert_eq!(phases.len(), 8, "{stderr}");
    for case in [0, 3] {
        assert!(phases[case + 2].contains("results written in "), "{stderr}");
    }
    assert!(
        phases[6].starts_with("comparison figure written in "),
        "{stderr}"
    );
    assert!(phases[7].starts_with("written to p ("), "{stderr}");
}

#[test]
fn bench_paper_says_what_it_solves() {
    let tmp = tempfile::tempdir().unwrap();
    let out = run(
        tmp.path(),
        &["bench", "--paper", "--n", "4", "8", "--repeat", "2"],
    );
    assert_success(&out);
    let stderr = text(&out.stderr);
    let lines: Vec<&str> = stderr.lines().filter(|l| !l.starts_with("note:")).collect();
    // Per mesh size: what is solved, then one line per repetition.
    assert_eq!(lines.len(), 6, "{stderr}");
    assert!(lines[0].starts_with("n = 4: 2 linear and 2 nonlinear solves"));
    assert!(lines[1].starts_with("n = 4, repetition 1/2: linear "));
    assert!(lines[2].starts_with("n = 4, repetition 2/2: linear "));
    assert!(lines[3].starts_with("n = 8: 2 linear and 2 nonlinear solves"));
    // The table has one row per size.
    assert_eq!(
        text(&out.stdout).lines().count(),
        4,
        "{}",
        text(&out.stdout)
    );
}

#[test]
fn completions_for_each_shell() {
    let tmp = tempfile::tempdir().unwrap();
    for shell in ["bash", "zsh", "fish"] {
        let out = run(tmp.path(), &["completions", shell]);
        assert_success(&out);
        let script = text(&out.stdout);
        assert!(script.len() > 1000, "{shell}: {script}");
        assert!(
            script.contains("hemicontact") && script.contains("convergence"),
            "{shell}: {script}"
        );
    }
    assert_eq!(
        run(tmp.path(), &["completions", "cmd.exe"]).status.code(),
        Some(2)
    );
}

#[test]
fn schema_is_a_json_schema_of_the_scenario() {
    let tmp = tempfile::tempdir().unwrap();
    let out = run(tmp.path(), &["schema"]);
    assert_success(&out);
    let schema: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(schema["$schema"]
        .as_str()
        .unwrap()
        .contains("json-schema.org"));
    assert_eq!(schema["type"], "object");
    let keys: Vec<&String> = schema["properties"].as_object().unwrap().keys().collect();
    for table in [
        "title",
        "mesh",
        "material",
        "locking",
        "dirichlet",
        "loads",
        "contact",
        "solver",
        "output",
    ] {
        assert!(keys.iter().any(|k| *k == table), "{table} not in {keys:?}");
    }
}

#[test]
fn paper3d_reaches_its_walls() {
    let tmp = tempfile::tempdir().unwrap();
    let file = repo_root().join("scenarios/paper3d.toml");
    let out = run(tmp.path(), &["solve", file.to_str().unwrap(), "--out", "r"]);
    assert_success(&out);
    let s = summary(&tmp.path().join("r"));
    let contact = s["contact_active"].as_u64().unwrap();
    assert!(contact > 0, "no contact point in contact: {s:#}");
}
