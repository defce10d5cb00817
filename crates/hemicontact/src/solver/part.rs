//! What one process of several holds of the system: its part of the mesh (the cells around
//! its own nodes, [`crate::parallel::Subdomain`]), renumbered with its own nodes first, the
//! DOF map of those nodes, and the slots of its contact points' Hessian blocks. It assembles
//! the bulk on that part alone, so that its pattern and Newton matrix hold its own rows and
//! nothing of the rest of the mesh.

use crate::assembly::contact::{node_block_slots, ContactAssembler, ContactData};
use crate::assembly::global::{IdealLocking, Want, Workspace};
use crate::assembly::{BulkAssembler, SystemPattern};
use crate::contact::ContactNodes;
use crate::error::Result;
use crate::fem::dofs::DofMap;
use crate::material::Material;
use crate::mesh::Mesh;
use crate::parallel::{ByRank, Processes, Subdomain};

/// This process's part of a distributed system; see the module documentation.
#[derive(Debug)]
pub(super) struct Part {
    /// Its subdomain of the whole mesh: the partition, its cells (whole numbering, owned
    /// first) and how many it owns.
    pub sub: Subdomain,
    /// Its part of the mesh: the subdomain's cells over its nodes, own nodes first.
    pub mesh: Mesh,
    /// The whole mesh's number of every node of [`Part::mesh`].
    pub nodes: Vec<u32>,
    /// The DOF map of [`Part::mesh`]: its DOFs prescribed as in the whole problem.
    pub dofs: DofMap,
    /// The contact points of every process: those on its nodes.
    pub points: ByRank,
    /// The Hessian slots (in the part's pattern) of this process's contact points, 6 per
    /// point, in the order of `points.of(rank)`.
    pub point_slots: Vec<u32>,
    /// The displacements of the part's nodes at the evaluation (work array).
    pub u: Vec<f64>,
    /// The part's bulk gradient (work array; exact at its own nodes).
    pub grad: Vec<f64>,
    /// The ideal-locking multipliers of the part's cells (work array).
    pub multipliers: Vec<f64>,
}

impl Part {
    /// The part `sub` of `mesh`, whose whole DOF map is `dofs` and contact points
    /// `contact`.
    ///
    /// # Errors
    /// As [`Subdomain::local_mesh`].
    pub fn new(mesh: &Mesh, sub: Subdomain, dofs: &DofMap, contact: &ContactNodes) -> Result<Part> {
        let (local, nodes) = sub.local_mesh(mesh)?;
        let part_dofs = dofs.restricted(&nodes);
        let partition = &sub.partition;
        let points = ByRank::group(
            contact
                .node
                .iter()
                .map(|&v| partition.rank_of[v as usize] as usize),
            partition.size(),
        );
        let n = part_dofs.n_dofs();
        Ok(Part {
            mesh: local,
            nodes,
            dofs: part_dofs,
            points,
            point_slots: Vec::new(),
            u: vec![0.0; n],
            grad: vec![0.0; n],
            multipliers: Vec::new(),
            sub,
        })
    }

    /// The number in [`Part::mesh`] of the whole mesh's node `v`, one of this process's own.
    pub fn own_node(&self, v: u32) -> usize {
        let p = &self.sub.partition;
        p.position[v as usize] as usize - p.first[self.sub.rank]
    }

    /// Sets [`Part::point_slots`] for the part's pattern `pattern`.
    pub fn set_point_slots(&mut self, contact: &ContactNodes, pattern: &SystemPattern) {
        let own: Vec<u32> = self
            .points
            .of(self.sub.rank)
            .iter()
            .map(|&i| self.own_node(contact.node[i as usize]) as u32)
            .collect();
        self.point_slots = node_block_slots(&own, self.mesh.dim(), self.dofs.equations(), pattern);
    }

    /// The entries of the upper triangle of the whole reduced system, from this process's
    /// rows of `pattern` (the part's): every free row's entries in both triangles, summed
    /// over the processes, give twice the upper triangle less the diagonal.
    ///
    /// # Errors
    /// MPI's.
    pub fn whole_nnz(&self, pattern: &SystemPattern, whole: &DofMap) -> Result<usize> {
        let own_eqs = self.dofs.equations()[..self.dofs.dim() * self.sub.nodes().len()]
            .iter()
            .filter(|&&eq| eq != crate::fem::dofs::FIXED)
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
        crate::parallel::Processes::current().sum(&mut total)?;
        Ok((total[0] as usize + whole.n_free()) / 2)
    }

    /// The bulk energy of the part's owned cells at the whole mesh's displacement `u`, for
    /// `material` with the ideal-locking term `ideal` of the whole mesh's cells (J): the
    /// part's gradient goes to [`Part::grad`] (exact at its own nodes) and with
    /// [`Want::Hessian`] its Hessian to `hess`, on the part's pattern `pattern`
    /// ([`BulkAssembler::assemble_parallel`]).
    #[allow(clippy::too_many_arguments)]
    pub fn assemble_bulk(
        &mut self,
        material: &Material,
        ideal: Option<IdealLocking<'_>>,
        u: &[f64],
        want: Want,
        pattern: &SystemPattern,
        hess: Option<&mut [f64]>,
        workspace: &mut Workspace,
    ) -> f64 {
        let d = self.mesh.dim();
        for (l, &v) in self.nodes.iter().enumerate() {
            let v = v as usize;
            self.u[d * l..d * l + d].copy_from_slice(&u[d * v..d * v + d]);
        }
        self.multipliers.clear();
        if let Some(whole) = &ideal {
            let cells = self.sub.cells.iter();
            self.multipliers
                .extend(cells.map(|&c| whole.multipliers[c as usize]));
        }
        let bulk = BulkAssembler {
            mesh: &self.mesh,
            material,
            ideal: ideal.map(|whole| IdealLocking {
                set: whole.set,
                r: whole.r,
                multipliers: &self.multipliers,
            }),
        };
        bulk.assemble_parallel(&self.u, &mut self.grad, want, pattern, hess, workspace)
    }

    /// Completes an evaluation with the other processes: the terms of this process's
    /// contact points (`contact`, for the frozen quantities `frozen`, at the whole mesh's
    /// displacement `u`; their node blocks of the Hessian added to `hess`) added to its own
    /// nodes' entries of the gradient `grad` (DOF order), which also gets its own nodes'
    /// bulk gradient minus the external forces `f_ext`, as `grad_bulk` does; the other
    /// entries of both are NaN here (a ghost node's are partial, the rest unknown), never
    /// read. Returns the bulk energy (from this process's `e_bulk`), the contact energy and
    /// the work of the external forces `f_ext · u` of the whole (J), summed over the
    /// processes ([`Processes::sum`], the one exchange of an evaluation).
    ///
    /// # Errors
    /// MPI's.
    #[allow(clippy::too_many_arguments)]
    pub fn complete(
        &mut self,
        processes: &Processes,
        contact: &ContactAssembler<'_>,
        frozen: &ContactData<'_>,
        u: &[f64],
        e_bulk: f64,
        mut hess: Option<&mut [f64]>,
        f_ext: &[f64],
        grad_bulk: &mut [f64],
        grad: &mut [f64],
    ) -> Result<[f64; 3]> {
        let d = self.mesh.dim();
        let rank = self.sub.rank;
        grad_bulk.fill(f64::NAN);
        grad.fill(f64::NAN);
        // Its own nodes, the first of its part: their bulk gradient is complete here.
        let own = self.sub.nodes().len();
        let mut work = 0.0;
        for (l, &v) in self.nodes[..own].iter().enumerate() {
            for k in 0..d {
                let dof = d * v as usize + k;
                let g = self.grad[d * l + k] - f_ext[dof];
                grad_bulk[dof] = g;
                grad[dof] = g;
                work += f_ext[dof] * u[dof];
            }
        }
        // Its contact points (on its own nodes), added point by point in their order as on
        // one process; their node blocks of the Hessian go to its rows.
        let mut e_contact = 0.0;
        for (j, &i) in self.points.of(rank).iter().enumerate() {
            let term = contact.point(u, frozen, i as usize);
            e_contact += term.energy;
            let v = contact.nodes.node[i as usize] as usize;
            for k in 0..d {
                grad[d * v + k] += term.gradient[k];
            }
            if let Some(h) = hess.as_deref_mut() {
                let slots = &self.point_slots[6 * j..6 * j + 6];
                ContactAssembler::add_block(d, &term, slots, h);
            }
        }
        let mut e = [e_bulk, e_contact, work];
        processes.sum(&mut e)?;
        Ok(e)
    }
}
