//! Pointwise constitutive laws: a constant strain in, energy density, stress and tangent out.
//!
//! The stored energy density of the body is `W(ε)` (SPEC §2: `A = ∂W`); the laws here know
//! nothing of meshes or DOFs, so each is testable on its own (finite-difference checks of
//! stress against energy and of tangent against stress live in `tests/`).

pub mod hooke;

pub use hooke::{Hooke, Plane};

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

/// The bulk material of the body: the elasticity law (SPEC §2, "Elasticity A").
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Elasticity operator A = ∂W.
    pub elasticity: Hooke,
}

impl StrainEnergy for Material {
    #[inline]
    fn energy(&self, eps: &Sym) -> f64 {
        self.elasticity.energy(eps)
    }
    #[inline]
    fn stress(&self, eps: &Sym) -> Sym {
        self.elasticity.stress(eps)
    }
    #[inline]
    fn tangent(&self, eps: &Sym) -> Tangent {
        self.elasticity.tangent(eps)
    }
}
