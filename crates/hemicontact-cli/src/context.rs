//! What the commands of one run share ([`RunContext`]) and what a command that solved
//! something returns ([`Outcome`]).

use crate::console::Console;
use crate::output;
use anyhow::Result;
use hemicontact::scenario::Scenario;
use std::path::Path;

/// Outcome of a command that solved something.
pub enum Outcome {
    /// Every solve converged (exit code 0).
    Done,
    /// Some solve did not converge; its results were written all the same (exit code 3).
    NotConverged,
}

/// What the commands of one run share: the global flags and the run's output folder.
/// Passed explicitly to every command (no process-global state).
pub struct RunContext {
    /// Set from `--ignore-memory-limit`: drop the scenario's memory limit.
    pub ignore_memory_limit: bool,
    /// This run's result set, shared with the Ctrl-C handler.
    pub output: output::Output,
    /// What the run prints, from `--quiet` and `-v`.
    pub console: Console,
    /// The processes of this run ([`hemicontact::parallel::Processes::launch`]), which
    /// every scenario it reads is solved on.
    pub processes: hemicontact::parallel::Processes,
}

impl RunContext {
    /// `s` on this run's processes, honouring `--ignore-memory-limit`.
    fn apply_memory_flag(&self, s: Scenario) -> Scenario {
        let mut s = s.on(self.processes);
        if self.ignore_memory_limit {
            s.memory_limit = None;
        }
        s
    }

    /// Reads a scenario file, honouring `--ignore-memory-limit`.
    pub fn read_scenario(&self, file: &Path) -> Result<Scenario> {
        Ok(self.apply_memory_flag(Scenario::from_file(file)?))
    }

    /// Parses scenario text, honouring `--ignore-memory-limit`.
    pub fn parse_scenario(&self, text: &str, source: &str) -> Result<Scenario> {
        Ok(self.apply_memory_flag(Scenario::from_str(text, source)?))
    }
}
