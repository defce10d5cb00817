//! End-to-end runs of the paper command and of the non-convergence path through the
//! command-line program.

use crate::common::bin;

/// `hemicontact paper` writes, for both cases, the VTU, the contact table, the summary and
/// the figures, plus the side-by-side figure; the summaries say converged and certify.
#[test]
fn paper_command_writes_all_outputs() {
    let dir = tempfile::tempdir().unwrap();
    let out = bin()
        .args(["paper", "--n", "8", "--out"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("C_kappa = 10000") && stdout.contains("C_kappa = 0"),
        "{stdout}"
    );
    for case in ["locking", "no-locking"] {
        for f in [
            "solution.vtu",
            "contact.csv",
            "summary.json",
            "deformed.png",
            "deformed.svg",
            "interface.png",
            "interface.svg",
        ] {
            let p = dir.path().join(case).join(f);
            assert!(
                p.is_file() && p.metadata().unwrap().len() > 0,
                "missing {}",
                p.display()
            );
        }
        let summary: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(dir.path().join(case).join("summary.json")).unwrap(),
        )
        .unwrap();
        assert_eq!(summary["converged"], true);
        let cert = &summary["report"]["certificate"];
        for key in ["equilibrium", "normal_law", "friction_law"] {
            assert!(cert[key].as_f64().unwrap() < 1e-8, "{key}: {}", cert[key]);
        }
        let csv = std::fs::read_to_string(dir.path().join(case).join("contact.csv")).unwrap();
        // Header + one row per contact point: 7 free nodes per vertical side at n = 8 (the
        // two bottom corners are clamped).
        assert_eq!(csv.lines().count(), 1 + 2 * 8);
    }
    for f in ["comparison.png", "comparison.svg"] {
        assert!(dir.path().join(f).is_file());
    }
    let png = std::fs::read(dir.path().join("comparison.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
}

/// A solve that hits its iteration cap exits with code 3, says so, and still writes its
/// last iterate marked `"converged": false`.
#[test]
fn non_converged_solve_exits_3_and_writes_last_iterate() {
    let dir = tempfile::tempdir().unwrap();
    let text = hemicontact::scenario::builtin::paper(8, 1.0e4).replace(
        "mu = { law = \"exponential\", a = 0.4, b = 0.1, beta = 100.0 }",
        "mu = { law = \"constant\", mu = 5.0 }",
    ) + "\n[solver.outer]\nacceleration = \"none\"\nmax_iterations = 3\n";
    let file = dir.path().join("capped.toml");
    std::fs::write(&file, text).unwrap();
    let out_dir = dir.path().join("out");
    let out = bin()
        .arg("solve")
        .arg(&file)
        .arg("--out")
        .arg(&out_dir)
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(3),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("not converged"), "{stderr}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["converged"], false);
    assert!(out_dir.join("solution.vtu").is_file());
}
