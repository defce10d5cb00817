//! The result files of one solution, written into a folder of a [`ResultSet`]:
//! `solution.vtu` ([`super::vtu::solution_vtu`]), `contact.csv` ([`super::csv::contact_csv`]),
//! extra files, and last `summary.json` ([`super::summary::Summary`]) listing them all.

use super::csv::contact_csv;
use super::result_set::ResultSet;
use super::summary::{Summary, SUMMARY_FILE};
use super::vtu::solution_files;
use crate::error::Result;
use crate::problem::Problem;
use crate::solver::Solution;
use std::path::PathBuf;

/// Writes the result files of a solution titled `title` into the sub-folder `folder` of the
/// result set `set` (`""`: its root): `solution.vtu`, or `solution.pvtu` and its pieces for
/// a solution of several processes (if `vtu`; [`super::vtu::solution_files`], the title and
/// the load factor 1 in its `FieldData`), `contact.csv` (if the problem has
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
    // The two encodings are independent: made in parallel, written in order.
    let (vtu_bytes, csv) = rayon::join(
        || {
            vtu.then(|| solution_files(problem, solution, title, 1.0))
                .transpose()
        },
        || (!problem.contact.is_empty()).then(|| contact_csv(problem, solution)),
    );
    for (file, bytes) in vtu_bytes?.unwrap_or_default() {
        written.push(set.write(&name(&file), &bytes)?);
    }
    if let Some(csv) = csv {
        written.push(set.write(&name("contact.csv"), csv.as_bytes())?);
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

/// A file of a result folder: its name and its bytes.
pub type ResultFile = (&'static str, Vec<u8>);

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
) -> Result<Vec<ResultFile>> {
    #[cfg(feature = "plot")]
    {
        use rayon::prelude::*;
        let (deformed, interface) = rayon::join(
            || crate::plot::deformed::figure(problem, solution, title),
            || crate::plot::interface::figure(problem, solution, title),
        );
        let mut figures = vec![("deformed.svg", "deformed.png", deformed)];
        figures.extend(interface.map(|f| ("interface.svg", "interface.png", f)));
        // Each figure's SVG and PNG are rendered in parallel, listed in a fixed order.
        let rendered: Vec<Result<[ResultFile; 2]>> = figures
            .par_iter()
            .map(|(svg_name, png_name, figure)| {
                let (svg, png) = rayon::join(|| figure.to_svg(), || figure.to_png());
                Ok([(*svg_name, svg.into_bytes()), (*png_name, png?)])
            })
            .collect();
        let mut files = Vec::new();
        for r in rendered {
            files.extend(r?);
        }
        Ok(files)
    }
    #[cfg(not(feature = "plot"))]
    {
        let _ = (problem, solution, title);
        Ok(Vec::new())
    }
}
