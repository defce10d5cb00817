//! `solve` of a scenario with `[loading]`: the load path
//! ([`hemicontact::loading::load_path`]) written as one result set: each step's usual
//! results in `step-001/`, `step-002/`, …, the ParaView collection `solution.pvd` over the
//! steps' `solution.vtu` (time value = load factor) and the table `load_path.csv`.

use crate::console::significant_seconds;
use crate::{Case, Outcome, RunContext};
use anyhow::{Context, Result};
use hemicontact::display::significant;
use hemicontact::io::results::{solution_figures, write_results};
use hemicontact::io::summary::Summary;
use hemicontact::io::vtu::solution_vtu;
use hemicontact::loading::{load_path, path_csv, LoadStep, PathRow};
use hemicontact::problem::Problem;
use hemicontact::scenario::Scenario;
use std::cell::Cell;
use std::sync::atomic::AtomicBool;

/// The folder of step `k` (from 1) of a path of `n` steps: `step-001`, … (at least three
/// digits, more for paths of 1000 steps or more, so the names sort in step order).
pub fn step_folder(k: usize, n: usize) -> String {
    let width = n.to_string().len().max(3);
    format!("step-{k:0width$}")
}

/// Solves `problem` along `factors` and writes the path's results into this run's result
/// set (begun by the caller, who commits it). Returns the steps solved, for the terminal
/// table, and the outcome: not converged if a step did not converge (the path stops there;
/// that step is written, marked `"converged": false`).
pub fn solve_path(
    ctx: &RunContext,
    problem: &Problem,
    scenario: &Scenario,
    notes: Vec<String>,
    factors: &[f64],
) -> Result<(Vec<Case>, Outcome)> {
    let c = &ctx.console;
    let settings = scenario.settings()?;
    let output = scenario.output();
    let n = factors.len();
    let progress = c.progress(&format!("step 1/{n}:"));
    let current = Cell::new(1);
    let steps = load_path(
        problem,
        &settings,
        factors,
        &AtomicBool::new(false),
        &|k, p| {
            if current.replace(k) != k {
                progress.set_what(&format!("step {k}/{n}:"));
            }
            progress.observe(p);
        },
        &mut |s: &LoadStep| {
            let r = &s.solution.report;
            progress.phase(format_args!(
                "step {}/{n} (load factor {}): {} outer iterations / {} Newton steps in {} s{}",
                s.step,
                significant(s.factor),
                r.outer.len(),
                r.newton.len(),
                significant_seconds(r.timings.total),
                if r.converged { "" } else { " (not converged)" }
            ));
            Ok(())
        },
    )
    .with_context(|| format!("{}: load path failed", scenario.source))?;
    progress.finish();
    let title = scenario
        .file
        .title
        .clone()
        .unwrap_or_else(|| "scenario".to_string());
    let mut datasets = Vec::new();
    let mut rows = Vec::new();
    let mut cases = Vec::new();
    // (step, load factor, notes of its solution) of the steps whose solution has notes.
    let mut noted = Vec::new();
    for s in &steps {
        let folder = step_folder(s.step, n);
        let mut summary = Summary::new(
            &s.problem,
            &settings,
            &s.solution,
            scenario.file.title.clone(),
            &scenario.source,
        );
        if !summary.notes.is_empty() {
            noted.push((s.step, s.factor, summary.notes.clone()));
        }
        summary.prepend_notes(notes.clone());
        let step_title = format!("{title}, load factor {}", significant(s.factor));
        let mut extra = Vec::new();
        if output.vtu {
            extra.push((
                "solution.vtu",
                solution_vtu(&s.problem, &s.solution, &step_title, s.factor)?.to_bytes(),
            ));
            datasets.push((s.factor, format!("{folder}/solution.vtu")));
        }
        extra.extend(solution_figures(&s.problem, &s.solution, &step_title)?);
        ctx.output.with(|set| {
            Ok(write_results(
                set,
                &folder,
                &s.problem,
                &s.solution,
                &step_title,
                output.summary.then_some(&summary),
                false,
                &extra,
            )?)
        })?;
        rows.push(PathRow::of(s));
        cases.push(Case {
            label: format!("{folder} (λ {:.3})", s.factor),
            problem: s.problem.clone(),
            solution: s.solution.clone(),
            summary,
        });
    }
    print_step_notes(c, &noted, n);
    let dim = problem.mesh().dim();
    ctx.output.with(|set| {
        if !datasets.is_empty() {
            let list: Vec<(f64, &str)> = datasets.iter().map(|(t, f)| (*t, f.as_str())).collect();
            set.write(
                "solution.pvd",
                hemicontact::io::pvd::collection(&list)?.as_bytes(),
            )?;
        }
        set.write("load_path.csv", path_csv(&rows, dim).as_bytes())?;
        Ok(())
    })?;
    let last = steps.last().map(|s| &s.solution.report);
    if let Some(r) = last.filter(|r| !r.converged) {
        c.warn(format_args!(
            "warning: step {}/{n} did not converge: {}; the path stops there: it was written, \
             marked \"converged\": false, and the later steps were not solved",
            steps.len(),
            r.message
        ));
    }
    let outcome = if last.is_some_and(|r| r.converged) && steps.len() == n {
        Outcome::Done
    } else {
        Outcome::NotConverged
    };
    Ok((cases, outcome))
}

/// Prints the notes of the solutions of a path of `n` steps (the small-deformation check),
/// given as (step, load factor, notes) for the steps that have any: those of the first
/// such step, and how many later steps have notes (each step's `summary.json` lists its
/// own).
fn print_step_notes(c: &crate::console::Console, noted: &[(usize, f64, Vec<String>)], n: usize) {
    let Some((step, factor, notes)) = noted.first() else {
        return;
    };
    for note in notes {
        c.warn(format_args!(
            "note: step {step}/{n} (load factor {}): {note}",
            significant(*factor)
        ));
    }
    if noted.len() > 1 {
        c.warn(format_args!(
            "note: {} later step(s) have such notes too, the last at step {}/{n}; each \
             step's summary.json lists its own",
            noted.len() - 1,
            noted[noted.len() - 1].0
        ));
    }
}
