//! The output folder of one run, staged as one result set
//! ([`hemicontact::io::result_set`]) and shared with the Ctrl-C handler.
//!
//! Every write and the commit happen under one lock, so the handler sees the set either
//! being written (and discards it: the folder keeps its previous content) or in place.

use anyhow::Result;
use hemicontact::io::result_set::ResultSet;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

/// Exit code of a run interrupted by Ctrl-C (128 + SIGINT, the shell convention).
const INTERRUPTED: i32 = 130;

/// State of this run's output folder.
enum State {
    /// No result set begun.
    None,
    /// A result set is being written into its staging folder.
    Writing(ResultSet),
    /// The result set is in place in this folder.
    Done(PathBuf),
}

/// This run's output: a handle shared (by cloning) between the commands and the Ctrl-C
/// handler, and whether this process writes (rank 0 of an MPI launch writes; the other
/// ranks compute the same results and write nothing).
#[derive(Clone)]
pub struct Output(Arc<Mutex<State>>, bool);

impl Output {
    /// No result set begun yet; `writes`: whether this process writes results.
    pub fn new(writes: bool) -> Self {
        Output(Arc::new(Mutex::new(State::None)), writes)
    }

    /// Whether this process writes results (rank 0, or the only process).
    pub fn writes(&self) -> bool {
        self.1
    }

    fn state(&self) -> MutexGuard<'_, State> {
        self.0.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Starts this run's result set for the folder `dir` (failing before any solve if
    /// another run writes there or the folder cannot be written). Nothing in `dir` changes
    /// until [`Output::commit`]; see [`hemicontact::io::result_set`].
    pub fn begin(&self, dir: &Path) -> Result<()> {
        if !self.1 {
            return Ok(());
        }
        let set = ResultSet::begin(dir)?;
        *self.state() = State::Writing(set);
        Ok(())
    }

    /// Runs `f` on this run's result set (begun by [`Output::begin`]); in a process that
    /// does not write, nothing (`T::default()`).
    pub fn with<T: Default>(&self, f: impl FnOnce(&mut ResultSet) -> Result<T>) -> Result<T> {
        if !self.1 {
            return Ok(T::default());
        }
        match &mut *self.state() {
            State::Writing(set) => f(set),
            _ => anyhow::bail!("internal error: no result set is being written"),
        }
    }

    /// Puts this run's result set in place as a unit. Returns the final paths of its files.
    pub fn commit(&self) -> Result<Vec<PathBuf>> {
        if !self.1 {
            return Ok(Vec::new());
        }
        let mut state = self.state();
        match std::mem::replace(&mut *state, State::None) {
            State::Writing(set) => {
                let dir = set.target().to_path_buf();
                let files = set.commit()?;
                *state = State::Done(dir);
                Ok(files)
            }
            other => {
                *state = other;
                anyhow::bail!("internal error: no result set is being written")
            }
        }
    }

    /// Discards this run's result set if it was not committed (after an error): the output
    /// folder keeps its previous content.
    pub fn discard(&self) {
        let mut state = self.state();
        if matches!(*state, State::Writing(_)) {
            *state = State::None;
        }
    }

    /// Installs the Ctrl-C handler of this run. On Ctrl-C it waits for a write or commit in
    /// progress to finish, discards a result set not yet in place (its staging folder and
    /// lock are removed, the output folder keeps its previous content), says which of the
    /// two happened, and exits with 130.
    ///
    /// The handler owns a clone of this handle: the state it needs lives in the run's
    /// `Output`, not in a process-global variable.
    pub fn install_interrupt_handler(&self) {
        let output = self.clone();
        let _ = ctrlc::set_handler(move || {
            // Held until exit: no file is written after this point.
            let mut state = output.state();
            let message = match std::mem::replace(&mut *state, State::None) {
                State::None => "interrupted before any result was written".to_string(),
                State::Writing(set) => {
                    let dir = set.target().display().to_string();
                    drop(set);
                    format!(
                        "interrupted: {dir} was left as it was (its previous results, if any, \
                         are intact); the unfinished new results were discarded"
                    )
                }
                State::Done(dir) => format!(
                    "interrupted after the results were complete: {} holds the new results",
                    dir.display()
                ),
            };
            // One message per run: an MPI launch's other ranks exit silently.
            if output.1 {
                eprintln!("{message}");
            }
            std::process::exit(INTERRUPTED);
        });
    }
}
