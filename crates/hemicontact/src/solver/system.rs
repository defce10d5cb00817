//! The discrete system, prepared once per problem: DOF map, sparsity pattern, symbolic
//! factorization, contact points, external forces, and the work arrays of the Newton
//! iteration. [`System::evaluate`] computes the convexified energy `E_k` with its
//! gradient and generalized Hessian for given frozen contact quantities.

use crate::assembly::contact::{contact_slots, ContactAssembler, Frozen};
use crate::assembly::global::{IdealLocking, Want, Workspace};
use crate::assembly::{BulkAssembler, SystemPattern};
use crate::contact::ContactNodes;
use crate::error::Result;
use crate::fem::dofs::{DofMap, FIXED};
use crate::fem::rigid::{RigidMotions, NEWTON_SHIFT};
use crate::linalg::{Cholesky, Multigrid};
use crate::problem::Problem;
use std::time::Instant;

/// Everything that depends only on the mesh and the boundary-condition *pattern*.
#[derive(Debug)]
pub struct System {
    /// DOF map (Dirichlet DOFs eliminated).
    pub dofs: DofMap,
    /// Upper-triangular pattern of the reduced system.
    pub pattern: SystemPattern,
    /// Cholesky factorization (symbolic analysis done); `None` with the iterative linear
    /// solver, which never factorizes the fine system.
    pub cholesky: Option<Cholesky>,
    /// Multigrid hierarchy of the iterative linear solver; `None` with the direct one.
    pub multigrid: Option<Multigrid>,
    /// Contact points.
    pub contact: ContactNodes,
    /// Hessian slots of the contact points' node blocks.
    pub contact_slots: Vec<u32>,
    /// Continuation floor of the numerical regularization ρ_num of a smoothed norm in the
    /// friction potential, in units of the displacement scale (the solver works in
    /// dimensionless variables, see [`super::scaling`]); each law uses the larger of this
    /// and its own value ([`System::set_regularization_stage`]). 0: the laws' own values.
    pub regularization_floor: f64,
    /// Augmented-Lagrangian penalty r_i per contact point (Pa/m), see
    /// [`super::constraints`].
    pub contact_penalty: Vec<f64>,
    /// Augmented-Lagrangian penalty r_T of ideal locking (0 without).
    pub locking_penalty: f64,
    /// The full penalties (contact points, locking) that `contact_penalty` and
    /// `locking_penalty` are scaled from during continuation.
    full_penalty: (Vec<f64>, f64),
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
    /// Hessian values of the current factorization or multigrid operators (empty: none
    /// yet).
    factored: Vec<f64>,
    /// PCG work vectors (r, z, p, Ap).
    work: [Vec<f64>; 4],
    /// Refactorize at the next linear solve (the factorization went stale).
    refactor_next: bool,
    /// Cost of a numeric factorization in units of one triangular solve (see
    /// [`System::linear_solve`]).
    factor_cost: f64,
    /// PCG work beyond plain solves since the last factorization, in solve units.
    pcg_spent: f64,
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

/// Cost of one PCG iteration (a triangular solve and a sparse product) in solve units.
const PCG_ITERATION_COST: f64 = 1.1;

/// Iteration cap of multigrid-preconditioned CG (iterative linear solver). Measured counts
/// are far below (tens at most); reaching the cap means the preconditioner failed.
pub const ITERATIVE_MAX_ITERATIONS: usize = 500;

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
    /// chosen by `problem.solver.linear_solver` (see [`super::LinearSolver::resolve`]).
    ///
    /// # Errors
    /// [`crate::Error::OutOfMemory`] if the pattern or factor cannot be allocated.
    pub fn new(problem: &Problem) -> Result<Self> {
        Self::with_linear_solver(problem, problem.solver.linear_solver)
    }

    /// As [`System::new`] with the linear solver `kind` instead of the problem's: for the
    /// direct solver the symbolic Cholesky analysis, for the iterative one the multigrid
    /// grids and prolongations (no factorization of the fine system).
    ///
    /// # Errors
    /// As [`System::new`].
    pub fn with_linear_solver(problem: &Problem, kind: super::LinearSolver) -> Result<Self> {
        let t0 = Instant::now();
        let dofs = problem.dof_map();
        let pattern = SystemPattern::new(&problem.mesh, &dofs)?;
        let contact = problem.contact_nodes();
        let contact_penalty = super::constraints::contact_penalties(problem, &contact.weight);
        let locking_penalty = problem.material.locking.ideal().map_or(0.0, |set| {
            super::constraints::locking_penalty(problem, &set)
        });
        let contact_slots = contact_slots(&contact, problem.mesh.dim(), dofs.equations(), &pattern);
        let t1 = Instant::now();
        let (cholesky, multigrid) = match kind.resolve(problem.mesh.dim(), pattern.n()) {
            super::LinearSolver::Iterative => (
                None,
                Some(Multigrid::new(&problem.mesh, dofs.equations(), &pattern)),
            ),
            _ => (
                Some(Cholesky::analyze(
                    &problem.mesh,
                    dofs.equations(),
                    &pattern,
                    problem.solver.ordering,
                    super::parallelism(problem.solver.factorization_threads),
                )?),
                None,
            ),
        };
        let t2 = Instant::now();
        // A solve streams the factor twice (2 nnz(L) multiply-adds); a factorization costs
        // Σ_j c_j² ≈ nnz(L) · (average column count). Measured on the paper square the
        // ratio is about nnz(L)/(12 n): 6 at n = 128 (30 ms vs 5 ms), 9 at n = 512 (1.1 s vs
        // 0.12 s). A count-based model, not a timer, keeps the solver's decisions — and so
        // its results — deterministic.
        let factor_cost = cholesky.as_ref().map_or(1.0, |c| {
            (c.nnz_factor() as f64 / (12.0 * pattern.n().max(1) as f64)).max(1.0)
        });
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
            cholesky,
            multigrid,
            contact,
            contact_slots,
            regularization_floor: 0.0,
            full_penalty: (contact_penalty.clone(), locking_penalty),
            contact_penalty,
            locking_penalty,
            f_ext,
            force_floor,
            grad: vec![0.0; n],
            grad_bulk: vec![0.0; n],
            hess,
            setup_time: ((t1 - t0).as_secs_f64(), (t2 - t1).as_secs_f64()),
            factored: Vec::new(),
            work: Default::default(),
            refactor_next: false,
            factor_cost,
            pcg_spent: 0.0,
            workspace: Workspace::new(match problem.solver.threads {
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
            penalty: &self.contact_penalty,
        }
    }

    /// The ideal-locking term of `problem` with the cell multipliers of `frozen`.
    fn ideal_locking<'a>(&self, problem: &Problem, frozen: &'a Frozen) -> Option<IdealLocking<'a>> {
        problem.material.locking.ideal().map(|set| IdealLocking {
            set,
            r: self.locking_penalty,
            multipliers: &frozen.locking,
        })
    }

    /// Sets the augmented-Lagrangian penalties of outer iteration `k` (continuation, see
    /// [`super::constraints`]).
    pub fn set_penalty_stage(&mut self, settings: &super::ConstraintSettings, k: usize) {
        let contact = settings.factor(k, settings.contact_penalty) / settings.contact_penalty;
        let locking = settings.factor(k, settings.locking_penalty) / settings.locking_penalty;
        for (r, full) in self.contact_penalty.iter_mut().zip(&self.full_penalty.0) {
            *r = contact * full;
        }
        self.locking_penalty = locking * self.full_penalty.1;
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
            next.locking = super::constraints::update_locking(
                &problem.mesh,
                &set,
                self.locking_penalty,
                u,
                &current.locking,
            );
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
            penalty: &self.contact_penalty,
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

    /// Solves `H x = b` for the current Hessian `self.hess`, to the relative residual `eta`
    /// where an iterative solve is used (the forcing term of the inexact Newton method).
    ///
    /// - If the Hessian equals the factorized one (to 1e-12 relative: it is piecewise
    ///   constant in the active sets, and the friction curvature of slipping nodes is
    ///   negligible), the factorization is reused: one triangular solve.
    /// - Else, if a factorization exists, preconditioned conjugate gradients with it as
    ///   preconditioner, up to `settings.pcg_iterations` iterations to the relative
    ///   residual `settings.pcg_tolerance`.
    /// - Otherwise (or if PCG does not get there) the Hessian is refactorized.
    ///
    /// With the iterative linear solver ([`System::multigrid`]) instead: the multigrid
    /// operators are rebuilt from `self.hess` when it changed (same 1e-12 test; the time
    /// goes to `timings.factorization` and counts as a factorization in
    /// `timings.n_factorizations` and `refactorized`), then multigrid-preconditioned CG
    /// solves to the relative residual `eta` within [`ITERATIVE_MAX_ITERATIONS`].
    ///
    /// # Errors
    /// As [`Cholesky::factorize`]; with the iterative solver, [`crate::Error::Breakdown`]
    /// if CG does not reach `eta` within [`ITERATIVE_MAX_ITERATIONS`] iterations or breaks
    /// down, and the errors of [`Multigrid::update`].
    pub fn linear_solve(
        &mut self,
        b: &[f64],
        x: &mut [f64],
        eta: f64,
        settings: &super::NewtonSettings,
        timings: &mut super::Timings,
    ) -> Result<LinearInfo> {
        if self.multigrid.is_some() {
            return self.iterative_solve(b, x, eta, timings);
        }
        let t = Instant::now();
        let mut info = LinearInfo {
            refactorized: false,
            pcg_iterations: 0,
        };
        if self.cholesky.is_none() {
            return Err(crate::Error::Breakdown(
                "no linear solver prepared for the system".into(),
            ));
        }
        if !self.factored.is_empty() && !self.refactor_next {
            let scale = self.factored.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let (mut change, mut changed) = (0.0f64, 0usize);
            for (a, c) in self.hess.iter().zip(&self.factored) {
                let d = (a - c).abs();
                change = change.max(d);
                changed += usize::from(d > 1e-12 * scale);
            }
            if change <= 1e-12 * scale {
                x.copy_from_slice(b);
                if let Some(cholesky) = self.cholesky.as_mut() {
                    cholesky.solve_in_place(x);
                }
                timings.solve += t.elapsed().as_secs_f64();
                return Ok(info);
            }
            // Each changed cell or contact node alters at most ld(ld+1)/2 entries and adds
            // about one PCG iteration; try PCG only when the estimated rank is small.
            let ld = self.pattern.local_dofs();
            let rank_estimate = changed / (ld * (ld + 1) / 2);
            // PCG pays while its iterations (one solve and one product each) cost less than
            // a factorization: cap them by the measured cost ratio.
            let affordable = (0.7 * self.factor_cost / PCG_ITERATION_COST) as usize;
            let max_iter = settings.pcg_iterations.min(affordable);
            if max_iter > 0 && rank_estimate < max_iter {
                let outcome = self.pcg(b, x, max_iter, eta);
                // Ski rental: pay PCG iterations ("rent") until their accumulated cost beyond
                // one plain solve reaches the cost of a factorization ("buy"), then
                // refactorize at the next step. This costs at most twice the optimum in
                // hindsight, whatever the sequence of Hessians. Costs are counted, not timed.
                let iterations = outcome.unwrap_or(max_iter) + 1;
                self.pcg_spent += iterations as f64 * PCG_ITERATION_COST - 1.0;
                if let Some(k) = outcome {
                    info.pcg_iterations = k;
                    self.refactor_next = self.pcg_spent >= self.factor_cost;
                    timings.solve += t.elapsed().as_secs_f64();
                    return Ok(info);
                }
            }
        }
        timings.solve += t.elapsed().as_secs_f64();
        let t = Instant::now();
        self.factored.clear();
        self.refactor_next = false;
        self.pcg_spent = 0.0;
        let Some(cholesky) = self.cholesky.as_mut() else {
            return Err(crate::Error::Breakdown(
                "no linear solver prepared for the system".into(),
            ));
        };
        cholesky.factorize(&self.pattern, &self.hess)?;
        self.factored.extend_from_slice(&self.hess);
        timings.factorization += t.elapsed().as_secs_f64();
        timings.n_factorizations += 1;
        let t = Instant::now();
        x.copy_from_slice(b);
        cholesky.solve_in_place(x);
        timings.solve += t.elapsed().as_secs_f64();
        info.refactorized = true;
        Ok(info)
    }

    /// Preconditioned conjugate gradients on `self.hess` with the current factorization as
    /// preconditioner, from x = P⁻¹b. Returns the iteration count if the relative residual
    /// reached `tol` within `max_iter` iterations.
    fn pcg(&mut self, b: &[f64], x: &mut [f64], max_iter: usize, tol: f64) -> Option<usize> {
        let n = b.len();
        let [r, z, p, ap] = &mut self.work;
        let cholesky = self.cholesky.as_mut()?;
        for v in [&mut *r, &mut *z, &mut *p, &mut *ap] {
            v.resize(n, 0.0);
        }
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let b_norm = dot(b, b).sqrt();
        if b_norm == 0.0 {
            x.fill(0.0);
            return Some(0);
        }
        x.copy_from_slice(b);
        cholesky.solve_in_place(x);
        self.pattern.sym_matvec(&self.hess, x, ap);
        for i in 0..n {
            r[i] = b[i] - ap[i];
        }
        z.copy_from_slice(r);
        cholesky.solve_in_place(z);
        p.copy_from_slice(z);
        let mut rz = dot(r, z);
        for k in 1..=max_iter {
            self.pattern.sym_matvec(&self.hess, p, ap);
            let pap = dot(p, ap);
            if pap.is_nan() || pap <= 0.0 {
                return None;
            }
            let alpha = rz / pap;
            for i in 0..n {
                x[i] += alpha * p[i];
                r[i] -= alpha * ap[i];
            }
            if dot(r, r).sqrt() <= tol * b_norm {
                return Some(k);
            }
            z.copy_from_slice(r);
            cholesky.solve_in_place(z);
            let rz_new = dot(r, z);
            let beta = rz_new / rz;
            rz = rz_new;
            for i in 0..n {
                p[i] = z[i] + beta * p[i];
            }
        }
        None
    }

    /// The iterative branch of [`System::linear_solve`]: multigrid-preconditioned CG, with
    /// the multigrid operators rebuilt when the Hessian changed.
    fn iterative_solve(
        &mut self,
        b: &[f64],
        x: &mut [f64],
        eta: f64,
        timings: &mut super::Timings,
    ) -> Result<LinearInfo> {
        let Some(mg) = self.multigrid.as_mut() else {
            return Err(crate::Error::Breakdown(
                "no multigrid hierarchy prepared for the system".into(),
            ));
        };
        let mut info = LinearInfo {
            refactorized: false,
            pcg_iterations: 0,
        };
        let scale = self.factored.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let unchanged = !self.factored.is_empty()
            && self
                .hess
                .iter()
                .zip(&self.factored)
                .all(|(a, c)| (a - c).abs() <= 1e-12 * scale);
        if !unchanged {
            let t = Instant::now();
            self.factored.clear();
            mg.update(&self.hess)?;
            self.factored.extend_from_slice(&self.hess);
            timings.factorization += t.elapsed().as_secs_f64();
            timings.n_factorizations += 1;
            info.refactorized = true;
        }
        let t = Instant::now();
        let outcome = mg.solve(b, x, eta, ITERATIVE_MAX_ITERATIONS)?;
        timings.solve += t.elapsed().as_secs_f64();
        if !outcome.converged {
            return Err(crate::Error::Breakdown(format!(
                "multigrid-preconditioned CG did not reach the relative residual {eta:e} in \
                 {} iterations (reached {:e}); try [solver] linear_solver = \"direct\"",
                outcome.iterations, outcome.relative_residual
            )));
        }
        info.pcg_iterations = outcome.iterations;
        Ok(info)
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
