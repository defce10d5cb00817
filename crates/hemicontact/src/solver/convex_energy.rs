//! The interface of Newton's method ([`super::newton`]) and its line search
//! ([`super::line_search`]) to the energy they minimize: a convex energy `Π(x)` of the
//! free unknowns with its gradient, residual and Newton direction ([`ConvexEnergy`]).

use super::system::LinearInfo;
use super::timings::Timings;
use crate::error::Result;

/// A convex energy `Π(x)` of n free unknowns, with what Newton's method needs of it.
pub trait ConvexEnergy {
    /// Number of free unknowns n.
    fn dimension(&self) -> usize;
    /// Evaluates `Π(x)` (J), keeping the gradient for [`ConvexEnergy::gradient`] and, with
    /// `hessian`, the (generalized) Hessian for [`ConvexEnergy::newton_direction`].
    fn evaluate(&mut self, x: &[f64], hessian: bool) -> f64;
    /// `∇Π` at the last evaluation (N), length n.
    fn gradient(&self) -> &[f64];
    /// The dot product `Σ_e a_e b_e` of two vectors of the n unknowns (a force and a
    /// displacement: J), added in order; an energy distributed over several processes
    /// completes it over them.
    fn dot(&self, a: &[f64], b: &[f64]) -> f64 {
        a.iter().zip(b).map(|(x, y)| x * y).sum()
    }
    /// The residual norm and the force scale (N) that makes it dimensionless, at the last
    /// evaluation: for an energy of independent parts (the bodies of a mesh,
    /// [`super::local_scales`]), those of the part farthest from equilibrium relative to its own
    /// scale.
    fn residual(&self) -> (f64, f64);
    /// The residual norm and force scale (N) that set the accuracy of the linear solves
    /// (the forcing term of the inexact Newton method): by default those of
    /// [`ConvexEnergy::residual`]. An energy whose convergence test also holds small parts
    /// to their own scales may return the coarse parts here, so that an iterative solver
    /// is not driven to the accuracy of the smallest part at every step.
    fn forcing_residual(&self) -> (f64, f64) {
        self.residual()
    }
    /// Discounts the round-off of the last evaluation until the next one (see
    /// [`super::round_off`]): [`ConvexEnergy::residual`] and
    /// [`ConvexEnergy::forcing_residual`] count only what lies above the round-off floors
    /// (where that is less), and a part of the energy left with nothing but round-off may
    /// be left out of [`ConvexEnergy::gradient`], so that no Newton step moves it. By
    /// default nothing is discounted.
    fn discount_round_off(&mut self) {}
    /// Solves `H Δ = rhs` with the Hessian of the last evaluation with one, to the relative
    /// residual `eta` where the solve is iterative; timings go to `timings`.
    ///
    /// # Errors
    /// A Hessian that cannot be factorized, or an iterative solve that fails.
    fn newton_direction(
        &mut self,
        rhs: &[f64],
        delta: &mut [f64],
        eta: f64,
        timings: &mut Timings,
    ) -> Result<LinearInfo>;
    /// Called with every accepted iterate; an error stops the minimization (e.g. a body
    /// running away along a rigid motion).
    ///
    /// # Errors
    /// Whatever the energy refuses at `x`.
    fn accept(&mut self, x: &[f64]) -> Result<()>;
}
