//! What the commands print of their solves: the files written and the table of cases with
//! their certificates.

use crate::console::Console;
use crate::say;
use std::path::{Path, PathBuf};

/// One row of the terminal table: what it prints of a solve, without the solution.
pub struct Row {
    /// The case's label.
    pub label: String,
    /// Degrees of freedom.
    pub n_dofs: usize,
    /// Outer iterations.
    pub outer: usize,
    /// Newton steps.
    pub newton: usize,
    /// Matrix factorizations.
    pub factorizations: usize,
    /// Wall time of the solve (s).
    pub seconds: f64,
    /// The solution's certificate.
    pub certificate: hemicontact::solver::Certificate,
    /// The largest displacement (m).
    pub max_displacement: f64,
    /// Whether the solve converged.
    pub converged: bool,
    /// The solver's verdict in words.
    pub message: String,
}

impl Row {
    /// The row of a solve labelled `label` with the report `r` and the largest
    /// displacement `max_displacement` (m).
    pub fn new(label: &str, r: &hemicontact::solver::SolveReport, max_displacement: f64) -> Row {
        Row {
            label: label.to_string(),
            n_dofs: r.n_dofs,
            outer: r.outer.len(),
            newton: r.newton.len(),
            factorizations: r.timings.n_factorizations,
            seconds: r.timings.total,
            certificate: r.certificate.clone(),
            max_displacement,
            converged: r.converged,
            message: r.message.clone(),
        }
    }
}

/// Prints the files of a result set once it is in place (and the phase line saying where).
pub fn print_written(c: &Console, dir: &Path, files: &[PathBuf]) {
    c.phase(format_args!(
        "written to {} ({} files)",
        dir.display(),
        files.len()
    ));
    for p in files {
        say!(c, "  wrote {}", p.display());
    }
}

/// Prints the table of `rows` (one line per case) and the exact constraints' residuals of
/// the cases that have them.
pub fn print_table(c: &Console, rows: &[Row]) {
    say!(
        c,
        "{:<22} {:>9} {:>6} {:>7} {:>8} {:>8} {:>7} {:>6} {:>6} {:>10} {:>10}",
        "case",
        "DOFs",
        "outer",
        "Newton",
        "factor.",
        "time s",
        "contact",
        "stick",
        "slip",
        "max |u| m",
        "certif."
    );
    for row in rows {
        let cert = &row.certificate;
        let worst = cert
            .equilibrium
            .max(cert.normal_law)
            .max(cert.friction_law)
            .max(cert.kkt.as_ref().map_or(0.0, |k| k.worst()));
        say!(
            c,
            "{:<22} {:>9} {:>6} {:>7} {:>8} {:>8.3} {:>7} {:>6} {:>6} {:>10.4e} {:>10.1e}{}",
            row.label,
            row.n_dofs,
            row.outer,
            row.newton,
            row.factorizations,
            row.seconds,
            cert.n_contact,
            cert.n_stick,
            cert.n_slip,
            row.max_displacement,
            worst,
            if row.converged { "" } else { "  NOT CONVERGED" }
        );
    }
    for row in rows {
        if let Some(k) = &row.certificate.kkt {
            let (cells, points, friction) = k.n_constraints;
            say!(
                c,
                "KKT ({}): exact constraints, relative residuals",
                row.label
            );
            if cells > 0 {
                say!(
            c,
                    "  ideal locking  {cells} cells, {} locked: violation {:.1e}, complementarity {:.1e}, min multiplier/max {:.1e}",
                    k.n_locked,
                    k.locking_violation,
                    k.locking_complementarity,
                    k.locking_min_multiplier
                );
            }
            if points > 0 {
                say!(
            c,
                    "  Signorini      {points} points: violation {:.1e}, complementarity {:.1e}, min pressure/max {:.1e}",
                    k.contact_violation,
                    k.contact_complementarity,
                    k.contact_min_multiplier
                );
            }
            if friction > 0 {
                say!(
            c,
                    "  exact friction {friction} points: largest slip of a sticking point {:.1e} (relative to max |u|)",
                    k.stick_slip
                );
            }
        }
    }
}
