//! Back to the user's units: a solution of the dimensionless problem
//! ([`Scales::dimensional`]) and the results of a contact point
//! ([`Scales::dimensional_contact`]).

use super::super::certificate::ContactResult;
use super::super::Solution;
use super::Scales;
use crate::problem::Problem;

impl Scales {
    /// Converts the results of a contact point of the dimensionless problem back to the
    /// user's units.
    pub fn dimensional_contact(&self, c: &ContactResult) -> ContactResult {
        let (u, t, f, w) = (
            self.displacement,
            self.traction(),
            self.force(),
            self.length.powi(self.dim as i32 - 1),
        );
        ContactResult {
            weight: c.weight * w,
            u_nu: c.u_nu * u,
            gap: c.gap * u,
            u_tau: c.u_tau.map(|x| x * u),
            slip: c.slip * u,
            pressure: c.pressure * t,
            bound: c.bound * t,
            force_normal: c.force_normal * f,
            force_tangential: c.force_tangential.map(|x| x * f),
            force: c.force.map(|x| x * f),
            friction_traction: c.friction_traction.map(|x| x * t),
            normal_residual: c.normal_residual * f,
            friction_residual: c.friction_residual * f,
            force_scale: c.force_scale * f,
            slip_scale: c.slip_scale * u,
            ..*c
        }
    }

    /// The unit (Pa) of the ideal-locking multiplier of each material of `problem`: it
    /// depends on how its set's function scales ([`crate::material::LockingSet::nondimensional`]).
    pub fn locking_units(&self, problem: &Problem) -> Vec<f64> {
        problem
            .materials
            .iter()
            .map(|m| m.nondimensional(self.stress, self.strain()).1)
            .collect()
    }

    /// Converts a solution of the dimensionless form of `problem` back to the user's units.
    pub fn dimensional(&self, problem: &Problem, mut s: Solution) -> Solution {
        let units = self.locking_units(problem);
        let unit = |c: usize| units[problem.cell_material(c)];
        let (u, t, f) = (self.displacement, self.traction(), self.force());
        s.u.iter_mut().for_each(|x| *x *= u);
        s.reactions.iter_mut().for_each(|x| *x *= f);
        s.energy *= self.energy();
        for (c, x) in s.locking_multiplier.iter_mut().enumerate() {
            *x *= unit(c);
        }
        for c in &mut s.contact {
            *c = self.dimensional_contact(c);
        }
        let (fr, z) = (&mut s.frozen.friction, &mut s.frozen.multipliers);
        fr.bound.iter_mut().for_each(|x| *x *= t);
        z.pressure.iter_mut().for_each(|x| *x *= t);
        fr.linear.iter_mut().for_each(|x| *x = x.map(|y| y * t));
        z.traction.iter_mut().for_each(|x| *x = x.map(|y| y * t));
        for (c, x) in z.locking.iter_mut().enumerate() {
            *x *= unit(c);
        }
        let r = &mut s.report;
        for step in &mut r.newton {
            step.residual *= f;
            step.energy *= self.energy();
        }
        r.residual *= f;
        r.rigid_shift *= f / u;
        r.residual_tolerance *= f;
        r.scales = Some(*self);
        s
    }
}
