//! `hemicontact`: the command-line program over the hemicontact library.
//!
//! Commands: `check FILE`, `solve FILE [--out DIR]`, `paper [--n N] [--out DIR]`,
//! `bench [--n LIST]`, `convergence FILE`, `completions SHELL`, `schema`; global flags
//! `--quiet`, `-v` (see [`console`]). Exit codes: 0 success, 1 invalid input or failed
//! solve, 2 usage error, 3 solve did not converge (results are still written, marked as not
//! converged), 130 interrupted by Ctrl-C. Each run writes its output folder as one result
//! set ([`hemicontact::io::result_set`]): the folder holds the previous complete set or the
//! new complete set, never a mix; a second run into a folder being written fails at once.

mod bench;
mod check;
mod console;
mod loading;
mod output;
mod study;

/// A line of results on standard output through a [`console::Console`] (nothing with
/// `--quiet`; a closed standard output is ignored instead of panicking).
#[macro_export]
macro_rules! say {
    ($console:expr, $($t:tt)*) => {
        $console.out(format_args!($($t)*))
    };
}

use anyhow::{Context, Result};
use clap::CommandFactory as _;
use clap::{Parser, Subcommand};
use console::{significant_seconds, Console, Verbosity};
use hemicontact::display::significant;
use hemicontact::io::results::{solution_figures, write_results};
use hemicontact::io::summary::Summary;
use hemicontact::plot::deformed;
use hemicontact::problem::Problem;
use hemicontact::scenario::{builtin, Scenario};
use hemicontact::solver::Solution;
use hemicontact::study::StudySettings;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

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
struct Cli {
    /// Skip the check of the estimated memory of a solve against the available memory.
    #[arg(long, global = true)]
    ignore_memory_limit: bool,
    /// Print nothing but errors (the exit code still tells a solve that did not converge).
    #[arg(long, short, global = true, conflicts_with = "verbose")]
    quiet: bool,
    /// Print one line per outer iteration of every solve, on a terminal or not.
    #[arg(long, short, global = true)]
    verbose: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
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

/// Outcome of a command that solved something.
enum Outcome {
    Done,
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
        Command::Solve { file, out } => solve(&ctx, &file, out.as_deref()),
        Command::Paper {
            n,
            out,
            study,
            levels,
            reference,
        } => {
            if study {
                let out = out.unwrap_or_else(|| PathBuf::from("out/paper-study"));
                paper_study(&ctx, &levels, reference, &out)
            } else {
                paper(&ctx, n, &out.unwrap_or_else(|| PathBuf::from("out/paper")))
            }
        }
        Command::Convergence {
            file,
            levels,
            reference,
            out,
            no_nested,
        } => convergence(&ctx, &file, &levels, reference, out.as_deref(), !no_nested),
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

fn solve(ctx: &RunContext, file: &Path, out: Option<&Path>) -> Result<Outcome> {
    let c = &ctx.console;
    let scenario = ctx.read_scenario(file)?;
    let (problem, notes) = scenario.into_problem_with_notes()?;
    check::print_notes(c, &notes);
    let settings = scenario.output();
    let dir = match (out, &settings.dir) {
        (Some(d), _) => d.to_path_buf(),
        (None, Some(d)) => d.clone(),
        (None, None) => {
            let stem = file
                .file_stem()
                .and_then(|s| s.to_str())
                .unwrap_or("scenario");
            Path::new("out").join(stem)
        }
    };
    // Fail before the solve if the results could not be written.
    ctx.output.begin(&dir)?;
    if let Some(factors) = scenario.load_factors()? {
        c.phase(format_args!(
            "solving {} in {} load steps: {}",
            file.display(),
            factors.len(),
            problem_size(&problem)
        ));
        let (rows, outcome) = loading::solve_path(ctx, &problem, &scenario, notes, &factors)?;
        print_written(c, &dir, &ctx.output.commit()?);
        print_table(c, &rows);
        return Ok(outcome);
    }
    c.phase(format_args!(
        "solving {}: {}",
        file.display(),
        problem_size(&problem)
    ));
    let case = run_and_write(
        ctx,
        problem,
        &scenario,
        notes,
        "",
        settings.vtu,
        settings.summary,
        "scenario",
    )?;
    print_written(c, &dir, &ctx.output.commit()?);
    let cases = [case];
    print_table(c, &[cases[0].row()]);
    Ok(outcome(&cases))
}

/// The size of a problem in words: nodes, cells, DOFs and contact points.
fn problem_size(problem: &Problem) -> String {
    let mesh = problem.mesh();
    let cells = if mesh.dim() == 2 {
        "triangles"
    } else {
        "tetrahedra"
    };
    let mut text = format!(
        "{} nodes, {} {cells}, {} DOFs",
        mesh.n_nodes(),
        mesh.n_cells(),
        problem.dof_map().n_dofs()
    );
    let points = problem.contact_nodes().map_or(0, |p| p.len());
    if points > 0 {
        text.push_str(&format!(", {points} contact points"));
    }
    text
}

/// A solved case, for the terminal table.
struct Case {
    label: String,
    problem: Problem,
    solution: Solution,
    summary: Summary,
}

impl Case {
    /// The case's row of the terminal table.
    fn row(&self) -> Row {
        Row::new(
            &self.label,
            &self.solution.report,
            self.summary.max_displacement,
        )
    }
}

/// One row of the terminal table: what it prints of a solve, without the solution.
struct Row {
    label: String,
    n_dofs: usize,
    outer: usize,
    newton: usize,
    factorizations: usize,
    seconds: f64,
    certificate: hemicontact::solver::Certificate,
    max_displacement: f64,
    converged: bool,
    /// The solver's verdict in words.
    message: String,
}

impl Row {
    /// The row of a solve labelled `label` with the report `r` and the largest
    /// displacement `max_displacement` (m).
    fn new(label: &str, r: &hemicontact::solver::SolveReport, max_displacement: f64) -> Row {
        Row {
            label: label.to_string(),
            n_dofs: r.n_dofs,
            outer: r.outer.len(),
            newton: r.newton.len(),
            factorizations: r.timings.n_factorizations,
            seconds: r.timings.total,
            certificate: r.certificate.clone(),
            max_displacement,
            converged: r.converged,
            message: r.message.clone(),
        }
    }
}

/// Prints the files of a result set once it is in place (and the phase line saying where).
fn print_written(c: &Console, dir: &Path, files: &[PathBuf]) {
    c.phase(format_args!(
        "written to {} ({} files)",
        dir.display(),
        files.len()
    ));
    for p in files {
        say!(c, "  wrote {}", p.display());
    }
}

/// Solves `problem` and writes its results into the sub-folder `folder` (`""`: the root)
/// of this run's result set.
fn run_and_write(
    ctx: &RunContext,
    problem: Problem,
    scenario: &Scenario,
    notes: Vec<String>,
    folder: &str,
    vtu: bool,
    json: bool,
    label: &str,
) -> Result<Case> {
    let settings = scenario.settings()?;
    let c = &ctx.console;
    let prefix = if folder.is_empty() {
        String::new()
    } else {
        format!("{label}: ")
    };
    let progress = c.progress(&if folder.is_empty() {
        "solving:".to_string()
    } else {
        format!("{label}:")
    });
    let solution = hemicontact::solver::solve_observed(
        &problem,
        &settings,
        problem.initial_displacement(),
        &std::sync::atomic::AtomicBool::new(false),
        &|p| progress.observe(p),
    )
    .with_context(|| format!("{}: solve failed", scenario.source))?;
    progress.finish();
    let r = &solution.report;
    c.phase(format_args!(
        "{prefix}solved in {} outer iterations / {} Newton steps in {} s{}",
        r.outer.len(),
        r.newton.len(),
        significant_seconds(r.timings.total),
        if r.converged { "" } else { " (not converged)" }
    ));
    let mut summary = Summary::new(
        &problem,
        &settings,
        &solution,
        scenario.file.title.clone(),
        &scenario.source,
    );
    // The notes of the solution (the scenario's were printed before the solve).
    for note in &summary.notes {
        c.warn(format_args!("note: {prefix}{note}"));
    }
    summary.prepend_notes(notes);
    let title = scenario
        .file
        .title
        .clone()
        .unwrap_or_else(|| label.to_string());
    let t = std::time::Instant::now();
    let extra = if ctx.output.writes() {
        solution_figures(&problem, &solution, &title)?
    } else {
        Vec::new()
    };
    ctx.output.with(|set| {
        Ok(write_results(
            set,
            folder,
            &problem,
            &solution,
            &title,
            json.then_some(&summary),
            vtu,
            &extra,
        )?)
    })?;
    c.phase(format_args!(
        "{prefix}results written in {} s",
        significant_seconds(t.elapsed().as_secs_f64())
    ));
    let r = &solution.report;
    if !r.converged {
        c.warn(format_args!(
            "warning: {label}: {}; the last iterate was written, marked \"converged\": false",
            r.message
        ));
    }
    Ok(Case {
        label: label.to_string(),
        problem,
        solution,
        summary,
    })
}

fn print_table(c: &Console, rows: &[Row]) {
    say!(
        c,
        "{:<22} {:>9} {:>6} {:>7} {:>8} {:>8} {:>7} {:>6} {:>6} {:>10} {:>10}",
        "case",
        "DOFs",
        "outer",
        "Newton",
        "factor.",
        "time s",
        "contact",
        "stick",
        "slip",
        "max |u| m",
        "certif."
    );
    for row in rows {
        let cert = &row.certificate;
        let worst = cert
            .equilibrium
            .max(cert.normal_law)
            .max(cert.friction_law)
            .max(cert.kkt.as_ref().map_or(0.0, |k| k.worst()));
        say!(
            c,
            "{:<22} {:>9} {:>6} {:>7} {:>8} {:>8.3} {:>7} {:>6} {:>6} {:>10.4e} {:>10.1e}{}",
            row.label,
            row.n_dofs,
            row.outer,
            row.newton,
            row.factorizations,
            row.seconds,
            cert.n_contact,
            cert.n_stick,
            cert.n_slip,
            row.max_displacement,
            worst,
            if row.converged { "" } else { "  NOT CONVERGED" }
        );
    }
    for row in rows {
        if let Some(k) = &row.certificate.kkt {
            let (cells, points, friction) = k.n_constraints;
            say!(
                c,
                "KKT ({}): exact constraints, relative residuals",
                row.label
            );
            if cells > 0 {
                say!(
            c,
                    "  ideal locking  {cells} cells, {} locked: violation {:.1e}, complementarity {:.1e}, min multiplier/max {:.1e}",
                    k.n_locked,
                    k.locking_violation,
                    k.locking_complementarity,
                    k.locking_min_multiplier
                );
            }
            if points > 0 {
                say!(
            c,
                    "  Signorini      {points} points: violation {:.1e}, complementarity {:.1e}, min pressure/max {:.1e}",
                    k.contact_violation,
                    k.contact_complementarity,
                    k.contact_min_multiplier
                );
            }
            if friction > 0 {
                say!(
            c,
                    "  exact friction {friction} points: largest slip of a sticking point {:.1e} (relative to max |u|)",
                    k.stick_slip
                );
            }
        }
    }
}

fn outcome(cases: &[Case]) -> Outcome {
    if cases.iter().all(|c| c.solution.report.converged) {
        Outcome::Done
    } else {
        Outcome::NotConverged
    }
}

fn paper(ctx: &RunContext, n: usize, out: &Path) -> Result<Outcome> {
    if n == 0 || !n.is_multiple_of(2) {
        anyhow::bail!(
            "--n {n}: the paper's mesh needs an even, positive number of squares per side"
        );
    }
    let c = &ctx.console;
    // Fail before the solves if the results could not be written.
    ctx.output.begin(out)?;
    let mut cases = Vec::new();
    for (label, c_kappa, sub) in [
        ("C_kappa = 10000", 10000.0, "locking"),
        ("C_kappa = 0", 0.0, "no-locking"),
    ] {
        let scenario = ctx.parse_scenario(
            &builtin::paper(n, c_kappa),
            &format!("<built-in paper, {label}>"),
        )?;
        let problem = scenario.into_problem()?;
        if cases.is_empty() {
            // The paper's h is the element area; the edge is the side of a square.
            let mesh = problem.mesh();
            let (lo, hi) = mesh.bounding_box();
            say!(
                c,
                "paper example, n = {n}: {} squares, h = {} m² (element area), edge h = {} m \
                 (square side)",
                n * n,
                significant(mesh.measure() / mesh.n_cells() as f64),
                significant((hi[0] - lo[0]) / n as f64)
            );
        }
        c.phase(format_args!("{label}: solving {}", problem_size(&problem)));
        cases.push(run_and_write(
            ctx,
            problem,
            &scenario,
            Vec::new(),
            sub,
            true,
            true,
            label,
        )?);
    }
    let panels: Vec<_> = cases
        .iter()
        .map(|c| (&c.problem, &c.solution, format!("{}, n = {n}", c.label)))
        .collect();
    let t = std::time::Instant::now();
    let comparison = deformed::side_by_side(&panels);
    let (svg, png) = rayon::join(|| comparison.to_svg(), || comparison.to_png());
    let png = png?;
    ctx.output.with(|set| {
        set.write("comparison.svg", svg.as_bytes())?;
        set.write("comparison.png", &png)?;
        Ok(())
    })?;
    c.phase(format_args!(
        "comparison figure written in {} s",
        significant_seconds(t.elapsed().as_secs_f64())
    ));
    print_written(c, out, &ctx.output.commit()?);
    print_table(c, &cases.iter().map(Case::row).collect::<Vec<_>>());
    Ok(outcome(&cases))
}

fn paper_study(
    ctx: &RunContext,
    levels: &[usize],
    reference: usize,
    out: &Path,
) -> Result<Outcome> {
    let mut cases = Vec::new();
    for (label, c_kappa) in [("C_kappa = 10000", 10000.0), ("C_kappa = 0", 0.0)] {
        let scenario = ctx.parse_scenario(
            &builtin::paper(reference, c_kappa),
            &format!("<built-in paper, {label}>"),
        )?;
        cases.push((label.to_string(), scenario));
    }
    let settings = StudySettings {
        levels: levels.to_vec(),
        reference,
        nested_iteration: true,
    };
    say!(
        &ctx.console,
        "paper convergence study: levels {levels:?}, reference n = {reference}"
    );
    let studies = study::run(
        ctx,
        &cases,
        &settings,
        out,
        "Paper example: relative energy-norm error",
    )?;
    Ok(study_outcome(&ctx.console, &studies))
}

fn convergence(
    ctx: &RunContext,
    file: &Path,
    levels: &[usize],
    reference: usize,
    out: Option<&Path>,
    nested: bool,
) -> Result<Outcome> {
    let scenario = ctx.read_scenario(file)?;
    // Validate once, at the coarsest level, before any long solve.
    scenario
        .with_resolution(levels.first().copied().unwrap_or(reference))?
        .into_problem()?;
    let dir = match out {
        Some(d) => d.to_path_buf(),
        None => {
            let stem = file
                .file_stem()
                .and_then(|s| s.to_str())
                .unwrap_or("scenario");
            Path::new("out").join(format!("{stem}-convergence"))
        }
    };
    let label = scenario
        .file
        .title
        .clone()
        .unwrap_or_else(|| file.display().to_string());
    let settings = StudySettings {
        levels: levels.to_vec(),
        reference,
        nested_iteration: nested,
    };
    let studies = study::run(ctx, &[(label.clone(), scenario)], &settings, &dir, &label)?;
    Ok(study_outcome(&ctx.console, &studies))
}

fn study_outcome(c: &Console, studies: &[hemicontact::study::Study]) -> Outcome {
    let all = studies
        .iter()
        .all(|s| s.reference_converged && s.levels.iter().all(|l| l.converged));
    if all {
        Outcome::Done
    } else {
        c.warn(format_args!(
            "warning: some solves did not converge (see table.md)"
        ));
        Outcome::NotConverged
    }
}
