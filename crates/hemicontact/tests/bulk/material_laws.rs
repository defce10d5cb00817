//! # Verification: pointwise material laws (Hencky, locking penalties, combined materials)
//!
//! What is verified, and why it must hold independently of the implementation:
//!
//! - **Derivative consistency.** Every law is hyperelastic: `σ = ∂(W + Ψ)/∂ε` and the tangent
//!   is `∂σ/∂ε`. Strains and stresses are Mandel vectors, in which the Euclidean inner
//!   product *is* the double contraction `a : b`; the partial derivative of the energy with
//!   respect to Mandel component `k` is therefore exactly component `k` of the stress, and
//!   the partial derivative of the stress is column `k` of the tangent (no shear factors).
//!   Central differences are checked at pseudo-random strains in 2D and 3D, for the Hencky
//!   law, each locking penalty (limited compressibility, Prager, ball) and their sums with
//!   Hooke/Hencky. The penalties `(C_κ/2) Q_+²` are only C¹ with a kink of the stress where
//!   `Q = 0`, so the sample strains keep `|Q(ε)| > 1e-3` (far beyond the difference step)
//!   and their magnitudes are spread so that both active (`Q > 0`) and inactive states
//!   occur; the test asserts that both were exercised. The tangent must be symmetric
//!   (it is a Hessian).
//! - **One-sided behaviour on ∂B.** On the boundary `Q = 0` the penalty energy and stress
//!   vanish. Since `σ = C_κ Q_+ ∂Q`, a step `t v` outward (`∂Q : v > 0`) gives
//!   `σ(ε + t v) = C_κ t (∂Q : v) ∂Q + O(t²)`, i.e. the one-sided derivative is
//!   `C_κ (∂Q ⊗ ∂Q) v` with `∂Q` written in closed form here (`sgn(tr ε) I`, `ε^D`,
//!   `ε/‖ε‖`), which is also the limit of the tangent evaluated just outside; a step inward
//!   (`∂Q : v < 0`) stays in B where the stress is identically 0.
//! - **Closed forms.** Limited compressibility: `σ = C_κ (|tr ε| − θ)_+ sgn(tr ε) I`
//!   (the limited-compressibility locking law). Hencky with `G_∞ = G` has `Φ(s) = G s`, so
//!   `W = ½K(tr ε)² + G‖ε^D‖² = ½(K − 2G/d)(tr ε)² + G‖ε‖²`: Hooke's law with
//!   `λ = K − 2G/d`. The Hencky operator is strongly monotone and Lipschitz with the
//!   constants it advertises; these inequalities are checked on random pairs of strains
//!   (including large deviatoric strains where the stiffening is active).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::material::{
    AugmentedLocking, Elasticity, Hencky, Hooke, Locking, LockingPenalty, LockingSet, Material,
    StrainEnergy,
};
use hemicontact::tensor::{apply, mandel_len, Sym, Tangent};

mod common;

use common::{random_strain, Rng};

/// Unit vector `e_k` in Mandel components.
fn unit(dim: usize, k: usize) -> Sym {
    let mut e = Sym::zero(dim);
    e.c[k] = 1.0;
    e
}

/// Central difference of the energy in every Mandel component.
fn fd_stress<L: StrainEnergy>(law: &L, eps: &Sym, h: f64) -> Sym {
    let mut out = Sym::zero(eps.dim);
    for k in 0..eps.len() {
        let e = unit(eps.dim, k);
        let wp = law.energy(&eps.add_scaled(h, &e));
        let wm = law.energy(&eps.add_scaled(-h, &e));
        out.c[k] = (wp - wm) / (2.0 * h);
    }
    out
}

/// Central difference of the stress: column `k` is `(σ(ε + h e_k) − σ(ε − h e_k)) / 2h`.
fn fd_tangent<L: StrainEnergy>(law: &L, eps: &Sym, h: f64) -> Tangent {
    let mut t = [[0.0; 6]; 6];
    for k in 0..eps.len() {
        let e = unit(eps.dim, k);
        let sp = law.stress(&eps.add_scaled(h, &e));
        let sm = law.stress(&eps.add_scaled(-h, &e));
        for i in 0..eps.len() {
            t[i][k] = (sp.c[i] - sm.c[i]) / (2.0 * h);
        }
    }
    t
}

fn sym_diff_norm(a: &Sym, b: &Sym) -> f64 {
    a.add_scaled(-1.0, b).norm()
}

/// Frobenius norm of the leading n×n block.
fn tangent_norm(t: &Tangent, n: usize) -> f64 {
    let mut s = 0.0;
    for row in t.iter().take(n) {
        for x in row.iter().take(n) {
            s += x * x;
        }
    }
    s.sqrt()
}

fn tangent_diff_norm(a: &Tangent, b: &Tangent, n: usize) -> f64 {
    let mut d = [[0.0; 6]; 6];
    for i in 0..n {
        for j in 0..n {
            d[i][j] = a[i][j] - b[i][j];
        }
    }
    tangent_norm(&d, n)
}

/// Checks stress = FD(energy), tangent = FD(stress) and tangent symmetry at `samples` strains
/// with `|Q| > 1e-3`, alternately active and inactive; returns the numbers of (active, inactive) penalty states visited.
fn check_derivatives<L: StrainEnergy>(
    name: &str,
    law: &L,
    penalty: Option<LockingPenalty>,
    dim: usize,
    seed: u64,
    samples: usize,
    scale_range: (f64, f64),
) -> (usize, usize) {
    let n = mandel_len(dim);
    let mut rng = Rng::new(seed);
    let (mut active, mut inactive) = (0, 0);
    let mut done = 0;
    let mut tries = 0;
    while done < samples {
        tries += 1;
        assert!(
            tries < 100 * samples,
            "{name}: cannot find strains off the kink in both states"
        );
        let scale = rng.log_uniform(scale_range.0, scale_range.1);
        let eps = random_strain(&mut rng, dim, scale);
        if let Some(p) = penalty {
            let q = p.set.q(&eps);
            // Alternate active and inactive states (rejection sampling).
            let want_active = done % 2 == 0;
            if q.abs() <= 1e-3 || (q > 0.0) != want_active {
                continue;
            }
            if q > 0.0 {
                active += 1;
            } else {
                inactive += 1;
            }
        }
        done += 1;
        let h = 1e-6 * eps.norm().max(1e-3);
        let sigma = law.stress(&eps);
        let fd = fd_stress(law, &eps, h);
        let err = sym_diff_norm(&sigma, &fd);
        assert!(
            err <= 1e-6 * sigma.norm(),
            "{name} d={dim} ε={:?}: stress {:?} vs FD of energy {:?} (error {err:e})",
            &eps.c[..n],
            &sigma.c[..n],
            &fd.c[..n]
        );
        let t = law.tangent(&eps);
        let fdt = fd_tangent(law, &eps, h);
        let terr = tangent_diff_norm(&t, &fdt, n);
        let tn = tangent_norm(&t, n);
        assert!(
            terr <= 1e-5 * tn,
            "{name} d={dim} ε={:?}: tangent vs FD of stress, error {terr:e} (|T| = {tn:e})",
            &eps.c[..n]
        );
        for i in 0..n {
            for j in 0..i {
                assert!(
                    (t[i][j] - t[j][i]).abs() <= 1e-12 * tn,
                    "{name} d={dim}: tangent not symmetric at ({i},{j})"
                );
            }
        }
    }
    (active, inactive)
}

fn hencky() -> Hencky {
    Hencky {
        bulk: 1500.0,
        shear: 700.0,
        shear_inf: 2100.0,
        s0: 0.01,
    }
}

fn hooke() -> Hooke {
    // E = 2000, ν = 0.3 (plane strain): λ = 15000/13, G = 10000/13.
    Hooke {
        lambda: 15000.0 / 13.0,
        mu: 10000.0 / 13.0,
    }
}

const C_KAPPA: f64 = 1e4;

fn locking_sets() -> [(&'static str, LockingSet); 3] {
    [
        (
            "limited-compressibility",
            LockingSet::LimitedCompressibility { theta: 0.16 },
        ),
        ("prager", LockingSet::Prager { kappa: 0.1 }),
        ("ball", LockingSet::Ball { r: 0.2 }),
    ]
}

/// A material made of the penalty alone (zero elasticity).
fn penalty_only(set: LockingSet) -> Material {
    Material {
        elasticity: Elasticity::Hooke(Hooke {
            lambda: 0.0,
            mu: 0.0,
        }),
        locking: Locking::Penalty(LockingPenalty {
            set,
            c_kappa: C_KAPPA,
        }),
    }
}

#[test]
fn hencky_stress_and_tangent_match_finite_differences() {
    let law = Material::elastic(Elasticity::Hencky(hencky()));
    for dim in [2, 3] {
        // ‖ε^D‖² from ~1e-5 to ~0.5: both sides of the transition s₀ = 0.01.
        check_derivatives("hencky", &law, None, dim, 11 + dim as u64, 24, (0.003, 0.5));
    }
}

#[test]
fn penalty_stress_and_tangent_match_finite_differences() {
    for (k, (name, set)) in locking_sets().into_iter().enumerate() {
        for dim in [2, 3] {
            let seed = 100 + 10 * k as u64 + dim as u64;
            let p = LockingPenalty {
                set,
                c_kappa: C_KAPPA,
            };
            let (active, inactive) =
                check_derivatives(name, &p, Some(p), dim, seed, 24, (0.05, 0.6));
            assert!(
                active >= 4 && inactive >= 4,
                "{name} d={dim}: only {active} active and {inactive} inactive samples"
            );
            // The same penalty inside a Material with zero elasticity gives the same
            // energy, stress and tangent.
            let law = penalty_only(set);
            let n = mandel_len(dim);
            let mut rng = Rng::new(seed + 7);
            for _ in 0..20 {
                let eps = {
                    let sc = rng.log_uniform(0.05, 0.6);
                    random_strain(&mut rng, dim, sc)
                };
                let m = law.stress(&eps);
                let s = p.stress(&eps);
                assert!(sym_diff_norm(&m, &s) <= 1e-12 * s.norm().max(1e-300));
                assert!((law.energy(&eps) - p.energy(&eps)).abs() <= 1e-12 * p.energy(&eps));
                let (tm, tp) = (law.tangent(&eps), p.tangent(&eps));
                assert!(tangent_diff_norm(&tm, &tp, n) <= 1e-12 * tangent_norm(&tp, n));
            }
        }
    }
}

#[test]
fn combined_materials_match_finite_differences() {
    for (k, (name, set)) in locking_sets().into_iter().enumerate() {
        let penalty = LockingPenalty {
            set,
            c_kappa: C_KAPPA,
        };
        for (ename, elasticity) in [
            ("hooke", Elasticity::Hooke(hooke())),
            ("hencky", Elasticity::Hencky(hencky())),
        ] {
            let law = Material {
                elasticity,
                locking: Locking::Penalty(penalty),
            };
            for dim in [2, 3] {
                let seed = 500 + 10 * k as u64 + dim as u64 + if ename == "hooke" { 0 } else { 5 };
                let label = format!("{ename} + {name}");
                let (active, inactive) =
                    check_derivatives(&label, &law, Some(penalty), dim, seed, 20, (0.05, 0.6));
                assert!(
                    active >= 3 && inactive >= 3,
                    "{label} d={dim}: only {active} active and {inactive} inactive samples"
                );
            }
        }
    }
}

/// Closed-form `∂Q` of each set (independent of the library's table).
fn closed_form_dq(set: LockingSet, eps: &Sym) -> Sym {
    match set {
        LockingSet::LimitedCompressibility { .. } => {
            Sym::identity(eps.dim).scaled(eps.trace().signum())
        }
        LockingSet::Prager { .. } => {
            // ε^D computed from the full matrix: ε − (tr ε / d) I.
            let m = eps.to_matrix();
            let tr: f64 = (0..eps.dim).map(|i| m[i][i]).sum();
            let mut dev = m;
            for (i, row) in dev.iter_mut().enumerate().take(eps.dim) {
                row[i] -= tr / eps.dim as f64;
            }
            Sym::from_matrix(eps.dim, &dev)
        }
        LockingSet::Ball { .. } => eps.scaled(1.0 / eps.norm()),
    }
}

/// Projects a random strain onto ∂B = {Q = 0} (exactly up to round-off).
fn on_boundary(set: LockingSet, eps: &Sym) -> Sym {
    let d = eps.dim;
    match set {
        LockingSet::LimitedCompressibility { theta } => {
            // Keep the sign of tr ε, set |tr ε| = θ.
            let target = theta * eps.trace().signum();
            eps.add_scaled((target - eps.trace()) / d as f64, &Sym::identity(d))
        }
        LockingSet::Prager { kappa } => {
            // ½‖ε^D‖² = κ²: rescale the deviator to norm √2 κ, keep the volumetric part.
            let dev = eps.deviator();
            let vol = eps.add_scaled(-1.0, &dev);
            vol.add_scaled(std::f64::consts::SQRT_2 * kappa / dev.norm(), &dev)
        }
        LockingSet::Ball { r } => eps.scaled(r / eps.norm()),
    }
}

#[test]
fn penalty_is_one_sided_at_the_kink() {
    for (k, (name, set)) in locking_sets().into_iter().enumerate() {
        let p = LockingPenalty {
            set,
            c_kappa: C_KAPPA,
        };
        for dim in [2, 3] {
            let n = mandel_len(dim);
            let mut rng = Rng::new(900 + 10 * k as u64 + dim as u64);
            for sample in 0..12 {
                let mut eps = on_boundary(set, &random_strain(&mut rng, dim, 0.1));
                if sample == 0 && matches!(set, LockingSet::LimitedCompressibility { .. }) {
                    // Also a compressive strain (tr ε = −θ).
                    eps = on_boundary(set, &eps.scaled(-1.0));
                }
                let q = set.q(&eps);
                assert!(q.abs() < 1e-15, "{name} d={dim}: Q = {q:e} on the boundary");
                // Energy and stress vanish on ∂B (up to the round-off of Q).
                assert!(
                    p.energy(&eps) <= 0.5 * C_KAPPA * 1e-30,
                    "{name}: energy on ∂B"
                );
                assert!(
                    p.stress(&eps).norm() <= C_KAPPA * 1e-15,
                    "{name}: stress on ∂B"
                );

                let dq = closed_form_dq(set, &eps);
                // Outward direction: a random direction with its ∂Q-component made positive.
                let mut v = random_strain(&mut rng, dim, 1.0);
                let along = v.dot(&dq) / dq.dot(&dq);
                v = v.add_scaled(-along + rng.uniform(0.5, 1.5), &dq);
                let slope = v.dot(&dq);
                assert!(slope > 0.0);
                let expected = dq.scaled(C_KAPPA * slope);
                // Forward differences with Richardson extrapolation (error O(t²)).
                let t = 1e-6;
                let d1 = p.stress(&eps.add_scaled(t, &v)).scaled(1.0 / t);
                let d2 = p.stress(&eps.add_scaled(0.5 * t, &v)).scaled(2.0 / t);
                let one_sided = d2.scaled(2.0).add_scaled(-1.0, &d1);
                let err = sym_diff_norm(&one_sided, &expected);
                assert!(
                    err <= 1e-6 * expected.norm(),
                    "{name} d={dim}: outward one-sided derivative {:?} vs C_κ ∂Q⊗∂Q v {:?}",
                    &one_sided.c[..n],
                    &expected.c[..n]
                );
                // The tangent just outside tends to C_κ ∂Q⊗∂Q (+ C_κ Q ∂²Q → 0).
                let outside = eps.add_scaled(1e-9, &v);
                assert!(p.is_active(&outside));
                let tv = apply(&p.tangent(&outside), &v);
                let err = sym_diff_norm(&tv, &expected);
                assert!(
                    err <= 1e-6 * expected.norm(),
                    "{name} d={dim}: tangent just outside {:?} vs C_κ ∂Q⊗∂Q v {:?}",
                    &tv.c[..n],
                    &expected.c[..n]
                );
                // Inward: the stress stays exactly zero, so the one-sided derivative is 0.
                let w = v.scaled(-1.0);
                for t in [1e-8, 1e-6, 1e-4] {
                    let inside = eps.add_scaled(t, &w);
                    assert!(set.q(&inside) < 0.0);
                    assert_eq!(p.energy(&inside), 0.0, "{name}: energy inside B");
                    assert_eq!(p.stress(&inside).norm(), 0.0, "{name}: stress inside B");
                    assert!(!p.is_active(&inside));
                    assert_eq!(tangent_norm(&p.tangent(&inside), n), 0.0);
                }
            }
        }
    }
}

#[test]
fn limited_compressibility_closed_form() {
    let theta = 0.16;
    let p = LockingPenalty {
        set: LockingSet::LimitedCompressibility { theta },
        c_kappa: C_KAPPA,
    };
    let mut rng = Rng::new(4242);
    let (mut pos, mut neg, mut zero) = (0, 0, 0);
    for dim in [2, 3] {
        for _ in 0..60 {
            let eps = random_strain(&mut rng, dim, 0.25);
            // Trace summed from the full matrix (independent of the Mandel layout).
            let m = eps.to_matrix();
            let tr: f64 = (0..dim).map(|i| m[i][i]).sum();
            let mag = C_KAPPA * (tr.abs() - theta).max(0.0);
            let expected = Sym::identity(dim).scaled(mag * tr.signum());
            let s = p.stress(&eps);
            assert!(
                sym_diff_norm(&s, &expected) <= 1e-13 * (mag + 1.0),
                "d={dim} tr ε = {tr}: stress {:?} vs closed form {:?}",
                &s.c[..mandel_len(dim)],
                &expected.c[..mandel_len(dim)]
            );
            // Off-diagonal components are zero, the diagonal ones all equal.
            for k in dim..mandel_len(dim) {
                assert_eq!(s.c[k], 0.0);
            }
            let w = 0.5 * C_KAPPA * (tr.abs() - theta).max(0.0).powi(2);
            assert!((p.energy(&eps) - w).abs() <= 1e-13 * (w + 1e-3));
            if mag == 0.0 {
                zero += 1;
            } else if tr > 0.0 {
                pos += 1;
            } else {
                neg += 1;
            }
        }
    }
    assert!(pos >= 5 && neg >= 5 && zero >= 5, "{pos} {neg} {zero}");
    // A hand value: tr ε = −0.2 in 2D gives σ = −C_κ·0.04 I = −400 I.
    let eps = Sym {
        dim: 2,
        c: [-0.125, -0.075, 0.03, 0.0, 0.0, 0.0],
    };
    let s = p.stress(&eps);
    assert!((s.c[0] + 400.0).abs() < 1e-9 && (s.c[1] + 400.0).abs() < 1e-9);
    assert_eq!(s.c[2], 0.0);
}

#[test]
fn hencky_without_stiffening_is_hooke() {
    for dim in [2, 3] {
        let (k, g) = (1500.0, 700.0);
        let hen = Hencky {
            bulk: k,
            shear: g,
            shear_inf: g,
            s0: 0.01,
        };
        let hoo = Hooke {
            lambda: k - 2.0 * g / dim as f64,
            mu: g,
        };
        let n = mandel_len(dim);
        let mut rng = Rng::new(77 + dim as u64);
        for _ in 0..30 {
            let eps = {
                let sc = rng.log_uniform(1e-4, 1.0);
                random_strain(&mut rng, dim, sc)
            };
            let (we, wo) = (hen.energy(&eps), hoo.energy(&eps));
            assert!(
                (we - wo).abs() <= 1e-12 * wo.abs(),
                "d={dim}: energy {we} vs {wo}"
            );
            let (se, so) = (hen.stress(&eps), hoo.stress(&eps));
            assert!(
                sym_diff_norm(&se, &so) <= 1e-12 * so.norm(),
                "d={dim}: stress"
            );
            let (te, to) = (hen.tangent(&eps), hoo.tangent(&eps));
            assert!(
                tangent_diff_norm(&te, &to, n) <= 1e-12 * tangent_norm(&to, n),
                "d={dim}: tangent"
            );
        }
        // The elasticity wrapper's small-strain Hooke law is the same λ, G.
        let ss = Elasticity::Hencky(hen).small_strain_hooke(dim);
        assert!((ss.lambda - hoo.lambda).abs() <= 1e-12 * k);
        assert!((ss.mu - hoo.mu).abs() <= 1e-12 * g);
    }
}

#[test]
fn hencky_is_strongly_monotone_and_lipschitz() {
    let law = hencky();
    for dim in [2, 3] {
        let m_a = law.monotonicity(dim);
        let l_a = law.lipschitz(dim);
        assert!(m_a > 0.0 && l_a >= m_a);
        let mut rng = Rng::new(31 + dim as u64);
        for s in 0..400 {
            let a = {
                let sc = rng.log_uniform(1e-3, 1.0);
                random_strain(&mut rng, dim, sc)
            };
            // Alternate far-apart pairs and nearby pairs (the local tangent bounds).
            let b = if s % 2 == 0 {
                {
                    let sc = rng.log_uniform(1e-3, 1.0);
                    random_strain(&mut rng, dim, sc)
                }
            } else {
                a.add_scaled(1.0, &random_strain(&mut rng, dim, 1e-4))
            };
            let dab = a.add_scaled(-1.0, &b);
            let ds = law.stress(&a).add_scaled(-1.0, &law.stress(&b));
            let dd = dab.dot(&dab);
            let mono = ds.dot(&dab);
            assert!(
                mono >= m_a * dd * (1.0 - 1e-10),
                "d={dim}: (σ(a)−σ(b)):(a−b) = {mono:e} < m_A‖a−b‖² = {:e}",
                m_a * dd
            );
            assert!(
                ds.norm() <= l_a * dd.sqrt() * (1.0 + 1e-10),
                "d={dim}: ‖σ(a)−σ(b)‖ = {:e} > L_A‖a−b‖ = {:e}",
                ds.norm(),
                l_a * dd.sqrt()
            );
        }
        // The constants are not vacuous. (i) At small strains, a deviatoric increment sees
        // exactly 2G = m_A (here 2G < dK). (ii) A radial deviatoric increment at
        // s = ‖ε^D‖² = 1.5 s₀ sees 2Φ'(s) + 4sΦ''(s) = 2G_∞ + (G_∞ − G)(4x − 2)e^{−x},
        // x = s/s₀ (the maximum over s of this stiffness), which must be ≤ L_A.
        assert!(2.0 * law.shear < dim as f64 * law.bulk);
        let dev = random_strain(&mut rng, dim, 1.0).deviator();
        let dev = dev.scaled(1.0 / dev.norm());
        let a = dev.scaled(1e-5);
        let b = a.add_scaled(1e-7, &dev);
        let ratio = law.stress(&b).add_scaled(-1.0, &law.stress(&a)).norm() / 1e-7;
        assert!(
            (ratio - m_a).abs() <= 1e-3 * m_a,
            "d={dim}: small-strain deviatoric stiffness {ratio} vs m_A = {m_a}"
        );
        let x: f64 = 1.5;
        let a = dev.scaled((x * law.s0).sqrt());
        let b = a.add_scaled(1e-7, &dev);
        let ratio = law.stress(&b).add_scaled(-1.0, &law.stress(&a)).norm() / 1e-7;
        let dg = law.shear_inf - law.shear;
        let expected = 2.0 * law.shear_inf + dg * (4.0 * x - 2.0) * (-x).exp();
        assert!(
            (ratio - expected).abs() <= 1e-5 * expected,
            "d={dim}: peak deviatoric stiffness {ratio} vs closed form {expected}"
        );
        assert!(
            expected <= l_a && expected >= 0.8 * l_a,
            "{expected} vs L_A = {l_a}"
        );
    }
}

/// The augmented Lagrangian term of ideal locking, `(1/2r)[(λ + rQ)_+² − λ²]`: stress and
/// tangent match finite differences in both states, for all three sets in 2D and 3D; with
/// λ = 0 it is the penalty with C_κ = r; and its stress magnitude is the updated multiplier.
#[test]
fn augmented_locking_matches_finite_differences_and_the_penalty() {
    for (k, (name, set)) in locking_sets().into_iter().enumerate() {
        let q_ref = match set {
            LockingSet::LimitedCompressibility { theta } => theta,
            LockingSet::Prager { kappa } => kappa * kappa,
            LockingSet::Ball { r } => r,
        };
        let r = C_KAPPA;
        // λ < r q_ref / 2 keeps the active region away from the kinks of ∂Q (tr ε = 0, ε = 0).
        let al = AugmentedLocking {
            set,
            r,
            lambda: 0.3 * r * q_ref,
        };
        for dim in [2, 3] {
            let seed = 700 + 10 * k as u64 + dim as u64;
            check_derivatives(name, &al, None, dim, seed, 24, (0.05, 0.6));
            let mut rng = Rng::new(seed + 3);
            let (mut active, mut inactive) = (0, 0);
            let zero = AugmentedLocking { lambda: 0.0, ..al };
            let pen = LockingPenalty { set, c_kappa: r };
            for _ in 0..200 {
                let scale = rng.log_uniform(0.05, 0.6);
                let eps = random_strain(&mut rng, dim, scale);
                let m = al.multiplier(&eps);
                let q = set.q(&eps);
                assert!((m - (al.lambda + r * q).max(0.0)).abs() <= 1e-12 * (m + al.lambda));
                if m > 0.0 {
                    active += 1;
                    // Stress = (λ + rQ)_+ ∂Q.
                    let expect = set.dq(&eps).scaled(m);
                    assert!(sym_diff_norm(&al.stress(&eps), &expect) <= 1e-12 * expect.norm());
                } else {
                    inactive += 1;
                    assert_eq!(al.stress(&eps).norm(), 0.0);
                }
                // λ = 0: the penalty (energy, stress).
                let (e1, e2) = (zero.energy(&eps), pen.energy(&eps));
                assert!(
                    (e1 - e2).abs() <= 1e-12 * e2.abs().max(1e-300),
                    "{name}: {e1} vs {e2}"
                );
                assert!(
                    sym_diff_norm(&zero.stress(&eps), &pen.stress(&eps))
                        <= 1e-9 * (1.0 + pen.stress(&eps).norm())
                );
            }
            assert!(
                active > 10 && inactive > 10,
                "{name} d={dim}: {active} active, {inactive} inactive"
            );
        }
    }
}
