//! `paper`: the paper's example with and without locking side by side, or with `--study`
//! its convergence study.

use crate::console::significant_seconds;
use crate::convergence::study_outcome;
use crate::solve::{outcome, problem_size, run_and_write, Case};
use crate::table::{print_table, print_written};
use crate::{say, study, Outcome, RunContext};
use anyhow::Result;
use hemicontact::display::significant;
use hemicontact::plot::deformed;
use hemicontact::scenario::builtin;
use hemicontact::study::StudySettings;
use std::path::Path;

/// Solves the paper's example on an `n` × `n` mesh with C_κ = 10 000 and C_κ = 0 and writes
/// both cases and the side-by-side figure into `out`.
pub fn paper(ctx: &RunContext, n: usize, out: &Path) -> Result<Outcome> {
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

/// The paper's convergence study on `levels` against the `reference` resolution (squares
/// per side), for both cases, written into `out`.
pub fn paper_study(
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
