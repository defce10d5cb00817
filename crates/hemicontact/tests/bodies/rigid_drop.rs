//! # Tiny loads and large gaps: the rigid drop
//!
//! A block held by rollers (2D: `u_x = 0` on its left side; 3D: `u_x = 0` on the left and
//! `u_y = 0` on the front face) rests across a gap g above a flat foundation of normal
//! compliance c_ν and is pressed by a uniform traction q on its top. The rollers leave the
//! vertical translation free; only contact carries it. The answer is a uniaxial stress
//! state `σ = −q e_v ⊗ e_v` (e_v the vertical), which P1 elements represent exactly, on a
//! rigid drop by the gap plus the penetration q/c_ν of the foundation (the lumped
//! foundation force `c_ν δ w_i` balances the consistent load `q w_i` node by node):
//!
//! - 2D (plane strain, σ_xx = 0): `u_x = ν(1+ν) q x / E`,
//!   `u_y = −g − q/c_ν − (1−ν²) q y / E`;
//! - 3D: `u_x = ν q x / E`, `u_y = ν q y / E`, `u_z = −g − q/c_ν − q z / E`;
//!
//! and every contact point carries the pressure q. The reference load `q = 1 Pa` with
//! E = 1000 Pa and c_ν = 1000 Pa/m deforms the block by about 10⁻³ of its height.
//!
//! 1. **Loads from 10⁻¹² to 10¹² times the reference, gaps from 0 to the body's size**
//!    (its largest distance from its centroid) give this closed form, in 2D and 3D: the
//!    displacement to 10⁻⁸ of the deformation `q/c_ν + q H/E` (plus the rounding of the
//!    total, a few units in the last place of g), each pressure and the resultant contact
//!    force to 10⁻⁸ of the load, each solve with a handful of Newton steps. For a gap more
//!    than a displacement scale wide the report names the rigid drop.
//! 2. **A load path** `[loading] factors = [1e-12, 1.0]` across a 1 mm gap converges at
//!    both steps, each to its closed form.
//!
//! 3. **The edge of the representable range**: loads down to 10⁻²⁹⁹ Pa (a deformation of
//!    10⁻³⁰² m, gaps of 10³⁰⁰ displacement units) and a load path whose first factor is
//!    10⁻³⁰⁰ give the same closed form.
//!
//! Before the rigid drop, the 2D block across 1 mm under 10⁻⁹ N/m ran 50 Newton steps
//! (the cap) without reaching the foundation ("Newton did not converge", exit 3), and the
//! load path stopped at its first step. Below about 10⁻¹⁵⁴ Pa across 1 mm the drop was
//! silently skipped (the norm of its coefficients, 10¹⁵⁵ displacement units, overflowed
//! when squared), with the same exit 3.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use hemicontact::loading::load_path;
use hemicontact::problem::Problem;
use hemicontact::solver::{solve, Solution};
use std::sync::atomic::AtomicBool;

const YOUNG: f64 = 1000.0;
const POISSON: f64 = 0.3;
const C_NU: f64 = 1000.0;
/// The reference load (Pa).
const Q_REF: f64 = 1.0;

/// The scenario of the block in `dim` dimensions across the gap `gap` (m) under the
/// traction `q` (Pa).
fn block(dim: usize, gap: f64, q: f64) -> String {
    let (mesh, rollers, load) = if dim == 2 {
        (
            "kind = \"rectangle\"\nsize = [2.0, 1.0]\nn = [8, 4]",
            "[[dirichlet]]\npart = \"left\"\ncomponents = [\"x\"]\n",
            format!("[0.0, {}]", -q),
        )
    } else {
        (
            "kind = \"box\"\nsize = [1.0, 1.0, 0.5]\nn = [4, 4, 2]",
            "[[dirichlet]]\npart = \"left\"\ncomponents = [\"x\"]\n\
             [[dirichlet]]\npart = \"front\"\ncomponents = [\"y\"]\n",
            format!("[0.0, 0.0, {}]", -q),
        )
    };
    format!(
        r#"
[mesh]
{mesh}
[material]
young = {YOUNG}
poisson = {POISSON}
{rollers}
[[contact]]
part = "bottom"
gap = {gap:e}
law = "normal-compliance"
c_nu = {C_NU}
[[loads.traction]]
part = "top"
value = {load}
"#
    )
}

/// Height H and body size (largest distance of a node from the centroid) of the block.
fn height_and_size(dim: usize) -> (f64, f64) {
    if dim == 2 {
        (1.0, (1.0f64 + 0.25).sqrt())
    } else {
        (0.5, (0.25f64 + 0.25 + 0.0625).sqrt())
    }
}

/// The closed-form displacement at `x`.
fn exact(dim: usize, gap: f64, q: f64, x: &[f64]) -> Vec<f64> {
    let (e, nu) = (YOUNG, POISSON);
    if dim == 2 {
        vec![
            nu * (1.0 + nu) * q * x[0] / e,
            -gap - q / C_NU - (1.0 - nu * nu) * q * x[1] / e,
        ]
    } else {
        vec![
            nu * q * x[0] / e,
            nu * q * x[1] / e,
            -gap - q / C_NU - q * x[2] / e,
        ]
    }
}

/// Asserts the closed form: displacements, pressures, resultant contact force.
#[track_caller]
fn assert_closed_form(problem: &Problem, sol: &Solution, gap: f64, q: f64, case: &str) {
    assert!(sol.report.converged, "{case}: {}", sol.report.message);
    let mesh = problem.mesh();
    let dim = mesh.dim();
    let (h, _) = height_and_size(dim);
    let deformation = q / C_NU + q * h / YOUNG;
    for v in 0..mesh.n_nodes() {
        let x = mesh.node(v);
        let e = exact(dim, gap, q, x);
        for i in 0..dim {
            let got = sol.u[dim * v + i];
            let tol = 1e-8 * deformation + 8.0 * f64::EPSILON * e[i].abs();
            assert!(
                (got - e[i]).abs() <= tol,
                "{case}: u_{i} at {x:?} = {got:e}, closed form {:e}",
                e[i]
            );
        }
    }
    for c in &sol.contact {
        assert!(
            (c.pressure - q).abs() <= 1e-8 * q,
            "{case}: pressure {:e} at node {}",
            c.pressure,
            c.node
        );
    }
    let area = if dim == 2 { 2.0 } else { 1.0 };
    let vertical: f64 = sol.contact.iter().map(|c| c.force[dim - 1]).sum();
    assert!(
        (vertical - q * area).abs() <= 1e-8 * q * area,
        "{case}: contact force {vertical:e} against the load {:e}",
        q * area
    );
}

#[test]
fn loads_from_1e_minus_12_to_1e12_across_gaps_up_to_the_body_size() {
    for dim in [2, 3] {
        let (_, size) = height_and_size(dim);
        for load in [1e-12, 1e-6, 1.0, 1e6, 1e12] {
            for fraction in [0.0, 1e-9, 1e-6, 1e-3, 0.1, 1.0] {
                let (q, gap) = (load * Q_REF, fraction * size);
                let case = format!("{dim}D, q = {q:e} Pa, gap = {gap:e} m");
                let (problem, settings) = common::setup(&block(dim, gap, q));
                let sol = solve(&problem, &settings).unwrap_or_else(|e| panic!("{case}: {e}"));
                assert_closed_form(&problem, &sol, gap, q, &case);
                assert!(
                    sol.report.newton.len() <= 12,
                    "{case}: {} Newton steps",
                    sol.report.newton.len()
                );
                let scale = sol.report.scales.unwrap().displacement;
                if gap > 2.0 * scale {
                    assert_eq!(sol.report.rigid_drop.len(), 1, "{case}");
                    let vertical = if dim == 2 { "y" } else { "z" };
                    assert!(
                        sol.report.rigid_drop[0]
                            .starts_with(&format!("translation along {vertical} by up to")),
                        "{case}: {:?}",
                        sol.report.rigid_drop
                    );
                } else if gap <= 0.5 * scale {
                    assert!(sol.report.rigid_drop.is_empty(), "{case}");
                }
            }
        }
    }
}

#[test]
fn a_load_path_from_1e_minus_12_converges_at_every_step() {
    for dim in [2, 3] {
        let gap = 1e-3;
        let text = block(dim, gap, Q_REF) + "[loading]\nfactors = [1e-12, 1.0]\n";
        let scenario = hemicontact::scenario::Scenario::from_str(&text, "<test>").unwrap();
        let problem = scenario.into_problem().unwrap();
        let settings = scenario.settings().unwrap();
        let factors = scenario.load_factors().unwrap().unwrap();
        assert_eq!(factors, vec![1e-12, 1.0]);
        let steps = load_path(
            &problem,
            &settings,
            &factors,
            &AtomicBool::new(false),
            &|_, _| {},
            &mut |_| Ok(()),
        )
        .unwrap();
        assert_eq!(steps.len(), 2, "{dim}D");
        for step in &steps {
            let case = format!("{dim}D, step {} (λ = {:e})", step.step, step.factor);
            assert_closed_form(
                &step.problem,
                &step.solution,
                gap,
                step.factor * Q_REF,
                &case,
            );
        }
    }
}

/// Loads at the bottom of the range of doubles, across gaps of up to 10³⁰⁰ displacement
/// units, with the drop, and a load path that starts there.
#[test]
fn loads_down_to_1e_minus_299_and_a_first_factor_of_1e_minus_300_converge() {
    for dim in [2, 3] {
        let (_, size) = height_and_size(dim);
        for q in [1e-160, 1e-299] {
            for fraction in [0.0, 1e-3, 1.0] {
                let gap = fraction * size;
                let case = format!("{dim}D, q = {q:e} Pa, gap = {gap:e} m");
                let (problem, settings) = common::setup(&block(dim, gap, q));
                let sol = solve(&problem, &settings).unwrap_or_else(|e| panic!("{case}: {e}"));
                assert_closed_form(&problem, &sol, gap, q, &case);
                assert_eq!(
                    sol.report.rigid_drop.len(),
                    usize::from(gap > 0.0),
                    "{case}"
                );
            }
        }
        let gap = 1e-3;
        let text = block(dim, gap, Q_REF) + "[loading]\nfactors = [1e-300, 1.0]\n";
        let scenario = hemicontact::scenario::Scenario::from_str(&text, "<test>").unwrap();
        let problem = scenario.into_problem().unwrap();
        let settings = scenario.settings().unwrap();
        let factors = scenario.load_factors().unwrap().unwrap();
        let steps = load_path(
            &problem,
            &settings,
            &factors,
            &AtomicBool::new(false),
            &|_, _| {},
            &mut |_| Ok(()),
        )
        .unwrap();
        assert_eq!(steps.len(), 2, "{dim}D");
        for step in &steps {
            let case = format!("{dim}D, step {} (λ = {:e})", step.step, step.factor);
            assert_closed_form(
                &step.problem,
                &step.solution,
                gap,
                step.factor * Q_REF,
                &case,
            );
        }
    }
}
