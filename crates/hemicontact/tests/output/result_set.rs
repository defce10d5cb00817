//! # Verification: the library's result-set writer
//!
//! - Nothing appears under the target before the commit; after it, the target holds exactly
//!   the files written (a previous set's other files are gone), with their content, and
//!   nothing else is left beside it (no staging folder, no lock).
//! - A set dropped without commit leaves the previous set untouched and nothing beside it.
//! - While a set is open, a second one for the same folder is refused with
//!   [`Error::OutputBusy`] naming the folder and this process's id; after the first is
//!   dropped, the folder can be written again.
//! - A set of more files than are flushed one by one ([`SYNC_EACH_LIMIT`], flushed with
//!   one flush of the file system) is put in place with every file and its content, in
//!   its sub-folders.
//! - File names must be plain relative names; `files_in` lists a sub-folder's files; a
//!   target without a name of its own (`.`) or a file in the way is refused.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::io::result_set::{ResultSet, SYNC_EACH_LIMIT};
use hemicontact::Error;
use std::path::{Path, PathBuf};

mod common;

/// A fresh empty folder under the system temporary folder.
fn work() -> PathBuf {
    common::fresh_dir("result-set")
}

/// Sorted names of the entries of `dir`.
fn names(dir: &Path) -> Vec<String> {
    let mut n: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    n.sort();
    n
}

#[test]
fn commit_replaces_the_previous_set_as_a_whole() {
    let w = work();
    let target = w.join("out");
    let mut first = ResultSet::begin(&target).unwrap();
    first.write("a.txt", b"first a").unwrap();
    first.write("only-first.txt", b"x").unwrap();
    assert!(!target.exists(), "visible before the commit");
    first.commit().unwrap();
    assert_eq!(names(&target), ["a.txt", "only-first.txt"]);

    let mut second = ResultSet::begin(&target).unwrap();
    second.write("a.txt", b"second a").unwrap();
    second.write("sub/b.txt", b"b").unwrap();
    // Until the commit, the first set is what a reader sees.
    assert_eq!(std::fs::read(target.join("a.txt")).unwrap(), b"first a");
    assert_eq!(second.files(), ["a.txt", "sub/b.txt"]);
    assert_eq!(second.files_in(""), ["a.txt"]);
    assert_eq!(second.files_in("sub"), ["b.txt"]);
    let paths = second.commit().unwrap();
    assert_eq!(paths, [target.join("a.txt"), target.join("sub/b.txt")]);
    assert_eq!(names(&target), ["a.txt", "sub"]);
    assert_eq!(std::fs::read(target.join("a.txt")).unwrap(), b"second a");
    assert_eq!(std::fs::read(target.join("sub/b.txt")).unwrap(), b"b");
    assert_eq!(names(&w), ["out"]);
    std::fs::remove_dir_all(&w).unwrap();
}

#[test]
fn a_set_dropped_without_commit_changes_nothing() {
    let w = work();
    let target = w.join("out");
    let mut first = ResultSet::begin(&target).unwrap();
    first.write("a.txt", b"kept").unwrap();
    first.commit().unwrap();
    let mut second = ResultSet::begin(&target).unwrap();
    second.write("a.txt", b"lost").unwrap();
    second.write("b.txt", b"lost").unwrap();
    drop(second);
    assert_eq!(names(&target), ["a.txt"]);
    assert_eq!(std::fs::read(target.join("a.txt")).unwrap(), b"kept");
    assert_eq!(names(&w), ["out"]);
    std::fs::remove_dir_all(&w).unwrap();
}

#[test]
fn a_second_set_for_the_same_folder_is_refused_while_the_first_is_open() {
    let w = work();
    let target = w.join("out");
    let first = ResultSet::begin(&target).unwrap();
    let e = ResultSet::begin(&target).unwrap_err();
    let message = e.to_string();
    let Error::OutputBusy { dir, pid, .. } = e else {
        panic!("not refused as busy: {message}");
    };
    assert_eq!(dir, target);
    assert_eq!(pid, Some(std::process::id()));
    assert!(
        message.contains(&target.display().to_string())
            && message.contains(&format!("PID {}", std::process::id())),
        "{message}"
    );
    drop(first);
    ResultSet::begin(&target).unwrap().commit().unwrap();
    assert_eq!(names(&w), ["out"]);
    std::fs::remove_dir_all(&w).unwrap();
}

#[test]
fn invalid_names_and_targets_are_refused() {
    let w = work();
    let target = w.join("out");
    let mut set = ResultSet::begin(&target).unwrap();
    for bad in [
        "",
        "/abs.txt",
        "../escape.txt",
        "a/../b.txt",
        "./a.txt",
        "a//b.txt",
    ] {
        assert!(set.write(bad, b"x").is_err(), "accepted `{bad}`");
    }
    drop(set);
    assert!(ResultSet::begin(Path::new(".")).is_err());
    let file = w.join("file");
    std::fs::write(&file, b"in the way").unwrap();
    let e = ResultSet::begin(&file).unwrap_err().to_string();
    assert!(e.contains("not a folder"), "{e}");
    assert_eq!(std::fs::read(&file).unwrap(), b"in the way");
    assert_eq!(names(&w), ["file"]);
    std::fs::remove_dir_all(&w).unwrap();
}

#[test]
fn a_large_set_is_committed_whole() {
    let w = work();
    let target = w.join("out");
    let n = 3 * SYNC_EACH_LIMIT;
    let mut set = ResultSet::begin(&target).unwrap();
    for k in 0..n {
        let name = format!("step-{:03}/file-{}.txt", k / 3, k % 3);
        set.write(&name, k.to_string().as_bytes()).unwrap();
    }
    let files = set.commit().unwrap();
    assert_eq!(files.len(), n);
    for k in 0..n {
        let path = target.join(format!("step-{:03}/file-{}.txt", k / 3, k % 3));
        assert_eq!(std::fs::read_to_string(path).unwrap(), k.to_string());
    }
    assert_eq!(names(&w), ["out"]);
}
