//! The discrete system, prepared once per problem: DOF map, sparsity pattern, linear
//! solver (see [`crate::linalg`]), contact points, external forces, free rigid motions and
//! the continuation stage. [`System::evaluate`] computes the convexified energy `E_k` with
//! its gradient and generalized Hessian for given frozen contact quantities into the work
//! arrays of an [`Evaluation`], which the outer loop owns.
//!
//! The set-up is in `build` ([`System::new`], [`System::for_solve`]), the evaluation of
//! the energy in `evaluate` ([`System::evaluate`]); the certificate of an
//! answer ([`System::certificate`]) is with the certificate
//! ([`super::certificate`]), the scales of the points ([`System::point_scales`]) with the
//! local scales ([`super::local_scales`]).

mod build;
pub(super) mod evaluate;

use super::continuation::Continuation;
use super::local_scales::Bodies;
use super::scaling::Scales;
use super::settings::{NewtonSettings, SolverSettings};
use super::timings::Timings;
use crate::assembly::contact::ContactAssembler;
use crate::assembly::global::Workspace;
use crate::assembly::SystemPattern;
use crate::contact::{ContactNodes, NormalResponse};
use crate::error::Result;
use crate::fem::dofs::{DofMap, FIXED};
use crate::linalg::{LinearSolver, SolveRequest, SpdSolver};
use crate::parallel::{Processes, Share, Subdomain};
use crate::problem::Problem;
use crate::rigid::RigidMotions;

/// Everything that depends only on the mesh and the boundary-condition *pattern*.
#[derive(Debug)]
pub struct System {
    /// DOF map (Dirichlet DOFs eliminated).
    pub dofs: DofMap,
    /// Upper-triangular pattern of the reduced system; in a distributed run, of this
    /// process's part of the mesh in its own numbering
    /// ([`crate::parallel::Subdomain::local_mesh`]), complete in the rows of its own
    /// nodes' equations only.
    pub pattern: SystemPattern,
    /// Stored entries of the upper triangle of the whole reduced system (over all
    /// processes; [`SystemPattern::nnz`] on one).
    pub nnz: usize,
    /// The sizes of the whole problem (those of `dofs` and `contact` on one process).
    pub whole: WholeCounts,
    /// The linear solver of the Newton systems, prepared on `pattern` (direct: symbolic
    /// analysis done; iterative: multigrid grids built).
    pub linear_solver: Box<dyn SpdSolver>,
    /// Contact points.
    pub contact: ContactNodes,
    /// Hessian slots of the contact points' node blocks.
    pub contact_slots: Vec<u32>,
    /// Elastic stiffness per unit area k_i of every contact point (Pa/m,
    /// [`super::constraints::contact_stiffness`]): the local scale of its friction
    /// regularization and of its certificate.
    pub contact_stiffness: Vec<f64>,
    /// The cells around the node of every contact point, in compressed rows: those of point
    /// i are `point_cells.1[point_cells.0[i]..point_cells.0[i + 1]]`.
    pub point_cells: (Vec<usize>, Vec<u32>),
    /// The continuation stage of the outer loop: penalties of the exact constraints and
    /// floor of the friction regularization.
    pub continuation: Continuation,
    /// External force vector (N), DOF order.
    pub f_ext: Vec<f64>,
    /// The bodies of the mesh, each with the force unit of its prescribed motions: the unit
    /// of the convergence tests ([`super::local_scales`]).
    pub bodies: Bodies,
    /// Seconds spent on (pattern, symbolic analysis or multigrid grids and prolongations).
    pub setup_time: (f64, f64),
    /// Parallel assembly buffers.
    workspace: Workspace,
    /// Rigid motions left free by the Dirichlet conditions (carried by contact, else
    /// [`Problem::validate`] refused the problem).
    pub rigid: RigidMotions,
    /// Diagonal slots of the free equations of the bodies with free rigid motions, in this
    /// process's rows (all of them on one process).
    rigid_slots: Vec<usize>,
    /// In a distributed run, this process's subdomain: the partition of the nodes and the
    /// cells of its part (whole numbering, owned first); `None` on one process.
    subdomain: Option<Subdomain>,
    /// What this process counts in the global sums and maxima of the outer loop, Newton
    /// and the certificate, and the reductions that complete them.
    share: Share,
    /// The processes of the run: with several, each assembles its
    /// [`crate::parallel::Subdomain`] and the gradient of its own nodes, and the energies
    /// are summed over them ([`Processes::sum`]).
    processes: Processes,
    /// The scales of the dimensionless variables the problem is solved in (set by the
    /// solver, see [`super::scaling`]); `None` for a problem in the user's units. Only
    /// messages and the runaway check read them.
    pub scales: Option<Scales>,
    /// A rigid placement of the bodies applied before the solve (DOF order, in the units
    /// of the displacements): the translations their supports carry them by
    /// ([`crate::rigid::carry`]) and a rigid drop ([`super::held::rigid_drop`]). The unknown
    /// is then the displacement relative to it, and the contact points' gaps and
    /// tangential displacements account for it ([`ContactNodes::new`],
    /// [`ContactNodes::place`]). `None`: no placement.
    pub placement: Option<Vec<f64>>,
}

/// The sizes of the whole problem, whatever part of it a process holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WholeCounts {
    /// Number of DOFs (d per node).
    pub dofs: usize,
    /// Number of equations (free DOFs).
    pub equations: usize,
    /// Number of contact points.
    pub contact_points: usize,
}

/// The user's units of the solver's variables ([`System::user_units`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UserUnits {
    /// Unit of the coordinates (m).
    pub length: f64,
    /// Unit of the displacements (m).
    pub displacement: f64,
    /// Unit of the nodal forces (N; N/m in 2D).
    pub force: f64,
    /// Unit of the tractions, pressures and Tresca bounds (Pa).
    pub traction: f64,
}

/// The linear solver that `kind` resolves to for `problem` on `processes`
/// ([`super::LinearSolver::resolve`] with the number of free equations): the one
/// [`System::with_linear_solver`] prepares.
pub fn resolved_linear_solver(
    problem: &Problem,
    kind: LinearSolver,
    processes: &Processes,
) -> LinearSolver {
    kind.resolve(problem.mesh.dim(), problem.dof_map().n_free(), processes)
}

pub use crate::linalg::ITERATIVE_MAX_ITERATIONS;

/// The derivatives of the convexified energy at the last evaluation
/// ([`System::evaluate`]): the work arrays of the Newton iteration, allocated once per solve.
#[derive(Debug)]
pub struct Evaluation {
    /// Gradient of the total energy, DOF order (N); in a distributed run, of this process's
    /// part, known at its own nodes only (NaN at its ghost nodes).
    pub grad: Vec<f64>,
    /// Gradient of the bulk energy minus the external forces (the negative of the interface
    /// forces plus residual), DOF order (N); in a distributed run, of this process's part,
    /// known at its own nodes only (NaN at its ghost nodes).
    pub grad_bulk: Vec<f64>,
    /// Hessian values at the last evaluation with a Hessian (upper triangle, on
    /// [`System::pattern`]: in a distributed run, of this process's part; N/m).
    pub hess: Vec<f64>,
    /// Shift α added to the Newton matrix on the bodies with free rigid motions (0 until
    /// the first Hessian; see [`crate::rigid::NEWTON_SHIFT`]).
    pub rigid_shift: f64,
    /// The responses of user-defined compliance laws at the last evaluation (empty without
    /// such laws).
    pub normal: Vec<NormalResponse>,
    /// The error of a user-defined compliance law at the last evaluation, which then
    /// returned a NaN energy; the outer loop ends the solve with it.
    pub law_error: Option<crate::Error>,
    /// The force `w_i max(F_i, p_i)` of every contact point at the last evaluation of a
    /// convex problem (N; [`System::point_scales`]).
    pub point_force: Vec<f64>,
    /// The floor `η L_i` of the force scale of every contact point at the last evaluation
    /// of a convex problem (N; [`System::point_scales`]).
    pub point_floor: Vec<f64>,
    /// The force scale `F_b` of every body at the last evaluation of a convex problem (N;
    /// [`super::local_scales::Bodies::force_scales`]).
    pub body_scale: Vec<f64>,
}

impl Evaluation {
    /// Zeroed work arrays for `system`.
    pub fn new(system: &System) -> Self {
        let n = system.dofs.n_dofs();
        Evaluation {
            grad: vec![0.0; n],
            grad_bulk: vec![0.0; n],
            hess: vec![0.0; system.pattern.nnz()],
            rigid_shift: 0.0,
            normal: Vec::new(),
            law_error: None,
            point_force: Vec::new(),
            point_floor: Vec::new(),
            body_scale: Vec::new(),
        }
    }
}

/// How a Newton system was solved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LinearInfo {
    /// Whether the Hessian was refactorized.
    pub refactorized: bool,
    /// PCG iterations (0: direct solve).
    pub pcg_iterations: usize,
}

impl System {
    /// Builds the DOF map, pattern and contact points, and prepares the linear solver
    /// chosen by `settings.linear_solver` (see [`super::LinearSolver::prepare`]).
    ///
    /// # Errors
    /// [`crate::Error::OutOfMemory`] if the pattern or factor cannot be allocated.
    pub fn new(problem: &Problem, settings: &SolverSettings) -> Result<Self> {
        Self::with_linear_solver(problem, settings, settings.linear_solver)
    }

    /// As [`System::new`] with the linear solver `kind` instead of the problem's: for the
    /// direct solver the symbolic Cholesky analysis, for the iterative one the multigrid
    /// grids and prolongations (no factorization of the fine system). The whole system, on
    /// this process alone, however many processes run.
    ///
    /// # Errors
    /// As [`System::new`].
    pub fn with_linear_solver(
        problem: &Problem,
        settings: &SolverSettings,
        kind: LinearSolver,
    ) -> Result<Self> {
        Ok(Self::build(problem, settings, kind, false)?.0)
    }

    /// The system of a solve of `problem`: on several processes with the distributed
    /// solver (PETSc), this process's part of it, with the part's problem (its
    /// mesh, [`crate::parallel::Subdomain::local_mesh`], under the same conditions) that
    /// the solve then runs on; on one process (or with
    /// another linear solver, every process holding the whole system alone), the whole
    /// system and `None`.
    ///
    /// # Errors
    /// As [`System::new`], and the partition's.
    pub fn for_solve(
        problem: &Problem,
        settings: &SolverSettings,
    ) -> Result<(Self, Option<Problem>)> {
        Self::build(problem, settings, settings.linear_solver, true)
    }

    /// How the nodes are split among the processes when this system is distributed (see
    /// [`crate::parallel::Subdomain`]); `None` on one process.
    pub fn partition(&self) -> Option<&crate::parallel::Partition> {
        self.subdomain.as_ref().map(|s| &s.partition)
    }

    /// What this process counts in global sums and maxima, and their completion over the
    /// processes (see [`Share`]).
    pub fn share(&self) -> &Share {
        &self.share
    }

    /// The unit of the coordinates in units of the displacements: 1 for a problem in the
    /// user's units, `L/U` in the dimensionless variables of [`super::scaling`].
    pub fn length_unit(&self) -> f64 {
        self.scales.map_or(1.0, |s| s.length / s.displacement)
    }

    /// The user's units of the solver's variables: (length, displacement, force, traction)
    /// in m, m, N (N/m in 2D) and Pa; all 1 for a problem in the user's units.
    pub fn user_units(&self) -> UserUnits {
        self.scales.map_or(
            UserUnits {
                length: 1.0,
                displacement: 1.0,
                force: 1.0,
                traction: 1.0,
            },
            |s| UserUnits {
                length: s.length,
                displacement: s.displacement,
                force: s.force(),
                traction: s.traction(),
            },
        )
    }

    /// Places the bodies rigidly by `u_r` (DOF order) before the solve, in addition to
    /// any placement before: see [`System::placement`] and [`ContactNodes::place`].
    pub fn place(&mut self, u_r: Vec<f64>) {
        self.contact.place(self.rigid.dim, &u_r);
        match &mut self.placement {
            Some(p) => p.iter_mut().zip(&u_r).for_each(|(p, x)| *p += x),
            None => self.placement = Some(u_r),
        }
    }

    /// The displacement `u` (DOF order) relative to the placement ([`System::placement`]):
    /// `u − u_R`, or `u` without placement.
    pub fn relative_to_placement(&self, mut u: Vec<f64>) -> Vec<f64> {
        if let Some(p) = &self.placement {
            u.iter_mut().zip(p).for_each(|(x, p)| *x -= p);
        }
        u
    }

    /// The contact assembler of `problem` on this system.
    pub fn contact_assembler<'a>(&'a self, problem: &'a Problem) -> ContactAssembler<'a> {
        ContactAssembler {
            dim: problem.mesh.dim(),
            nodes: &self.contact,
            boundaries: &problem.contact,
            stiffness: &self.contact_stiffness,
            penalty: self.continuation.penalties.contact(),
            responses: &[],
        }
    }

    /// Solves `H x = b` for the Hessian values `hess` with [`System::linear_solver`],
    /// to the relative residual `eta` where the solve is iterative (the forcing term of the
    /// inexact Newton method), reusing a factorization for at most
    /// `settings.pcg_iterations` PCG iterations (see [`crate::linalg::direct`]). The
    /// solver's times go to `timings` (rebuilding the factorization or the multigrid
    /// operators counts as a factorization).
    ///
    /// # Errors
    /// Those of [`SpdSolver::solve`].
    pub fn linear_solve(
        &mut self,
        hess: &[f64],
        b: &[f64],
        x: &mut [f64],
        eta: f64,
        settings: &NewtonSettings,
        timings: &mut Timings,
    ) -> Result<LinearInfo> {
        let request = SolveRequest {
            eta,
            reuse_iterations: settings.pcg_iterations,
        };
        let stats = self
            .linear_solver
            .solve(&self.pattern, hess, b, x, &request)?;
        timings.factorization += stats.factorization_time;
        timings.n_factorizations += usize::from(stats.refactorized);
        timings.solve += stats.solve_time;
        Ok(LinearInfo {
            refactorized: stats.refactorized,
            pcg_iterations: stats.iterations,
        })
    }

    /// Gradient restricted to the free DOFs (equation order) into `r`.
    pub fn reduce(&self, full: &[f64], r: &mut [f64]) {
        for (dof, &eq) in self.dofs.equations().iter().enumerate() {
            if eq != FIXED {
                r[eq as usize] = full[dof];
            }
        }
    }

    /// Reaction forces at prescribed DOFs (zero elsewhere) from the gradient `grad` of an
    /// evaluation.
    pub fn reactions(&self, grad: &[f64]) -> Vec<f64> {
        (0..self.dofs.n_dofs())
            .map(|k| if self.dofs.is_fixed(k) { grad[k] } else { 0.0 })
            .collect()
    }
}
