//! `hemicontact`: the command-line program over the hemicontact library.
//!
//! Commands: `check FILE`, `solve FILE [--out DIR]`, `paper [--n N] [--out DIR]`,
//! `bench [--n LIST]`. Exit codes: 0 success, 1 invalid input or failed solve, 2 usage
//! error, 3 solve did not converge (results are still written, marked as not converged).

mod bench;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use hemicontact::io::atomic::prepare_dir;
use hemicontact::io::summary::{write_results, Summary};
use hemicontact::plot::deformed;
use hemicontact::problem::Problem;
use hemicontact::scenario::{builtin, Scenario};
use hemicontact::solver::Solution;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Finite element solver for contact of elastic locking materials with nonmonotone friction.
#[derive(Parser, Debug)]
#[command(name = "hemicontact", version, about)]
struct Cli {
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
    /// side-by-side figure DIR/comparison.{png,svg}.
    Paper {
        /// Squares per side (even).
        #[arg(long, default_value_t = 128)]
        n: usize,
        /// Output folder.
        #[arg(long, default_value = "out/paper")]
        out: PathBuf,
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
    },
}

/// Outcome of a command that solved something.
enum Outcome {
    Done,
    NotConverged,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Check { file } => check(&file).map(|_| Outcome::Done),
        Command::Solve { file, out } => solve(&file, out.as_deref()),
        Command::Paper { n, out } => paper(n, &out),
        Command::Bench {
            n,
            repeat,
            threads,
            paper,
        } => if paper {
            bench::run_paper(&n, repeat)
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
    let scenario = Scenario::from_file(file)?;
    let problem = scenario.into_problem()?;
    print_problem(&problem, &scenario.source);
    println!("ok: {} is valid", file.display());
    Ok(())
}

fn print_problem(problem: &Problem, source: &str) {
    let mesh = &problem.mesh;
    let dofs = problem.dof_map();
    println!("scenario   {source}");
    println!("dimension  {}", mesh.dim());
    println!("nodes      {}", mesh.n_nodes());
    println!("cells      {}", mesh.n_cells());
    println!(
        "DOFs       {} ({} free, {} prescribed)",
        dofs.n_dofs(),
        dofs.n_free(),
        dofs.n_dofs() - dofs.n_free()
    );
    let h = problem.material.elasticity.small_strain_hooke(mesh.dim());
    println!("Lamé       λ = {:.6e} Pa, G = {:.6e} Pa", h.lambda, h.mu);
    let lock = &problem.material.locking;
    if lock.c_kappa > 0.0 {
        println!(
            "locking    {:?}, penalty C_κ = {:e} Pa",
            lock.set, lock.c_kappa
        );
    } else {
        println!("locking    none");
    }
    for (k, c) in problem.contact.iter().enumerate() {
        let friction = match &c.friction {
            None => "frictionless".to_string(),
            Some(f) => format!(
                "{:?}-type bound, μ = {:?}, j = {:?}",
                f.bound, f.mu, f.potential
            ),
        };
        println!(
            "contact[{k}] part `{}`: gap {} m, normal compliance c_ν = {:e}, {friction}",
            mesh.part_names()[c.part],
            c.gap,
            c.normal.c_nu
        );
    }
    println!("contact points {}", problem.contact_nodes().len());
    println!("boundary parts:");
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
        println!("  {name:<10} {facets:>6} facets {nodes:>6} nodes  {role}");
    }
}

fn solve(file: &Path, out: Option<&Path>) -> Result<Outcome> {
    let scenario = Scenario::from_file(file)?;
    let problem = scenario.into_problem()?;
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
    dir: &Path,
    vtu: bool,
    json: bool,
    label: &str,
) -> Result<Case> {
    // Fail before the solve if the results could not be written.
    prepare_dir(dir)?;
    let solution = hemicontact::solver::solve(&problem).context("solve failed")?;
    let summary = Summary::new(
        &problem,
        &solution,
        scenario.file.title.clone(),
        &scenario.source,
    );
    let mut written = write_results(dir, &problem, &solution, &summary, vtu, json)?;
    if problem.mesh.dim() == 2 {
        let title = scenario
            .file
            .title
            .clone()
            .unwrap_or_else(|| label.to_string());
        written.extend(deformed::figure(&problem, &solution, &title).write(dir, "deformed")?);
    }
    for p in &written {
        println!("  wrote {}", p.display());
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
    println!(
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
        let worst = cert.equilibrium.max(cert.normal_law).max(cert.friction_law);
        println!(
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
    println!(
        "paper example (SPEC §5), n = {n}: {} squares, h = {}",
        n * n,
        16.0 / (2.0 * (n * n) as f64)
    );
    let mut cases = Vec::new();
    for (label, c_kappa, sub) in [
        ("C_kappa = 10000", 10000.0, "locking"),
        ("C_kappa = 0", 0.0, "no-locking"),
    ] {
        let scenario = Scenario::from_str(
            &builtin::paper(n, c_kappa),
            &format!("<built-in paper, {label}>"),
        )?;
        let problem = scenario.into_problem()?;
        println!("{label}:");
        cases.push(run_and_write(
            problem,
            &scenario,
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
        println!("  wrote {}", p.display());
    }
    print_table(&cases);
    Ok(outcome(&cases))
}
