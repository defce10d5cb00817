//! What one process of several holds of the system: its part of the mesh (the cells around
//! its own nodes, [`crate::parallel::Subdomain`]), renumbered with its own nodes first, the
//! DOF map of those nodes, and the slots of its contact points' Hessian blocks. It assembles
//! the bulk on that part alone, so that its pattern and Newton matrix hold its own rows and
//! nothing of the rest of the mesh.

use crate::assembly::contact::node_block_slots;
use crate::assembly::SystemPattern;
use crate::contact::ContactNodes;
use crate::error::Result;
use crate::fem::dofs::DofMap;
use crate::mesh::Mesh;
use crate::parallel::{ByRank, Subdomain};

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
    /// This process's share of an evaluation: its own nodes' bulk gradient, then its
    /// contact points' gradient (work array).
    pub mine: Vec<f64>,
    /// Every process's share, rank after rank (work array).
    pub all: Vec<f64>,
    /// The contact gradient of every point (work array; N, `d` entries per point).
    pub point_grad: Vec<f64>,
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
            mine: Vec::new(),
            all: Vec::new(),
            point_grad: Vec::new(),
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
}
