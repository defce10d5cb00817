//! Contact and friction on Γ_C: pointwise laws ([`normal`], [`friction`], with user-defined
//! friction coefficients of the slip in [`slip_law`] and of the position in [`field_law`]) and the contact nodes with their lumped weights,
//! normals and tangents ([`nodes`]), and the gap and normal of rigid obstacles of given
//! shape by closest-point projection ([`obstacle`]).
//!
//! Conventions: `ν` is the outward unit normal of the body; `u_ν = u·ν` is the
//! normal displacement and `g ≥ 0` the initial gap to the foundation, so `u_ν − g > 0` is a
//! penetration. The tangential displacement `u_τ = u − u_ν ν` is stored in the coordinates of
//! an orthonormal tangent basis (1 component in 2D, 2 in 3D). The interface force on the
//! body has normal part `σ_ν = −p(u_ν) ≤ 0` and tangential part `σ_τ ∈ −F ∂j(u_τ)`.

pub mod compliance_law;
mod describe;
pub mod field_law;
pub mod friction;
pub mod nodes;
pub mod normal;
pub mod obstacle;
pub mod slip_law;

pub use compliance_law::{ComplianceFunction, CustomCompliance, NormalResponse};
pub use field_law::{CustomField, PositionFunction};
pub use friction::{
    Friction, FrictionBound, FrictionCoefficient, FrictionPotential, NormTreatment, TangentialData,
    TangentialTerm,
};
pub use nodes::ContactNodes;
pub use normal::{NormalCompliance, NormalLaw};
pub use slip_law::{CustomCoefficient, SlipFunction};

/// One contact boundary: a part of the mesh facing a rigid foundation, with its laws.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactBoundary {
    /// Boundary part index (see [`crate::mesh::Mesh::part_names`]).
    pub part: usize,
    /// Initial gap g ≥ 0 along the normal (m).
    pub gap: f64,
    /// Normal law: normal compliance or the Signorini constraint.
    pub normal: NormalLaw,
    /// Friction law, or `None` for frictionless contact.
    pub friction: Option<Friction>,
}

impl ContactBoundary {
    /// Checks the laws and the gap of the boundary (not its part, which only a
    /// [`crate::problem::Problem`] can check against its mesh).
    ///
    /// # Errors
    /// [`crate::Error::Invalid`] naming the parameter: `gap` finite and ≥ 0, and the ranges
    /// of [`NormalLaw::validate`] and [`Friction::validate`] (under `friction.`).
    pub fn validate(&self) -> crate::Result<()> {
        crate::error::require(
            self.gap.is_finite() && self.gap >= 0.0,
            "gap",
            self.gap,
            "a gap g ≥ 0 (m)",
        )?;
        self.normal.validate()?;
        match &self.friction {
            Some(f) => f.validate().map_err(|e| e.within("friction")),
            None => Ok(()),
        }
    }
}
