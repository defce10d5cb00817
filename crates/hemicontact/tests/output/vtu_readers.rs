//! # Verification: every reader reads the same `.vtu`
//!
//! What is verified, and why it must hold:
//!
//! - **Own blocks.** In every file written, each `<DataArray format="appended">` has an
//!   offset of its own, and the encoded arrays at those offsets tile the appended data
//!   exactly (no gap, no overlap, nothing shared), each decoding to the size its type and
//!   counts call for; the blocks follow one another in the reverse order of their
//!   elements, the layout that meshio's offset lookup (below) cannot confuse. Checked here
//!   in Rust, without Python.
//! - **meshio reads what VTK reads.** `tests/python/check_readers.py` reads every file with
//!   meshio and with VTK's `vtkXMLUnstructuredGridReader` and requires the same points,
//!   connectivity and point, cell and field arrays: same names, dtypes, shapes and bytes.
//!   meshio rewrites raw appended data to base64 and finds the array of each block by its
//!   offset, one block after the other, renumbering offsets as it goes; a block whose raw
//!   offset equals an offset already renumbered used to be handed to the wrong array (a
//!   `step-001/solution.vtu` of a load path with a tiny first factor had its `reaction`
//!   and `contact_normal` swapped), which only the comparison with VTK shows.
//! - **Which files.** Every committed scenario in `scenarios/` (generated meshes at a small
//!   resolution, the Gmsh mesh as it is), both steps of a load path with a tiny first load
//!   factor (`[loading] factors = [1e-6, 1.0]` on the paper's example at n = 2, the case
//!   that was misread), and files with many short `FieldData` arrays of arbitrary content,
//!   where raw offsets and renumbered offsets meet often.
//!
//! The interpreter is `$HEMICONTACT_PYTHON`, else `python3`; under `CI=true` a missing
//! meshio or vtk fails the test, elsewhere the reader comparison is skipped with a loud line
//! saying it is no evidence (the Rust checks still run).
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use hemicontact::io::vtu::{solution_vtu, VtuWriter};
use hemicontact::io::zlib_blocks;
use hemicontact::loading::load_path;
use hemicontact::scenario::schema::MeshKind;
use hemicontact::scenario::Scenario;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::AtomicBool;

/// The repository's committed scenarios, sorted by name.
fn committed_scenarios() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 10, "{} scenarios in {dir:?}", files.len());
    files
}

/// The scenario at a resolution that solves in a fraction of a second: generated meshes
/// with 4 cells along x (2D) or 2 (3D); a Gmsh mesh as it is.
fn small(scenario: &Scenario) -> Scenario {
    let spec = scenario.mesh_spec().unwrap();
    match spec.kind {
        MeshKind::Rectangle => scenario.with_resolution(4).unwrap(),
        MeshKind::Box => scenario.with_resolution(2).unwrap(),
        MeshKind::Gmsh => scenario.clone(),
    }
}

/// Writes the `solution.vtu` of every committed scenario (small, one solve at the full
/// load, the scenario's title) into `dir`; returns the paths.
fn write_committed(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for file in committed_scenarios() {
        let scenario = small(&Scenario::from_file(&file).unwrap());
        let problem = scenario.into_problem().unwrap();
        let settings = scenario.settings().unwrap();
        let solution = hemicontact::solver::solve(&problem, &settings).unwrap();
        let title = scenario.file.title.clone().unwrap_or("scenario".into());
        let stem = file.file_stem().unwrap().to_str().unwrap();
        let path = dir.join(format!("{stem}.vtu"));
        solution_vtu(&problem, &solution, &title, 1.0)
            .unwrap()
            .write(&path)
            .unwrap();
        out.push(path);
    }
    out
}

/// Solves the paper's example at n = 2 along `[loading] factors = [1e-6, 1.0]` and writes
/// each step's `solution.vtu` into `dir` (the step's title and load factor, as
/// `hemicontact solve` writes them); returns the paths.
fn write_tiny_first_factor_path(dir: &Path) -> Vec<PathBuf> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/paper.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("n = [128, 128]"));
    let text =
        text.replace("n = [128, 128]", "n = [2, 2]") + "\n[loading]\nfactors = [1e-6, 1.0]\n";
    let scenario = Scenario::from_str(&text, "paper.toml at n = 2").unwrap();
    let problem = scenario.into_problem().unwrap();
    let settings = scenario.settings().unwrap();
    let factors = scenario.load_factors().unwrap().unwrap();
    let title = scenario.file.title.clone().unwrap();
    let steps = load_path(
        &problem,
        &settings,
        &factors,
        &AtomicBool::new(false),
        &|_, _| {},
        &mut |_| Ok(()),
    )
    .unwrap();
    assert_eq!(steps.len(), 2);
    steps
        .iter()
        .map(|s| {
            let path = dir.join(format!("step-{:03}.vtu", s.step));
            let step_title = format!("{title}, load factor {:e}", s.factor);
            solution_vtu(&s.problem, &s.solution, &step_title, s.factor)
                .unwrap()
                .write(&path)
                .unwrap();
            path
        })
        .collect()
}

/// Writes `count` files on a small mesh, each with many `FieldData` arrays beside point and
/// cell arrays: first 30 all-zero arrays of 8 to 40 values (their base64 form is long,
/// their compressed form short), then 150 arrays of 1 to 3 arbitrary values (compressed
/// longer than they are), so that the raw offsets of the later arrays pass through the
/// range of the base64 offsets meshio gives the earlier ones; returns the paths.
fn write_many_short_arrays(dir: &Path, count: usize) -> Vec<PathBuf> {
    let problem = common::problem(
        "[mesh]\nkind = \"rectangle\"\nsize = [1.0, 1.0]\nn = [2, 2]\n\
         [material]\nyoung = 1.0\npoisson = 0.3\n[[dirichlet]]\npart = \"bottom\"\n",
    );
    let mesh = problem.mesh();
    let mut rng = common::Rng::new(7);
    (0..count)
        .map(|f| {
            let mut w = VtuWriter::new(mesh);
            w.field_text("TITLE", &format!("file {f}"));
            for k in 0..30 {
                let len = 8 + (rng.next_u64() % 33) as usize;
                w.field_f64(&format!("zeros{k:03}"), vec![0.0; len]);
            }
            for k in 0..150 {
                let len = 1 + (rng.next_u64() % 3) as usize;
                let values = (0..len).map(|_| rng.uniform(-1.0, 1.0)).collect();
                w.field_f64(&format!("short{k:03}"), values);
            }
            let n = mesh.n_nodes();
            w.point_f64("zeros", 3, vec![0.0; 3 * n])
                .point_i32("ids", (0..n as i32).collect())
                .point_f64("also_zeros", 1, vec![0.0; n])
                .cell_f64("x", 1, (0..mesh.n_cells()).map(|c| c as f64).collect())
                .cell_i32("none", vec![0; mesh.n_cells()]);
            let path = dir.join(format!("short-{f:02}.vtu"));
            w.write(&path).unwrap();
            path
        })
        .collect()
}

/// Bytes per value of a VTK type name.
fn type_size(ty: &str) -> usize {
    match ty {
        "Float64" | "Int64" => 8,
        "Int32" => 4,
        "UInt8" => 1,
        _ => panic!("unexpected type {ty}"),
    }
}

/// Asserts that every appended `DataArray` of the file at `path` has its own offset and its
/// own block: the blocks at the offsets tile the appended data, and each decodes to the size
/// its type and counts call for. Returns (offset, name) of each in document order.
fn own_blocks(path: &Path) -> Vec<(usize, String)> {
    use common::vtu::attr;
    let bytes = std::fs::read(path).unwrap();
    let marker = b"<AppendedData encoding=\"raw\">\n_";
    let start = bytes
        .windows(marker.len())
        .position(|w| w == marker)
        .expect("appended data")
        + marker.len();
    let end = bytes.len() - b"\n</AppendedData>\n</VTKFile>\n".len();
    let head = String::from_utf8(bytes[..start].to_vec()).unwrap();
    let count = |key: &str| -> usize {
        let at = head.find(key).unwrap() + key.len();
        head[at..].split('"').next().unwrap().parse().unwrap()
    };
    let (n_points, n_cells) = (count("NumberOfPoints=\""), count("NumberOfCells=\""));
    let mut blocks: Vec<(usize, usize, String)> = Vec::new();
    let mut section = "";
    for line in head.lines() {
        if let Some(tag) = line.strip_prefix('<').and_then(|l| l.strip_suffix('>')) {
            if !tag.starts_with("DataArray") && !tag.starts_with('/') {
                section = ["FieldData", "PointData", "CellData", "Points", "Cells"]
                    .into_iter()
                    .find(|s| tag == *s)
                    .unwrap_or(section);
            }
        }
        if !line.starts_with("<DataArray") {
            continue;
        }
        assert_eq!(attr(line, "format"), "appended", "{path:?}: {line}");
        let name = attr(line, "Name").to_string();
        let offset: usize = attr(line, "offset").parse().unwrap();
        let (data, used) = zlib_blocks::decompress(&bytes[start + offset..end])
            .unwrap_or_else(|e| panic!("{path:?}: {name} at {offset}: {e}"));
        let values = data.len() / type_size(attr(line, "type"));
        let expected = match (section, name.as_str()) {
            ("FieldData", _) => attr(line, "NumberOfTuples").parse().unwrap(),
            ("Cells", "connectivity") => values, // checked by the readers
            ("Cells", _) => n_cells,
            (section, _) => {
                let components: usize = attr(line, "NumberOfComponents").parse().unwrap();
                let tuples = if section == "CellData" {
                    n_cells
                } else {
                    n_points
                };
                tuples * components
            }
        };
        assert_eq!(values, expected, "{path:?}: {section} {name}");
        blocks.push((offset, used, format!("{section} {name}")));
    }
    let in_document_order: Vec<(usize, String)> =
        blocks.iter().map(|(o, _, n)| (*o, n.clone())).collect();
    blocks.sort();
    let mut at = 0;
    for (offset, used, name) in &blocks {
        assert_eq!(
            *offset, at,
            "{path:?}: {name} starts at {offset}, the block before it ends at {at}: \
             every array has its own block, one after the other ({blocks:?})"
        );
        at = offset + used;
    }
    assert_eq!(
        at,
        end - start,
        "{path:?}: the blocks fill the appended data"
    );
    in_document_order
}

/// Asserts the layout that meshio's offset lookup cannot confuse: the blocks of the
/// arrays `blocks` (offset, name; in document order) of the file at `path` follow one
/// another in the reverse order of their elements.
fn assert_reverse_layout(path: &Path, blocks: &[(usize, String)]) {
    for pair in blocks.windows(2) {
        assert!(
            pair[0].0 > pair[1].0,
            "{path:?}: {} at {} comes before {} at {} in the XML: the blocks are laid out \
             in the reverse order of their elements",
            pair[0].1,
            pair[0].0,
            pair[1].1,
            pair[1].0
        );
    }
}

/// All checks on `files`: every array in a block of its own, meshio and VTK reading the
/// same, and the reverse layout (checked last, so that on a file in another layout the
/// readers' disagreement, if any, is what is reported).
fn check_files(files: &[PathBuf]) {
    let layouts: Vec<Vec<(usize, String)>> = files.iter().map(|f| own_blocks(f)).collect();
    readers_agree(files);
    for (f, blocks) in files.iter().zip(&layouts) {
        assert_reverse_layout(f, blocks);
    }
}

/// The Python interpreter of the reader checks: `$HEMICONTACT_PYTHON`, else `python3`.
fn python() -> String {
    std::env::var("HEMICONTACT_PYTHON").unwrap_or_else(|_| "python3".to_string())
}

/// Runs `tests/python/check_readers.py` on `files`: panics if a check fails; announces the
/// skip (or fails under `CI=true`) if the interpreter cannot import meshio and vtk.
fn readers_agree(files: &[PathBuf]) {
    python_check("check_readers.py", files);
}

/// Runs the script `tests/python/<script>` on `args`: panics if a check fails; announces
/// the skip (or fails under `CI=true`) if the interpreter cannot import meshio and vtk
/// (exit code 77).
fn python_check(script: &str, args: &[PathBuf]) {
    use std::io::Write as _;
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/python")
        .join(script);
    let out = Command::new(python())
        .arg(&path)
        .args(args)
        .output()
        .expect("the Python interpreter runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    if out.status.code() == Some(77) {
        assert!(
            std::env::var("CI").as_deref() != Ok("true"),
            "CI=true and `{}` cannot import meshio and vtk: {stderr}; .ci/run installs them \
             with scripts/install-test-deps.sh and sets HEMICONTACT_PYTHON",
            python()
        );
        let _ = writeln!(
            std::io::stderr().lock(),
            "\n*** SKIPPED {script}: `{}` cannot import meshio, vtk and numpy. This run is \
             NO evidence that the readers read the files as written. Install the readers \
             with `bash scripts/install-test-deps.sh target/test-venv` and set \
             HEMICONTACT_PYTHON=$PWD/target/test-venv/bin/python (an absolute path). ***\n",
            python()
        );
        return;
    }
    assert!(
        out.status.success(),
        "{script} failed (exit {:?}):\n{}{stderr}",
        out.status.code(),
        String::from_utf8_lossy(&out.stdout)
    );
}

#[test]
fn committed_scenarios_are_read_the_same_by_meshio_and_vtk() {
    let dir = common::fresh_dir("vtu-readers-scenarios");
    let files = write_committed(&dir);
    check_files(&files);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn load_path_with_a_tiny_first_factor_is_read_the_same_by_meshio_and_vtk() {
    let dir = common::fresh_dir("vtu-readers-path");
    let files = write_tiny_first_factor_path(&dir);
    check_files(&files);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn many_short_arrays_are_read_the_same_by_meshio_and_vtk() {
    let dir = common::fresh_dir("vtu-readers-short");
    let files = write_many_short_arrays(&dir, 16);
    check_files(&files);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The parallel format: the solution of every kind of mesh (2D generated, 3D generated,
/// Gmsh), split into 3 pieces by contiguous ranges of nodes and by a scattered split (node
/// v to rank 7v mod 3, the most borders), written as `hemicontact solve` writes it under
/// `mpirun -np 3`:
/// - the files are `solution_<r>.vtu` for every rank r that owns a cell (all three here but
///   for a rank whose nodes are the lowest of no cell) and the index `solution.pvtu` last,
///   which names them and declares every piece array with its type and components;
/// - every cell of the mesh is in exactly one piece (`cell_id`);
/// - every value of every point and cell array, every point's coordinates and every cell's
///   nodes are the serial `solution.vtu`'s at that node (`node_id`) or cell, bit for bit;
/// - each piece passes the single-file checks (own blocks, meshio and VTK agree), and VTK's
///   parallel reader reads the index as the serial file (`tests/python/check_pvtu.py`).
#[test]
fn parallel_pieces_hold_every_cell_once_with_the_serial_values() {
    use common::vtu::{arrays, f64s, i32s, i64s};
    use hemicontact::io::vtu::solution_files;
    use hemicontact::parallel::Partition;
    let dir = common::fresh_dir("vtu-readers-pieces");
    let mut to_check = Vec::new();
    let mut pairs = Vec::new();
    for name in ["paper.toml", "paper3d.toml", "half-disc.toml"] {
        let file = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenarios")
            .join(name);
        let scenario = small(&Scenario::from_file(&file).unwrap());
        let problem = scenario.into_problem().unwrap();
        let settings = scenario.settings().unwrap();
        let mut solution = hemicontact::solver::solve(&problem, &settings).unwrap();
        let mesh = problem.mesh();
        let n = mesh.n_nodes();
        let serial = solution_files(&problem, &solution, "t", 1.0).unwrap();
        assert_eq!(serial.len(), 1);
        assert_eq!(serial[0].0, "solution.vtu");
        let whole = &serial[0].1;
        let scattered = Partition::from_ranks((0..n).map(|v| (7 * v % 3) as u32).collect(), 3);
        for (split, partition) in [
            ("ranges", Partition::ranges(n, 3)),
            ("scattered", scattered),
        ] {
            let owned = partition.owned_cells(mesh);
            solution.partition = Some(partition);
            let files = solution_files(&problem, &solution, "t", 1.0).unwrap();
            let names: Vec<&str> = files.iter().map(|(f, _)| f.as_str()).collect();
            let mut expected: Vec<String> = (0..3)
                .filter(|&r| !owned[r].is_empty())
                .map(|r| format!("solution_{r}.vtu"))
                .collect();
            assert!(expected.len() >= 2, "{name} {split}: {expected:?}");
            expected.push("solution.pvtu".into());
            assert_eq!(names, expected);
            let pieces = files.len() - 1;
            let index = String::from_utf8(files[pieces].1.clone()).unwrap();
            let sources: Vec<&str> = index
                .lines()
                .filter_map(|l| l.strip_prefix("<Piece Source=\""))
                .map(|l| l.trim_end_matches("\"/>"))
                .collect();
            assert_eq!(sources, names[..pieces]);
            let mut seen = vec![0u32; mesh.n_cells()];
            for (_, piece) in &files[..pieces] {
                for (section, ids, id) in [
                    ("PointData", "node", "node_id"),
                    ("CellData", "cell", "cell_id"),
                ] {
                    let declared = arrays(index.as_bytes(), &format!("P{section}"));
                    assert_eq!(declared, arrays(piece, section), "{name} {split} {section}");
                    let at: Vec<usize> = i64s(piece, id).iter().map(|&i| i as usize).collect();
                    if ids == "cell" {
                        for &c in &at {
                            seen[c] += 1;
                        }
                    }
                    for (array, ty, k) in arrays(whole, section) {
                        let same = match ty.as_str() {
                            "Float64" => {
                                let (all, part) = (f64s(whole, &array), f64s(piece, &array));
                                at.iter().enumerate().all(|(j, &i)| {
                                    (0..k).all(|c| {
                                        all[k * i + c].to_bits() == part[k * j + c].to_bits()
                                    })
                                })
                            }
                            "Int32" => {
                                let (all, part) = (i32s(whole, &array), i32s(piece, &array));
                                at.iter().enumerate().all(|(j, &i)| {
                                    (0..k).all(|c| all[k * i + c] == part[k * j + c])
                                })
                            }
                            other => panic!("{array}: type {other}"),
                        };
                        assert!(
                            same,
                            "{name} {split}: {section} {array} differs from the serial file"
                        );
                    }
                    if ids == "cell" {
                        // Each cell's nodes, through node_id, are the serial cell's.
                        let (all, part) =
                            (i64s(whole, "connectivity"), i64s(piece, "connectivity"));
                        let node_id = i64s(piece, "node_id");
                        let nv = all.len() / mesh.n_cells();
                        assert!(at.iter().enumerate().all(|(j, &c)| (0..nv)
                            .all(|k| node_id[part[nv * j + k] as usize] == all[nv * c + k])));
                    }
                    if ids == "node" {
                        let (all, part) = (f64s(whole, "Points"), f64s(piece, "Points"));
                        assert!(at
                            .iter()
                            .enumerate()
                            .all(|(j, &i)| all[3 * i..3 * i + 3] == part[3 * j..3 * j + 3]));
                    }
                }
            }
            assert!(
                seen.iter().all(|&s| s == 1),
                "{name} {split}: a cell not in exactly one piece"
            );
            let folder = dir.join(format!("{}-{split}", name.trim_end_matches(".toml")));
            std::fs::create_dir_all(&folder).unwrap();
            for (f, bytes) in files.iter().chain(&serial) {
                std::fs::write(folder.join(f), bytes).unwrap();
            }
            // Every piece written holds cells (a rank that owns none writes none).
            to_check.extend(files[..pieces].iter().map(|(f, _)| folder.join(f)));
            pairs.push(folder);
        }
    }
    check_files(&to_check);
    python_check("check_pvtu.py", &pairs);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A mesh of 2 triangles on 4 processes (each node its own rank): the ranks that own no
/// cell (a cell belongs to the rank of its lowest node) write no piece and the index names
/// only the others; every piece holds points and cells and is read by meshio as by VTK,
/// and VTK's parallel reader reads the index as the serial file. Before, every rank had a
/// piece, and meshio could not read one of 0 points.
#[test]
fn ranks_that_own_no_cell_of_a_tiny_mesh_write_no_piece() {
    use common::vtu::i64s;
    use hemicontact::io::vtu::solution_files;
    use hemicontact::parallel::Partition;
    let text = r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [1, 1]
pattern = "uniform"
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "bottom"
[[loads.traction]]
part = "top"
value = [0.0, -10.0]
"#;
    let (problem, settings) = common::setup(text);
    let mut solution = hemicontact::solver::solve(&problem, &settings).unwrap();
    let mesh = problem.mesh();
    assert_eq!((mesh.n_nodes(), mesh.n_cells()), (4, 2));
    let serial = solution_files(&problem, &solution, "t", 1.0).unwrap();
    let partition = Partition::ranges(4, 4);
    let owned = partition.owned_cells(mesh);
    // Node 3 is the lowest node of no triangle: at least one rank owns nothing.
    let empty = owned.iter().filter(|c| c.is_empty()).count();
    assert!((2..=3).contains(&empty), "{owned:?}");
    solution.partition = Some(partition);
    let files = solution_files(&problem, &solution, "t", 1.0).unwrap();
    let names: Vec<&str> = files.iter().map(|(f, _)| f.as_str()).collect();
    let mut expected: Vec<String> = (0..4)
        .filter(|&r| !owned[r].is_empty())
        .map(|r| format!("solution_{r}.vtu"))
        .collect();
    expected.push("solution.pvtu".into());
    assert_eq!(names, expected);
    let pieces = files.len() - 1;
    assert_eq!(pieces, 4 - empty);
    let index = String::from_utf8(files[pieces].1.clone()).unwrap();
    let sources: Vec<&str> = index
        .lines()
        .filter_map(|l| l.strip_prefix("<Piece Source=\""))
        .map(|l| l.trim_end_matches("\"/>"))
        .collect();
    assert_eq!(sources, names[..pieces]);
    let mut cells: Vec<i64> = files[..pieces]
        .iter()
        .flat_map(|(_, piece)| {
            assert!(!i64s(piece, "node_id").is_empty());
            i64s(piece, "cell_id")
        })
        .collect();
    cells.sort_unstable();
    assert_eq!(cells, [0, 1]);
    let dir = common::fresh_dir("vtu-readers-tiny-pieces");
    for (f, bytes) in files.iter().chain(&serial) {
        std::fs::write(dir.join(f), bytes).unwrap();
    }
    let written: Vec<PathBuf> = files[..pieces].iter().map(|(f, _)| dir.join(f)).collect();
    check_files(&written);
    python_check("check_pvtu.py", std::slice::from_ref(&dir));
    let _ = std::fs::remove_dir_all(&dir);
}
