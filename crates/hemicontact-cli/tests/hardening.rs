//! Hardening of the command-line program: oversized requests fail fast with a memory
//! estimate; Ctrl-C leaves no partial files and exits with 130; a device as scenario,
//! contradictory boundary conditions and a study without load are refused with a message.

use std::process::Command;
use std::time::{Duration, Instant};

use crate::common::bin;

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

/// Ctrl-C (SIGINT) during a solve, or SIGTERM (what `kill` and MPI launchers send):
/// exit code 130, a message saying the folder was left as it was, and nothing in the work
/// folder: no output folder, no temporary, no lock.
#[test]
fn interrupt_exits_130_and_leaves_no_partial_files() {
    for signal in ["-INT", "-TERM"] {
        let dir = tempfile::tempdir().unwrap();
        let out_dir = dir.path().join("out");
        let child = bin()
            .args(["paper", "--n", "512", "--out"])
            .arg(&out_dir)
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(1500));
        let status = Command::new("kill")
            .args([signal, &child.id().to_string()])
            .status()
            .unwrap();
        assert!(status.success());
        let out = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(130), "{signal}: {stderr}");
        assert!(stderr.contains("was left as it was"), "{signal}: {stderr}");
        let left: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .flatten()
            .map(|e| e.file_name())
            .collect();
        assert!(left.is_empty(), "{signal}: left behind: {left:?}");
    }
}

/// A device that never ends (`/dev/zero`) is refused at once as a scenario: it is not a
/// regular file.
#[test]
fn check_dev_zero_is_refused_at_once() {
    let start = Instant::now();
    let out = bin().args(["check", "/dev/zero"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("/dev/zero") && stderr.contains("not a regular file"),
        "{stderr}"
    );
    assert!(start.elapsed() < Duration::from_secs(2));
}

/// Contradictory Dirichlet values at the corner shared by two parts: exit 1, naming both
/// entries.
#[test]
fn contradictory_dirichlet_entries_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("corner.toml");
    std::fs::write(
        &file,
        "[mesh]\nkind = \"rectangle\"\nsize = [1.0, 1.0]\nn = [4, 4]\n\
         [material]\nyoung = 1000.0\npoisson = 0.3\n\
         [[dirichlet]]\npart = \"bottom\"\n\
         [[dirichlet]]\npart = \"left\"\ncomponents = [\"x\"]\nvalue = [0.1, 0.0]\n",
    )
    .unwrap();
    let out = bin().arg("check").arg(&file).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    for part in ["corner.toml", "dirichlet[1].value", "dirichlet[0]", "u_x"] {
        assert!(stderr.contains(part), "`{part}` missing: {stderr}");
    }
}

/// A convergence study of a scenario without load has nothing to measure (the relative
/// error is 0/0): exit 1 with that message, no NaN table, no output folder.
#[test]
fn convergence_without_load_has_nothing_to_measure() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("zero.toml");
    std::fs::write(
        &file,
        "[mesh]\nkind = \"rectangle\"\nsize = [1.0, 1.0]\nn = [4, 4]\n\
         [material]\nyoung = 1000.0\npoisson = 0.3\n[[dirichlet]]\npart = \"bottom\"\n",
    )
    .unwrap();
    let out = bin()
        .current_dir(dir.path())
        .arg("convergence")
        .arg(&file)
        .args(["--levels", "2,4", "--reference", "8", "--out", "conv"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stdout}{stderr}");
    assert!(stderr.contains("nothing to measure"), "{stderr}");
    assert!(!stdout.contains("NaN"), "{stdout}");
    assert!(!dir.path().join("conv").exists());
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

/// Started as several MPI processes (`mpirun -np 2`, seen through the variables OpenMPI and
/// MPICH set for each process), a build without PETSc refuses to run rather than solve the
/// whole problem once per process: rank 0 says why, every rank exits with 1 and writes
/// nothing. A launch of one process runs as usual.
#[cfg(not(feature = "petsc"))]
#[test]
fn several_mpi_processes_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("paper.toml");
    std::fs::write(&file, hemicontact::scenario::builtin::paper(4, 1.0e4)).unwrap();
    for (rank_var, size_var) in [
        ("OMPI_COMM_WORLD_RANK", "OMPI_COMM_WORLD_SIZE"),
        ("PMI_RANK", "PMI_SIZE"),
    ] {
        for rank in ["0", "1"] {
            let out = bin()
                .current_dir(dir.path())
                .args(["solve", "paper.toml", "--out", "out"])
                .env(rank_var, rank)
                .env(size_var, "2")
                .output()
                .unwrap();
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(1), "{rank_var}={rank}: {stderr}");
            if rank == "0" {
                assert!(
                    stderr.contains("`processes` = 2") && stderr.contains("distributed.md"),
                    "{stderr}"
                );
            } else {
                assert!(stderr.is_empty(), "rank {rank}: {stderr}");
            }
            assert!(!dir.path().join("out").exists());
        }
    }
    let one = bin()
        .current_dir(dir.path())
        .args(["solve", "paper.toml", "--out", "out"])
        .env("OMPI_COMM_WORLD_RANK", "0")
        .env("OMPI_COMM_WORLD_SIZE", "1")
        .output()
        .unwrap();
    assert_eq!(
        one.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&one.stderr)
    );
    assert!(dir.path().join("out/summary.json").exists());
}
