//! Isotropic Hooke's law: `A ε = λ tr(ε) I + 2G ε`.
//!
//! Energy `W(ε) = λ/2 (tr ε)² + G ε:ε`; stress `σ = λ tr(ε) I + 2G ε`;
//! tangent `λ I ⊗ I + 2G 𝕀`; out-of-plane stress in plane strain `σ_zz = λ tr ε`. Strongly monotone with constant `m_A = 2G` when `λ ≥ 0`
//! (always true for `0 ≤ ν < 1/2`), Lipschitz with constant `dλ + 2G`.

use super::StrainEnergy;
use crate::tensor::{add_identity, add_outer, zero_tangent, Sym, Tangent};

/// Two-dimensional idealization of a plane problem.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Plane {
    /// Plane strain: `λ = Eν/((1+ν)(1−2ν))` (also used in 3D).
    Strain,
    /// Plane stress: `λ = Eν/(1−ν²)`.
    Stress,
}

/// Isotropic linear elasticity with Lamé constants `lambda` and `mu` (Pa).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hooke {
    /// First Lamé constant λ (Pa).
    pub lambda: f64,
    /// Shear modulus G = μ_Lamé (Pa).
    pub mu: f64,
}

impl Hooke {
    /// Lamé constants from Young's modulus `young` (Pa) and Poisson ratio `poisson`, for
    /// the given plane idealization (ignored in 3D, where the plane-strain formula is the
    /// 3D one).
    pub fn from_young_poisson(young: f64, poisson: f64, dim: usize, plane: Plane) -> Self {
        let mu = young / (2.0 * (1.0 + poisson));
        let lambda = if dim == 2 && plane == Plane::Stress {
            young * poisson / (1.0 - poisson * poisson)
        } else {
            young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson))
        };
        Hooke { lambda, mu }
    }

    /// Strong monotonicity constant `m_A` of A (Pa) in dimension `dim`: the smallest
    /// eigenvalue of the tangent, `min(2G, dλ + 2G)` (deviatoric and volumetric
    /// directions): `2G` for `λ ≥ 0`.
    pub fn monotonicity(&self, dim: usize) -> f64 {
        2.0 * self.mu + (dim as f64 * self.lambda).min(0.0)
    }
}

impl StrainEnergy for Hooke {
    #[inline]
    fn energy(&self, eps: &Sym) -> f64 {
        let tr = eps.trace();
        0.5 * self.lambda * tr * tr + self.mu * eps.dot(eps)
    }

    #[inline]
    fn stress(&self, eps: &Sym) -> Sym {
        let tr = eps.trace();
        eps.scaled(2.0 * self.mu)
            .add_scaled(self.lambda * tr, &Sym::identity(eps.dim))
    }

    #[inline]
    fn tangent(&self, eps: &Sym) -> Tangent {
        let mut t = zero_tangent();
        let i = Sym::identity(eps.dim);
        add_outer(&mut t, self.lambda, &i, &i);
        add_identity(&mut t, eps.dim, 2.0 * self.mu);
        t
    }

    /// `σ_zz = λ tr ε`: 3D Hooke's law at `ε_zz = 0`.
    #[inline]
    fn plane_strain_stress_zz(&self, eps: &Sym) -> f64 {
        self.lambda * eps.trace()
    }
}
