//! # Verification: convergence to a manufactured solution in 3D (P1 tetrahedra)
//!
//! The exact displacement on the unit cube is the quadratic field
//!
//! `u_x = α (x² + x y)`, `u_y = β (y² − y z)`, `u_z = γ (z² + x z)`,
//!
//! so `ε_xx = α(2x + y)`, `ε_yy = β(2y − z)`, `ε_zz = γ(2z + x)`, `ε_xy = α x/2`,
//! `ε_yz = −β y/2`, `ε_xz = γ z/2`, `div u = α(2x+y) + β(2y−z) + γ(2z+x)`, `Δu = 2(α, β, γ)`,
//! and with `div σ = (λ+G) ∇(div u) + G Δu` the body force `f_0 = −div σ` is the constant
//!
//! `f_0 = −[(λ+G) (2α+γ, α+2β, 2γ−β) + 2G (α, β, γ)]`
//!
//! (derived by hand). The problem is solved with `f_0` as body force and `u_D = u` on the
//! whole boundary, on box meshes n = 2, 4, 8, 16 (Kuhn tetrahedra, mirror-symmetric
//! pattern). P1 strains are piecewise constant, so the energy error must decrease with
//! order 1 in the mesh size (±0.1), and the Galerkin solution must beat the interpolant.
//! The energy error is integrated exactly (the integrand is quadratic on each tetrahedron;
//! the 4-point rule with weights ¼ is exact for quadratics).

use crate::common::{lame, problem, solve_with_prescribed_field};
use hemicontact::assembly::BulkAssembler;
use hemicontact::geometry::simplex;
use hemicontact::problem::Problem;
use hemicontact::tensor::SQRT2;

const YOUNG: f64 = 2000.0;
const POISSON: f64 = 0.3;
const A: f64 = 0.01;
const B: f64 = 0.015;
const C: f64 = -0.012;

fn exact_u(x: &[f64]) -> [f64; 3] {
    [
        A * (x[0] * x[0] + x[0] * x[1]),
        B * (x[1] * x[1] - x[1] * x[2]),
        C * (x[2] * x[2] + x[0] * x[2]),
    ]
}

/// Exact strain, tensor components `[xx, yy, zz, yz, xz, xy]`.
fn exact_strain(x: &[f64]) -> [f64; 6] {
    [
        A * (2.0 * x[0] + x[1]),
        B * (2.0 * x[1] - x[2]),
        C * (2.0 * x[2] + x[0]),
        -0.5 * B * x[1],
        0.5 * C * x[2],
        0.5 * A * x[0],
    ]
}

fn body_force(lambda: f64, g: f64) -> [f64; 3] {
    [
        -((lambda + g) * (2.0 * A + C) + 2.0 * g * A),
        -((lambda + g) * (A + 2.0 * B) + 2.0 * g * B),
        -((lambda + g) * (2.0 * C - B) + 2.0 * g * C),
    ]
}

/// `W(e) = λ/2 (tr e)² + G e:e` for tensor components `[xx, yy, zz, yz, xz, xy]`.
fn w(lambda: f64, g: f64, e: &[f64; 6]) -> f64 {
    let tr = e[0] + e[1] + e[2];
    let ee =
        e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + 2.0 * (e[3] * e[3] + e[4] * e[4] + e[5] * e[5]);
    0.5 * lambda * tr * tr + g * ee
}

fn scenario(n: usize, f: [f64; 3]) -> Problem {
    let mut text = format!(
        r#"
[mesh]
kind = "box"
size = [1.0, 1.0, 1.0]
n = [{n}, {n}, {n}]
pattern = "symmetric"
[material]
young = {YOUNG:?}
poisson = {POISSON:?}
[loads]
body_force = [{:?}, {:?}, {:?}]
"#,
        f[0], f[1], f[2]
    );
    for part in ["left", "right", "front", "back", "bottom", "top"] {
        text += &format!("[[dirichlet]]\npart = \"{part}\"\n");
    }
    problem(&text)
}

/// `‖u − v_h‖_E²` for a P1 field `v` (exact 4-point rule per tetrahedron).
fn error_energy_sq(problem: &Problem, v: &[f64], lambda: f64, g: f64) -> f64 {
    let mesh = problem.mesh();
    let strains = BulkAssembler::new(mesh, &problem.materials()[0]).cell_strains(v);
    let (qa, qb) = (0.585_410_196_624_968_5, 0.138_196_601_125_010_5);
    let mut sum = 0.0;
    for (c, e) in strains.iter().enumerate() {
        // Mandel [xx, yy, zz, √2 yz, √2 xz, √2 xy] to tensor components.
        let eh = [
            e.c[0],
            e.c[1],
            e.c[2],
            e.c[3] / SQRT2,
            e.c[4] / SQRT2,
            e.c[5] / SQRT2,
        ];
        let x = mesh.cell_coords(c);
        let vol = simplex::signed_measure(3, &x);
        for q in 0..4 {
            let mut p = [0.0; 3];
            for (a, xa) in x.iter().enumerate() {
                let l = if a == q { qa } else { qb };
                for i in 0..3 {
                    p[i] += l * xa[i];
                }
            }
            let ex = exact_strain(&p);
            let diff: [f64; 6] = std::array::from_fn(|k| ex[k] - eh[k]);
            sum += 0.25 * vol * w(lambda, g, &diff);
        }
    }
    sum
}

#[test]
fn energy_error_converges_with_order_one_in_3d() {
    let (lambda, g) = lame(YOUNG, POISSON, false);
    let f = body_force(lambda, g);
    let levels = [2usize, 4, 8, 16];
    let mut errors = Vec::new();
    for &n in &levels {
        let pr = scenario(n, f);
        let (uh, _) = solve_with_prescribed_field(&pr, exact_u);
        let interp: Vec<f64> = (0..pr.mesh().n_nodes())
            .flat_map(|k| exact_u(pr.mesh().node(k)))
            .collect();
        let err_h = error_energy_sq(&pr, &uh, lambda, g);
        let err_i = error_energy_sq(&pr, &interp, lambda, g);
        eprintln!(
            "n = {n:>2}: ‖u − u_h‖_E = {:.6e}  (interpolant: {:.6e})",
            err_h.sqrt(),
            err_i.sqrt()
        );
        assert!(
            err_h <= err_i * (1.0 + 1e-9),
            "n = {n}: u_h is worse than I_h u"
        );
        errors.push(err_h.sqrt());
    }
    let orders: Vec<f64> = (1..levels.len())
        .map(|k| (errors[k - 1] / errors[k]).ln() / 2f64.ln())
        .collect();
    eprintln!("observed orders in mesh size: {orders:?}");
    for (k, o) in orders.iter().enumerate().skip(1) {
        assert!(
            (o - 1.0).abs() <= 0.1,
            "order between n = {} and n = {} is {o:.4}, expected 1 ± 0.1",
            levels[k],
            levels[k + 1]
        );
    }
}
