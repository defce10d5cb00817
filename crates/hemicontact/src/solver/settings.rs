//! The settings of the solver ([`SolverSettings`]) and of its parts: the Newton method
//! ([`NewtonSettings`]), the outer loop ([`OuterSettings`]) and the exact constraints
//! ([`ConstraintSettings`]); each with the check of its ranges.

use super::constraints::ConstraintSettings;
use crate::error::Result;
use crate::linalg::{LinearSolver, Ordering, PetscSettings};
use crate::parallel::Processes;
use serde::{Deserialize, Serialize};

/// Solver settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SolverSettings {
    /// Fill-reducing ordering of the sparse Cholesky factorization. Default: nested
    /// dissection, which gives the smallest factor on the meshes measured by
    /// `hemicontact bench`.
    pub ordering: Ordering,
    /// Parallel tasks for the assembly (0: one per core; each task a range of nodes, the
    /// result the same to the last bit for any number). Default 0: on the 2-core target,
    /// two tasks assemble 1.2 to 1.9 times faster than one, the machine's noise included
    /// (`cargo run --release -p hemicontact --example assembly_threads`).
    pub threads: usize,
    /// Threads inside the dense blocks of the sparse Cholesky factorization and solves (0:
    /// all cores). Default 1: faer's parallel supernodal factorization was measured *slower*
    /// than the sequential one on the 2-core target (paper square, n = 512: 1.5–1.7 s
    /// against 1.1 s; n = 128: 80 ms against 35 ms), the two cores contending for memory
    /// bandwidth. A factorization laid out as two substructures
    /// ([`crate::linalg::substructures`]) runs them side by side on rayon's pool whatever
    /// this setting.
    pub factorization_threads: usize,
    /// Linear solver of the Newton systems (`[solver] linear_solver = "direct"`,
    /// `"iterative"`, `"auto"` or `"petsc"`). Default `auto`; see [`LinearSolver`].
    pub linear_solver: LinearSolver,
    /// Settings of the PETSc linear solver (`[solver.petsc]`), used with
    /// `linear_solver = "petsc"`.
    pub petsc: PetscSettings,
    /// Newton method settings.
    pub newton: NewtonSettings,
    /// Outer (convexification) loop settings.
    pub outer: OuterSettings,
    /// Exact constraints (augmented Lagrangian) settings.
    pub constraints: ConstraintSettings,
    /// Tolerance of the certificate (dimensionless): every residual of the contact laws,
    /// of equilibrium and of the exact constraints, relative to the solution's own scales,
    /// must be at most this for a solve to count as converged. Default 1e-6; see
    /// [`super::certificate`].
    pub certificate_tolerance: f64,
    /// The processes the solve runs on: not a setting of the file, but those of the
    /// program's launch ([`Processes::launch`]), which the caller passes here
    /// ([`crate::scenario::Scenario::on`]); on several, `auto` resolves to PETSc and the
    /// problem is split among them ([`LinearSolver::splits_the_problem`]). Default: this
    /// process alone.
    #[serde(skip)]
    pub processes: Processes,
}

impl Default for SolverSettings {
    fn default() -> Self {
        SolverSettings {
            ordering: Ordering::default(),
            threads: 0,
            factorization_threads: 1,
            linear_solver: LinearSolver::default(),
            petsc: PetscSettings::default(),
            newton: NewtonSettings::default(),
            outer: OuterSettings::default(),
            constraints: ConstraintSettings::default(),
            certificate_tolerance: 1e-6,
            processes: Processes::alone(),
        }
    }
}

/// Most threads a setting may ask for: far above any core count this solver runs on, low
/// enough that the per-thread buffers of a mistyped count cannot exhaust memory.
pub const MAX_THREADS: usize = 1024;

impl SolverSettings {
    /// Checks every setting against its range, the nested ones included.
    ///
    /// # Errors
    /// [`crate::Error::Invalid`] naming the setting by its path from here (e.g.
    /// `newton.armijo`): `certificate_tolerance` in [1e-14, 1), thread counts up to
    /// [`MAX_THREADS`], `linear_solver` available in this build and on [`Self::processes`]
    /// ([`LinearSolver::validate`]),
    /// [`PetscSettings::validate`], and the ranges of [`NewtonSettings::validate`],
    /// [`OuterSettings::validate`] and [`ConstraintSettings::validate`].
    pub fn validate(&self) -> Result<()> {
        use crate::error::require;
        let tol = self.certificate_tolerance;
        require(
            tol.is_finite() && (1e-14..1.0).contains(&tol),
            "certificate_tolerance",
            tol,
            "a relative tolerance in [1e-14, 1)",
        )?;
        for (field, n) in [
            ("threads", self.threads),
            ("factorization_threads", self.factorization_threads),
        ] {
            require(
                n <= MAX_THREADS,
                field,
                n,
                &format!("a thread count from 0 (all cores) to {MAX_THREADS}"),
            )?;
        }
        self.linear_solver.validate(&self.processes)?;
        self.petsc.validate().map_err(|e| e.within("petsc"))?;
        self.newton.validate().map_err(|e| e.within("newton"))?;
        self.outer.validate().map_err(|e| e.within("outer"))?;
        self.constraints
            .validate()
            .map_err(|e| e.within("constraints"))
    }
}

/// Builds the faer parallelism for `threads` (0: all available cores).
pub fn parallelism(threads: usize) -> faer::Par {
    let threads = if threads == 0 {
        rayon::current_num_threads()
    } else {
        threads
    };
    if threads <= 1 {
        faer::Par::Seq
    } else {
        faer::Par::rayon(threads)
    }
}

/// Newton method settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct NewtonSettings {
    /// Maximum number of Newton steps. Default 50: a convex piecewise-quadratic energy
    /// converges in far fewer; hitting the cap signals a modelling problem.
    pub max_iterations: usize,
    /// Relative residual tolerance (dimensionless, relative to the force scale).
    /// Default 1e-10, a few orders above round-off for the systems solved here.
    pub residual_tolerance: f64,
    /// Armijo sufficient-decrease constant in (0, ½). Default 1e-4 (Nocedal–Wright).
    pub armijo: f64,
    /// Maximum number of trial steps per line search beyond the full step. Default 40.
    pub max_backtracks: usize,
    /// Maximum conjugate-gradient iterations preconditioned by the last factorization
    /// before the Hessian is refactorized. Default 8: one triangular solve costs about a
    /// tenth of a factorization, and changes of the active sets (locking cells, contact and
    /// stick nodes) are low-rank updates that PCG resolves in about as many iterations as
    /// their rank. 0 disables PCG (every changed Hessian is refactorized) and, with the
    /// iterative solver, the lagged multigrid set-up (every changed Hessian is set up
    /// fully).
    pub pcg_iterations: usize,
    /// Largest relative residual PCG may stop at (the loosest forcing term of the inexact
    /// Newton method; the actual one is `min(pcg_tolerance, 0.1 · tolerance / residual)`, so
    /// the last steps are solved as accurately as the convergence criterion needs). Default
    /// 1e-3: near the solution Newton then still gains three digits per step.
    pub pcg_tolerance: f64,
}

impl Default for NewtonSettings {
    fn default() -> Self {
        NewtonSettings {
            max_iterations: 50,
            residual_tolerance: 1e-10,
            armijo: 1e-4,
            max_backtracks: 40,
            pcg_iterations: 8,
            pcg_tolerance: 1e-3,
        }
    }
}

impl NewtonSettings {
    /// Checks every setting against its range.
    ///
    /// # Errors
    /// [`crate::Error::Invalid`] naming the setting (`residual_tolerance` in (0, 1), `armijo` in
    /// (0, ½), `pcg_tolerance` in [1e-12, 1), `max_iterations` ≥ 1, `max_backtracks` ≤
    /// [`MAX_BACKTRACKS`], `pcg_iterations` ≤ [`MAX_PCG_ITERATIONS`]).
    pub fn validate(&self) -> Result<()> {
        use crate::error::require;
        let tol = self.residual_tolerance;
        require(
            tol.is_finite() && tol > 0.0 && tol < 1.0,
            "residual_tolerance",
            tol,
            "a number in (0, 1)",
        )?;
        require(
            self.armijo > 0.0 && self.armijo < 0.5,
            "armijo",
            self.armijo,
            "a number in (0, 0.5)",
        )?;
        require(
            self.pcg_tolerance >= 1e-12 && self.pcg_tolerance < 1.0,
            "pcg_tolerance",
            self.pcg_tolerance,
            "a number in [1e-12, 1)",
        )?;
        require(
            self.max_iterations > 0,
            "max_iterations",
            0,
            "a positive integer",
        )?;
        require(
            self.max_backtracks <= MAX_BACKTRACKS,
            "max_backtracks",
            self.max_backtracks,
            &format!(
                "an integer from 0 (the full step only) to {MAX_BACKTRACKS} (trial steps \
                 beyond the full step)"
            ),
        )?;
        require(
            self.pcg_iterations <= MAX_PCG_ITERATIONS,
            "pcg_iterations",
            self.pcg_iterations,
            &format!(
                "an integer from 0 (every changed Hessian is refactorized) to \
                 {MAX_PCG_ITERATIONS}"
            ),
        )
    }
}

/// Largest [`NewtonSettings::max_backtracks`]: 200 trial steps shrink the step far below
/// any representable change of a displacement.
pub const MAX_BACKTRACKS: usize = 200;

/// Largest [`NewtonSettings::pcg_iterations`] before a refactorization.
pub const MAX_PCG_ITERATIONS: usize = 10_000;

/// Acceleration of the outer fixed-point iteration; see [`super::outer`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Acceleration {
    /// Plain (relaxed) fixed point with oscillation detection.
    None,
    /// Safeguarded Anderson acceleration.
    #[default]
    Anderson,
}

/// Outer-loop settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OuterSettings {
    /// Maximum number of outer iterations (convex solves). Default 100.
    pub max_iterations: usize,
    /// Tolerance on the relative change of u in the energy norm. Default 1e-10.
    pub tolerance: f64,
    /// Acceleration. Default Anderson.
    pub acceleration: Acceleration,
    /// Anderson depth (number of differences kept). Default 5.
    pub depth: usize,
    /// Initial relaxation factor ω ∈ (0, 1] of the plain fixed point. Default 1.
    pub relaxation: f64,
    /// Deprecated: the numerical regularization of the norm in the friction potential of
    /// every contact part, now a parameter of the friction law
    /// ([`crate::contact::NormTreatment::Smoothed`], scenario key `[contact.friction]
    /// regularization`); read by the scenario loader only. `None` unless given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_regularization: Option<f64>,
    /// Solve early convex problems inexactly. Default true.
    pub inexact: bool,
}

impl Default for OuterSettings {
    fn default() -> Self {
        OuterSettings {
            max_iterations: 100,
            tolerance: 1e-10,
            acceleration: Acceleration::Anderson,
            depth: 5,
            relaxation: 1.0,
            friction_regularization: None,
            inexact: true,
        }
    }
}

/// Largest Anderson depth [`OuterSettings::validate`] accepts: the history is a dense
/// least-squares problem of this size per outer iteration, and depths beyond a few tens
/// only add round-off.
pub const MAX_DEPTH: usize = 50;

impl OuterSettings {
    /// Checks every setting against its range.
    ///
    /// # Errors
    /// [`crate::Error::Invalid`] naming the setting (`tolerance` in (0, 1), `depth` from 1
    /// to [`MAX_DEPTH`], `max_iterations` ≥ 1, `relaxation` in (0, 1],
    /// the deprecated `friction_regularization`, if given, in (0, 0.01)).
    pub fn validate(&self) -> crate::Result<()> {
        use crate::error::require;
        let tol = self.tolerance;
        require(
            tol.is_finite() && tol > 0.0 && tol < 1.0,
            "tolerance",
            tol,
            "a number in (0, 1)",
        )?;
        require(
            (1..=MAX_DEPTH).contains(&self.depth),
            "depth",
            self.depth,
            &format!("an Anderson depth from 1 to {MAX_DEPTH}"),
        )?;
        require(
            self.max_iterations > 0,
            "max_iterations",
            0,
            "a positive integer",
        )?;
        require(
            self.relaxation > 0.0 && self.relaxation <= 1.0,
            "relaxation",
            self.relaxation,
            "a factor in (0, 1]",
        )?;
        match self.friction_regularization {
            Some(rho) => require(
                rho.is_finite() && rho > 0.0 && rho < 1e-2,
                "friction_regularization",
                rho,
                "a number in (0, 0.01)",
            ),
            None => Ok(()),
        }
    }
}
