//! The solver in 3D (P1 tetrahedra on generated boxes): patch test, a closed-form uniform
//! state, and frictionless normal-compliance contact against a hand solution — the same
//! code paths as 2D with `LD = 12` element kernels and 2D tangent planes at contact nodes.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::solver::convex::minimize;
use hemicontact::solver::newton::{NewtonRecord, NewtonSettings};
use hemicontact::solver::SolverSettings;
use hemicontact::solver::{solve, System};

mod common;

use common::problem;

const E: f64 = 1000.0;
const NU: f64 = 0.3;

/// Lamé constants `(λ, G)` of `E`, `ν` (3D).
fn lame() -> (f64, f64) {
    common::lame(E, NU, false)
}

/// An affine displacement prescribed on the whole boundary of a box is reproduced at the
/// interior nodes to round-off, for both cut patterns.
#[test]
fn patch_test_3d() {
    for pattern in ["uniform", "symmetric"] {
        let mut text = format!(
            "[mesh]\nkind = \"box\"\nsize = [2.0, 1.0, 1.5]\nn = [4, 3, 3]\npattern = \"{pattern}\"\n\
             [material]\nyoung = {E}\npoisson = {NU}\n"
        );
        for part in ["left", "right", "front", "back", "bottom", "top"] {
            text.push_str(&format!("[[dirichlet]]\npart = \"{part}\"\n"));
        }
        let p = problem(&text);
        let a = [0.01, -0.02, 0.03];
        let b = [[0.1, 0.02, -0.03], [0.04, -0.05, 0.06], [-0.07, 0.08, 0.09]];
        let exact = |x: &[f64]| -> [f64; 3] {
            let mut u = a;
            for i in 0..3 {
                for j in 0..3 {
                    u[i] += b[i][j] * x[j];
                }
            }
            u
        };
        let mut system = System::new(&p, &SolverSettings::default()).unwrap();
        let mut u = vec![0.0; 3 * p.mesh().n_nodes()];
        for n in 0..p.mesh().n_nodes() {
            let e = exact(p.mesh().node(n));
            for i in 0..3 {
                if system.dofs.is_fixed(3 * n + i) {
                    u[3 * n + i] = e[i];
                }
            }
        }
        let frozen = hemicontact::solver::Frozen::initial(&system, &p, &u).expect("friction data");
        let settings = NewtonSettings::default();
        let mut eval = hemicontact::solver::Evaluation::new(&system);
        let mut energy = hemicontact::solver::convex::ConvexProblem::new(
            &mut system,
            &mut eval,
            &p,
            &frozen,
            &settings,
            &u,
        );
        let out = minimize(&mut energy, 1e-12, &mut u, &mut NewtonRecord::default()).unwrap();
        assert!(out.converged);
        for n in 0..p.mesh().n_nodes() {
            let e = exact(p.mesh().node(n));
            for i in 0..3 {
                assert!(
                    (u[3 * n + i] - e[i]).abs() < 1e-10,
                    "{pattern}: node {n} comp {i}"
                );
            }
        }
    }
}

/// A unit cube on rollers (left: x, front: y, bottom: z), pressed by p on top, back face
/// free, expanding into a frictionless normal-compliance wall on the right at gap g. The
/// state is uniform: σ_zz = −p, σ_yy = 0, σ_xx = −c_ν(ε_xx − g).
#[test]
fn cube_pressed_against_normal_compliance_wall_3d() {
    let (p, g, c_nu) = (200.0, 0.02, 5.0e4);
    let text = format!(
        r#"
[mesh]
kind = "box"
size = [1.0, 1.0, 1.0]
n = [3, 3, 3]
pattern = "uniform"
[material]
young = {E}
poisson = {NU}
[[dirichlet]]
part = "left"
components = ["x"]
[[dirichlet]]
part = "front"
components = ["y"]
[[dirichlet]]
part = "bottom"
components = ["z"]
[[loads.traction]]
part = "top"
value = [0.0, 0.0, -{p}]
[[contact]]
part = "right"
gap = {g}
c_nu = {c_nu}
"#
    );
    let pr = problem(&text);
    let s = solve(&pr, &SolverSettings::default()).unwrap();
    assert!(s.report.converged, "{}", s.report.message);
    assert!(s.report.certificate.normal_law < 1e-8 && s.report.certificate.equilibrium < 1e-8);
    let (l, mu) = lame();
    // Solve the 3×3 system for (ε_xx, ε_yy, ε_zz) by Cramer's rule.
    let a = [
        [l + 2.0 * mu + c_nu, l, l],
        [l, l + 2.0 * mu, l],
        [l, l, l + 2.0 * mu],
    ];
    let rhs = [c_nu * g, 0.0, -p];
    let det3 = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det3(a);
    let mut e = [0.0; 3];
    for k in 0..3 {
        let mut m = a;
        for r in 0..3 {
            m[r][k] = rhs[r];
        }
        e[k] = det3(m) / d;
    }
    assert!(e[0] > g, "the hand solution must be in contact");
    for n in 0..pr.mesh().n_nodes() {
        let x = pr.mesh().node(n);
        for i in 0..3 {
            assert!(
                (s.u[3 * n + i] - e[i] * x[i]).abs() < 1e-10,
                "node {n} comp {i}"
            );
        }
    }
    let pressure = c_nu * (e[0] - g);
    assert_eq!(s.contact.len(), 16);
    for c in &s.contact {
        assert!((c.pressure - pressure).abs() < 1e-8 * pressure);
    }
}
