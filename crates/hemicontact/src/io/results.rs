//! The result files of one solution, written into a folder of a [`ResultSet`]:
//! `solution.vtu` ([`super::vtu::solution_vtu`]), `contact.csv` ([`super::csv::contact_csv`]),
//! extra files, and last `summary.json` ([`super::summary::Summary`]) listing them all.

use super::csv::contact_csv;
use super::result_set::ResultSet;
use super::summary::{Summary, SUMMARY_FILE};
use super::vtu::solution_vtu;
use crate::error::Result;
use crate::problem::Problem;
use crate::solver::Solution;
use std::path::PathBuf;

/// Writes the result files of a solution titled `title` into the sub-folder `folder` of the
/// result set `set` (`""`: its root): `solution.vtu` (if `vtu`; the title and the load
/// factor 1 in its `FieldData`), `contact.csv` (if the problem has
/// contact), the `extra` files (name within the folder, content), and last, if `summary` is
/// given, `summary.json`, whose `files` lists every file of the folder, itself included.
/// Returns the final paths written.
///
/// # Errors
/// [`crate::Error::Io`] if a file cannot be written.
pub fn write_results(
    set: &mut ResultSet,
    folder: &str,
    problem: &Problem,
    solution: &Solution,
    title: &str,
    summary: Option<&Summary>,
    vtu: bool,
    extra: &[(&str, Vec<u8>)],
) -> Result<Vec<PathBuf>> {
    let name = |file: &str| {
        if folder.is_empty() {
            file.to_string()
        } else {
            format!("{}/{file}", folder.trim_end_matches('/'))
        }
    };
    let mut written = Vec::new();
    if vtu {
        written.push(set.write(
            &name("solution.vtu"),
            &solution_vtu(problem, solution, title, 1.0)?.to_bytes(),
        )?);
    }
    if !problem.contact.is_empty() {
        written.push(set.write(
            &name("contact.csv"),
            contact_csv(problem, solution).as_bytes(),
        )?);
    }
    for (file, bytes) in extra {
        written.push(set.write(&name(file), bytes)?);
    }
    if let Some(summary) = summary {
        let mut summary = summary.clone();
        summary.files = set.files_in(folder);
        summary.files.push(SUMMARY_FILE.to_string());
        summary.files.dedup();
        let text = serde_json::to_string_pretty(&summary)
            .map_err(|e| crate::Error::Breakdown(format!("summary serialization: {e}")))?;
        written.push(set.write(&name(SUMMARY_FILE), text.as_bytes())?);
    }
    Ok(written)
}

/// The figures `hemicontact solve` writes beside the results of a solution titled `title`:
/// the deformed mesh coloured by the von Mises stress, with its interface tractions
/// (`deformed.svg`, `deformed.png`), and for a 2D problem with contact the contact
/// quantities along each contact part (`interface.svg`, `interface.png`). Empty without
/// the cargo feature `plot`.
///
/// # Errors
/// [`crate::Error::Io`] if the PNG cannot be encoded.
pub fn solution_figures(
    problem: &Problem,
    solution: &Solution,
    title: &str,
) -> Result<Vec<(&'static str, Vec<u8>)>> {
    #[cfg(feature = "plot")]
    {
        let figure = crate::plot::deformed::figure(problem, solution, title);
        let mut files = vec![
            ("deformed.svg", figure.to_svg().into_bytes()),
            ("deformed.png", figure.to_png()?),
        ];
        if let Some(figure) = crate::plot::interface::figure(problem, solution, title) {
            files.push(("interface.svg", figure.to_svg().into_bytes()));
            files.push(("interface.png", figure.to_png()?));
        }
        Ok(files)
    }
    #[cfg(not(feature = "plot"))]
    {
        let _ = (problem, solution, title);
        Ok(Vec::new())
    }
}
