//! The material of a scenario: `[material]` (E, ν, plane idealization, elasticity model)
//! and `[locking]` (set, treatment, compliance) into a [`Material`].

use super::schema::{ElasticityModel, LockingSetKind, LockingTreatment};
use super::Scenario;
use crate::error::Result;
use crate::material::{
    Elasticity, Hencky, Hooke, Locking, LockingPenalty, LockingSet, Material, Plane,
};

impl Scenario {
    pub(super) fn build_material(&self, dim: usize) -> Result<Material> {
        let m = &self.file.material;
        if !(m.young.is_finite() && m.young > 0.0) {
            return Err(self.err("material.young", m.young, "a positive Young's modulus (Pa)"));
        }
        if !(m.poisson.is_finite() && m.poisson > -1.0 && m.poisson < 0.5) {
            return Err(self.err(
                "material.poisson",
                m.poisson,
                "a Poisson ratio with -1 < ν < 0.5",
            ));
        }
        if dim == 3 && m.plane == Plane::Stress {
            return Err(self.err("material.plane", "\"stress\"", "\"strain\" in 3D"));
        }
        let hooke = Hooke::from_young_poisson(m.young, m.poisson, dim, m.plane);
        let elasticity = match m.model {
            ElasticityModel::Hooke => {
                for (field, v) in [
                    ("material.stiffening", m.stiffening),
                    ("material.reference_strain", m.reference_strain),
                ] {
                    if let Some(v) = v {
                        return Err(self.err(field, v, "only with model = \"hencky\""));
                    }
                }
                Elasticity::Hooke(hooke)
            }
            ElasticityModel::Hencky => {
                let ratio =
                    self.positive("material.stiffening", m.stiffening, "a ratio G_∞/G ≥ 1")?;
                if ratio < 1.0 {
                    return Err(self.err(
                        "material.stiffening",
                        ratio,
                        "a ratio G_∞/G ≥ 1 (strain stiffening keeps Φ convex)",
                    ));
                }
                let e0 = self.positive(
                    "material.reference_strain",
                    m.reference_strain,
                    "a strain magnitude",
                )?;
                if m.poisson < 0.0 && hooke.lambda + 2.0 * hooke.mu / dim as f64 <= 0.0 {
                    return Err(self.err(
                        "material.poisson",
                        m.poisson,
                        "a ratio giving a positive bulk modulus",
                    ));
                }
                Elasticity::Hencky(Hencky {
                    bulk: hooke.lambda + 2.0 * hooke.mu / dim as f64,
                    shear: hooke.mu,
                    shear_inf: ratio * hooke.mu,
                    s0: e0 * e0,
                })
            }
        };
        // Finite, positive inputs can still give unusable derived constants (λ → ∞ as ν → ½
        // in floating point, G = 0 for a subnormal E, s₀ = e₀² = 0): check what is used.
        let usable = |v: f64| v.is_finite() && v > 0.0;
        let base = elasticity.small_strain_hooke(dim);
        if !(base.lambda.is_finite() && usable(base.mu) && usable(elasticity.monotonicity(dim))) {
            return Err(self.err(
                "material.young",
                format!(
                    "{} (with poisson = {}: λ = {:e}, G = {:e})",
                    m.young, m.poisson, base.lambda, base.mu
                ),
                "values giving finite Lamé constants and a positive shear modulus",
            ));
        }
        if let Elasticity::Hencky(h) = &elasticity {
            if !usable(h.s0) {
                return Err(self.err(
                    "material.reference_strain",
                    format!("{:?} (s₀ = e₀² = {:e})", m.reference_strain, h.s0),
                    "a strain whose square is a positive normal number",
                ));
            }
            if !usable(h.shear_inf) || !usable(h.bulk) {
                return Err(self.err(
                    "material.stiffening",
                    format!("{:?} (G_∞ = {:e})", m.stiffening, h.shear_inf),
                    "a ratio giving a finite large-strain shear modulus",
                ));
            }
        }
        let l = &self.file.locking;
        // A threshold of another set would be silently ignored: refuse it.
        let thresholds = [
            (
                "locking.theta",
                l.theta,
                LockingSetKind::LimitedCompressibility,
            ),
            ("locking.kappa", l.kappa, LockingSetKind::Prager),
            ("locking.radius", l.radius, LockingSetKind::Ball),
        ];
        for (field, value, owner) in thresholds {
            if let (Some(v), true) = (value, l.set != owner) {
                let name = |k: LockingSetKind| match k {
                    LockingSetKind::None => "none",
                    LockingSetKind::LimitedCompressibility => "limited-compressibility",
                    LockingSetKind::Prager => "prager",
                    LockingSetKind::Ball => "ball",
                };
                return Err(self.err(
                    field,
                    v,
                    &format!(
                        "only with set = \"{}\" (this [locking] has set = \"{}\")",
                        name(owner),
                        name(l.set)
                    ),
                ));
            }
        }
        let set = match l.set {
            LockingSetKind::None => None,
            LockingSetKind::LimitedCompressibility => Some(LockingSet::LimitedCompressibility {
                theta: self.required(
                    "locking.theta",
                    l.theta,
                    "a volumetric strain threshold θ > 0",
                )?,
            }),
            LockingSetKind::Prager => Some(LockingSet::Prager {
                kappa: self.required("locking.kappa", l.kappa, "a deviatoric threshold κ > 0")?,
            }),
            LockingSetKind::Ball => Some(LockingSet::Ball {
                r: self.required("locking.radius", l.radius, "a strain radius r > 0")?,
            }),
        };
        if l.treatment == LockingTreatment::Exact {
            let Some(set) = set else {
                return Err(self.err(
                    "locking.treatment",
                    "\"exact\"",
                    "\"exact\" only with a locking set (locking.set)",
                ));
            };
            if let Some(c) = l.c_kappa {
                return Err(self.err(
                    "locking.c_kappa",
                    c,
                    "no compliance with treatment = \"exact\" (ideal locking has none)",
                ));
            }
            return Ok(Material {
                elasticity,
                locking: Locking::Ideal(set),
            });
        }
        let locking = match (set, l.c_kappa) {
            (None, None) => Locking::None,
            (None, Some(c)) => {
                return Err(self.err(
                    "locking.c_kappa",
                    c,
                    "only with a locking set (locking.set)",
                ))
            }
            (Some(set), Some(c)) if c.is_finite() && c >= 0.0 => {
                Locking::Penalty(LockingPenalty { set, c_kappa: c })
            }
            (_, Some(c)) => {
                return Err(self.err("locking.c_kappa", c, "a compliance C_κ ≥ 0 (Pa)"))
            }
            (Some(_), None) => {
                return Err(self.err(
                    "locking.c_kappa",
                    "missing",
                    "a compliance C_κ ≥ 0 (Pa) for treatment = \"penalty\"",
                ))
            }
        };
        Ok(Material {
            elasticity,
            locking,
        })
    }
}
