//! `solve` of a scenario with `[loading]`: the load path
//! ([`hemicontact::loading::for_each_step`]) written as one result set, each step as it is
//! solved: each step's results in `step-001/`, `step-002/`, … (the figures in the last
//! step's folder only), the ParaView collection `solution.pvd` over the steps'
//! `solution.vtu` (time value = load factor) and the table `load_path.csv`.

use crate::console::significant_seconds;
use crate::table::Row;
use crate::{Outcome, RunContext};
use anyhow::{Context, Result};
use hemicontact::display::significant;
use hemicontact::io::results::{solution_figures, write_results};
use hemicontact::io::summary::Summary;
use hemicontact::io::vtu::solution_files;
use hemicontact::loading::{for_each_step, path_csv, LoadStep, PathRow};
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
/// set (begun by the caller, who commits it), each step as soon as it is solved: only the
/// rows of `load_path.csv` and of the terminal table are kept, not the steps. Returns the
/// table rows and the outcome: not converged if a step did not converge (the path stops
/// there; that step is written, marked `"converged": false`).
///
/// The figures (`deformed`, `interface`) are drawn for the last step only (the last load
/// factor, or the step that did not converge): drawing them is most of the cost of a step
/// of a small problem, and `solution.pvd` shows every step.
pub fn solve_path(
    ctx: &RunContext,
    problem: &Problem,
    scenario: &Scenario,
    notes: Vec<String>,
    factors: &[f64],
) -> Result<(Vec<Row>, Outcome)> {
    let c = &ctx.console;
    let settings = scenario.settings()?;
    let output = scenario.output();
    let n = factors.len();
    let progress = c.progress(&format!("step 1/{n}:"));
    let current = Cell::new(1);
    let title = scenario
        .file
        .title
        .clone()
        .unwrap_or_else(|| "scenario".to_string());
    let mut datasets = Vec::new();
    let mut rows = Vec::new();
    let mut table = Vec::new();
    // (step, load factor, notes of its solution) of the steps whose solution has notes.
    let mut noted = Vec::new();
    // Whether the last step handed over converged.
    let mut converged = true;
    // An error of this run's output, which the library's error type cannot carry.
    let mut failure: Option<anyhow::Error> = None;
    let solved = for_each_step(
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
        &mut |s: LoadStep| {
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
            converged = r.converged;
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
            let mut files: Vec<(String, Vec<u8>)> = Vec::new();
            if output.vtu && ctx.output.writes() {
                // solution.vtu, or solution.pvtu (last) and its pieces.
                files = solution_files(&s.problem, &s.solution, &step_title, s.factor)?;
                if let Some((index, _)) = files.last() {
                    datasets.push((s.factor, format!("{folder}/{index}")));
                }
            }
            if (s.step == n || !r.converged) && ctx.output.writes() {
                files.extend(
                    solution_figures(&s.problem, &s.solution, &step_title)?
                        .into_iter()
                        .map(|(name, bytes)| (name.to_string(), bytes)),
                );
            }
            let (names, bytes): (Vec<String>, Vec<Vec<u8>>) = files.into_iter().unzip();
            let extra: Vec<(&str, Vec<u8>)> = names.iter().map(String::as_str).zip(bytes).collect();
            let written = ctx.output.with(|set| {
                Ok(Some(write_results(
                    set,
                    &folder,
                    &s.problem,
                    &s.solution,
                    &step_title,
                    output.summary.then_some(&summary),
                    false,
                    &extra,
                )))
            });
            match written {
                Ok(Some(files)) => {
                    files?;
                }
                Ok(None) => {}
                // The output's own error (no result set): kept, and the path stopped.
                Err(e) => {
                    let text = e.to_string();
                    failure = Some(e);
                    return Err(hemicontact::Error::Breakdown(text));
                }
            }
            rows.push(PathRow::of(&s));
            table.push(Row::new(
                &format!("{folder} (λ {:.3})", s.factor),
                r,
                summary.max_displacement,
            ));
            Ok(())
        },
    );
    if let Some(e) = failure {
        return Err(e);
    }
    let solved = solved.with_context(|| format!("{}: load path failed", scenario.source))?;
    progress.finish();
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
    if !converged {
        if let Some(r) = table.last() {
            c.warn(format_args!(
                "warning: step {solved}/{n} did not converge: {}; the path stops there: it was \
                 written, marked \"converged\": false, and the later steps were not solved",
                r.message
            ));
        }
    }
    let outcome = if converged && solved == n {
        Outcome::Done
    } else {
        Outcome::NotConverged
    };
    Ok((table, outcome))
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
