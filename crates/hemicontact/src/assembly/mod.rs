//! Global assembly: the bulk energy of a displacement field, its gradient and its
//! (generalized) Hessian on a fixed sparsity pattern.
//!
//! The local/global split follows the classical design: [`element`] computes per-cell
//! quantities into small fixed-size arrays, [`pattern`] owns the global indexing (built
//! once per mesh and DOF map), and [`global`] loops over cells and scatters;
//! [`magnitudes`] sums the magnitudes of the terms of every gradient entry (its round-off);
//! [`norms`] measures a displacement field (its energy norm, its largest nodal value).

pub mod contact;
pub mod element;
pub mod global;
pub mod magnitudes;
pub mod norms;
pub mod pattern;

/// The consistent nodal loads of constant data, which the problem's external forces sum
/// ([`crate::problem::loads`], where they live: the problem's own data).
pub use crate::problem::loads;
pub use global::BulkAssembler;
pub use pattern::SystemPattern;
