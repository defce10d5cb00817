//! `mpirun -np N hemicontact solve` (cargo feature `petsc`): 1, 2 and 3 processes (3
//! oversubscribed on two cores) give the serial direct solver's displacement to 1e-8 on
//! the paper's example, its 3D analogue, Hertz 3D, Hertz 2D (a free rigid motion carried
//! by contact), a Gmsh scenario, ideal locking, exact Signorini contact, a block held by
//! friction alone (refused above its limit with the serial message) and contact between
//! two bodies (a punch on a block, a fault, two cylinders, Cattaneo–Mindlin); a given number of
//! processes is bitwise reproducible;
//! one result set is written, by rank 0, and the summary says how many processes ran; an
//! invalid scenario and a solve that does not converge end every process with the serial
//! program's message and exit code, without hanging; a mesh of 2 cells on 4 processes
//! writes no empty piece, and meshio reads every piece it writes as VTK does.
#![cfg(feature = "petsc")]
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

#[allow(dead_code)] // The reader's other arrays are not read here.
#[path = "../../hemicontact/tests/common/vtu.rs"]
mod vtu;

use common::{bin, repo_root};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// `mpirun -np N` of this build's program (as root too, oversubscribed), with a time limit
/// that turns a hang into a failure.
fn mpirun(np: usize) -> Command {
    let mut c = Command::new("timeout");
    c.args(["600", "mpirun", "-np", &np.to_string(), "--oversubscribe"])
        .arg(env!("CARGO_BIN_EXE_hemicontact"))
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1");
    c
}

/// A copy of `scenarios/NAME` as `dir/copy` with `lines` added to its `[solver]` table and
/// its mesh file (if any) referred to by absolute path.
fn variant(dir: &Path, name: &str, copy: &str, lines: &str) -> PathBuf {
    let scenarios = repo_root().join("scenarios");
    let mut text = std::fs::read_to_string(scenarios.join(name)).unwrap();
    text = text.replace(
        "file = \"meshes/",
        &format!("file = \"{}/meshes/", scenarios.display()),
    );
    text = if text.contains("\n[solver]\n") {
        text.replace("\n[solver]\n", &format!("\n[solver]\n{lines}\n"))
    } else {
        format!("{text}\n[solver]\n{lines}\n")
    };
    let file = dir.join(copy);
    std::fs::write(&file, text).unwrap();
    file
}

/// The displacement (3 components per node) of the result folder `dir`; see
/// [`point_field`].
fn displacement(dir: &Path) -> Vec<f64> {
    point_field(dir, "displacement")
}

/// The point field `name` (3 components per node) of the result folder `dir`: from
/// `solution.vtu`, or from the pieces that `solution.pvtu` names, put together by their
/// `node_id`. A node in several pieces must have the same bits in each, every node must be
/// in one, and a folder holds one of the two formats, not both.
fn point_field(dir: &Path, name: &str) -> Vec<f64> {
    let serial = dir.join("solution.vtu");
    let index = dir.join("solution.pvtu");
    assert!(
        serial.exists() != index.exists(),
        "{dir:?}: one of solution.vtu and solution.pvtu"
    );
    if serial.exists() {
        return vtu::f64s(&std::fs::read(serial).unwrap(), name);
    }
    let text = std::fs::read_to_string(index).unwrap();
    let mut u: Vec<Option<[u64; 3]>> = Vec::new();
    for source in text
        .lines()
        .filter_map(|l| l.strip_prefix("<Piece Source=\""))
        .map(|l| l.trim_end_matches("\"/>"))
    {
        let piece = std::fs::read(dir.join(source)).unwrap();
        let values = vtu::f64s(&piece, name);
        for (j, &node) in vtu::i64s(&piece, "node_id").iter().enumerate() {
            let node = node as usize;
            if u.len() <= node {
                u.resize(node + 1, None);
            }
            let bits = [0, 1, 2].map(|k| values[3 * j + k].to_bits());
            assert!(
                u[node].is_none_or(|b| b == bits),
                "{dir:?}: node {node} differs between pieces"
            );
            u[node] = Some(bits);
        }
    }
    u.iter()
        .enumerate()
        .flat_map(|(v, b)| b.unwrap_or_else(|| panic!("{dir:?}: node {v} in no piece")))
        .map(f64::from_bits)
        .collect()
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

/// Runs `hemicontact solve -q FILE --out FOLDER` on `np` processes; it must succeed.
#[track_caller]
fn solve_on(np: usize, file: &Path, folder: &Path) {
    let out = mpirun(np)
        .args(["solve", "-q"])
        .arg(file)
        .arg("--out")
        .arg(folder)
        .output()
        .unwrap();
    assert_exit(&out, 0);
}

#[track_caller]
fn assert_exit(out: &Output, code: i32) {
    assert_eq!(
        out.status.code(),
        Some(code),
        "stdout:\n{}\nstderr:\n{}",
        common::text(&out.stdout),
        common::text(&out.stderr)
    );
}

/// The serial program's solve of `scenarios/NAME` with the direct solver, into
/// `dir/serial`, which it returns.
fn solve_serial_direct(dir: &Path, name: &str) -> PathBuf {
    let direct = variant(dir, name, "direct.toml", "linear_solver = \"direct\"");
    let serial = dir.join("serial");
    let out = bin()
        .args(["solve", "-q"])
        .arg(&direct)
        .arg("--out")
        .arg(&serial)
        .output()
        .unwrap();
    assert_exit(&out, 0);
    serial
}

/// The rows of a CSV file, each split at its commas.
fn csv_rows(file: &Path) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(file).unwrap();
    text.lines()
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

/// `max |a − b|` over the entries, every one of `a` finite (a NaN would slip through the
/// maximum).
#[track_caller]
fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    assert!(
        a.iter().all(|v| v.is_finite()),
        "a value that is not finite"
    );
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The serial direct solve of a scenario against 1, 2 and 3 processes.
fn agrees_across_processes(name: &str) {
    let dir = tempfile::tempdir().unwrap();
    let serial = solve_serial_direct(dir.path(), name);
    let reference = displacement(&serial);
    let scale = reference.iter().map(|v| v.abs()).fold(0.0, f64::max);
    let shift = summary(&serial)["report"]["rigid_shift"].as_f64().unwrap();
    // `auto` is PETSc's solver when run as several processes (and the direct one on one).
    let file = variant(dir.path(), name, "auto.toml", "");
    for np in [1, 2, 3] {
        let folder = dir.path().join(format!("np{np}"));
        solve_on(np, &file, &folder);
        let s = summary(&folder);
        assert_eq!(s["report"]["processes"], np, "{name}, {np} processes");
        assert_eq!(s["report"]["converged"], true, "{name}, {np} processes");
        // The size of the whole system, though each process holds its part of the matrix.
        let whole = summary(&serial);
        for size in ["n_equations", "nnz_matrix"] {
            assert_eq!(
                s["report"][size], whole["report"][size],
                "{name}, {np}: {size}"
            );
        }
        // ParaView's parallel format, one piece per process, listed in the summary.
        let files: Vec<&str> = s["files"]
            .as_array()
            .unwrap()
            .iter()
            .map(|f| f.as_str().unwrap())
            .collect();
        let pieces: Vec<String> = (0..np).map(|r| format!("solution_{r}.vtu")).collect();
        if np > 1 {
            assert!(files.contains(&"solution.pvtu"), "{name}, {np}: {files:?}");
            assert!(
                pieces.iter().all(|p| files.contains(&p.as_str())),
                "{files:?}"
            );
        } else {
            assert!(
                files.contains(&"solution.vtu"),
                "{name}, 1 process: {files:?}"
            );
        }
        let diff = max_difference(&displacement(&folder), &reference) / scale;
        eprintln!(
            "{name}, np = {np} ({}): max relative difference from the serial direct \
             solve {diff:.1e}",
            s["report"]["linear_solver"]
        );
        assert!(diff <= 1e-8, "{name}, {np} processes: {diff:e}");
        // The reactions, each process's own nodes' put together.
        let (r, r_serial) = (
            point_field(&folder, "reaction"),
            point_field(&serial, "reaction"),
        );
        let r_scale = r_serial.iter().map(|v| v.abs()).fold(0.0, f64::max);
        let r_diff = max_difference(&r, &r_serial);
        eprintln!(
            "{name}, np = {np}: reactions, max difference {r_diff:.1e} of the largest \
             {r_scale:.1e}"
        );
        assert!(
            r_diff <= 1e-8 * r_scale || (r_scale == 0.0 && r_diff == 0.0),
            "{name}, {np} processes: reactions differ by {r_diff:e} of {r_scale:e}"
        );
        // The contact results, each computed by the process that owns its point: every
        // point of the serial file, in its order, with its states and the same slips
        // and pressures to 1e-6 of the largest (slips, which are displacements, at least
        // to the displacements' 1e-8: a contact that sticks everywhere has slips of
        // round-off only).
        let (mine, theirs) = (
            csv_rows(&folder.join("contact.csv")),
            csv_rows(&serial.join("contact.csv")),
        );
        assert_eq!(mine.len(), theirs.len(), "{name}, {np}: contact.csv rows");
        let column = |name: &str| theirs[0].iter().position(|c| c == name).unwrap();
        for field in ["slip", "pressure"] {
            let k = column(field);
            let value = |r: &Vec<String>| r[k].parse::<f64>().unwrap();
            let largest = theirs[1..].iter().map(value).fold(0.0, f64::max);
            let floor = if field == "slip" { 1e-8 * scale } else { 0.0 };
            for (a, b) in mine[1..].iter().zip(&theirs[1..]) {
                assert!(
                    (value(a) - value(b)).abs() <= (1e-6 * largest).max(floor),
                    "{name}, {np}: {field} {} against {}",
                    value(a),
                    value(b)
                );
            }
        }
        for field in ["node", "boundary", "normal_state", "friction_state"] {
            let k = column(field);
            for (a, b) in mine[1..].iter().zip(&theirs[1..]) {
                assert_eq!(a[k], b[k], "{name}, {np}: {field}");
            }
        }
        // The certificate's counts of exact constraints (cells, Signorini points, exact
        // friction points) are sums over the processes of what each counts.
        let kkt = &whole["report"]["certificate"]["kkt"];
        if !kkt.is_null() {
            assert_eq!(
                s["report"]["certificate"]["kkt"]["n_constraints"], kkt["n_constraints"],
                "{name}, {np} processes"
            );
        }
        // The Newton shift on free rigid motions is the largest diagonal entry on them,
        // found from each process's complete rows.
        let s_np = s["report"]["rigid_shift"].as_f64().unwrap();
        assert!(
            (s_np - shift).abs() <= 1e-12 * shift,
            "{name}, {np} processes: rigid shift {s_np:e}, serial {shift:e}"
        );
    }
}

#[test]
fn paper_across_processes() {
    agrees_across_processes("paper.toml");
}

#[test]
fn paper3d_across_processes() {
    agrees_across_processes("paper3d.toml");
}

#[test]
fn hertz3d_across_processes() {
    agrees_across_processes("hertz3d.toml");
}

/// A body whose vertical translation only contact carries: the Newton matrix is shifted on
/// that motion.
#[test]
fn hertz2d_free_rigid_motion_across_processes() {
    agrees_across_processes("hertz2d.toml");
}

#[test]
fn gmsh_half_disc_across_processes() {
    agrees_across_processes("half-disc.toml");
}

/// A body of two materials (cell regions of the generated mesh), one of them nearly
/// locking, with exact Coulomb friction: each process's part keeps its cells' materials.
#[test]
fn two_materials_across_processes() {
    agrees_across_processes("layered-block.toml");
}

/// Two deformable bodies: a stiff punch on a soft block, non-matching meshes, exact Coulomb
/// friction between them. Each process holds the pairs of its own slave nodes and, as ghost
/// points, those whose master facet has a node of its own, so that its rows are complete.
#[test]
fn a_contact_pair_across_processes() {
    agrees_across_processes("punch-on-block.toml");
}

/// Two blocks across a fault with slip weakening (exact friction, Signorini), most of the
/// fault slipping: the pairs' outer loop and certificate across processes.
#[test]
fn a_slipping_fault_across_processes() {
    agrees_across_processes("fault.toml");
}

/// Hertz between two cylinders of different materials (regularized friction): curved
/// master facets, most of the interface separated.
#[test]
fn two_cylinders_across_processes() {
    agrees_across_processes("two-cylinders.toml");
}

/// Cattaneo–Mindlin between two identical cylinders: pressed, then sheared below the
/// friction limit (exact Coulomb), a stick zone inside a slipping annulus.
#[test]
fn cattaneo_mindlin_across_processes() {
    agrees_across_processes("cattaneo-mindlin.toml");
}

/// Cattaneo–Mindlin between two whole spheres (3D): the pairs' tetrahedral master facets
/// across processes.
#[test]
fn cattaneo_spheres_across_processes() {
    agrees_across_processes("cattaneo-spheres.toml");
}

/// A free body as the master side of a pair: the two cylinders with the sides swapped (the
/// upper body's vertical translation carried by the pair through its master points), and
/// a block held by friction alone as the master side of a held block (Gmsh, matching
/// meshes: the relief of the first iteration spread onto the master facets' nodes).
#[test]
fn a_free_master_body_across_processes() {
    let dir = tempfile::tempdir().unwrap();
    let scenarios = repo_root().join("scenarios");
    let swapped = std::fs::read_to_string(scenarios.join("two-cylinders.toml"))
        .unwrap()
        .replace(
            "file = \"meshes/",
            &format!("file = \"{}/meshes/", scenarios.display()),
        )
        .replace(
            "part = \"upper_bottom\"\nagainst = \"lower_top\"",
            "part = \"lower_top\"\nagainst = \"upper_bottom\"",
        );
    assert!(swapped.contains("against = \"upper_bottom\""));
    let file = dir.path().join("swapped.toml");
    std::fs::write(&file, swapped).unwrap();
    agrees_across_processes(file.to_str().unwrap());
    let blocks = repo_root().join("crates/hemicontact/tests/data/gmsh/two-blocks.msh");
    let held = format!(
        r#"
[mesh]
kind = "gmsh"
file = "{}"
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "lower_bottom"
[[loads.traction]]
part = "upper_top"
value = [2.0, -10.0]
[[contact]]
part = "lower_top"
against = "upper_bottom"
law = "signorini"
[contact.friction]
bound = "coulomb"
mu = 0.3
exact = true
"#,
        blocks.display()
    );
    let file = dir.path().join("held-master.toml");
    std::fs::write(&file, held).unwrap();
    agrees_across_processes(file.to_str().unwrap());
}

/// A load path with a moving obstacle: the sliding indenter's five steps, each warm-started
/// from the last one's answer put together from every process's part. Every step's
/// contact forces, counts and largest displacement, and the last step's displacements,
/// agree with the serial direct solve on 2 and 3 processes.
#[test]
fn a_load_path_across_processes() {
    let name = "sliding-indenter.toml";
    let dir = tempfile::tempdir().unwrap();
    let serial = solve_serial_direct(dir.path(), name);
    let theirs = csv_rows(&serial.join("load_path.csv"));
    let reference = displacement(&serial.join("step-005"));
    let scale = reference.iter().map(|v| v.abs()).fold(0.0, f64::max);
    let file = variant(dir.path(), name, "auto.toml", "");
    for np in [2, 3] {
        let folder = dir.path().join(format!("np{np}"));
        solve_on(np, &file, &folder);
        let mine = csv_rows(&folder.join("load_path.csv"));
        assert_eq!(mine.len(), 6, "{np}: a header and five steps");
        assert_eq!(mine[0], theirs[0], "{np}: columns");
        let column = |name: &str| theirs[0].iter().position(|c| c == name).unwrap();
        for (a, b) in mine[1..].iter().zip(&theirs[1..]) {
            for field in ["load_factor", "n_contact", "n_slip", "converged"] {
                assert_eq!(a[column(field)], b[column(field)], "{np}: {field}");
            }
            for field in ["contact_force_x", "contact_force_y", "max_displacement"] {
                let (x, y): (f64, f64) = (
                    a[column(field)].parse().unwrap(),
                    b[column(field)].parse().unwrap(),
                );
                assert!(
                    (x - y).abs() <= 1e-8 * y.abs(),
                    "{np}: {field} {x:e} against {y:e}"
                );
            }
        }
        let diff = max_difference(&displacement(&folder.join("step-005")), &reference) / scale;
        eprintln!(
            "{name}, np = {np}: last step, max relative difference from the serial direct \
             solve {diff:.1e}"
        );
        assert!(diff <= 1e-8, "{np} processes: {diff:e}");
    }
}

/// A block held sideways by friction alone, 0.5 m above a compliant foundation: dropped
/// onto it first (a linear programme over every process's contact points), then its side
/// load, 0.9 of the friction limit μ N = 3 N, relieved in the first outer iteration and its
/// slips centred (sums over the body's nodes and points, completed over the processes).
/// Above the limit every process refuses it with the serial program's message.
#[test]
fn a_block_held_by_friction_across_processes() {
    let dir = tempfile::tempdir().unwrap();
    let block = |side: f64| {
        format!(
            r#"
[mesh]
kind = "box"
size = [1.0, 1.0, 0.5]
n = [6, 6, 3]
[material]
young = 1000.0
poisson = 0.3
[[contact]]
part = "bottom"
gap = 0.5
law = "normal-compliance"
c_nu = 2000.0
[contact.friction]
bound = "coulomb"
mu = {{ law = "constant", mu = 0.3 }}
potential = {{ kind = "norm" }}
[[loads.traction]]
part = "top"
value = [{side}, 0.0, -10.0]
"#
        )
    };
    let held = dir.path().join("held.toml");
    std::fs::write(&held, block(2.7)).unwrap();
    agrees_across_processes(held.to_str().unwrap());
    let above = dir.path().join("above.toml");
    std::fs::write(&above, block(3.03)).unwrap();
    let serial = bin()
        .args(["solve", "-q"])
        .arg(&above)
        .arg("--out")
        .arg(dir.path().join("s"))
        .output()
        .unwrap();
    let code = serial.status.code().unwrap();
    assert_ne!(code, 0);
    let message = common::text(&serial.stderr);
    assert!(message.contains("above the friction limit"), "{message}");
    let out = mpirun(3)
        .args(["solve", "-q"])
        .arg(&above)
        .arg("--out")
        .arg(dir.path().join("m"))
        .output()
        .unwrap();
    assert_exit(&out, code);
    let stderr = common::text(&out.stderr);
    // The serial message, after its `error:` prefix (each rank names itself instead).
    let first = message.lines().next().unwrap();
    let (_, text) = first.split_once(": ").unwrap();
    assert!(stderr.contains(text), "{first}\n{stderr}");
}

/// Exact constraints: ideal locking (a multiplier per cell, in the outer loop's mixing and
/// the KKT certificate) and exact Signorini contact.
#[test]
fn exact_constraints_across_processes() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["paper-ideal.toml", "paper-signorini.toml"] {
        // On a 64 × 64 mesh instead of 128 × 128, for time.
        let text = std::fs::read_to_string(repo_root().join("scenarios").join(name)).unwrap();
        assert!(text.contains("n = [128, 128]"), "{name}");
        let file = dir.path().join(name);
        std::fs::write(&file, text.replace("n = [128, 128]", "n = [64, 64]")).unwrap();
        agrees_across_processes(file.to_str().unwrap());
    }
}

/// Two runs on the same number of processes write the same bytes of displacement: on 2
/// processes (paper3d), and on 3, where PETSc's default triple product of GAMG's coarse
/// matrices would add other processes' contributions in their order of arrival (paper);
/// the output folder holds one result set (no other rank wrote anything beside it). On 2
/// processes, a third run assembling on three tasks per process instead of one per core
/// writes the same bytes too (the assembly's result does not depend on its tasks).
#[test]
fn a_number_of_processes_is_bitwise_reproducible() {
    for (np, scenario) in [(2, "paper3d.toml"), (3, "paper.toml")] {
        let dir = tempfile::tempdir().unwrap();
        let file = variant(dir.path(), scenario, scenario, "");
        let mut fields = Vec::new();
        for run in ["a", "b"] {
            let folder = dir.path().join(run);
            solve_on(np, &file, &folder);
            fields.push(displacement(&folder));
        }
        assert!(
            fields[0] == fields[1],
            "two runs of {scenario} on {np} processes differ"
        );
        let mut expected = vec!["a", "b", scenario];
        if np == 2 {
            let tasks = variant(dir.path(), scenario, "three-tasks.toml", "threads = 3");
            let folder = dir.path().join("c");
            solve_on(np, &tasks, &folder);
            assert!(
                displacement(&folder) == fields[0],
                "{scenario} on {np} processes: three assembly tasks per process differ"
            );
            expected = vec!["a", "b", "c", "three-tasks.toml", scenario];
        }
        let mut entries: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        entries.sort();
        expected.sort();
        assert_eq!(entries, expected);
    }
}

/// An invalid scenario: every process stops with the serial program's message (once or
/// from several ranks) and exit code 1, within the time limit.
#[test]
fn an_invalid_scenario_ends_every_process() {
    let dir = tempfile::tempdir().unwrap();
    let file = variant(
        dir.path(),
        "paper3d.toml",
        "paper3d.toml",
        "certificate_tolerance = 2.0",
    );
    let out = mpirun(3)
        .args(["solve"])
        .arg(&file)
        .arg("--out")
        .arg(dir.path().join("out"))
        .output()
        .unwrap();
    assert_exit(&out, 1);
    let stderr = common::text(&out.stderr);
    assert!(stderr.contains("certificate_tolerance"), "{stderr}");
    assert!(!dir.path().join("out").exists());
}

/// A solve that does not converge: exit code 3 from every process, and rank 0's results
/// written, marked not converged.
#[test]
fn a_solve_that_does_not_converge_is_written_and_exits_3() {
    let dir = tempfile::tempdir().unwrap();
    let file = variant(
        dir.path(),
        "paper3d.toml",
        "paper3d.toml",
        "[solver.outer]\nmax_iterations = 1",
    );
    let folder = dir.path().join("out");
    let out = mpirun(2)
        .args(["solve", "-q"])
        .arg(&file)
        .arg("--out")
        .arg(&folder)
        .output()
        .unwrap();
    assert_exit(&out, 3);
    let s = summary(&folder);
    assert_eq!(s["report"]["converged"], false);
    assert_eq!(s["report"]["processes"], 2);
}

/// A mesh of 2 triangles on 4 processes, more than it can share: the ranks that own no cell
/// write no piece, `solution.pvtu` names only the pieces written (each in the summary's
/// files), every node is in one of them with the serial direct solve's displacement, and
/// meshio reads every piece as VTK does (`tests/python/check_readers.py` of the library,
/// with `$HEMICONTACT_PYTHON`, else `python3`; skipped with a loud line without meshio and
/// vtk, a failure under `CI=true`). Before, each rank wrote a piece, and meshio could not
/// read one of 0 points (`IndexError`).
#[test]
fn more_processes_than_cells_write_no_empty_piece() {
    use std::io::Write as _;
    let dir = tempfile::tempdir().unwrap();
    let scenario = |solver: &str| {
        format!(
            "[mesh]\nkind = \"rectangle\"\nsize = [1.0, 1.0]\nn = [1, 1]\n\
             pattern = \"uniform\"\n[material]\nyoung = 1000.0\npoisson = 0.3\n\
             [[dirichlet]]\npart = \"bottom\"\n[[loads.traction]]\npart = \"top\"\n\
             value = [1.0, -10.0]\n[solver]\n{solver}\n"
        )
    };
    let direct = dir.path().join("direct.toml");
    std::fs::write(&direct, scenario("linear_solver = \"direct\"")).unwrap();
    let serial = dir.path().join("serial");
    let out = bin()
        .args(["solve", "-q"])
        .arg(&direct)
        .arg("--out")
        .arg(&serial)
        .output()
        .unwrap();
    assert_exit(&out, 0);
    let reference = displacement(&serial);
    let scale = reference.iter().map(|v| v.abs()).fold(0.0, f64::max);
    let file = dir.path().join("auto.toml");
    std::fs::write(&file, scenario("")).unwrap();
    let folder = dir.path().join("np4");
    solve_on(4, &file, &folder);
    let s = summary(&folder);
    assert_eq!(s["report"]["processes"], 4);
    assert_eq!(s["report"]["converged"], true);
    let files: Vec<&str> = s["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap())
        .collect();
    let index = std::fs::read_to_string(folder.join("solution.pvtu")).unwrap();
    let sources: Vec<&str> = index
        .lines()
        .filter_map(|l| l.strip_prefix("<Piece Source=\""))
        .map(|l| l.trim_end_matches("\"/>"))
        .collect();
    // Two cells: one or two pieces, each in the summary, and no other piece on disk.
    assert!((1..=2).contains(&sources.len()), "{sources:?}");
    for r in 0..4 {
        let piece = format!("solution_{r}.vtu");
        let listed = sources.contains(&piece.as_str());
        assert_eq!(folder.join(&piece).exists(), listed, "{piece}: {sources:?}");
        assert_eq!(
            files.contains(&piece.as_str()),
            listed,
            "{piece}: {files:?}"
        );
        if listed {
            let bytes = std::fs::read(folder.join(&piece)).unwrap();
            assert!(!vtu::i64s(&bytes, "cell_id").is_empty(), "{piece}: no cell");
        }
    }
    let diff = max_difference(&displacement(&folder), &reference) / scale;
    assert!(diff <= 1e-8, "4 processes: {diff:e}");
    // meshio and VTK read every piece written, the same.
    let python = std::env::var("HEMICONTACT_PYTHON").unwrap_or_else(|_| "python3".to_string());
    let script = repo_root().join("crates/hemicontact/tests/python/check_readers.py");
    let out = Command::new(&python)
        .arg(&script)
        .args(sources.iter().map(|p| folder.join(p)))
        .output()
        .unwrap();
    let stderr = common::text(&out.stderr);
    if out.status.code() == Some(77) {
        assert!(
            std::env::var("CI").as_deref() != Ok("true"),
            "CI=true and `{python}` cannot import meshio and vtk: {stderr}"
        );
        let _ = writeln!(
            std::io::stderr().lock(),
            "\n*** SKIPPED check_readers.py: `{python}` cannot import meshio, vtk and numpy. \
             This run is NO evidence that meshio reads the pieces. Install them with `bash \
             scripts/install-test-deps.sh target/test-venv` and set \
             HEMICONTACT_PYTHON=$PWD/target/test-venv/bin/python. ***\n"
        );
        return;
    }
    assert!(
        out.status.success(),
        "check_readers.py failed (exit {:?}):\n{}{stderr}",
        out.status.code(),
        common::text(&out.stdout)
    );
}
