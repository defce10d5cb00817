//! Contact and friction on Γ_C: pointwise laws ([`normal`], [`friction`], with user-defined
//! friction coefficients of the slip in [`slip_law`] and of the position in [`field_law`]) and the contact nodes with their lumped weights,
//! normals and tangents ([`nodes`]), the gap and normal of rigid obstacles of given
//! shape by closest-point projection ([`obstacle`]), and how an obstacle sits against its
//! contact part ([`placement`]: facing it, resolved by its mesh). A problem's contact
//! boundaries, each a part with its foundation and laws, are [`ContactBoundary`]s.
//!
//! Conventions: `ν` is the outward unit normal of the body; `u_ν = u·ν` is the
//! normal displacement and `g` the initial gap to the foundation (`g ≥ 0` for a flat
//! foundation; of either sign against an obstacle, negative where the obstacle starts out
//! pressed into the body), so `u_ν − g > 0` is a penetration. The tangential displacement
//! `u_τ = u − u_ν ν` is stored in the coordinates of an orthonormal tangent basis (1 component in 2D, 2 in 3D). The interface force on the
//! body has normal part `σ_ν = −p(u_ν) ≤ 0` and tangential part `σ_τ ∈ −F ∂j(u_τ)`.

mod boundary;
pub mod compliance_law;
mod describe;
pub mod directions;
pub mod field_law;
pub mod friction;
pub mod interpenetration;
pub mod nodes;
pub mod normal;
pub mod obstacle;
pub mod pair_placement;
pub mod pairing;
pub mod placement;
pub mod slip_law;

pub use boundary::{ContactBoundary, MasterPart};
pub use compliance_law::{ComplianceFunction, CustomCompliance, NormalResponse};
pub use field_law::{CustomField, PositionFunction};
pub use friction::{
    Friction, FrictionBound, FrictionCoefficient, FrictionPotential, NormTreatment, TangentialData,
    TangentialTerm,
};
pub use nodes::ContactNodes;
pub use normal::{NormalCompliance, NormalLaw};
pub use obstacle::{ContactObstacle, Obstacle, ObstacleSpec};
pub use slip_law::{CustomCoefficient, SlipFunction};
