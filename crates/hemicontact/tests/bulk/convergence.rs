//! # Verification: convergence to a manufactured solution (plane strain)
//!
//! The exact displacement on the unit square is the quadratic field
//!
//! `u_x = α (x² + x y)`, `u_y = β (y² − x y)`,
//!
//! so `ε_xx = α(2x + y)`, `ε_yy = β(2y − x)`, `ε_xy = (α x − β y)/2`, and with
//! `σ = λ tr(ε) I + 2G ε` the body force `f_0 = −div σ` is the constant
//!
//! `f_0 = −( λ(2α − β) + G(4α − β),  λ(α + 2β) + G(α + 4β) )`
//!
//! (derived by hand; the test re-derives it numerically by central differences, which are
//! exact for these polynomials). The problem is solved with `f_0` as body force and
//! `u_D = u` at the boundary nodes on `n × n` meshes, n = 4, 8, 16, 32 (symmetric pattern).
//!
//! What is verified, and why it must hold:
//!
//! - **Order 1 in the mesh size.** P1 elements approximate `ε(u)` by piecewise constants,
//!   so for a smooth solution `‖u − u_h‖_E = C h + o(h)` with `C > 0` (ε(u) is not constant
//!   here). The observed order `log₂(e_n / e_2n)` must be within ±0.1 of 1, and the errors
//!   must decrease monotonically. `‖v‖_E² = ∫ W(ε(v))` is computed exactly: the
//!   integrand is quadratic on each triangle and the edge-midpoint rule is exact for
//!   quadratics.
//! - **Galerkin optimality (Pythagoras).** With exact loads, `a(u − u_h, v_h) = 0` for every
//!   P1 field `v_h` vanishing on the boundary, and `u_h − I_h u` is such a field (both equal
//!   `u` at boundary nodes). Hence `‖u − I_h u‖² = ‖u − u_h‖² + ‖u_h − I_h u‖²`, and in
//!   particular the solver's answer beats the interpolant. On the uniform meshes `u_h`
//!   coincides with `I_h u` (uniform-grid stencils are exact for quadratics), so the
//!   identity is also checked on meshes with randomly perturbed interior nodes, where
//!   `‖u_h − I_h u‖_E > 0`.
//! - **The library energy norm** `hemicontact::assembly::norms::energy_norm` equals the hand-computed
//!   `(Σ_T |T| W(ε_T))^{1/2}` on a discrete field.

use crate::common;
use crate::common::{lame, problem, solve_with_prescribed_field};
use hemicontact::assembly::BulkAssembler;
use hemicontact::geometry::simplex;
use hemicontact::material::{Hooke, Plane, StrainEnergy};
use hemicontact::mesh::Mesh;
use hemicontact::problem::Problem;
use hemicontact::tensor::SQRT2;

const YOUNG: f64 = 2000.0;
const POISSON: f64 = 0.3;
const ALPHA: f64 = 0.01;
const BETA: f64 = 0.015;

fn exact_u(x: &[f64]) -> [f64; 2] {
    [
        ALPHA * (x[0] * x[0] + x[0] * x[1]),
        BETA * (x[1] * x[1] - x[0] * x[1]),
    ]
}

/// Exact strain `[ε_xx, ε_yy, ε_xy]` (tensor components, not Mandel).
fn exact_strain(x: &[f64]) -> [f64; 3] {
    [
        ALPHA * (2.0 * x[0] + x[1]),
        BETA * (2.0 * x[1] - x[0]),
        0.5 * (ALPHA * x[0] - BETA * x[1]),
    ]
}

/// The hand-derived constant body force `f_0 = −div σ(u)`.
fn body_force(lambda: f64, g: f64) -> [f64; 2] {
    [
        -(lambda * (2.0 * ALPHA - BETA) + g * (4.0 * ALPHA - BETA)),
        -(lambda * (ALPHA + 2.0 * BETA) + g * (ALPHA + 4.0 * BETA)),
    ]
}

/// Energy density `W(e) = λ/2 (tr e)² + G e:e` for tensor components `[e_xx, e_yy, e_xy]`.
fn w(lambda: f64, g: f64, e: [f64; 3]) -> f64 {
    let tr = e[0] + e[1];
    0.5 * lambda * tr * tr + g * (e[0] * e[0] + e[1] * e[1] + 2.0 * e[2] * e[2])
}

/// Checks the hand derivation of `f_0` numerically: strain by central differences of `u`,
/// stress by the library's Hooke law (verified in `laws.rs`), divergence by central
/// differences of the stress.
#[test]
fn manufactured_body_force_is_minus_div_sigma() {
    let (lambda, g) = lame(YOUNG, POISSON, false);
    let hooke = Hooke::from_young_poisson(YOUNG, POISSON, 2, Plane::Strain);
    let h = 1e-3;
    let strain = |x: [f64; 2]| {
        let du = |i: usize, j: usize| {
            let (mut p, mut m) = (x, x);
            p[j] += h;
            m[j] -= h;
            (exact_u(&p)[i] - exact_u(&m)[i]) / (2.0 * h)
        };
        let exy = 0.5 * (du(0, 1) + du(1, 0));
        hemicontact::tensor::Sym {
            dim: 2,
            c: [du(0, 0), du(1, 1), SQRT2 * exy, 0.0, 0.0, 0.0],
        }
    };
    let sigma = |x: [f64; 2]| {
        let s = hooke.stress(&strain(x)).c;
        [s[0], s[1], s[2] / SQRT2] // [σ_xx, σ_yy, σ_xy]
    };
    let f = body_force(lambda, g);
    for x in [[0.2, 0.7], [0.9, 0.1], [0.5, 0.5]] {
        let d = |k: usize, j: usize| {
            let (mut p, mut m) = (x, x);
            p[j] += h;
            m[j] -= h;
            (sigma(p)[k] - sigma(m)[k]) / (2.0 * h)
        };
        let div = [d(0, 0) + d(2, 1), d(2, 0) + d(1, 1)];
        for i in 0..2 {
            assert!(
                (-div[i] - f[i]).abs() < 1e-8 * f[i].abs().max(1.0),
                "at {x:?}: −div σ[{i}] = {}, hand f_0 = {}",
                -div[i],
                f[i]
            );
        }
    }
}

fn scenario(n: usize, f: [f64; 2]) -> Problem {
    let mut text = format!(
        r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [{n}, {n}]
pattern = "symmetric"
[material]
young = {YOUNG:?}
poisson = {POISSON:?}
plane = "strain"
[loads]
body_force = [{:?}, {:?}]
"#,
        f[0], f[1]
    );
    for part in ["bottom", "right", "top", "left"] {
        text += &format!("[[dirichlet]]\npart = \"{part}\"\n");
    }
    problem(&text)
}

/// Per-cell constant strains `[e_xx, e_yy, e_xy]` of a P1 field.
fn p1_strains(problem: &Problem, v: &[f64]) -> Vec<[f64; 3]> {
    BulkAssembler::new(problem.mesh(), &problem.materials()[0])
        .cell_strains(v)
        .into_iter()
        .map(|e| [e.c[0], e.c[1], e.c[2] / SQRT2])
        .collect()
}

/// `‖u − v_h‖_E²` for the exact `u` and a P1 field with cell strains `eh`: on each
/// triangle the integrand is quadratic, integrated exactly by the edge-midpoint rule.
fn error_energy_sq(problem: &Problem, eh: &[[f64; 3]], lambda: f64, g: f64) -> f64 {
    let mesh = problem.mesh();
    let mut sum = 0.0;
    for (c, e_c) in eh.iter().enumerate() {
        let x = mesh.cell_coords(c);
        let area = simplex::signed_measure(2, &x);
        for (a, b) in [(0, 1), (1, 2), (2, 0)] {
            let m = [0.5 * (x[a][0] + x[b][0]), 0.5 * (x[a][1] + x[b][1])];
            let e = exact_strain(&m);
            sum += area / 3.0 * w(lambda, g, [e[0] - e_c[0], e[1] - e_c[1], e[2] - e_c[2]]);
        }
    }
    sum
}

/// `Σ_T |T| W(ε_T)` for per-cell constant strains.
fn discrete_energy_sq(problem: &Problem, e: &[[f64; 3]], lambda: f64, g: f64) -> f64 {
    let mesh = problem.mesh();
    (0..mesh.n_cells())
        .map(|c| simplex::signed_measure(2, &mesh.cell_coords(c)) * w(lambda, g, e[c]))
        .sum()
}

/// The nodal interpolant `I_h u` (DOF order).
fn interpolant(problem: &Problem) -> Vec<f64> {
    let mesh = problem.mesh();
    (0..mesh.n_nodes())
        .flat_map(|k| exact_u(mesh.node(k)))
        .collect()
}

#[test]
fn energy_error_converges_with_order_one() {
    let (lambda, g) = lame(YOUNG, POISSON, false);
    let f = body_force(lambda, g);
    let hooke = Hooke::from_young_poisson(YOUNG, POISSON, 2, Plane::Strain);
    let levels = [4usize, 8, 16, 32];
    let mut errors = Vec::new();
    for &n in &levels {
        let pr = scenario(n, f);
        let (uh, _) = solve_with_prescribed_field(&pr, exact_u);
        let interp = interpolant(&pr);
        let eh = p1_strains(&pr, &uh);
        let err_h = error_energy_sq(&pr, &eh, lambda, g);
        let err_i = error_energy_sq(&pr, &p1_strains(&pr, &interp), lambda, g);
        eprintln!(
            "n = {n:>2}: ‖u − u_h‖_E = {:.6e}  (interpolant: {:.6e})",
            err_h.sqrt(),
            err_i.sqrt()
        );
        // Galerkin optimality: u_h is at least as good as I_h u, which has the same
        // boundary values.
        assert!(
            err_h <= err_i * (1.0 + 1e-9),
            "n = {n}: u_h is worse than I_h u"
        );
        // The library's energy norm agrees with the hand computation on a P1 field.
        let lib = hemicontact::assembly::norms::energy_norm(pr.mesh(), &hooke, &uh);
        let hand = discrete_energy_sq(&pr, &eh, lambda, g);
        assert!(
            (lib * lib - hand).abs() <= 1e-12 * hand,
            "energy_norm {lib:e} vs {hand:e}"
        );
        errors.push(err_h.sqrt());
    }
    let mut orders = Vec::new();
    for k in 1..levels.len() {
        assert!(
            errors[k] < errors[k - 1],
            "error did not decrease: {errors:?}"
        );
        let ratio = levels[k] as f64 / levels[k - 1] as f64;
        orders.push((errors[k - 1] / errors[k]).ln() / ratio.ln());
    }
    eprintln!("observed orders in mesh size: {orders:?}");
    for (k, o) in orders.iter().enumerate() {
        assert!(
            (o - 1.0).abs() <= 0.1,
            "order between n = {} and n = {} is {o:.4}, expected 1 ± 0.1",
            levels[k],
            levels[k + 1]
        );
    }
}

/// On the structured meshes above, `u_h` happens to coincide with `I_h u` at the nodes (as
/// for the 5-point Laplacian, the uniform-grid stencils are exact for quadratics), which
/// makes the optimality check there hold with equality. Randomly perturbing the interior
/// nodes breaks this, and Galerkin orthogonality must then show up as an exact Pythagoras
/// identity with a nonzero `‖u_h − I_h u‖_E`.
#[test]
fn galerkin_orthogonality_on_perturbed_meshes() {
    let (lambda, g) = lame(YOUNG, POISSON, false);
    let f = body_force(lambda, g);
    let mut rng = common::Rng::new(21);
    for n in [8usize, 16] {
        let base = scenario(n, f);
        let mesh = base.mesh();
        let h = 1.0 / n as f64;
        let mut coords = mesh.coords().to_vec();
        for x in coords.chunks_mut(2) {
            let interior = x.iter().all(|&c| c > 0.5 * h && c < 1.0 - 0.5 * h);
            if interior {
                x[0] += 0.2 * h * rng.uniform(-1.0, 1.0);
                x[1] += 0.2 * h * rng.uniform(-1.0, 1.0);
            }
        }
        let perturbed = Mesh::try_new(
            2,
            coords,
            mesh.cells().to_vec(),
            (0..mesh.n_facets())
                .flat_map(|k| mesh.facet(k).to_vec())
                .collect(),
            (0..mesh.n_facets())
                .map(|k| mesh.facet_part(k) as u16)
                .collect(),
            mesh.part_names().to_vec(),
        )
        .expect("perturbed mesh is valid");
        let pr = base.to_builder().mesh(perturbed).build().unwrap();
        let (uh, _) = solve_with_prescribed_field(&pr, exact_u);
        let interp = interpolant(&pr);
        let eh = p1_strains(&pr, &uh);
        let ei = p1_strains(&pr, &interp);
        let err_h = error_energy_sq(&pr, &eh, lambda, g);
        let err_i = error_energy_sq(&pr, &ei, lambda, g);
        let d: Vec<[f64; 3]> = eh
            .iter()
            .zip(&ei)
            .map(|(a, b)| [a[0] - b[0], a[1] - b[1], a[2] - b[2]])
            .collect();
        let diff = discrete_energy_sq(&pr, &d, lambda, g);
        eprintln!(
            "perturbed n = {n}: ‖u − I_h u‖² = {err_i:.6e} = ‖u − u_h‖² {err_h:.6e} + ‖u_h − I_h u‖² {diff:.6e}"
        );
        assert!(
            diff > 1e-6 * err_i,
            "n = {n}: u_h ≈ I_h u, the check is vacuous"
        );
        assert!(
            (err_i - err_h - diff).abs() <= 1e-9 * err_i,
            "n = {n}: Pythagoras fails: {err_i:e} ≠ {err_h:e} + {diff:e}"
        );
        // The library's energy norm of the discrete difference.
        let dv: Vec<f64> = uh.iter().zip(&interp).map(|(a, b)| a - b).collect();
        let hooke = Hooke::from_young_poisson(YOUNG, POISSON, 2, Plane::Strain);
        let lib = hemicontact::assembly::norms::energy_norm(pr.mesh(), &hooke, &dv);
        assert!(
            (lib * lib - diff).abs() <= 1e-10 * diff,
            "energy_norm {lib:e} vs {diff:e}"
        );
    }
}
