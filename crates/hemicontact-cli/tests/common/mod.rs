//! Helpers shared by the command-line tests: the program under test, the repository root,
//! runs and their output, and the deterministic pseudo-random generator of the library's
//! tests (included by path: one definition for both crates).
//!
//! The test binaries declare this module once (`tests/main.rs`, `tests/mpi_cli.rs`); each
//! test module uses part of it.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

#[path = "../../../hemicontact/tests/common/rng.rs"]
mod rng;

#[allow(unused_imports)] // Not every test file draws random numbers.
pub use rng::Rng;

/// The `hemicontact` binary of this build, as a command to add arguments to.
pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_hemicontact"))
}

/// The root of the repository (where `scenarios/` is).
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs the binary with `args` in the folder `cwd`.
pub fn run(cwd: &Path, args: &[&str]) -> Output {
    bin()
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("the binary runs")
}

/// Bytes of a standard stream as text (invalid UTF-8 replaced).
pub fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Asserts that a run succeeded, showing its exit code and both streams otherwise.
#[track_caller]
pub fn assert_success(out: &Output) {
    assert!(
        out.status.success(),
        "exit {:?}\nstdout:\n{}\nstderr:\n{}",
        out.status.code(),
        text(&out.stdout),
        text(&out.stderr)
    );
}
