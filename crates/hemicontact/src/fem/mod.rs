//! P1 finite element space: degree-of-freedom numbering, the translation its supports carry a
//! body by, rigid motions and transfer between meshes, on the simplex geometry of
//! [`crate::geometry::simplex`].

pub mod carry;
pub mod dofs;
pub mod rigid;
/// The simplex geometry, now on the ground floor in [`crate::geometry::simplex`]; kept here
/// so that `hemicontact::fem::simplex` still names it.
pub use crate::geometry::simplex;
pub mod transfer;
