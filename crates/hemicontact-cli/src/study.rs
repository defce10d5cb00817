//! `hemicontact convergence` and `hemicontact paper --study`: convergence studies with a
//! progress bar (drawn only on a terminal) and their outputs.

use anyhow::Result;
use hemicontact::io::atomic::write;
use hemicontact::plot::convergence;
use hemicontact::scenario::Scenario;
use hemicontact::study::{self, Progress, Study, StudySettings};
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::Path;

/// Runs the studies of `cases` (label, scenario) and writes table.md, table.csv,
/// convergence.png/.svg and summary.json into `out`. Returns the studies.
pub fn run(
    cases: &[(String, Scenario)],
    settings: &StudySettings,
    out: &Path,
    title: &str,
) -> Result<Vec<Study>> {
    crate::prepare_output(out)?;
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
    let table = study::markdown(&studies);
    write(&out.join("table.md"), table.as_bytes())?;
    write(&out.join("table.csv"), study::csv(&studies).as_bytes())?;
    convergence::figure(&studies, title).write(out, "convergence")?;
    let summary = serde_json::json!({
        "version": env!("CARGO_PKG_VERSION"),
        "levels": settings.levels,
        "reference": settings.reference,
        "nested_iteration": settings.nested_iteration,
        "total_seconds": total,
        "studies": studies,
    });
    write(
        &out.join("summary.json"),
        serde_json::to_string_pretty(&summary)?.as_bytes(),
    )?;
    crate::say!("{table}");
    crate::say!("total {total:.2} s; wrote {}/{{table.md, table.csv, convergence.png, convergence.svg, summary.json}}", out.display());
    Ok(studies)
}
