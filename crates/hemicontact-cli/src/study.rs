//! `hemicontact convergence` and `hemicontact paper --study`: convergence studies with a
//! progress bar (drawn only on a terminal) and their outputs.

use anyhow::Result;
use hemicontact::io::study_table;
use hemicontact::io::summary::SUMMARY_FILE;
use hemicontact::plot::convergence;
use hemicontact::scenario::Scenario;
use hemicontact::study::{self, Progress, Study, StudySettings};
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::Path;

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
    let solves = cases.len() * (settings.levels.len() + 1);
    let bar = if std::io::stderr().is_terminal() {
        ProgressBar::new(solves as u64)
    } else {
        ProgressBar::hidden()
    };
    bar.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let started = std::time::Instant::now();
    let mut studies = Vec::new();
    for (label, scenario) in cases {
        let mut on_progress = |p: Progress| match p {
            Progress::Solving {
                label,
                n,
                reference,
            } => bar.set_message(format!(
                "{label}: {} n = {n}",
                if reference { "reference" } else { "level" }
            )),
            Progress::Solved { .. } => bar.inc(1),
        };
        studies.push(study::run(scenario, label, settings, &mut on_progress)?);
    }
    bar.finish_and_clear();
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
    crate::say!("{table}");
    crate::say!("total {total:.2} s; wrote {}/{{table.md, table.csv, convergence.png, convergence.svg, summary.json}}", out.display());
    Ok(studies)
}
