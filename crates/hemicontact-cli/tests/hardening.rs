//! Hardening of the command-line program: oversized requests fail fast with a memory
//! estimate; Ctrl-C leaves no partial files and exits with 130.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::process::Command;
use std::time::{Duration, Instant};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_hemicontact"))
}

/// A mesh whose solve would need more memory than the machine has is refused before
/// anything is allocated, naming the field and the estimate.
#[test]
fn oversized_mesh_fails_fast_with_memory_estimate() {
    let dir = tempfile::tempdir().unwrap();
    let text = hemicontact::scenario::builtin::paper(4096, 1.0e4);
    let file = dir.path().join("huge.toml");
    std::fs::write(&file, text).unwrap();
    let start = Instant::now();
    let out = bin().arg("check").arg(&file).output().unwrap();
    let elapsed = start.elapsed();
    let stderr = String::from_utf8_lossy(&out.stderr);
    // A 4096 × 4096 paper square needs about 62 GiB (estimate): more than any machine
    // this runs on in CI (24 GiB).
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("mesh.n") && stderr.contains("GiB"),
        "{stderr}"
    );
    assert!(stderr.contains("--ignore-memory-limit"), "{stderr}");
    assert!(elapsed < Duration::from_secs(2), "took {elapsed:?}");
}

/// Ctrl-C during a solve: exit code 130 and no file, partial or temporary, in the output
/// folder.
#[test]
fn interrupt_exits_130_and_leaves_no_partial_files() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("out");
    let mut child = bin()
        .args(["paper", "--n", "512", "--out"])
        .arg(&out_dir)
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let code = child.wait().unwrap().code();
    assert_eq!(code, Some(130));
    let mut files = Vec::new();
    for case in ["locking", "no-locking"] {
        if let Ok(entries) = std::fs::read_dir(out_dir.join(case)) {
            files.extend(entries.flatten().map(|e| e.path()));
        }
    }
    assert!(files.is_empty(), "files left behind: {files:?}");
}

/// A body whose rigid motion is not blocked (rollers in x only: it can translate in y and
/// rotate about the bottom's midpoint) has a singular stiffness matrix: this is found
/// before the solve and reported, naming the free motions, as an error (exit 1), and
/// nothing is written.
#[test]
fn singular_stiffness_is_reported_not_panicked() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("floating.toml");
    std::fs::write(
        &file,
        r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [4, 4]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "bottom"
components = ["x"]
[[loads.traction]]
part = "top"
value = [0.0, -1.0]
"#,
    )
    .unwrap();
    let out_dir = dir.path().join("out");
    let out = bin()
        .arg("solve")
        .arg(&file)
        .arg("--out")
        .arg(&out_dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("singular")
            && stderr.contains("translation along y")
            && stderr.contains("rotation about z through (0.5, 0)"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    let written: Vec<_> = std::fs::read_dir(&out_dir)
        .map(|d| d.flatten().map(|e| e.file_name()).collect())
        .unwrap_or_default();
    assert!(written.is_empty(), "files written: {written:?}");
}
