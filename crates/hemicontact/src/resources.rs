//! Resource limits: an estimate of the memory a solve needs, checked against the memory
//! available before anything large is allocated, so that an oversized request fails fast
//! with a clear message instead of after minutes or by the kernel's OOM killer.

/// Memory currently available to the process (bytes): `MemAvailable` of `/proc/meminfo`,
/// lowered to the room left under the memory limit of the process's control group (a
/// container or batch-job limit: cgroup v2 `memory.max − memory.current`, or v1
/// `memory.limit_in_bytes − memory.usage_in_bytes`) where one is set; `None` where
/// nothing can be read (then no limit is applied).
pub fn available_memory() -> Option<u64> {
    let meminfo = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|text| {
            let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
            let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
            Some(kib * 1024)
        });
    let cgroup = cgroup_room();
    match (meminfo, cgroup) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// Room left under the control group's memory limit (bytes), if a limit is set.
fn cgroup_room() -> Option<u64> {
    let read = |p: &str| std::fs::read_to_string(p).ok();
    // cgroup v2: the unified hierarchy, at the path of the `0::` line of /proc/self/cgroup.
    let v2_path = read("/proc/self/cgroup").and_then(|t| {
        t.lines()
            .find_map(|l| l.strip_prefix("0::").map(|p| p.trim().to_string()))
    });
    if let Some(path) = v2_path {
        let base = format!("/sys/fs/cgroup{}", if path == "/" { "" } else { &path });
        if let (Some(max), Some(cur)) = (
            read(&format!("{base}/memory.max")),
            read(&format!("{base}/memory.current")),
        ) {
            return room(&max, &cur);
        }
    }
    // cgroup v1: the memory controller's own mount (a container sees its group as root).
    room(
        &read("/sys/fs/cgroup/memory/memory.limit_in_bytes")?,
        &read("/sys/fs/cgroup/memory/memory.usage_in_bytes")?,
    )
}

/// `limit − usage` from the two files' contents; `None` without a limit (`max`, or v1's
/// "unlimited" 2⁶³ − page size) or on unreadable contents.
fn room(limit: &str, usage: &str) -> Option<u64> {
    let limit: u64 = limit.trim().parse().ok()?;
    let usage: u64 = usage.trim().parse().ok()?;
    if limit >= 1 << 62 {
        return None;
    }
    Some(limit.saturating_sub(usage))
}

/// Estimated peak memory (bytes) of a solve on a generated `nx × ny` rectangle (2D).
///
/// Calibrated on the paper's square (`hemicontact bench --paper`): the nested-dissection
/// Cholesky factor holds about `6 N log₂ N` entries for N DOFs (measured 5.3 at n = 128,
/// 5.9 at n = 512), the matrix about `8 N` (stored four times: pattern, values, factorized
/// copy, assembly buffer), plus 84 bytes of scatter slots per cell and about ten DOF
/// vectors; a 20 % margin covers the solver's work space. A factorization laid out as two
/// substructures ([`crate::linalg::substructures`]) holds 8 % more factor entries and a
/// copy of the matrix in each substructure (values, 32-bit positions and row indices, and
/// the counting sort's pairs while it is built: 24 bytes per entry). The estimate for
/// n = 512 is 0.95 GiB; the measured peak is 0.93 GiB with substructures (two threads) and
/// 0.80 GiB without (one thread).
pub fn estimate_rectangle(nx: u64, ny: u64) -> u64 {
    let nodes = (nx as f64 + 1.0) * (ny as f64 + 1.0);
    let cells = 2.0 * nx as f64 * ny as f64;
    estimate_triangles(nodes, cells)
}

/// [`estimate_rectangle`]'s model for any triangle mesh of `nodes` nodes and `cells` cells.
fn estimate_triangles(nodes: f64, cells: f64) -> u64 {
    let n = 2.0 * nodes;
    let factor = 1.08 * 6.0 * n * n.max(2.0).log2() * 8.0;
    let matrix = 8.0 * n * 32.0;
    let substructures = 8.0 * n * 24.0;
    let slots = 84.0 * cells;
    let vectors = 10.0 * 8.0 * n + 28.0 * nodes + 12.0 * cells;
    let total = 1.2 * (factor + matrix + substructures + slots + vectors);
    total.min(u64::MAX as f64) as u64
}

/// Formats a byte count in GiB.
pub fn gib(bytes: u64) -> String {
    format!("{:.2} GiB", bytes as f64 / (1u64 << 30) as f64)
}

/// Estimated peak memory (bytes) of a solve on a generated `nx × ny × nz` box (3D).
///
/// Provisional (not yet calibrated against a 3D benchmark): a nested-dissection factor of
/// about `25 N^{4/3}` entries for N DOFs, the matrix about `40 N` entries stored four
/// times, 312 bytes of scatter slots per tetrahedron, ten DOF vectors, and a 20 % margin.
pub fn estimate_box(nx: u64, ny: u64, nz: u64) -> u64 {
    let nodes = (nx as f64 + 1.0) * (ny as f64 + 1.0) * (nz as f64 + 1.0);
    let cells = 6.0 * nx as f64 * ny as f64 * nz as f64;
    estimate_tetrahedra(nodes, cells)
}

/// Estimated peak memory (bytes) of a solve on a generated `nx × ny × nz` box (3D) with
/// the iterative linear solver ([`crate::solver::LinearSolver::Iterative`]): no factor;
/// the matrix as in [`estimate_box`], plus the multigrid fine operator in full CSR (about
/// 80 N entries of 16 bytes: column, value, slot), coarse operators and work products
/// (about 30 % more), the prolongations (8 entries of 12 bytes per row, twice) and the
/// Galerkin intermediate `A P` (about 30 N entries), with the same 20 % margin. On
/// `scenarios/paper3d-paper-gap.toml` the estimate is 0.51 GiB at n = 32 (measured peak 0.38 GiB)
/// and 1.69 GiB at n = 48 (measured 1.23 GiB): conservative by about 1.4×.
pub fn estimate_box_iterative(nx: u64, ny: u64, nz: u64) -> u64 {
    let nodes = (nx as f64 + 1.0) * (ny as f64 + 1.0) * (nz as f64 + 1.0);
    let cells = 6.0 * nx as f64 * ny as f64 * nz as f64;
    estimate_tetrahedra_iterative(nodes, cells)
}

/// [`estimate_box_iterative`]'s model for any tetrahedral mesh.
pub fn estimate_tetrahedra_iterative(nodes: f64, cells: f64) -> u64 {
    let n = 3.0 * nodes;
    let matrix = 40.0 * n * 32.0;
    let hierarchy = 1.3 * 80.0 * n * 16.0 + 2.0 * 8.0 * n * 12.0 + 30.0 * n * 12.0;
    let slots = 312.0 * cells;
    let vectors = 20.0 * 8.0 * n + 40.0 * nodes + 16.0 * cells;
    let total = 1.2 * (matrix + hierarchy + slots + vectors);
    total.min(u64::MAX as f64) as u64
}

/// [`estimate_box`]'s model for any tetrahedral mesh of `nodes` nodes and `cells` cells.
fn estimate_tetrahedra(nodes: f64, cells: f64) -> u64 {
    let n = 3.0 * nodes;
    let factor = 25.0 * n.powf(4.0 / 3.0) * 8.0;
    let matrix = 40.0 * n * 32.0;
    let slots = 312.0 * cells;
    let vectors = 10.0 * 8.0 * n + 40.0 * nodes + 16.0 * cells;
    let total = 1.2 * (factor + matrix + slots + vectors);
    total.min(u64::MAX as f64) as u64
}

/// Estimated peak memory (bytes) of a solve on a read mesh of dimension `dim` with `nodes`
/// nodes and `cells` cells: the models of [`estimate_rectangle`] (d = 2) and
/// [`estimate_box`] (d = 3) applied to the counts. A rough guide for unstructured meshes,
/// whose fill-in depends on their shape.
pub fn estimate_mesh(dim: usize, nodes: u64, cells: u64) -> u64 {
    if dim == 2 {
        estimate_triangles(nodes as f64, cells as f64)
    } else {
        estimate_tetrahedra(nodes as f64, cells as f64)
    }
}

/// Resident memory (bytes) of one process of an MPI launch before its share of the problem:
/// the program, PETSc and MPI. The processes of `scenarios/paper3d.toml` (14 739 DOFs)
/// peaked at 64.1 to 78.0 MiB on 4 processes, 58.1 to 70.5 MiB on 16.
pub const PROCESS_BASE: u64 = 64 << 20;

/// Estimated peak memory (bytes) that the `on_machine` processes of an MPI launch of
/// `processes` processes need on one machine, for a solve whose one-process estimate is
/// `whole` on a mesh of dimension `dim` with `nodes` nodes and `cells` cells. Each process
/// holds [`PROCESS_BASE`], its share `whole / processes` of the Newton matrix and the linear
/// solver, and the replicated mesh and vectors, `1.5 V` (`V`: the DOF-vector term of the
/// one-process models, with their 20 % margin); rank 0 holds `4 V` more (the partition of
/// the whole node graph and the writing of every piece of the result), counted on every
/// machine:
///
/// `on_machine · (PROCESS_BASE + whole / processes + 1.5 V) + 4 V`.
///
/// Measured on `scenarios/hertz3d.toml` with PETSc (107 811 DOFs; one process: 0.50 GB,
/// the model 0.55 GB), all processes together: 0.74, 0.78, 1.13 and 1.95 GB on 2, 4, 8 and
/// 16 processes, the model 0.87, 1.08, 1.51 and 2.36 GB.
pub fn estimate_machine(
    whole: u64,
    dim: usize,
    nodes: u64,
    cells: u64,
    processes: usize,
    on_machine: usize,
) -> u64 {
    let v = replicated(dim, nodes as f64, cells as f64) as u64;
    let per_process = PROCESS_BASE + whole / processes.max(1) as u64 + 3 * v / 2;
    (on_machine as u64)
        .saturating_mul(per_process)
        .saturating_add(4 * v)
}

/// The DOF-vector term of the one-process models with their 20 % margin (bytes): what every
/// process of an MPI launch holds whole.
fn replicated(dim: usize, nodes: f64, cells: f64) -> f64 {
    let n = dim as f64 * nodes;
    let vectors = if dim == 2 {
        10.0 * 8.0 * n + 28.0 * nodes + 12.0 * cells
    } else {
        20.0 * 8.0 * n + 40.0 * nodes + 16.0 * cells
    };
    1.2 * vectors
}

/// Estimated peak memory (bytes) of reading a mesh file of `file_bytes` bytes: the file's
/// content, plus the node, cell and facet arrays and the facet-matching work space. The
/// densest case is an ASCII tetrahedral mesh written with one-digit node tags (about 10
/// bytes per tetrahedron in the file, 64 bytes of facet keys and about 20 of cell data in
/// memory): nine times the file covers it.
pub fn estimate_mesh_read(file_bytes: u64) -> u64 {
    file_bytes.saturating_mul(9)
}

#[cfg(test)]
mod tests {
    use super::room;

    /// The model bounds a measured run with the parallel assembly's work arrays:
    /// `scenarios/paper3d.toml` at n = 64 (274 625 nodes, 1 572 864 tetrahedra, 823 875
    /// DOFs, iterative solver) on 2 threads peaked at 2 929 120 KiB (`RAYON_NUM_THREADS=2
    /// /usr/bin/time -f %M hemicontact solve`; 3 096 900 KiB with the earlier assembly's
    /// second Hessian). The work arrays are a few bytes per cell, none on one task or below
    /// 4096 cells per task.
    #[test]
    fn the_memory_model_bounds_a_measured_3d_run() {
        use crate::assembly::global::Workspace;
        let (nodes, cells) = (274_625usize, 1_572_864usize);
        let measured = 2_929_120u64 * 1024;
        let model = super::estimate_tetrahedra_iterative(nodes as f64, cells as f64)
            + Workspace::buffer_bytes(2, cells);
        assert!(model >= measured, "{model} {measured}");
        // Not wildly above it either: within 1.5 times.
        assert!(model as f64 <= 1.5 * measured as f64, "{model} {measured}");
        assert_eq!(Workspace::buffer_bytes(2, cells), 26 * cells as u64);
        assert_eq!(Workspace::buffer_bytes(1, cells), 0);
        assert_eq!(Workspace::buffer_bytes(16, 4095), 0);
        assert_eq!(Workspace::buffer_bytes(16, 2 * 4096), 26 * 2 * 4096);
    }

    /// The model of the processes of an MPI launch on one machine bounds the measured peaks
    /// of `scenarios/hertz3d.toml` with `linear_solver = "petsc"` (35 937 nodes, 196 608
    /// tetrahedra), one thread per process, `mpirun -np N /usr/bin/time -f %M hemicontact
    /// solve`, 1 to 16 processes on the 2-core machine: the sum over the processes and the
    /// largest (rank 0), within 1.5 times; and the sum for `scenarios/paper3d.toml` on 4
    /// and 16 processes, where [`super::PROCESS_BASE`] is most of it.
    #[test]
    fn the_model_of_several_processes_bounds_measured_runs() {
        use super::{estimate_machine, estimate_tetrahedra_iterative};
        let (nodes, cells) = (35_937u64, 196_608u64);
        let whole = estimate_tetrahedra_iterative(nodes as f64, cells as f64);
        let kib = |k: &[u64]| k.iter().sum::<u64>() * 1024;
        // Peak KiB of each process, rank 0 first.
        let np1 = [483_532u64];
        let np2 = [409_564u64, 317_320];
        let np4 = [250_256u64, 172_320, 170_396, 170_292];
        let np8 = [
            210_964u64, 122_584, 123_824, 125_948, 126_072, 130_676, 131_008, 133_008,
        ];
        let np16 = [
            187_548u64, 108_556, 110_000, 111_316, 111_384, 111_940, 112_212, 113_096, 113_188,
            113_596, 114_832, 116_248, 117_104, 117_420, 119_440, 122_784,
        ];
        assert!(whole >= kib(&np1) && (whole as f64) < 1.5 * kib(&np1) as f64);
        for runs in [&np2[..], &np4[..], &np8[..], &np16[..]] {
            let p = runs.len();
            let all = estimate_machine(whole, 3, nodes, cells, p, p);
            assert!(all >= kib(runs), "{p} processes: {all} {}", kib(runs));
            assert!((all as f64) < 1.5 * kib(runs) as f64, "{p}: {all}");
            // Rank 0 alone (one process on its machine).
            let root = estimate_machine(whole, 3, nodes, cells, p, 1);
            assert!(root >= kib(&runs[..1]), "{p}: rank 0 {root}");
        }
        // A small mesh, where the processes' own memory dominates: paper3d.toml (4913
        // nodes, 24 576 tetrahedra) on 4 and 16 processes.
        let (nodes, cells) = (4913u64, 24_576u64);
        let whole = estimate_tetrahedra_iterative(nodes as f64, cells as f64);
        let small4 = [79_888u64, 66_152, 65_624, 65_664];
        let small16 = [
            72_196u64, 59_544, 59_632, 60_268, 60_364, 60_372, 60_424, 60_572, 60_892, 61_064,
            61_168, 61_584, 61_628, 61_908, 62_440, 62_684,
        ];
        for runs in [&small4[..], &small16[..]] {
            let p = runs.len();
            let all = estimate_machine(whole, 3, nodes, cells, p, p);
            assert!(all >= kib(runs), "{p} processes: {all} {}", kib(runs));
            assert!((all as f64) < 1.5 * kib(runs) as f64, "{p}: {all}");
        }
        // More processes on a machine need more of it than one process does.
        assert!(estimate_machine(whole, 3, nodes, cells, 16, 16) > 2 * whole);
    }

    /// The cgroup limit files: v2 `max` and v1's "unlimited" mean no limit; otherwise the
    /// room is limit − usage, never negative.
    #[test]
    fn cgroup_room_reads_limits() {
        assert_eq!(room("max\n", "123\n"), None);
        assert_eq!(room("9223372036854771712\n", "5"), None);
        assert_eq!(room("1000\n", "250\n"), Some(750));
        assert_eq!(room("1000", "2000"), Some(0));
        assert_eq!(room("garbage", "1"), None);
    }
}
