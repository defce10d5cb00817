//! The stress written to `solution.vtu`: the full 3×3 tensor and the von Mises stress of its
//! three-dimensional deviator, checked against hand values on homogeneous strain states.
//!
//! - **Homogeneous states.** A unit square (unit cube) on rollers, with the normal
//!   displacement of the opposite sides prescribed, `u_x = a` on `right`, `u_y = b` on
//!   `top` (`u_z = c` on `top` in 3D), has the uniform strain `ε = diag(a, b[, c])` exactly
//!   (P1 contains the linear field, and its constant stress has no shear, so the rollers
//!   carry no tangential force). Every cell then has the same stress, computed here by hand:
//!   Hooke `σ = λ tr ε I + 2G ε`, plane strain `σ_zz = λ tr ε`, plane stress `σ_zz = 0`,
//!   limited-compressibility locking adds `C_κ (|tr ε| − θ)_+ sgn(tr ε)` to every normal
//!   component including σ_zz.
//! - **Von Mises** is computed here from the principal stresses,
//!   `√(½[(σ₁−σ₂)² + (σ₂−σ₃)² + (σ₃−σ₁)²])` (the stress is diagonal), not from the
//!   library's deviator formula.
//! - **Out-of-plane stress of every law** (plane strain): each 2D law is a function of
//!   `tr ε` and `ε:ε`; σ_zz is the derivative of that function with respect to ε_zz at
//!   ε_zz = 0. It is checked by a central difference of the law's own 2D energy, evaluated
//!   at the 2D strain with the same two invariants as the 3D strain `ε + h e_z⊗e_z`.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use common::{lame, problem};
use hemicontact::io::vtu::solution_vtu;
use hemicontact::material::{
    AugmentedLocking, Elasticity, Hencky, Hooke, Locking, LockingPenalty, LockingSet, Material,
    Plane, StrainEnergy,
};
use hemicontact::solver::SolverSettings;
use hemicontact::tensor::Sym;

const YOUNG: f64 = 1000.0;
const POISSON: f64 = 0.25;
/// Prescribed normal strains: `ε_xx = A`, `ε_yy = B` (`ε_zz = C` in 3D).
const A: f64 = 0.02;
const B: f64 = -0.01;
const C: f64 = 0.005;

/// Von Mises stress of a diagonal stress from its principal values.
fn von_mises_principal(s: [f64; 3]) -> f64 {
    (0.5 * ((s[0] - s[1]).powi(2) + (s[1] - s[2]).powi(2) + (s[2] - s[0]).powi(2))).sqrt()
}

/// Solves the homogeneous state and returns the written cell arrays `stress` and `von_mises`.
fn written_stress(text: &str) -> (Vec<f64>, Vec<f64>, usize) {
    let p = problem(text);
    let solution = hemicontact::solver::solve(&p, &SolverSettings::default()).unwrap();
    assert!(solution.report.converged, "{}", solution.report.message);
    let bytes = solution_vtu(&p, &solution, "homogeneous", 1.0)
        .unwrap()
        .to_bytes();
    (
        common::vtu::f64s(&bytes, "stress"),
        common::vtu::f64s(&bytes, "von_mises"),
        p.mesh().n_cells(),
    )
}

/// Asserts that every cell carries the diagonal stress `expect` and its von Mises stress.
fn assert_uniform(text: &str, expect: [f64; 3]) {
    let (stress, vm, n_cells) = written_stress(text);
    assert_eq!(stress.len(), 9 * n_cells);
    let scale = expect.iter().fold(1.0f64, |m, s| m.max(s.abs()));
    let vm_expect = von_mises_principal(expect);
    for c in 0..n_cells {
        let s = &stress[9 * c..9 * c + 9];
        for i in 0..3 {
            for j in 0..3 {
                let e = if i == j { expect[i] } else { 0.0 };
                assert!(
                    (s[3 * i + j] - e).abs() <= 1e-9 * scale,
                    "cell {c}: σ[{i}][{j}] = {} written, {e} by hand",
                    s[3 * i + j]
                );
            }
        }
        assert!(
            (vm[c] - vm_expect).abs() <= 1e-9 * scale,
            "cell {c}: von Mises {} written, {vm_expect} by hand",
            vm[c]
        );
    }
}

fn square(plane: &str, extra: &str) -> String {
    format!(
        r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [2, 2]
[material]
young = {YOUNG:?}
poisson = {POISSON:?}
plane = "{plane}"
{extra}
[[dirichlet]]
part = "left"
components = ["x"]
[[dirichlet]]
part = "bottom"
components = ["y"]
[[dirichlet]]
part = "right"
components = ["x"]
value = [{A:?}, 0.0]
[[dirichlet]]
part = "top"
components = ["y"]
value = [0.0, {B:?}]
"#
    )
}

/// Plane strain, Hooke: λ = G = 400 Pa, tr ε = 0.01, so σ = diag(20, −4, 4) Pa.
#[test]
fn plane_strain_writes_sigma_zz_and_von_mises_of_the_full_tensor() {
    let (lambda, g) = lame(YOUNG, POISSON, false);
    let tr = A + B;
    let expect = [
        lambda * tr + 2.0 * g * A,
        lambda * tr + 2.0 * g * B,
        lambda * tr,
    ];
    assert!((expect[0] - 20.0).abs() < 1e-12 && (expect[2] - 4.0).abs() < 1e-12);
    assert_uniform(&square("strain", ""), expect);
}

/// Plane stress, Hooke with λ* = Eν/(1−ν²): σ_zz = 0, von Mises still of the 3×3 tensor.
#[test]
fn plane_stress_writes_zero_sigma_zz_and_von_mises_of_the_full_tensor() {
    let (lambda, g) = lame(YOUNG, POISSON, true);
    let tr = A + B;
    let expect = [lambda * tr + 2.0 * g * A, lambda * tr + 2.0 * g * B, 0.0];
    assert_uniform(&square("stress", ""), expect);
}

/// Plane strain with the limited-compressibility penalty active: θ = 0.004 < tr ε = 0.01,
/// so `C_κ (tr ε − θ) = 10⁴ · 0.006 = 60` Pa is added to σ_xx, σ_yy and σ_zz.
#[test]
fn plane_strain_with_locking_adds_the_locking_stress_to_sigma_zz() {
    let (lambda, g) = lame(YOUNG, POISSON, false);
    let tr = A + B;
    let lock = 1.0e4 * (tr - 0.004);
    assert!((lock - 60.0).abs() < 1e-9);
    let expect = [
        lambda * tr + 2.0 * g * A + lock,
        lambda * tr + 2.0 * g * B + lock,
        lambda * tr + lock,
    ];
    let extra = "[locking]\nset = \"limited-compressibility\"\ntheta = 0.004\ntreatment = \"penalty\"\nc_kappa = 1.0e4";
    assert_uniform(&square("strain", extra), expect);
}

/// Plane strain, strain-stiffening Hencky law (G_∞ = 2G, e₀ = 0.01): in 2D
/// `W = ½K (tr ε)² + Φ(ε:ε − (tr ε)²/2)` with `K = λ + G`; its ε_zz-derivative at
/// ε_zz = 0 is `(K − Φ'(s)) tr ε` with `Φ'(s) = G_∞ − (G_∞ − G) e^{−s/s₀}`.
#[test]
fn plane_strain_hencky_writes_its_out_of_plane_stress() {
    let (lambda, g) = lame(YOUNG, POISSON, false);
    let (k, g_inf, s0) = (lambda + g, 2.0 * g, 1.0e-4);
    let tr = A + B;
    let s = A * A + B * B - tr * tr / 2.0;
    let dphi = g_inf - (g_inf - g) * (-s / s0).exp();
    let expect = [
        k * tr + 2.0 * dphi * (A - tr / 2.0),
        k * tr + 2.0 * dphi * (B - tr / 2.0),
        (k - dphi) * tr,
    ];
    let extra = "model = \"hencky\"\nstiffening = 2.0\nreference_strain = 0.01";
    assert_uniform(&square("strain", extra), expect);
}

/// 3D: the unit cube on rollers with `ε = diag(A, B, C)`, Hooke.
#[test]
fn three_d_writes_the_stress_and_its_von_mises() {
    let (lambda, g) = lame(YOUNG, POISSON, false);
    let tr = A + B + C;
    let expect = [
        lambda * tr + 2.0 * g * A,
        lambda * tr + 2.0 * g * B,
        lambda * tr + 2.0 * g * C,
    ];
    let text = format!(
        r#"
[mesh]
kind = "box"
size = [1.0, 1.0, 1.0]
n = [2, 2, 2]
[material]
young = {YOUNG:?}
poisson = {POISSON:?}
[[dirichlet]]
part = "left"
components = ["x"]
[[dirichlet]]
part = "front"
components = ["y"]
[[dirichlet]]
part = "bottom"
components = ["z"]
[[dirichlet]]
part = "right"
components = ["x"]
value = [{A:?}, 0.0, 0.0]
[[dirichlet]]
part = "back"
components = ["y"]
value = [0.0, {B:?}, 0.0]
[[dirichlet]]
part = "top"
components = ["z"]
value = [0.0, 0.0, {C:?}]
"#
    );
    assert_uniform(&text, expect);
}

/// The 2D strain with trace `t` and squared norm `n` (`n ≥ t²/2`): `[[t/2, c], [c, t/2]]`
/// with `2c² = n − t²/2`.
fn with_invariants(t: f64, n: f64) -> Sym {
    let c2 = 0.5 * (n - 0.5 * t * t);
    assert!(c2 >= 0.0);
    Sym::from_matrix(
        2,
        &[
            [0.5 * t, c2.sqrt(), 0.0],
            [c2.sqrt(), 0.5 * t, 0.0],
            [0.0; 3],
        ],
    )
}

/// `∂W/∂ε_zz` at ε_zz = 0 by central differences of the law's 2D energy read as a function
/// of `tr ε` and `ε:ε`.
fn fd_stress_zz<L: StrainEnergy>(law: &L, eps: &Sym, h: f64) -> f64 {
    let (t, n) = (eps.trace(), eps.dot(eps));
    let w = |z: f64| law.energy(&with_invariants(t + z, n + z * z));
    (w(h) - w(-h)) / (2.0 * h)
}

/// Every law's `plane_strain_stress_zz` is the ε_zz-derivative of its energy, and
/// `Material::stress_3x3` adds the ideal-locking multiplier's part `λ_T ∂Q/∂ε_zz`.
#[test]
fn out_of_plane_stress_is_the_derivative_of_the_energy() {
    let eps = Sym::from_matrix(2, &[[0.03, 0.01, 0.0], [0.01, -0.012, 0.0], [0.0; 3]]);
    let hooke = Hooke {
        lambda: 400.0,
        mu: 300.0,
    };
    let hencky = Hencky {
        bulk: 700.0,
        shear: 300.0,
        shear_inf: 900.0,
        s0: 1.0e-3,
    };
    let h = 1.0e-7;
    let check = |name: &str, got: f64, fd: f64, scale: f64| {
        assert!(
            (got - fd).abs() <= 1e-6 * scale,
            "{name}: σ_zz = {got}, finite difference {fd}"
        );
    };
    check(
        "hooke",
        hooke.plane_strain_stress_zz(&eps),
        fd_stress_zz(&hooke, &eps, h),
        10.0,
    );
    assert!((hooke.plane_strain_stress_zz(&eps) - 400.0 * 0.018).abs() < 1e-12);
    check(
        "hencky",
        hencky.plane_strain_stress_zz(&eps),
        fd_stress_zz(&hencky, &eps, h),
        10.0,
    );
    for set in [
        LockingSet::LimitedCompressibility { theta: 0.005 },
        LockingSet::Prager { kappa: 0.01 },
        LockingSet::Ball { r: 0.01 },
    ] {
        let pen = LockingPenalty {
            set,
            c_kappa: 1.0e4,
        };
        assert!(pen.is_active(&eps), "{set:?} must be active");
        check(
            &format!("{set:?}"),
            pen.plane_strain_stress_zz(&eps),
            fd_stress_zz(&pen, &eps, h),
            1.0e2,
        );
        let al = AugmentedLocking {
            set,
            r: 1.0e4,
            lambda: 3.0,
        };
        check(
            &format!("augmented {set:?}"),
            al.plane_strain_stress_zz(&eps),
            fd_stress_zz(&al, &eps, h),
            1.0e2,
        );
    }
    // Limited compressibility: C_κ (|tr ε| − θ) sgn(tr ε) = 10⁴ · 0.013 = 130 Pa.
    let lc = LockingPenalty {
        set: LockingSet::LimitedCompressibility { theta: 0.005 },
        c_kappa: 1.0e4,
    };
    assert!((lc.plane_strain_stress_zz(&eps) - 130.0).abs() < 1e-9);
    // Ideal locking: the multiplier stress λ_T sgn(tr ε) I has zz part λ_T.
    let mut material = Material::elastic(Elasticity::Hooke(hooke));
    material.locking = Locking::Ideal(LockingSet::LimitedCompressibility { theta: 0.005 });
    let s = material.stress_3x3(&eps, Plane::Strain, 50.0);
    assert!((s[2][2] - (400.0 * 0.018 + 50.0)).abs() < 1e-12);
    assert!((s[0][0] - (400.0 * 0.018 + 600.0 * 0.03 + 50.0)).abs() < 1e-12);
    assert_eq!(material.stress_3x3(&eps, Plane::Stress, 50.0)[2][2], 0.0);
}
