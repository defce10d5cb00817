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

mod partition;
mod processes;
pub mod share;
mod subdomain;

pub use partition::{contiguous_range, ByRank, Partition, Placement};
pub use processes::{mpi_launch, Processes};
pub use share::Share;
pub use subdomain::Subdomain;
