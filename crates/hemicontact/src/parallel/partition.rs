//! How the nodes are split among the processes ([`Partition`]), where a process's nodes
//! sit in the whole ([`Placement`]), and items grouped by the rank that owns them
//! ([`ByRank`]).

use super::processes::Processes;
#[cfg(feature = "petsc")]
use crate::error::Error;
use crate::error::Result;

/// Range `rank` of `count` items split into `size` contiguous ranges of (almost) equal
/// length, in rank order: `rank · count / size .. (rank + 1) · count / size`.
pub fn contiguous_range(count: usize, rank: usize, size: usize) -> std::ops::Range<usize> {
    rank * count / size..(rank + 1) * count / size
}

/// How the nodes are split among the processes: each node's rank, and the *distributed
/// numbering* of the nodes (rank 0's nodes in increasing order, then rank 1's, …), in
/// which every rank's nodes, and the rows of their DOFs in PETSc's matrix, are contiguous.
/// On one process, the identity.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Partition {
    /// The rank of every node.
    pub rank_of: Vec<u32>,
    /// The nodes in the distributed numbering.
    pub order: Vec<u32>,
    /// The position of every node in [`Partition::order`].
    pub position: Vec<u32>,
    /// Rank r's nodes are `order[first[r]..first[r + 1]]`.
    pub first: Vec<usize>,
}

impl Partition {
    /// The partition giving node `v` to `rank_of[v]`, of `size` ranks.
    ///
    /// # Panics
    /// If a rank is `size` or more.
    pub fn from_ranks(rank_of: Vec<u32>, size: usize) -> Partition {
        let mut first = vec![0usize; size + 1];
        for &r in &rank_of {
            first[r as usize + 1] += 1;
        }
        for r in 0..size {
            first[r + 1] += first[r];
        }
        let mut next = first.clone();
        let mut order = vec![0u32; rank_of.len()];
        let mut position = vec![0u32; rank_of.len()];
        for (v, &r) in rank_of.iter().enumerate() {
            let p = next[r as usize];
            next[r as usize] += 1;
            order[p] = v as u32;
            position[v] = p as u32;
        }
        Partition {
            rank_of,
            order,
            position,
            first,
        }
    }

    /// Contiguous ranges of node numbers ([`contiguous_range`]) for `size` ranks.
    pub fn ranges(nodes: usize, size: usize) -> Partition {
        let rank_of = (0..size)
            .flat_map(|r| contiguous_range(nodes, r, size).map(move |_| r as u32))
            .collect();
        Partition::from_ranks(rank_of, size)
    }

    /// The partition of `mesh` for the processes of the run: on several processes, the
    /// parts of its node graph by Scotch (balanced, with few cells on their borders),
    /// computed on rank 0 and sent to the others; on one process, the identity.
    ///
    /// # Errors
    /// Scotch's and MPI's.
    pub fn of(mesh: &crate::mesh::Mesh, processes: &Processes) -> Result<Partition> {
        let size = processes.size();
        if size == 1 {
            return Ok(Partition::ranges(mesh.n_nodes(), 1));
        }
        #[cfg(feature = "petsc")]
        {
            let n = mesh.n_nodes();
            let mine: Vec<f64> = if processes.is_root() {
                let (ptr, adj) = mesh.node_adjacency();
                let adj: Vec<usize> = adj.iter().map(|&w| w as usize).collect();
                hemicontact_petsc::partition(&ptr, &adj, size)
                    .map_err(|e| Error::Breakdown(format!("the mesh partition: {e}")))?
                    .into_iter()
                    .map(|r| r as f64)
                    .collect()
            } else {
                Vec::new()
            };
            let rank_of = processes.all_gather(&mine, n)?;
            Ok(Partition::from_ranks(
                rank_of.iter().map(|&r| r as u32).collect(),
                size,
            ))
        }
        #[cfg(not(feature = "petsc"))]
        Ok(Partition::ranges(mesh.n_nodes(), size))
    }

    /// Rank `rank`'s nodes, in increasing order.
    pub fn nodes(&self, rank: usize) -> &[u32] {
        &self.order[self.first[rank]..self.first[rank + 1]]
    }

    /// The number of ranks.
    pub fn size(&self) -> usize {
        self.first.len() - 1
    }

    /// The rank that owns cell `cell` of `mesh`: the rank of its lowest-numbered node
    /// (see [`Subdomain`](super::Subdomain)).
    pub fn owner(&self, mesh: &crate::mesh::Mesh, cell: usize) -> usize {
        let lowest = mesh.cell(cell).iter().min().copied().unwrap_or(0);
        self.rank_of[lowest as usize] as usize
    }

    /// The cells every rank owns ([`Partition::owner`]), each list in increasing order:
    /// every cell in exactly one.
    pub fn owned_cells(&self, mesh: &crate::mesh::Mesh) -> Vec<Vec<u32>> {
        let mut cells = vec![Vec::new(); self.size()];
        for c in 0..mesh.n_cells() {
            cells[self.owner(mesh, c)].push(c as u32);
        }
        cells
    }
}

/// Where the nodes of the mesh a process holds sit in the whole: what the distributed
/// linear solver needs to number its rows. On one process the mesh is the whole mesh; on
/// several it is the process's part ([`Subdomain::local_mesh`](super::Subdomain::local_mesh)), its own nodes first, in
/// increasing order, so that its first `d ·` (own nodes) DOFs are its rows.
#[derive(Clone, Copy, Debug)]
pub struct Placement<'a> {
    /// How the whole mesh's nodes are split among the processes.
    pub partition: &'a Partition,
    /// The whole mesh's number of every node of the part, its own first (`None`: the whole
    /// mesh, which this process solves alone).
    pub nodes: Option<&'a [u32]>,
}

/// Items (contact points, say) grouped by the rank that owns them, each group in increasing
/// order: compressed rows, those of rank `r` being `items[first[r]..first[r + 1]]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ByRank {
    /// Where each rank's items start in [`ByRank::items`] (length: ranks + 1).
    pub first: Vec<usize>,
    /// The items' indices, rank after rank.
    pub items: Vec<u32>,
}

impl ByRank {
    /// Items `0, 1, …` owned by the ranks `rank_of` yields (each below `size`), grouped.
    pub fn group(rank_of: impl Iterator<Item = usize> + Clone, size: usize) -> ByRank {
        let mut first = vec![0usize; size + 1];
        for r in rank_of.clone() {
            first[r + 1] += 1;
        }
        for r in 0..size {
            first[r + 1] += first[r];
        }
        let mut next = first.clone();
        let mut items = vec![0u32; first[size]];
        for (i, r) in rank_of.enumerate() {
            items[next[r]] = i as u32;
            next[r] += 1;
        }
        ByRank { first, items }
    }

    /// The items of rank `rank`, in increasing order.
    pub fn of(&self, rank: usize) -> &[u32] {
        &self.items[self.first[rank]..self.first[rank + 1]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The distributed numbering lists every rank's nodes in increasing order, rank after
    /// rank, and `position` inverts it; contiguous ranges are the identity.
    #[test]
    fn a_partition_numbers_the_nodes_rank_by_rank() {
        let p = Partition::from_ranks(vec![1, 0, 2, 1, 0, 2, 2], 3);
        assert_eq!(p.order, [1, 4, 0, 3, 2, 5, 6]);
        assert_eq!(p.first, [0, 2, 4, 7]);
        assert_eq!(p.nodes(1), [0, 3]);
        for (k, &v) in p.order.iter().enumerate() {
            assert_eq!(p.position[v as usize] as usize, k);
        }
        let by = ByRank::group([2usize, 0, 2, 1, 0].into_iter(), 3);
        assert_eq!(by.of(0), [1, 4]);
        assert_eq!(by.of(1), [3]);
        assert_eq!(by.of(2), [0, 2]);
        let r = Partition::ranges(10, 3);
        assert_eq!(r.order, (0..10).collect::<Vec<u32>>());
        assert_eq!(r.first, [0, 3, 6, 10]);
        assert_eq!(r.rank_of, [0, 0, 0, 1, 1, 1, 2, 2, 2, 2]);
    }
}
