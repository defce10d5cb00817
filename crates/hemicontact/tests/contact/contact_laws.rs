//! # Verification: pointwise contact and friction laws, and the assembled contact terms
//!
//! What is verified, and why it must hold independently of the implementation:
//!
//! - **Normal compliance** `P(s) = (c_ν/2)(s − g)_+²` has derivative
//!   `p = c_ν (s − g)_+` and second derivative `c_ν H(s − g)`: checked by central
//!   differences away from the kink `s = g`, and against hand values.
//! - **Friction coefficient μ(r).** Constant; the paper's exponential law (41)
//!   `μ(r) = (a − b)e^{−βr} + b` with a = 0.4, b = 0.1, β = 100, so μ(0) = a, μ(∞) = b and
//!   μ(0.01) = 0.3 e^{−1} + 0.1 (a hand value); a table interpolated linearly and constant
//!   beyond its last point. `lipschitz()` must bound every secant and difference slope (and
//!   be attained, otherwise it is not *the* constant of the law), and `validate()` must reject
//!   negative or non-finite values and tables whose slips are not strictly increasing.
//! - **Friction potential j(r)**, r = ‖ξ‖: `slope` is `j'` (central differences for r > 0).
//!   For the paper's nonconvex law (17), `j = r − h` with h convex and C¹, `h' = h_slope`,
//!   and `∇h(ξ) = h'(r) ξ/r` is Lipschitz with constant `alpha_j() = (1 − a)/a`; hence
//!   ∂j is relaxed monotone with that constant. j is continuous and C¹ at r = a (both
//!   branches give `j(a) = a(1 + a)/2` and `j'(a) = a`).
//! - **`regularized_norm`** `φ(ξ) = √(‖ξ‖² + ρ²) − ρ`: value in closed form, gradient and
//!   Hessian by central differences, for m = 1 and 2 tangential components.
//! - **`ContactAssembler::assemble`** returns the contact energy
//!   `Σ_i w_i [P(u_ν,i) + F_i φ(ξ_i) − b_i·ξ_i]` and adds its gradient and node-block
//!   Hessian: the gradient must be the central difference of the returned energy in every
//!   DOF, the Hessian the central difference of the gradient (the energy is C² away from
//!   `u_ν = g` thanks to the numerical regularization ρ_num, and the samples keep
//!   `|u_ν − g|` far above the step). This is checked in 2D on a problem built from a
//!   scenario (three contact parts sharing corner nodes, so two points can sit on one node;
//!   the Hessian read through the global sparsity pattern) and in 3D on hand-built contact
//!   points (m = 2, node blocks read through private slots). With all frozen bounds
//!   `F_i ≥ 0` the energy is a sum of convex functions of u, so every second difference
//!   along a line is ≥ 0; with negative bounds this must fail somewhere (the check is
//!   sensitive).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::assembly::contact::{contact_slots, ContactAssembler, FrictionData};
use hemicontact::assembly::SystemPattern;
use hemicontact::contact::friction::regularized_norm;
use hemicontact::contact::nodes::tangent_basis;
use hemicontact::contact::{
    ContactBoundary, ContactNodes, Friction, FrictionBound, FrictionCoefficient, FrictionPotential,
    NormTreatment, NormalCompliance, NormalLaw,
};
use hemicontact::scenario::Scenario;
use hemicontact::solver::{Frozen, Multipliers};

mod common;

use common::Rng;

// ---------------------------------------------------------------------------------------
// Normal compliance
// ---------------------------------------------------------------------------------------

#[test]
fn normal_compliance_consistency_and_closed_form() {
    let law = NormalCompliance { c_nu: 1e4 };
    let mut rng = Rng::new(1);
    for gap in [0.0, 0.002] {
        let (mut active, mut inactive) = (0, 0);
        for _ in 0..200 {
            let s = rng.uniform(-0.01, 0.02);
            if (s - gap).abs() < 1e-6 {
                continue;
            }
            let h = 1e-8;
            let p = law.pressure(s, gap);
            let fd = (law.energy(s + h, gap) - law.energy(s - h, gap)) / (2.0 * h);
            assert!((fd - p).abs() <= 1e-7 * p, "s = {s}: p = {p} vs FD {fd}");
            let k = law.stiffness(s, gap);
            let fdk = (law.pressure(s + h, gap) - law.pressure(s - h, gap)) / (2.0 * h);
            assert!(
                (fdk - k).abs() <= 1e-6 * law.c_nu,
                "s = {s}: p' = {k} vs FD {fdk}"
            );
            // Closed form p = c_ν (s − g)_+, P = (c_ν/2)(s − g)_+².
            let pen = (s - gap).max(0.0);
            assert!((p - 1e4 * pen).abs() <= 1e-12 * p);
            assert!((law.energy(s, gap) - 0.5 * 1e4 * pen * pen).abs() <= 1e-12 * p * pen);
            if s > gap {
                active += 1;
                assert_eq!(k, 1e4);
            } else {
                inactive += 1;
                assert_eq!((p, k, law.energy(s, gap)), (0.0, 0.0, 0.0));
            }
        }
        assert!(active > 20 && inactive > 20);
    }
    // Hand values: c_ν = 1e4, g = 0.002, u_ν = 0.005 → p = 30, P = 0.045.
    assert!((law.pressure(0.005, 0.002) - 30.0).abs() < 1e-10);
    assert!((law.energy(0.005, 0.002) - 0.045).abs() < 1e-13);
    // At the kink: no pressure, no energy; the generalized derivative is taken as 0.
    assert_eq!(law.pressure(0.002, 0.002), 0.0);
    assert_eq!(law.energy(0.002, 0.002), 0.0);
    assert_eq!(law.stiffness(0.002, 0.002), 0.0);
}

// ---------------------------------------------------------------------------------------
// Friction coefficient
// ---------------------------------------------------------------------------------------

fn paper_exponential() -> FrictionCoefficient {
    FrictionCoefficient::Exponential {
        a: 0.4,
        b: 0.1,
        beta: 100.0,
    }
}

fn table() -> FrictionCoefficient {
    FrictionCoefficient::Table {
        points: vec![[0.0, 0.4], [0.01, 0.1], [0.03, 0.2]],
    }
}

/// Checks that `lipschitz()` bounds all secant slopes on [0, r_max] and is nearly attained.
fn check_lipschitz(mu: &FrictionCoefficient, r_max: f64, seed: u64) {
    let l = mu.lipschitz();
    let mut rng = Rng::new(seed);
    let mut worst = 0.0f64;
    for k in 0..2000 {
        // Every tenth pair starts at r = 0, where the slip weakening is steepest.
        let r1 = if k % 10 == 1 {
            0.0
        } else {
            rng.uniform(0.0, r_max)
        };
        let r2 = if k % 2 == 0 {
            rng.uniform(0.0, r_max)
        } else {
            (r1 + rng.uniform(-1e-6, 1e-6)).max(0.0)
        };
        if r1 == r2 {
            continue;
        }
        let slope = (mu.value(r1) - mu.value(r2)).abs() / (r1 - r2).abs();
        assert!(
            slope <= l * (1.0 + 1e-6) + 1e-12,
            "{mu:?}: slope {slope} between r = {r1} and {r2} exceeds L_μ = {l}"
        );
        worst = worst.max(slope);
    }
    // A central difference anywhere is a secant too; the supremum is attained (up to the
    // sampling) for these laws.
    assert!(
        worst >= 0.99 * l,
        "{mu:?}: max observed slope {worst} vs L_μ = {l}"
    );
}

#[test]
fn friction_coefficient_constant() {
    let mu = FrictionCoefficient::Constant { mu: 0.3 };
    for r in [0.0, 1e-6, 0.01, 1.0, 1e6] {
        assert_eq!(mu.value(r), 0.3);
    }
    assert_eq!(mu.lipschitz(), 0.0);
    assert_eq!(mu.sup(), 0.3);
    assert!(mu.validate().is_ok());
}

#[test]
fn friction_coefficient_exponential_paper_law() {
    let mu = paper_exponential();
    assert!((mu.value(0.0) - 0.4).abs() < 1e-15);
    assert!((mu.value(1.0) - 0.1).abs() < 1e-15);
    assert!((mu.value(1e3) - 0.1).abs() < 1e-15);
    // By hand: (0.4 − 0.1) e^{−100·0.01} + 0.1 = 0.3 · 0.36787944117144233 + 0.1.
    assert!((mu.value(0.01) - 0.210_363_832_351_432_7).abs() < 1e-15);
    // Monotonically decreasing (slip weakening) from a to b.
    let mut prev = mu.value(0.0);
    for k in 1..200 {
        let v = mu.value(k as f64 * 1e-3);
        assert!(v < prev && v > 0.1);
        prev = v;
    }
    // |μ'(r)| = (a − b) β e^{−βr} ≤ (a − b) β = 30 = L_μ, attained at r = 0.
    assert!((mu.lipschitz() - 30.0).abs() < 1e-12);
    let h = 1e-9;
    let fd0 = (mu.value(h) - mu.value(0.0)) / h;
    assert!((fd0 + 30.0).abs() < 1e-5, "μ'(0) = {fd0}");
    let mut rng = Rng::new(3);
    for _ in 0..100 {
        let r = rng.uniform(1e-6, 0.1);
        let fd = (mu.value(r + h) - mu.value(r - h)) / (2.0 * h);
        let exact = -30.0 * (-100.0 * r).exp();
        assert!((fd - exact).abs() < 1e-5, "r = {r}: FD {fd} vs {exact}");
        assert!(fd.abs() <= mu.lipschitz() * (1.0 + 1e-6));
    }
    check_lipschitz(&mu, 0.1, 4);
    assert_eq!(mu.sup(), 0.4);
    assert!(mu.validate().is_ok());
}

#[test]
fn friction_coefficient_table() {
    let mu = table();
    // At the points.
    for (r, v) in [(0.0, 0.4), (0.01, 0.1), (0.03, 0.2)] {
        assert!((mu.value(r) - v).abs() < 1e-15, "μ({r}) = {}", mu.value(r));
    }
    // At the midpoints.
    assert!((mu.value(0.005) - 0.25).abs() < 1e-15);
    assert!((mu.value(0.02) - 0.15).abs() < 1e-15);
    // A quarter of the way: 0.4 + 0.25·(0.1 − 0.4).
    assert!((mu.value(0.0025) - 0.325).abs() < 1e-15);
    // Constant beyond the last point.
    for r in [0.030_000_1, 0.05, 1.0, 1e9] {
        assert_eq!(mu.value(r), 0.2);
    }
    // Continuous at the interior point.
    assert!((mu.value(0.01 - 1e-12) - mu.value(0.01 + 1e-12)).abs() < 1e-9);
    // Slopes −30 then +5: L_μ = 30.
    assert!((mu.lipschitz() - 30.0).abs() < 1e-9);
    let h = 1e-7;
    for (r, slope) in [(0.004, -30.0), (0.02, 5.0), (0.1, 0.0)] {
        let fd = (mu.value(r + h) - mu.value(r - h)) / (2.0 * h);
        assert!(
            (fd - slope).abs() < 1e-6,
            "r = {r}: FD slope {fd} vs {slope}"
        );
    }
    check_lipschitz(&mu, 0.05, 5);
    assert_eq!(mu.sup(), 0.4);
    assert!(mu.validate().is_ok());
}

#[test]
fn friction_coefficient_validation() {
    let bad = [
        FrictionCoefficient::Constant { mu: -0.1 },
        FrictionCoefficient::Constant { mu: f64::NAN },
        FrictionCoefficient::Constant { mu: f64::INFINITY },
        FrictionCoefficient::Exponential {
            a: -0.4,
            b: 0.1,
            beta: 100.0,
        },
        FrictionCoefficient::Exponential {
            a: 0.4,
            b: f64::NAN,
            beta: 100.0,
        },
        FrictionCoefficient::Exponential {
            a: 0.4,
            b: 0.1,
            beta: -1.0,
        },
        FrictionCoefficient::Table { points: vec![] },
        FrictionCoefficient::Table {
            points: vec![[0.01, 0.4], [0.02, 0.1]],
        },
        FrictionCoefficient::Table {
            points: vec![[0.0, 0.4], [0.01, -0.1]],
        },
        FrictionCoefficient::Table {
            points: vec![[0.0, 0.4], [0.01, f64::NAN]],
        },
        FrictionCoefficient::Table {
            points: vec![[0.0, 0.4], [0.01, 0.1], [0.01, 0.2]],
        },
        FrictionCoefficient::Table {
            points: vec![[0.0, 0.4], [0.02, 0.1], [0.01, 0.2]],
        },
        FrictionCoefficient::Table {
            points: vec![[0.0, 0.4], [f64::NAN, 0.1]],
        },
    ];
    for mu in &bad {
        let res = mu.validate();
        assert!(res.is_err(), "{mu:?} accepted");
        assert!(!res.unwrap_err().is_empty());
    }
    let good = [
        FrictionCoefficient::Constant { mu: 0.0 },
        paper_exponential(),
        table(),
        FrictionCoefficient::Table {
            points: vec![[0.0, 0.3]],
        },
    ];
    for mu in &good {
        assert!(mu.validate().is_ok(), "{mu:?} rejected");
    }
}

// ---------------------------------------------------------------------------------------
// Friction potential
// ---------------------------------------------------------------------------------------

const A_J: f64 = 0.3;

fn potentials() -> [FrictionPotential; 3] {
    [
        FrictionPotential::Norm {
            treatment: NormTreatment::default(),
        },
        FrictionPotential::Nonconvex {
            a: A_J,
            unit: 1.0,
            treatment: NormTreatment::default(),
        },
        FrictionPotential::Regularized { rho: 0.01 },
    ]
}

#[test]
fn friction_potential_slope_is_derivative() {
    let mut rng = Rng::new(10);
    for j in potentials() {
        assert_eq!(j.value(0.0), 0.0, "{j:?}: j(0)");
        let (mut below, mut above) = (0, 0);
        for _ in 0..300 {
            let r = rng.log_uniform(1e-4, 2.0);
            if (r - A_J).abs() < 1e-5 {
                continue;
            }
            if r < A_J {
                below += 1;
            } else {
                above += 1;
            }
            let h = 1e-7 * r.max(0.01);
            let fd = (j.value(r + h) - j.value(r - h)) / (2.0 * h);
            let s = j.slope(r);
            assert!((fd - s).abs() < 1e-7, "{j:?} r = {r}: slope {s} vs FD {fd}");
            // |∂j| ≤ c_j.
            assert!(s.abs() <= j.c_j() * (1.0 + 1e-15));
        }
        assert!(below > 50 && above > 50);
    }
    // Closed forms.
    let r = 0.02_f64;
    let reg = FrictionPotential::Regularized { rho: 0.01 };
    assert!((reg.value(r) - (0.0005f64.sqrt() - 0.01)).abs() < 1e-16);
    assert_eq!(reg.slope(0.0), 0.0);
    assert_eq!(
        FrictionPotential::Norm {
            treatment: NormTreatment::default()
        }
        .slope(0.0),
        1.0
    );
    assert_eq!(
        FrictionPotential::Nonconvex {
            a: A_J,
            unit: 1.0,
            treatment: NormTreatment::default()
        }
        .slope(0.0),
        1.0
    );
    let nc = FrictionPotential::Nonconvex {
        a: A_J,
        unit: 1.0,
        treatment: NormTreatment::default(),
    };
    // r = 1 > a: a·1 + a(1 − a)/2 = 0.3 + 0.105.
    assert!((nc.value(1.0) - 0.405).abs() < 1e-15);
    // r = 0.1 < a: 0.1 + (a − 1)/(2a)·0.01 = 0.1 − 0.7/0.6·0.01.
    assert!((nc.value(0.1) - (0.1 - 0.7 / 0.6 * 0.01)).abs() < 1e-15);
}

#[test]
fn nonconvex_potential_dc_split_and_regularity() {
    let a = A_J;
    let j = FrictionPotential::Nonconvex {
        a,
        unit: 1.0,
        treatment: NormTreatment::default(),
    };
    let alpha = j.alpha_j();
    assert!((alpha - (1.0 - a) / a).abs() < 1e-15);
    let h_val = |r: f64| r - j.value(r);
    let mut rng = Rng::new(20);
    // h' = h_slope, h convex (h' nondecreasing), h' Lipschitz with α_j.
    for _ in 0..300 {
        let r = rng.uniform(1e-4, 1.5);
        if (r - a).abs() < 1e-5 {
            continue;
        }
        let d = 1e-7;
        let fd = (h_val(r + d) - h_val(r - d)) / (2.0 * d);
        assert!(
            (fd - j.h_slope(r)).abs() < 1e-7,
            "r = {r}: h' = {} vs FD {fd}",
            j.h_slope(r)
        );
        // j = j_cvx − h with j_cvx = ‖·‖: the slopes add up.
        assert!((j.slope(r) + j.h_slope(r) - 1.0).abs() < 1e-15);
    }
    let mut worst = 0.0f64;
    for _ in 0..2000 {
        let (r1, r2) = (rng.uniform(0.0, 1.5), rng.uniform(0.0, 1.5));
        if r1 == r2 {
            continue;
        }
        let (h1, h2) = (j.h_slope(r1), j.h_slope(r2));
        assert!((h1 - h2) * (r1 - r2) >= 0.0, "h' not monotone");
        let slope = (h1 - h2).abs() / (r1 - r2).abs();
        assert!(
            slope <= alpha * (1.0 + 1e-12),
            "h' slope {slope} > α_j = {alpha}"
        );
        worst = worst.max(slope);
    }
    assert!(
        worst >= 0.999 * alpha,
        "α_j = {alpha} not attained ({worst})"
    );
    // Vector form in 2D: ∇h(ξ) = h'(r) ξ/r is α_j-Lipschitz, and ∂j = j'(r) ξ/r is relaxed
    // monotone with α_j; the convex potentials are monotone (α_j = 0).
    let grad = |p: &FrictionPotential, s: fn(&FrictionPotential, f64) -> f64, x: [f64; 2]| {
        let r = x[0].hypot(x[1]);
        let g = s(p, r) / r;
        [g * x[0], g * x[1]]
    };
    for p in potentials() {
        let al = p.alpha_j();
        for _ in 0..2000 {
            let x1 = [rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)];
            let x2 = [rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)];
            let dx = [x1[0] - x2[0], x1[1] - x2[1]];
            let dd = dx[0] * dx[0] + dx[1] * dx[1];
            let (g1, g2) = (
                grad(&p, FrictionPotential::h_slope, x1),
                grad(&p, FrictionPotential::h_slope, x2),
            );
            let dg = (g1[0] - g2[0]).hypot(g1[1] - g2[1]);
            assert!(dg <= al * dd.sqrt() * (1.0 + 1e-12) + 1e-15, "{p:?}: ∇h");
            let (z1, z2) = (
                grad(&p, FrictionPotential::slope, x1),
                grad(&p, FrictionPotential::slope, x2),
            );
            let mono = (z1[0] - z2[0]) * dx[0] + (z1[1] - z2[1]) * dx[1];
            assert!(
                mono >= -al * dd * (1.0 + 1e-12) - 1e-15,
                "{p:?}: (ζ1 − ζ2)·(ξ1 − ξ2) = {mono} < −α_j‖ξ1 − ξ2‖²"
            );
        }
    }
    // Continuity and C¹ at r = a: j(a) = a(1 + a)/2 from both branches, j'(a±) = a.
    let ja = a * (1.0 + a) / 2.0;
    assert!((j.value(a) - ja).abs() < 1e-15);
    let right_branch = a * a + a * (1.0 - a) / 2.0;
    assert!((right_branch - ja).abs() < 1e-15);
    for t in [1e-6, 1e-9] {
        assert!((j.value(a + t) - j.value(a - t)).abs() <= 2.0 * a * t * (1.0 + 1e-3) + 1e-15);
    }
    let t = 1e-7;
    let left = (j.value(a) - j.value(a - t)) / t;
    let right = (j.value(a + t) - j.value(a)) / t;
    assert!((left - a).abs() < 1e-5, "j'(a−) = {left}");
    assert!((right - a).abs() < 1e-6, "j'(a+) = {right}");
    assert!((j.slope(a) - a).abs() < 1e-15);
    assert!((j.slope(a + 1e-12) - a).abs() < 1e-15);
    assert!((j.h_slope(a) - (1.0 - a)).abs() < 1e-15);
    // The convex potentials have no h.
    for p in [
        FrictionPotential::Norm {
            treatment: NormTreatment::default(),
        },
        FrictionPotential::Regularized { rho: 0.01 },
    ] {
        assert_eq!(p.alpha_j(), 0.0);
        assert_eq!(p.h_slope(0.5), 0.0);
    }
}

// ---------------------------------------------------------------------------------------
// regularized_norm
// ---------------------------------------------------------------------------------------

#[test]
fn regularized_norm_derivatives() {
    let mut rng = Rng::new(30);
    for m in [1usize, 2] {
        for rho in [1e-3, 0.01, 1.0] {
            for _ in 0..40 {
                let scale = rho * rng.log_uniform(1e-2, 1e2);
                let mut xi = [rng.uniform(-scale, scale), rng.uniform(-scale, scale)];
                if m == 1 {
                    // Components beyond m are ignored.
                    xi[1] = 1234.5;
                }
                let r2: f64 = xi[..m].iter().map(|x| x * x).sum();
                let (phi, g, h) = regularized_norm(&xi, m, rho);
                let exact = (r2 + rho * rho).sqrt() - rho;
                assert!((phi - exact).abs() <= 1e-14 * (exact + rho));
                let step = 1e-6 * (r2.sqrt() + rho);
                for a in 0..m {
                    let mut xp = xi;
                    let mut xm = xi;
                    xp[a] += step;
                    xm[a] -= step;
                    let (fp, gp, _) = regularized_norm(&xp, m, rho);
                    let (fm, gm, _) = regularized_norm(&xm, m, rho);
                    let fd = (fp - fm) / (2.0 * step);
                    assert!(
                        (fd - g[a]).abs() < 1e-7,
                        "m={m} ρ={rho} ξ={xi:?}: ∂φ/∂ξ{a} = {} vs FD {fd}",
                        g[a]
                    );
                    for b in 0..m {
                        let fdh = (gp[b] - gm[b]) / (2.0 * step);
                        assert!(
                            (fdh - h[b][a]).abs() < 1e-6 / (r2.sqrt() + rho),
                            "m={m} ρ={rho} ξ={xi:?}: H[{b}][{a}] = {} vs FD {fdh}",
                            h[b][a]
                        );
                    }
                }
                // Symmetric Hessian, unit-bounded gradient, nothing beyond m.
                assert_eq!(h[0][1], h[1][0]);
                assert!(g[0].hypot(g[1]) < 1.0);
                if m == 1 {
                    assert_eq!((g[1], h[0][1], h[1][1]), (0.0, 0.0, 0.0));
                }
            }
        }
    }
    // ρ = 0 at ξ = 0: the documented zero subgradient.
    let (phi, g, h) = regularized_norm(&[0.0, 0.0], 2, 0.0);
    assert_eq!((phi, g, h), (0.0, [0.0; 2], [[0.0; 2]; 2]));
}

// ---------------------------------------------------------------------------------------
// ContactAssembler::assemble
// ---------------------------------------------------------------------------------------

/// Elastic stiffness per unit area k_i of every point (Pa/m): with a smoothed norm of
/// regularization ε, the interface compliance ε/k.
const STIFFNESS: f64 = 1e3;

/// Energy and gradient (all DOFs) of the contact terms.
fn energy_grad(asm: &ContactAssembler<'_>, frozen: &Frozen, u: &[f64]) -> (f64, Vec<f64>) {
    let mut g = vec![0.0; u.len()];
    let e = asm.assemble(u, &frozen.contact(), &mut g, None);
    (e, g)
}

fn energy(asm: &ContactAssembler<'_>, frozen: &Frozen, u: &[f64]) -> f64 {
    energy_grad(asm, frozen, u).0
}

/// Whether every contact point is at least `margin` away from its kinks: `u_ν = g` (for a
/// Signorini point the augmented Lagrangian's `u_ν = g − λ/r`), and for friction through a
/// multiplier the stick/slip switch `‖z‖ = F`, `z = r'ξ + (r'/r)τ`, `r' = r/(1 + rc)` (c the
/// compliance of the elastic slip, 0 when exact).
fn off_kink(asm: &ContactAssembler<'_>, frozen: &Frozen, u: &[f64], margin: f64) -> bool {
    let m = asm.dim - 1;
    (0..asm.nodes.len()).all(|i| {
        let cb = &asm.boundaries[asm.nodes.boundary[i] as usize];
        let r = asm.penalty[i];
        let (_, gap) = cb
            .normal
            .effective(cb.gap, frozen.multipliers.pressure[i], r);
        let (u_nu, xi) = asm.nodes.kinematics(asm.dim, u, i);
        let tau = frozen.multipliers.traction[i];
        let c = cb
            .friction
            .as_ref()
            .and_then(|f| f.compliance(asm.stiffness[i]));
        let r_eff = r / (1.0 + r * c.unwrap_or(0.0));
        let nz = (0..m)
            .map(|a| (r_eff / r * tau[a] + r_eff * xi[a]).powi(2))
            .sum::<f64>()
            .sqrt();
        (u_nu - gap).abs() > margin
            && (c.is_none() || (nz - frozen.friction.bound[i]).abs() > r_eff * margin)
    })
}

/// Checks, at `samples` random displacements, the gradient against central differences of
/// the energy and the Hessian (dense, NaN where not comparable) against central differences
/// of the gradient. Returns the number of (penetrating, separated) point states visited.
fn check_assembler(
    label: &str,
    asm: &ContactAssembler<'_>,
    frozen: &Frozen,
    ndof: usize,
    hessian: &dyn Fn(&[f64]) -> Vec<f64>,
    seed: u64,
    samples: usize,
) -> (usize, usize) {
    let n = asm.nodes.len();
    let mut rng = Rng::new(seed);
    let (mut pen, mut sep) = (0, 0);
    let mut done = 0;
    while done < samples {
        let scale = rng.log_uniform(3e-4, 0.02);
        let u: Vec<f64> = (0..ndof).map(|_| rng.uniform(-scale, scale)).collect();
        if !off_kink(asm, frozen, &u, 1e-5) {
            continue;
        }
        done += 1;
        for i in 0..n {
            let s = asm.state(&u, i, &frozen.contact());
            if s.pressure > 0.0 {
                pen += 1;
            } else {
                sep += 1;
            }
        }
        let h = 1e-5 * scale;
        let (_, g) = energy_grad(asm, frozen, &u);
        let gmax = g.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let mut up = u.clone();
        let mut fd_h = vec![0.0; ndof * ndof];
        for k in 0..ndof {
            up[k] = u[k] + h;
            let (ep, gp) = energy_grad(asm, frozen, &up);
            up[k] = u[k] - h;
            let (em, gm) = energy_grad(asm, frozen, &up);
            up[k] = u[k];
            let fd = (ep - em) / (2.0 * h);
            assert!(
                (fd - g[k]).abs() <= 1e-8 * gmax + 1e-10,
                "{label}: dof {k}: gradient {} vs FD of energy {fd} (scale {scale:e})",
                g[k]
            );
            for r in 0..ndof {
                fd_h[r * ndof + k] = (gp[r] - gm[r]) / (2.0 * h);
            }
        }
        let hm = hessian(&u);
        let hmax = hm
            .iter()
            .filter(|x| !x.is_nan())
            .fold(0.0f64, |m, x| m.max(x.abs()));
        let mut compared = 0;
        for r in 0..ndof {
            for c in 0..ndof {
                let a = hm[r * ndof + c];
                if a.is_nan() {
                    continue;
                }
                compared += 1;
                let fd = fd_h[r * ndof + c];
                assert!(
                    (fd - a).abs() <= 1e-7 * hmax + 1e-8,
                    "{label}: Hessian ({r}, {c}) = {a} vs FD of gradient {fd} (scale {scale:e})"
                );
            }
        }
        assert!(compared > 0);
    }
    (pen, sep)
}

/// Second differences of the energy along random lines: ≥ 0 (up to round-off) when the
/// frozen bounds are ≥ 0. Returns the most negative relative second difference.
fn min_second_difference(
    asm: &ContactAssembler<'_>,
    frozen: &Frozen,
    ndof: usize,
    seed: u64,
    lines: usize,
) -> f64 {
    let mut rng = Rng::new(seed);
    let mut worst = f64::INFINITY;
    for _ in 0..lines {
        let scale = rng.log_uniform(1e-4, 0.02);
        let u: Vec<f64> = (0..ndof).map(|_| rng.uniform(-scale, scale)).collect();
        let v: Vec<f64> = (0..ndof).map(|_| rng.uniform(-1.0, 1.0)).collect();
        let s = scale * rng.log_uniform(1e-3, 3.0);
        let at = |t: f64| -> f64 {
            let w: Vec<f64> = u.iter().zip(&v).map(|(a, b)| a + t * b).collect();
            energy(asm, frozen, &w)
        };
        let (ep, e0, em) = (at(s), at(0.0), at(-s));
        let size = ep.abs() + e0.abs() + em.abs() + 1e-300;
        worst = worst.min((ep - 2.0 * e0 + em) / size);
    }
    worst
}

const SCENARIO: &str = r#"
[mesh]
kind = "rectangle"
size = [2.0, 2.0]
n = [2, 2]

[material]
young = 1000.0
poisson = 0.3

[[dirichlet]]
part = "bottom"

[[contact]]
part = "right"
gap = 0.001
c_nu = 10000.0
[contact.friction]
bound = "tresca"
mu = { law = "constant", mu = 0.5 }

[[contact]]
part = "top"
gap = 0.0
c_nu = 5000.0
[contact.friction]
bound = "coulomb"
potential = "regularized"
rho = 0.005
mu = { law = "exponential", a = 0.4, b = 0.1, beta = 100.0 }

[[contact]]
part = "left"
gap = 0.002
c_nu = 20000.0
"#;

fn random_frozen(rng: &mut Rng, n: usize, m: usize, nonnegative: bool) -> Frozen {
    let mut f = Frozen {
        friction: FrictionData::zero(n),
        multipliers: Multipliers::zero(n, 0),
    };
    for i in 0..n {
        f.friction.bound[i] = if i % 5 == 3 {
            0.0
        } else if nonnegative {
            rng.uniform(0.1, 2.0)
        } else {
            -rng.uniform(1.0, 10.0)
        };
        for a in 0..m {
            f.friction.linear[i][a] = rng.uniform(-1.0, 1.0);
            f.multipliers.traction[i][a] = rng.uniform(-1.0, 1.0);
        }
        f.multipliers.pressure[i] = rng.uniform(0.0, 1.0);
    }
    f
}

#[test]
fn assembled_contact_terms_2d_match_finite_differences() {
    let problem = Scenario::from_str(SCENARIO, "test")
        .unwrap()
        .into_problem()
        .unwrap();
    let nodes = problem.contact_nodes().unwrap();
    let d = problem.mesh().dim();
    assert_eq!(d, 2);
    // right: y = 1, 2 (the bottom corner is on Γ_D); top: x = 0, 1, 2; left: y = 1, 2.
    assert_eq!(nodes.len(), 7);
    let ndof = d * problem.mesh().n_nodes();
    let dofs = problem.dof_map();
    let pattern = SystemPattern::new(problem.mesh(), &dofs).unwrap();
    let slots = contact_slots(&nodes, d, dofs.equations(), &pattern);
    let penalty = vec![500.0; nodes.len()];
    let stiffness = vec![STIFFNESS; nodes.len()];
    let asm = ContactAssembler {
        dim: d,
        nodes: &nodes,
        boundaries: problem.contact(),
        stiffness: &stiffness,
        penalty: &penalty,
        responses: &[],
    };
    let equations = dofs.equations().to_vec();
    let mut rng = Rng::new(40);
    let frozen = random_frozen(&mut rng, nodes.len(), d - 1, true);
    // The Hessian read back through the pattern on the free DOFs (NaN elsewhere).
    let hessian = |u: &[f64]| -> Vec<f64> {
        let mut values = vec![0.0; pattern.nnz()];
        let mut g = vec![0.0; u.len()];
        asm.assemble(u, &frozen.contact(), &mut g, Some((&mut values, &slots)));
        let mut dense = vec![f64::NAN; ndof * ndof];
        for r in 0..ndof {
            for c in 0..ndof {
                let (er, ec) = (equations[r], equations[c]);
                if er == u32::MAX || ec == u32::MAX {
                    continue;
                }
                dense[r * ndof + c] = pattern
                    .find(er as usize, ec as usize)
                    .map_or(0.0, |s| values[s]);
            }
        }
        dense
    };
    let (pen, sep) = check_assembler("2D", &asm, &frozen, ndof, &hessian, 41, 30);
    assert!(pen > 20 && sep > 20, "{pen} penetrating, {sep} separated");
    // Convexity along lines with F ≥ 0.
    let worst = min_second_difference(&asm, &frozen, ndof, 42, 400);
    assert!(
        worst >= -1e-9,
        "2D: negative second difference {worst:e} with F ≥ 0"
    );
    // Sensitivity of that check: with negative bounds (concave friction) it fails.
    let neg = random_frozen(&mut rng, nodes.len(), d - 1, false);
    let worst = min_second_difference(&asm, &neg, ndof, 43, 400);
    assert!(
        worst < -1e-6,
        "2D: no negative second difference with F < 0 ({worst:e})"
    );
}

#[test]
fn assembled_contact_terms_3d_match_finite_differences() {
    // Hand-built 3D contact points on 4 nodes (node 2 carries two points on two
    // boundaries), with random unit normals and the library's tangent basis.
    let d = 3;
    let mut rng = Rng::new(50);
    let boundaries = vec![
        ContactBoundary {
            against: None,
            part: 0,
            gap: 0.001,
            obstacle: None,
            normal: NormalLaw::Compliance(NormalCompliance { c_nu: 1e4 }),
            friction: Some(Friction {
                bound: FrictionBound::Tresca,
                mu: FrictionCoefficient::Constant { mu: 0.5 },
                potential: FrictionPotential::Norm {
                    treatment: NormTreatment::default(),
                },
            }),
        },
        ContactBoundary {
            against: None,
            part: 1,
            gap: 0.0,
            obstacle: None,
            normal: NormalLaw::Compliance(NormalCompliance { c_nu: 5e3 }),
            friction: Some(Friction {
                bound: FrictionBound::Coulomb,
                mu: paper_exponential(),
                potential: FrictionPotential::Nonconvex {
                    a: A_J,
                    unit: 1.0,
                    treatment: NormTreatment::default(),
                },
            }),
        },
        ContactBoundary {
            against: None,
            part: 2,
            gap: 0.0005,
            obstacle: None,
            normal: NormalLaw::Compliance(NormalCompliance { c_nu: 2e4 }),
            friction: Some(Friction {
                bound: FrictionBound::Coulomb,
                mu: table(),
                potential: FrictionPotential::Regularized { rho: 0.005 },
            }),
        },
        ContactBoundary {
            against: None,
            part: 3,
            gap: 0.0,
            obstacle: None,
            normal: NormalLaw::Compliance(NormalCompliance { c_nu: 1e4 }),
            friction: None,
        },
        // Exact constraints: the augmented Lagrangian terms of Signorini contact and exact
        // friction (with the random multipliers of `random_frozen`).
        ContactBoundary {
            against: None,
            part: 4,
            gap: 0.001,
            obstacle: None,
            normal: NormalLaw::Signorini,
            friction: Some(Friction {
                bound: FrictionBound::Tresca,
                mu: FrictionCoefficient::Constant { mu: 0.5 },
                potential: FrictionPotential::Norm {
                    treatment: NormTreatment::Exact,
                },
            }),
        },
        ContactBoundary {
            against: None,
            part: 5,
            gap: 0.0,
            obstacle: None,
            normal: NormalLaw::Signorini,
            friction: Some(Friction {
                bound: FrictionBound::Coulomb,
                mu: paper_exponential(),
                potential: FrictionPotential::Nonconvex {
                    a: A_J,
                    unit: 1.0,
                    treatment: NormTreatment::Exact,
                },
            }),
        },
        ContactBoundary {
            against: None,
            part: 6,
            gap: 0.0005,
            obstacle: None,
            normal: NormalLaw::Compliance(NormalCompliance { c_nu: 2e4 }),
            friction: Some(Friction {
                bound: FrictionBound::Coulomb,
                mu: table(),
                potential: FrictionPotential::Norm {
                    treatment: NormTreatment::Exact,
                },
            }),
        },
    ];
    let layout: [(u32, u16); 9] = [
        (0, 0),
        (1, 1),
        (2, 1),
        (2, 2),
        (3, 3),
        (0, 2),
        (1, 4),
        (3, 5),
        (2, 6),
    ];
    let mut nodes = ContactNodes::default();
    for &(v, b) in &layout {
        let mut n = [
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
        ];
        let len = n.iter().map(|x| x * x).sum::<f64>().sqrt();
        n.iter_mut().for_each(|x| *x /= len);
        let t = tangent_basis(3, &n);
        // The basis is orthonormal and orthogonal to ν (the assembler relies on it).
        let dot = |a: &[f64; 3], b: &[f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        for (x, y, e) in [
            (&t[0], &t[0], 1.0),
            (&t[1], &t[1], 1.0),
            (&t[0], &t[1], 0.0),
            (&t[0], &n, 0.0),
            (&t[1], &n, 0.0),
        ] {
            assert!((dot(x, y) - e).abs() < 1e-14);
        }
        nodes.node.push(v);
        nodes.boundary.push(b);
        nodes.weight.push(rng.uniform(0.1, 1.0));
        nodes.normal.push(n);
        nodes.gap.push(boundaries[b as usize].gap);
        nodes.tangent.push(t);
        nodes.foundation_motion.push([0.0; 2]);
    }
    let penalty = vec![500.0; nodes.len()];
    let stiffness = vec![STIFFNESS; nodes.len()];
    let asm = ContactAssembler {
        dim: d,
        nodes: &nodes,
        boundaries: &boundaries,
        stiffness: &stiffness,
        penalty: &penalty,
        responses: &[],
    };
    let np = nodes.len();
    let ndof = 12;
    let frozen = random_frozen(&mut rng, np, d - 1, true);
    // Private slots: point i writes its upper-triangular node block to values[6i..6i+6].
    let slots: Vec<u32> = (0..6 * np as u32).collect();
    let hessian = |u: &[f64]| -> Vec<f64> {
        let mut values = vec![0.0; 6 * np];
        let mut g = vec![0.0; u.len()];
        asm.assemble(u, &frozen.contact(), &mut g, Some((&mut values, &slots)));
        let mut dense = vec![0.0; ndof * ndof];
        for i in 0..np {
            let v = nodes.node[i] as usize;
            let mut idx = 0;
            for k in 0..d {
                for l in k..d {
                    let x = values[6 * i + idx];
                    dense[(d * v + k) * ndof + d * v + l] += x;
                    if k != l {
                        dense[(d * v + l) * ndof + d * v + k] += x;
                    }
                    idx += 1;
                }
            }
        }
        dense
    };
    let (pen, sep) = check_assembler("3D", &asm, &frozen, ndof, &hessian, 51, 30);
    assert!(pen > 20 && sep > 20, "{pen} penetrating, {sep} separated");
    let worst = min_second_difference(&asm, &frozen, ndof, 52, 400);
    assert!(
        worst >= -1e-9,
        "3D: negative second difference {worst:e} with F ≥ 0"
    );
    let neg = random_frozen(&mut rng, np, d - 1, false);
    let worst = min_second_difference(&asm, &neg, ndof, 53, 400);
    assert!(
        worst < -1e-6,
        "3D: no negative second difference with F < 0 ({worst:e})"
    );
}
