//! The tables of convergence studies ([`crate::study::Study`]): Markdown (`table.md`, one
//! table per case with its reference) and CSV (`table.csv`, one row per case and level).

use crate::study::Study;

/// The studies as a Markdown table.
pub fn markdown(studies: &[Study]) -> String {
    let mut s = String::new();
    for st in studies {
        s.push_str(&format!(
            "### {}\n\nReference: n = {} ({} DOFs, {}), ‖u_ref‖_E = {:.6e}\n\n",
            st.label,
            st.reference_n,
            st.reference_dofs,
            if st.reference_converged {
                "converged"
            } else {
                "NOT converged"
            },
            st.reference_norm
        ));
        s.push_str("| n | h (area) | edge | DOFs | rel. error ‖·‖_E | order in h | order in edge | outer | Newton | time s |\n");
        s.push_str("|---|---|---|---|---|---|---|---|---|---|\n");
        for l in &st.levels {
            let o = |x: Option<f64>| x.map_or("–".to_string(), |v| format!("{v:.3}"));
            s.push_str(&format!(
                "| {} | {:.6e} | {:.6e} | {} | {:.6e} | {} | {} | {} | {} | {:.3}{} |\n",
                l.n,
                l.h_area,
                l.h_edge,
                l.dofs,
                l.error,
                o(l.order_area),
                o(l.order_edge),
                l.outer,
                l.newton,
                l.seconds,
                if l.converged { "" } else { " (not converged)" }
            ));
        }
        s.push('\n');
    }
    s
}

/// The studies as CSV (one row per case and level).
pub fn csv(studies: &[Study]) -> String {
    let mut s = String::from(
        "case,n,h_area,h_edge,dofs,error,order_area,order_edge,outer,newton,converged,seconds\n",
    );
    for st in studies {
        for l in &st.levels {
            let o = |x: Option<f64>| x.map_or(String::new(), |v| format!("{v:e}"));
            s.push_str(&format!(
                "{},{},{:e},{:e},{},{:e},{},{},{},{},{},{:e}\n",
                super::csv::field(&st.label),
                l.n,
                l.h_area,
                l.h_edge,
                l.dofs,
                l.error,
                o(l.order_area),
                o(l.order_edge),
                l.outer,
                l.newton,
                l.converged,
                l.seconds
            ));
        }
    }
    s
}
