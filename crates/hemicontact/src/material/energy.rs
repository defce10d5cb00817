//! The interface every pointwise hyperelastic law implements: energy density, stress and
//! tangent of a constant strain.

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
    /// Out-of-plane normal stress `σ_zz = ∂W/∂ε_zz` (Pa) of a two-dimensional strain `eps`
    /// under plane strain (`ε_zz = 0`); see the [`crate::material`] module documentation.
    fn plane_strain_stress_zz(&self, eps: &Sym) -> f64;
}
