//! The scenario file format, mirrored literally (serde, unknown fields rejected).
//!
//! ```toml
//! [mesh]
//! kind = "rectangle"        # built-in generator; parts: bottom, right, top, left
//! origin = [0.0, 0.0]       # m (default)
//! size = [4.0, 4.0]         # m
//! n = [16, 16]              # squares per side, each cut into two triangles
//! pattern = "symmetric"     # or "uniform" (default "symmetric")
//!
//! [material]
//! model = "hooke"           # (default)
//! young = 2000.0            # Pa
//! poisson = 0.3
//! plane = "strain"          # or "stress" (2D only; default "strain")
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
//! [solver]                  # all optional, see SolverSettings
//! ordering = "nested-dissection"
//!
//! [output]
//! dir = "out/example"       # default: given on the command line
//! ```

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
    /// Geometry and mesh.
    pub mesh: MeshSpec,
    /// Bulk material.
    pub material: MaterialSpec,
    /// Dirichlet parts (Γ_D).
    #[serde(default)]
    pub dirichlet: Vec<DirichletSpec>,
    /// Loads.
    #[serde(default)]
    pub loads: LoadsSpec,
    /// Solver settings.
    #[serde(default)]
    pub solver: SolverSettings,
    /// Outputs.
    #[serde(default)]
    pub output: OutputSpec,
}

/// Mesh source.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MeshKind {
    /// Built-in rectangle generator.
    Rectangle,
}

fn default_origin() -> Vec<f64> {
    vec![0.0, 0.0]
}

fn default_pattern() -> CutPattern {
    CutPattern::Symmetric
}

/// `[mesh]`.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSpec {
    /// Mesh source.
    pub kind: MeshKind,
    /// Lower-left corner (m).
    #[serde(default = "default_origin")]
    pub origin: Vec<f64>,
    /// Side lengths (m).
    pub size: Vec<f64>,
    /// Subdivisions per side.
    pub n: Vec<u64>,
    /// Diagonal pattern.
    #[serde(default = "default_pattern")]
    pub pattern: CutPattern,
}

/// Elasticity model name.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ElasticityModel {
    /// Isotropic Hooke's law.
    #[default]
    Hooke,
}

fn default_plane() -> Plane {
    Plane::Strain
}

/// `[material]`.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
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
