//! The linear-solver setting (`[solver] linear_solver = "direct" | "iterative" | "auto" |
//! "petsc"`):
//! the one place where `auto` is decided ([`LinearSolver::resolve`]), and where the chosen
//! solver is prepared ([`LinearSolver::prepare`]) and its memory estimated
//! ([`LinearSolver::memory_estimate`]). A new backend adds a variant to [`LinearSolver`]
//! (defined beside the interface [`SpdSolver`] whose `kind` names it, in [`super::solver`]),
//! one arm in each of these matches, and its implementation of [`SpdSolver`] in this
//! module's folder.

use super::direct::DirectSolver;
use super::iterative::MultigridCg;
/// The setting's values, defined beside the interface whose `kind` names them; kept here so
/// that `linalg::choice::LinearSolver` still names it.
pub use super::solver::LinearSolver;
use super::solver::SpdSolver;
use super::Ordering;
use crate::assembly::SystemPattern;
use crate::error::Result;
use crate::mesh::Mesh;
use crate::parallel::Processes;
use serde::{Deserialize, Serialize};

/// Whether this build has the PETSc backend (cargo feature `petsc`).
pub const HAS_PETSC: bool = cfg!(feature = "petsc");

/// Settings of the PETSc linear solver (`[solver.petsc]`).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PetscSettings {
    /// PETSc options in its command-line syntax, applied after the defaults (CG with GAMG)
    /// and before the `PETSC_OPTIONS` environment variable, e.g. `"-pc_type hypre"` or
    /// `"-ksp_type preonly -pc_type cholesky -pc_factor_mat_solver_type mumps"`. Default
    /// empty.
    pub options: String,
}

impl PetscSettings {
    /// Longest options string accepted (characters).
    pub const MAX_OPTIONS: usize = 4096;

    /// Checks the options: printable text (no control characters) of at most
    /// [`PetscSettings::MAX_OPTIONS`] characters, made of `-option [value]` words.
    ///
    /// # Errors
    /// [`crate::Error::Invalid`] naming `options`.
    pub fn validate(&self) -> Result<()> {
        let o = &self.options;
        let well_formed = o.chars().count() <= Self::MAX_OPTIONS
            && !o.chars().any(|c| c.is_control() && c != ' ' && c != '\t')
            && o.split_whitespace()
                .next()
                .is_none_or(|w| w.starts_with('-'));
        crate::error::require(
            well_formed,
            "options",
            format!("{o:?}"),
            &format!(
                "PETSc options as on its command line (e.g. \"-pc_type hypre\"): words \
                 starting with '-' and their values, at most {} characters",
                Self::MAX_OPTIONS
            ),
        )
    }
}

/// What the preparation of a linear solver needs besides the system.
#[derive(Clone, Copy, Debug)]
pub struct PrepareOptions<'a> {
    /// Fill-reducing ordering of the direct solver.
    pub ordering: Ordering,
    /// Parallelism of the direct solver's factorization and solves.
    pub par: faer::Par,
    /// PETSc options of the PETSc solver ([`PetscSettings::options`]).
    pub petsc_options: &'a str,
    /// Where the mesh's nodes sit among the processes (PETSc's rows follow it).
    pub placement: crate::parallel::Placement<'a>,
    /// The processes of the solve ([`crate::solver::SolverSettings::processes`]): those
    /// that share PETSc's distributed system when `placement` is of a part.
    pub processes: Processes,
}

impl LinearSolver {
    /// Number of equations from which `auto` chooses the iterative solver in 3D. Measured
    /// on `scenarios/paper3d-paper-gap.toml` (README section "3D at scale", end-to-end solves on the
    /// 2-core target, direct / iterative): 14 739 equations 0.99 s / 0.66 s, 46 875
    /// equations 8.2 s / 2.3 s, 104 544 equations 45 s / 5.3 s. Below 30 000 the gain is
    /// small and the direct solver is kept for its robustness (exact-constraint penalties
    /// make the Hessian ill-conditioned, which costs PCG iterations but not a
    /// factorization).
    pub const AUTO_ITERATIVE_EQUATIONS: usize = 30_000;

    /// The solver used for a system of dimension `dim` with `n_free` free equations (the
    /// unknowns after the Dirichlet elimination: `DofMap::n_free`, the order of the
    /// system pattern): [`LinearSolver::Direct`] or [`LinearSolver::Iterative`], or
    /// [`LinearSolver::Petsc`] when run as several MPI `processes`. The only
    /// place where `auto` is decided; every caller passes the number of free equations and
    /// the processes of the solve.
    pub fn resolve(self, dim: usize, n_free: usize, processes: &Processes) -> LinearSolver {
        match self {
            // Several MPI processes: the distributed solver.
            LinearSolver::Auto if processes.size() > 1 => LinearSolver::Petsc,
            LinearSolver::Auto if dim == 3 && n_free >= Self::AUTO_ITERATIVE_EQUATIONS => {
                LinearSolver::Iterative
            }
            LinearSolver::Auto => LinearSolver::Direct,
            other => other,
        }
    }

    /// Whether a Cholesky factorization of the stiffness is affordable for a check beside
    /// the solve (the uniqueness estimate): with the direct solver, and with PETSc where
    /// `auto` would choose the direct solver (on `processes`).
    pub fn cholesky_affordable(self, dim: usize, n_free: usize, processes: &Processes) -> bool {
        let kind = match self {
            LinearSolver::Petsc => LinearSolver::Auto,
            other => other,
        };
        kind.resolve(dim, n_free, processes) == LinearSolver::Direct
    }

    /// Whether this choice, resolved ([`LinearSolver::resolve`]), splits the problem among
    /// `processes`: each process then holds and solves its part of the mesh, whose
    /// matrix is partial in its ghost rows. Only the distributed solver (PETSc) can take
    /// such matrices, and only several processes have parts; every other solver (and any
    /// solver on one process) holds the whole system. The one place the solve decides to
    /// partition ([`crate::solver::System`]'s set-up).
    pub fn splits_the_problem(self, processes: &Processes) -> bool {
        self == LinearSolver::Petsc && processes.size() > 1
    }

    /// Checks that this build has the solver (`petsc` needs the cargo feature `petsc`), and
    /// that it is distributed when run as several MPI `processes`.
    ///
    /// # Errors
    /// [`crate::Error::Invalid`] naming `linear_solver`.
    pub fn validate(self, processes: &Processes) -> Result<()> {
        if self == LinearSolver::Petsc && !HAS_PETSC {
            return Err(Self::no_petsc());
        }
        let processes = processes.size();
        crate::error::require(
            processes == 1 || matches!(self, LinearSolver::Petsc | LinearSolver::Auto),
            "linear_solver",
            format!("{:?}", format!("{self:?}").to_lowercase()),
            &format!(
                "\"petsc\" or \"auto\" when run as {processes} MPI processes: only PETSc's \
                 solvers are distributed"
            ),
        )
    }

    /// The error of `linear_solver = "petsc"` in a build without PETSc.
    fn no_petsc() -> crate::Error {
        crate::Error::invalid(
            "linear_solver",
            "\"petsc\"",
            "\"direct\", \"iterative\" or \"auto\": this build of hemicontact has no PETSc \
             backend (build it with `--features petsc`, see docs/distributed.md)",
        )
    }

    /// Prepares the solver this setting resolves to ([`LinearSolver::resolve`] with
    /// `pattern.n()` free equations) for `pattern`, the reduced system of `mesh` with
    /// equation numbers `equations`: the symbolic Cholesky analysis for the direct solver,
    /// the multigrid grids and prolongations for the iterative one, PETSc's matrix and KSP
    /// for PETSc.
    ///
    /// # Errors
    /// [`crate::Error::OutOfMemory`] if the factor cannot be allocated;
    /// [`crate::Error::Invalid`] for PETSc options that PETSc refuses, or `petsc` in a
    /// build without it.
    pub fn prepare(
        self,
        mesh: &Mesh,
        equations: &[u32],
        pattern: &SystemPattern,
        options: &PrepareOptions,
    ) -> Result<Box<dyn SpdSolver>> {
        Ok(
            match self.resolve(mesh.dim(), pattern.n(), &options.processes) {
                LinearSolver::Iterative => Box::new(MultigridCg::new(mesh, equations, pattern)),
                #[cfg(feature = "petsc")]
                LinearSolver::Petsc => Box::new(super::petsc::PetscSolver::new(
                    mesh,
                    equations,
                    pattern,
                    options.petsc_options,
                    &options.placement,
                    &options.processes,
                )?),
                #[cfg(not(feature = "petsc"))]
                LinearSolver::Petsc => return Err(Self::no_petsc()),
                LinearSolver::Direct | LinearSolver::Auto => Box::new(DirectSolver::new(
                    mesh,
                    equations,
                    pattern,
                    options.ordering,
                    options.par,
                )?),
            },
        )
    }

    /// Estimated peak memory (bytes) of a solve on a mesh of dimension `dim` with `nodes`
    /// nodes and `cells` cells with the solver this setting resolves to for `n_free` free
    /// equations on `processes` (see [`LinearSolver::resolve`]).
    pub fn memory_estimate(
        self,
        dim: usize,
        n_free: usize,
        nodes: u64,
        cells: u64,
        processes: &Processes,
    ) -> u64 {
        match self.resolve(dim, n_free, processes) {
            // PETSc with GAMG was measured below the in-house multigrid (whole process,
            // `scripts/bench-petsc`: 537 MB against 697 MB at 107 811 DOFs), whose model
            // therefore bounds it.
            LinearSolver::Iterative | LinearSolver::Petsc => {
                MultigridCg::memory_estimate(dim, nodes, cells)
            }
            LinearSolver::Direct | LinearSolver::Auto => {
                DirectSolver::memory_estimate(dim, nodes, cells)
            }
        }
    }

    /// A lower bound of [`LinearSolver::memory_estimate`] over every number of free
    /// equations up to `max_free`, for a check before the free equations are known (the
    /// Dirichlet conditions not yet applied): the smaller estimate of the solvers this
    /// setting can resolve to on `processes`.
    pub fn memory_lower_bound(
        self,
        dim: usize,
        max_free: usize,
        nodes: u64,
        cells: u64,
        processes: &Processes,
    ) -> u64 {
        self.memory_estimate(dim, 0, nodes, cells, processes)
            .min(self.memory_estimate(dim, max_free, nodes, cells, processes))
    }
}
