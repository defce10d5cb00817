//! The materials of a scenario: `[material]` (E, ν, plane idealization, elasticity model)
//! and `[locking]` (set, treatment, compliance) into a [`Material`] for the whole mesh, or
//! one `[[material]]` table with its own `locking` per cell region of the mesh.

use super::schema::{ElasticityModel, LockingSetKind, LockingSpec, LockingTreatment, MaterialSpec};
use super::Scenario;
use crate::error::Result;
use crate::material::{
    Elasticity, Hencky, Hooke, Locking, LockingPenalty, LockingSet, Material, Plane,
};
use crate::mesh::Mesh;

impl Scenario {
    /// The plane idealization of the materials (all the same).
    pub(super) fn plane(&self) -> Plane {
        self.file
            .material
            .first()
            .map_or(Plane::Strain, |m| m.plane)
    }

    /// The materials of the scenario on `mesh` and the material of each of its cell regions
    /// (empty for one `[material]` table); see [`crate::problem::ProblemBuilder::materials`].
    pub(super) fn build_materials(&self, mesh: &Mesh) -> Result<(Vec<Material>, Vec<u16>)> {
        let dim = mesh.dim();
        let specs = &self.file.material;
        let default_locking = LockingSpec::default();
        if let [one] = specs.as_slice() {
            if one.part.is_none() {
                if one.locking.is_some() {
                    return Err(self.err(
                        "material.locking",
                        "a table",
                        "the locking of a [material] table in [locking] (a [[material]] table \
                         has its own)",
                    ));
                }
                return Ok((
                    vec![self.build_material(dim, one, &self.file.locking, None)?],
                    Vec::new(),
                ));
            }
        }
        let names = mesh.region_names();
        let listed = || {
            if names.is_empty() {
                "the mesh has no cell regions (give a [mesh] generator [[mesh.region]] boxes, \
                 or a Gmsh file physical groups of dimension d)"
                    .to_string()
            } else {
                format!("one of the mesh's cell regions {names:?}")
            }
        };
        if specs.is_empty() {
            return Err(self.err("material", "[]", "at least one [[material]] table"));
        }
        if self.file.locking != default_locking {
            return Err(self.err(
                "locking",
                "a [locking] table",
                "with [[material]] tables, the locking of each in its own `locking` table",
            ));
        }
        let mut region_material = vec![u16::MAX; names.len()];
        let mut materials = Vec::with_capacity(specs.len());
        for (k, spec) in specs.iter().enumerate() {
            let at = format!("material[{k}]");
            let Some(part) = &spec.part else {
                return Err(self.err(
                    &format!("{at}.part"),
                    "missing",
                    &format!("{} (required with several materials)", listed()),
                ));
            };
            let Some(r) = mesh.region_index(part) else {
                return Err(self.err(&format!("{at}.part"), format!("{part:?}"), &listed()));
            };
            if region_material[r] != u16::MAX {
                return Err(self.err(
                    &format!("{at}.part"),
                    format!("{part:?}"),
                    &format!(
                        "a region not given a material yet (material[{}] has it)",
                        region_material[r]
                    ),
                ));
            }
            if spec.plane != specs[0].plane {
                return Err(self.err(
                    &format!("{at}.plane"),
                    format!("{:?}", spec.plane),
                    &format!(
                        "the plane idealization of material[0] ({:?}): one for the whole body",
                        specs[0].plane
                    ),
                ));
            }
            region_material[r] = k as u16;
            let locking = spec.locking.as_ref().unwrap_or(&default_locking);
            materials.push(self.build_material(dim, spec, locking, Some(&at))?);
        }
        if let Some(r) = region_material.iter().position(|&k| k == u16::MAX) {
            return Err(self.err(
                "material",
                format!("no [[material]] table for the cell region {:?}", names[r]),
                "one [[material]] table per cell region of the mesh",
            ));
        }
        Ok((materials, region_material))
    }

    /// The material of `m` with the locking `l`; fields are named under `at` (`material[k]`,
    /// its locking `material[k].locking`) or, without, as `material.…` and `locking.…`.
    fn build_material(
        &self,
        dim: usize,
        m: &MaterialSpec,
        l: &LockingSpec,
        at: Option<&str>,
    ) -> Result<Material> {
        let named = |name: &str| match (at, name.split_once('.')) {
            (None, _) => name.to_string(),
            (Some(at), Some(("material", rest))) => format!("{at}.{rest}"),
            (Some(at), _) => format!("{at}.{name}"),
        };
        let elasticity = self.elasticity(dim, m, &named)?;
        let locking = self.locking(l, &named)?;
        Ok(Material {
            elasticity,
            locking,
        })
    }

    /// The elasticity of `m` in dimension `dim`, its constants checked; `named` names the
    /// fields (see [`Self::build_material`]).
    fn elasticity(
        &self,
        dim: usize,
        m: &MaterialSpec,
        named: &dyn Fn(&str) -> String,
    ) -> Result<Elasticity> {
        if !(m.young.is_finite() && m.young > 0.0) {
            return Err(self.err(
                &named("material.young"),
                m.young,
                "a positive Young's modulus (Pa)",
            ));
        }
        if !(m.poisson.is_finite() && m.poisson > -1.0 && m.poisson < 0.5) {
            return Err(self.err(
                &named("material.poisson"),
                m.poisson,
                "a Poisson ratio with -1 < ν < 0.5",
            ));
        }
        if dim == 3 && m.plane == Plane::Stress {
            return Err(self.err(&named("material.plane"), "\"stress\"", "\"strain\" in 3D"));
        }
        let hooke = Hooke::from_young_poisson(m.young, m.poisson, dim, m.plane);
        let elasticity = match m.model {
            ElasticityModel::Hooke => {
                for (field, v) in [
                    (&named("material.stiffening"), m.stiffening),
                    (&named("material.reference_strain"), m.reference_strain),
                ] {
                    if let Some(v) = v {
                        return Err(self.err(field, v, "only with model = \"hencky\""));
                    }
                }
                Elasticity::Hooke(hooke)
            }
            ElasticityModel::Hencky => {
                let ratio = self.positive(
                    &named("material.stiffening"),
                    m.stiffening,
                    "a ratio G_∞/G ≥ 1",
                )?;
                if ratio < 1.0 {
                    return Err(self.err(
                        &named("material.stiffening"),
                        ratio,
                        "a ratio G_∞/G ≥ 1 (strain stiffening keeps Φ convex)",
                    ));
                }
                let e0 = self.positive(
                    &named("material.reference_strain"),
                    m.reference_strain,
                    "a strain magnitude",
                )?;
                if m.poisson < 0.0 && hooke.lambda + 2.0 * hooke.mu / dim as f64 <= 0.0 {
                    return Err(self.err(
                        &named("material.poisson"),
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
                &named("material.young"),
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
                    &named("material.reference_strain"),
                    format!("{:?} (s₀ = e₀² = {:e})", m.reference_strain, h.s0),
                    "a strain whose square is a positive normal number",
                ));
            }
            if !usable(h.shear_inf) || !usable(h.bulk) {
                return Err(self.err(
                    &named("material.stiffening"),
                    format!("{:?} (G_∞ = {:e})", m.stiffening, h.shear_inf),
                    "a ratio giving a finite large-strain shear modulus",
                ));
            }
        }
        Ok(elasticity)
    }

    /// The locking `l`: its set with the set's threshold, and its treatment (exact, or a
    /// penalty with the compliance C_κ); `named` names the fields (see
    /// [`Self::build_material`]).
    fn locking(&self, l: &LockingSpec, named: &dyn Fn(&str) -> String) -> Result<Locking> {
        // A threshold of another set would be silently ignored: refuse it.
        let thresholds = [
            (
                &named("locking.theta"),
                l.theta,
                LockingSetKind::LimitedCompressibility,
            ),
            (&named("locking.kappa"), l.kappa, LockingSetKind::Prager),
            (&named("locking.radius"), l.radius, LockingSetKind::Ball),
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
                    &named("locking.theta"),
                    l.theta,
                    "a volumetric strain threshold θ > 0",
                )?,
            }),
            LockingSetKind::Prager => Some(LockingSet::Prager {
                kappa: self.required(
                    &named("locking.kappa"),
                    l.kappa,
                    "a deviatoric threshold κ > 0",
                )?,
            }),
            LockingSetKind::Ball => Some(LockingSet::Ball {
                r: self.required(&named("locking.radius"), l.radius, "a strain radius r > 0")?,
            }),
        };
        if l.treatment == LockingTreatment::Exact {
            let Some(set) = set else {
                return Err(self.err(
                    &named("locking.treatment"),
                    "\"exact\"",
                    "\"exact\" only with a locking set (locking.set)",
                ));
            };
            if let Some(c) = l.c_kappa {
                return Err(self.err(
                    &named("locking.c_kappa"),
                    c,
                    "no compliance with treatment = \"exact\" (ideal locking has none)",
                ));
            }
            return Ok(Locking::Ideal(set));
        }
        let locking = match (set, l.c_kappa) {
            (None, None) => Locking::None,
            (None, Some(c)) => {
                return Err(self.err(
                    &named("locking.c_kappa"),
                    c,
                    "only with a locking set (locking.set)",
                ))
            }
            (Some(set), Some(c)) if c.is_finite() && c >= 0.0 => {
                Locking::Penalty(LockingPenalty { set, c_kappa: c })
            }
            (_, Some(c)) => {
                return Err(self.err(&named("locking.c_kappa"), c, "a compliance C_κ ≥ 0 (Pa)"))
            }
            (Some(_), None) => {
                return Err(self.err(
                    &named("locking.c_kappa"),
                    "missing",
                    "a compliance C_κ ≥ 0 (Pa) for treatment = \"penalty\"",
                ))
            }
        };
        Ok(locking)
    }
}
