//! hemicontact's bindings to PETSc: one symmetric positive definite system on a fixed
//! sparsity pattern, solved by a KSP (conjugate gradients with smoothed-aggregation
//! algebraic multigrid, GAMG, by default; any KSP and PC PETSc offers through its options).
//!
//! The C shim `src/shim.c` wraps the few PETSc calls used, with fixed-width argument types,
//! so this crate depends neither on the width of `PetscInt` nor on PETSc's macros. Its
//! unsafe code is confined here: every function of the shim is called under one process-wide
//! lock (PETSc is not thread-safe), and a [`KspSystem`] owns its PETSc objects.
//!
//! The crate is built only by hemicontact's `petsc` feature; it needs PETSc (≥ 3.18) found
//! by pkg-config.

use std::ffi::{c_char, c_int, CStr, CString};
use std::sync::Mutex;

mod ffi {
    use std::ffi::{c_char, c_int};

    /// The opaque system of the shim (`hc_system`).
    #[repr(C)]
    pub struct System {
        _private: [u8; 0],
    }

    extern "C" {
        pub fn hc_initialize() -> c_int;
        pub fn hc_last_error() -> *const c_char;
        pub fn hc_version() -> c_int;
        pub fn hc_int_size() -> c_int;
        pub fn hc_world(rank: *mut c_int, size: *mut c_int) -> c_int;
        pub fn hc_ranks_on_node(count: *mut c_int) -> c_int;
        pub fn hc_allreduce(values: *mut f64, n: i64, op: c_int) -> c_int;
        pub fn hc_allgatherv(
            local: *const f64,
            n_local: i64,
            global: *mut f64,
            n_global: i64,
        ) -> c_int;
        pub fn hc_abort(code: c_int);
        pub fn hc_partition(
            n: i64,
            xadj: *const i64,
            adjncy: *const i64,
            nparts: i64,
            parts: *mut i64,
        ) -> c_int;
        pub fn hc_system_create(
            n: i64,
            n_global: i64,
            first: i64,
            block_size: i64,
            row_ptr: *const i64,
            cols: *const i64,
            coordinates: *const f64,
            prefix: *const c_char,
            options: *const c_char,
            distributed: c_int,
            out: *mut *mut System,
        ) -> c_int;
        pub fn hc_system_destroy(system: *mut System);
        pub fn hc_system_set_values(system: *mut System, values: *const f64) -> c_int;
        pub fn hc_system_setup(system: *mut System) -> c_int;
        pub fn hc_system_can_keep_preconditioner(system: *mut System) -> c_int;
        pub fn hc_system_solve(
            system: *mut System,
            rtol: f64,
            max_iterations: i64,
            keep: c_int,
            b: *const f64,
            x: *mut f64,
            iterations: *mut i64,
            reason: *mut c_int,
            residual: *mut f64,
        ) -> c_int;
        pub fn hc_system_set_ghosts(system: *mut System, n: i64, rows: *const i64) -> c_int;
        pub fn hc_system_ghost_values(system: *mut System, out: *mut f64) -> c_int;
        pub fn hc_converged_reason(reason: c_int) -> *const c_char;
        pub fn hc_system_describe(system: *mut System, buf: *mut c_char, size: usize) -> c_int;
    }
}

/// The lock held around every call into PETSc, and the count of systems created (their
/// option prefixes `hc<k>_`).
static PETSC: Mutex<u64> = Mutex::new(0);

/// A PETSc error: its code and message.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Error {
    /// PETSc's error code (`PetscErrorCode`), or -1 for an error of these bindings.
    pub code: i32,
    /// What went wrong, as PETSc reported it where the error was raised.
    pub message: String,
}

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for Error {}

/// The error of the shim's return code `code` (`Ok` for 0), with the recorded message.
fn check(code: c_int) -> Result<(), Error> {
    if code == 0 {
        return Ok(());
    }
    // SAFETY: the shim returns a pointer to its static, NUL-terminated message buffer.
    let message = unsafe { CStr::from_ptr(ffi::hc_last_error()) }
        .to_string_lossy()
        .trim()
        .to_string();
    Err(Error {
        code,
        message: if message.is_empty() {
            format!("PETSc error {code}")
        } else {
            message
        },
    })
}

fn lock() -> std::sync::MutexGuard<'static, u64> {
    // A panic while the lock was held leaves PETSc's state as it was; go on with it.
    PETSC
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Initializes PETSc (and MPI, unless already initialized) once per process: without
/// PETSc's signal handler (`-no_signal_handler`: a Ctrl-C stays the application's), errors
/// recorded for [`Error`] instead of printed, finalized when the process exits. The
/// `PETSC_OPTIONS` environment variable is read here, as by every PETSc program.
///
/// # Errors
/// If PETSc cannot be initialized.
pub fn initialize() -> Result<(), Error> {
    let _guard = lock();
    // SAFETY: called under the lock; the shim initializes at most once.
    check(unsafe { ffi::hc_initialize() })
}

/// The parts of a graph split into `parts` by Scotch (the sequential library PT-Scotch is
/// built on, in a deterministic context: the same graph gives the same parts, every call
/// and every run), on this process alone: balanced parts with few edges between them. The
/// graph has `xadj.len() − 1` vertices; the neighbours of vertex `v` are
/// `adjncy[xadj[v]..xadj[v + 1]]` (symmetric, without `v` itself). Returns the part of
/// every vertex, `0..parts`.
///
/// # Errors
/// Scotch's; a build without Scotch's header; adjacency lists that are not a CSR graph of
/// their vertices.
pub fn partition(xadj: &[usize], adjncy: &[usize], parts: usize) -> Result<Vec<usize>, Error> {
    let invalid = |message: String| Error { code: -1, message };
    let n = xadj
        .len()
        .checked_sub(1)
        .ok_or_else(|| invalid("no vertex offsets".into()))?;
    if xadj[0] != 0 || xadj.windows(2).any(|w| w[0] > w[1]) || xadj[n] != adjncy.len() {
        return Err(invalid(
            "vertex offsets not increasing from 0 to the adjacency's length".into(),
        ));
    }
    if let Some(v) = (0..n).find(|&v| {
        adjncy[xadj[v]..xadj[v + 1]]
            .iter()
            .any(|&w| w >= n || w == v)
    }) {
        return Err(invalid(format!(
            "vertex {v} has a neighbour out of range or itself"
        )));
    }
    if parts == 0 {
        return Err(invalid("zero parts".into()));
    }
    let xadj: Vec<i64> = xadj.iter().map(|&k| k as i64).collect();
    let adjncy: Vec<i64> = adjncy.iter().map(|&k| k as i64).collect();
    let mut out = vec![0i64; n];
    let _guard = lock();
    // SAFETY: under the lock; initialized first; the arrays have the lengths the shim reads
    // (n + 1 offsets, xadj[n] neighbours, n parts).
    unsafe {
        check(ffi::hc_initialize())?;
        check(ffi::hc_partition(
            n as i64,
            xadj.as_ptr(),
            adjncy.as_ptr(),
            parts as i64,
            out.as_mut_ptr(),
        ))?;
    }
    Ok(out.into_iter().map(|p| p as usize).collect())
}

/// The PETSc version linked, as `(major, minor, subminor)`.
pub fn version() -> (u32, u32, u32) {
    // SAFETY: returns a compile-time constant of the shim.
    let v = unsafe { ffi::hc_version() } as u32;
    (v / 10000, v / 100 % 100, v % 100)
}

/// Bytes of PETSc's index type `PetscInt` (4 or 8): the largest system PETSc can hold has
/// fewer than 2^31 (or 2^63) rows and nonzeros.
pub fn index_bytes() -> usize {
    // SAFETY: returns a compile-time constant of the shim.
    unsafe { ffi::hc_int_size() as usize }
}

/// The processes of an MPI launch (`PETSC_COMM_WORLD`, which is `MPI_COMM_WORLD`): this
/// process's rank, their number, and the few collective operations a distributed solve
/// needs. Every method but [`World::rank`] and [`World::size`] is collective: every process
/// must call it, in the same order. A single process (no `mpirun`) is a world of size 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct World {
    rank: usize,
    size: usize,
}

impl World {
    /// Initializes PETSc and MPI ([`initialize`]) and returns the world.
    ///
    /// # Errors
    /// If PETSc or MPI cannot be initialized.
    pub fn get() -> Result<World, Error> {
        let _guard = lock();
        // SAFETY: under the lock; the shim initializes at most once.
        check(unsafe { ffi::hc_initialize() })?;
        let (mut rank, mut size) = (0 as c_int, 0 as c_int);
        // SAFETY: two valid out-pointers.
        check(unsafe { ffi::hc_world(&mut rank, &mut size) })?;
        Ok(World {
            rank: rank as usize,
            size: size as usize,
        })
    }

    /// This process's rank, 0 to `size − 1`.
    pub fn rank(&self) -> usize {
        self.rank
    }

    /// Number of processes.
    pub fn size(&self) -> usize {
        self.size
    }

    /// The number of processes of the world on this process's machine (those that share
    /// its memory, `MPI_COMM_TYPE_SHARED`), this one included. Collective.
    ///
    /// # Errors
    /// MPI's.
    pub fn ranks_on_node(&self) -> Result<usize, Error> {
        let _guard = lock();
        let mut count = 0 as c_int;
        // SAFETY: a valid out-pointer.
        check(unsafe { ffi::hc_ranks_on_node(&mut count) })?;
        Ok(count.max(1) as usize)
    }

    fn allreduce(&self, values: &mut [f64], op: c_int) -> Result<(), Error> {
        let _guard = lock();
        // SAFETY: the slice's pointer and length.
        check(unsafe { ffi::hc_allreduce(values.as_mut_ptr(), values.len() as i64, op) })
    }

    /// `values` ← their element-wise sum over the processes (same length on every one).
    ///
    /// # Errors
    /// MPI's.
    pub fn sum(&self, values: &mut [f64]) -> Result<(), Error> {
        self.allreduce(values, 0)
    }

    /// `values` ← their element-wise maximum over the processes.
    ///
    /// # Errors
    /// MPI's.
    pub fn max(&self, values: &mut [f64]) -> Result<(), Error> {
        self.allreduce(values, 1)
    }

    /// The concatenation of every process's `local` values, in rank order, on every process
    /// (`total`: its length, the sum of the local lengths).
    ///
    /// # Errors
    /// MPI's; a `total` other than the sum of the local lengths.
    pub fn all_gather(&self, local: &[f64], total: usize) -> Result<Vec<f64>, Error> {
        let mut global = vec![0.0; total];
        self.all_gather_into(local, &mut global)?;
        Ok(global)
    }

    /// As [`World::all_gather`], into `global` (its length: the sum of the local lengths).
    ///
    /// # Errors
    /// As [`World::all_gather`].
    pub fn all_gather_into(&self, local: &[f64], global: &mut [f64]) -> Result<(), Error> {
        let _guard = lock();
        // SAFETY: `local` and `global` with their lengths; the shim checks the total.
        check(unsafe {
            ffi::hc_allgatherv(
                local.as_ptr(),
                local.len() as i64,
                global.as_mut_ptr(),
                global.len() as i64,
            )
        })
    }

    /// Ends every process of the world with exit code `code` (`MPI_Abort`): the way out of
    /// a failure that only some processes see, which would otherwise leave the others
    /// waiting in a collective operation.
    pub fn abort(&self, code: i32) -> ! {
        // SAFETY: MPI_Abort does not return on a conforming MPI.
        unsafe { ffi::hc_abort(code) };
        std::process::exit(code)
    }
}

/// The outcome of one Krylov solve.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// Krylov iterations.
    pub iterations: usize,
    /// KSP's converged reason (`KSPConvergedReason`): positive when converged, negative when
    /// it diverged.
    pub reason: i32,
    /// The name of the reason (e.g. `CONVERGED_RTOL`, `DIVERGED_ITS`).
    pub reason_name: String,
    /// The final residual norm, in the norm the KSP measures (the true residual
    /// `‖b − A x‖` for the default conjugate gradients).
    pub residual_norm: f64,
}

impl Outcome {
    /// Whether the KSP converged (a positive reason).
    pub fn converged(&self) -> bool {
        self.reason > 0
    }
}

/// A symmetric positive definite system `A x = b` on a fixed sparsity pattern with its
/// Krylov solver: a sequential AIJ matrix preallocated once, values replaced in place, the
/// rigid-body modes of the nodes' coordinates as the near-null space of the preconditioner.
#[derive(Debug)]
pub struct KspSystem {
    raw: *mut ffi::System,
    n: usize,
    nnz: usize,
    prefix: String,
    /// Number of ghost rows set ([`KspSystem::set_ghost_rows`]).
    ghosts: usize,
}

// SAFETY: a system's PETSc objects are used by one thread at a time (`&mut self`), and every
// call into PETSc holds the process-wide lock.
unsafe impl Send for KspSystem {}

impl KspSystem {
    /// Creates the system of order `row_ptr.len() − 1` with the CSR pattern `(row_ptr,
    /// cols)` (both triangles, columns sorted within each row), the nodes' `coordinates`
    /// in DOF order (`block_size` DOFs per node, the rows of a node contiguous) for the
    /// rigid-body modes, and the KSP configured by: the defaults (CG with GAMG), then
    /// `options` (PETSc's command-line syntax,
    /// e.g. `-ksp_type preonly -pc_type cholesky`), then the `PETSC_OPTIONS` environment
    /// variable, the later winning. The options are stored under this system's own prefix
    /// ([`KspSystem::prefix`]), so systems of one process do not share them.
    ///
    /// # Errors
    /// PETSc's, e.g. for an unknown KSP or PC type; and for inconsistent arrays.
    pub fn new(
        row_ptr: &[usize],
        cols: &[usize],
        coordinates: &[f64],
        block_size: usize,
        options: &str,
    ) -> Result<Self, Error> {
        let n = row_ptr.len().saturating_sub(1);
        Self::create(n, 0, row_ptr, cols, coordinates, block_size, options, false)
    }

    /// As [`KspSystem::new`] for a system of order `n_global` distributed over the
    /// processes of the [`World`] (collective): this process holds the rows `first ..
    /// first + row_ptr.len() − 1` (a whole number of `block_size` blocks), with their
    /// pattern in global column numbers and the coordinates of their nodes; the vectors of
    /// [`KspSystem::solve`] are then this process's part.
    ///
    /// # Errors
    /// As [`KspSystem::new`]; rows that do not add up to `n_global` over the processes.
    pub fn new_distributed(
        n_global: usize,
        first: usize,
        row_ptr: &[usize],
        cols: &[usize],
        coordinates: &[f64],
        block_size: usize,
        options: &str,
    ) -> Result<Self, Error> {
        Self::create(
            n_global,
            first,
            row_ptr,
            cols,
            coordinates,
            block_size,
            options,
            true,
        )
    }

    #[allow(clippy::too_many_arguments)]
    fn create(
        n_global: usize,
        first: usize,
        row_ptr: &[usize],
        cols: &[usize],
        coordinates: &[f64],
        block_size: usize,
        options: &str,
        distributed: bool,
    ) -> Result<Self, Error> {
        let n = row_ptr.len().saturating_sub(1);
        let n_global = if distributed { n_global } else { n };
        let nnz = row_ptr.last().copied().unwrap_or(0);
        let invalid = |message: String| Err(Error { code: -1, message });
        if row_ptr.is_empty() || cols.len() != nnz || coordinates.len() != n {
            return invalid(format!(
                "inconsistent system: {} row pointers, {} columns, {} coordinates",
                row_ptr.len(),
                cols.len(),
                coordinates.len()
            ));
        }
        if !(1..=3).contains(&block_size)
            || !n.is_multiple_of(block_size)
            || !first.is_multiple_of(block_size)
            || first + n > n_global
        {
            return invalid(format!(
                "rows {first} to {} of {n_global} are not whole blocks of {block_size} (allowed \
                 block sizes: 1 to 3)",
                first + n
            ));
        }
        if row_ptr.windows(2).any(|w| w[0] > w[1]) || cols.iter().any(|&c| c >= n_global) {
            return invalid("row pointers not monotone or a column out of range".into());
        }
        let mut env = String::new();
        if let Ok(value) = std::env::var("PETSC_OPTIONS") {
            env = value;
        }
        let all = format!("{options} {env}");
        let Ok(c_options) = CString::new(all) else {
            return invalid("the PETSc options contain a NUL character".into());
        };
        let to_i64 = |v: &[usize]| v.iter().map(|&k| k as i64).collect::<Vec<i64>>();
        let (row_ptr, cols) = (to_i64(row_ptr), to_i64(cols));
        let mut count = lock();
        // SAFETY: under the lock.
        check(unsafe { ffi::hc_initialize() })?;
        *count += 1;
        let prefix = format!("hc{}_", *count);
        let c_prefix = CString::new(prefix.clone()).unwrap_or_default();
        let mut raw = std::ptr::null_mut();
        // SAFETY: the arrays have the lengths checked above (n + 1, nnz, n); the strings are
        // NUL-terminated; the shim copies what it keeps.
        check(unsafe {
            ffi::hc_system_create(
                n as i64,
                n_global as i64,
                first as i64,
                block_size as i64,
                row_ptr.as_ptr(),
                cols.as_ptr(),
                coordinates.as_ptr(),
                c_prefix.as_ptr(),
                c_options.as_ptr(),
                c_int::from(distributed),
                &mut raw,
            )
        })?;
        Ok(KspSystem {
            raw,
            n,
            nnz,
            prefix,
            ghosts: 0,
        })
    }

    /// Rows of the system held by this process (its order, unless distributed).
    pub fn n(&self) -> usize {
        self.n
    }

    /// The options prefix of this system (`hc<k>_`): `-hc<k>_ksp_monitor` on the command
    /// line or in `PETSC_OPTIONS` would reach this system alone.
    pub fn prefix(&self) -> &str {
        &self.prefix
    }

    /// Replaces the matrix values, given in the CSR order of the pattern (length: the
    /// pattern's nonzeros). The preconditioner is not touched: [`KspSystem::setup`] builds
    /// it for the new values, or a solve keeping it uses the old one.
    ///
    /// # Errors
    /// PETSc's; a length other than the pattern's.
    pub fn set_values(&mut self, values: &[f64]) -> Result<(), Error> {
        if values.len() != self.nnz {
            return Err(Error {
                code: -1,
                message: format!("{} values for {} nonzeros", values.len(), self.nnz),
            });
        }
        let _guard = lock();
        // SAFETY: `values` has the pattern's length; the system is alive.
        check(unsafe { ffi::hc_system_set_values(self.raw, values.as_ptr()) })
    }

    /// Sets the preconditioner up for the current matrix values (GAMG's coarsening and
    /// Galerkin products, a factorization, …).
    ///
    /// # Errors
    /// PETSc's, e.g. a zero pivot.
    pub fn setup(&mut self) -> Result<(), Error> {
        let _guard = lock();
        // SAFETY: the system is alive.
        check(unsafe { ffi::hc_system_setup(self.raw) })
    }

    /// Whether a solve may keep a preconditioner set up for other matrix values: only for
    /// conjugate gradients measuring the true residual `‖b − A x‖`, where an old
    /// preconditioner costs iterations and never accuracy (not, e.g., for `preonly`, whose
    /// "solve" would be the old factor's).
    pub fn can_keep_preconditioner(&self) -> bool {
        let _guard = lock();
        // SAFETY: the system is alive.
        unsafe { ffi::hc_system_can_keep_preconditioner(self.raw) != 0 }
    }

    /// Solves `A x = b` from a zero initial guess to the relative residual `rtol` in at
    /// most `max_iterations` iterations (0: the KSP's own limit; both unless the options
    /// fixed `-ksp_rtol` or `-ksp_max_it`), with the preconditioner kept as it is (`keep`)
    /// or set up for changed values.
    ///
    /// # Errors
    /// PETSc's (a failed preconditioner set-up included); lengths other than the order.
    /// A solve that stops without converging is not an error: see [`Outcome::converged`].
    pub fn solve(
        &mut self,
        b: &[f64],
        x: &mut [f64],
        rtol: f64,
        max_iterations: usize,
        keep: bool,
    ) -> Result<Outcome, Error> {
        if b.len() != self.n || x.len() != self.n {
            return Err(Error {
                code: -1,
                message: format!(
                    "vectors of lengths {} and {} for a system of order {}",
                    b.len(),
                    x.len(),
                    self.n
                ),
            });
        }
        let _guard = lock();
        let (mut iterations, mut reason, mut residual) = (0i64, 0 as c_int, 0.0f64);
        // SAFETY: `b` and `x` have the system's order; the system is alive.
        check(unsafe {
            ffi::hc_system_solve(
                self.raw,
                rtol,
                max_iterations as i64,
                c_int::from(keep),
                b.as_ptr(),
                x.as_mut_ptr(),
                &mut iterations,
                &mut reason,
                &mut residual,
            )
        })?;
        // SAFETY: the shim returns one of PETSc's static reason names.
        let reason_name = unsafe { CStr::from_ptr(ffi::hc_converged_reason(reason)) }
            .to_string_lossy()
            .into_owned();
        Ok(Outcome {
            iterations: iterations.max(0) as usize,
            reason,
            reason_name,
            residual_norm: residual,
        })
    }

    /// Sets the rows `rows` (global numbers, held by any process) whose values of the last
    /// solution [`KspSystem::ghost_values`] fetches: a PETSc scatter from the distributed
    /// solution vector, built once. Collective: every process calls it, with its own rows
    /// (none is allowed).
    ///
    /// # Errors
    /// PETSc's, e.g. a row beyond the system's order.
    pub fn set_ghost_rows(&mut self, rows: &[usize]) -> Result<(), Error> {
        let rows: Vec<i64> = rows.iter().map(|&r| r as i64).collect();
        let _guard = lock();
        // SAFETY: `rows` has the length passed; the shim copies it; the system is alive.
        check(unsafe { ffi::hc_system_set_ghosts(self.raw, rows.len() as i64, rows.as_ptr()) })?;
        self.ghosts = rows.len();
        Ok(())
    }

    /// The values of the last solution ([`KspSystem::solve`]) at the rows of
    /// [`KspSystem::set_ghost_rows`], in their order, into `out`, each from the process
    /// that holds it. Collective: every process calls it after the same solve.
    ///
    /// # Errors
    /// PETSc's; no ghost rows set; an `out` of another length.
    pub fn ghost_values(&mut self, out: &mut [f64]) -> Result<(), Error> {
        if out.len() != self.ghosts {
            return Err(Error {
                code: -1,
                message: format!("{} values for {} ghost rows", out.len(), self.ghosts),
            });
        }
        let _guard = lock();
        // SAFETY: `out` has the number of ghost rows set (the shim refuses if none was).
        check(unsafe { ffi::hc_system_ghost_values(self.raw, out.as_mut_ptr()) })
    }

    /// The Krylov method and preconditioner in use, e.g. `ksp cg, pc gamg`, or
    /// `ksp preonly, pc cholesky, mumps` (known after the first solve for factor packages).
    pub fn describe(&self) -> String {
        let mut buf = vec![0 as c_char; 256];
        let _guard = lock();
        // SAFETY: the buffer's length is passed; the shim NUL-terminates within it.
        let code = unsafe { ffi::hc_system_describe(self.raw, buf.as_mut_ptr(), buf.len()) };
        if code != 0 {
            return String::from("?");
        }
        // SAFETY: NUL-terminated by the shim (snprintf).
        unsafe { CStr::from_ptr(buf.as_ptr()) }
            .to_string_lossy()
            .into_owned()
    }
}

impl Drop for KspSystem {
    fn drop(&mut self) {
        let _guard = lock();
        // SAFETY: the system was created by the shim and is destroyed once.
        unsafe { ffi::hc_system_destroy(self.raw) }
    }
}
