//! The convex problem of one outer iteration as a [`ConvexEnergy`] of the free DOFs: the
//! convexified energy `E_k` of [`System::evaluate`] for fixed frozen quantities, with the
//! system's linear solver for the Newton directions and the runaway check of free rigid
//! motions ([`crate::fem::rigid`]) on every accepted iterate.

use super::frozen::Frozen;
use super::newton::{ConvexEnergy, NewtonSettings};
use super::report::Timings;
use super::system::{Evaluation, LinearInfo};
use super::System;
use crate::error::Result;
use crate::fem::dofs::FIXED;
use crate::problem::Problem;
use std::sync::atomic::{AtomicBool, Ordering};

/// `E_k` on the free DOFs of `system`; see the module documentation.
pub struct ConvexProblem<'a> {
    system: &'a mut System,
    /// The work arrays of the evaluations.
    eval: &'a mut Evaluation,
    problem: &'a Problem,
    frozen: &'a Frozen,
    settings: &'a NewtonSettings,
    /// The displacement at every DOF (prescribed values in place) of the last evaluation.
    u: Vec<f64>,
    /// `∇E_k` on the free DOFs at the last evaluation.
    gradient: Vec<f64>,
    /// `‖f_ext‖` (N).
    external: f64,
    /// Raised by the caller to interrupt the minimization ([`ConvexProblem::with_stop`]).
    stop: Option<&'a AtomicBool>,
}

impl<'a> ConvexProblem<'a> {
    /// The convex problem of `problem` on `system` for the frozen quantities `frozen`,
    /// evaluated into `eval`; `u` gives the prescribed values (its free values are replaced
    /// by each evaluation).
    pub fn new(
        system: &'a mut System,
        eval: &'a mut Evaluation,
        problem: &'a Problem,
        frozen: &'a Frozen,
        settings: &'a NewtonSettings,
        u: &[f64],
    ) -> Self {
        let external = system.f_ext.iter().map(|v| v * v).sum::<f64>().sqrt();
        ConvexProblem {
            gradient: vec![0.0; system.dofs.n_free()],
            system,
            eval,
            problem,
            frozen,
            settings,
            u: u.to_vec(),
            external,
            stop: None,
        }
    }

    /// The same problem, interrupted with [`crate::Error::Interrupted`] at the next accepted
    /// Newton iterate once `stop` is raised.
    pub fn with_stop(mut self, stop: &'a AtomicBool) -> Self {
        self.stop = Some(stop);
        self
    }

    /// Writes the free values `x` into the displacement `u` (DOF order).
    fn expand(&mut self, x: &[f64]) {
        for (dof, &eq) in self.system.dofs.equations().iter().enumerate() {
            if eq != FIXED {
                self.u[dof] = x[eq as usize];
            }
        }
    }
}

impl ConvexEnergy for ConvexProblem<'_> {
    fn dimension(&self) -> usize {
        self.gradient.len()
    }

    fn evaluate(&mut self, x: &[f64], hessian: bool) -> f64 {
        self.expand(x);
        let e = self
            .system
            .evaluate(self.problem, &self.u, self.frozen, self.eval, hessian);
        self.system.reduce(&self.eval.grad, &mut self.gradient);
        e
    }

    fn gradient(&self) -> &[f64] {
        &self.gradient
    }

    /// `max(‖f_ext‖, ‖∇W‖, f_D)`: ‖∇W‖ the internal forces over all DOFs, reactions
    /// included, and f_D the force unit of the prescribed displacements
    /// ([`System::force_floor`]), so the criterion is meaningful for load-driven and
    /// displacement-driven problems alike, including stress-free ones.
    fn force_scale(&self) -> f64 {
        let internal = self
            .eval
            .grad_bulk
            .iter()
            .zip(&self.system.f_ext)
            .map(|(g, f)| (g + f).powi(2))
            .sum::<f64>()
            .sqrt();
        self.external
            .max(internal)
            .max(self.system.force_floor)
            .max(f64::MIN_POSITIVE)
    }

    fn newton_direction(
        &mut self,
        rhs: &[f64],
        delta: &mut [f64],
        eta: f64,
        timings: &mut Timings,
    ) -> Result<LinearInfo> {
        self.system
            .linear_solve(&self.eval.hess, rhs, delta, eta, self.settings, timings)
    }

    /// A body whose free rigid motions only contact carries, pulled off that contact,
    /// moves without bound: [`crate::Error::ContactLost`]. A raised stop flag:
    /// [`crate::Error::Interrupted`].
    fn accept(&mut self, x: &[f64]) -> Result<()> {
        if self.stop.is_some_and(|s| s.load(Ordering::Relaxed)) {
            return Err(crate::Error::Interrupted);
        }
        if self.eval.rigid_shift > 0.0 {
            self.expand(x);
            self.system
                .rigid
                .check_runaway(&self.u, self.system.length_unit)?;
        }
        Ok(())
    }
}

/// Minimizes `energy` from `u` (holding the prescribed values) by
/// [`super::newton::minimize`] to the relative residual `tolerance`; on return `u` is the
/// last iterate. Steps and timings go to `record`.
///
/// # Errors
/// As [`super::newton::minimize`].
pub fn minimize(
    energy: &mut ConvexProblem<'_>,
    tolerance: f64,
    u: &mut [f64],
    record: &mut super::newton::NewtonRecord,
) -> Result<super::newton::NewtonOutcome> {
    let mut x = vec![0.0; energy.system.dofs.n_free()];
    energy.system.reduce(u, &mut x);
    energy.u.copy_from_slice(u);
    let settings = energy.settings;
    let result = super::newton::minimize(energy, &mut x, settings, tolerance, record);
    for (dof, &eq) in energy.system.dofs.equations().iter().enumerate() {
        if eq != FIXED {
            u[dof] = x[eq as usize];
        }
    }
    result
}
