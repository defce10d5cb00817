//! Rigid motions left free by the Dirichlet conditions, found algebraically from the mesh
//! and the pattern of prescribed components (independent of loads and of the linear solver).
//!
//! The linear elastic energy of a connected body vanishes exactly on its rigid motions. On
//! each connected component of the cell graph (a *body*) these are, in coefficients
//! `c ∈ ℝ^m` (m = 3 in 2D, 6 in 3D),
//!
//! ```text
//!     r(x) = a + ω × (x − x̄),   a = (c_1, …, c_d),   ω = (c_{d+1}, …, c_m) / L
//! ```
//!
//! about the body's centroid `x̄` (mean of its node coordinates), with `L` the largest
//! distance of a node from `x̄`; so every basis field has components of size at most 1 at
//! every node, and the matrices below are well scaled whatever the units and the size.
//!
//! Each prescribed DOF (node `v`, component `i`) is a row `C_{·j} = φ_j(x_v)_i` of the
//! constraint matrix acting on `c`; the free motions are the null space of the normal
//! matrix `N = CᵀC` (m × m), computed by a Jacobi eigendecomposition. An eigenvalue counts
//! as zero when it is at most [`NULL_TOLERANCE`] times `tr N`. Every row has norm between 1
//! (its translation entry) and √2, so `tr N` lies between the row count and twice it, the
//! round-off of `N` is about `10⁻¹⁶ tr N`, and the tolerance `10⁻¹⁰ tr N` sits six orders
//! above it; the price is that a rotation held only by lever arms below about `10⁻⁵ L`
//! counts as free — such a constraint would leave the stiffness matrix with a condition
//! number above 10¹⁰ anyway.
//!
//! A free motion is *carried* by contact when a contact point's normal (or, on a part with
//! friction, a tangent) moves under it: the same construction with one row `ν_i · r(x_i)`
//! per contact point (and `τ_i · r(x_i)` with friction), restricted to the free motions,
//! has no null space. A contact pair's point acts on the slave body at its node and on the
//! master body at its master point `x_m = Σ_j N_j x(m_j)` ([`crate::contact::ContactNodes::on_body`]); when
//! both bodies of a pair have free motions, the bodies so linked are analysed together, a
//! *group* whose unknowns are their stacked coefficients and whose pair rows are
//! `ν_i · (r_s(x_s) − r_m(x_m))` ([`groups`]; a body in no such pair is a group of one).
//! Motions neither prescribed nor carried make the problem singular: [`RigidMotions::check`]
//! turns them into an [`crate::error::Error::RigidMotion`] that names the bodies and the motion
//! (translation along x, rotation about z through a point, …) and what would block it.
//!
//! The free motions of a group split into two orthogonal subspaces (in the coefficients
//! `c`): the *sliding* motions, which move no contact point along its normal (the null
//! space of the normal rows alone: friction, if anything, carries them), and the *pressed*
//! motions, which move some contact point along its normal (normal contact carries them).
//! A block resting on a flat foundation without supports slides along the foundation's
//! plane (2D: translation along it; 3D: two translations and the rotation about the
//! normal) and is pressed along the normal and by the tilts. The solver treats them
//! differently ([`crate::solver::held`]): the rigid drop before Newton moves along the
//! pressed motions only, and the load along the sliding ones is checked against the
//! friction limit.

mod body;
pub mod carry;
mod dense;
pub mod groups;
mod motions;
mod words;

pub use body::{bodies, n_modes, Body};
pub use dense::{solve_small, solve_symmetric, NULL_TOLERANCE};
pub use groups::{Group, Motion, Side};
pub use motions::{RigidMotions, Runaway, NEWTON_SHIFT};
pub use words::describe;
