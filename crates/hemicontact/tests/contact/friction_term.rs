//! The tangential term of the friction law on its own ([`Friction::tangential_term`],
//! [`Friction::updated_traction`]): finite differences of energy against gradient and of
//! gradient against Hessian in 2D (one tangential component) and 3D (two), on the stick and
//! slip branches of exact friction and for the smoothed norm; closed forms of each branch
//! (the Moreau envelope of `F‖·‖` is `τ·ξ + r‖ξ‖²/2 − b·ξ` while `‖τ + rξ‖ ≤ F`, its gradient
//! has length F beyond); the smoothed norm as exact friction in series with an elastic slip,
//! whose multiplier converges to the law `τ = proj_{B_F}(ξ k/ε)`; the smooth law (19) with its
//! own ρ.

use hemicontact::contact::{
    Friction, FrictionBound, FrictionCoefficient, FrictionPotential, NormTreatment, TangentialData,
};

fn law(potential: FrictionPotential) -> Friction {
    Friction {
        bound: FrictionBound::Tresca,
        mu: FrictionCoefficient::Constant { mu: 1.0 },
        potential,
    }
}

fn exact() -> Friction {
    law(FrictionPotential::Norm {
        treatment: NormTreatment::Exact,
    })
}

fn smoothed(regularization: f64) -> Friction {
    law(FrictionPotential::Nonconvex {
        a: 0.5,
        unit: 1.0,
        treatment: NormTreatment::Smoothed { regularization },
    })
}

fn norm(x: &[f64], m: usize) -> f64 {
    x[..m].iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// Central differences of the energy against the gradient and of the gradient against the
/// Hessian at ξ, relative to `scale`.
fn check_derivatives(f: &Friction, xi: [f64; 2], m: usize, data: &TangentialData, label: &str) {
    let h = 1e-7;
    let t = f.tangential_term(&xi, m, data);
    let gscale = 1.0 + norm(&t.gradient, m);
    for a in 0..m {
        let (mut xp, mut xm) = (xi, xi);
        xp[a] += h;
        xm[a] -= h;
        let (tp, tm) = (
            f.tangential_term(&xp, m, data),
            f.tangential_term(&xm, m, data),
        );
        let fd = (tp.energy - tm.energy) / (2.0 * h);
        assert!(
            (fd - t.gradient[a]).abs() < 1e-6 * gscale,
            "{label} m={m}: dE/dξ_{a} = {fd} by differences, gradient {}",
            t.gradient[a]
        );
        let hscale = 1.0
            + t.hessian
                .iter()
                .flatten()
                .fold(0.0f64, |s, v| s.max(v.abs()));
        for c in 0..m {
            let fd = (tp.gradient[c] - tm.gradient[c]) / (2.0 * h);
            assert!(
                (fd - t.hessian[c][a]).abs() < 1e-5 * hscale,
                "{label} m={m}: d g_{c}/dξ_{a} = {fd} by differences, Hessian {}",
                t.hessian[c][a]
            );
        }
    }
    // The Hessian is symmetric.
    assert_eq!(t.hessian[0][1], t.hessian[1][0], "{label}");
}

#[test]
fn exact_stick_branch_is_the_quadratic_of_the_envelope() {
    let f = exact();
    for m in [1, 2] {
        let data = TangentialData {
            bound: 2.0,
            linear: [0.3, -0.2],
            traction: [0.5, 0.4],
            penalty: 10.0,
            stiffness: 1.0,
        };
        // ‖τ + rξ‖ ≤ ‖τ‖ + r‖ξ‖ < 0.65 + 10·0.05 < F = 2: stick.
        let xi = [0.03, -0.04];
        let t = f.tangential_term(&xi, m, &data);
        let dot = |x: &[f64; 2], y: &[f64; 2]| (0..m).map(|a| x[a] * y[a]).sum::<f64>();
        let energy =
            dot(&data.traction, &xi) + 0.5 * data.penalty * dot(&xi, &xi) - dot(&data.linear, &xi);
        assert!(
            (t.energy - energy).abs() < 1e-14,
            "m={m}: {} vs {energy}",
            t.energy
        );
        for a in 0..m {
            let g = data.traction[a] + data.penalty * xi[a] - data.linear[a];
            assert!((t.gradient[a] - g).abs() < 1e-14);
            for c in 0..m {
                let h = if a == c { data.penalty } else { 0.0 };
                assert_eq!(t.hessian[a][c], h);
            }
        }
        check_derivatives(&f, xi, m, &data, "exact stick");
        // The multiplier update keeps τ + rξ inside the ball.
        let tau = f
            .updated_traction(&xi, m, &data.traction, data.penalty, 1.0, data.bound)
            .expect("exact friction updates its multiplier");
        for a in 0..m {
            assert!((tau[a] - (data.traction[a] + data.penalty * xi[a])).abs() < 1e-15);
        }
    }
}

#[test]
fn exact_slip_branch_carries_the_bound() {
    let f = exact();
    for m in [1, 2] {
        let data = TangentialData {
            bound: 0.7,
            linear: [0.1, 0.05],
            traction: [0.5, -0.3],
            penalty: 40.0,
            stiffness: 1.0,
        };
        for xi in [[0.05, 0.02], [-0.08, 0.03], [0.04, -0.09]] {
            let z = [
                data.traction[0] + data.penalty * xi[0],
                data.traction[1] + data.penalty * xi[1],
            ];
            assert!(norm(&z, m) > 1.5 * data.bound, "sample on the slip branch");
            let t = f.tangential_term(&xi, m, &data);
            // The friction traction g + b has exactly the bound's length, along z.
            let traction = [
                t.gradient[0] + data.linear[0],
                t.gradient[1] + data.linear[1],
            ];
            assert!((norm(&traction, m) - data.bound).abs() < 1e-14);
            for a in 0..m {
                assert!((traction[a] - data.bound * z[a] / norm(&z, m)).abs() < 1e-14);
            }
            // The Hessian annihilates z (no stiffness along the slip direction) in 3D and
            // vanishes in 2D.
            for a in 0..m {
                let hz: f64 = (0..m).map(|c| t.hessian[a][c] * z[c]).sum();
                assert!(hz.abs() < 1e-12, "m={m}: H z = {hz}");
            }
            // Energy: (F‖z‖ − F²/2 − ‖τ‖²/2)/r − b·ξ.
            let (fb, r) = (data.bound, data.penalty);
            let energy = (fb * norm(&z, m) - 0.5 * fb * fb - 0.5 * norm(&data.traction, m).powi(2))
                / r
                - (0..m).map(|a| data.linear[a] * xi[a]).sum::<f64>();
            assert!((t.energy - energy).abs() < 1e-14);
            check_derivatives(&f, xi, m, &data, "exact slip");
            let tau = f
                .updated_traction(&xi, m, &data.traction, r, 1.0, fb)
                .expect("exact friction updates its multiplier");
            assert!((norm(&tau, m) - fb).abs() < 1e-14);
        }
    }
}

#[test]
fn exact_envelope_is_continuous_across_the_ball() {
    // ‖τ + rξ‖ = F exactly at ξ = s e₁ with s = (F − τ₁)/r (τ along e₁): both branches give
    // the same energy and gradient there.
    let f = exact();
    let data = TangentialData {
        bound: 1.0,
        linear: [0.0; 2],
        traction: [0.25, 0.0],
        penalty: 8.0,
        stiffness: 1.0,
    };
    let s = (1.0 - 0.25) / 8.0;
    let below = f.tangential_term(&[s * (1.0 - 1e-9), 0.0], 2, &data);
    let above = f.tangential_term(&[s * (1.0 + 1e-9), 0.0], 2, &data);
    assert!((below.energy - above.energy).abs() < 1e-9);
    assert!((below.gradient[0] - above.gradient[0]).abs() < 1e-7);
}

#[test]
fn smoothed_norm_is_the_envelope_with_an_elastic_slip() {
    // A smoothed norm of regularization ε at a point of stiffness k is exact friction in
    // series with an elastic slip of compliance c = ε/k: the envelope's argument is
    // z = r'ξ + (r'/r)τ with r' = r/(1 + rc), its energy (H_F(z) − (r'/r)‖τ‖²/2)/r' − b·ξ.
    for m in [1, 2] {
        for (eps, k) in [(1e-3, 1.0), (1e-2, 4.0), (0.5, 0.25)] {
            let f = smoothed(eps);
            let data = TangentialData {
                bound: 1.5,
                linear: [0.2, -0.1],
                traction: [0.3, -0.4],
                penalty: 10.0,
                stiffness: k,
            };
            let (r, c) = (data.penalty, eps / k);
            assert_eq!(f.compliance(k), Some(c));
            let r_eff = r / (1.0 + r * c);
            // Sticking and slipping samples.
            for xi in [[2e-3, -1e-3], [0.05, 0.08], [-0.3, 0.01]] {
                let t = f.tangential_term(&xi, m, &data);
                let z = [
                    r_eff * xi[0] + r_eff / r * data.traction[0],
                    r_eff * xi[1] + r_eff / r * data.traction[1],
                ];
                let nz = norm(&z, m);
                let huber = if nz <= data.bound {
                    0.5 * nz * nz
                } else {
                    data.bound * nz - 0.5 * data.bound * data.bound
                };
                let energy = (huber - 0.5 * r_eff / r * norm(&data.traction, m).powi(2)) / r_eff
                    - (0..m).map(|a| data.linear[a] * xi[a]).sum::<f64>();
                assert!(
                    (t.energy - energy).abs() < 1e-13,
                    "m={m} ε={eps}: energy {} vs {energy}",
                    t.energy
                );
                let scale = data.bound.min(nz) / nz;
                for a in 0..m {
                    let g = z[a] * scale - data.linear[a];
                    assert!((t.gradient[a] - g).abs() < 1e-13);
                }
                check_derivatives(&f, xi, m, &data, "smoothed");
            }
        }
    }
}

#[test]
fn the_multiplier_of_the_smoothed_norm_converges_to_the_elastic_slip_law() {
    // At a fixed slip ξ the multiplier update τ ← proj_{B_F}(z) converges to the law of
    // the smoothed norm, τ = proj_{B_F}(ξ k/ε): a spring of stiffness k/ε up to the bound.
    let (eps, k) = (0.1, 2.0);
    let f = smoothed(eps);
    for m in [1, 2] {
        for xi in [[0.01, -0.02], [0.3, 0.1], [-0.05, 0.0]] {
            let (penalty, bound) = (5.0, 1.0);
            let mut tau = [0.0; 2];
            for _ in 0..200 {
                tau = f
                    .updated_traction(&xi, m, &tau, penalty, k, bound)
                    .expect("the smoothed norm has a multiplier");
            }
            let spring = [xi[0] * k / eps, xi[1] * k / eps];
            let ns = norm(&spring, m);
            for a in 0..m {
                let law = spring[a] * (bound.min(ns) / ns);
                assert!((tau[a] - law).abs() < 1e-12, "m={m} ξ={xi:?}: {tau:?}");
            }
        }
    }
}

#[test]
fn smooth_law_uses_its_own_rho() {
    let f = law(FrictionPotential::Regularized { rho: 0.02 });
    assert!(!f.is_exact());
    assert_eq!(f.potential.regularization(), None);
    assert_eq!(f.compliance(1.0), None);
    let data = TangentialData {
        bound: 1.0,
        stiffness: 1e-9,
        ..Default::default()
    };
    // F ξ/√(ξ² + ρ²) with ρ = 0.02: at ξ = 0.02, 1/√2.
    let t = f.tangential_term(&[0.02, 0.0], 1, &data);
    assert!((t.gradient[0] - 0.5f64.sqrt()).abs() < 1e-15);
    assert_eq!(
        f.updated_traction(&[0.1, 0.1], 1, &[0.0; 2], 1.0, 1.0, 1.0),
        None
    );
}
