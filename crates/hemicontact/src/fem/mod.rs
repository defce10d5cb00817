//! P1 finite element space: simplex geometry and degree-of-freedom numbering.

pub mod carry;
pub mod dofs;
pub mod rigid;
pub mod simplex;
pub mod transfer;
