//! The discrete system, prepared once per problem: DOF map, sparsity pattern, linear
//! solver (see [`crate::linalg`]), contact points, external forces, free rigid motions and
//! the continuation stage. [`System::evaluate`] computes the convexified energy `E_k` with
//! its gradient and generalized Hessian for given frozen contact quantities into the work
//! arrays of an [`Evaluation`], which the outer loop owns.

use super::certificate::{Certificate, ContactResult};
use super::constraints::AugmentedLagrangian;
use super::continuation::Continuation;
use super::frozen::Frozen;
use super::local_scales::Bodies;
use super::scaling::Scales;
use crate::assembly::contact::{contact_slots, ContactAssembler};
use crate::assembly::global::{IdealLocking, Want, Workspace};
use crate::assembly::{BulkAssembler, SystemPattern};
use crate::contact::{ContactNodes, NormalResponse};
use crate::error::Result;
use crate::fem::dofs::{DofMap, FIXED};
use crate::fem::rigid::{RigidMotions, NEWTON_SHIFT};
use crate::linalg::{PrepareOptions, SolveRequest, SpdSolver};
use crate::parallel::Share;
use crate::parallel::{Partition, Placement, Processes, Subdomain};
use crate::problem::Problem;
use std::time::Instant;

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
    /// ([`crate::fem::carry`]) and a rigid drop ([`super::held::rigid_drop`]). The unknown
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

/// The linear solver that `kind` resolves to for `problem` ([`super::LinearSolver::resolve`]
/// with the number of free equations): the one [`System::with_linear_solver`] prepares.
pub fn resolved_linear_solver(problem: &Problem, kind: super::LinearSolver) -> super::LinearSolver {
    kind.resolve(problem.mesh.dim(), problem.dof_map().n_free())
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
    /// the first Hessian; see [`crate::fem::rigid::NEWTON_SHIFT`]).
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
    pub fn new(problem: &Problem, settings: &super::SolverSettings) -> Result<Self> {
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
        settings: &super::SolverSettings,
        kind: super::LinearSolver,
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
        settings: &super::SolverSettings,
    ) -> Result<(Self, Option<Problem>)> {
        Self::build(problem, settings, settings.linear_solver, true)
    }

    /// [`System::with_linear_solver`], or with `split` [`System::for_solve`].
    fn build(
        problem: &Problem,
        settings: &super::SolverSettings,
        kind: super::LinearSolver,
        split: bool,
    ) -> Result<(Self, Option<Problem>)> {
        let t0 = Instant::now();
        let dofs = problem.dof_map();
        let d = problem.mesh.dim();
        // Several processes with the distributed solver: the nodes split among them
        // (PETSc's rows and the cells each assembles follow the split), each holding the
        // cells around its own nodes (only that solver can take partial matrices), their
        // nodes, its contact points and every array of the solve on that part alone.
        // Otherwise every process holds the whole system.
        let processes = Processes::current();
        let distributed = split
            && processes.size() > 1
            && kind.resolve(d, dofs.n_free()) == super::LinearSolver::Petsc;
        let contact = problem.contact_nodes()?;
        let continuation = Continuation::new(problem, &settings.constraints, &contact);
        let contact_stiffness = super::constraints::contact_stiffness(problem, &contact);
        let f_ext = problem.external_forces();
        let rigid = problem.rigid_motions()?;
        let bodies = Bodies::new(problem, &rigid);
        let whole_counts = WholeCounts {
            dofs: dofs.n_dofs(),
            equations: dofs.n_free(),
            contact_points: contact.len(),
        };
        // On several processes, this process's part of all that: its subdomain, the part's
        // mesh and the whole numbers of its nodes, and its contact points: its own (those of
        // its own nodes), then its ghost points (pairs whose slave node is another's but
        // whose master facet has a node of its own, assembled again so that that node's rows
        // are complete). The pairs' couplings join the node graph that is split, which keeps
        // most pairs inside one part, and bring their other nodes into the part as ghosts.
        let mut part = None;
        let (dofs, contact, contact_stiffness, continuation, f_ext, rigid, bodies) = if distributed
        {
            let coupled;
            let whole_mesh = if contact.has_pairs() {
                coupled = problem.mesh.clone().with_couplings(contact.couplings(d));
                &coupled
            } else {
                &problem.mesh
            };
            let partition = Partition::of(whole_mesh, &processes)?;
            let sub = Subdomain::new(whole_mesh, partition, processes.rank());
            let (mesh, nodes) = sub.local_mesh(whole_mesh)?;
            let mut local_of = vec![u32::MAX; problem.mesh.n_nodes()];
            for (l, &v) in nodes.iter().enumerate() {
                local_of[v as usize] = l as u32;
            }
            let (points, own_points) = sub.contact_points(&contact, d);
            let pick = |all: &[f64]| points.iter().map(|&i| all[i as usize]).collect();
            let restricted = (
                dofs.restricted(&nodes),
                contact.restricted(&points, points.len() - own_points, |v| local_of[v as usize]),
                pick(&contact_stiffness),
                continuation.restricted(&points),
                nodes
                    .iter()
                    .flat_map(|&v| f_ext[d * v as usize..d * v as usize + d].iter().copied())
                    .collect(),
                rigid.restricted(&nodes),
                bodies.restricted(&nodes, &mesh, &sub.cells),
            );
            part = Some((sub, mesh, nodes, points));
            restricted
        } else {
            (
                dofs,
                contact,
                contact_stiffness,
                continuation,
                f_ext,
                rigid,
                bodies,
            )
        };
        let mesh = part.as_ref().map_or(&problem.mesh, |p| &p.1);
        // The contact pairs couple each slave node with its master facet's nodes: the
        // matrix's graph (its pattern and fill-reducing ordering) has those couplings too.
        let coupled;
        let mesh = if contact.has_pairs() {
            coupled = mesh.clone().with_couplings(contact.couplings(d));
            &coupled
        } else {
            mesh
        };
        // This process's rows: the DOFs of its own nodes (all of them on one process).
        let own_dofs = part
            .as_ref()
            .map_or(dofs.n_dofs(), |p| d * p.0.nodes().len());
        let pattern = SystemPattern::new(mesh, &dofs)?;
        let nnz = match &part {
            None => pattern.nnz(),
            Some(_) => whole_nnz(
                &pattern,
                &dofs,
                own_dofs,
                whole_counts.equations,
                &processes,
            )?,
        };
        let mut point_cells = cells_around(mesh, &contact.node);
        if let Some((sub, ..)) = &part {
            // The cells around each point in the whole mesh's order, as on one process.
            for i in 0..contact.len() {
                let (a, b) = (point_cells.0[i], point_cells.0[i + 1]);
                point_cells.1[a..b].sort_unstable_by_key(|&c| sub.cells[c as usize]);
            }
        }
        let t1 = Instant::now();
        let one;
        let partition = match &part {
            Some(p) => &p.0.partition,
            None => {
                one = Partition::ranges(problem.mesh.n_nodes(), 1);
                &one
            }
        };
        let options = PrepareOptions {
            ordering: settings.ordering,
            par: super::parallelism(settings.factorization_threads),
            petsc_options: &settings.petsc.options,
            placement: Placement {
                partition,
                nodes: part.as_ref().map(|p| p.2.as_slice()),
            },
        };
        let linear_solver = kind.prepare(mesh, dofs.equations(), &pattern, &options)?;
        let t2 = Instant::now();
        let contact_slots = contact_slots(&contact, d, dofs.equations(), &pattern);
        let rigid_slots = rigid_slots(&rigid, &dofs, &pattern, own_dofs);
        let mut workspace = Workspace::new(match settings.threads {
            0 => rayon::current_num_threads(),
            t => t,
        });
        // The translation the supports carry each body by: the solve is for the
        // displacement beyond it (the contact points already meet the obstacles there).
        let placement = problem.carried_displacement().map(|c| match &part {
            None => c,
            Some((_, _, nodes, _)) => nodes
                .iter()
                .flat_map(|&v| c[d * v as usize..d * v as usize + d].iter().copied())
                .collect(),
        });
        let (subdomain, share, processes, part_problem) = match part {
            None => (None, Share::whole(), Processes::alone(), None),
            Some((sub, mesh, nodes, points)) => {
                workspace.owned_cells = Some(sub.owned);
                let whole = [
                    problem.mesh.n_nodes(),
                    whole_counts.contact_points,
                    problem.mesh.n_cells(),
                ];
                let own_points = contact.owned();
                let share = Share::of(d, &sub, nodes, &dofs, points, own_points, whole, processes);
                let part_problem = Problem {
                    mesh,
                    materials: problem.materials.clone(),
                    region_material: problem.region_material.clone(),
                    plane: problem.plane,
                    dirichlet: problem.dirichlet.clone(),
                    tractions: problem.tractions.clone(),
                    body_force: problem.body_force,
                    contact: problem.contact.clone(),
                };
                (Some(sub), share, processes, Some(part_problem))
            }
        };
        let system = System {
            dofs,
            pattern,
            nnz,
            whole: whole_counts,
            linear_solver,
            contact,
            contact_slots,
            contact_stiffness,
            point_cells,
            continuation,
            f_ext,
            bodies,
            setup_time: ((t1 - t0).as_secs_f64(), (t2 - t1).as_secs_f64()),
            workspace,
            rigid,
            rigid_slots,
            subdomain,
            share,
            processes,
            scales: None,
            placement,
        };
        Ok((system, part_problem))
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

    /// The contact results and the certificate ([`super::certificate::evaluate`]) of `u` for
    /// the frozen quantities `frozen`, from the evaluation `eval` at `u` (its bulk gradient
    /// and the responses of user-defined compliance laws), the force scales of the bodies
    /// `body_scale`, the friction coefficients `mu` at `u` and the tolerance `tolerance`.
    #[allow(clippy::too_many_arguments)]
    pub fn certificate(
        &self,
        problem: &Problem,
        u: &[f64],
        frozen: &Frozen,
        eval: &Evaluation,
        body_scale: &[f64],
        mu: &[f64],
        tolerance: f64,
    ) -> (Vec<ContactResult>, Certificate) {
        let (mut point_force, mut floor) = (Vec::new(), Vec::new());
        self.point_scales(
            problem,
            u,
            frozen,
            &eval.normal,
            body_scale,
            &mut point_force,
            &mut floor,
        );
        let mut round_off = super::round_off::Floors::default();
        self.round_off_floors(problem, u, frozen, &eval.normal, &mut round_off);
        let mut ca = self.contact_assembler(problem);
        ca.responses = &eval.normal;
        super::certificate::evaluate(
            &ca,
            &super::certificate::Inputs {
                u,
                mu,
                grad_bulk: &eval.grad_bulk,
                f_ext: &self.f_ext,
                fixed: &|k| self.dofs.is_fixed(k),
                bodies: &self.bodies,
                floor: &floor,
                round_off: &round_off,
                mesh: &problem.mesh,
                frozen: frozen.contact(),
                tolerance,
                share: &self.share,
            },
        )
    }

    /// Convexified energy `E_k(u) = Σ_T |T| (W + Ψ)(ε_T(u)) + contact terms − f·u` for the
    /// frozen quantities `frozen`; the gradient goes to `out.grad` (and the bulk part minus
    /// `f` to `out.grad_bulk`), and with `hessian` the Hessian to `out.hess`. A user-defined
    /// compliance law that fails leaves its error in `out.law_error` and returns NaN.
    ///
    /// On several processes, `problem` and `u` are this process's part
    /// ([`System::for_solve`]): it assembles the cells of its part (counting the energy of
    /// those it owns) and its contact points (counting the energy of its own; its ghost
    /// points complete its master nodes' rows), so the gradients are complete at its own
    /// nodes; their entries at its ghost nodes are set to NaN (partial there, never read).
    /// The energies and the work of the loads are summed over the processes
    /// ([`Processes::sum`] of three numbers, the one exchange of an evaluation).
    pub fn evaluate(
        &mut self,
        problem: &Problem,
        u: &[f64],
        frozen: &Frozen,
        out: &mut Evaluation,
        hessian: bool,
    ) -> f64 {
        let want = if hessian {
            Want::Hessian
        } else {
            Want::Gradient
        };
        let hess = if hessian {
            Some(out.hess.as_mut_slice())
        } else {
            None
        };
        let bulk = BulkAssembler {
            ideal: ideal_locking(&self.continuation.penalties, problem, frozen),
            ..BulkAssembler::of(problem, &problem.mesh)
        };
        let e_bulk = bulk.assemble_parallel(
            u,
            &mut out.grad_bulk,
            want,
            &self.pattern,
            hess,
            &mut self.workspace,
        );
        let mut contact = self.contact_assembler(problem);
        let share = &self.share;
        if let Err(e) = contact.normal_responses(u, hessian, &mut out.normal) {
            out.law_error.get_or_insert(e);
            return f64::NAN;
        }
        contact.responses = &out.normal;
        let hc = if hessian {
            Some((out.hess.as_mut_slice(), self.contact_slots.as_slice()))
        } else {
            None
        };
        let work = subtract_external(&mut out.grad_bulk, &self.f_ext, u, |k| share.counts_dof(k));
        if share.is_split() {
            // A ghost node's bulk gradient is partial here: unknown.
            for (k, g) in out.grad_bulk.iter_mut().enumerate() {
                if !share.counts_dof(k) {
                    *g = f64::NAN;
                }
            }
        }
        out.grad.copy_from_slice(&out.grad_bulk);
        let e_contact = contact.assemble(u, &frozen.contact(), &mut out.grad, hc);
        let mut e = [e_bulk, e_contact, work];
        share.sum(&mut e);
        let [e_bulk, e_contact, work] = e;
        if hessian && self.rigid.any_free() {
            // Free rigid motions carried by contact: shift the Newton matrix (not the
            // energy) on their bodies, see `fem::rigid::NEWTON_SHIFT`. Decided on the whole
            // problem's bodies: a process without a node of them still takes part in the
            // maximum.
            if out.rigid_shift == 0.0 {
                let mut max = [self
                    .rigid_slots
                    .iter()
                    .fold(0.0f64, |m, &k| m.max(out.hess[k]))];
                if let Err(e) = self.processes.max(&mut max) {
                    out.law_error.get_or_insert(e);
                    return f64::NAN;
                }
                out.rigid_shift = NEWTON_SHIFT * max[0];
            }
            for &k in &self.rigid_slots {
                out.hess[k] += out.rigid_shift;
            }
        }
        // A failed reduction of the solver's (MPI's error) ends the solve with that error.
        if let Some(e) = self.share.failure() {
            out.law_error.get_or_insert(e);
            return f64::NAN;
        }
        e_bulk + e_contact - work
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
        settings: &super::NewtonSettings,
        timings: &mut super::Timings,
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

/// `grad ← grad − f_ext`; returns the work of the external forces `f_ext · u` (J, J/m in
/// 2D) over the DOFs `counted`, in order.
fn subtract_external(
    grad: &mut [f64],
    f_ext: &[f64],
    u: &[f64],
    counted: impl Fn(usize) -> bool,
) -> f64 {
    let mut work = 0.0;
    for (k, ((g, f), x)) in grad.iter_mut().zip(f_ext).zip(u).enumerate() {
        *g -= f;
        if counted(k) {
            work += f * x;
        }
    }
    work
}

/// The diagonal slots in `pattern` of the free DOFs (of `dofs`, below `rows`) on which
/// `rigid` shifts the Newton matrix: this process's rows of them.
fn rigid_slots(
    rigid: &RigidMotions,
    dofs: &DofMap,
    pattern: &SystemPattern,
    rows: usize,
) -> Vec<usize> {
    rigid
        .shifted_dofs()
        .into_iter()
        .filter(|&k| k < rows && !dofs.is_fixed(k))
        .map(|k| pattern.diagonal_slot(dofs.equation(k) as usize))
        .collect()
}

/// The entries of the upper triangle of the whole reduced system, from this process's
/// `pattern` (its part's, DOF map `dofs`, its own DOFs the first `own_dofs`): every free
/// own row's entries in both triangles, summed over the processes, give twice the upper
/// triangle less the diagonal (`n_free` equations in all).
///
/// # Errors
/// MPI's.
fn whole_nnz(
    pattern: &SystemPattern,
    dofs: &DofMap,
    own_dofs: usize,
    n_free: usize,
    processes: &Processes,
) -> Result<usize> {
    let own_eqs = dofs.equations()[..own_dofs]
        .iter()
        .filter(|&&eq| eq != FIXED)
        .count();
    let (col_ptr, row_idx) = (pattern.col_ptr(), pattern.row_idx());
    // Own equations are the first ones of the part's numbering.
    let mut full = 0usize;
    for j in 0..pattern.n() {
        for &i in &row_idx[col_ptr[j]..col_ptr[j + 1]] {
            full += usize::from(j < own_eqs);
            full += usize::from(i != j && i < own_eqs);
        }
    }
    // Counts below 2^53 add exactly in floating point.
    let mut total = [full as f64];
    processes.sum(&mut total)?;
    Ok((total[0] as usize + n_free) / 2)
}

/// The cells around each of the nodes `nodes`, in compressed rows (see
/// [`System::point_cells`]).
fn cells_around(mesh: &crate::mesh::Mesh, nodes: &[u32]) -> (Vec<usize>, Vec<u32>) {
    let mut wanted = vec![u32::MAX; mesh.n_nodes()];
    let mut lists: Vec<Vec<u32>> = vec![Vec::new(); nodes.len()];
    let mut first_point = Vec::with_capacity(nodes.len());
    for (i, &v) in nodes.iter().enumerate() {
        if wanted[v as usize] == u32::MAX {
            wanted[v as usize] = i as u32;
        }
        first_point.push(wanted[v as usize] as usize);
    }
    for c in 0..mesh.n_cells() {
        for &v in mesh.cell(c) {
            let i = wanted[v as usize];
            if i != u32::MAX {
                lists[i as usize].push(c as u32);
            }
        }
    }
    let mut offsets = vec![0];
    let mut cells = Vec::new();
    for &j in &first_point {
        cells.extend_from_slice(&lists[j]);
        offsets.push(cells.len());
    }
    (offsets, cells)
}

/// The ideal-locking term of `problem` with the penalties `penalties` and the cell
/// multipliers of `frozen`.
pub(super) fn ideal_locking<'a>(
    penalties: &'a AugmentedLagrangian,
    problem: &Problem,
    frozen: &'a Frozen,
) -> Option<IdealLocking<'a>> {
    problem.has_ideal_locking().then(|| IdealLocking {
        sets: penalties.locking_sets(),
        r: penalties.locking(),
        multipliers: &frozen.multipliers.locking,
    })
}
