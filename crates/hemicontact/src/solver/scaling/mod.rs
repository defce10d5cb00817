//! Dimensionless variables: the solver never sees units.
//!
//! Every solve is carried out on the problem written in three scales taken from its data:
//!
//! - length `L`: the diameter of the mesh's bounding box (m);
//! - stress `S`: the P-wave modulus `λ + 2G` of the small-strain elasticity (Pa), the
//!   largest of the materials' for a body of several ([`Problem::stiffness`]);
//! - displacement `U`: the largest displacement the data can cause beyond the rigid
//!   translations that are taken exactly (the translation a body's supports carry it by,
//!   [`crate::rigid::carry`], and an obstacle's own translation, which place the body against
//!   its obstacle) — the largest prescribed displacement beyond the carried translation
//!   ([`Problem::largest_prescribed_motion`]), `|f_N| L / S` for the largest traction and
//!   `|f_0| L² / S` for the body force, and the deepest initial penetration `−g_i` of a
//!   contact point into a rigid obstacle or another body where the carried body meets it,
//!   up to `L` (m) (a displacement-driven indentation; a translation along the obstacle's
//!   surface drives the body only through friction, whose forces the penetration and the
//!   loads bound); `L` when there is no load at all.
//!
//! Each scale is rounded to a power of two, so that scaling is exact in floating point:
//! a problem and the same problem with every stiffness and load multiplied by 2^k give
//! bit-identical dimensionless problems. From them follow the strain unit `e = U/L`, the
//! traction unit `Σ = S e` (Pa), the nodal force unit `Σ L^{d−1}` (N, or N/m in 2D) and the
//! energy unit `Σ U L^{d−1}` (J, or J/m in 2D). The dimensionless problem is
//!
//! `x̂ = x/L`, `û = u/U`, `Ê = E/S`, `f̂_N = f_N/Σ`, `f̂_0 = f_0 L/Σ`, `ĝ = g/U`,
//! `ĉ_ν = c_ν U/Σ`, and each law rewritten for dimensionless strains and slips
//! ([`crate::material::Material::nondimensional`],
//! [`crate::contact::FrictionCoefficient::nondimensional`],
//! [`crate::contact::FrictionPotential::nondimensional`]).
//!
//! Because every tolerance, regularization and threshold of the solver is a pure number
//! applied in these variables, they are all relative to the problem's own scales: units do
//! not matter (from 1e-250 to 1e250 and under any change of length unit), and the results
//! are converted back to the user's units at the end.

//!
//! The scales and the dimensionless problem are here; the way back to the user's units (of
//! a solution and its contact results) in `dimensional`.

mod dimensional;

use crate::contact::{ContactBoundary, FrictionBound};
use crate::error::{Error, Result};
use crate::problem::{Dirichlet, Problem, Traction};

/// The scales of a problem; see the module documentation.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Scales {
    /// Spatial dimension d.
    pub dim: usize,
    /// Length scale L (m).
    pub length: f64,
    /// Stress scale S (Pa): the stiffness of the material.
    pub stress: f64,
    /// Displacement scale U (m).
    pub displacement: f64,
    /// Unit of the ideal-locking multiplier (Pa), see
    /// [`crate::material::Material::nondimensional`]: that of the first material (each
    /// material's multipliers are converted with their own, [`Scales::locking_units`]).
    pub locking_multiplier: f64,
}

/// The power of two nearest to `x > 0` in the logarithm.
fn power_of_two(x: f64) -> f64 {
    x.log2().round().exp2()
}

impl Scales {
    /// The scales of `problem`; see the module documentation.
    ///
    /// # Errors
    /// [`Error::Breakdown`] if a scale is zero or not finite, that is if the loads and the
    /// stiffness are so far apart that the displacements they cause cannot be represented
    /// (beyond about 10^±300); the errors of [`Problem::contact_nodes`] for an obstacle.
    pub fn of(problem: &Problem) -> Result<Scales> {
        let dim = problem.mesh.dim();
        let length = problem.diameter();
        let stress = problem.stiffness();
        let max_abs = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let mut displacement = problem.largest_prescribed_motion();
        for t in &problem.tractions {
            displacement = displacement.max(max_abs(&t.value[..dim]) / stress * length);
        }
        displacement =
            displacement.max(max_abs(&problem.body_force[..dim]) / stress * length * length);
        if problem
            .contact
            .iter()
            .any(|c| c.obstacle.is_some() || c.against.is_some())
        {
            let points = problem.contact_nodes()?;
            let penetration = points.gap.iter().fold(0.0f64, |m, g| m.max(-g));
            displacement = displacement.max(penetration.min(length));
        }
        if displacement == 0.0 {
            displacement = length;
        }
        for (name, x) in [
            ("length", length),
            ("stress", stress),
            ("displacement", displacement),
        ] {
            if !(x.is_finite() && x >= f64::MIN_POSITIVE) {
                return Err(Error::Breakdown(format!(
                    "the {name} scale of the problem is {x:e}: loads, stiffness and size are \
                     too far apart to represent the displacements in double precision"
                )));
            }
        }
        let (length, stress, displacement) = (
            power_of_two(length),
            power_of_two(stress),
            power_of_two(displacement),
        );
        let e = displacement / length;
        let (_, locking_multiplier) = problem.materials[0].nondimensional(stress, e);
        Ok(Scales {
            dim,
            length,
            stress,
            displacement,
            locking_multiplier,
        })
    }

    /// Strain unit `e = U/L`.
    pub fn strain(&self) -> f64 {
        self.displacement / self.length
    }

    /// Traction unit `Σ = S U/L` (Pa): stresses, contact pressures, friction bounds.
    pub fn traction(&self) -> f64 {
        self.stress * self.strain()
    }

    /// Nodal force unit `Σ L^{d−1}` (N; N/m in 2D).
    pub fn force(&self) -> f64 {
        self.traction() * self.length.powi(self.dim as i32 - 1)
    }

    /// Energy unit `Σ U L^{d−1}` (J; J/m in 2D).
    pub fn energy(&self) -> f64 {
        self.force() * self.displacement
    }

    /// The problem in dimensionless variables; see the module documentation.
    pub fn nondimensional(&self, problem: &Problem) -> Problem {
        let (u, t) = (self.displacement, self.traction());
        let materials = problem
            .materials
            .iter()
            .map(|m| m.nondimensional(self.stress, self.strain()).0)
            .collect();
        let scaled = |v: [f64; 3], unit: f64| v.map(|x| x / unit);
        Problem {
            mesh: problem.mesh.in_units_of(self.length),
            materials,
            region_material: problem.region_material.clone(),
            dirichlet: problem
                .dirichlet
                .iter()
                .map(|b| Dirichlet {
                    value: scaled(b.value, u),
                    ..b.clone()
                })
                .collect(),
            tractions: problem
                .tractions
                .iter()
                .map(|tr| Traction {
                    part: tr.part,
                    value: scaled(tr.value, t),
                })
                .collect(),
            body_force: scaled(problem.body_force, t / self.length),
            contact: problem
                .contact
                .iter()
                .map(|c| ContactBoundary {
                    against: c.against.map(|a| a.nondimensional(self.length, u)),
                    part: c.part,
                    gap: c.gap / u,
                    obstacle: c
                        .obstacle
                        .as_ref()
                        .map(|o| o.nondimensional(self.length, u)),
                    normal: c.normal.nondimensional(u, t),
                    friction: c.friction.as_ref().map(|f| {
                        let value = match f.bound {
                            FrictionBound::Tresca => t,
                            FrictionBound::Coulomb => 1.0,
                        };
                        crate::contact::Friction {
                            mu: f.mu.nondimensional(u, self.length, value),
                            potential: f.potential.nondimensional(u),
                            ..f.clone()
                        }
                    }),
                })
                .collect(),
            plane: problem.plane,
        }
    }
}
