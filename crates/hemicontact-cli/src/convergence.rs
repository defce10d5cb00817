//! `convergence FILE`: the convergence study of a scenario on a generated mesh, and the
//! outcome of a study.

use crate::console::Console;
use crate::{study, Outcome, RunContext};
use anyhow::Result;
use hemicontact::study::StudySettings;
use std::path::Path;

/// The convergence study of the scenario `file` on `levels` against the `reference`
/// resolution (squares along x), written into `out` (default `out/<file stem>-convergence`);
/// `nested`: each level starts from the previous level's solution.
pub fn convergence(
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

/// Whether every solve of the `studies` converged (else a warning).
pub fn study_outcome(c: &Console, studies: &[hemicontact::study::Study]) -> Outcome {
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
