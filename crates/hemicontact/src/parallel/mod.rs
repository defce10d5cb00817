//! The processes a run is made of: one, or the ranks of an MPI launch (`mpirun -np N`,
//! with the cargo feature `petsc`, whose PETSc brings the MPI).
//!
//! [`Processes`] is the one seam through which the rest of the program learns its rank and
//! the number of processes, and the few collective operations it needs. Its one-process
//! form is trivial (rank 0 of 1, every reduction the identity), so a run without MPI pays
//! nothing for it. With several processes each rank owns a part of the nodes
//! ([`Partition`]: Scotch's parts of the node graph) and solves on the cells around them
//! (its [`Subdomain`]) as a mesh of its own ([`Subdomain::local_mesh`]: its own nodes
//! first, then the ghost nodes of those cells): every array of the solve is that part's.
//! It hands PETSc's distributed matrix the rows of its own nodes ([`Placement`]). An
//! evaluation computes the gradient of its own nodes and the terms of its own contact
//! points, and sums the energies over the ranks; a Newton step's solution is known at its
//! own rows and fetched at its ghost rows from their owners (a PETSc scatter). Each sum,
//! norm and maximum the solver decides on counts every entry on one rank only and is
//! completed over the ranks ([`Share`]), so every rank takes the same decisions. The whole
//! problem is still read by every rank and put together from the parts once, for the
//! answer.

pub mod share;

pub use share::Share;

use crate::error::{Error, Result};
use std::sync::OnceLock;

/// The rank and size of this process's MPI world and the number of its processes on this
/// machine, once it was started by [`Processes::launch`].
static WORLD: OnceLock<(usize, usize, usize)> = OnceLock::new();

/// The processes of this run; see the module documentation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Processes {
    rank: usize,
    size: usize,
    on_machine: usize,
}

/// The rank and size of an MPI launch with more than one process, from the variables that
/// OpenMPI (`OMPI_COMM_WORLD_RANK`, `OMPI_COMM_WORLD_SIZE`) and MPICH's launcher
/// (`PMI_RANK`, `PMI_SIZE`) set for each process; `None` for a single process.
pub fn mpi_launch() -> Option<(usize, usize)> {
    let var = |name: &str| std::env::var(name).ok()?.trim().parse::<usize>().ok();
    [
        ("OMPI_COMM_WORLD_RANK", "OMPI_COMM_WORLD_SIZE"),
        ("PMI_RANK", "PMI_SIZE"),
    ]
    .iter()
    .find_map(|&(rank, size)| Some((var(rank).unwrap_or(0), var(size)?)))
    .filter(|&(_, size)| size > 1)
}

impl Processes {
    /// The processes of this run: those of the MPI launch that started it
    /// ([`mpi_launch`]; MPI initialized through PETSc), else this process alone. Called
    /// once, first thing, by a program that may run under `mpirun`.
    ///
    /// # Errors
    /// [`Error::Invalid`] for an MPI launch of a build without the feature `petsc`;
    /// MPI's errors.
    pub fn launch() -> Result<Processes> {
        let Some((_, size)) = mpi_launch() else {
            return Ok(Self::current());
        };
        #[cfg(feature = "petsc")]
        {
            let world = hemicontact_petsc::World::get().map_err(|e| {
                Error::Breakdown(format!("MPI could not be initialized through PETSc: {e}"))
            })?;
            let on_machine = world.ranks_on_node().map_err(mpi_error)?;
            let _ = WORLD.set((world.rank(), world.size(), on_machine));
            let _ = size;
            Ok(Self::current())
        }
        #[cfg(not(feature = "petsc"))]
        Err(Error::invalid(
            "processes",
            size,
            "1: this build of hemicontact runs as one process (an MPI launch needs the cargo \
             feature `petsc`, see docs/distributed.md)",
        ))
    }

    /// The processes as launched (rank 0 of 1 before or without [`Processes::launch`]).
    pub fn current() -> Processes {
        let (rank, size, on_machine) = WORLD.get().copied().unwrap_or((0, 1, 1));
        Processes {
            rank,
            size,
            on_machine,
        }
    }

    /// This process alone (rank 0 of 1), whatever the launch: for work that one process does
    /// on its own, every collective then the identity.
    pub fn alone() -> Processes {
        Processes {
            rank: 0,
            size: 1,
            on_machine: 1,
        }
    }

    /// This process's rank, 0 to `size − 1`.
    pub fn rank(&self) -> usize {
        self.rank
    }

    /// Number of processes.
    pub fn size(&self) -> usize {
        self.size
    }

    /// The number of processes on this process's machine, this one included (those that
    /// share its memory; 1 on one process).
    pub fn on_this_machine(&self) -> usize {
        self.on_machine
    }

    /// Whether this is rank 0, the one that prints and writes the results.
    pub fn is_root(&self) -> bool {
        self.rank == 0
    }

    /// `values` ← their element-wise sum over the processes (collective; the identity on
    /// one process). The partial values are gathered and added in rank order on every
    /// process, so that the sum is the same to the last bit on every rank and in every run
    /// on the same number of processes (an MPI reduction guarantees neither). For a few
    /// values: it moves `size × values.len()` numbers.
    ///
    /// # Errors
    /// MPI's.
    pub fn sum(&self, values: &mut [f64]) -> Result<()> {
        if self.size == 1 {
            return Ok(());
        }
        let m = values.len();
        let all = self.all_gather(values, m * self.size)?;
        values.fill(0.0);
        for part in all.chunks_exact(m.max(1)) {
            for (v, p) in values.iter_mut().zip(part) {
                *v += p;
            }
        }
        Ok(())
    }

    /// `values` ← their element-wise maximum over the processes (collective; the identity
    /// on one process).
    ///
    /// # Errors
    /// MPI's.
    pub fn max(&self, values: &mut [f64]) -> Result<()> {
        if self.size == 1 {
            return Ok(());
        }
        #[cfg(feature = "petsc")]
        {
            let world = hemicontact_petsc::World::get().map_err(mpi_error)?;
            world.max(values).map_err(mpi_error)
        }
        #[cfg(not(feature = "petsc"))]
        {
            let _ = values;
            Err(self.without_mpi())
        }
    }

    /// The concatenation of every rank's `local` values in rank order, on every rank
    /// (collective; a copy on one process). `total` is the sum of the local lengths.
    ///
    /// # Errors
    /// MPI's.
    pub fn all_gather(&self, local: &[f64], total: usize) -> Result<Vec<f64>> {
        let mut global = vec![0.0; total];
        self.all_gather_into(local, &mut global)?;
        Ok(global)
    }

    /// As [`Processes::all_gather`], into `global`, whose length is the sum of the local
    /// lengths (no allocation: for the gathers of every evaluation).
    ///
    /// # Errors
    /// MPI's; a `global` of another length.
    pub fn all_gather_into(&self, local: &[f64], global: &mut [f64]) -> Result<()> {
        if self.size == 1 {
            if global.len() != local.len() {
                return Err(crate::Error::Breakdown(format!(
                    "gather of {} values into {}",
                    local.len(),
                    global.len()
                )));
            }
            global.copy_from_slice(local);
            return Ok(());
        }
        #[cfg(feature = "petsc")]
        {
            let world = hemicontact_petsc::World::get().map_err(mpi_error)?;
            world.all_gather_into(local, global).map_err(mpi_error)
        }
        #[cfg(not(feature = "petsc"))]
        {
            let _ = local;
            Err(self.without_mpi())
        }
    }

    /// The error of a collective operation over several processes in a build without MPI
    /// (no cargo feature `petsc`), which has nothing to complete it with: such processes
    /// exist only where this crate makes them itself.
    #[cfg(not(feature = "petsc"))]
    fn without_mpi(&self) -> Error {
        Error::Breakdown(format!(
            "a collective operation over {} processes in a build without MPI (the cargo \
             feature `petsc`, see docs/distributed.md)",
            self.size
        ))
    }

    /// Ends every process with exit code `code`: the way out of a failure that only some
    /// ranks may see, which would leave the others waiting in a collective operation. On
    /// one process, `std::process::exit`.
    pub fn abort(&self, code: i32) -> ! {
        #[cfg(feature = "petsc")]
        if self.size > 1 {
            if let Ok(world) = hemicontact_petsc::World::get() {
                world.abort(code);
            }
        }
        std::process::exit(code)
    }
}

#[cfg(feature = "petsc")]
fn mpi_error(e: hemicontact_petsc::Error) -> Error {
    Error::Breakdown(format!("MPI: {e}"))
}

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
    /// (see [`Subdomain`]).
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
/// several it is the process's part ([`Subdomain::local_mesh`]), its own nodes first, in
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
