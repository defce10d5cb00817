//! Cells in words, for error messages: a few named, then how many more.

/// Cells named in one error message at most (then "and N more").
pub(crate) const LISTED: usize = 10;

/// Names of at most [`LISTED`] cells, then how many more: "cell 3, cell 7 and 2 more".
pub(crate) fn list_cells(cells: &[usize], name: &dyn Fn(usize) -> String) -> String {
    let mut out: Vec<String> = cells.iter().take(LISTED).map(|&c| name(c)).collect();
    if cells.len() > LISTED {
        out.push(format!("{} more", cells.len() - LISTED));
    }
    match out.len() {
        0 => String::new(),
        1 => out.remove(0),
        n => format!("{} and {}", out[..n - 1].join(", "), out[n - 1]),
    }
}

/// The pairs of cells `folds` (the two cells of an interior facet, on the same side of it)
/// in words: "the cells on both sides of N interior facet(s) lie on the same side of it
/// (they overlap): cell 0 and cell 2; …", at most [`LISTED`] pairs, then how many more.
pub(super) fn overlapping_pairs(
    folds: &[(usize, usize)],
    name: &dyn Fn(usize) -> String,
) -> String {
    let pairs: Vec<String> = folds
        .iter()
        .take(LISTED)
        .map(|&(a, b)| format!("{} and {}", name(a), name(b)))
        .collect();
    format!(
        "the cells on both sides of {} interior facet(s) lie on the same side of it (they \
         overlap): {}{}",
        folds.len(),
        pairs.join("; "),
        if folds.len() > LISTED {
            format!(" and {} more", folds.len() - LISTED)
        } else {
            String::new()
        }
    )
}
