//! `hemicontact`: the command-line program over the hemicontact library.
//!
//! Commands: `check FILE`, `solve FILE [--out DIR]`, `paper [--n N] [--out DIR]`,
//! `bench [--n LIST]`, `convergence FILE`, `completions SHELL`, `schema`; global flags
//! `--quiet`, `-v` (see [`console`]). Exit codes: 0 success, 1 invalid input or failed
//! solve, 2 usage error, 3 solve did not converge (results are still written, marked as not
//! converged), 130 interrupted by Ctrl-C. Each run writes its output folder as one result
//! set ([`hemicontact::io::result_set`]): the folder holds the previous complete set or the
//! new complete set, never a mix; a second run into a folder being written fails at once.

mod args;
mod bench;
mod check;
mod console;
mod context;
mod convergence;
mod loading;
mod output;
mod paper;
mod solve;
mod study;
mod table;

/// A line of results on standard output through a [`console::Console`] (nothing with
/// `--quiet`; a closed standard output is ignored instead of panicking).
#[macro_export]
macro_rules! say {
    ($console:expr, $($t:tt)*) => {
        $console.out(format_args!($($t)*))
    };
}

use args::{Cli, Command};
use clap::CommandFactory as _;
use clap::Parser as _;
use console::{Console, Verbosity};
pub use context::{Outcome, RunContext};
use std::path::PathBuf;
use std::process::ExitCode;

fn main() -> ExitCode {
    // The processes of an MPI launch (one without `mpirun`): rank 0 prints and writes, the
    // other ranks compute the same and stay silent.
    let processes = match hemicontact::parallel::Processes::launch() {
        Ok(p) => p,
        Err(e) => {
            if hemicontact::parallel::mpi_launch().is_none_or(|(rank, _)| rank == 0) {
                eprintln!("error: {e}");
            }
            return ExitCode::from(1);
        }
    };
    if processes.size() > 1 {
        // The same number of threads on every rank, so that the ranks run at even speeds
        // (the results do not depend on it: the assembly gives the same bits on any number
        // of threads, and every rank must compute the same numbers to take the same
        // decisions).
        let own = std::env::var("RAYON_NUM_THREADS")
            .ok()
            .and_then(|v| v.trim().parse::<usize>().ok())
            .filter(|&n| n > 0)
            .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
        let mut threads = [own as f64];
        if let Err(e) = processes.max(&mut threads) {
            eprintln!("error: {e}");
            processes.abort(1);
        }
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(threads[0] as usize)
            .build_global();
    }
    let output = output::Output::new(processes.is_root());
    output.install_interrupt_handler();
    let cli = Cli::parse();
    let verbosity = match (cli.quiet, cli.verbose) {
        _ if !processes.is_root() => Verbosity::Quiet,
        (true, _) => Verbosity::Quiet,
        (false, true) => Verbosity::Verbose,
        (false, false) => Verbosity::Normal,
    };
    let ctx = RunContext {
        ignore_memory_limit: cli.ignore_memory_limit,
        output,
        console: Console::new(verbosity),
        processes,
    };
    let result = match cli.command {
        Command::Check { file } => check::check(&ctx, &file).map(|_| Outcome::Done),
        Command::Solve { file, out } => solve::solve(&ctx, &file, out.as_deref()),
        Command::Paper {
            n,
            out,
            study,
            levels,
            reference,
        } => {
            if study {
                let out = out.unwrap_or_else(|| PathBuf::from("out/paper-study"));
                paper::paper_study(&ctx, &levels, reference, &out)
            } else {
                paper::paper(&ctx, n, &out.unwrap_or_else(|| PathBuf::from("out/paper")))
            }
        }
        Command::Convergence {
            file,
            levels,
            reference,
            out,
            no_nested,
        } => convergence::convergence(&ctx, &file, &levels, reference, out.as_deref(), !no_nested),
        Command::Bench {
            n,
            repeat,
            threads,
            paper,
            scenario,
        } => if paper {
            bench::run_paper(&ctx, &n, repeat, scenario.as_deref())
        } else {
            bench::run(&ctx, &n, repeat, threads)
        }
        .map(|_| Outcome::Done),
        Command::Completions { shell } => {
            let mut stdout = std::io::stdout().lock();
            clap_complete::generate(shell, &mut Cli::command(), "hemicontact", &mut stdout);
            Ok(Outcome::Done)
        }
        Command::Schema => {
            use std::io::Write as _;
            let _ = writeln!(
                std::io::stdout().lock(),
                "{}",
                hemicontact::scenario::JSON_SCHEMA.trim_end()
            );
            Ok(Outcome::Done)
        }
    };
    ctx.output.discard();
    match result {
        Ok(outcome) => {
            // Every rank waits for rank 0's results to be in place before it exits (an MPI
            // launcher ends the others when one process exits with an error code).
            if let Err(e) = processes.max(&mut [0.0]) {
                eprintln!("error: {e}");
                processes.abort(1);
            }
            match outcome {
                Outcome::Done => ExitCode::SUCCESS,
                Outcome::NotConverged => ExitCode::from(3),
            }
        }
        Err(e) => {
            if processes.size() > 1 {
                // Possibly this rank's alone: end every rank rather than leave them waiting.
                eprintln!(
                    "error on rank {} of {}: {}",
                    processes.rank(),
                    processes.size(),
                    error_chain(&e)
                );
                processes.abort(1);
            }
            eprintln!("error: {}", error_chain(&e));
            ExitCode::from(1)
        }
    }
}

/// The error and its causes, `: `-separated, without repeating a cause that the message
/// before it already ends with (an I/O error's message includes its source).
fn error_chain(e: &anyhow::Error) -> String {
    let mut message = e.to_string();
    for cause in e.chain().skip(1) {
        let cause = cause.to_string();
        if !message.ends_with(&cause) {
            message = format!("{message}: {cause}");
        }
    }
    message
}
