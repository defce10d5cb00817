//! # Verification: a certificate above its tolerance never exits 0
//!
//! The same frictional solve, certified at the default tolerance (exit 0), is refused when
//! the certificate tolerance is set below what the equilibrium iteration delivers (Newton
//! stops at a relative residual of 1e-10): exit 3, the results written and marked
//! `"converged": false`, and the message naming the law that failed.

use crate::common::bin;

const SCENARIO: &str = r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [8, 8]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "bottom"
[[loads.traction]]
part = "top"
value = [-200.0, -300.0]
[[contact]]
part = "left"
gap = 0.0
law = "normal-compliance"
c_nu = 1.0e4
[contact.friction]
bound = "coulomb"
mu = { law = "constant", mu = 0.3 }
"#;

#[test]
fn failing_certificate_exits_3_naming_the_law() {
    let tmp = tempfile::tempdir().unwrap();
    for (tol, code) in [("1e-6", 0), ("1e-14", 3)] {
        let path = tmp.path().join(format!("wall-{tol}.toml"));
        std::fs::write(
            &path,
            format!("{SCENARIO}\n[solver]\ncertificate_tolerance = {tol}\n"),
        )
        .unwrap();
        let dir = tmp.path().join(format!("out-{tol}"));
        let out = bin()
            .args([
                "solve",
                path.to_str().unwrap(),
                "--out",
                dir.to_str().unwrap(),
            ])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(code), "tolerance {tol}: {stderr}");
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(summary["converged"], serde_json::Value::Bool(code == 0));
        if code == 3 {
            assert!(
                stderr.contains("not certified") && stderr.contains("residual"),
                "{stderr}"
            );
        }
    }
}
