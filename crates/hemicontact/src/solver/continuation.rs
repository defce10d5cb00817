//! Continuation over the first outer iterations, the *stages*: each stage is warm-started
//! from the last, and the outer loop mixes its iterates only after the last stage, since the
//! map of the fixed point changes with each.
//!
//! The penalties of the augmented Lagrangians (exact constraints, and the friction norm,
//! exact or with its elastic slip) grow tenfold per stage from `γ₀` to `γ`
//! ([`super::constraints::ConstraintSettings::factor`]): starting at the full penalty from
//! the unloaded state costs tens of damped Newton steps.

use super::constraints::{AugmentedLagrangian, ConstraintSettings};
use crate::contact::ContactNodes;
use crate::problem::Problem;

/// The continuation state of the outer loop.
#[derive(Clone, Debug)]
pub struct Continuation {
    /// The penalties of the augmented Lagrangians at the current stage.
    pub penalties: AugmentedLagrangian,
    /// Number of stages of the problem.
    stages: usize,
}

impl Continuation {
    /// The continuation of `problem` with the penalty settings `settings` for its contact
    /// points `points`: full penalties until [`Continuation::set_stage`] is called.
    pub fn new(problem: &Problem, settings: &ConstraintSettings, points: &ContactNodes) -> Self {
        let penalties = AugmentedLagrangian::new(problem, settings, points);
        let stages = penalties.stages(problem);
        Continuation { penalties, stages }
    }

    /// This continuation for the contact points `points` of the ones it was built for
    /// ([`AugmentedLagrangian::restricted`]).
    pub(crate) fn restricted(&self, points: &[u32]) -> Self {
        Continuation {
            penalties: self.penalties.restricted(points),
            stages: self.stages,
        }
    }

    /// Sets the penalties of outer iteration `k` ([`AugmentedLagrangian::set_stage`]).
    pub fn set_stage(&mut self, k: usize) {
        self.penalties.set_stage(k);
    }

    /// The number of stages: the first outer iteration at which every penalty is full (0
    /// without continuation).
    pub fn stages(&self) -> usize {
        self.stages
    }
}
