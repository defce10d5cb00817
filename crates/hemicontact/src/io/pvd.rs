//! ParaView collections (`.pvd`): one file listing a sequence of datasets, each with its
//! time value, so that ParaView opens them as one time series (a load-stepping history,
//! the levels of a study).
//!
//! ```xml
//! <?xml version="1.0"?>
//! <VTKFile type="Collection" version="1.0" byte_order="LittleEndian">
//! <Collection>
//! <DataSet timestep="0.5" group="" part="0" file="step-1/solution.vtu"/>
//! …
//! </Collection>
//! </VTKFile>
//! ```
//!
//! File paths are relative to the folder of the `.pvd` file, written with `/`.

use crate::error::{Error, Result};
use std::fmt::Write as _;
use std::path::Path;

/// The text of a `.pvd` collection of `datasets`: (time value, path of the dataset relative
/// to the collection's folder) in the order given. For load stepping the time value is the
/// load factor; for a sequence without a physical time, the index.
///
/// # Errors
/// [`Error::Invalid`] if a time value is not finite or smaller than the one before (ParaView
/// needs a non-decreasing time), or a path is empty, absolute, contains `..`, a backslash, a
/// double quote, `<`, `&` or a control character.
pub fn collection(datasets: &[(f64, &str)]) -> Result<String> {
    let mut out = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" \
         byte_order=\"LittleEndian\">\n<Collection>\n",
    );
    let mut previous = f64::NEG_INFINITY;
    for (i, &(time, file)) in datasets.iter().enumerate() {
        if !time.is_finite() || time < previous {
            return Err(Error::Invalid {
                field: format!("pvd dataset {i}: timestep"),
                value: format!("{time:?}"),
                allowed: format!("a finite number at least the previous one ({previous:?})"),
            });
        }
        check_relative_path(i, file)?;
        previous = time;
        let _ = writeln!(
            out,
            "<DataSet timestep=\"{time:?}\" group=\"\" part=\"0\" file=\"{file}\"/>"
        );
    }
    out.push_str("</Collection>\n</VTKFile>\n");
    Ok(out)
}

/// Writes the collection of `datasets` ([`collection`]) to `path` atomically. The paths of
/// the datasets are relative to the folder of `path`.
///
/// # Errors
/// As [`collection`]; [`Error::Io`] if the file cannot be written.
pub fn write(path: &Path, datasets: &[(f64, &str)]) -> Result<()> {
    crate::atomic_file::write(path, collection(datasets)?.as_bytes())
}

/// Refuses a path that is not a plain relative path inside the collection's folder.
fn check_relative_path(i: usize, file: &str) -> Result<()> {
    let bad = file.is_empty()
        || file.starts_with('/')
        || file.split('/').any(|c| c == "..")
        || file
            .chars()
            .any(|c| matches!(c, '\\' | '"' | '<' | '&') || c.is_control());
    if bad {
        return Err(Error::Invalid {
            field: format!("pvd dataset {i}: file"),
            value: format!("{file:?}"),
            allowed: "a non-empty path relative to the collection's folder, with `/` between \
                      folders, no `..`, and none of \\ \" < & or control characters"
                .into(),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn lists_the_datasets_in_order_with_their_times() {
        let text = collection(&[(0.0, "a/solution.vtu"), (0.5, "b.vtu"), (0.5, "c.vtu")]).unwrap();
        let lines: Vec<&str> = text.lines().filter(|l| l.starts_with("<DataSet")).collect();
        assert_eq!(
            lines,
            [
                "<DataSet timestep=\"0.0\" group=\"\" part=\"0\" file=\"a/solution.vtu\"/>",
                "<DataSet timestep=\"0.5\" group=\"\" part=\"0\" file=\"b.vtu\"/>",
                "<DataSet timestep=\"0.5\" group=\"\" part=\"0\" file=\"c.vtu\"/>",
            ]
        );
        assert!(text.contains("<VTKFile type=\"Collection\""));
        assert!(text.ends_with("</Collection>\n</VTKFile>\n"));
        assert_eq!(
            collection(&[]).unwrap().matches("<DataSet").count(),
            0,
            "an empty collection is valid"
        );
    }

    #[test]
    fn refuses_decreasing_or_non_finite_times_and_bad_paths() {
        let e = collection(&[(1.0, "a.vtu"), (0.5, "b.vtu")])
            .unwrap_err()
            .to_string();
        assert!(e.contains("dataset 1") && e.contains("0.5"), "{e}");
        let e = collection(&[(f64::NAN, "a.vtu")]).unwrap_err().to_string();
        assert!(e.contains("NaN"), "{e}");
        for file in [
            "",
            "/abs.vtu",
            "../up.vtu",
            "a\\b.vtu",
            "q\".vtu",
            "a<b.vtu",
        ] {
            let e = collection(&[(0.0, file)]).unwrap_err().to_string();
            assert!(e.contains("dataset 0: file"), "{file}: {e}");
        }
    }
}
