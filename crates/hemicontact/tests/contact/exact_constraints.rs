//! Verification of the exact constraints (augmented Lagrangian): ideal locking, Signorini
//! contact, exact stick/slip.
//!
//! - hand-derived solutions: a block locked in uniaxial compression (uniform strain on the
//!   boundary of B with a known multiplier), a block pressed onto a rigid Signorini
//!   foundation (known contact pressure), a block sheared over a Tresca foundation (a
//!   sliding block carries exactly the friction bound; a sticking one does not slip);
//! - limits: nearly locking → ideal locking as C_κ → ∞, normal compliance → Signorini as
//!   c_ν → ∞, regularized friction (19) → exact friction as ρ → 0, each at the rate 1/C,
//!   1/c_ν, ρ;
//! - the KKT certificate of the paper's example with exact constraints.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use common::{assert_certified, lame, problem, rel};
use hemicontact::solver::SolverSettings;
use hemicontact::solver::{solve, FrictionState, NormalState, Solution};

const E: f64 = 1000.0;
const NU: f64 = 0.3;

/// Certified (common::assert_certified) and the KKT residuals of the exact constraints below
/// `tol`, with nonnegative multipliers.
#[track_caller]
fn assert_kkt(s: &Solution, tol: f64) {
    assert_certified(s, tol);
    let kkt = s
        .report
        .certificate
        .kkt
        .as_ref()
        .expect("a KKT certificate");
    assert!(kkt.worst() < tol, "KKT residuals {kkt:?}");
    assert!(kkt.locking_min_multiplier >= 0.0 && kkt.contact_min_multiplier >= 0.0);
}

/// Cell strain (ε_xx, ε_yy, ε_xy) of a P1 triangle, computed here from the nodal values.
fn strains(p: &hemicontact::problem::Problem, u: &[f64]) -> Vec<[f64; 3]> {
    let m = p.mesh();
    (0..m.n_cells())
        .map(|c| {
            let v = m.cell(c);
            let x: Vec<&[f64]> = v.iter().map(|&n| m.node(n as usize)).collect();
            let det = (x[1][0] - x[0][0]) * (x[2][1] - x[0][1])
                - (x[2][0] - x[0][0]) * (x[1][1] - x[0][1]);
            // Gradients of the hat functions.
            let g = [
                [(x[1][1] - x[2][1]) / det, (x[2][0] - x[1][0]) / det],
                [(x[2][1] - x[0][1]) / det, (x[0][0] - x[2][0]) / det],
                [(x[0][1] - x[1][1]) / det, (x[1][0] - x[0][0]) / det],
            ];
            let mut e = [0.0; 3];
            for a in 0..3 {
                let (ux, uy) = (u[2 * v[a] as usize], u[2 * v[a] as usize + 1]);
                e[0] += g[a][0] * ux;
                e[1] += g[a][1] * uy;
                e[2] += 0.5 * (g[a][1] * ux + g[a][0] * uy);
            }
            e
        })
        .collect()
}

/// A unit block on rollers (left: x fixed, bottom: y fixed), pressed by p on top, with
/// ideal locking `|tr ε| ≤ θ`. Elastically `tr ε = −p / (2(λ+G))` (plane strain); for
/// `p > 2(λ+G)θ` the block locks: `σ = Aε − λ_m I` with `tr ε = −θ`, `σ_xx = 0`,
/// `σ_yy = −p`, so `ε_xx − ε_yy = p/(2G)`, `ε_xx = (−θ + p/2G)/2`, `ε_yy = (−θ − p/2G)/2`,
/// and the multiplier `λ_m = p/2 − (λ+G)θ > 0` in every cell.
#[test]
fn block_locked_in_uniaxial_compression_matches_hand_solution() {
    let theta = 0.01;
    let (lam, g) = lame(E, NU, false);
    let p_lock = 2.0 * (lam + g) * theta;
    for (p, locked) in [(3.0 * p_lock, true), (0.5 * p_lock, false)] {
        let text = format!(
            r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [4, 4]
[material]
young = {E}
poisson = {NU}
[locking]
set = "limited-compressibility"
theta = {theta}
treatment = "exact"
[[dirichlet]]
part = "left"
components = ["x"]
[[dirichlet]]
part = "bottom"
components = ["y"]
[[loads.traction]]
part = "top"
value = [0.0, {}]
"#,
            -p
        );
        let prob = problem(&text);
        let s = solve(&prob, &SolverSettings::default()).unwrap();
        assert_kkt(&s, 1e-8);
        let (exx, eyy, lm) = if locked {
            (
                0.5 * (-theta + p / (2.0 * g)),
                0.5 * (-theta - p / (2.0 * g)),
                p / 2.0 - (lam + g) * theta,
            )
        } else {
            // Uniaxial stress, plane strain.
            let eyy = -p * (1.0 - NU * NU) / E;
            (p * NU * (1.0 + NU) / E, eyy, 0.0)
        };
        for (c, e) in strains(&prob, &s.u).iter().enumerate() {
            assert!(
                rel(e[0], exx, 1e-3) < 1e-8,
                "cell {c}: ε_xx {} vs {exx}",
                e[0]
            );
            assert!(
                rel(e[1], eyy, 1e-3) < 1e-8,
                "cell {c}: ε_yy {} vs {eyy}",
                e[1]
            );
            assert!(e[2].abs() < 1e-10, "cell {c}: ε_xy {}", e[2]);
            let l = s.locking_multiplier[c];
            assert!(rel(l, lm, 1.0) < 1e-8, "cell {c}: multiplier {l} vs {lm}");
        }
        let kkt = s.report.certificate.kkt.as_ref().unwrap();
        assert_eq!(kkt.n_locked, if locked { prob.mesh().n_cells() } else { 0 });
    }
}

/// Signorini scenario: a unit block, left side on rollers, top moved down by δ (x free),
/// bottom frictionless on a rigid foundation at gap g.
fn signorini_block(delta: f64, gap: f64, friction: &str) -> String {
    format!(
        r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [4, 4]
[material]
young = {E}
poisson = {NU}
[[dirichlet]]
part = "left"
components = ["x"]
[[dirichlet]]
part = "top"
components = ["y"]
value = [0.0, {}]
[[contact]]
part = "bottom"
gap = {gap}
law = "signorini"
{friction}
"#,
        -delta
    )
}

/// A unit block pressed onto a rigid Signorini foundation (its top moved by (s, −δ)),
/// sides free, with Tresca friction of bound F on the bottom; `friction` gives the
/// potential lines.
fn sheared_block(s: f64, f: f64, friction: &str) -> String {
    format!(
        r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [4, 4]
[material]
young = {E}
poisson = {NU}
[[dirichlet]]
part = "top"
value = [{s}, -0.02]
[[contact]]
part = "bottom"
law = "signorini"
[contact.friction]
bound = "tresca"
mu = {{ law = "constant", mu = {f} }}
{friction}
"#
    )
}

/// The block touches the foundation when δ > g: then `u_y = −g` on the bottom exactly, the
/// stress is uniaxial `σ_yy = E/(1−ν²) ε_yy` with `ε_yy = −(δ−g)`, and every contact point
/// carries the pressure `p = −σ_yy`; for δ < g it translates rigidly, separated.
#[test]
fn block_on_signorini_foundation_matches_hand_solution() {
    let gap = 0.01;
    for (delta, touches) in [(0.03, true), (0.005, false)] {
        let prob = problem(&signorini_block(delta, gap, ""));
        let s = solve(&prob, &SolverSettings::default()).unwrap();
        assert_kkt(&s, 1e-8);
        let p = if touches {
            E / (1.0 - NU * NU) * (delta - gap)
        } else {
            0.0
        };
        assert_eq!(s.contact.len(), 5);
        for c in &s.contact {
            let uy = s.u[2 * c.node as usize + 1];
            if touches {
                assert!(rel(uy, -gap, 1.0) < 1e-10, "u_y {uy} vs −g");
                assert!(
                    rel(c.pressure, p, 1.0) < 1e-8,
                    "pressure {} vs {p}",
                    c.pressure
                );
                // The equilibrium force is the pressure on the node's share of Γ_C.
                assert!(rel(-c.force_normal, c.weight * p, 1.0) < 1e-8);
                assert_eq!(c.normal_state, NormalState::Contact);
            } else {
                assert!(rel(uy, -delta, 1.0) < 1e-10, "u_y {uy} vs −δ");
                assert_eq!(c.pressure, 0.0);
                assert_eq!(c.normal_state, NormalState::Separated);
            }
        }
    }
}

/// A block pressed onto a rigid foundation (δ) and sheared by moving its top sideways by s,
/// with exact Tresca friction of bound F. When the whole contact slides, the foundation's
/// tangential force is exactly `Σ w_i F = F L` (L = 1), so the top's x-reaction is `F L`
/// (the regularized norm would carry slightly less); when s is small and F large
/// everything sticks, with zero slip to round-off.
#[test]
fn sheared_block_on_tresca_foundation_slides_at_the_bound_or_sticks() {
    // Sliding: F = 10 against the shear of s = 0.2; sticking: F = 200 also holds the
    // Poisson expansion of the pressed block (δ = 0.02) at the corners.
    for (s_top, f, slides) in [(0.2, 10.0, true), (1e-3, 200.0, false)] {
        let text = sheared_block(s_top, f, "exact = true");
        let prob = problem(&text);
        let s = solve(&prob, &SolverSettings::default()).unwrap();
        assert_kkt(&s, 1e-8);
        let top = prob.mesh().part_index("top").unwrap();
        let top_nodes = prob.mesh().part_nodes(top);
        let rx: f64 = top_nodes.iter().map(|&n| s.reactions[2 * n as usize]).sum();
        let u_max = s.u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if slides {
            assert!(rel(rx, f, 1.0) < 1e-8, "top x-reaction {rx} vs F L = {f}");
            assert!(s
                .contact
                .iter()
                .all(|c| c.friction_state == FrictionState::Slip));
        } else {
            assert!(rx < 0.9 * f, "top x-reaction {rx} reaches the bound {f}");
            for c in &s.contact {
                assert_eq!(c.friction_state, FrictionState::Stick);
                assert!(c.slip <= 1e-12 * u_max, "sticking slip {:e}", c.slip);
            }
        }
    }
}

/// The paper's example at n = 16 with a scenario text edit.
fn paper(file: &str, edits: &[(&str, &str)]) -> String {
    let mut text = std::fs::read_to_string(format!(
        "{}/../../scenarios/{file}",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
    .replace("n = [128, 128]", "n = [16, 16]");
    for (a, b) in edits {
        assert!(text.contains(a), "{a} not in {file}");
        text = text.replace(a, b);
    }
    text
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

/// Checks that `diffs[k]` decreases like the parameter (ratio 10 per step, ±30 %).
#[track_caller]
fn assert_linear_rate(label: &str, diffs: &[f64]) {
    for w in diffs.windows(2) {
        let ratio = w[0] / w[1];
        assert!(
            (7.0..13.0).contains(&ratio),
            "{label}: differences {diffs:?}, ratio {ratio} (expected 10)"
        );
    }
}

/// Solves the scenario `text(p)` for each parameter `p` and returns the largest nodal
/// displacement difference to `limit` for each (asserting convergence).
fn distances(limit: &Solution, params: &[f64], text: impl Fn(f64) -> String) -> Vec<f64> {
    params
        .iter()
        .map(|&p| {
            let s = solve(&problem(&text(p)), &SolverSettings::default()).unwrap();
            assert!(
                s.report.converged,
                "not converged at {p}: {}",
                s.report.message
            );
            max_diff(&s.u, &limit.u)
        })
        .collect()
}

/// Nearly locking → ideal locking: the penalty solutions approach the ideal one like 1/C_κ.
#[test]
fn nearly_locking_tends_to_ideal_locking_like_one_over_c_kappa() {
    let ideal = solve(
        &problem(&paper("paper-ideal.toml", &[])),
        &SolverSettings::default(),
    )
    .unwrap();
    assert_kkt(&ideal, 1e-8);
    let diffs = distances(&ideal, &[1e5, 1e6, 1e7], |c| {
        paper(
            "paper-ideal.toml",
            &[(
                "treatment = \"exact\"",
                &format!("treatment = \"penalty\"\nc_kappa = {c}"),
            )],
        )
    });
    assert_linear_rate("C_κ → ∞", &diffs);
}

/// Normal compliance → Signorini: like 1/c_ν.
#[test]
fn normal_compliance_tends_to_signorini_like_one_over_c_nu() {
    let sig = solve(
        &problem(&paper("paper-signorini.toml", &[])),
        &SolverSettings::default(),
    )
    .unwrap();
    assert_kkt(&sig, 1e-8);
    let kkt = sig.report.certificate.kkt.as_ref().unwrap();
    assert!(sig.report.certificate.n_contact > 0 && kkt.n_constraints.1 > 0);
    let diffs = distances(&sig, &[1e7, 1e8, 1e9], |c| {
        paper(
            "paper-signorini.toml",
            &[(
                "law = \"signorini\"",
                &format!("law = \"normal-compliance\"\nc_nu = {c}"),
            )],
        )
    });
    assert_linear_rate("c_ν → ∞", &diffs);
}

/// Regularized friction (19) → exact friction: like ρ, on the sticking sheared block (where
/// the regularization matters at first order: a "sticking" point of (19) creeps by O(ρ)).
#[test]
fn regularized_friction_tends_to_exact_friction_like_rho() {
    let exact = solve(
        &problem(&sheared_block(1e-3, 10.0, "exact = true")),
        &SolverSettings::default(),
    )
    .unwrap();
    assert_kkt(&exact, 1e-8);
    let diffs = distances(&exact, &[1e-5, 1e-6, 1e-7], |rho| {
        sheared_block(
            1e-3,
            10.0,
            &format!("potential = \"regularized\"\nrho = {rho}"),
        )
    });
    assert_linear_rate("ρ → 0", &diffs);
}

/// The three paper variants with exact constraints are certified (KKT ≤ 1e-8) and mirror
/// symmetric.
#[test]
fn paper_example_with_exact_constraints_is_certified() {
    for file in ["paper-ideal.toml", "paper-signorini.toml"] {
        let prob = problem(&paper(file, &[]));
        let s = solve(&prob, &SolverSettings::default()).unwrap();
        assert_kkt(&s, 1e-8);
        assert!(s.report.certificate.n_contact > 0, "{file}: no contact");
    }
}

/// Ideal locking for each of the three sets, with Hooke and with the strain-stiffening
/// Hencky law, on the paper's example (n = 16): certified, with locked cells.
#[test]
fn ideal_locking_of_every_set_and_material_is_certified() {
    let sets = [
        (
            "set = \"limited-compressibility\"\ntheta = 0.16",
            "limited compressibility",
        ),
        ("set = \"prager\"\nkappa = 0.1", "Prager"),
        ("set = \"ball\"\nradius = 0.2", "ball"),
    ];
    let materials = [
        ("poisson = 0.3", "Hooke"),
        (
            "poisson = 0.3\nmodel = \"hencky\"\nstiffening = 3.0\nreference_strain = 0.05",
            "Hencky",
        ),
    ];
    for (set, set_name) in sets {
        for (mat, mat_name) in materials {
            let text = paper(
                "paper-ideal.toml",
                &[
                    ("set = \"limited-compressibility\"\ntheta = 0.16", set),
                    ("poisson = 0.3", mat),
                ],
            );
            let s = solve(&problem(&text), &SolverSettings::default()).unwrap();
            assert_kkt(&s, 1e-8);
            let kkt = s.report.certificate.kkt.as_ref().unwrap();
            assert!(kkt.n_locked > 0, "{set_name} + {mat_name}: nothing locked");
        }
    }
}

/// 3D: the paper's cube with ideal locking, Signorini walls (at a gap the coarse cube
/// reaches) and exact friction: certified, in contact, and mirror symmetric.
#[test]
fn cube_with_all_exact_constraints_is_certified_and_symmetric() {
    let mut text = std::fs::read_to_string(format!(
        "{}/../../scenarios/paper3d.toml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
    .replace("n = [16, 16, 16]", "n = [4, 4, 4]")
    .replace(
        "treatment = \"penalty\"\nc_kappa = 10000.0",
        "treatment = \"exact\"",
    )
    .replace(
        "law = \"normal-compliance\"\nc_nu = 10000.0",
        "law = \"signorini\"",
    )
    .replace("gap = 0.1", "gap = 0.05")
    .replace(
        "mu = { law = \"exponential\", a = 0.4, b = 0.1, beta = 100.0 }",
        "mu = { law = \"exponential\", a = 0.4, b = 0.1, beta = 100.0 }\nexact = true",
    );
    assert!(text.contains("signorini") && text.contains("exact = true"));
    text = text.replace("[output]", "[output]\n");
    let prob = problem(&text);
    let s = solve(&prob, &SolverSettings::default()).unwrap();
    assert_kkt(&s, 1e-8);
    let cert = &s.report.certificate;
    assert!(cert.n_contact > 0, "no contact");
    // Mirror symmetry x ↦ 4 − x: u_x(x) = −u_x(x̄), u_y, u_z equal.
    let m = prob.mesh();
    let scale = s.u.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    for n in 0..m.n_nodes() {
        let x = m.node(n);
        let mirror = (0..m.n_nodes())
            .find(|&k| {
                let y = m.node(k);
                (y[0] - (4.0 - x[0])).abs() < 1e-12
                    && (y[1] - x[1]).abs() < 1e-12
                    && (y[2] - x[2]).abs() < 1e-12
            })
            .unwrap();
        assert!((s.u[3 * n] + s.u[3 * mirror]).abs() <= 1e-7 * scale);
        assert!((s.u[3 * n + 1] - s.u[3 * mirror + 1]).abs() <= 1e-7 * scale);
        assert!((s.u[3 * n + 2] - s.u[3 * mirror + 2]).abs() <= 1e-7 * scale);
    }
}

/// A non-finite iterate is caught as a numerical breakdown that names where it happened
/// (here the starting point: there is no good iterate to keep, so it is an error).
#[test]
fn non_finite_start_is_a_reported_breakdown() {
    let prob = problem(&signorini_block(0.03, 0.01, ""));
    let mut u = prob.prescribed_displacement();
    let dofs = prob.dof_map();
    let free = (0..u.len()).find(|&k| !dofs.is_fixed(k)).unwrap();
    u[free] = f64::NAN;
    let err = hemicontact::solver::solve_from(&prob, &SolverSettings::default(), u).unwrap_err();
    let msg = err.to_string();
    assert!(
        msg.contains("numerical breakdown") && msg.contains("Newton step 0"),
        "{msg}"
    );
}

/// The figure of a 3D solution is a front view: the deformed front facets, the visible
/// contact nodes and the foundations seen edge-on (two walls facing x).
#[cfg(feature = "plot")]
#[test]
fn three_d_figure_is_a_front_view() {
    use hemicontact::plot::{deformed, Prim};
    let text = std::fs::read_to_string(format!(
        "{}/../../scenarios/paper3d.toml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
    .replace("n = [16, 16, 16]", "n = [4, 4, 4]")
    .replace("gap = 0.1", "gap = 0.05");
    let prob = problem(&text);
    let s = solve(&prob, &SolverSettings::default()).unwrap();
    assert!(s.report.converged);
    let fig = deformed::figure(&prob, &s, "3D");
    // Front facets (y = 0): 4 × 4 squares, 2 triangles each, 3 edges each.
    let segments: Vec<usize> = fig
        .prims
        .iter()
        .filter_map(|p| match p {
            Prim::Segments { segments, .. } => Some(segments.len()),
            _ => None,
        })
        .collect();
    assert_eq!(segments[0], 4 * 4 * 2 * 3, "{segments:?}");
    // Foundations of the left and right walls (facets seen edge-on), 3 edges per facet.
    assert_eq!(segments[1], 2 * 4 * 4 * 2 * 3, "{segments:?}");
    let dots = fig
        .prims
        .iter()
        .filter(|p| matches!(p, Prim::Circle { .. }))
        .count();
    // Contact nodes on the front face (5 × 5 minus the 5 clamped bottom nodes; edge nodes
    // carry two points) plus the 3 legend dots.
    assert!(dots > 20 + 3, "{dots} dots");
}
