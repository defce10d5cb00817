//! What a solve did: iterations, residuals, timings, sizes.

use super::System;
use serde::Serialize;

/// Wall-clock time per phase (s).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Timings {
    /// Sparsity pattern and DOF map.
    pub pattern: f64,
    /// Fill-reducing ordering and symbolic factorization (iterative linear solver: the
    /// multigrid grids and prolongations).
    pub symbolic: f64,
    /// Assembly of energy, gradient and Hessian (all Newton steps).
    pub assembly: f64,
    /// Numeric factorizations (all Newton steps); with the iterative linear solver, the
    /// multigrid set-ups (Galerkin operators, smoother intervals, coarsest factor).
    pub factorization: f64,
    /// Triangular solves and PCG iterations (all Newton steps).
    pub solve: f64,
    /// Number of numeric factorizations (iterative linear solver: multigrid set-ups).
    pub n_factorizations: usize,
    /// Line searches (energy evaluations).
    pub line_search: f64,
    /// Whole solve, end to end.
    pub total: f64,
}

/// One Newton step.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NewtonStep {
    /// Outer iteration this step belongs to.
    pub outer: usize,
    /// Euclidean norm of the residual (gradient on free DOFs) before the step (N).
    pub residual: f64,
    /// Energy before the step (J).
    pub energy: f64,
    /// Line-search step length taken (1 = full Newton step).
    pub step_length: f64,
    /// Whether the Hessian was refactorized for this step.
    pub refactorized: bool,
    /// Conjugate-gradient iterations (0: direct solve with the factorization).
    pub pcg_iterations: usize,
}

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
    /// Why the outer loop stopped ([`super::StopReason`]); a converged loop whose
    /// certificate fails is reported with `converged = false` and the failing law in
    /// `message`.
    pub stop: super::StopReason,
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
    /// words (empty: none; see [`crate::fem::rigid`]).
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

    /// An empty report for `system`, with its sizes and set-up timings filled in.
    pub fn new(system: &System) -> Self {
        SolveReport {
            converged: false,
            message: "not started".into(),
            stop: super::StopReason::IterationCap,
            n_dofs: system.whole.dofs,
            n_equations: system.whole.equations,
            nnz_matrix: system.nnz,
            linear_solver: system.linear_solver.describe(),
            processes: crate::parallel::Processes::current().size(),
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
