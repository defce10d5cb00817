//! P1 finite element space: degree-of-freedom numbering and transfer between meshes, on the
//! simplex geometry of [`crate::geometry::simplex`]. The rigid motions and the translation
//! its supports carry a body by are a floor above, in [`crate::rigid`] (they read the
//! contact points).

pub mod dofs;
pub mod transfer;
