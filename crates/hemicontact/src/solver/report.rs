//! What a solve did: iterations, residuals, timings, sizes.

pub use super::newton::NewtonStep;
use super::settings::OuterSettings;
pub use super::timings::Timings;
use super::System;
use serde::Serialize;

/// One outer (convexification) iteration.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OuterStep {
    /// Relative change `‖u^k − u^{k−1}‖_E / ‖u^k‖_E` (∞ for the first iteration).
    pub change: f64,
    /// Relative fixed-point residual `‖G(z) − z‖ / ‖G(z)‖` of the frozen quantities.
    pub fixed_point_residual: f64,
    /// Newton steps of this convex solve.
    pub newton_steps: usize,
    /// Relative Newton tolerance used.
    pub newton_tolerance: f64,
    /// Whether the convex solve met its tolerance.
    pub newton_converged: bool,
    /// How the next frozen quantities were formed.
    pub mixing: super::Mixing,
}

/// The report of a solve.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SolveReport {
    /// Whether the convergence criterion was met.
    pub converged: bool,
    /// Why the solve stopped, in words.
    pub message: String,
    /// Why the outer loop stopped ([`StopReason`]); a converged loop whose
    /// certificate fails is reported with `converged = false` and the failing law in
    /// `message`.
    pub stop: StopReason,
    /// Number of DOFs (d · nodes).
    pub n_dofs: usize,
    /// Number of free DOFs (equations).
    pub n_equations: usize,
    /// Stored entries of the matrix (upper triangle).
    pub nnz_matrix: usize,
    /// The linear solver that solved the Newton systems: `direct`, `iterative`, or
    /// `petsc (ksp cg, pc gamg)` with PETSc's Krylov method and preconditioner.
    pub linear_solver: String,
    /// MPI processes that ran the solve (1 without MPI; see [`crate::parallel`]).
    pub processes: usize,
    /// Stored entries of the Cholesky factor (0 with the iterative linear solver).
    pub nnz_factor: usize,
    /// Equations per multigrid level, finest first, with the iterative linear solver
    /// (empty with the direct one).
    pub multigrid_levels: Vec<usize>,
    /// Outer iterations.
    pub outer: Vec<OuterStep>,
    /// Newton steps (all outer iterations).
    pub newton: Vec<NewtonStep>,
    /// Number of contact points.
    pub n_contact_points: usize,
    /// The certificate of the final iterate.
    pub certificate: super::certificate::Certificate,
    /// Final residual norm (N).
    pub residual: f64,
    /// Residual tolerance that was applied (N): relative tolerance × force scale.
    pub residual_tolerance: f64,
    /// The scales in which the problem was solved (see [`super::scaling`]).
    pub scales: Option<super::scaling::Scales>,
    /// Largest relative residual at which a Newton solve stopped at the round-off floor
    /// above the tolerance (0: never; see [`super::newton`]).
    pub round_off_floor: f64,
    /// The rigid motions that the Dirichlet conditions leave free and contact carries, in
    /// words (empty: none; see [`crate::rigid`]).
    pub free_rigid_motions: Vec<String>,
    /// Shift α added to the diagonal of the Newton matrix on their bodies (N/m in 2D per
    /// unit thickness, N/m in 3D; 0: none). It changes Newton directions only, never the
    /// energy or the gradient, so it exerts no force on the answer.
    pub rigid_shift: f64,
    /// The rigid drop made before Newton, in words with how far each body moved (empty:
    /// none; see [`super::held::rigid_drop`]), e.g. `translation along y by up to 0.001 m`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub rigid_drop: Vec<String>,
    /// Largest unbalanced generalized force along those motions at the final iterate,
    /// relative to the force scale of the Newton criterion (0 without them): how well
    /// contact balances the load along them.
    pub rigid_residual: f64,
    /// Timings per phase.
    pub timings: Timings,
}

impl SolveReport {
    /// Files the record of a Newton solve: its steps, timings, last residual and
    /// tolerance, and round-off floor.
    pub fn add_newton(&mut self, record: super::newton::NewtonRecord) {
        self.newton.extend(record.steps);
        let (t, r) = (&mut self.timings, &record.timings);
        t.assembly += r.assembly;
        t.factorization += r.factorization;
        t.solve += r.solve;
        t.n_factorizations += r.n_factorizations;
        t.line_search += r.line_search;
        self.residual = record.residual;
        self.residual_tolerance = record.residual_tolerance;
        self.round_off_floor = self.round_off_floor.max(record.round_off_floor);
    }

    /// An empty report for `system`, solved on `processes`, with its sizes and set-up
    /// timings filled in.
    pub fn new(system: &System, processes: &crate::parallel::Processes) -> Self {
        SolveReport {
            converged: false,
            message: "not started".into(),
            stop: StopReason::IterationCap,
            n_dofs: system.whole.dofs,
            n_equations: system.whole.equations,
            nnz_matrix: system.nnz,
            linear_solver: system.linear_solver.describe(),
            processes: processes.size(),
            nnz_factor: system.linear_solver.nnz_factor(),
            multigrid_levels: system.linear_solver.level_sizes(),
            outer: Vec::new(),
            newton: Vec::new(),
            n_contact_points: system.whole.contact_points,
            certificate: Default::default(),
            residual: f64::NAN,
            residual_tolerance: f64::NAN,
            round_off_floor: 0.0,
            scales: None,
            free_rigid_motions: system.rigid.describe_all(),
            rigid_shift: 0.0,
            rigid_drop: Vec::new(),
            rigid_residual: 0.0,
            timings: Timings {
                pattern: system.setup_time.0,
                symbolic: system.setup_time.1,
                ..Timings::default()
            },
        }
    }
}

/// Why the outer loop stopped.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "reason", rename_all = "kebab-case")]
pub enum StopReason {
    /// The stopping test held after a convex solve at the final Newton tolerance.
    Converged,
    /// The convex solve of outer iteration `outer`, at the final Newton tolerance, did not
    /// reach it.
    NewtonNotConverged {
        /// The outer iteration.
        outer: usize,
        /// The Newton residual reached (N, in the solver's units).
        residual: f64,
        /// The residual tolerance (N, in the solver's units).
        tolerance: f64,
    },
    /// A numerical breakdown in a Newton step after some step succeeded; the last good
    /// iterate is kept.
    Breakdown {
        /// The outer iteration.
        outer: usize,
        /// The Newton step of that iteration (1-based).
        step: usize,
        /// The error.
        error: String,
    },
    /// `max_iterations` outer iterations without meeting the stopping test.
    IterationCap,
}

impl StopReason {
    /// The stop in words, for the report, given the report of the loop and its settings.
    pub fn message(
        &self,
        report: &SolveReport,
        settings: &OuterSettings,
        oscillations: usize,
    ) -> String {
        match self {
            StopReason::Converged => format!(
                "converged: {} outer iterations, {} Newton steps{}",
                report.outer.len(),
                report.newton.len(),
                if report.round_off_floor > 0.0 {
                    format!(
                        " (a Newton solve stopped at the round-off floor, relative residual {:.1e})",
                        report.round_off_floor
                    )
                } else {
                    String::new()
                }
            ),
            StopReason::NewtonNotConverged {
                outer,
                residual,
                tolerance,
            } => format!(
                "Newton did not converge in outer iteration {outer}: residual {residual:e} > tolerance {tolerance:e}"
            ),
            StopReason::Breakdown { outer, step, error } => format!(
                "not converged: numerical breakdown in outer iteration {outer}, Newton step {step}: {error}"
            ),
            StopReason::IterationCap => format!(
                "not converged: {} outer iterations (cap); last relative change {:e}, fixed-point residual {:e} (tolerance {:e}){}",
                report.outer.len(),
                report.outer.last().map_or(f64::NAN, |o| o.change),
                report.outer.last().map_or(f64::NAN, |o| o.fixed_point_residual),
                settings.tolerance,
                if oscillations > 0 { "; oscillation was detected" } else { "" }
            ),
        }
    }
}
