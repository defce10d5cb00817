//! What a run prints, and where: results on standard output; notes, warnings, phase lines
//! and progress on standard error.
//!
//! - On a terminal (standard error is a tty), a long phase shows a live progress line
//!   (indicatif): the outer iteration, its residual, the Newton steps so far and the
//!   elapsed time.
//! - Off a terminal (a log file, a pipe, CI), one line per phase instead: what is being
//!   solved, how it ended, where the results went.
//! - `-v` adds one line per outer iteration, on a terminal or not; `--quiet` prints nothing
//!   but errors (the exit code still tells a solve that did not converge).

use hemicontact::display::significant;
use hemicontact::solver::OuterProgress;
use indicatif::{ProgressBar, ProgressStyle};
use std::cell::Cell;
use std::fmt;
use std::io::{IsTerminal, Write as _};
use std::time::{Duration, Instant};

/// How much a run prints.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Verbosity {
    /// Errors only (`--quiet`).
    Quiet,
    /// Results, notes, warnings and one line per phase (progress on a terminal).
    Normal,
    /// Also one line per outer iteration (`-v`).
    Verbose,
}

/// The printing side of a run.
pub struct Console {
    verbosity: Verbosity,
    /// Whether standard error is a terminal (live progress instead of phase lines).
    terminal: bool,
}

impl Console {
    /// A console printing at `verbosity`, drawing progress if standard error is a terminal.
    pub fn new(verbosity: Verbosity) -> Self {
        Console {
            verbosity,
            terminal: std::io::stderr().is_terminal(),
        }
    }

    /// Prints a line of results on standard output (nothing with `--quiet`), ignoring a
    /// closed standard output (a pipe into `head`).
    pub fn out(&self, line: fmt::Arguments<'_>) {
        if self.verbosity > Verbosity::Quiet {
            let _ = writeln!(std::io::stdout().lock(), "{line}");
        }
    }

    /// Prints a note or warning line on standard error (nothing with `--quiet`).
    pub fn warn(&self, line: fmt::Arguments<'_>) {
        if self.verbosity > Verbosity::Quiet {
            let _ = writeln!(std::io::stderr().lock(), "{line}");
        }
    }

    /// Prints the line of a phase on standard error (nothing with `--quiet`).
    pub fn phase(&self, line: fmt::Arguments<'_>) {
        self.warn(line);
    }

    /// The progress display of a solve (or of a series of solves): a live line on a
    /// terminal, nothing off a terminal or with `--quiet`; with `-v`, one line per outer
    /// iteration in both cases.
    pub fn progress(&self, what: &str) -> Progress {
        let bar = if self.terminal && self.verbosity > Verbosity::Quiet {
            let bar = ProgressBar::new_spinner();
            bar.set_style(
                ProgressStyle::with_template("{spinner} {elapsed:>4} {prefix} {msg}")
                    .unwrap_or_else(|_| ProgressStyle::default_spinner()),
            );
            bar.enable_steady_tick(Duration::from_millis(200));
            bar
        } else {
            ProgressBar::hidden()
        };
        bar.set_prefix(what.to_string());
        Progress {
            bar,
            quiet: self.verbosity == Verbosity::Quiet,
            verbose: self.verbosity >= Verbosity::Verbose,
            started: Instant::now(),
            last: Cell::new(None),
        }
    }
}

/// The live progress of one solve (or a series of solves): see [`Console::progress`].
pub struct Progress {
    bar: ProgressBar,
    quiet: bool,
    verbose: bool,
    started: Instant,
    last: Cell<Option<OuterProgress>>,
}

impl Progress {
    /// Names what is being solved now (the prefix of the live line).
    pub fn set_what(&self, what: &str) {
        self.bar.set_prefix(what.to_string());
        self.last.set(None);
    }

    /// The observer of a solve: called once per outer iteration.
    pub fn observe(&self, p: &OuterProgress) {
        self.last.set(Some(*p));
        let line = format!(
            "outer {}: residual {:.1e} (tolerance {:.0e}), {} Newton steps",
            p.iteration + 1,
            p.residual(),
            p.tolerance,
            p.newton_steps
        );
        if self.verbose {
            self.phase(format_args!(
                "  {line}, {} s",
                significant_seconds(self.started.elapsed().as_secs_f64())
            ));
        }
        self.bar.set_message(line);
    }

    /// Prints a phase line on standard error above the live line (nothing with `--quiet`).
    pub fn phase(&self, line: fmt::Arguments<'_>) {
        if self.quiet {
            return;
        }
        if self.bar.is_hidden() {
            let _ = writeln!(std::io::stderr().lock(), "{line}");
        } else {
            self.bar.println(line.to_string());
        }
    }

    /// The last outer iteration observed since the last [`Progress::set_what`].
    pub fn last(&self) -> Option<OuterProgress> {
        self.last.get()
    }

    /// Removes the live line.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}

/// Seconds rounded to three significant digits, for the phase lines.
pub fn significant_seconds(s: f64) -> String {
    let rounded: f64 = format!("{s:.2e}").parse().unwrap_or(s);
    significant(rounded)
}
