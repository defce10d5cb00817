//! Ground-floor geometry: the measure and hat-function gradients of one simplex, shared by
//! the mesh (orientation checks) and the finite element space above it.

pub mod simplex;
