//! Bodies held by contact alone: the free rigid motions of a body (those the Dirichlet
//! conditions leave free, [`crate::rigid`]) that contact carries.
//!
//! The free motions of a body split into *pressed* ones, which move some contact point
//! along its normal (normal contact carries them), and *sliding* ones, which move every
//! contact point within its tangent plane (only friction can carry them). Two things
//! follow.
//!
//! Everything below runs over a *group* of bodies ([`crate::rigid::groups`]): the
//! bodies whose contact pairs join two of them with free motions, analysed together. Its
//! motions are those of its bodies together ([`crate::rigid::Motion`]), the
//! coefficients c below are its stacked coefficients (at most 6 per body), and the row of
//! a point between two of its bodies is the change of the point's relative displacement,
//! `r_s(x_s) − r_m(x_m)`. A body in no such pair is a group of one.
//!
//! # The rigid drop
//!
//! A body resting across a gap (a block above its foundation) first moves rigidly until
//! it touches, then deforms. When the load is small the deformation is many orders of
//! magnitude below the gap: the displacement scale U of [`super::scaling`] follows the
//! load, the gap is `g/U` in its units, and Newton's method would cross it in steps of
//! the size the shift of the Newton matrix allows ([`crate::rigid::NEWTON_SHIFT`]),
//! thousands of them; worse, a displacement `g + δ` with `δ ≪ g` cannot even carry the
//! digits of δ. So before Newton ([`rigid_drop`]), every such body is moved along its
//! pressed motions to where it rests on its contact points: the rigid motion `u_R` that
//! maximizes the work of the load `f·u_R` without any contact point crossing its gap,
//!
//! ```text
//!     maximize  F·c   subject to  a_i·c ≤ h_i  for every contact point i of the body,
//! ```
//!
//! with c the coefficients of `u_R` in an orthonormal basis of the pressed motions, `F_l =
//! f·r_l` the load along basis motion l, `a_{il} = ν_i·r_l(x_i)` the normal displacement
//! of point i under it and `h_i = g_i − u_ν,i ≥ 0` its gap. This linear programme is
//! solved by steepest ascent on the cone of feasible directions: at c, with `A` the rows
//! of the touching points, the direction `ρ = F − A λ` with `λ = argmin_{λ ≥ 0} ‖F −
//! Aλ‖` (non-negative least squares) is the projection of F onto the feasible cone (so
//! `a_i·ρ ≤ 0` for every touching point and `F·ρ = ‖ρ‖² > 0`); the body moves along ρ
//! until the next point touches; it rests when `ρ = 0` (the load lies in the cone of the
//! touching points' normals). A body with no point ahead is pulled off its contact:
//! [`crate::Error::ContactLost`], before any Newton step. The solve then goes on for the
//! displacement relative to `u_R` ([`super::System::place`]): the gaps become `g_i −
//! ν_i·u_R(x_i)`, the closed part subtracted once and exactly (for a translation along an
//! axis and axis-aligned normals, bit for bit), and the answer is `u_R` plus the relative
//! displacement. Only drops of more than the displacement scale U are made: a gap that
//! the deformation itself closes, or one of the order of U, is left to Newton.
//!
//! # The friction limit
//!
//! Along a sliding motion r, friction alone balances the load: with friction forces
//! `|t_i| ≤ w_i F_i`, equilibrium along r needs
//!
//! ```text
//!     f·r  ≤  Σ_i w_i F_i ‖r_τ(x_i)‖,
//! ```
//!
//! the *friction limit* along r, `r_τ` the tangential part of r at contact point i and
//! `F_i` the largest bound friction can reach there: `μ₀ p_i` for a Coulomb bound (p_i the
//! pressure), `μ₀` for a Tresca bound, with `μ₀ = sup_r μ(r)` the largest coefficient —
//! the static value μ(0) for a slip-weakening law (a sticking body), the value at the
//! point for a law of the position — since the force of a slipping point, `F j'(r)`,
//! never exceeds F (`j' ≤ 1` for every potential). For a translation along a flat
//! foundation `‖r_τ‖ = 1` and the limit is `μ₀ × normal force` (Coulomb; the normal force
//! `Σ w_i p_i` balances the normal load) or `μ₀ × contact area` (Tresca). The check is
//! made along the direction r of the load within the body's sliding motions ([`Sliding`]);
//! a load above the limit is refused with [`crate::Error::FrictionLimit`], naming the
//! motion, the load and the limit in the user's units.
//!
//! The outer loop freezes the bound F at the last iterate. A Coulomb bound starts from the
//! pressure of the unloaded state, zero, so its first convex problem cannot hold the body
//! and the body would slide away. That iteration is therefore solved with the load along
//! the sliding motions balanced by tangential forces at the frictional contact points,
//! proportional to their weights (as if friction were uniformly mobilized:
//! [`Sliding::relief`]); its pressures give the friction limit, which is checked, and the
//! bound of the next iteration, which carries the load when the load is below the limit.
//! Mixing conserves the total: for a constant μ on a flat foundation every image has
//! `Σ w_i F_i = μ × normal force`, and the affine combinations of the Anderson step keep
//! it. A slip-dependent μ may still weaken the bound of a later iteration below the load
//! (the slips of the iterates on the way to equilibrium): the body is then first brought
//! to rest with its static coefficient ([`AtRest`]), and if the real law loses it from
//! there, the error says what the bound of that iteration carried and the static limit.

mod at_rest;
mod drop;
mod motions;
mod sliding;

pub use at_rest::AtRest;
pub use drop::{describe_placement, rigid_drop, Placement, MAX_DROP_STEPS};
pub use sliding::{largest_bounds, Sliding};
