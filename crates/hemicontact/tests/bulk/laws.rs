//! # Verification: constitutive laws (derivative consistency and closed forms)
//!
//! What is verified, and why it must hold:
//!
//! - **Stress is the gradient of the energy.** A hyperelastic law has `σ = ∂W/∂ε`. Strains
//!   and stresses are Mandel vectors (`[a_xx, a_yy, √2 a_xy]` in 2D, six components in 3D),
//!   in which the Euclidean inner product *is* the double contraction `a : b`. Hence the
//!   partial derivative of `W` with respect to Mandel component `k` is exactly Mandel
//!   component `k` of the stress: a central finite difference of the energy in Mandel
//!   components must reproduce `stress(ε)` with no shear factors.
//! - **Tangent is the Jacobian of the stress**, column by column, and is symmetric
//!   (hyperelasticity).
//! - **Closed forms of Hooke's law.** `σ = λ tr(ε) I + 2G ε` written on full matrices;
//!   `2W = σ : ε` (W is homogeneous of degree 2); the tangent maps `I` to `(dλ + 2G) I` and
//!   every deviatoric tensor `e` to `2G e` (its two eigenvalues, whence `m_A = 2G`).
//! - **Lamé constants** of `Hooke::from_young_poisson` against hand values for E = 2000,
//!   ν = 0.3 (the paper's material): plane strain / 3D `λ = 15000/13`, `G = 10000/13`;
//!   plane stress `λ = Eν/(1−ν²) = 60000/91`.
//!
//! For a quadratic energy the central differences are exact up to round-off, so the
//! tolerances are round-off tolerances (1e-7 relative), far below any modelling error
//! (a missing √2 or factor 2 would show as an O(1) relative error).
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use common::{random_strain, Rng};
use hemicontact::material::{Hooke, Plane, StrainEnergy};
use hemicontact::tensor::{mandel_len, Sym};

/// Checks `stress ≈ ∇W` and `tangent ≈ ∇σ` by central differences in Mandel components,
/// and the symmetry of the tangent, at `samples` random strains. Generic, so every law of
/// the catalogue can reuse it.
fn check_derivatives<L: StrainEnergy>(law: &L, dim: usize, scale: f64, seed: u64, samples: usize) {
    let n = mandel_len(dim);
    let mut rng = Rng::new(seed);
    for s in 0..samples {
        let eps = random_strain(&mut rng, dim, scale);
        let sigma = law.stress(&eps);
        let tangent = law.tangent(&eps);
        let h = 1e-6 * scale;
        let sigma_norm = sigma.norm().max(f64::MIN_POSITIVE);
        let tangent_norm = (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .map(|(i, j)| tangent[i][j].powi(2))
            .sum::<f64>()
            .sqrt();
        for k in 0..n {
            let (mut ep, mut em) = (eps, eps);
            ep.c[k] += h;
            em.c[k] -= h;
            let fd = (law.energy(&ep) - law.energy(&em)) / (2.0 * h);
            assert!(
                (fd - sigma.c[k]).abs() <= 1e-7 * sigma_norm,
                "dim {dim} sample {s}: dW/dε[{k}] = {fd:e} but σ[{k}] = {:e}",
                sigma.c[k]
            );
            let (sp, sm) = (law.stress(&ep), law.stress(&em));
            for i in 0..n {
                let fd = (sp.c[i] - sm.c[i]) / (2.0 * h);
                assert!(
                    (fd - tangent[i][k]).abs() <= 1e-7 * tangent_norm,
                    "dim {dim} sample {s}: dσ[{i}]/dε[{k}] = {fd:e} but C[{i}][{k}] = {:e}",
                    tangent[i][k]
                );
            }
        }
        for i in 0..n {
            for j in 0..n {
                assert!(
                    (tangent[i][j] - tangent[j][i]).abs() <= 1e-14 * tangent_norm,
                    "tangent not symmetric at ({i}, {j})"
                );
            }
        }
        // Padding beyond the Mandel length stays zero.
        assert!(sigma.c[n..].iter().all(|&x| x == 0.0));
        for (i, row) in tangent.iter().enumerate() {
            for (j, &x) in row.iter().enumerate() {
                if i >= n || j >= n {
                    assert_eq!(x, 0.0, "tangent padding ({i}, {j}) is not zero");
                }
            }
        }
    }
}

#[test]
fn hooke_stress_and_tangent_are_derivatives_2d() {
    for plane in [Plane::Strain, Plane::Stress] {
        let law = Hooke::from_young_poisson(2000.0, 0.3, 2, plane);
        check_derivatives(&law, 2, 1e-3, 1, 20);
        check_derivatives(&law, 2, 0.5, 2, 20);
    }
}

#[test]
fn hooke_stress_and_tangent_are_derivatives_3d() {
    let law = Hooke::from_young_poisson(2.1e11, 0.27, 3, Plane::Strain);
    check_derivatives(&law, 3, 1e-3, 3, 20);
    // A law with negative λ (auxetic, ν < 0) is still a quadratic energy.
    let law = Hooke::from_young_poisson(1.0, -0.4, 3, Plane::Strain);
    assert!(law.lambda < 0.0);
    check_derivatives(&law, 3, 1.0, 4, 20);
}

/// `σ = λ tr(ε) I + 2G ε` evaluated on full d×d matrices, compared component-wise, and the
/// Euler identity `σ : ε = 2W` of a quadratic energy.
#[test]
fn hooke_matches_the_closed_form_on_full_matrices() {
    let (lambda, g) = (1153.0, 769.0);
    let law = Hooke { lambda, mu: g };
    let mut rng = Rng::new(5);
    for dim in [2, 3] {
        for _ in 0..10 {
            let mut m = [[0.0; 3]; 3];
            for i in 0..dim {
                for j in i..dim {
                    m[i][j] = rng.uniform(-1.0, 1.0);
                    m[j][i] = m[i][j];
                }
            }
            let tr: f64 = (0..dim).map(|i| m[i][i]).sum();
            let eps = Sym::from_matrix(dim, &m);
            let sigma = law.stress(&eps).to_matrix();
            let mut contraction = 0.0;
            for i in 0..dim {
                for j in 0..dim {
                    let delta = if i == j { 1.0 } else { 0.0 };
                    let expected = lambda * tr * delta + 2.0 * g * m[i][j];
                    assert!(
                        (sigma[i][j] - expected).abs() <= 1e-12 * (lambda + g),
                        "dim {dim}: σ[{i}][{j}] = {} expected {expected}",
                        sigma[i][j]
                    );
                    contraction += sigma[i][j] * m[i][j];
                }
            }
            let w = law.energy(&eps);
            assert!((contraction - 2.0 * w).abs() <= 1e-12 * contraction.abs().max(1.0));
            let expected_w = 0.5 * lambda * tr * tr
                + g * (0..dim)
                    .flat_map(|i| (0..dim).map(move |j| (i, j)))
                    .map(|(i, j)| m[i][j] * m[i][j])
                    .sum::<f64>();
            assert!((w - expected_w).abs() <= 1e-12 * expected_w.abs().max(1.0));
        }
    }
}

/// The tangent has eigenvalue `dλ + 2G` on the identity and `2G` on deviatoric tensors.
#[test]
fn hooke_tangent_eigenstructure() {
    let (lambda, g) = (3.0, 2.0);
    let law = Hooke { lambda, mu: g };
    let mut rng = Rng::new(6);
    for dim in [2, 3] {
        let n = mandel_len(dim);
        let c = law.tangent(&Sym::zero(dim));
        let apply = |a: &Sym| {
            let mut out = Sym::zero(dim);
            for i in 0..n {
                out.c[i] = (0..n).map(|j| c[i][j] * a.c[j]).sum();
            }
            out
        };
        let id = Sym::identity(dim);
        let ci = apply(&id);
        let bulk = dim as f64 * lambda + 2.0 * g;
        for k in 0..n {
            assert!((ci.c[k] - bulk * id.c[k]).abs() < 1e-13);
        }
        for _ in 0..5 {
            let e = random_strain(&mut rng, dim, 1.0).deviator();
            let ce = apply(&e);
            for k in 0..n {
                assert!((ce.c[k] - 2.0 * g * e.c[k]).abs() < 1e-13);
            }
        }
        assert_eq!(law.monotonicity(dim), 2.0 * g);
    }
    // With λ < 0 (ν < 0) the smallest eigenvalue in 3D is the bulk one, 3λ + 2G > 0.
    let auxetic = Hooke::from_young_poisson(1.0, -0.4, 3, Plane::Strain);
    let smallest = 3.0 * auxetic.lambda + 2.0 * auxetic.mu;
    assert!(smallest > 0.0 && smallest < 2.0 * auxetic.mu);
    assert!((auxetic.monotonicity(3) - smallest).abs() < 1e-14);
    // In 2D the volumetric eigenvalue is 2λ + 2G (the bound is sharp there too).
    let auxetic_2d = Hooke::from_young_poisson(1.0, -0.4, 2, Plane::Strain);
    let smallest_2d = 2.0 * auxetic_2d.lambda + 2.0 * auxetic_2d.mu;
    assert!((auxetic_2d.monotonicity(2) - smallest_2d).abs() < 1e-14);
}

/// Hand values for the paper's material, E = 2000 Pa, ν = 0.3:
/// plane strain λ = 600/0.52 = 15000/13 ≈ 1153.846, G = 2000/2.6 = 10000/13 ≈ 769.231;
/// plane stress λ = 600/0.91 = 60000/91 ≈ 659.341 (same G).
#[test]
fn lame_constants_of_the_paper_material() {
    let strain = Hooke::from_young_poisson(2000.0, 0.3, 2, Plane::Strain);
    assert!((strain.lambda - 15000.0 / 13.0).abs() < 1e-9);
    assert!((strain.lambda - 1_153.846_153_846).abs() < 1e-8);
    assert!((strain.mu - 10000.0 / 13.0).abs() < 1e-9);
    assert!((strain.mu - 769.230_769_230_8).abs() < 1e-8);

    let stress = Hooke::from_young_poisson(2000.0, 0.3, 2, Plane::Stress);
    assert!((stress.lambda - 60000.0 / 91.0).abs() < 1e-9);
    assert!((stress.lambda - 659.340_659_340_7).abs() < 1e-8);
    assert!((stress.mu - 10000.0 / 13.0).abs() < 1e-9);

    // 3D ignores the plane idealization: the plane-strain formula is the 3D one.
    for plane in [Plane::Strain, Plane::Stress] {
        let h3 = Hooke::from_young_poisson(2000.0, 0.3, 3, plane);
        assert!((h3.lambda - 15000.0 / 13.0).abs() < 1e-9);
        assert!((h3.mu - 10000.0 / 13.0).abs() < 1e-9);
    }

    // Plane stress: a uniaxial stress state σ = diag(s, 0) has ε_xx = s/E and
    // ε_yy = −ν s/E (the defining property of the 2D plane-stress law).
    let e = Sym::from_matrix(
        2,
        &[
            [1.0 / 2000.0, 0.0, 0.0],
            [0.0, -0.3 / 2000.0, 0.0],
            [0.0; 3],
        ],
    );
    let s = stress.stress(&e);
    assert!((s.c[0] - 1.0).abs() < 1e-12 && s.c[1].abs() < 1e-12 && s.c[2].abs() < 1e-12);
    // Plane strain: the same uniaxial in-plane stress gives ε_xx = (1−ν²) s/E and
    // ε_yy = −ν(1+ν) s/E.
    let e = Sym::from_matrix(
        2,
        &[
            [0.91 / 2000.0, 0.0, 0.0],
            [0.0, -0.39 / 2000.0, 0.0],
            [0.0; 3],
        ],
    );
    let s = strain.stress(&e);
    assert!((s.c[0] - 1.0).abs() < 1e-12 && s.c[1].abs() < 1e-12 && s.c[2].abs() < 1e-12);
}
