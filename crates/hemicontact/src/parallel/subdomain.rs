//! What one rank assembles and holds when the run is several processes ([`Subdomain`]):
//! its own nodes, the cells around them, its part of the mesh and its contact points.

use super::partition::Partition;
use crate::error::Result;

/// What one rank assembles when the run is several processes: the nodes it owns (its part
/// of a [`Partition`]), whose rows of the Newton matrix and entries of the gradient it
/// computes exactly, and the cells around them. A cell is *owned* by the rank of its
/// lowest-numbered node, which alone counts its energy; the other cells with a node of the
/// rank are its *ghost* layer, assembled again so that the rows of its nodes are complete
/// without sending matrix entries between processes. No rank needs another's partial
/// sums, so the result does not depend on the order in which messages arrive.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Subdomain {
    /// This rank.
    pub rank: usize,
    /// The partition of the nodes among the ranks.
    pub partition: Partition,
    /// The cells this rank assembles: its owned cells, then its ghost cells, each in
    /// increasing order.
    pub cells: Vec<u32>,
    /// How many of [`Subdomain::cells`] are owned (their energy is counted here).
    pub owned: usize,
}

impl Subdomain {
    /// Rank `rank`'s subdomain of `mesh` in `partition`: the cells around its nodes,
    /// owned first.
    pub fn new(mesh: &crate::mesh::Mesh, partition: Partition, rank: usize) -> Subdomain {
        let inside = |v: &u32| partition.rank_of[*v as usize] as usize == rank;
        let mut owned = Vec::new();
        let mut ghosts = Vec::new();
        for c in 0..mesh.n_cells() {
            if partition.owner(mesh, c) == rank {
                owned.push(c as u32);
            } else if mesh.cell(c).iter().any(inside) {
                ghosts.push(c as u32);
            }
        }
        let n_owned = owned.len();
        owned.extend(ghosts);
        Subdomain {
            rank,
            partition,
            cells: owned,
            owned: n_owned,
        }
    }

    /// The nodes this rank owns, in increasing order.
    pub fn nodes(&self) -> &[u32] {
        self.partition.nodes(self.rank)
    }

    /// The nodes this rank holds: its own ([`Subdomain::nodes`]), then the other nodes of
    /// its cells and the nodes its own ones are coupled to outside the cells (the slave
    /// node or the master facet's nodes of a contact pair, [`crate::mesh::Mesh::couplings`]):
    /// its *ghost* nodes, each in increasing order. In that order they number the nodes of
    /// its part of the mesh ([`Subdomain::local_mesh`]); every column of its own rows is
    /// among them.
    pub fn local_nodes(&self, mesh: &crate::mesh::Mesh) -> Vec<u32> {
        let mut nodes = self.nodes().to_vec();
        let mut seen = vec![false; mesh.n_nodes()];
        for &v in &nodes {
            seen[v as usize] = true;
        }
        let mut ghosts = Vec::new();
        for &c in &self.cells {
            for &v in mesh.cell(c as usize) {
                if !seen[v as usize] {
                    seen[v as usize] = true;
                    ghosts.push(v);
                }
            }
        }
        let own = |v: u32| self.partition.rank_of[v as usize] as usize == self.rank;
        for &[a, b] in mesh.couplings() {
            for (x, y) in [(a, b), (b, a)] {
                if own(x) && !seen[y as usize] {
                    seen[y as usize] = true;
                    ghosts.push(y);
                }
            }
        }
        ghosts.sort_unstable();
        nodes.extend(ghosts);
        nodes
    }

    /// The contact points this rank holds, by their numbers among `contact` (the whole
    /// problem's, in dimension `dim`): its own (those of its own nodes), then its *ghost*
    /// points (of contact pairs whose slave node is another rank's but whose master facet
    /// has a node of its own), each in increasing order; and the number of its own. A
    /// ghost point is assembled again here so that the rows of its master nodes are
    /// complete, as a ghost cell is; its other nodes are ghost nodes of the part when the
    /// mesh carries the pairs' couplings ([`Subdomain::local_nodes`]).
    pub fn contact_points(
        &self,
        contact: &crate::contact::ContactNodes,
        dim: usize,
    ) -> (Vec<u32>, usize) {
        let own = |v: u32| self.partition.rank_of[v as usize] as usize == self.rank;
        let all = 0..contact.len() as u32;
        let mut points: Vec<u32> = all
            .clone()
            .filter(|&i| own(contact.node[i as usize]))
            .collect();
        let n_own = points.len();
        points.extend(all.filter(|&i| {
            let (n, stencil, _) = contact.stencil(dim, i as usize);
            !own(stencil[0]) && stencil[1..n].iter().any(|&v| own(v))
        }));
        (points, n_own)
    }

    /// This rank's part of `mesh`: its cells ([`Subdomain::cells`], owned first) over its
    /// nodes ([`Subdomain::local_nodes`], own first), renumbered, with the boundary facets
    /// of those cells; and the local nodes' numbers in `mesh`.
    ///
    /// # Errors
    /// As [`crate::mesh::Mesh`]'s restriction (a subdomain of another mesh).
    pub fn local_mesh(&self, mesh: &crate::mesh::Mesh) -> Result<(crate::mesh::Mesh, Vec<u32>)> {
        let nodes = self.local_nodes(mesh);
        Ok((mesh.restricted(&self.cells, &nodes)?, nodes))
    }

    /// Whether DOF `dof` (of `dim` per node) is one of this rank's.
    pub fn owns_dof(&self, dof: usize, dim: usize) -> bool {
        self.partition.rank_of[dof / dim] as usize == self.rank
    }
}
