//! `hemicontact convergence` and `hemicontact paper --study`: convergence studies with a
//! progress bar (drawn only on a terminal; off a terminal one line per solve) and their
//! outputs.

use anyhow::Result;
use hemicontact::io::study_table;
use hemicontact::io::summary::SUMMARY_FILE;
use hemicontact::plot::convergence;
use hemicontact::scenario::Scenario;
use hemicontact::study::{self, Progress, Study, StudySettings};
use std::cell::RefCell;
use std::path::Path;
use std::sync::atomic::AtomicBool;

/// Runs the studies of `cases` (label, scenario) and writes table.md, table.csv,
/// convergence.png/.svg and summary.json into `out`. Returns the studies.
pub fn run(
    ctx: &crate::RunContext,
    cases: &[(String, Scenario)],
    settings: &StudySettings,
    out: &Path,
    title: &str,
) -> Result<Vec<Study>> {
    // Fail before the solves if the results could not be written.
    ctx.output.begin(out)?;
    let c = &ctx.console;
    let solves = cases.len() * (settings.levels.len() + 1);
    let progress = c.progress("");
    c.phase(format_args!(
        "convergence study: {solves} solves (levels {:?}, reference n = {}), results to {}",
        settings.levels,
        settings.reference,
        out.display()
    ));
    let started = std::time::Instant::now();
    let mut studies = Vec::new();
    let mut done = 0;
    for (label, scenario) in cases {
        // What is being solved, for the phase line of the solve when it ends.
        let current = RefCell::new(String::new());
        let mut on_progress = |p: Progress| match p {
            Progress::Solving {
                label,
                n,
                reference,
            } => {
                let what = format!(
                    "{label}: {} n = {n}",
                    if reference { "reference" } else { "level" }
                );
                progress.set_what(&format!("[{}/{solves}] {what}:", done + 1));
                *current.borrow_mut() = what;
            }
            Progress::Solved { seconds } => {
                done += 1;
                let steps = progress.last().map_or(String::new(), |p| {
                    format!(
                        " in {} outer iterations / {} Newton steps",
                        p.iteration + 1,
                        p.newton_steps
                    )
                });
                progress.phase(format_args!(
                    "[{done}/{solves}] {} solved{steps} in {} s",
                    current.borrow(),
                    crate::console::significant_seconds(seconds)
                ));
            }
        };
        studies.push(study::run_observed(
            scenario,
            label,
            settings,
            &mut on_progress,
            &AtomicBool::new(false),
            &|p| progress.observe(p),
        )?);
    }
    progress.finish();
    let total = started.elapsed().as_secs_f64();
    let table = study_table::markdown(&studies);
    let figure = convergence::figure(&studies, title);
    let (svg, png) = (figure.to_svg(), figure.to_png()?);
    ctx.output.with(|set| {
        set.write("table.md", table.as_bytes())?;
        set.write("table.csv", study_table::csv(&studies).as_bytes())?;
        set.write("convergence.svg", svg.as_bytes())?;
        set.write("convergence.png", &png)?;
        let mut files = set.files_in("");
        files.push(SUMMARY_FILE.to_string());
        let summary = serde_json::json!({
            "version": env!("CARGO_PKG_VERSION"),
            "levels": settings.levels,
            "reference": settings.reference,
            "nested_iteration": settings.nested_iteration,
            "total_seconds": total,
            "studies": studies,
            "files": files,
        });
        set.write(
            SUMMARY_FILE,
            serde_json::to_string_pretty(&summary)?.as_bytes(),
        )?;
        Ok(())
    })?;
    ctx.output.commit()?;
    crate::say!(c, "{table}");
    crate::say!(c, "total {total:.2} s; wrote {}/{{table.md, table.csv, convergence.png, convergence.svg, summary.json}}", out.display());
    Ok(studies)
}
