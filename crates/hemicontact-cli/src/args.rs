//! The command line: the global flags and the subcommands with their arguments (clap).

use clap::{Parser, Subcommand};
use std::path::PathBuf;

/// Finite element solver for contact of elastic locking materials with nonmonotone friction.
#[derive(Parser, Debug)]
#[command(
    name = "hemicontact",
    version,
    about,
    after_help = "Documentation: docs/ in the repository (running.md: commands and exit codes; \
                  scenario.md: every scenario key; model.md: the laws; method.md: the solver \
                  and its certificate; outputs.md: the result files)."
)]
pub(crate) struct Cli {
    /// Skip the check of the estimated memory of a solve against the available memory.
    #[arg(long, global = true)]
    pub(crate) ignore_memory_limit: bool,
    /// Print nothing but errors (the exit code still tells a solve that did not converge).
    #[arg(long, short, global = true, conflicts_with = "verbose")]
    pub(crate) quiet: bool,
    /// Print one line per outer iteration of every solve, on a terminal or not.
    #[arg(long, short, global = true)]
    pub(crate) verbose: bool,
    #[command(subcommand)]
    pub(crate) command: Command,
}

#[derive(Subcommand, Debug)]
pub(crate) enum Command {
    /// Validate a scenario file and print its sizes, material constants and boundary parts.
    Check {
        /// Scenario file (TOML).
        file: PathBuf,
    },
    /// Solve a scenario and write solution.vtu, contact.csv, the deformed-mesh figures and
    /// summary.json.
    Solve {
        /// Scenario file (TOML).
        file: PathBuf,
        /// Output folder (default: the scenario's output.dir, else `out/<file stem>`).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Solve the paper's example on an n × n mesh, with C_κ = 10 000 and C_κ = 0;
    /// write each case's results and figures into DIR/locking and DIR/no-locking and the
    /// side-by-side figure DIR/comparison.{png,svg}. With --study, run the paper's
    /// convergence study for both cases instead (results in DIR).
    Paper {
        /// Squares per side (even).
        #[arg(long, default_value_t = 128)]
        n: usize,
        /// Output folder, replaced as a whole by this run's results (default `out/paper`;
        /// with --study `out/paper-study`).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Run the convergence study (levels and reference below).
        #[arg(long)]
        study: bool,
        /// Study levels (squares per side), space- or comma-separated: `--levels 4 8 16` or
        /// `--levels 4,8,16`.
        #[arg(long, num_args = 1.., value_delimiter = ',', default_values_t = vec![4usize, 8, 16, 32, 64, 128])]
        levels: Vec<usize>,
        /// Study reference resolution.
        #[arg(long, default_value_t = 512)]
        reference: usize,
    },
    /// Convergence study of a scenario on a generated mesh (rectangle or box): solve on each level and
    /// measure the relative energy-norm error against a reference solution.
    Convergence {
        /// Scenario file (TOML).
        file: PathBuf,
        /// Levels (squares along x), increasing, space- or comma-separated: `--levels 4 8 16`
        /// or `--levels 4,8,16`.
        #[arg(long, num_args = 1.., value_delimiter = ',', default_values_t = vec![4usize, 8, 16, 32, 64, 128])]
        levels: Vec<usize>,
        /// Reference resolution (squares along x).
        #[arg(long, default_value_t = 512)]
        reference: usize,
        /// Output folder (default `out/<file stem>-convergence`).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Start every level from zero instead of the previous level's solution.
        #[arg(long)]
        no_nested: bool,
    },
    /// Time the phases of a linear solve of the paper's square (pattern, assembly,
    /// ordering + symbolic analysis, numeric factorization, triangular solve), or with
    /// --paper the whole nonlinear paper solve against a linear elastic solve.
    Bench {
        /// Mesh sizes n (squares per side), space- or comma-separated.
        #[arg(long, num_args = 1.., value_delimiter = ',', default_values_t = vec![128usize, 512])]
        n: Vec<usize>,
        /// Repetitions of the numeric phases (the median is reported).
        #[arg(long, default_value_t = 3)]
        repeat: usize,
        /// Threads of the factorization in the linear-algebra benchmark (0: all cores).
        #[arg(long, default_value_t = 1)]
        threads: usize,
        /// Benchmark the nonlinear paper solve (C_κ = 10 000) against a linear elastic
        /// solve on the same mesh instead of the linear-algebra phases.
        #[arg(long)]
        paper: bool,
        /// With --paper: benchmark this scenario (on a generated rectangle, refined to
        /// each n) instead of the built-in paper example, e.g. scenarios/paper-ideal.toml.
        #[arg(long, requires = "paper")]
        scenario: Option<PathBuf>,
    },
    /// Print a shell completion script, e.g. `hemicontact completions bash >
    /// ~/.local/share/bash-completion/completions/hemicontact`.
    Completions {
        /// The shell.
        #[arg(value_enum)]
        shell: clap_complete::Shell,
    },
    /// Print the JSON Schema of the scenario file (for editors that check TOML against a
    /// schema).
    Schema,
}
