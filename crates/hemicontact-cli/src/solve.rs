//! `solve FILE`: one scenario solved (in load steps if it has them), its results written;
//! the solve of one case and the writing of its results, shared with `paper`.

use crate::console::significant_seconds;
use crate::table::{print_table, print_written, Row};
use crate::{check, loading, Outcome, RunContext};
use anyhow::{Context, Result};
use hemicontact::io::results::{solution_figures, write_results};
use hemicontact::io::summary::Summary;
use hemicontact::problem::Problem;
use hemicontact::scenario::Scenario;
use hemicontact::solver::Solution;
use std::path::Path;

/// Solves the scenario `file` and writes its results into `out` (default: the scenario's
/// output.dir, else `out/<file stem>`).
pub fn solve(ctx: &RunContext, file: &Path, out: Option<&Path>) -> Result<Outcome> {
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
pub fn problem_size(problem: &Problem) -> String {
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
pub struct Case {
    /// The case's label.
    pub label: String,
    /// The problem solved.
    pub problem: Problem,
    /// Its solution.
    pub solution: Solution,
    /// Its summary (summary.json).
    pub summary: Summary,
}

impl Case {
    /// The case's row of the terminal table.
    pub fn row(&self) -> Row {
        Row::new(
            &self.label,
            &self.solution.report,
            self.summary.max_displacement,
        )
    }
}

/// Solves `problem` and writes its results into the sub-folder `folder` (`""`: the root)
/// of this run's result set.
pub fn run_and_write(
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

/// Whether every case converged.
pub fn outcome(cases: &[Case]) -> Outcome {
    if cases.iter().all(|c| c.solution.report.converged) {
        Outcome::Done
    } else {
        Outcome::NotConverged
    }
}
