//! # Verification: patch tests (affine solutions are reproduced exactly)
//!
//! P1 elements contain every affine displacement field, and a conforming Galerkin method
//! returns the exact solution whenever it lies in the discrete space (the discrete solution
//! is the energy minimizer over a space that contains the exact minimizer). So for data
//! compatible with an affine field, the computed displacement must equal that field at every
//! node, and the strain and stress must be the same constant in every cell, up to round-off
//! and the solver tolerance (here 1e-10 relative). This is MFEM's "perfect approximation"
//! test and the classical engineering patch test, run on both cut patterns.
//!
//! 1. **Displacement patch test:** `u(x) = a + B x` (B not symmetric: includes a rotation)
//!    prescribed on the whole boundary; interior nodes start at zero and must converge to
//!    `u(x)`; every cell must carry `σ = λ tr(ε) I + 2G ε` with `ε = sym(B)`.
//! 2. **Traction patch test (block on rollers):** bottom roller (`u_y = 0`), left roller
//!    (`u_x = 0`), traction `(0, −p)` on top and `(q, 0)` on the right. The exact solution is
//!    the uniform stress `σ_xx = q, σ_yy = −p, σ_xy = 0` and `u = (ε_xx x, ε_yy y)` with `ε`
//!    from inverting Hooke's law by hand; checked for plane strain and plane stress.
//! 3. **Block compressed by a prescribed displacement:** rollers on bottom and left, top
//!    moved by `u_y = −δ`: uniform `ε_yy = −δ/H`, `σ_xx = 0`, `σ_yy = E/(1−ν²) ε_yy` (plane
//!    strain), and the reactions on top and bottom are `±σ_yy L`.
//! 4. **Uniaxial strain (confined compression):** rollers on left, right and bottom, top
//!    pressed by `p`: `ε_xx = 0`, `ε_yy = −p/(λ+2G)`, `σ_xx = λ ε_yy`, `σ_yy = −p`.
//! 5. **Discrete virtual work:** on the paper's square (clamped bottom, `(0, −900)` on top),
//!    the P1 fields `v = (0, y)` and `v = (y, 0)` vanish on Γ_D, so the discrete equilibrium
//!    gives `Σ_T |T| σ_yy,T = ∫_top t_y y = −900 · 4 · 4` and `Σ_T |T| σ_xy,T = 0` exactly,
//!    and the reactions balance the load: `Σ R_y = 900 · 4`, `Σ R_x = 0`.

use crate::common::{lame, problem, rel, solve_with_prescribed_field};
use hemicontact::assembly::BulkAssembler;
use hemicontact::material::StrainEnergy;
use hemicontact::problem::Problem;
use hemicontact::solver::SolverSettings;
use hemicontact::tensor::{Sym, SQRT2};

const YOUNG: f64 = 2000.0;
const POISSON: f64 = 0.3;

/// Cell strains and stresses of the displacement `u`.
fn cell_fields(problem: &Problem, u: &[f64]) -> Vec<(Sym, Sym)> {
    let bulk = BulkAssembler::new(problem.mesh(), &problem.materials()[0]);
    bulk.cell_strains(u)
        .into_iter()
        .map(|e| (e, problem.materials()[0].stress(&e)))
        .collect()
}

/// Asserts that every cell carries the Mandel tensors `eps` and `sigma`.
#[track_caller]
fn assert_uniform(problem: &Problem, u: &[f64], eps: &Sym, sigma: &Sym, tol: f64) {
    let (es, ss) = (eps.norm(), sigma.norm());
    for (c, (e, s)) in cell_fields(problem, u).iter().enumerate() {
        for k in 0..3 {
            assert!(
                (e.c[k] - eps.c[k]).abs() <= tol * es,
                "cell {c}: ε[{k}] = {:e}, exact {:e}",
                e.c[k],
                eps.c[k]
            );
            assert!(
                (s.c[k] - sigma.c[k]).abs() <= tol * ss,
                "cell {c}: σ[{k}] = {:e}, exact {:e}",
                s.c[k],
                sigma.c[k]
            );
        }
    }
}

/// Asserts that the displacement `u` equals `exact` at every node.
#[track_caller]
fn assert_nodal(problem: &Problem, u: &[f64], exact: impl Fn(&[f64]) -> [f64; 2], tol: f64) {
    let mesh = problem.mesh();
    let scale = (0..mesh.n_nodes())
        .map(|n| {
            let v = exact(mesh.node(n));
            v[0].hypot(v[1])
        })
        .fold(0.0, f64::max);
    for n in 0..mesh.n_nodes() {
        let x = mesh.node(n);
        let v = exact(x);
        for i in 0..2 {
            assert!(
                (u[2 * n + i] - v[i]).abs() <= tol * scale,
                "node {n} at {x:?}: u[{i}] = {:e}, exact {:e}",
                u[2 * n + i],
                v[i]
            );
        }
    }
}

fn rectangle_scenario(origin: [f64; 2], size: [f64; 2], n: [usize; 2], pattern: &str) -> String {
    format!(
        r#"
[mesh]
kind = "rectangle"
origin = [{}, {}]
size = [{}, {}]
n = [{}, {}]
pattern = "{pattern}"
[material]
young = {YOUNG}
poisson = {POISSON}
"#,
        origin[0], origin[1], size[0], size[1], n[0], n[1]
    )
}

#[test]
fn affine_displacement_prescribed_on_the_boundary_is_reproduced() {
    let a = [1.0e-3, -2.0e-3];
    let b = [[0.010, -0.020], [0.015, 0.005]];
    let exact = |x: &[f64]| {
        [
            a[0] + b[0][0] * x[0] + b[0][1] * x[1],
            a[1] + b[1][0] * x[0] + b[1][1] * x[1],
        ]
    };
    let (lambda, g) = lame(YOUNG, POISSON, false);
    let eps = Sym::from_matrix(
        2,
        &[
            [b[0][0], 0.5 * (b[0][1] + b[1][0]), 0.0],
            [0.5 * (b[0][1] + b[1][0]), b[1][1], 0.0],
            [0.0; 3],
        ],
    );
    let tr = b[0][0] + b[1][1];
    let sigma = Sym {
        dim: 2,
        c: [
            lambda * tr + 2.0 * g * eps.c[0],
            lambda * tr + 2.0 * g * eps.c[1],
            2.0 * g * eps.c[2],
            0.0,
            0.0,
            0.0,
        ],
    };
    for pattern in ["uniform", "symmetric"] {
        let mut text = rectangle_scenario([0.3, -0.2], [2.0, 1.5], [6, 4], pattern);
        for part in ["bottom", "right", "top", "left"] {
            text += &format!("[[dirichlet]]\npart = \"{part}\"\n");
        }
        let p = problem(&text);
        let (u, steps) = solve_with_prescribed_field(&p, exact);
        assert!(
            steps > 0,
            "{pattern}: the solver took no step (interior nodes started at zero)"
        );
        assert_nodal(&p, &u, exact, 1e-10);
        assert_uniform(&p, &u, &eps, &sigma, 1e-10);
    }
}

/// Inverts the 2D Hooke law `σ_xx = (λ+2G) ε_xx + λ ε_yy`, `σ_yy = λ ε_xx + (λ+2G) ε_yy`
/// (no shear) by Cramer's rule.
fn invert_hooke(lambda: f64, g: f64, sxx: f64, syy: f64) -> (f64, f64) {
    let (a, b) = (lambda + 2.0 * g, lambda);
    let det = a * a - b * b;
    ((a * sxx - b * syy) / det, (a * syy - b * sxx) / det)
}

#[test]
fn block_on_rollers_with_tractions_has_uniform_stress() {
    let (p, q) = (900.0, 250.0);
    for (plane, plane_stress) in [("strain", false), ("stress", true)] {
        for pattern in ["uniform", "symmetric"] {
            let text = rectangle_scenario([0.0, 0.0], [3.0, 2.0], [6, 4], pattern)
                + &format!(
                    r#"plane = "{plane}"
[[dirichlet]]
part = "bottom"
components = ["y"]
[[dirichlet]]
part = "left"
components = ["x"]
[[loads.traction]]
part = "top"
value = [0.0, -{p}]
[[loads.traction]]
part = "right"
value = [{q}, 0.0]
"#
                );
            let pr = problem(&text);
            let solution = hemicontact::solver::solve(&pr, &SolverSettings::default()).unwrap();
            assert!(solution.report.converged, "{}", solution.report.message);
            let (lambda, g) = lame(YOUNG, POISSON, plane_stress);
            let (exx, eyy) = invert_hooke(lambda, g, q, -p);
            let eps = Sym {
                dim: 2,
                c: [exx, eyy, 0.0, 0.0, 0.0, 0.0],
            };
            let sigma = Sym {
                dim: 2,
                c: [q, -p, 0.0, 0.0, 0.0, 0.0],
            };
            assert_uniform(&pr, &solution.u, &eps, &sigma, 1e-10);
            assert_nodal(&pr, &solution.u, |x| [exx * x[0], eyy * x[1]], 1e-10);
            // Independent cross-check of the inversion for plane stress: ε_xx = (q + νp)/E.
            if plane_stress {
                assert!(rel(exx, (q + POISSON * p) / YOUNG, 1e-300) < 1e-12);
                assert!(rel(eyy, (-p - POISSON * q) / YOUNG, 1e-300) < 1e-12);
            }
        }
    }
}

#[test]
fn block_compressed_by_prescribed_displacement() {
    let (length, height, delta) = (3.0, 2.0, 0.01);
    for pattern in ["uniform", "symmetric"] {
        let text = rectangle_scenario([0.0, 0.0], [length, height], [6, 4], pattern)
            + &format!(
                r#"
[[dirichlet]]
part = "bottom"
components = ["y"]
[[dirichlet]]
part = "left"
components = ["x"]
[[dirichlet]]
part = "top"
components = ["y"]
value = [0.0, -{delta}]
"#
            );
        let pr = problem(&text);
        let solution = hemicontact::solver::solve(&pr, &SolverSettings::default()).unwrap();
        assert!(solution.report.converged, "{}", solution.report.message);
        let (lambda, g) = lame(YOUNG, POISSON, false);
        let eyy = -delta / height;
        let exx = -lambda * eyy / (lambda + 2.0 * g); // from σ_xx = 0
        let syy = lambda * exx + (lambda + 2.0 * g) * eyy;
        // Plane strain, uniaxial stress: σ_yy = E/(1−ν²) ε_yy, independently.
        assert!(rel(syy, YOUNG / (1.0 - POISSON * POISSON) * eyy, 1e-300) < 1e-12);
        let eps = Sym {
            dim: 2,
            c: [exx, eyy, 0.0, 0.0, 0.0, 0.0],
        };
        let sigma = Sym {
            dim: 2,
            c: [0.0, syy, 0.0, 0.0, 0.0, 0.0],
        };
        assert_uniform(&pr, &solution.u, &eps, &sigma, 1e-10);
        assert_nodal(&pr, &solution.u, |x| [exx * x[0], eyy * x[1]], 1e-10);
        // Reactions: the top support carries ∫_top σ_yy n_y = σ_yy L, the bottom the
        // opposite, the left roller nothing (σ_xx = 0).
        let mesh = pr.mesh();
        let sum_on = |part: &str, i: usize| -> f64 {
            mesh.part_nodes(mesh.part_index(part).unwrap())
                .iter()
                .map(|&n| solution.reactions[2 * n as usize + i])
                .sum()
        };
        let force = syy * length;
        assert!(
            rel(sum_on("top", 1), force, 1e-300) < 1e-9,
            "top: {}",
            sum_on("top", 1)
        );
        assert!(rel(sum_on("bottom", 1), -force, 1e-300) < 1e-9);
        assert!(sum_on("left", 0).abs() < 1e-9 * force.abs());
    }
}

#[test]
fn confined_compression_is_uniaxial_strain() {
    let p = 900.0;
    for pattern in ["uniform", "symmetric"] {
        let text = rectangle_scenario([0.0, 0.0], [4.0, 4.0], [8, 8], pattern)
            + &format!(
                r#"
[[dirichlet]]
part = "bottom"
components = ["y"]
[[dirichlet]]
part = "left"
components = ["x"]
[[dirichlet]]
part = "right"
components = ["x"]
[[loads.traction]]
part = "top"
value = [0.0, -{p}]
"#
            );
        let pr = problem(&text);
        let solution = hemicontact::solver::solve(&pr, &SolverSettings::default()).unwrap();
        assert!(solution.report.converged, "{}", solution.report.message);
        let (lambda, g) = lame(YOUNG, POISSON, false);
        let eyy = -p / (lambda + 2.0 * g);
        let eps = Sym {
            dim: 2,
            c: [0.0, eyy, 0.0, 0.0, 0.0, 0.0],
        };
        let sigma = Sym {
            dim: 2,
            c: [lambda * eyy, -p, 0.0, 0.0, 0.0, 0.0],
        };
        // σ_xx / σ_yy = ν/(1−ν) for confined compression (oedometer), independently.
        assert!(rel(sigma.c[0] / sigma.c[1], POISSON / (1.0 - POISSON), 1e-300) < 1e-12);
        assert_uniform(&pr, &solution.u, &eps, &sigma, 1e-10);
        assert_nodal(&pr, &solution.u, |x| [0.0, eyy * x[1]], 1e-10);
    }
}

#[test]
fn paper_square_satisfies_discrete_virtual_work() {
    let text = hemicontact::scenario::builtin::paper_elastic(8);
    let pr = problem(&text);
    let solution = hemicontact::solver::solve(&pr, &SolverSettings::default()).unwrap();
    assert!(solution.report.converged, "{}", solution.report.message);
    let mesh = pr.mesh();
    let mut syy = 0.0;
    let mut sxy = 0.0;
    for (c, (_, s)) in cell_fields(&pr, &solution.u).iter().enumerate() {
        let area = hemicontact::geometry::simplex::signed_measure(2, &mesh.cell_coords(c));
        syy += area * s.c[1];
        sxy += area * s.c[2] / SQRT2;
    }
    let load = 900.0 * 4.0;
    assert!(rel(syy, -load * 4.0, 1.0) < 1e-8, "Σ|T|σ_yy = {syy}");
    assert!(sxy.abs() < 1e-8 * load * 4.0, "Σ|T|σ_xy = {sxy}");
    let rx: f64 = solution.reactions.iter().step_by(2).sum();
    let ry: f64 = solution.reactions.iter().skip(1).step_by(2).sum();
    assert!(rel(ry, load, 1.0) < 1e-8, "Σ R_y = {ry}");
    assert!(rx.abs() < 1e-8 * load, "Σ R_x = {rx}");
    // Reactions live on the clamped bottom only.
    let bottom = mesh.part_nodes(mesh.part_index("bottom").unwrap());
    for n in 0..mesh.n_nodes() {
        if bottom.binary_search(&(n as u32)).is_err() {
            assert_eq!(solution.reactions[2 * n], 0.0);
            assert_eq!(solution.reactions[2 * n + 1], 0.0);
        }
    }
}
