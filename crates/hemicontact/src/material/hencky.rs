//! A strain-stiffening Hencky law satisfying the paper's hypotheses on A:
//! `W(ε) = ½ K (tr ε)² + Φ(‖ε^D‖²)` with
//! `Φ(s) = G_∞ s − (G_∞ − G) s₀ (1 − e^{−s/s₀})`, so that
//! `Φ'(s) = G_∞ − (G_∞ − G) e^{−s/s₀}` rises from `G` (small strains) to `G_∞ ≥ G`
//! (large deviatoric strains) and `Φ'' ≥ 0` (Φ convex).
//!
//! Stress `σ = K tr(ε) I + 2Φ'(s) ε^D`, tangent `K I⊗I + 2Φ'(s) 𝕀^D + 4Φ''(s) ε^D⊗ε^D`
//! with `s = ‖ε^D‖²` and `𝕀^D = 𝕀 − (1/d) I⊗I`. Out-of-plane stress in plane strain (d = 2,
//! see [`crate::material`]): `σ_zz = (K − Φ'(s)) tr ε`.
//!
//! Constants (d the dimension): strongly monotone with `m_A = min(dK, 2G)` (the Hessian is
//! at least `dK` on the volumetric direction and at least `2Φ' ≥ 2G` on deviatoric ones),
//! Lipschitz with `L_A = max(dK, 2G_∞ + 4(G_∞ − G)/e)` (since `sup_s s Φ''(s) = (G_∞−G)/e`),
//! and `A(0) = 0`. With `G_∞ = G` it is Hooke's law with `K = λ + 2G/d`.

use super::StrainEnergy;
use crate::tensor::{add_identity, add_outer, zero_tangent, Sym, Tangent};

/// Strain-stiffening Hencky law; see the module documentation. Moduli in Pa.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hencky {
    /// Bulk-type modulus K of the volumetric energy `½ K (tr ε)²` (Pa).
    pub bulk: f64,
    /// Small-strain shear modulus G (Pa).
    pub shear: f64,
    /// Large-strain shear modulus G_∞ ≥ G (Pa).
    pub shear_inf: f64,
    /// Reference squared deviatoric strain s₀ > 0 of the transition.
    pub s0: f64,
}

impl Hencky {
    /// Strong monotonicity constant `m_A = min(dK, 2G)` (Pa).
    pub fn monotonicity(&self, dim: usize) -> f64 {
        (dim as f64 * self.bulk).min(2.0 * self.shear)
    }

    /// Lipschitz constant `L_A = max(dK, 2G_∞ + 4(G_∞ − G)/e)` (Pa).
    pub fn lipschitz(&self, dim: usize) -> f64 {
        let dev = 2.0 * self.shear_inf + 4.0 * (self.shear_inf - self.shear) / std::f64::consts::E;
        (dim as f64 * self.bulk).max(dev)
    }

    #[inline]
    fn phi(&self, s: f64) -> (f64, f64, f64) {
        let dg = self.shear_inf - self.shear;
        let e = (-s / self.s0).exp();
        let phi = self.shear_inf * s - dg * self.s0 * (1.0 - e);
        (phi, self.shear_inf - dg * e, dg / self.s0 * e)
    }
}

impl StrainEnergy for Hencky {
    #[inline]
    fn energy(&self, eps: &Sym) -> f64 {
        let tr = eps.trace();
        let dev = eps.deviator();
        0.5 * self.bulk * tr * tr + self.phi(dev.dot(&dev)).0
    }

    #[inline]
    fn stress(&self, eps: &Sym) -> Sym {
        let dev = eps.deviator();
        let (_, d1, _) = self.phi(dev.dot(&dev));
        dev.scaled(2.0 * d1)
            .add_scaled(self.bulk * eps.trace(), &Sym::identity(eps.dim))
    }

    #[inline]
    fn tangent(&self, eps: &Sym) -> Tangent {
        let d = eps.dim;
        let dev = eps.deviator();
        let (_, d1, d2) = self.phi(dev.dot(&dev));
        let i = Sym::identity(d);
        let mut t = zero_tangent();
        add_outer(&mut t, self.bulk - 2.0 * d1 / d as f64, &i, &i);
        add_identity(&mut t, d, 2.0 * d1);
        add_outer(&mut t, 4.0 * d2, &dev, &dev);
        t
    }

    /// `σ_zz = (K − (2/d) Φ'(s)) tr ε`: with `s = ε:ε − (tr ε)²/d`,
    /// `∂s/∂ε_zz = 2ε_zz − (2/d) tr ε = −(2/d) tr ε` at `ε_zz = 0`.
    #[inline]
    fn plane_strain_stress_zz(&self, eps: &Sym) -> f64 {
        let dev = eps.deviator();
        let (_, d1, _) = self.phi(dev.dot(&dev));
        (self.bulk - 2.0 * d1 / eps.dim as f64) * eps.trace()
    }
}
