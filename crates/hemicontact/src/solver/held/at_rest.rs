//! Friction-held bodies brought to rest first: the static coefficient while a
//! slip-dependent law would lose the body on its way to equilibrium.
//!
//! The outer loop freezes the friction bound at the slips of the last iterate. With a
//! slip-weakening coefficient, the slips of an iterate on the way to equilibrium (the
//! relieved first iteration, whose uniform friction deforms the body; the early,
//! strongly regularized, continuation stages; bounds frozen at pressures that are not yet
//! the final ones) weaken μ, and a bound frozen there may not carry the load along the
//! sliding motions of a body held by friction alone, though the static coefficient μ(0)
//! does: the convex problem then has no minimum, and the body would slide away from an
//! equilibrium that exists (a body that sticks has `μ(r) = μ(0)` at its points).
//!
//! So when the frozen bound of an outer iteration cannot carry the sliding load of a group
//! of bodies (`f·r > Σ_i w_i F_i ‖r_τ(x_i)‖`, see [`super::Sliding`]), the group is put *at
//! rest*: at its frictional points the friction law is replaced by its value at rest,
//! the bound `F_i = μ_i(0) p_i` (the static coefficient; `μ_i(0)` for a Tresca bound) with
//! the potential's convex part alone (the linear term of the difference-of-convex split,
//! `F ∇h(0) = 0` at rest), and the outer loop iterates on that problem, with its pressures,
//! to convergence. Its answer is the slip-dependent problem's wherever every point of the
//! group sticks; the slip-dependent law then takes over from it (*released*), and the
//! iteration goes on to the fixed point of the real law: at once when the body sticks,
//! from a consistent partial-slip state otherwise. A group is put at rest once per solve;
//! a body the real law then loses is refused with the bound of that iteration and the
//! static limit ([`super::Sliding::slid_away`]).

use super::sliding::{bounds_at, capacity};
use super::Sliding;
use crate::error::Result;
use crate::problem::Problem;
use crate::solver::frozen::Frozen;
use crate::solver::System;

/// Which groups of a [`Sliding`] are at rest (see the module documentation).
#[derive(Clone, Debug, Default)]
pub struct AtRest {
    /// Per sliding load: whether its points are at rest.
    held: Vec<bool>,
    /// Whether the groups at rest were released to the real law (once per solve).
    released: bool,
}

impl AtRest {
    /// Whether some group is at rest.
    pub fn is_active(&self) -> bool {
        self.held.iter().any(|&h| h)
    }

    /// Before the convex problem of `frozen` (at the iterate `u`): puts at rest every group
    /// whose sliding load `frozen`'s bounds cannot carry, and gives `frozen` the friction
    /// data at rest of every group at rest ([`AtRest::apply`]). Returns whether a group was
    /// put at rest now. Nothing after a release.
    ///
    /// # Errors
    /// [`crate::Error::Law`] if a user-defined friction law fails.
    pub fn enter(
        &mut self,
        sliding: &Sliding,
        system: &System,
        problem: &Problem,
        u: &[f64],
        frozen: &mut Frozen,
    ) -> Result<bool> {
        if self.released || sliding.is_empty() {
            return Ok(false);
        }
        self.held.resize(sliding.bodies.len(), false);
        let mut entered = false;
        for (s, held) in sliding.bodies.iter().zip(self.held.iter_mut()) {
            if !*held && s.load > capacity(system, s, &frozen.friction.bound) {
                *held = true;
                entered = true;
            }
        }
        if entered {
            self.apply(sliding, system, problem, u, frozen)?;
        }
        Ok(entered)
    }

    /// Replaces the friction data of `frozen` at the frictional points of every group at
    /// rest by the data at rest at `u`: the bound `μ(0) p` (the pressure `p(u)`, or at a
    /// Signorini point `frozen`'s multiplier), no linear term.
    ///
    /// # Errors
    /// [`crate::Error::Law`] if a user-defined friction law fails.
    pub fn apply(
        &self,
        sliding: &Sliding,
        system: &System,
        problem: &Problem,
        u: &[f64],
        frozen: &mut Frozen,
    ) -> Result<()> {
        if !self.is_active() {
            return Ok(());
        }
        let (bounds, _, _) = bounds_at(system, problem, u, frozen, true, false)?;
        for (s, _) in sliding.bodies.iter().zip(&self.held).filter(|(_, &h)| h) {
            for &(i, _) in &s.points {
                frozen.friction.bound[i] = bounds[i];
                frozen.friction.linear[i] = [0.0; 2];
            }
        }
        Ok(())
    }

    /// Releases the groups at rest to the real friction law: returns whether some group was
    /// at rest.
    pub fn release(&mut self) -> bool {
        let active = self.is_active();
        if active {
            self.held.fill(false);
            self.released = true;
        }
        active
    }
}
