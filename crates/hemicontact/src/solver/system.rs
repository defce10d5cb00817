//! The discrete system, prepared once per problem: DOF map, sparsity pattern, linear
//! solver (see [`crate::linalg`]), contact points, external forces, and the work arrays of the Newton
//! iteration. [`System::evaluate`] computes the convexified energy `E_k` with its
//! gradient and generalized Hessian for given frozen contact quantities.

use super::constraints::AugmentedLagrangian;
use crate::assembly::contact::{contact_slots, ContactAssembler, Frozen};
use crate::assembly::global::{IdealLocking, Want, Workspace};
use crate::assembly::{BulkAssembler, SystemPattern};
use crate::contact::ContactNodes;
use crate::error::Result;
use crate::fem::dofs::{DofMap, FIXED};
use crate::fem::rigid::{RigidMotions, NEWTON_SHIFT};
use crate::linalg::{PrepareOptions, SolveRequest, SpdSolver};
use crate::problem::Problem;
use std::time::Instant;

/// Everything that depends only on the mesh and the boundary-condition *pattern*.
#[derive(Debug)]
pub struct System {
    /// DOF map (Dirichlet DOFs eliminated).
    pub dofs: DofMap,
    /// Upper-triangular pattern of the reduced system.
    pub pattern: SystemPattern,
    /// The linear solver of the Newton systems, prepared on `pattern` (direct: symbolic
    /// analysis done; iterative: multigrid grids built).
    pub linear_solver: Box<dyn SpdSolver>,
    /// Contact points.
    pub contact: ContactNodes,
    /// Hessian slots of the contact points' node blocks.
    pub contact_slots: Vec<u32>,
    /// Continuation floor of the numerical regularization ρ_num of a smoothed norm in the
    /// friction potential, in units of the displacement scale (the solver works in
    /// dimensionless variables, see [`super::scaling`]); each law uses the larger of this
    /// and its own value ([`System::set_regularization_stage`]). 0: the laws' own values.
    pub regularization_floor: f64,
    /// The penalties of the exact constraints and their continuation
    /// ([`super::constraints::AugmentedLagrangian`]).
    pub constraints: AugmentedLagrangian,
    /// External force vector (N), DOF order.
    pub f_ext: Vec<f64>,
    /// Force unit of the prescribed displacements, `S · max|u_D| · diam^{d−2}` (N; S the
    /// P-wave modulus): the floor of the force scales of the Newton criterion and the
    /// certificate, so that a displacement-driven solution without stress (a prescribed
    /// rigid motion) is measured against the forces its data could cause, not against
    /// zero.
    pub force_floor: f64,
    /// Gradient of the total energy at the last evaluation, DOF order.
    pub grad: Vec<f64>,
    /// Gradient of the bulk energy minus external forces at the last evaluation (the
    /// negative of the interface forces plus residual), DOF order.
    pub grad_bulk: Vec<f64>,
    /// Hessian values at the last evaluation with a Hessian (upper triangle).
    pub hess: Vec<f64>,
    /// Seconds spent on (pattern, symbolic analysis or multigrid grids and prolongations).
    pub setup_time: (f64, f64),
    /// Parallel assembly buffers.
    workspace: Workspace,
    /// Rigid motions left free by the Dirichlet conditions (carried by contact, else
    /// [`Problem::validate`] refused the problem).
    pub rigid: RigidMotions,
    /// Diagonal slots of the free equations of the bodies with free rigid motions.
    rigid_slots: Vec<usize>,
    /// Shift α added there to the Newton matrix (0 until the first Hessian; see
    /// [`crate::fem::rigid::NEWTON_SHIFT`]).
    pub rigid_shift: f64,
    /// The unit of the coordinates in units of the displacements: 1 for a problem in
    /// metres, `L/U` when it is solved in the dimensionless variables of
    /// [`super::scaling`] (set by the solver).
    pub length_unit: f64,
}

/// The linear solver that `kind` resolves to for `problem` ([`super::LinearSolver::resolve`]
/// with the number of free equations): the one [`System::with_linear_solver`] prepares.
pub fn resolved_linear_solver(problem: &Problem, kind: super::LinearSolver) -> super::LinearSolver {
    kind.resolve(problem.mesh.dim(), problem.dof_map().n_free())
}

/// Friction regularization (relative to the displacement scale) at which the continuation
/// of [`System::set_regularization_stage`] starts.
pub const REGULARIZATION_START: f64 = 1e-2;

/// Factor by which the friction regularization shrinks per outer iteration. Measured on a
/// pressed and sheared block with Coulomb friction (16 × 8 cells, 12 sticking and 5
/// slipping points, target 1e-8): 77 Newton steps with 0.1, 228 with 0.01, 346 without
/// continuation.
pub const REGULARIZATION_STEP: f64 = 0.1;

/// Number of outer iterations the regularization continuation of `problem` needs to reach
/// the targets of its friction laws: the largest over the contact parts whose norm is
/// smoothed (0 without one).
pub fn regularization_stages(problem: &Problem) -> usize {
    problem
        .contact
        .iter()
        .filter_map(|c| c.friction.as_ref()?.potential.regularization())
        .map(|target| {
            if target >= REGULARIZATION_START {
                0
            } else {
                ((REGULARIZATION_START / target).ln() / REGULARIZATION_STEP.recip().ln()).ceil()
                    as usize
            }
        })
        .max()
        .unwrap_or(0)
}

pub use crate::linalg::ITERATIVE_MAX_ITERATIONS;

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
    pub fn new(problem: &Problem, settings: &super::SolverSettings) -> Result<Self> {
        Self::with_linear_solver(problem, settings, settings.linear_solver)
    }

    /// As [`System::new`] with the linear solver `kind` instead of the problem's: for the
    /// direct solver the symbolic Cholesky analysis, for the iterative one the multigrid
    /// grids and prolongations (no factorization of the fine system).
    ///
    /// # Errors
    /// As [`System::new`].
    pub fn with_linear_solver(
        problem: &Problem,
        settings: &super::SolverSettings,
        kind: super::LinearSolver,
    ) -> Result<Self> {
        let t0 = Instant::now();
        let dofs = problem.dof_map();
        let pattern = SystemPattern::new(&problem.mesh, &dofs)?;
        let contact = problem.contact_nodes();
        let constraints = AugmentedLagrangian::new(problem, &settings.constraints, &contact.weight);
        let contact_slots = contact_slots(&contact, problem.mesh.dim(), dofs.equations(), &pattern);
        let t1 = Instant::now();
        let options = PrepareOptions {
            ordering: settings.ordering,
            par: super::parallelism(settings.factorization_threads),
        };
        let linear_solver = kind.prepare(&problem.mesh, dofs.equations(), &pattern, &options)?;
        let t2 = Instant::now();
        let f_ext = problem.external_forces();
        let force_floor = {
            let d = problem.mesh.dim();
            let h = problem.material.elasticity.small_strain_hooke(d);
            let u_d = problem
                .prescribed_displacement()
                .iter()
                .fold(0.0f64, |m, x| m.max(x.abs()));
            (h.lambda + 2.0 * h.mu) * u_d * problem.diameter().powi(d as i32 - 2)
        };
        let n = dofs.n_dofs();
        let hess = vec![0.0; pattern.nnz()];
        let rigid = problem.rigid_motions();
        let rigid_slots = rigid
            .shifted_dofs()
            .into_iter()
            .filter(|&k| !dofs.is_fixed(k))
            .map(|k| pattern.diagonal_slot(dofs.equation(k) as usize))
            .collect();
        Ok(System {
            dofs,
            pattern,
            linear_solver,
            contact,
            contact_slots,
            regularization_floor: 0.0,
            constraints,
            f_ext,
            force_floor,
            grad: vec![0.0; n],
            grad_bulk: vec![0.0; n],
            hess,
            setup_time: ((t1 - t0).as_secs_f64(), (t2 - t1).as_secs_f64()),
            workspace: Workspace::new(match settings.threads {
                0 => rayon::current_num_threads(),
                t => t,
            }),
            rigid,
            rigid_slots,
            rigid_shift: 0.0,
            length_unit: 1.0,
        })
    }

    /// The contact assembler of `problem` on this system.
    pub fn contact_assembler<'a>(&'a self, problem: &'a Problem) -> ContactAssembler<'a> {
        ContactAssembler {
            dim: problem.mesh.dim(),
            nodes: &self.contact,
            boundaries: &problem.contact,
            regularization_floor: self.regularization_floor,
            penalty: self.constraints.contact(),
        }
    }

    /// The ideal-locking term of `problem` with the cell multipliers of `frozen`.
    fn ideal_locking<'a>(&self, problem: &Problem, frozen: &'a Frozen) -> Option<IdealLocking<'a>> {
        problem.material.locking.ideal().map(|set| IdealLocking {
            set,
            r: self.constraints.locking(),
            multipliers: &frozen.locking,
        })
    }

    /// Sets the friction regularization of outer iteration `k`: continuation from
    /// [`REGULARIZATION_START`] down by [`REGULARIZATION_STEP`] per outer iteration to the
    /// target value of each law, which all reach by iteration [`regularization_stages`]. A sticking point of the
    /// regularized norm `√(r² + ρ²)` has curvature 1/ρ only within |r| ≲ ρ; approached from
    /// slips many times ρ, Newton sees almost no curvature and overshoots, so a small ρ
    /// is reached from a large one, each convex problem warm-started from the last.
    pub fn set_regularization_stage(&mut self, k: usize) {
        self.regularization_floor =
            REGULARIZATION_START * REGULARIZATION_STEP.powi(k.min(300) as i32);
    }

    /// The frozen quantities of the first convex problem, at `u`: friction data from `u`,
    /// all multipliers zero (so the first problem is the penalty problem).
    pub fn initial_frozen(&self, problem: &Problem, u: &[f64]) -> Frozen {
        let mut zero = Frozen::zero(self.contact.len());
        let ideal = problem.material.locking.ideal().is_some();
        super::constraints::zero_multipliers(&mut zero, problem.mesh.n_cells(), ideal);
        let mut frozen = self.contact_assembler(problem).freeze(u, &zero);
        super::constraints::zero_multipliers(&mut frozen, problem.mesh.n_cells(), ideal);
        frozen
    }

    /// The map G of the outer fixed point: frozen friction data at `u` and the multiplier
    /// updates from `current` (see [`super::constraints`]).
    pub fn freeze(&self, problem: &Problem, u: &[f64], current: &Frozen) -> Frozen {
        let mut next = self.contact_assembler(problem).freeze(u, current);
        if let Some(set) = problem.material.locking.ideal() {
            next.locking =
                self.constraints
                    .update_locking(&problem.mesh, &set, u, &current.locking);
        }
        next
    }

    /// Convexified energy `E_k(u) = Σ_T |T| (W + Ψ)(ε_T(u)) + contact terms − f·u` for the
    /// frozen quantities `frozen`; the gradient goes to `self.grad` (and the bulk part minus
    /// `f` to `self.grad_bulk`), and with `hessian` the Hessian to `self.hess`.
    pub fn evaluate(
        &mut self,
        problem: &Problem,
        u: &[f64],
        frozen: &Frozen,
        hessian: bool,
    ) -> f64 {
        let bulk = BulkAssembler {
            mesh: &problem.mesh,
            material: &problem.material,
            ideal: self.ideal_locking(problem, frozen),
        };
        let want = if hessian {
            Want::Hessian
        } else {
            Want::Gradient
        };
        let hess = if hessian {
            Some(self.hess.as_mut_slice())
        } else {
            None
        };
        let e_bulk = bulk.assemble_parallel(
            u,
            &mut self.grad_bulk,
            want,
            &self.pattern,
            hess,
            &mut self.workspace,
        );
        let mut work = 0.0;
        for ((g, f), x) in self.grad_bulk.iter_mut().zip(&self.f_ext).zip(u) {
            *g -= f;
            work += f * x;
        }
        self.grad.copy_from_slice(&self.grad_bulk);
        let contact = ContactAssembler {
            dim: problem.mesh.dim(),
            nodes: &self.contact,
            boundaries: &problem.contact,
            regularization_floor: self.regularization_floor,
            penalty: self.constraints.contact(),
        };
        let hc = if hessian {
            Some((self.hess.as_mut_slice(), self.contact_slots.as_slice()))
        } else {
            None
        };
        let e_contact = contact.assemble(u, frozen, &mut self.grad, hc);
        if hessian && !self.rigid_slots.is_empty() {
            // Free rigid motions carried by contact: shift the Newton matrix (not the
            // energy) on their bodies, see `fem::rigid::NEWTON_SHIFT`.
            if self.rigid_shift == 0.0 {
                let max = self
                    .rigid_slots
                    .iter()
                    .fold(0.0f64, |m, &k| m.max(self.hess[k]));
                self.rigid_shift = NEWTON_SHIFT * max;
            }
            for &k in &self.rigid_slots {
                self.hess[k] += self.rigid_shift;
            }
        }
        e_bulk + e_contact - work
    }

    /// Solves `H x = b` for the current Hessian `self.hess` with [`System::linear_solver`],
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
        b: &[f64],
        x: &mut [f64],
        eta: f64,
        settings: &super::NewtonSettings,
        timings: &mut super::Timings,
    ) -> Result<LinearInfo> {
        let request = SolveRequest {
            eta,
            reuse_iterations: settings.pcg_iterations,
        };
        let stats = self
            .linear_solver
            .solve(&self.pattern, &self.hess, b, x, &request)?;
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

    /// Reaction forces at prescribed DOFs (zero elsewhere) from the last evaluation.
    pub fn reactions(&self) -> Vec<f64> {
        (0..self.dofs.n_dofs())
            .map(|k| {
                if self.dofs.is_fixed(k) {
                    self.grad[k]
                } else {
                    0.0
                }
            })
            .collect()
    }
}
