//! # Verification: an output folder holds one complete result set, never a mix
//!
//! Two scenarios on a 4 m square write different sets into the same folder `out`: the
//! "old" one has a contact part, so its set has a `contact.csv`; the "new" one has none.
//! A folder is *the complete old set* if it is byte for byte what the old run left, and
//! *the complete new set* if its `summary.json` has the new title, lists exactly the files
//! of the folder, and every file is complete (non-empty; the `.vtu` ends with its closing
//! tag). What must hold:
//!
//! - A second run replaces the whole set: files of the old set that the new one lacks
//!   (`contact.csv`) are gone, and nothing but the folder is left beside it (no lock, no
//!   temporary).
//! - A run killed at a random moment of its run (`SIGKILL` or `SIGINT`, 60 trials, most of
//!   them while writing) leaves the complete old set or the complete new set; after
//!   `SIGINT` the message says which; the next run cleans up every temporary and lock.
//! - Temporaries and a lock file left by dead processes are removed by the next run.
//! - A write that fails after most of the new set was written (a file size limit exceeded by
//!   the last file of `paper`, as on a full disk) exits with 1 naming the file and leaves the
//!   old set, no temporary and no lock; a file in the way of the folder is refused before
//!   solving, the file untouched.
//! - Two runs into one folder at the same time: one fails at once naming the folder and the
//!   other process, the other completes.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

use crate::common::{assert_success, bin, text, Rng};

/// A 4 m square on an n × n mesh, clamped at the bottom, pressed on top; with a contact part
/// on the right if `contact`.
fn scenario(title: &str, n: usize, contact: bool) -> String {
    let mut s = format!(
        "title = \"{title}\"\n[mesh]\nkind = \"rectangle\"\nsize = [4.0, 4.0]\nn = [{n}, {n}]\n\
         [material]\nyoung = 2000.0\npoisson = 0.3\n[[dirichlet]]\npart = \"bottom\"\n\
         [[loads.traction]]\npart = \"top\"\nvalue = [0.0, -900.0]\n"
    );
    if contact {
        s.push_str("[[contact]]\npart = \"right\"\ngap = 0.0\nc_nu = 1000.0\n");
    }
    s
}

/// A work folder with the scenario files `old.toml` (with contact) and `new.toml`.
struct Work {
    _tmp: tempfile::TempDir,
    dir: PathBuf,
}

impl Work {
    fn new(n_new: usize) -> Self {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().to_path_buf();
        std::fs::write(dir.join("old.toml"), scenario("old", 16, true)).unwrap();
        std::fs::write(dir.join("new.toml"), scenario("new", n_new, false)).unwrap();
        Work { _tmp: tmp, dir }
    }

    fn out(&self) -> PathBuf {
        self.dir.join("out")
    }

    fn command(&self, which: &str) -> Command {
        let mut c = bin();
        c.current_dir(&self.dir)
            .args(["solve", &format!("{which}.toml"), "--out", "out"]);
        c
    }

    fn run(&self, which: &str) -> Output {
        self.command(which).output().unwrap()
    }

    fn spawn(&self, which: &str) -> Child {
        self.command(which)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap()
    }

    /// The names in the work folder other than the scenario files.
    fn beside(&self) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(&self.dir)
            .unwrap()
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| !n.ends_with(".toml"))
            .collect();
        names.sort();
        names
    }
}

/// Every file under `dir` (relative names, `/`-separated) with its content.
fn snapshot(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    fn walk(root: &Path, dir: &Path, out: &mut BTreeMap<String, Vec<u8>>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                walk(root, &p, out);
            } else {
                let name = p.strip_prefix(root).unwrap().to_string_lossy().into_owned();
                out.insert(name, std::fs::read(&p).unwrap_or_default());
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(dir, dir, &mut out);
    out
}

/// Whether `files` is a complete set of the run titled `title`: its summary has the title
/// and lists exactly the files present, and every file is complete.
fn is_complete_set(files: &BTreeMap<String, Vec<u8>>, title: &str) -> Result<(), String> {
    let summary = files.get("summary.json").ok_or("no summary.json")?;
    let json: serde_json::Value =
        serde_json::from_slice(summary).map_err(|e| format!("summary.json: {e}"))?;
    if json["title"] != title {
        return Err(format!("title {} instead of {title}", json["title"]));
    }
    let mut listed: Vec<String> = json["files"]
        .as_array()
        .ok_or("no files list")?
        .iter()
        .map(|f| f.as_str().unwrap_or_default().to_string())
        .collect();
    listed.sort();
    let present: Vec<String> = files.keys().cloned().collect();
    if listed != present {
        return Err(format!(
            "summary lists {listed:?}, folder holds {present:?}"
        ));
    }
    if let Some((name, _)) = files.iter().find(|(_, b)| b.is_empty()) {
        return Err(format!("{name} is empty"));
    }
    let vtu = files.get("solution.vtu").ok_or("no solution.vtu")?;
    if !vtu.ends_with(b"</VTKFile>\n") {
        return Err("solution.vtu is truncated".into());
    }
    Ok(())
}

#[test]
fn second_run_replaces_the_whole_set() {
    let w = Work::new(16);
    assert_success(&w.run("old"));
    let old = snapshot(&w.out());
    is_complete_set(&old, "old").unwrap();
    assert!(old.contains_key("contact.csv"));
    assert_success(&w.run("new"));
    let new = snapshot(&w.out());
    is_complete_set(&new, "new").unwrap();
    assert!(!new.contains_key("contact.csv"), "{:?}", new.keys());
    assert_eq!(w.beside(), ["out"]);
}

/// Sends `signal` (`KILL` or `INT`) to the process `pid`.
fn signal(pid: u32, signal: &str) {
    // The process may have ended already: the exit status of `kill` does not matter.
    let _ = Command::new("kill")
        .args([&format!("-{signal}"), &pid.to_string()])
        .status();
}

#[test]
fn signals_at_random_moments_leave_the_old_or_the_new_set() {
    let w = Work::new(16);
    assert_success(&w.run("old"));
    // The duration of a whole new run, to spread the signals over it.
    let start = Instant::now();
    assert_success(&w.run("new"));
    let whole = start.elapsed();
    let seed = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap()
        .as_nanos() as u64
        | 1;
    eprintln!("seed {seed}, a whole run takes {whole:?}");
    // The seed is printed for a rerun.
    let mut random = Rng::new(seed);
    let (mut kept_old, mut got_new, mut while_writing) = (0, 0, 0);
    let trials = 60;
    for trial in 0..trials {
        // The next run cleans up after the previous trial and restores the old set.
        assert_success(&w.run("old"));
        assert_eq!(w.beside(), ["out"], "trial {trial}: left beside the folder");
        let old = snapshot(&w.out());
        is_complete_set(&old, "old").unwrap();

        let sig = if trial % 2 == 0 { "KILL" } else { "INT" };
        let mut child = w.spawn("new");
        let staging = w.dir.join(format!(".out.tmp-{}", child.id()));
        std::thread::sleep(whole.mul_f64(1.2 * random.unit()));
        if staging.exists() {
            while_writing += 1;
        }
        signal(child.id(), sig);
        let status = child.wait().unwrap();
        let mut stderr = String::new();
        std::io::Read::read_to_string(child.stderr.as_mut().unwrap(), &mut stderr).unwrap();

        let now = snapshot(&w.out());
        let is_old = now == old;
        let is_new = is_complete_set(&now, "new");
        assert!(
            is_old || is_new.is_ok(),
            "trial {trial} (SIG{sig}, exit {status:?}): a mix: {:?} ({is_new:?})\n{stderr}",
            now.keys()
        );
        if is_old {
            kept_old += 1;
        } else {
            got_new += 1;
        }
        if status.code() == Some(130) {
            let truthful = if is_old {
                stderr.contains("was left as it was")
                    || stderr.contains("before any result was written")
            } else {
                stderr.contains("holds the new results")
            };
            assert!(truthful, "trial {trial}: old = {is_old}, message: {stderr}");
        }
    }
    eprintln!(
        "{trials} trials: {kept_old} kept the old set, {got_new} have the new set, \
         {while_writing} signalled while the staging folder existed"
    );
    assert_success(&w.run("old"));
    assert_eq!(w.beside(), ["out"]);
    // Signals spread over a whole run hit both sides of the commit.
    assert!(kept_old > 0 && got_new > 0, "{kept_old} old, {got_new} new");
}

#[test]
fn stale_temporaries_and_lock_of_dead_processes_are_removed() {
    let w = Work::new(16);
    assert_success(&w.run("old"));
    // As left by killed runs: a staging folder, a previous set put aside, a lock file with
    // the id of a process that no longer exists (not locked by anyone).
    let stale = w.dir.join(".out.tmp-4000001");
    std::fs::create_dir(&stale).unwrap();
    std::fs::write(stale.join("solution.vtu"), b"<VTKFile").unwrap();
    std::fs::create_dir(w.dir.join(".out.tmp-4000002.old")).unwrap();
    std::fs::write(w.dir.join(".out.lock"), b"4000003").unwrap();
    // Not ours: names that only look alike stay.
    std::fs::write(w.dir.join(".out.tmp-notes"), b"keep").unwrap();
    std::fs::write(w.dir.join(".outer.tmp-1"), b"keep").unwrap();
    assert_success(&w.run("new"));
    is_complete_set(&snapshot(&w.out()), "new").unwrap();
    assert_eq!(w.beside(), [".out.tmp-notes", ".outer.tmp-1", "out"]);
}

#[test]
fn failing_write_keeps_the_old_set_and_leaves_nothing_behind() {
    let w = Work::new(16);
    let paper = |n: &str| {
        let mut c = bin();
        c.current_dir(&w.dir)
            .args(["paper", "--n", n, "--out", "out"]);
        c
    };
    assert_success(&paper("8").output().unwrap());
    let old = snapshot(&w.out());
    // The paper example at n = 10 writes its two cases (every file below 135 kB), then
    // the side-by-side comparison.png (about 185 kB). A file size limit of 160 kB makes that
    // last write fail with "file too large", as a full disk would, after most of the new
    // set was written (SIGXFSZ ignored, so the write returns the error instead of killing
    // the process).
    let out = Command::new("bash")
        .current_dir(&w.dir)
        .arg("-c")
        .arg(format!(
            "trap '' XFSZ; ulimit -f 160; exec '{}' paper --n 10 --out out",
            env!("CARGO_BIN_EXE_hemicontact")
        ))
        .output()
        .unwrap();
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("comparison.png"), "{stderr}");
    assert!(snapshot(&w.out()) == old, "the old set changed:\n{stderr}");
    assert_eq!(w.beside(), ["out"]);
}

#[test]
fn file_in_the_way_is_refused_before_solving() {
    let w = Work::new(16);
    std::fs::write(w.out(), b"a regular file").unwrap();
    let start = Instant::now();
    let out = w.run("new");
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("out") && stderr.contains("not a folder"),
        "{stderr}"
    );
    assert!(start.elapsed() < Duration::from_secs(5));
    assert_eq!(std::fs::read(w.out()).unwrap(), b"a regular file");
    assert_eq!(w.beside(), ["out"]);
}

/// Waits until `path` exists and holds text, for at most 20 s.
fn wait_for_text(path: &Path) -> String {
    let start = Instant::now();
    loop {
        if let Ok(t) = std::fs::read_to_string(path) {
            if !t.is_empty() {
                return t;
            }
        }
        assert!(
            start.elapsed() < Duration::from_secs(20),
            "{path:?} never came"
        );
        std::thread::sleep(Duration::from_millis(2));
    }
}

#[test]
fn concurrent_run_fails_fast_naming_the_folder_and_the_other_process() {
    // A new run long enough (a 160 × 160 mesh) to still hold the lock when the second
    // starts.
    let w = Work::new(160);
    let first = w.spawn("new");
    let holder = wait_for_text(&w.dir.join(".out.lock"));
    assert_eq!(holder.trim(), first.id().to_string());
    let start = Instant::now();
    let second = w.run("old");
    let stderr = text(&second.stderr);
    assert_eq!(second.status.code(), Some(1), "{stderr}");
    assert!(start.elapsed() < Duration::from_secs(5));
    assert!(
        stderr.contains("out:")
            && stderr.contains(&format!("PID {}", first.id()))
            && stderr.contains("another process"),
        "{stderr}"
    );
    let first = first.wait_with_output().unwrap();
    assert_success(&first);
    is_complete_set(&snapshot(&w.out()), "new").unwrap();
    assert_eq!(w.beside(), ["out"]);
}

#[test]
fn simultaneous_runs_one_completes_the_other_fails_with_the_lock_message() {
    let w = Work::new(160);
    std::fs::write(w.dir.join("old.toml"), scenario("old", 160, true)).unwrap();
    let a = w.spawn("old");
    let b = w.spawn("new");
    let (a, b) = (a.wait_with_output().unwrap(), b.wait_with_output().unwrap());
    let (ok, failed) = match (a.status.code(), b.status.code()) {
        (Some(0), Some(1)) => ("old", &b),
        (Some(1), Some(0)) => ("new", &a),
        codes => panic!(
            "exit codes {codes:?}\n{}\n{}",
            text(&a.stderr),
            text(&b.stderr)
        ),
    };
    assert!(
        text(&failed.stderr).contains("another process"),
        "{}",
        text(&failed.stderr)
    );
    is_complete_set(&snapshot(&w.out()), ok).unwrap();
    assert_eq!(w.beside(), ["out"]);
}
