//! Scenario files: the TOML description of a problem, and its translation into a validated
//! [`Problem`].
//!
//! Configuration is two-staged: [`schema`] mirrors the file literally (unknown fields are
//! rejected), and [`Scenario::into_problem`] resolves and validates everything, reporting
//! the file, the field, the value and what is allowed.

pub mod builtin;
pub mod schema;

use crate::error::{Error, Result};
use crate::material::{Hooke, Material, Plane};
use crate::mesh::generate::{self, Rectangle};
use crate::mesh::Mesh;
use crate::problem::{Dirichlet, Problem, Traction};
use schema::{MeshKind, ScenarioFile};
use std::path::{Path, PathBuf};

/// A parsed scenario file (not yet validated).
#[derive(Clone, Debug)]
pub struct Scenario {
    /// Where it came from (a path, or a name such as `<built-in paper>`).
    pub source: String,
    /// The file's content.
    pub file: ScenarioFile,
}

/// Output settings resolved from a scenario.
#[derive(Clone, Debug, PartialEq)]
pub struct OutputSettings {
    /// Output folder, if the scenario names one.
    pub dir: Option<PathBuf>,
    /// Write `solution.vtu`.
    pub vtu: bool,
    /// Write `summary.json`.
    pub summary: bool,
}

impl Scenario {
    /// Reads and parses a scenario file.
    ///
    /// # Errors
    /// [`Error::Io`] if the file cannot be read, [`Error::Parse`] on a syntax error, an
    /// unknown field or a wrongly typed value.
    pub fn from_file(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        Self::from_str(&text, &path.display().to_string())
    }

    /// Parses scenario text; `source` names it in error messages.
    ///
    /// # Errors
    /// [`Error::Parse`] on a syntax error, an unknown field or a wrongly typed value.
    #[allow(clippy::should_implement_trait)]
    pub fn from_str(text: &str, source: &str) -> Result<Self> {
        let file: ScenarioFile = toml::from_str(text).map_err(|e| Error::Parse {
            file: source.to_string(),
            message: e.to_string().trim_end().to_string(),
        })?;
        Ok(Scenario {
            source: source.to_string(),
            file,
        })
    }

    fn err(&self, field: &str, value: impl std::fmt::Display, allowed: &str) -> Error {
        Error::Scenario {
            file: self.source.clone(),
            field: field.to_string(),
            value: value.to_string(),
            allowed: allowed.to_string(),
        }
    }

    fn finite(&self, field: &str, v: &[f64], dim: usize) -> Result<[f64; 3]> {
        if v.len() != dim {
            return Err(self.err(
                field,
                format!("{v:?}"),
                &format!("a vector of {dim} numbers"),
            ));
        }
        if v.iter().any(|x| !x.is_finite()) {
            return Err(self.err(field, format!("{v:?}"), "finite numbers"));
        }
        let mut out = [0.0; 3];
        out[..dim].copy_from_slice(v);
        Ok(out)
    }

    /// The output settings of the scenario.
    pub fn output(&self) -> OutputSettings {
        let o = &self.file.output;
        OutputSettings {
            dir: o.dir.clone(),
            vtu: o.vtu,
            summary: o.summary,
        }
    }

    fn build_mesh(&self) -> Result<Mesh> {
        let m = &self.file.mesh;
        match m.kind {
            MeshKind::Rectangle => {
                for (k, &s) in m.size.iter().enumerate() {
                    if !(s.is_finite() && s > 0.0) {
                        return Err(self.err(&format!("mesh.size[{k}]"), s, "a positive length"));
                    }
                }
                if m.size.len() != 2 {
                    return Err(self.err(
                        "mesh.size",
                        format!("{:?}", m.size),
                        "two lengths [lx, ly]",
                    ));
                }
                if m.n.len() != 2 {
                    return Err(self.err("mesh.n", format!("{:?}", m.n), "two counts [nx, ny]"));
                }
                for (k, &n) in m.n.iter().enumerate() {
                    if n == 0 || n > generate::MAX_SUBDIVISIONS as u64 {
                        return Err(self.err(
                            &format!("mesh.n[{k}]"),
                            n,
                            &format!("an integer from 1 to {}", generate::MAX_SUBDIVISIONS),
                        ));
                    }
                }
                let origin = self.finite("mesh.origin", &m.origin, 2)?;
                if m.pattern == generate::CutPattern::Symmetric && m.n[0] % 2 != 0 {
                    return Err(self.err(
                        "mesh.n[0]",
                        m.n[0],
                        "an even number with pattern = \"symmetric\" (mirror symmetry about the centre line)",
                    ));
                }
                generate::rectangle(&Rectangle {
                    origin: [origin[0], origin[1]],
                    size: [m.size[0], m.size[1]],
                    n: [m.n[0] as usize, m.n[1] as usize],
                    pattern: m.pattern,
                })
            }
        }
    }

    fn part(&self, mesh: &Mesh, field: &str, name: &str) -> Result<usize> {
        mesh.part_index(name).ok_or_else(|| {
            self.err(
                field,
                format!("\"{name}\""),
                &format!(
                    "one of the mesh's boundary parts: {}",
                    mesh.part_names().join(", ")
                ),
            )
        })
    }

    fn build_material(&self, dim: usize) -> Result<Material> {
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
        Ok(Material {
            elasticity: Hooke::from_young_poisson(m.young, m.poisson, dim, m.plane),
        })
    }

    /// Resolves and validates the scenario into a [`Problem`].
    ///
    /// # Errors
    /// [`Error::Scenario`] naming the file, field, value and what is allowed, or
    /// [`Error::Mesh`] if the mesh cannot be built.
    pub fn into_problem(&self) -> Result<Problem> {
        let mesh = self.build_mesh()?;
        let dim = mesh.dim();
        let material = self.build_material(dim)?;
        let axes = ["x", "y", "z"];
        let mut dirichlet = Vec::new();
        if self.file.dirichlet.is_empty() {
            return Err(self.err(
                "dirichlet",
                "[]",
                "at least one [[dirichlet]] part: without one the body can move rigidly and the problem is singular",
            ));
        }
        for (k, bc) in self.file.dirichlet.iter().enumerate() {
            let part = self.part(&mesh, &format!("dirichlet[{k}].part"), &bc.part)?;
            let mut components = [false; 3];
            match &bc.components {
                None => components[..dim].fill(true),
                Some(list) => {
                    if list.is_empty() {
                        return Err(self.err(
                            &format!("dirichlet[{k}].components"),
                            "[]",
                            "a non-empty list of axes",
                        ));
                    }
                    for c in list {
                        match axes[..dim].iter().position(|a| a == c) {
                            Some(i) => components[i] = true,
                            None => {
                                return Err(self.err(
                                    &format!("dirichlet[{k}].components"),
                                    format!("\"{c}\""),
                                    &format!("axes among {:?}", &axes[..dim]),
                                ))
                            }
                        }
                    }
                }
            }
            let value = match &bc.value {
                None => [0.0; 3],
                Some(v) => self.finite(&format!("dirichlet[{k}].value"), v, dim)?,
            };
            dirichlet.push(Dirichlet {
                part,
                components,
                value,
            });
        }
        let mut tractions = Vec::new();
        for (k, t) in self.file.loads.traction.iter().enumerate() {
            let part = self.part(&mesh, &format!("loads.traction[{k}].part"), &t.part)?;
            let value = self.finite(&format!("loads.traction[{k}].value"), &t.value, dim)?;
            tractions.push(Traction { part, value });
        }
        let body_force = match &self.file.loads.body_force {
            None => [0.0; 3],
            Some(v) => self.finite("loads.body_force", v, dim)?,
        };
        let solver = self.file.solver.clone();
        let nw = &solver.newton;
        if !(nw.residual_tolerance.is_finite()
            && nw.residual_tolerance > 0.0
            && nw.residual_tolerance < 1.0)
        {
            return Err(self.err(
                "solver.newton.residual_tolerance",
                nw.residual_tolerance,
                "a number in (0, 1)",
            ));
        }
        if !(nw.armijo > 0.0 && nw.armijo < 0.5) {
            return Err(self.err("solver.newton.armijo", nw.armijo, "a number in (0, 0.5)"));
        }
        if nw.max_iterations == 0 {
            return Err(self.err("solver.newton.max_iterations", 0, "a positive integer"));
        }
        let problem = Problem {
            mesh,
            material,
            dirichlet,
            tractions,
            body_force,
            solver,
        };
        problem.validate()?;
        Ok(problem)
    }
}
