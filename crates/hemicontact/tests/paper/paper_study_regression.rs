//! Regression test of the paper's convergence study: levels 4, 8, 16, 32 against a
//! reference at 64, for C_κ = 10 000 and C_κ = 0, compared with the committed table
//! `tests/data/paper_study_64.json`.
//!
//! What it guards: any change of the numbers the solver produces for the paper's example —
//! discretization, laws, assembly, solver path, tolerances, transfer between meshes, error
//! norm. The solve is deterministic, so the table is reproduced to round-off: the errors
//! within [`REL_TOL`] relative, the orders within the corresponding absolute bound
//! [`ORDER_TOL`]. It also checks two facts that hold independently of the table: every solve
//! converged and the errors decrease strictly under refinement.
//!
//! Why 1e-9: the only variation allowed between correct builds is the grouping of
//! floating-point operations. The assembly sums per-chunk buffers, and the number of chunks
//! follows the number of threads (the reference mesh at n = 64 has 8192 cells, two chunks
//! from two threads on), which moves the displacements by at most 1e-12 relative (test
//! `determinism`). Measured on the committed table: with one thread and with two the
//! errors differ from each other by about 1e-15 relative, and from the table (blessed
//! before later reorderings of the arithmetic, such as the energy norm computed without a
//! scaled copy of the field) by at most 2.1e-11 relative. 1e-9 leaves a margin of 50 over
//! that drift, while a change of the method (a tolerance, a quadrature, a law) moves the
//! errors by far more than 1e-9.
//!
//! Re-blessing, only deliberately: run
//! `HEMICONTACT_BLESS=paper_study cargo test --release -p hemicontact --test paper_study_regression`;
//! the run rewrites the table and then fails on purpose (a blessing run checks nothing).
//! Review the diff of the JSON and commit it with a message that says why the numbers
//! changed.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::scenario::{builtin, Scenario};
use hemicontact::study::{run, StudySettings};

/// Relative tolerance on the errors of the table.
const REL_TOL: f64 = 1e-9;

/// Absolute tolerance on the orders in the element area: an order is
/// `ln(e_{k−1}/e_k) / ln 4`, so errors each within [`REL_TOL`] move it by at most
/// `2·REL_TOL / ln 4 = REL_TOL / ln 2` (to first order).
const ORDER_TOL: f64 = REL_TOL / std::f64::consts::LN_2;

/// Value of `HEMICONTACT_BLESS` that rewrites the table of this test.
const BLESS: &str = "paper_study";

/// One row of the committed table: a case, its levels, their errors and orders.
#[derive(serde::Serialize, serde::Deserialize)]
struct Reference {
    case: String,
    n: Vec<usize>,
    error: Vec<f64>,
    order_area: Vec<f64>,
}

#[test]
fn paper_study_regression() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/paper_study_64.json");
    let mut computed = Vec::new();
    for (case, c_kappa) in [("C_kappa = 10000", 1.0e4), ("C_kappa = 0", 0.0)] {
        let scenario = Scenario::from_str(&builtin::paper(8, c_kappa), "test").unwrap();
        let settings = StudySettings {
            levels: vec![4, 8, 16, 32],
            reference: 64,
            nested_iteration: true,
        };
        let s = run(&scenario, "test", &settings, &mut |_| {}).unwrap();
        assert!(s.reference_converged && s.levels.iter().all(|l| l.converged));
        for w in s.levels.windows(2) {
            assert!(w[1].error < w[0].error, "{case}: errors must decrease");
        }
        computed.push(Reference {
            case: case.into(),
            n: s.levels.iter().map(|l| l.n).collect(),
            error: s.levels.iter().map(|l| l.error).collect(),
            order_area: s
                .levels
                .iter()
                .skip(1)
                .map(|l| l.order_area.unwrap())
                .collect(),
        });
    }
    if std::env::var("HEMICONTACT_BLESS").is_ok_and(|v| v == BLESS) {
        std::fs::write(
            &path,
            serde_json::to_string_pretty(&computed).unwrap() + "\n",
        )
        .unwrap();
        panic!(
            "blessed: {} rewritten; review its diff, commit it saying why the numbers changed, \
             and run again without HEMICONTACT_BLESS",
            path.display()
        );
    }
    let reference: Vec<Reference> =
        serde_json::from_str(&std::fs::read_to_string(&path).expect("reference table")).unwrap();
    assert_eq!(computed.len(), reference.len());
    let mut worst = 0.0f64;
    for (c, r) in computed.iter().zip(&reference) {
        assert_eq!(c.case, r.case);
        assert_eq!(c.n, r.n);
        assert_eq!(c.error.len(), r.error.len());
        assert_eq!(c.order_area.len(), r.order_area.len());
        for (a, b) in c.error.iter().zip(&r.error) {
            let rel = (a - b).abs() / b.abs();
            worst = worst.max(rel);
            assert!(
                rel <= REL_TOL,
                "{}: error {a:e} vs blessed {b:e} (relative difference {rel:e} > {REL_TOL:e})",
                c.case
            );
        }
        for (a, b) in c.order_area.iter().zip(&r.order_area) {
            assert!(
                (a - b).abs() <= ORDER_TOL,
                "{}: order {a} vs blessed {b} (difference {:e} > {ORDER_TOL:e})",
                c.case,
                (a - b).abs()
            );
        }
    }
    eprintln!("largest relative difference of the errors from the table: {worst:e}");
}
