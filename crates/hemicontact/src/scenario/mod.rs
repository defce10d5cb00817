//! Scenario files: the TOML description of a problem, and its translation into a validated
//! [`Problem`].
//!
//! Configuration is two-staged: [`schema`] mirrors the file literally (unknown fields are
//! rejected), and [`Scenario::into_problem`] resolves and validates everything, reporting
//! the file, the field, the value and what is allowed.

pub mod builtin;
mod friction;
mod material;
mod mesh;
pub mod schema;

use crate::contact::{ContactBoundary, NormalCompliance, NormalLaw};
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::problem::{Dirichlet, Problem, Traction};
use crate::solver::SolverSettings;
use schema::{NormalLawKind, OutputSpec, ScenarioFile};
use std::path::{Path, PathBuf};

/// A JSON Schema (draft 2020-12) of the scenario file, for editors that complete and check
/// TOML against a schema (`hemicontact schema` prints it). It mirrors [`schema`] key for
/// key, with the documented ranges as `minimum`/`maximum` and the choices as `enum`; a
/// number for `mu` is the constant coefficient. Cross-key rules (e.g. `c_nu` only with
/// `normal-compliance`) are checked when the scenario is read, not by the schema.
pub const JSON_SCHEMA: &str = include_str!("scenario.schema.json");

/// Largest scenario file [`Scenario::from_file`] reads (bytes): 1 MiB, far above any
/// hand-written scenario (the examples are below 2 kB); meshes come from separate files.
pub const MAX_SCENARIO_BYTES: u64 = 1 << 20;

/// A parsed scenario file (not yet validated).
#[derive(Clone, Debug)]
pub struct Scenario {
    /// Where it came from (a path, or a name such as `<built-in paper>`).
    pub source: String,
    /// The file's content.
    pub file: ScenarioFile,
    /// Memory budget (bytes) checked against the estimate of [`crate::resources`] before
    /// the mesh is built; set from the memory available when the scenario is read, `None`
    /// to skip the check (the CLI's `--ignore-memory-limit`).
    pub memory_limit: Option<u64>,
    /// Folder against which relative paths of the file (`mesh.file`) are resolved: the
    /// scenario file's folder for [`Scenario::from_file`], `None` (the working folder) for
    /// text parsed with [`Scenario::from_str`].
    pub dir: Option<PathBuf>,
    /// A mesh given in memory (built from arrays, e.g. by the Python package) instead of a
    /// `[mesh]` table; its parts are the names its boundary facets carry.
    pub given_mesh: Option<Mesh>,
    /// Friction coefficients given in memory (user-defined laws, e.g. Python callables
    /// through [`crate::contact::CustomCoefficient`]) by contact entry: each replaces the
    /// `mu` of `[[contact]]` entry k, which the file still gives (any valid law) so that
    /// the schema holds.
    pub given_friction: Vec<(usize, crate::contact::FrictionCoefficient)>,
    /// Normal laws given in memory (user-defined compliance laws, e.g. Python callables
    /// through [`crate::contact::CustomCompliance`]) by contact entry: each replaces the
    /// normal law (`law`, `c_nu`) of `[[contact]]` entry k.
    pub given_normal: Vec<(usize, NormalLaw)>,
}

impl Scenario {
    /// Reads and parses a scenario file: a regular file of at most
    /// [`MAX_SCENARIO_BYTES`] bytes, UTF-8 encoded.
    ///
    /// # Errors
    /// [`Error::Io`] if the file cannot be read, is not a regular file (a folder, a device
    /// such as `/dev/zero`, a pipe: reading it could take without end) or is larger than
    /// [`MAX_SCENARIO_BYTES`]; [`Error::Parse`] on a syntax error, an unknown field or a
    /// wrongly typed value.
    pub fn from_file(path: &Path) -> Result<Self> {
        use std::io::Read as _;
        let refuse = |why: String| {
            Error::io(
                path,
                std::io::Error::new(std::io::ErrorKind::InvalidInput, why),
            )
        };
        let meta = std::fs::metadata(path).map_err(|e| Error::io(path, e))?;
        if !meta.is_file() {
            return Err(refuse(
                "not a regular file (a scenario is a TOML text file)".into(),
            ));
        }
        let too_large = |size: u64| {
            refuse(format!(
                "{size} bytes: larger than the {MAX_SCENARIO_BYTES} bytes allowed for a \
                 scenario file (meshes belong in a separate .msh file)"
            ))
        };
        if meta.len() > MAX_SCENARIO_BYTES {
            return Err(too_large(meta.len()));
        }
        // The limit also holds if the file grows between the size check and the read.
        let file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
        let mut text = String::new();
        file.take(MAX_SCENARIO_BYTES + 1)
            .read_to_string(&mut text)
            .map_err(|e| Error::io(path, e))?;
        if text.len() as u64 > MAX_SCENARIO_BYTES {
            return Err(too_large(text.len() as u64));
        }
        let mut scenario = Self::from_str(&text, &path.display().to_string())?;
        scenario.dir = path.parent().map(Path::to_path_buf);
        Ok(scenario)
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
            memory_limit: crate::resources::available_memory(),
            dir: None,
            given_mesh: None,
            given_friction: Vec::new(),
            given_normal: Vec::new(),
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

    /// The output settings of the scenario (`[output]`).
    pub fn output(&self) -> &OutputSpec {
        &self.file.output
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

    /// A parameter the file must give; its range is checked by the library's laws.
    /// `allowed` names the parameter with its range (e.g. `a parameter 0 < a < 1`).
    fn required(&self, field: &str, v: Option<f64>, allowed: &str) -> Result<f64> {
        v.ok_or_else(|| self.err(field, "missing", &format!("{allowed} (required)")))
    }

    fn positive(&self, field: &str, v: Option<f64>, what: &str) -> Result<f64> {
        match v {
            Some(x) if x.is_finite() && x > 0.0 => Ok(x),
            Some(x) => Err(self.err(field, x, &format!("{what} > 0"))),
            None => Err(self.err(field, "missing", &format!("{what} > 0 (required)"))),
        }
    }

    fn build_contact(&self, mesh: &Mesh) -> Result<Vec<ContactBoundary>> {
        for (k, mu) in &self.given_friction {
            if self
                .file
                .contact
                .get(*k)
                .is_none_or(|c| c.friction.is_none())
            {
                return Err(self.err(
                    &format!("contact[{k}].friction.mu"),
                    format!("{mu:?} (given in memory)"),
                    "a law for a [[contact]] entry that has a [contact.friction] table",
                ));
            }
        }
        if let Some((k, law)) = self
            .given_normal
            .iter()
            .find(|(k, _)| *k >= self.file.contact.len())
        {
            return Err(self.err(
                &format!("contact[{k}].normal"),
                format!("{law:?} (given in memory)"),
                "a law for an existing [[contact]] entry",
            ));
        }
        let mut out = Vec::new();
        for (k, c) in self.file.contact.iter().enumerate() {
            let f = |name: &str| format!("contact[{k}].{name}");
            let part = self.part(mesh, &f("part"), &c.part)?;
            let given = self.given_normal.iter().find(|(entry, _)| *entry == k);
            let normal = match given {
                Some((_, law)) => law.clone(),
                None => match c.law {
                    NormalLawKind::NormalCompliance => NormalLaw::Compliance(NormalCompliance {
                        c_nu: self.required(
                            &f("c_nu"),
                            c.c_nu,
                            "a normal compliance stiffness c_ν > 0 (Pa/m)",
                        )?,
                    }),
                    NormalLawKind::Signorini => {
                        if let Some(c_nu) = c.c_nu {
                            return Err(self.err(
                                &f("c_nu"),
                                c_nu,
                                "no stiffness with law = \"signorini\" (a rigid foundation)",
                            ));
                        }
                        NormalLaw::Signorini
                    }
                },
            };
            let friction = match &c.friction {
                None => None,
                Some(fs) => Some(self.build_friction(k, fs)?),
            };
            let obstacle = c.obstacle.clone().map(crate::contact::ContactObstacle::new);
            let against = match &c.against {
                Some(name) => Some(crate::contact::MasterPart::new(self.part(
                    mesh,
                    &f("against"),
                    name,
                )?)),
                None => None,
            };
            out.push(ContactBoundary {
                against,
                part,
                gap: c.gap,
                obstacle,
                normal,
                friction,
            });
        }
        Ok(out)
    }

    /// Resolves and validates the scenario into a [`Problem`].
    ///
    /// # Errors
    /// [`Error::Scenario`] naming the file, field, value and what is allowed,
    /// [`Error::Mesh`] if the mesh cannot be built, or [`Error::MeshFile`] if a Gmsh file
    /// cannot be read.
    pub fn into_problem(&self) -> Result<Problem> {
        self.into_problem_with_notes().map(|(problem, _)| problem)
    }

    /// [`Scenario::into_problem`], with the notes (warnings that do not stop the run) the
    /// scenario raised: those of the Gmsh reader (see [`crate::mesh::gmsh::GmshMesh::notes`])
    /// and of the problem ([`Problem::notes`]).
    ///
    /// # Errors
    /// As [`Scenario::into_problem`].
    pub fn into_problem_with_notes(&self) -> Result<(Problem, Vec<String>)> {
        let (mesh, mut notes) = self.build_mesh()?;
        let dim = mesh.dim();
        let (materials, region_material) = self.build_materials(&mesh)?;
        let axes = ["x", "y", "z"];
        let mut dirichlet = Vec::new();
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
        self.settings()?;
        self.load_factors()?;
        let contact = self.build_contact(&mesh)?;
        let mut builder = Problem::builder(mesh, materials[0].clone())
            .materials(materials, region_material)
            .plane(self.plane())
            .body_force(body_force);
        for d in dirichlet {
            builder = builder.dirichlet(d);
        }
        for t in tractions {
            builder = builder.traction(t);
        }
        for c in contact {
            builder = builder.contact(c);
        }
        // Rigid motions left free are named with this file (the library says `problem`);
        // invalid data are named by their field in the file.
        let problem = builder.build().map_err(|e| match e {
            Error::RigidMotion { motions, .. } => Error::RigidMotion {
                file: self.source.clone(),
                motions,
            },
            e => e.in_file(&self.source, field_in_file),
        })?;
        self.check_solve_memory(&problem)?;
        notes.extend(self.friction_notes());
        notes.extend(problem.notes());
        Ok((problem, notes))
    }

    /// The load factors of `[loading]` ([`crate::loading`]), checked; `None` without a
    /// `[loading]` table (one solve at the full load).
    ///
    /// # Errors
    /// [`Error::Scenario`] naming `loading`, `loading.steps`, `loading.factors` or
    /// `loading.factors[k]`: exactly one of `steps` (1 to [`crate::loading::MAX_STEPS`]) and
    /// `factors` (finite, > 0, strictly increasing) must be given.
    pub fn load_factors(&self) -> Result<Option<Vec<f64>>> {
        let Some(spec) = &self.file.loading else {
            return Ok(None);
        };
        let in_file = |e: Error| e.in_file(&self.source, |f| format!("loading.{f}"));
        let factors = match (spec.steps, &spec.factors) {
            (Some(n), None) => crate::loading::uniform_factors(n).map_err(in_file)?,
            (None, Some(list)) => {
                crate::loading::validate_factors(list).map_err(in_file)?;
                list.clone()
            }
            (Some(n), Some(_)) => {
                return Err(self.err(
                    "loading",
                    format!("steps = {n} and factors"),
                    "exactly one of steps and factors",
                ))
            }
            (None, None) => {
                return Err(self.err(
                    "loading",
                    "an empty table",
                    "exactly one of steps (a number of uniform steps) and factors (a list of \
                     load factors)",
                ))
            }
        };
        Ok(Some(factors))
    }

    /// This scenario solved on `processes` (those of the program's launch,
    /// [`crate::parallel::Processes::launch`]): its settings
    /// ([`SolverSettings::processes`]) and the memory check of its problem count them.
    /// Without, a scenario is solved on this process alone.
    pub fn on(mut self, processes: crate::parallel::Processes) -> Scenario {
        self.file.solver.processes = processes;
        self
    }

    /// The solver settings of `[solver]`, checked ([`SolverSettings::validate`]).
    ///
    /// # Errors
    /// [`Error::Scenario`] naming the field under `solver.`, its value and what is allowed.
    pub fn settings(&self) -> Result<SolverSettings> {
        let settings = self.file.solver.clone();
        settings
            .validate()
            .map_err(|e| e.in_file(&self.source, |f| format!("solver.{f}")))?;
        Ok(settings)
    }
}

/// The field of a scenario file that holds the datum at `field` of a [`Problem`] (see
/// [`Problem::validate`]): the file groups loads under `loads` and locking under
/// `[locking]`, and gives the elastic constants as E and ν.
fn field_in_file(field: &str) -> String {
    let renamed = [
        ("tractions[", "loads.traction["),
        ("body_force", "loads.body_force"),
        ("plane", "material.plane"),
        ("material.elasticity.s0", "material.reference_strain"),
        ("material.elasticity.shear_inf", "material.stiffening"),
        ("material.elasticity", "material.young"),
        ("material.locking.r", "locking.radius"),
        ("material.locking", "locking"),
    ];
    for (from, to) in renamed {
        if let Some(rest) = field.strip_prefix(from) {
            // E and ν are not the library's constants: name E for any of them.
            let rest = if from == "material.elasticity" {
                ""
            } else {
                rest
            };
            return format!("{to}{rest}");
        }
    }
    field.to_string()
}
