//! The scenario file format, mirrored literally (serde, unknown fields rejected).
//!
//! ```toml
//! [mesh]
//! kind = "rectangle"        # built-in generator; parts: bottom, right, top, left
//!                           # ("box": 3D, size/n/origin of length 3, parts left, right,
//!                           #  front, back, bottom, top)
//! origin = [0.0, 0.0]       # m (default)
//! size = [4.0, 4.0]         # m
//! n = [16, 16]              # squares per side, each cut into two triangles
//! pattern = "symmetric"     # or "uniform" (default "symmetric")
//! # progression = [1.0, 1.0]  # ratio of consecutive cell sizes per axis, from the origin
//! #                         # side (default all 1: equal cells; x ≠ 1 needs "uniform")
//! # kind = "gmsh"           # a Gmsh 4.1 file (ASCII or binary) instead of a generator:
//! # file = "meshes/half-disc.msh"   # relative to the scenario file's folder; parts are the
//! #                         # physical groups of dimension d − 1 (see mesh::gmsh); no
//! #                         # origin/size/n/pattern/progression
//!
//! [material]
//! model = "hooke"           # (default)
//! young = 2000.0            # Pa
//! poisson = 0.3
//! plane = "strain"          # or "stress" (2D only; default "strain")
//! # model = "hencky": also stiffening = G_∞/G ≥ 1, reference_strain = e₀ > 0
//!
//! [[dirichlet]]
//! part = "bottom"
//! components = ["x", "y"]   # default: all
//! value = [0.0, 0.0]        # m, default: zero
//!
//! [loads]
//! body_force = [0.0, 0.0]   # N/m³ (default zero)
//! [[loads.traction]]
//! part = "top"
//! value = [0.0, -900.0]     # N/m² (N/m in 2D)
//!
//! [locking]                 # optional (default: none)
//! set = "limited-compressibility"   # or "prager" (kappa), "ball" (radius), "none"
//! theta = 0.16
//! treatment = "penalty"     # nearly locking, paper eq. (40); or "exact" (ideal locking,
//!                           # no c_kappa)
//! c_kappa = 10000.0         # Pa
//!
//! [[contact]]               # optional, one per contact part
//! part = "left"
//! gap = 0.4                 # m
//! law = "normal-compliance" # or "signorini" (rigid foundation u_ν ≤ g, no c_nu)
//! c_nu = 10000.0            # Pa/m
//! [contact.friction]        # optional (default: frictionless)
//! bound = "coulomb"         # or "tresca"
//! potential = { kind = "norm" }     # (default)
//! # potential = { kind = "nonconvex", a = 0.5 }
//! # potential = { kind = "regularized", rho = 1e-3 }   # m
//! mu = { law = "exponential", a = 0.4, b = 0.1, beta = 100.0 }
//! # mu = { law = "constant", mu = 0.3 }   # or just mu = 0.3
//! # mu = { law = "table", points = [[0.0, 0.4], [0.01, 0.1]] }
//! exact = false             # true: exact stick/slip (potentials norm and nonconvex)
//! regularization = 1e-8     # else an elastic slip of at most regularization · F/k
//!                           # (U the displacement scale of the solve; default 1e-8)
//!
//! [solver]                  # all optional, see SolverSettings
//! ordering = "nested-dissection"
//! linear_solver = "auto"    # "direct", "iterative" (multigrid CG) or "auto" (3D ≥ 30k eq.),
//!                           # or "petsc" (builds with the `petsc` feature)
//! certificate_tolerance = 1e-6   # every certificate residual (relative) must be below it
//! [solver.constraints]      # exact constraints (augmented Lagrangian)
//! locking_penalty = 1000.0  # dimensionless factors γ (ideal locking; Signorini and
//! contact_penalty = 100.0   #   exact friction) and γ₀ of the continuation
//! initial_penalty = 1.0
//! [solver.petsc]            # with linear_solver = "petsc": PETSc options (after the
//! options = "-pc_type gamg" #   defaults CG + GAMG, before the PETSC_OPTIONS variable)
//!
//! [output]
//! dir = "out/example"       # default: given on the command line
//! ```
//!
//! Deprecated forms, still read with a note: `potential = "nonconvex"` with a sibling
//! `a = 0.5` (likewise `"norm"`, `"regularized"` with `rho`), and `[solver.outer]
//! friction_regularization` for the `regularization` of every contact part.
//!
//! Entries that contradict each other are refused, naming both: two `[[dirichlet]]`
//! prescribing one component with different values at a common node (one part, or a corner
//! shared by two parts); a `[[loads.traction]]` component that a `[[dirichlet]]` of the same
//! part prescribes (it would do no work); a `[[contact]]` part given twice, or also a
//! Dirichlet part. Equal repeated values, several tractions on one part (they add up) and a
//! traction on the free components of a roller are consistent and accepted. A scenario file
//! is read only if it is a regular file of at most 1 MiB.

use crate::contact::{FrictionBound, FrictionCoefficient};
use crate::material::Plane;
use crate::mesh::generate::CutPattern;
use crate::solver::SolverSettings;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// The whole file.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScenarioFile {
    /// Optional title, copied to the summary.
    #[serde(default)]
    pub title: Option<String>,
    /// Geometry and mesh (`[mesh]`): required, unless a mesh is given in memory
    /// ([`super::Scenario::given_mesh`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mesh: Option<MeshSpec>,
    /// Bulk material: one table `[material]` for the whole mesh, or one `[[material]]`
    /// table per cell region (each naming its region in `part`).
    #[serde(deserialize_with = "one_or_many", serialize_with = "table_if_one")]
    pub material: Vec<MaterialSpec>,
    /// Locking of a `[material]` table (each `[[material]]` table has its own `locking`).
    #[serde(default)]
    pub locking: LockingSpec,
    /// Dirichlet parts (Γ_D).
    #[serde(default)]
    pub dirichlet: Vec<DirichletSpec>,
    /// Contact parts (Γ_C).
    #[serde(default)]
    pub contact: Vec<ContactSpec>,
    /// Loads.
    #[serde(default)]
    pub loads: LoadsSpec,
    /// Solver settings.
    #[serde(default)]
    pub solver: SolverSettings,
    /// Outputs.
    #[serde(default)]
    pub output: OutputSpec,
    /// Load stepping (`[loading]`); absent: one solve at the full load.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub loading: Option<LoadingSpec>,
}

/// Mesh source.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MeshKind {
    /// Built-in rectangle generator (2D): parts bottom, right, top, left.
    Rectangle,
    /// Built-in box generator (3D, 6 tetrahedra per cube): parts left, right, front, back,
    /// bottom, top.
    Box,
    /// A Gmsh `.msh` file (format 4.1, ASCII or binary; see [`crate::mesh::gmsh`]): parts
    /// are its physical groups of dimension d − 1.
    Gmsh,
}

/// `[mesh]`.
///
/// The generators (`rectangle`, `box`) require `size` and `n` and accept `origin`,
/// `pattern` and `progression`; `gmsh` requires `file` and accepts none of the generator
/// fields.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSpec {
    /// Mesh source.
    pub kind: MeshKind,
    /// Gmsh only: the `.msh` file, relative to the scenario file's folder.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<PathBuf>,
    /// Generators: corner with the smallest coordinates (m); zero by default.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub origin: Option<Vec<f64>>,
    /// Generators (required): side lengths (m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub size: Option<Vec<f64>>,
    /// Generators (required): subdivisions per side.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub n: Option<Vec<u64>>,
    /// Generators: diagonal pattern (default `symmetric`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pattern: Option<CutPattern>,
    /// Generators: ratio of consecutive cell sizes along each axis, from the origin side to
    /// the far side (dimensionless; default 1: equal cells); see
    /// [`crate::mesh::generate::axis_nodes`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub progression: Option<Vec<f64>>,
    /// Generators: named cell regions (`[[mesh.region]]`), each the cells whose centroid
    /// lies in a box; a cell goes to the first box that holds it, and every cell must be in
    /// one. A Gmsh file's regions are its physical groups of dimension d.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub region: Vec<RegionSpec>,
}

/// `[[mesh.region]]`: the cells of a generated mesh whose centroid lies in a box.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RegionSpec {
    /// The region's name, which a `[[material]]` table names in `part`.
    pub name: String,
    /// The box's corner with the smallest coordinates (m), d values.
    pub min: Vec<f64>,
    /// The box's corner with the largest coordinates (m), d values.
    pub max: Vec<f64>,
}

/// Reads `material`: a table is the one material of the whole mesh, an array of tables one
/// material per cell region.
fn one_or_many<'de, D: serde::Deserializer<'de>>(
    deserializer: D,
) -> Result<Vec<MaterialSpec>, D::Error> {
    use serde::de;
    struct Visit;
    impl<'de> de::Visitor<'de> for Visit {
        type Value = Vec<MaterialSpec>;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str(
                "a table [material] (one material for the whole mesh) or tables [[material]] \
                 (one per cell region, each naming it in `part`)",
            )
        }
        fn visit_map<A: de::MapAccess<'de>>(self, map: A) -> Result<Vec<MaterialSpec>, A::Error> {
            MaterialSpec::deserialize(de::value::MapAccessDeserializer::new(map)).map(|m| vec![m])
        }
        fn visit_seq<A: de::SeqAccess<'de>>(self, seq: A) -> Result<Vec<MaterialSpec>, A::Error> {
            Vec::<MaterialSpec>::deserialize(de::value::SeqAccessDeserializer::new(seq))
        }
    }
    deserializer.deserialize_any(Visit)
}

/// Writes `material` as it is read: one table for a material without `part`, else an array.
fn table_if_one<S: serde::Serializer>(
    m: &[MaterialSpec],
    serializer: S,
) -> Result<S::Ok, S::Error> {
    match m {
        [one] if one.part.is_none() => one.serialize(serializer),
        many => many.serialize(serializer),
    }
}

impl MeshSpec {
    /// The diagonal pattern of a generated mesh: as given, `symmetric` by default.
    pub fn pattern(&self) -> CutPattern {
        self.pattern.unwrap_or(CutPattern::Symmetric)
    }
}

/// Elasticity model name.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ElasticityModel {
    /// Isotropic Hooke's law.
    #[default]
    Hooke,
    /// Strain-stiffening Hencky law (see `material::hencky`).
    Hencky,
}

fn default_plane() -> Plane {
    Plane::Strain
}

/// `[material]`, or one of the `[[material]]` tables.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// `[[material]]`: the cell region of the mesh it fills (a Gmsh physical group of
    /// dimension d, or a `[[mesh.region]]` of a generated mesh).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub part: Option<String>,
    /// Elasticity model.
    #[serde(default)]
    pub model: ElasticityModel,
    /// Young's modulus E (Pa).
    pub young: f64,
    /// Poisson ratio ν.
    pub poisson: f64,
    /// Plane idealization (2D).
    #[serde(default = "default_plane")]
    pub plane: Plane,
    /// Hencky only: ratio G_∞/G ≥ 1 of large- to small-strain shear modulus.
    #[serde(default)]
    pub stiffening: Option<f64>,
    /// Hencky only: deviatoric strain magnitude e₀ > 0 of the transition (s₀ = e₀²).
    #[serde(default)]
    pub reference_strain: Option<f64>,
    /// `[[material]]`: its locking (`[material.locking]`, the fields of `[locking]`); none
    /// if absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub locking: Option<LockingSpec>,
}

/// Locking set name.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LockingSetKind {
    /// No locking.
    #[default]
    None,
    /// `|tr ε| ≤ θ`.
    LimitedCompressibility,
    /// `½‖ε^D‖² ≤ κ²`.
    Prager,
    /// `‖ε‖ ≤ r`.
    Ball,
}

/// How the locking constraint is imposed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LockingTreatment {
    /// Nearly locking: the penalty `(C_κ/2) Q_+²` (paper eq. (40)).
    #[default]
    Penalty,
    /// Ideal locking: the exact constraint `ε_T ∈ B` in every cell (augmented Lagrangian,
    /// see `solver::constraints`).
    Exact,
}

/// `[locking]`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LockingSpec {
    /// The locking set.
    #[serde(default)]
    pub set: LockingSetKind,
    /// Threshold θ (limited compressibility).
    #[serde(default)]
    pub theta: Option<f64>,
    /// κ (Prager).
    #[serde(default)]
    pub kappa: Option<f64>,
    /// Radius r (ball).
    #[serde(default)]
    pub radius: Option<f64>,
    /// Treatment: penalty (nearly locking) or exact (ideal locking).
    #[serde(default)]
    pub treatment: LockingTreatment,
    /// Penalty compliance C_κ ≥ 0 (Pa), with `treatment = "penalty"` only.
    #[serde(default)]
    pub c_kappa: Option<f64>,
}

/// Normal contact law name.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum NormalLawKind {
    /// `p = c_ν (u_ν − g)_+`.
    #[default]
    NormalCompliance,
    /// The Signorini condition `u_ν ≤ g` of a rigid foundation (exact constraint).
    Signorini,
}

/// `[[contact]]`.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// Boundary part name (Γ_C).
    pub part: String,
    /// Initial gap g ≥ 0 (m) to a flat foundation; 0 (absent) with an obstacle.
    #[serde(default)]
    pub gap: f64,
    /// A rigid obstacle of given shape instead of the flat foundation, e.g.
    /// `obstacle = { kind = "circle", center = [0.0, 1.0], radius = 1.0 }`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub obstacle: Option<crate::contact::ObstacleSpec>,
    /// The master part this (slave) part touches, a boundary part of another body or the
    /// other face of a crack, instead of the flat foundation, e.g. `against = "b_top"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub against: Option<String>,
    /// Normal law.
    #[serde(default)]
    pub law: NormalLawKind,
    /// Normal compliance stiffness c_ν > 0 (Pa/m), with `law = "normal-compliance"` only.
    #[serde(default)]
    pub c_nu: Option<f64>,
    /// Friction; frictionless if absent.
    #[serde(default)]
    pub friction: Option<FrictionSpec>,
}

/// Friction potential name (the deprecated form `potential = "nonconvex"`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PotentialKind {
    /// `j = ‖ξ‖`.
    #[default]
    Norm,
    /// The paper's nonconvex example (17), parameter `a`.
    Nonconvex,
    /// The regularized law (19), parameter `rho`.
    Regularized,
}

/// A friction potential with its parameters, `potential = { kind = "…", … }`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum PotentialLaw {
    /// `j = ‖ξ‖` (a variant with no fields rather than a unit variant, so that unknown
    /// fields in its table are refused).
    Norm {},
    /// The paper's nonconvex example (17) with parameter `0 < a < 1` (slips in m).
    Nonconvex {
        /// a_j (dimensionless).
        a: f64,
    },
    /// The regularized law (19) `√(‖ξ‖² + ρ²) − ρ`.
    Regularized {
        /// ρ > 0 (m).
        rho: f64,
    },
}

/// `potential`: a table `{ kind = "…", … }`, or the deprecated bare name whose parameter
/// is a sibling key (`a`, `rho`) of `[contact.friction]`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum PotentialSpec {
    /// `potential = { kind = "nonconvex", a = 0.5 }`.
    Law(PotentialLaw),
    /// `potential = "nonconvex"` (deprecated).
    Name(PotentialKind),
}

impl<'de> Deserialize<'de> for PotentialSpec {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        use serde::de::{self, IntoDeserializer};
        struct Visit;
        impl<'de> de::Visitor<'de> for Visit {
            type Value = PotentialSpec;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(
                    "a friction potential { kind = \"norm\" }, { kind = \"nonconvex\", a = … } \
                     or { kind = \"regularized\", rho = … }",
                )
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<PotentialSpec, E> {
                let name: de::value::StrDeserializer<E> = v.into_deserializer();
                PotentialKind::deserialize(name).map(PotentialSpec::Name)
            }
            fn visit_map<A: de::MapAccess<'de>>(self, map: A) -> Result<PotentialSpec, A::Error> {
                PotentialLaw::deserialize(de::value::MapAccessDeserializer::new(map))
                    .map(PotentialSpec::Law)
            }
        }
        deserializer.deserialize_any(Visit)
    }
}

/// Reads `mu`: a number is the constant coefficient (`mu = 0.3` is
/// `mu = { law = "constant", mu = 0.3 }`), a table one of the laws of
/// [`FrictionCoefficient`].
fn coefficient_or_number<'de, D: serde::Deserializer<'de>>(
    deserializer: D,
) -> Result<FrictionCoefficient, D::Error> {
    use serde::de;
    struct Visit;
    impl<'de> de::Visitor<'de> for Visit {
        type Value = FrictionCoefficient;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str(
                "a friction coefficient: a number (a constant μ, e.g. mu = 0.3) or a table \
                 { law = \"constant\", mu = … }, { law = \"exponential\", a = …, b = …, \
                 beta = … } or { law = \"table\", points = [[r, μ], …] }",
            )
        }
        fn visit_f64<E: de::Error>(self, mu: f64) -> Result<FrictionCoefficient, E> {
            Ok(FrictionCoefficient::Constant { mu })
        }
        fn visit_i64<E: de::Error>(self, mu: i64) -> Result<FrictionCoefficient, E> {
            Ok(FrictionCoefficient::Constant { mu: mu as f64 })
        }
        fn visit_u64<E: de::Error>(self, mu: u64) -> Result<FrictionCoefficient, E> {
            Ok(FrictionCoefficient::Constant { mu: mu as f64 })
        }
        fn visit_map<A: de::MapAccess<'de>>(self, map: A) -> Result<FrictionCoefficient, A::Error> {
            FrictionCoefficient::deserialize(de::value::MapAccessDeserializer::new(map))
        }
    }
    deserializer.deserialize_any(Visit)
}

/// `[contact.friction]`.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionSpec {
    /// Friction bound type.
    pub bound: FrictionBound,
    /// Potential j; `norm` if absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub potential: Option<PotentialSpec>,
    /// Deprecated: parameter a_j of `potential = "nonconvex"`, 0 < a < 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub a: Option<f64>,
    /// Deprecated: parameter ρ > 0 of `potential = "regularized"` (m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rho: Option<f64>,
    /// The coefficient μ(r): a table `{ law = "…", … }`, or a bare number for a constant
    /// (`mu = 0.3` reads as `{ law = "constant", mu = 0.3 }`).
    #[serde(deserialize_with = "coefficient_or_number")]
    pub mu: FrictionCoefficient,
    /// Exact stick/slip (augmented Lagrangian) instead of the numerically regularized norm;
    /// potentials `norm` and `nonconvex` only. Default false.
    #[serde(default)]
    pub exact: bool,
    /// Numerical regularization of the norm, ε in (0, 0.01): the elastic slip of a sticking
    /// point is at most ε times its slip scale `F/k` (friction bound over elastic stiffness
    /// per unit area, see [`crate::contact::friction`]); potentials `norm` and `nonconvex`
    /// without `exact` only. Default 1e-8
    /// ([`crate::contact::friction::DEFAULT_REGULARIZATION`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub regularization: Option<f64>,
}

/// `[[dirichlet]]`.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DirichletSpec {
    /// Boundary part name.
    pub part: String,
    /// Prescribed components (`"x"`, `"y"`, `"z"`); all if absent.
    #[serde(default)]
    pub components: Option<Vec<String>>,
    /// Prescribed values (m); zero if absent.
    #[serde(default)]
    pub value: Option<Vec<f64>>,
}

/// `[loads]`.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadsSpec {
    /// Constant body force f_0 (N/m³).
    #[serde(default)]
    pub body_force: Option<Vec<f64>>,
    /// Surface tractions (Γ_N).
    #[serde(default)]
    pub traction: Vec<TractionSpec>,
}

/// `[[loads.traction]]`.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TractionSpec {
    /// Boundary part name.
    pub part: String,
    /// Traction vector (N/m², N/m in 2D).
    pub value: Vec<f64>,
}

fn yes() -> bool {
    true
}

/// `[output]`.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Output folder.
    #[serde(default)]
    pub dir: Option<PathBuf>,
    /// Write the VTK file.
    #[serde(default = "yes")]
    pub vtu: bool,
    /// Write the JSON summary.
    #[serde(default = "yes")]
    pub summary: bool,
}

impl Default for OutputSpec {
    fn default() -> Self {
        OutputSpec {
            dir: None,
            vtu: true,
            summary: true,
        }
    }
}

/// `[loading]`: the path of load factors λ by which every load and prescribed displacement
/// is multiplied (see [`crate::loading`]). Exactly one of `steps` and `factors`.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadingSpec {
    /// Number N of uniform steps: λ_k = k/N, k = 1 … N (1 ≤ N ≤ 10000).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steps: Option<usize>,
    /// The load factors themselves: finite, > 0, strictly increasing (1 to 10000 of them).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub factors: Option<Vec<f64>>,
}
