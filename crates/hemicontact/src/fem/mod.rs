//! P1 finite element space: degree-of-freedom numbering and transfer between meshes, on the
//! simplex geometry of [`crate::geometry::simplex`]. The rigid motions and the translation
//! its supports carry a body by are a floor above, in [`crate::rigid`] (they read the
//! contact points).

/// The translation its supports carry a body by, now in [`crate::rigid::carry`]; kept here
/// so that `hemicontact::fem::carry` still names it.
pub use crate::rigid::carry;
pub mod dofs;
/// The simplex geometry, now on the ground floor in [`crate::geometry::simplex`]; kept here
/// so that `hemicontact::fem::simplex` still names it.
pub use crate::geometry::simplex;
/// The rigid motions the supports leave free, now the top-level [`crate::rigid`]; kept here
/// so that `hemicontact::fem::rigid` still names it.
pub use crate::rigid;
pub mod transfer;
