//! The frozen quantities computed on the system at a displacement: those of the first
//! convex problem ([`Frozen::initial`]), the image `G(z)` of the outer fixed point
//! ([`Frozen::image`]) and the fixed-point residual ([`Frozen::residual`]).

use super::super::multipliers::Multipliers;
use super::super::System;
use super::Frozen;
use crate::assembly::contact::FrictionData;
use crate::error::Result;
use crate::problem::Problem;

impl Frozen {
    /// The frozen quantities of the first convex problem, at `u`: friction data from `u`,
    /// all multipliers zero (so the first problem is the penalty problem).
    ///
    /// # Errors
    /// [`crate::Error::Law`] if a user-defined friction law fails
    /// ([`crate::assembly::contact::ContactAssembler::friction_coefficients`]).
    pub fn initial(system: &System, problem: &Problem, u: &[f64]) -> Result<Frozen> {
        let n = system.contact.len();
        let n_cells = problem.mesh.n_cells() * usize::from(problem.has_ideal_locking());
        let zero = Frozen {
            friction: FrictionData::zero(n),
            multipliers: Multipliers::zero(n, n_cells),
        };
        Ok(Frozen {
            friction: system
                .contact_assembler(problem)
                .convexify(u, &zero.contact())?,
            multipliers: zero.multipliers,
        })
    }

    /// The image `G(z)` of these quantities at the solution `u` of their convex problem:
    /// the friction data at `u` and the multiplier updates
    /// ([`Multipliers::updated`]).
    ///
    /// # Errors
    /// As [`Frozen::initial`].
    pub fn image(&self, system: &System, problem: &Problem, u: &[f64]) -> Result<Frozen> {
        let ca = system.contact_assembler(problem);
        let data = self.contact();
        Ok(Frozen {
            friction: ca.convexify(u, &data)?,
            multipliers: self.multipliers.updated(
                &ca,
                &data,
                &system.continuation.penalties,
                problem,
                u,
            ),
        })
    }

    /// The relative fixed-point residual between these quantities `z` and their image
    /// `g = G(z)`, each contact point on its own scale `scale[i]` (N, see
    /// [`crate::solver::local_scales`]): the larger of the largest change of a point's friction data
    /// as a force, `w_i ‖(F, b)_g − (F, b)_z‖_i / scale_i`, and the multiplier change as a
    /// primal residual ([`Multipliers::change`]); over every process.
    pub fn residual(
        &self,
        image: &Frozen,
        system: &System,
        problem: &Problem,
        scale: &[f64],
    ) -> f64 {
        let (z, g) = (&self.friction, &image.friction);
        let share = system.share();
        let mut fp = 0.0f64;
        for i in 0..system.contact.owned() {
            let mut diff = (g.bound[i] - z.bound[i]).powi(2);
            for a in 0..2 {
                diff += (g.linear[i][a] - z.linear[i][a]).powi(2);
            }
            let change = system.contact.weight[i] * diff.sqrt() / scale[i];
            fp = if change.is_nan() {
                change
            } else {
                fp.max(change)
            };
        }
        let multipliers = self.multipliers.change(
            &image.multipliers,
            &system.continuation.penalties,
            &system.contact_stiffness,
            &system.contact.weight,
            problem,
            scale,
            share,
        );
        let mut worst = [if multipliers.is_nan() {
            multipliers
        } else {
            fp.max(multipliers)
        }];
        share.max(&mut worst);
        worst[0]
    }
}
