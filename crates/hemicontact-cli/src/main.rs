//! `hemicontact`: the command-line program over the hemicontact library.
//!
//! Commands: `check FILE`, `solve FILE [--out DIR]`, `paper [--n N] [--out DIR]`,
//! `bench [--n LIST]`, `convergence FILE`. Exit codes: 0 success, 1 invalid input or failed
//! solve, 2 usage error, 3 solve did not converge (results are still written, marked as not
//! converged), 130 interrupted by Ctrl-C (no partial files are left).

mod bench;
mod study;

/// `println!` that ignores a closed standard output (a pipe into `head`) instead of
/// panicking.
#[macro_export]
macro_rules! say {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout().lock(), $($t)*);
    }};
}

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use hemicontact::io::summary::{write_results, Summary};
use hemicontact::plot::deformed;
use hemicontact::problem::Problem;
use hemicontact::scenario::{builtin, Scenario};
use hemicontact::solver::Solution;
use hemicontact::study::StudySettings;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Finite element solver for contact of elastic locking materials with nonmonotone friction.
#[derive(Parser, Debug)]
#[command(name = "hemicontact", version, about)]
struct Cli {
    /// Skip the check of the estimated memory of a solve against the available memory.
    #[arg(long, global = true)]
    ignore_memory_limit: bool,
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
    /// Solve a scenario and write solution.vtu and summary.json.
    Solve {
        /// Scenario file (TOML).
        file: PathBuf,
        /// Output folder (default: the scenario's output.dir, else `out/<file stem>`).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Solve the paper's example (SPEC §5) on an n × n mesh, with C_κ = 10 000 and C_κ = 0;
    /// write each case's results and figures into DIR/locking and DIR/no-locking and the
    /// side-by-side figure DIR/comparison.{png,svg}. With --study, run the paper's
    /// convergence study for both cases instead (results in DIR/study).
    Paper {
        /// Squares per side (even).
        #[arg(long, default_value_t = 128)]
        n: usize,
        /// Output folder.
        #[arg(long, default_value = "out/paper")]
        out: PathBuf,
        /// Run the convergence study (levels and reference below).
        #[arg(long)]
        study: bool,
        /// Study levels (squares per side).
        #[arg(long, value_delimiter = ',', default_values_t = vec![4usize, 8, 16, 32, 64, 128])]
        levels: Vec<usize>,
        /// Study reference resolution.
        #[arg(long, default_value_t = 512)]
        reference: usize,
    },
    /// Convergence study of a scenario on a generated rectangle: solve on each level and
    /// measure the relative energy-norm error against a reference solution.
    Convergence {
        /// Scenario file (TOML).
        file: PathBuf,
        /// Levels (squares along x), increasing.
        #[arg(long, value_delimiter = ',', default_values_t = vec![4usize, 8, 16, 32, 64, 128])]
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
        /// Comma-separated mesh sizes n (squares per side).
        #[arg(long, value_delimiter = ',', default_values_t = vec![128usize, 512])]
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
}

/// Outcome of a command that solved something.
enum Outcome {
    Done,
    NotConverged,
}

/// Set from `--ignore-memory-limit`.
static IGNORE_MEMORY_LIMIT: std::sync::OnceLock<bool> = std::sync::OnceLock::new();

fn apply_memory_flag(mut s: Scenario) -> Scenario {
    if IGNORE_MEMORY_LIMIT.get().copied().unwrap_or(false) {
        s.memory_limit = None;
    }
    s
}

/// Reads a scenario file, honouring `--ignore-memory-limit`.
pub fn read_scenario(file: &Path) -> Result<Scenario> {
    Ok(apply_memory_flag(Scenario::from_file(file)?))
}

/// Parses scenario text, honouring `--ignore-memory-limit`.
pub fn parse_scenario(text: &str, source: &str) -> Result<Scenario> {
    Ok(apply_memory_flag(Scenario::from_str(text, source)?))
}

/// Output folders of this run: on Ctrl-C their temporary files are removed.
static OUTPUT_DIRS: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

/// Creates an output folder (failing before any solve if it cannot be written) and
/// registers it for clean-up on interruption.
pub fn prepare_output(dir: &Path) -> Result<()> {
    hemicontact::io::atomic::prepare_dir(dir)?;
    if let Ok(mut dirs) = OUTPUT_DIRS.lock() {
        dirs.push(dir.to_path_buf());
    }
    Ok(())
}

/// Exit code of a run interrupted by Ctrl-C (128 + SIGINT, the shell convention).
const INTERRUPTED: i32 = 130;

/// On Ctrl-C: remove this process's temporary files (every result is written to a temporary
/// file and renamed, so no partial result exists under a final name) and exit with 130.
fn install_interrupt_handler() {
    let _ = ctrlc::set_handler(|| {
        let suffix = format!(".tmp-{}", std::process::id());
        if let Ok(dirs) = OUTPUT_DIRS.lock() {
            for dir in dirs.iter() {
                let Ok(entries) = std::fs::read_dir(dir) else {
                    continue;
                };
                for e in entries.flatten() {
                    if e.file_name().to_string_lossy().ends_with(&suffix) {
                        let _ = std::fs::remove_file(e.path());
                    }
                }
            }
        }
        eprintln!("interrupted: no partial result files were left");
        std::process::exit(INTERRUPTED);
    });
}

fn main() -> ExitCode {
    install_interrupt_handler();
    let cli = Cli::parse();
    let _ = IGNORE_MEMORY_LIMIT.set(cli.ignore_memory_limit);
    let result = match cli.command {
        Command::Check { file } => check(&file).map(|_| Outcome::Done),
        Command::Solve { file, out } => solve(&file, out.as_deref()),
        Command::Paper {
            n,
            out,
            study,
            levels,
            reference,
        } => {
            if study {
                paper_study(&levels, reference, &out.join("study"))
            } else {
                paper(n, &out)
            }
        }
        Command::Convergence {
            file,
            levels,
            reference,
            out,
            no_nested,
        } => convergence(&file, &levels, reference, out.as_deref(), !no_nested),
        Command::Bench {
            n,
            repeat,
            threads,
            paper,
            scenario,
        } => if paper {
            bench::run_paper(&n, repeat, scenario.as_deref())
        } else {
            bench::run(&n, repeat, threads)
        }
        .map(|_| Outcome::Done),
    };
    match result {
        Ok(Outcome::Done) => ExitCode::SUCCESS,
        Ok(Outcome::NotConverged) => ExitCode::from(3),
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(1)
        }
    }
}

fn check(file: &Path) -> Result<()> {
    let scenario = read_scenario(file)?;
    let (problem, notes) = scenario.into_problem_with_notes()?;
    print_problem(&problem, &scenario.source);
    print_notes(&notes);
    // Rigid motions not blocked by a Dirichlet condition that contact carries (those it
    // does not carry were refused above).
    for motion in problem.rigid_motions().describe_all() {
        say!("free rigid motion carried by contact: {motion}");
    }
    let iterative = problem
        .solver
        .linear_solver
        .resolve(problem.mesh.dim(), problem.dof_map().n_free())
        == hemicontact::solver::LinearSolver::Iterative;
    if !problem.contact.is_empty() && iterative {
        say!(
            "uniqueness (Theorem 4): not checked — the discrete trace constant needs a Cholesky \
             factorization, and this scenario uses the iterative linear solver"
        );
    } else if !problem.contact.is_empty() {
        print_uniqueness(&hemicontact::solver::uniqueness::check(&problem)?);
    }
    say!("ok: {} is valid", file.display());
    Ok(())
}

fn print_problem(problem: &Problem, source: &str) {
    let mesh = &problem.mesh;
    let dofs = problem.dof_map();
    say!("scenario   {source}");
    say!("dimension  {}", mesh.dim());
    say!("nodes      {}", mesh.n_nodes());
    say!("cells      {}", mesh.n_cells());
    say!(
        "DOFs       {} ({} free, {} prescribed)",
        dofs.n_dofs(),
        dofs.n_free(),
        dofs.n_dofs() - dofs.n_free()
    );
    let h = problem.material.elasticity.small_strain_hooke(mesh.dim());
    say!("Lamé       λ = {:.6e} Pa, G = {:.6e} Pa", h.lambda, h.mu);
    let lock = &problem.material.locking;
    if let Some(set) = &problem.material.ideal_locking {
        say!("locking    {set:?}, ideal (exact constraint, augmented Lagrangian)");
    } else if lock.c_kappa > 0.0 {
        say!(
            "locking    {:?}, penalty C_κ = {:e} Pa",
            lock.set,
            lock.c_kappa
        );
    } else {
        say!("locking    none");
    }
    for (k, c) in problem.contact.iter().enumerate() {
        let friction = match &c.friction {
            None => "frictionless".to_string(),
            Some(f) => format!(
                "{:?}-type bound, μ = {:?}, j = {:?}{}",
                f.bound,
                f.mu,
                f.potential,
                if f.exact { ", exact stick/slip" } else { "" }
            ),
        };
        let normal = match c.normal {
            hemicontact::contact::NormalLaw::Compliance(n) => {
                format!("normal compliance c_ν = {:e}", n.c_nu)
            }
            hemicontact::contact::NormalLaw::Signorini => "Signorini (rigid)".to_string(),
        };
        say!(
            "contact[{k}] part `{}`: gap {} m, {normal}, {friction}",
            mesh.part_names()[c.part],
            c.gap,
        );
    }
    say!("contact points {}", problem.contact_nodes().len());
    say!("boundary parts:");
    for (p, name) in mesh.part_names().iter().enumerate() {
        let facets = mesh.part_facets(p).count();
        let nodes = mesh.part_nodes(p).len();
        let mut roles = Vec::new();
        if problem.dirichlet.iter().any(|b| b.part == p) {
            roles.push("Dirichlet");
        }
        if problem.tractions.iter().any(|t| t.part == p) {
            roles.push("Neumann");
        }
        if problem.contact.iter().any(|c| c.part == p) {
            roles.push("contact");
        }
        let role = if roles.is_empty() {
            "free".to_string()
        } else {
            roles.join(" + ")
        };
        say!("  {name:<10} {facets:>6} facets {nodes:>6} nodes  {role}");
    }
}

/// Prints the notes of a scenario (warnings that do not stop the run) to standard error.
fn print_notes(notes: &[String]) {
    for n in notes {
        eprintln!("note: {n}");
    }
}

fn print_uniqueness(u: &hemicontact::solver::uniqueness::Uniqueness) {
    say!(
        "uniqueness (Theorem 4): m_A = {:.6e}, μ₀ = {}, L_μ = {}, c_j = {}, α_j = {}",
        u.m_a,
        u.mu0,
        u.l_mu,
        u.c_j,
        u.alpha_j
    );
    match (&u.note, u.trace_constant) {
        (Some(note), _) => say!("  not applicable: {note}"),
        (None, Some(g)) => say!(
            "  ‖γ‖ = {g:.6e} ({} power iterations); (μ₀α_j + c_jL_μ)‖γ‖² = {:.6e} {} m_A: condition {} (margin {:.6e})",
            u.iterations,
            u.lhs,
            if u.holds { "<" } else { "≥" },
            if u.holds { "holds" } else { "FAILS" },
            u.margin
        ),
        (None, None) => {}
    }
}

fn solve(file: &Path, out: Option<&Path>) -> Result<Outcome> {
    let scenario = read_scenario(file)?;
    let (problem, notes) = scenario.into_problem_with_notes()?;
    print_notes(&notes);
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
    let case = run_and_write(
        problem,
        &scenario,
        notes,
        &dir,
        settings.vtu,
        settings.summary,
        "scenario",
    )?;
    let cases = [case];
    print_table(&cases);
    Ok(outcome(&cases))
}

/// A solved case, for the terminal table.
struct Case {
    label: String,
    problem: Problem,
    solution: Solution,
    summary: Summary,
}

fn run_and_write(
    problem: Problem,
    scenario: &Scenario,
    notes: Vec<String>,
    dir: &Path,
    vtu: bool,
    json: bool,
    label: &str,
) -> Result<Case> {
    // Fail before the solve if the results could not be written.
    prepare_output(dir)?;
    let solution = hemicontact::solver::solve(&problem)
        .with_context(|| format!("{}: solve failed", scenario.source))?;
    let mut summary = Summary::new(
        &problem,
        &solution,
        scenario.file.title.clone(),
        &scenario.source,
    );
    summary.notes = notes;
    let mut written = write_results(dir, &problem, &solution, &summary, vtu, json)?;
    {
        let title = scenario
            .file
            .title
            .clone()
            .unwrap_or_else(|| label.to_string());
        written.extend(deformed::figure(&problem, &solution, &title).write(dir, "deformed")?);
    }
    for p in &written {
        say!("  wrote {}", p.display());
    }
    let r = &solution.report;
    if !r.converged {
        eprintln!(
            "warning: {label}: {}; the last iterate was written, marked \"converged\": false",
            r.message
        );
    }
    Ok(Case {
        label: label.to_string(),
        problem,
        solution,
        summary,
    })
}

fn print_table(cases: &[Case]) {
    say!(
        "{:<22} {:>9} {:>6} {:>7} {:>8} {:>8} {:>6} {:>12} {:>10} {:>10}",
        "case",
        "DOFs",
        "outer",
        "Newton",
        "factor.",
        "time s",
        "contact",
        "slip",
        "max |u| m",
        "certif."
    );
    for c in cases {
        let r = &c.solution.report;
        let cert = &r.certificate;
        let worst = cert
            .equilibrium
            .max(cert.normal_law)
            .max(cert.friction_law)
            .max(cert.kkt.as_ref().map_or(0.0, |k| k.worst()));
        say!(
            "{:<22} {:>9} {:>6} {:>7} {:>8} {:>8.3} {:>6} {:>12} {:>10.6} {:>10.1e}{}",
            c.label,
            r.n_dofs,
            r.outer.len(),
            r.newton.len(),
            r.timings.n_factorizations,
            r.timings.total,
            cert.n_contact,
            cert.n_slip,
            c.summary.max_displacement,
            worst,
            if r.converged { "" } else { "  NOT CONVERGED" }
        );
    }
    for c in cases {
        if let Some(k) = &c.solution.report.certificate.kkt {
            let (cells, points, friction) = k.n_constraints;
            say!("KKT ({}): exact constraints, relative residuals", c.label);
            if cells > 0 {
                say!(
                    "  ideal locking  {cells} cells, {} locked: violation {:.1e}, complementarity {:.1e}, min multiplier/max {:.1e}",
                    k.n_locked,
                    k.locking_violation,
                    k.locking_complementarity,
                    k.locking_min_multiplier
                );
            }
            if points > 0 {
                say!(
                    "  Signorini      {points} points: violation {:.1e}, complementarity {:.1e}, min pressure/max {:.1e}",
                    k.contact_violation,
                    k.contact_complementarity,
                    k.contact_min_multiplier
                );
            }
            if friction > 0 {
                say!(
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

fn paper(n: usize, out: &Path) -> Result<Outcome> {
    if n == 0 || !n.is_multiple_of(2) {
        anyhow::bail!(
            "--n {n}: the paper's mesh needs an even, positive number of squares per side"
        );
    }
    say!(
        "paper example (SPEC §5), n = {n}: {} squares, h = {}",
        n * n,
        16.0 / (2.0 * (n * n) as f64)
    );
    let mut cases = Vec::new();
    for (label, c_kappa, sub) in [
        ("C_kappa = 10000", 10000.0, "locking"),
        ("C_kappa = 0", 0.0, "no-locking"),
    ] {
        let scenario = parse_scenario(
            &builtin::paper(n, c_kappa),
            &format!("<built-in paper, {label}>"),
        )?;
        let problem = scenario.into_problem()?;
        say!("{label}:");
        cases.push(run_and_write(
            problem,
            &scenario,
            Vec::new(),
            &out.join(sub),
            true,
            true,
            label,
        )?);
    }
    let panels: Vec<_> = cases
        .iter()
        .map(|c| (&c.problem, &c.solution, format!("{}, n = {n}", c.label)))
        .collect();
    for p in deformed::side_by_side(&panels).write(out, "comparison")? {
        say!("  wrote {}", p.display());
    }
    print_table(&cases);
    Ok(outcome(&cases))
}

fn paper_study(levels: &[usize], reference: usize, out: &Path) -> Result<Outcome> {
    let mut cases = Vec::new();
    for (label, c_kappa) in [("C_kappa = 10000", 10000.0), ("C_kappa = 0", 0.0)] {
        let scenario = parse_scenario(
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
    say!("paper convergence study: levels {levels:?}, reference n = {reference}");
    let studies = study::run(
        &cases,
        &settings,
        out,
        "Paper example: relative energy-norm error",
    )?;
    Ok(study_outcome(&studies))
}

fn convergence(
    file: &Path,
    levels: &[usize],
    reference: usize,
    out: Option<&Path>,
    nested: bool,
) -> Result<Outcome> {
    let scenario = read_scenario(file)?;
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
    let studies = study::run(&[(label.clone(), scenario)], &settings, &dir, &label)?;
    Ok(study_outcome(&studies))
}

fn study_outcome(studies: &[hemicontact::study::Study]) -> Outcome {
    let all = studies
        .iter()
        .all(|s| s.reference_converged && s.levels.iter().all(|l| l.converged));
    if all {
        Outcome::Done
    } else {
        eprintln!("warning: some solves did not converge (see table.md)");
        Outcome::NotConverged
    }
}
