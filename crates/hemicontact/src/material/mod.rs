//! Pointwise constitutive laws: a constant strain in, energy density, stress and tangent out.
//!
//! The stored energy density of the body is `W(ε) + Ψ(ε)` (SPEC §2 and §4: `A = ∂W`, Ψ the
//! nearly-locking penalty); the laws here know nothing of meshes or DOFs, so each is
//! testable on its own (finite-difference checks of stress against energy and of tangent
//! against stress live in `tests/`).

pub mod hencky;
pub mod hooke;
pub mod locking;

pub use hencky::Hencky;
pub use hooke::{Hooke, Plane};
pub use locking::{AugmentedLocking, LockingPenalty, LockingSet};

use crate::tensor::{Sym, Tangent};

/// A hyperelastic law: energy density `W(ε)` (J/m³), stress `σ = ∂W/∂ε` (Pa) and tangent
/// `∂σ/∂ε` (Pa), all in Mandel notation (see [`crate::tensor`]).
pub trait StrainEnergy {
    /// Energy density `W(ε)`.
    fn energy(&self, eps: &Sym) -> f64;
    /// Stress `σ = ∂W/∂ε`.
    fn stress(&self, eps: &Sym) -> Sym;
    /// Tangent `∂σ/∂ε` (a generalized derivative where σ is only piecewise smooth).
    fn tangent(&self, eps: &Sym) -> Tangent;
}

/// The elasticity operator A = ∂W (SPEC §2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Elasticity {
    /// Isotropic Hooke's law.
    Hooke(Hooke),
    /// Strain-stiffening Hencky law.
    Hencky(Hencky),
}

impl Elasticity {
    /// Strong monotonicity constant `m_A` (Pa) in dimension `dim`.
    pub fn monotonicity(&self, dim: usize) -> f64 {
        match self {
            Elasticity::Hooke(h) => h.monotonicity(dim),
            Elasticity::Hencky(h) => h.monotonicity(dim),
        }
    }

    /// The Hooke operator used for the energy norm of SPEC §5: Hooke's law itself, or the
    /// small-strain Hooke law of the Hencky model (`λ = K − 2G/d`, `G`).
    pub fn small_strain_hooke(&self, dim: usize) -> Hooke {
        match *self {
            Elasticity::Hooke(h) => h,
            Elasticity::Hencky(h) => Hooke {
                lambda: h.bulk - 2.0 * h.shear / dim as f64,
                mu: h.shear,
            },
        }
    }
}

impl Elasticity {
    /// The same law for the dimensionless strain `ε̂ = ε/e` and energy density `Ŵ = W/(S e²)`
    /// (S the stress scale, Pa): the moduli divided by S; the Hencky transition strain
    /// `s₀` (a squared strain) divided by e².
    pub fn nondimensional(&self, stress: f64, e: f64) -> Elasticity {
        match *self {
            Elasticity::Hooke(h) => Elasticity::Hooke(Hooke {
                lambda: h.lambda / stress,
                mu: h.mu / stress,
            }),
            Elasticity::Hencky(h) => Elasticity::Hencky(Hencky {
                bulk: h.bulk / stress,
                shear: h.shear / stress,
                shear_inf: h.shear_inf / stress,
                s0: h.s0 / (e * e),
            }),
        }
    }
}

impl StrainEnergy for Elasticity {
    #[inline]
    fn energy(&self, eps: &Sym) -> f64 {
        match self {
            Elasticity::Hooke(h) => h.energy(eps),
            Elasticity::Hencky(h) => h.energy(eps),
        }
    }
    #[inline]
    fn stress(&self, eps: &Sym) -> Sym {
        match self {
            Elasticity::Hooke(h) => h.stress(eps),
            Elasticity::Hencky(h) => h.stress(eps),
        }
    }
    #[inline]
    fn tangent(&self, eps: &Sym) -> Tangent {
        match self {
            Elasticity::Hooke(h) => h.tangent(eps),
            Elasticity::Hencky(h) => h.tangent(eps),
        }
    }
}

/// The bulk material of the body: elasticity plus the nearly-locking penalty.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Elasticity operator A = ∂W.
    pub elasticity: Elasticity,
    /// Nearly-locking penalty Ψ ([`LockingPenalty::NONE`] without locking or with ideal
    /// locking).
    pub locking: LockingPenalty,
    /// Ideal locking: the exact constraint `ε_T ∈ B` in every cell, imposed by an augmented
    /// Lagrangian ([`AugmentedLocking`]); `None` for no or nearly locking.
    pub ideal_locking: Option<LockingSet>,
}

impl Material {
    /// A material with elasticity `elasticity` and no locking.
    pub fn elastic(elasticity: Elasticity) -> Self {
        Material {
            elasticity,
            locking: LockingPenalty::NONE,
            ideal_locking: None,
        }
    }
}

impl Material {
    /// The same material for the dimensionless strain `ε̂ = ε/e` and energy density
    /// `Ŵ = W/(S e²)` (S the stress scale, Pa), with the unit of its ideal-locking
    /// multiplier `S e²/q` (Pa; q the unit of the locking function,
    /// [`LockingSet::nondimensional`]). The penalty `Ψ = (C_κ/2) Q_+²` keeps its form with
    /// `Ĉ_κ = C_κ q²/(S e²)`.
    pub fn nondimensional(&self, stress: f64, e: f64) -> (Material, f64) {
        let (set, q) = self.locking.set.nondimensional(e);
        let locking = LockingPenalty {
            set,
            c_kappa: self.locking.c_kappa * (q / e) * (q / e) / stress,
        };
        let (ideal_locking, multiplier_unit) = match self.ideal_locking {
            Some(b) => {
                let (set, q) = b.nondimensional(e);
                (Some(set), stress * (e / q) * e)
            }
            None => (None, stress * e),
        };
        let material = Material {
            elasticity: self.elasticity.nondimensional(stress, e),
            locking,
            ideal_locking,
        };
        (material, multiplier_unit)
    }
}

impl StrainEnergy for Material {
    #[inline]
    fn energy(&self, eps: &Sym) -> f64 {
        self.elasticity.energy(eps) + self.locking.energy(eps)
    }
    #[inline]
    fn stress(&self, eps: &Sym) -> Sym {
        let s = self.elasticity.stress(eps);
        if self.locking.c_kappa == 0.0 {
            return s;
        }
        let p = self.locking.stress(eps);
        s.add_scaled(1.0, &p)
    }
    #[inline]
    fn tangent(&self, eps: &Sym) -> Tangent {
        let mut t = self.elasticity.tangent(eps);
        if self.locking.is_active(eps) {
            let p = self.locking.tangent(eps);
            for (row, prow) in t.iter_mut().zip(p.iter()) {
                for (a, b) in row.iter_mut().zip(prow.iter()) {
                    *a += b;
                }
            }
        }
        t
    }
}
