//! The PETSc linear solver (`[solver] linear_solver = "petsc"`, cargo feature `petsc`): the
//! Newton matrix and right-hand side handed to a PETSc KSP, by default conjugate gradients
//! preconditioned by smoothed-aggregation algebraic multigrid (GAMG) with the rigid-body
//! modes as near-null space; any KSP and PC of PETSc through `[solver.petsc] options` and
//! the `PETSC_OPTIONS` environment variable (MUMPS's Cholesky:
//! `-ksp_type preonly -pc_type cholesky -pc_factor_mat_solver_type mumps`).
//!
//! PETSc gets the **whole** DOF system, in blocks of one node's `d` DOFs (what GAMG's
//! aggregation and the rigid-body modes expect): the free equations as assembled, and an
//! identity row scaled by the mean diagonal of the free ones for each prescribed DOF, with a
//! zero right-hand side there, so the prescribed DOFs solve to zero and decouple. The
//! pattern is given to PETSc once (exact preallocation); every changed matrix replaces the
//! values in place.
//!
//! Run as several MPI processes ([`crate::parallel`]), each rank hands PETSc the rows of
//! its part of the nodes ([`crate::parallel::Partition`]) of a distributed matrix (MatMPIAIJ), numbered in
//! the partition's distributed numbering (each rank's rows contiguous):
//! complete rows, since it assembled every cell around its nodes
//! ([`crate::parallel::Subdomain`]); its other rows of `values` are partial and never read.
//! Whether the matrix changed is decided on each rank's rows and agreed by all, and the
//! Krylov solve runs on all of them. Each rank then has the solution at its own rows and
//! fetches it at its ghost rows (the free DOFs of the other nodes of its part) from their
//! owners through a PETSc scatter: the rest of the Newton step runs on its part alone. On
//! one process the same code holds every row.
//!
//! A changed matrix does not always get a new preconditioner: a GAMG set-up costs about
//! [`SETUP_COST`] CG iterations, and between Newton steps the matrix changes only at the
//! contact points and locked cells. The choice is the one of the in-house iterative solver
//! ([`super::iterative`], a ski rental counted in iterations): the first solve after a
//! set-up gives the iterations per decade of residual reduction of a fresh preconditioner;
//! a solve with the kept one pays the iterations beyond that rate, and may spend what is
//! left of one set-up's cost before it is abandoned for a set-up and solved again; once the
//! extra iterations add up to a set-up, the next changed matrix is set up. The kept
//! preconditioner is used only with conjugate gradients on the true residual (the
//! default), where it costs iterations and never accuracy: other KSPs (`preonly` with a
//! factorization, say) are set up for every changed matrix. `newton.pcg_iterations = 0`
//! sets up every changed matrix too. An unchanged matrix (within
//! [`super::direct::UNCHANGED`]) keeps the preconditioner.

use super::direct::matrix_unchanged;
use super::solver::{SolveRequest, SolveStats, SpdSolver};
use super::ITERATIVE_MAX_ITERATIONS;
use crate::assembly::SystemPattern;
use crate::error::{Error, Result};
use crate::fem::dofs::FIXED;
use crate::mesh::Mesh;
use crate::parallel::{Placement, Processes};
use hemicontact_petsc::KspSystem;
use std::time::Instant;

/// Source marker of the diagonal entry of a prescribed DOF's identity row.
const PRESCRIBED: u32 = u32::MAX;

/// The PETSc linear solver; see the module documentation.
#[derive(Debug)]
pub struct PetscSolver {
    /// PETSc's matrix and KSP.
    system: KspSystem,
    /// For every entry of this rank's rows of PETSc's CSR matrix (DOF numbering, both
    /// triangles), the slot of its value in the upper-triangle values of
    /// [`SystemPattern`], or [`PRESCRIBED`].
    source: Vec<u32>,
    /// The CSR values of this rank's rows handed to PETSc.
    csr_values: Vec<f64>,
    /// Slots of the diagonal of the free equations of this rank's rows (for the prescribed
    /// rows' scale).
    diagonal: Vec<usize>,
    /// Number of free equations (all processes).
    n_free: usize,
    /// The equation number (in the numbering of the system it is given: the part's on
    /// several processes) of each of this rank's rows ([`FIXED`] for a prescribed DOF), in
    /// PETSc's order.
    row_equations: Vec<u32>,
    /// Right-hand side of this rank's rows.
    b_local: Vec<f64>,
    /// Solution of this rank's rows.
    x_local: Vec<f64>,
    /// The equation of each ghost row of this rank (the free DOFs of its part's other
    /// nodes, in the part's numbering), in the order handed to
    /// [`KspSystem::set_ghost_rows`] (several processes).
    ghost_equations: Vec<u32>,
    /// The solution at the ghost rows (several processes).
    ghost_values: Vec<f64>,
    /// The processes of the run.
    processes: Processes,
    /// Whether PETSc holds matrix values yet.
    has_matrix: bool,
    /// The options as given, for messages.
    options: String,
    /// Whether the KSP may keep a preconditioner of other values
    /// ([`KspSystem::can_keep_preconditioner`]).
    can_keep: bool,
    /// CG iterations per decade of residual reduction of the first solve after the last
    /// set-up (0: not measured yet).
    fresh_rate: f64,
    /// Iterations beyond that rate spent with a kept preconditioner since the last set-up.
    rent: f64,
    /// Whether the next changed matrix gets a set-up.
    setup_next: bool,
}

/// Cost of a PETSc preconditioner set-up in CG iterations with it. Measured for GAMG:
/// see `docs/distributed.md`.
pub const SETUP_COST: f64 = 50.0;

impl PetscSolver {
    /// Hands the pattern of `pattern` (the reduced system of `mesh` with equation numbers
    /// `equations`) to PETSc, with the nodes' coordinates for the rigid-body modes, and
    /// configures the KSP from the defaults, `options` and `PETSC_OPTIONS`. With
    /// `placement.nodes`, `mesh` is this process's part of the mesh, its own nodes first, and
    /// the system is distributed over `processes`: the rows of its own nodes are the
    /// ones it hands PETSc. Without, `mesh` is the whole mesh, solved by this process alone.
    ///
    /// # Errors
    /// [`Error::Invalid`] (field `petsc.options`) when PETSc refuses the options or cannot
    /// be initialized.
    pub fn new(
        mesh: &Mesh,
        equations: &[u32],
        pattern: &SystemPattern,
        options: &str,
        placement: &Placement,
        processes: &Processes,
    ) -> Result<Self> {
        let d = mesh.dim();
        let partition = placement.partition;
        let processes = match placement.nodes {
            Some(_) => *processes,
            None => Processes::alone(),
        };
        let rank = processes.rank();
        // The whole mesh's number of every node of `mesh`.
        let node = |l: usize| placement.nodes.map_or(l, |nodes| nodes[l] as usize);
        // PETSc's number of every DOF: its node's place in the distributed numbering.
        let global = |dof: usize| (d * partition.position[node(dof / d)] as usize + dof % d) as u32;
        let mut dof_of = vec![0u32; pattern.n()];
        for (dof, &eq) in equations.iter().enumerate() {
            if eq != FIXED {
                dof_of[eq as usize] = dof as u32;
            }
        }
        let (col_ptr, row_idx) = (pattern.col_ptr(), pattern.row_idx());
        // This rank's rows: the DOFs of its own nodes, the first of `mesh` (all of them on
        // one process), in PETSc's order.
        let own_nodes = partition.first[rank + 1] - partition.first[rank];
        if own_nodes > mesh.n_nodes() {
            return Err(Error::Breakdown(format!(
                "a part of {} nodes cannot hold its {own_nodes} own nodes",
                mesh.n_nodes()
            )));
        }
        let n_rows = d * own_nodes;
        let mine = |dof: u32| (dof as usize) < n_rows;
        // Entries per row of this rank: both triangles of the free block, one diagonal
        // entry for each prescribed DOF.
        let mut local_ptr = vec![0usize; n_rows + 1];
        let mut count = |dof: u32| {
            if mine(dof) {
                local_ptr[dof as usize + 1] += 1;
            }
        };
        for (dof, &eq) in equations.iter().enumerate() {
            if eq == FIXED {
                count(dof as u32);
            }
        }
        for j in 0..pattern.n() {
            for &i in &row_idx[col_ptr[j]..col_ptr[j + 1]] {
                count(dof_of[j]);
                if i != j {
                    count(dof_of[i]);
                }
            }
        }
        for r in 0..n_rows {
            local_ptr[r + 1] += local_ptr[r];
        }
        // (PETSc's column, source slot) of every entry, sorted by column within each row.
        let mut entries = vec![(0u32, 0u32); local_ptr[n_rows]];
        let mut next = local_ptr.clone();
        let mut push = |row: u32, col: u32, src: u32| {
            if mine(row) {
                entries[next[row as usize]] = (global(col as usize), src);
                next[row as usize] += 1;
            }
        };
        for (dof, &eq) in equations.iter().enumerate() {
            if eq == FIXED {
                push(dof as u32, dof as u32, PRESCRIBED);
            }
        }
        for j in 0..pattern.n() {
            for (k, &i) in row_idx[col_ptr[j]..col_ptr[j + 1]].iter().enumerate() {
                let slot = (col_ptr[j] + k) as u32;
                push(dof_of[j], dof_of[i], slot);
                if i != j {
                    push(dof_of[i], dof_of[j], slot);
                }
            }
        }
        for r in 0..n_rows {
            entries[local_ptr[r]..local_ptr[r + 1]].sort_unstable();
        }
        let (cols, source): (Vec<usize>, Vec<u32>) =
            entries.into_iter().map(|(c, s)| (c as usize, s)).unzip();
        let coordinates = &mesh.coords()[..n_rows];
        let row_equations: Vec<u32> = equations[..n_rows].to_vec();
        let own_free = row_equations.iter().filter(|&&eq| eq != FIXED).count();
        // Counts below 2^53 add exactly in floating point.
        let mut n_free = [own_free as f64];
        processes.sum(&mut n_free)?;
        let n_free = n_free[0] as usize;
        let first_row = d * partition.first[rank];
        let created = if processes.size() > 1 {
            let n = d * partition.rank_of.len();
            KspSystem::new_distributed(n, first_row, &local_ptr, &cols, coordinates, d, options)
        } else {
            KspSystem::new(&local_ptr, &cols, coordinates, d, options)
        };
        let mut system = created.map_err(|e| Error::Invalid {
            field: "petsc.options".into(),
            value: format!("{options:?}"),
            allowed: format!("options PETSc accepts: {e}"),
        })?;
        // The free DOFs of the part's other nodes (its ghosts): their solution comes from
        // the ranks that own them.
        let mut ghost_rows = Vec::new();
        let mut ghost_equations = Vec::new();
        if processes.size() > 1 {
            for (dof, &eq) in equations.iter().enumerate().skip(n_rows) {
                if eq != FIXED {
                    ghost_rows.push(global(dof) as usize);
                    ghost_equations.push(eq);
                }
            }
            system
                .set_ghost_rows(&ghost_rows)
                .map_err(|e| Error::Breakdown(format!("PETSc refused the ghost rows: {e}")))?;
        }
        Ok(PetscSolver {
            csr_values: vec![0.0; source.len()],
            source,
            diagonal: row_equations
                .iter()
                .filter(|&&eq| eq != FIXED)
                .map(|&eq| col_ptr[eq as usize + 1] - 1)
                .collect(),
            n_free,
            row_equations,
            b_local: vec![0.0; n_rows],
            x_local: vec![0.0; n_rows],
            ghost_values: vec![0.0; ghost_equations.len()],
            ghost_equations,
            processes,
            has_matrix: false,
            options: options.to_string(),
            can_keep: system.can_keep_preconditioner(),
            system,
            fresh_rate: 0.0,
            rent: 0.0,
            setup_next: false,
        })
    }

    fn breakdown(&self, what: &str, e: &hemicontact_petsc::Error) -> Error {
        Error::Breakdown(format!(
            "PETSc ({}) {what}: {e}; options {:?}",
            self.system.describe(),
            self.options
        ))
    }
}

impl SpdSolver for PetscSolver {
    fn kind(&self) -> super::LinearSolver {
        super::LinearSolver::Petsc
    }

    /// `petsc (ksp cg, pc gamg)`: the Krylov method and preconditioner in use.
    fn describe(&self) -> String {
        format!("petsc ({})", self.system.describe())
    }

    /// # Errors
    /// [`Error::Breakdown`] when PETSc fails (e.g. a zero pivot in a factorization) or its
    /// KSP does not converge to `request.eta`.
    fn solve(
        &mut self,
        _pattern: &SystemPattern,
        values: &[f64],
        b: &[f64],
        x: &mut [f64],
        request: &SolveRequest,
    ) -> Result<SolveStats> {
        let mut stats = SolveStats::default();
        // Whether the matrix changed, decided on this process's rows (the only complete
        // ones here) and agreed by all.
        let given = self
            .csr_values
            .iter()
            .zip(&self.source)
            .filter(|(_, &s)| s != PRESCRIBED)
            .map(|(&c, &s)| (values[s as usize], c));
        let mut changed = [f64::from(u8::from(
            !self.has_matrix || !matrix_unchanged(given),
        ))];
        self.processes.max(&mut changed)?;
        let unchanged = changed[0] == 0.0;
        let eta = request.eta;
        // Decades of residual reduction asked for (at least one).
        let decades = (1.0 / eta).log10().max(1.0);
        if !unchanged {
            let t = Instant::now();
            let mut sum = [self.diagonal.iter().map(|&s| values[s].abs()).sum::<f64>()];
            self.processes.sum(&mut sum)?;
            let mean = sum[0] / self.n_free.max(1) as f64;
            let prescribed = if mean > 0.0 { mean } else { 1.0 };
            for (v, &s) in self.csr_values.iter_mut().zip(&self.source) {
                *v = if s == PRESCRIBED {
                    prescribed
                } else {
                    values[s as usize]
                };
            }
            self.system
                .set_values(&self.csr_values)
                .map_err(|e| self.breakdown("refused the matrix", &e))?;
            self.has_matrix = true;
            // Copying values is part of the solve; only set-ups count as factorizations.
            stats.solve_time = t.elapsed().as_secs_f64();
        }
        for (bl, &eq) in self.b_local.iter_mut().zip(&self.row_equations) {
            *bl = if eq == FIXED { 0.0 } else { b[eq as usize] };
        }
        let keep = !unchanged
            && self.can_keep
            && request.reuse_iterations > 0
            && !self.setup_next
            && self.fresh_rate > 0.0;
        let mut solved = false;
        if keep {
            let t = Instant::now();
            let expected = self.fresh_rate * decades;
            // What is left of one set-up's cost may be spent before giving up.
            let cap = (expected + SETUP_COST - self.rent).ceil() as usize + 1;
            let outcome = self
                .system
                .solve(&self.b_local, &mut self.x_local, eta, cap, true)
                .map_err(|e| self.breakdown("failed", &e))?;
            stats.solve_time += t.elapsed().as_secs_f64();
            stats.iterations = outcome.iterations;
            if outcome.converged() {
                self.rent += (outcome.iterations as f64 - expected).max(0.0);
                self.setup_next = self.rent >= SETUP_COST;
                solved = true;
            }
        }
        if !solved {
            if !unchanged {
                let t = Instant::now();
                self.system
                    .setup()
                    .map_err(|e| self.breakdown("could not set the preconditioner up", &e))?;
                stats.factorization_time += t.elapsed().as_secs_f64();
                stats.refactorized = true;
                self.rent = 0.0;
                self.setup_next = false;
            }
            let t = Instant::now();
            let outcome = self
                .system
                .solve(
                    &self.b_local,
                    &mut self.x_local,
                    eta,
                    ITERATIVE_MAX_ITERATIONS,
                    true,
                )
                .map_err(|e| self.breakdown("failed", &e))?;
            stats.solve_time += t.elapsed().as_secs_f64();
            stats.iterations += outcome.iterations;
            if !outcome.converged() {
                // The right-hand side's norm over every rank's rows (the KSP stopped on all).
                let mut b_norm = [self.b_local.iter().map(|v| v * v).sum::<f64>()];
                self.processes.sum(&mut b_norm)?;
                return Err(Error::Breakdown(format!(
                    "PETSc ({}) did not reach the relative residual {eta:e}: {} after {} \
                     iterations (residual norm {:e}, right-hand side norm {:e}); options {:?}",
                    self.system.describe(),
                    outcome.reason_name,
                    outcome.iterations,
                    outcome.residual_norm,
                    b_norm[0].sqrt(),
                    self.options
                )));
            }
            if stats.refactorized {
                self.fresh_rate = outcome.iterations.max(1) as f64 / decades;
            }
        }
        // This rank's rows, then (several processes) its ghost rows from their owners;
        // nothing else of the solution is known here.
        if self.processes.size() > 1 {
            self.system
                .ghost_values(&mut self.ghost_values)
                .map_err(|e| self.breakdown("could not fetch the ghost rows", &e))?;
            x.fill(f64::NAN);
            for (&eq, &v) in self.ghost_equations.iter().zip(&self.ghost_values) {
                x[eq as usize] = v;
            }
        }
        for (&eq, &v) in self.row_equations.iter().zip(&self.x_local) {
            if eq != FIXED {
                x[eq as usize] = v;
            }
        }
        Ok(stats)
    }
}
