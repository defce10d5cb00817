//! The convex problem of one outer iteration as a [`ConvexEnergy`] of the free DOFs: the
//! convexified energy `E_k` of [`System::evaluate`] for fixed frozen quantities, with the
//! system's linear solver for the Newton directions and the runaway check of free rigid
//! motions ([`crate::rigid`]) on every accepted iterate.

use super::frozen::Frozen;
use super::newton::{ConvexEnergy, NewtonSettings};
use super::report::Timings;
use super::round_off::{above_floor, Floors};
use super::system::{Evaluation, LinearInfo};
use super::System;
use crate::error::Result;
use crate::fem::dofs::FIXED;
use crate::problem::Problem;
use crate::rigid::Runaway;
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
    /// `‖f_ext|_b‖` per body (N).
    external: Vec<f64>,
    /// Per body at the last evaluation: the residual `‖∇E_k|_b‖` over the free DOFs (N), see
    /// [`super::local_scales`]; its force scale is in the evaluation.
    body_residual: Vec<f64>,
    /// The round-off floors of the gradient at the last evaluation
    /// ([`System::round_off_floors`]), if [`ConvexEnergy::discount_round_off`] computed them
    /// since: the entries within them count as zero, the regions' resultants count.
    floors: Floors,
    /// Whether [`ConvexProblem::floors`] are those of the last evaluation.
    discounted: bool,
    /// Raised by the caller to interrupt the minimization ([`ConvexProblem::with_stop`]).
    stop: Option<&'a AtomicBool>,
    /// The body that moved by more than its size, if the minimization stopped for that
    /// ([`ConvexEnergy::accept`]).
    pub runaway: Option<Runaway>,
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
        let mut external = Vec::new();
        let d = problem.mesh.dim();
        let f = &system.f_ext;
        system
            .bodies
            .norms(system.share(), d, f.len(), |k| f[k], &mut external);
        ConvexProblem {
            gradient: vec![0.0; system.dofs.n_free()],
            system,
            eval,
            problem,
            frozen,
            settings,
            u: u.to_vec(),
            external,
            body_residual: Vec::new(),
            floors: Floors::default(),
            discounted: false,
            stop: None,
            runaway: None,
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

impl ConvexProblem<'_> {
    /// The gradient's entry at DOF `k` at the last evaluation, 0 where it is within its
    /// round-off floor once the floors are computed ([`ConvexEnergy::discount_round_off`]).
    fn counted(&self, k: usize) -> f64 {
        if self.discounted {
            above_floor(self.eval.grad[k], self.floors.dof[k])
        } else {
            self.eval.grad[k]
        }
    }
}

impl ConvexEnergy for ConvexProblem<'_> {
    fn dimension(&self) -> usize {
        self.gradient.len()
    }

    fn evaluate(&mut self, x: &[f64], hessian: bool) -> f64 {
        self.expand(x);
        self.discounted = false;
        let e = self
            .system
            .evaluate(self.problem, &self.u, self.frozen, self.eval, hessian);
        self.system.reduce(&self.eval.grad, &mut self.gradient);
        let (d, dofs, bodies, share) = (
            self.problem.mesh.dim(),
            &self.system.dofs,
            &self.system.bodies,
            self.system.share(),
        );
        let eval = &mut *self.eval;
        bodies.residuals(
            share,
            d,
            &eval.grad,
            |k| dofs.is_fixed(k),
            &mut self.body_residual,
        );
        bodies.force_scales(
            share,
            d,
            &eval.grad_bulk,
            &self.system.f_ext,
            &self.external,
            &mut eval.body_scale,
        );
        let (mut force, mut floor) = (
            std::mem::take(&mut eval.point_force),
            std::mem::take(&mut eval.point_floor),
        );
        self.system.point_scales(
            self.problem,
            &self.u,
            self.frozen,
            &eval.normal,
            &eval.body_scale,
            &mut force,
            &mut floor,
        );
        (eval.point_force, eval.point_floor) = (force, floor);
        e
    }

    fn gradient(&self) -> &[f64] {
        &self.gradient
    }

    /// Over the equations this process counts, completed over the processes.
    fn dot(&self, a: &[f64], b: &[f64]) -> f64 {
        self.system.share().dot_equations(a, b)
    }

    /// Per body b: the residual `‖∇E_k|_b‖` over its free DOFs against
    /// `max(‖f_ext|_b‖, ‖∇W|_b‖, f_D,b)`: ‖∇W‖ the internal forces over all DOFs, reactions
    /// included, and f_D,b the force unit of the body's prescribed motions
    /// ([`super::local_scales::Bodies::force_floor`]), so the criterion is meaningful for
    /// load-driven and displacement-driven problems alike, including stress-free ones; and
    /// per contact point i the residual at its node against its force scale
    /// `max(w_i σ_i, η L_i)` (see [`super::local_scales`]). The part farthest from equilibrium relative to its
    /// scale.
    fn residual(&self) -> (f64, f64) {
        let (mut res, mut scale) =
            super::local_scales::Bodies::worst(&self.body_residual, &self.eval.body_scale);
        let d = self.problem.mesh.dim();
        let (eval, dofs, share) = (&*self.eval, &self.system.dofs, self.system.share());
        let owned = self.system.contact.owned();
        for (i, &v) in self.system.contact.node[..owned].iter().enumerate() {
            let v = v as usize;
            let r = (0..d)
                .filter(|&k| !dofs.is_fixed(d * v + k))
                .map(|k| self.counted(d * v + k).powi(2))
                .sum::<f64>()
                .sqrt();
            let s = eval.point_force[i]
                .max(eval.point_floor[i])
                .max(f64::MIN_POSITIVE);
            if r.is_nan() || r / s > res / scale {
                (res, scale) = (r, s);
            }
        }
        // The worst of every process's worst, in rank order (the same pick as one pass).
        let all = share.gather(&[res, scale]);
        (res, scale) = (all[0], all[1]);
        for pair in all.chunks_exact(2).skip(1) {
            let (r, s) = (pair[0], pair[1]);
            if r.is_nan() || r / s > res / scale {
                (res, scale) = (r, s);
            }
        }
        (res, scale)
    }

    /// The body farthest from equilibrium: the contact points' own scales are for the
    /// convergence test; the linear solves are driven by the bodies' residuals (a point
    /// left behind converges within the next Newton steps, each solved to at least
    /// `newton.pcg_tolerance`).
    fn forcing_residual(&self) -> (f64, f64) {
        super::local_scales::Bodies::worst(&self.body_residual, &self.eval.body_scale)
    }

    /// The floors of [`System::round_off_floors`] at the last evaluation; the body
    /// residuals are taken again over what lies above them, regions' resultants included
    /// ([`super::round_off::body_residuals`]). A body left with nothing but round-off, at
    /// its entries and at its contact points, gets no Newton step: its gradient entries are
    /// set to zero.
    fn discount_round_off(&mut self) {
        let mut floors = std::mem::take(&mut self.floors);
        let (problem, frozen) = (self.problem, self.frozen);
        let normal = &self.eval.normal;
        self.system
            .round_off_floors(problem, &self.u, frozen, normal, &mut floors);
        self.floors = floors;
        self.discounted = true;
        let (mesh, system, grad) = (&problem.mesh, &*self.system, &self.eval.grad);
        let value = |k: usize| {
            if system.dofs.is_fixed(k) {
                0.0
            } else {
                grad[k]
            }
        };
        let bodies = &system.bodies;
        let (share, floors) = (system.share(), &self.floors);
        let mut above = Vec::new();
        super::round_off::body_residuals(bodies, mesh, share, floors, value, value, &mut above);
        // Converged either way: plainly, or above the round-off.
        for (r, a) in self.body_residual.iter_mut().zip(above) {
            *r = r.min(a);
        }
        // The bodies with a contact point whose node's residual is above its floor.
        let d = mesh.dim();
        let mut busy = vec![false; bodies.count];
        for &v in &system.contact.node[..system.contact.owned()] {
            let v = v as usize;
            if (0..d).any(|k| self.counted(d * v + k) != 0.0 && !system.dofs.is_fixed(d * v + k)) {
                if let Some(b) = busy.get_mut(bodies.of_node[v] as usize) {
                    *b = true;
                }
            }
        }
        share.any_each(&mut busy);
        for (dof, &eq) in system.dofs.equations().iter().enumerate() {
            let b = bodies.of_node[dof / d] as usize;
            if eq != FIXED && self.body_residual.get(b) == Some(&0.0) && !busy[b] {
                self.gradient[eq as usize] = 0.0;
            }
        }
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
    /// moves without bound: [`crate::Error::ContactLost`] once it has moved by more than its
    /// size along a motion that presses no contact point into its foundation, the forces at
    /// `x` still driving it along that motion (a body pressed into its foundation, or pushed
    /// back after an overshoot, is let come back), naming the motion in the user's units, with the
    /// body and motion kept in [`ConvexProblem::runaway`]. A raised stop flag:
    /// [`crate::Error::Interrupted`].
    fn accept(&mut self, x: &[f64]) -> Result<()> {
        if self.stop.is_some_and(|s| s.load(Ordering::Relaxed)) {
            return Err(crate::Error::Interrupted);
        }
        if self.eval.rigid_shift > 0.0 {
            self.expand(x);
            let length = self.system.length_unit();
            let share = self.system.share();
            let Some(r) = self
                .system
                .rigid
                .runaway(&self.problem.mesh, &self.u, length, share)
            else {
                return Ok(());
            };
            // A body runs away along a motion that moves no contact point into its
            // foundation (it lifts off or slides) and along which the forces at x still
            // drive it. One moving into its foundation meets a growing resistance (a load
            // that deforms by more than the body's size, linear elasticity allows it), and
            // one that the forces push back has overshot its equilibrium (a line search
            // along a nearly flat energy, e.g. friction close to its limit): both come back.
            if r.moved.is_finite() {
                let d = self.problem.mesh.dim();
                let rigid = &self.system.rigid;
                let mesh = &self.problem.mesh;
                let contact = &self.system.contact;
                let nodes = rigid.bodies[r.body].nodes.iter();
                let reach = nodes
                    .filter(|&&v| share.counts_node(v as usize))
                    .map(|&v| {
                        let m = rigid.displacement(r.body, &r.motion, mesh.node(v as usize));
                        m.iter().map(|c| c * c).sum::<f64>().sqrt()
                    })
                    .fold(0.0f64, f64::max);
                // How far the motion presses a point of the body (its node, or a master
                // point) into its contact.
                let into = (0..contact.len())
                    .filter_map(|i| {
                        let (x, sign, _) = contact.on_body(mesh, i, &rigid.body_of, r.body)?;
                        let m = rigid.displacement(r.body, &r.motion, &x[..d]);
                        Some(sign * (0..d).map(|j| m[j] * contact.normal[i][j]).sum::<f64>())
                    })
                    .fold(0.0f64, f64::max);
                let mut extent = [reach, into];
                share.max(&mut extent);
                let [reach, into] = extent;
                if into > 1e-2 * reach {
                    return Ok(());
                }
                self.evaluate(x, false);
                let (rigid, share) = (&self.system.rigid, self.system.share());
                let mut push = 0.0;
                let nodes = rigid.bodies[r.body].nodes.iter();
                for &v in nodes.filter(|&&v| share.counts_node(v as usize)) {
                    let m =
                        rigid.displacement(r.body, &r.motion, self.problem.mesh.node(v as usize));
                    for i in 0..d {
                        let dof = d * v as usize + i;
                        if !self.system.dofs.is_fixed(dof) {
                            push -= m[i] * self.eval.grad[dof];
                        }
                    }
                }
                let mut push = [push];
                share.sum(&mut push);
                if push[0] <= 0.0 {
                    return Ok(());
                }
            }
            self.runaway = Some(r);
            let units = self.system.user_units();
            return Err(self
                .system
                .rigid
                .contact_lost(&r, units.length, units.displacement));
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
