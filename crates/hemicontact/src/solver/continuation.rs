//! Continuation over the first outer iterations, the *stages*: each stage is warm-started
//! from the last, and the outer loop mixes its iterates only after the last stage, since the
//! map of the fixed point changes with each.
//!
//! - **Penalties of the exact constraints** grow tenfold per stage from `γ₀` to `γ`
//!   ([`super::constraints::ConstraintSettings::factor`]): starting at the full penalty from
//!   the unloaded state costs tens of damped Newton steps.
//! - **The floor of the friction regularization** shrinks tenfold per stage from
//!   [`REGULARIZATION_START`] to each law's own value: a sticking point of the regularized
//!   norm `√(r² + ρ²)` has curvature 1/ρ only within |r| ≲ ρ; approached from slips many
//!   times ρ, Newton sees almost no curvature and overshoots, so a small ρ is reached from a
//!   large one.

use super::constraints::{AugmentedLagrangian, ConstraintSettings};
use crate::problem::Problem;

/// Friction regularization (relative to the displacement scale) at which the continuation
/// of [`Continuation::set_stage`] starts.
pub const REGULARIZATION_START: f64 = 1e-2;

/// Factor by which the friction regularization shrinks per outer iteration. Measured on a
/// pressed and sheared block with Coulomb friction (16 × 8 cells, 12 sticking and 5
/// slipping points, target 1e-8): 77 Newton steps with 0.1, 228 with 0.01, 346 without
/// continuation.
pub const REGULARIZATION_STEP: f64 = 0.1;

/// Number of outer iterations the regularization continuation of `problem` needs to reach
/// the targets of its friction laws: the largest over the contact parts whose norm is
/// smoothed (0 without one).
pub fn regularization_stages(problem: &Problem) -> usize {
    problem
        .contact
        .iter()
        .filter_map(|c| c.friction.as_ref()?.potential.regularization())
        .map(|target| {
            if target >= REGULARIZATION_START {
                0
            } else {
                ((REGULARIZATION_START / target).ln() / REGULARIZATION_STEP.recip().ln()).ceil()
                    as usize
            }
        })
        .max()
        .unwrap_or(0)
}

/// The continuation state of the outer loop.
#[derive(Clone, Debug)]
pub struct Continuation {
    /// The penalties of the exact constraints at the current stage.
    pub penalties: AugmentedLagrangian,
    /// Floor of the numerical regularization ρ_num of a smoothed norm in the friction
    /// potential at the current stage, in units of the displacement scale (the solver works
    /// in dimensionless variables, see [`super::scaling`]); each law uses the larger of this
    /// and its own value. 0 (the laws' own values) until [`Continuation::set_stage`].
    pub regularization_floor: f64,
    /// Number of stages of the problem.
    stages: usize,
}

impl Continuation {
    /// The continuation of `problem` with the penalty settings `settings` for contact
    /// points of weights `weight`: full penalties and the laws' own regularizations until
    /// [`Continuation::set_stage`] is called.
    pub fn new(problem: &Problem, settings: &ConstraintSettings, weight: &[f64]) -> Self {
        let penalties = AugmentedLagrangian::new(problem, settings, weight);
        let stages = penalties
            .stages(problem)
            .max(regularization_stages(problem));
        Continuation {
            penalties,
            regularization_floor: 0.0,
            stages,
        }
    }

    /// Sets the penalties and the regularization floor of outer iteration `k`: penalties
    /// [`AugmentedLagrangian::set_stage`], floor `REGULARIZATION_START ·
    /// REGULARIZATION_STEP^k`.
    pub fn set_stage(&mut self, k: usize) {
        self.penalties.set_stage(k);
        self.regularization_floor =
            REGULARIZATION_START * REGULARIZATION_STEP.powi(k.min(300) as i32);
    }

    /// The number of stages: the first outer iteration at which every penalty is full and
    /// every regularization at its law's value (0 without continuation).
    pub fn stages(&self) -> usize {
        self.stages
    }
}
