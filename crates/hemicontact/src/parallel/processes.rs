//! The processes of this run ([`Processes`]): one, or the ranks of an MPI launch, with the
//! few collective operations the program needs; see [`super`].

use crate::error::{Error, Result};

/// The processes of this run; see the module documentation.
///
/// A value, passed explicitly from where a solve starts (the program's
/// [`Processes::launch`], then [`crate::solver::SolverSettings::processes`]): no library
/// code reads it from a global. MPI itself, once initialized, stays a process-wide state of
/// the PETSc bindings (`hemicontact_petsc::World`), which the collectives complete through.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Processes {
    pub(super) rank: usize,
    pub(super) size: usize,
    pub(super) on_machine: usize,
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

impl Default for Processes {
    /// [`Processes::alone`]: a solve whose caller passes no launch runs on this process
    /// alone.
    fn default() -> Self {
        Processes::alone()
    }
}

impl Processes {
    /// The processes of this run: those of the MPI launch that started it
    /// ([`mpi_launch`]; MPI initialized through PETSc), else this process alone. Called
    /// once, first thing, by a program that may run under `mpirun`: the one place a process
    /// learns its rank, which it then passes on (a solve's
    /// [`crate::solver::SolverSettings::processes`]).
    ///
    /// # Errors
    /// [`Error::Invalid`] for an MPI launch of a build without the feature `petsc`;
    /// MPI's errors.
    pub fn launch() -> Result<Processes> {
        let Some((_, size)) = mpi_launch() else {
            return Ok(Self::alone());
        };
        #[cfg(feature = "petsc")]
        {
            let world = hemicontact_petsc::World::get().map_err(|e| {
                Error::Breakdown(format!("MPI could not be initialized through PETSc: {e}"))
            })?;
            let on_machine = world.ranks_on_node().map_err(mpi_error)?;
            let _ = size;
            Ok(Processes {
                rank: world.rank(),
                size: world.size(),
                on_machine,
            })
        }
        #[cfg(not(feature = "petsc"))]
        Err(Error::invalid(
            "processes",
            size,
            "1: this build of hemicontact runs as one process (an MPI launch needs the cargo \
             feature `petsc`, see docs/distributed.md)",
        ))
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
