//! Scenario files: the TOML description of a problem, and its translation into a validated
//! [`Problem`].
//!
//! Configuration is two-staged: [`schema`] mirrors the file literally (unknown fields are
//! rejected), and [`Scenario::into_problem`] resolves and validates everything, reporting
//! the file, the field, the value and what is allowed.

pub mod builtin;
mod friction;
pub mod schema;

use crate::contact::{ContactBoundary, NormalCompliance, NormalLaw};
use crate::error::{Error, Result};
use crate::material::{
    Elasticity, Hencky, Hooke, Locking, LockingPenalty, LockingSet, Material, Plane,
};
use crate::mesh::generate::{self, Rectangle};
use crate::mesh::Mesh;
use crate::problem::{Dirichlet, Problem, Traction};
use crate::solver::SolverSettings;
use schema::{
    ElasticityModel, LockingSetKind, LockingTreatment, MeshKind, NormalLawKind, ScenarioFile,
};
use std::path::{Path, PathBuf};

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

    /// The same scenario with `n` squares along x (and proportionally many along y), for
    /// mesh-refinement studies.
    ///
    /// # Errors
    /// [`Error::Scenario`] if the mesh is read from a file (it cannot be refined), if `n` is
    /// zero or the y count would not be an integer.
    pub fn with_resolution(&self, n: usize) -> Result<Scenario> {
        let m = &self.file.mesh;
        if m.kind == MeshKind::Gmsh {
            return Err(self.err(
                "mesh.kind",
                "\"gmsh\"",
                "a generated mesh (\"rectangle\" or \"box\"): a read mesh cannot be refined; \
                 use a generated mesh for convergence studies",
            ));
        }
        let Some(counts) = &m.n else {
            return Err(self.err(
                "mesh.n",
                "missing",
                "subdivisions per side (required for a generated mesh)",
            ));
        };
        let nx = counts.first().copied().unwrap_or(0);
        let allowed = "a resolution for which every count scales to an integer from 1 to the generator's maximum";
        let bad = || {
            self.err(
                "mesh.n",
                format!("{counts:?} scaled to {n} along x"),
                allowed,
            )
        };
        if n == 0 || nx == 0 {
            return Err(bad());
        }
        let n64 = n as u64;
        let mut scaled = Vec::with_capacity(counts.len());
        for &k in counts {
            let product = n64.checked_mul(k).ok_or_else(bad)?;
            if !product.is_multiple_of(nx)
                || product / nx == 0
                || product / nx > generate::MAX_SUBDIVISIONS as u64
            {
                return Err(bad());
            }
            scaled.push(product / nx);
        }
        let mut out = self.clone();
        out.file.mesh.n = Some(scaled);
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

    /// The mesh of `[mesh]`, and the notes of the Gmsh reader.
    fn build_mesh(&self) -> Result<(Mesh, Vec<String>)> {
        let m = &self.file.mesh;
        match m.kind {
            MeshKind::Gmsh => self.read_mesh(),
            MeshKind::Rectangle | MeshKind::Box => {
                if let Some(file) = &m.file {
                    return Err(self.err(
                        "mesh.file",
                        format!("{:?}", file.display().to_string()),
                        "only with kind = \"gmsh\" (a generated mesh has no file)",
                    ));
                }
                Ok((self.generate_mesh()?, Vec::new()))
            }
        }
    }

    /// Reads the Gmsh file of `[mesh]`, checking the memory needed to read it and to solve
    /// on it against [`Scenario::memory_limit`].
    fn read_mesh(&self) -> Result<(Mesh, Vec<String>)> {
        let m = &self.file.mesh;
        let given = [
            ("mesh.origin", m.origin.is_some()),
            ("mesh.size", m.size.is_some()),
            ("mesh.n", m.n.is_some()),
            ("mesh.pattern", m.pattern.is_some()),
        ];
        if let Some((field, _)) = given.iter().find(|(_, g)| *g) {
            return Err(self.err(
                field,
                "given",
                "nothing with kind = \"gmsh\": the mesh comes from mesh.file (origin, size, n \
                 and pattern are for generated meshes)",
            ));
        }
        let Some(file) = &m.file else {
            return Err(self.err(
                "mesh.file",
                "missing",
                "the path of a Gmsh .msh file (format 4.1), relative to the scenario file's \
                 folder (required with kind = \"gmsh\")",
            ));
        };
        let path = match &self.dir {
            Some(dir) if file.is_relative() => dir.join(file),
            _ => file.clone(),
        };
        let shown = format!("{:?}", file.display().to_string());
        let unreadable = |e: std::io::Error| {
            self.err(
                "mesh.file",
                &shown,
                &format!(
                    "a readable Gmsh .msh file, relative to the scenario file's folder ({}: {e})",
                    path.display()
                ),
            )
        };
        let too_large = |need: u64, limit: u64, what: String| {
            self.err(
                "mesh.file",
                &shown,
                &format!(
                    "a mesh whose {what} fits in memory: it needs about {} (estimate), {} are \
                     available; use --ignore-memory-limit to try anyway",
                    crate::resources::gib(need),
                    crate::resources::gib(limit)
                ),
            )
        };
        let meta = std::fs::metadata(&path).map_err(unreadable)?;
        if !meta.is_file() {
            return Err(unreadable(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "not a regular file",
            )));
        }
        let bytes = meta.len();
        if let Some(limit) = self.memory_limit {
            let need = crate::resources::estimate_mesh_read(bytes);
            if need > limit {
                return Err(too_large(need, limit, format!("file ({bytes} bytes)")));
            }
        }
        let read = match crate::mesh::gmsh::read_msh(&path) {
            Err(Error::Io { source, .. }) => return Err(unreadable(source)),
            other => other?,
        };
        let mesh = read.mesh;
        if let Some(limit) = self.memory_limit {
            // The free equations are known only with the boundary conditions: a lower bound
            // here, the estimate itself in `check_solve_memory`.
            let need = self.file.solver.linear_solver.memory_lower_bound(
                mesh.dim(),
                mesh.dim() * mesh.n_nodes(),
                mesh.n_nodes() as u64,
                mesh.n_cells() as u64,
            );
            if need > limit {
                return Err(too_large(
                    need,
                    limit,
                    format!("solve ({} nodes, {} cells)", mesh.n_nodes(), mesh.n_cells()),
                ));
            }
        }
        Ok((mesh, read.notes))
    }

    /// Generates the rectangle or box of `[mesh]`.
    fn generate_mesh(&self) -> Result<Mesh> {
        let m = &self.file.mesh;
        let dim = if m.kind == MeshKind::Box { 3 } else { 2 };
        let axes = if dim == 2 { "[lx, ly]" } else { "[lx, ly, lz]" };
        let Some(size) = &m.size else {
            return Err(self.err(
                "mesh.size",
                "missing",
                &format!("{dim} lengths {axes} (required for a generated mesh)"),
            ));
        };
        let Some(counts) = &m.n else {
            return Err(self.err(
                "mesh.n",
                "missing",
                &format!("{dim} subdivision counts (required for a generated mesh)"),
            ));
        };
        if size.len() != dim {
            return Err(self.err(
                "mesh.size",
                format!("{size:?}"),
                &format!("{dim} lengths {axes}"),
            ));
        }
        if counts.len() != dim {
            return Err(self.err("mesh.n", format!("{counts:?}"), &format!("{dim} counts")));
        }
        for (k, &s) in size.iter().enumerate() {
            if !(s.is_finite() && s > 0.0) {
                return Err(self.err(&format!("mesh.size[{k}]"), s, "a positive length"));
            }
        }
        for (k, &n) in counts.iter().enumerate() {
            if n == 0 || n > generate::MAX_SUBDIVISIONS as u64 {
                return Err(self.err(
                    &format!("mesh.n[{k}]"),
                    n,
                    &format!("an integer from 1 to {}", generate::MAX_SUBDIVISIONS),
                ));
            }
        }
        let origin = match &m.origin {
            None => [0.0; 3],
            Some(o) => self.finite("mesh.origin", o, dim)?,
        };
        if m.pattern() == generate::CutPattern::Symmetric && !counts[0].is_multiple_of(2) {
            return Err(self.err(
                "mesh.n[0]",
                counts[0],
                "an even number with pattern = \"symmetric\" (mirror symmetry about the centre plane)",
            ));
        }
        if let Some(limit) = self.memory_limit {
            // The free equations are known only with the boundary conditions: a lower bound
            // here, before anything is allocated, the estimate itself in
            // `check_solve_memory`.
            let nodes: u64 = counts.iter().map(|&c| c + 1).product();
            let cells: u64 = counts.iter().product::<u64>() * if dim == 2 { 2 } else { 6 };
            let max_free = (dim as u64).saturating_mul(nodes);
            let need = self.file.solver.linear_solver.memory_lower_bound(
                dim,
                usize::try_from(max_free).unwrap_or(usize::MAX),
                nodes,
                cells,
            );
            if need > limit {
                return Err(self.err(
                    "mesh.n",
                    format!("{counts:?}"),
                    &format!(
                        "a mesh whose solve fits in memory: this one needs about {} (estimate), {} are available; \
                         use --ignore-memory-limit to try anyway",
                        crate::resources::gib(need),
                        crate::resources::gib(limit)
                    ),
                ));
            }
        }
        let n = |k: usize| counts[k] as usize;
        let generated = if dim == 2 {
            generate::rectangle(&Rectangle {
                origin: [origin[0], origin[1]],
                size: [size[0], size[1]],
                n: [n(0), n(1)],
                pattern: m.pattern(),
            })
        } else {
            generate::cuboid(&generate::BoxSpec {
                origin,
                size: [size[0], size[1], size[2]],
                n: [n(0), n(1), n(2)],
                pattern: m.pattern(),
            })
        };
        // A generated mesh can only be invalid through the numbers of [mesh]: name them.
        generated.map_err(|e| match e {
            Error::Mesh(msg) => self.err(
                "mesh.size / mesh.origin / mesh.n",
                format!("size {size:?}, origin {:?}, n {counts:?}", m.origin),
                &format!("sizes and an origin for which the cells are representable ({msg})"),
            ),
            other => other,
        })
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
    fn required(&self, field: &str, v: Option<f64>, what: &str) -> Result<f64> {
        v.ok_or_else(|| self.err(field, "missing", &format!("{what} > 0 (required)")))
    }

    fn positive(&self, field: &str, v: Option<f64>, what: &str) -> Result<f64> {
        match v {
            Some(x) if x.is_finite() && x > 0.0 => Ok(x),
            Some(x) => Err(self.err(field, x, &format!("{what} > 0"))),
            None => Err(self.err(field, "missing", &format!("{what} > 0 (required)"))),
        }
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
        let set = match l.set {
            LockingSetKind::None => None,
            LockingSetKind::LimitedCompressibility => Some(LockingSet::LimitedCompressibility {
                theta: self.required(
                    "locking.theta",
                    l.theta,
                    "a volumetric strain threshold θ",
                )?,
            }),
            LockingSetKind::Prager => Some(LockingSet::Prager {
                kappa: self.required("locking.kappa", l.kappa, "a deviatoric threshold κ")?,
            }),
            LockingSetKind::Ball => Some(LockingSet::Ball {
                r: self.required("locking.radius", l.radius, "a strain radius r")?,
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

    fn build_contact(&self, mesh: &Mesh) -> Result<Vec<ContactBoundary>> {
        let mut out = Vec::new();
        for (k, c) in self.file.contact.iter().enumerate() {
            let f = |name: &str| format!("contact[{k}].{name}");
            let part = self.part(mesh, &f("part"), &c.part)?;
            let normal = match c.law {
                NormalLawKind::NormalCompliance => NormalLaw::Compliance(NormalCompliance {
                    c_nu: self.required(
                        &f("c_nu"),
                        c.c_nu,
                        "a normal compliance stiffness c_ν (Pa/m)",
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
            };
            let friction = match &c.friction {
                None => None,
                Some(fs) => Some(self.build_friction(k, fs)?),
            };
            out.push(ContactBoundary {
                part,
                gap: c.gap,
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
        let material = self.build_material(dim)?;
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
        let contact = self.build_contact(&mesh)?;
        let mut builder = Problem::builder(mesh, material)
            .plane(self.file.material.plane)
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

    /// Checks the estimated memory of a solve of `problem` against
    /// [`Scenario::memory_limit`], for the linear solver the solve will use
    /// ([`crate::solver::system::resolved_linear_solver`]).
    fn check_solve_memory(&self, problem: &Problem) -> Result<()> {
        let Some(limit) = self.memory_limit else {
            return Ok(());
        };
        let mesh = &problem.mesh;
        let kind =
            crate::solver::system::resolved_linear_solver(problem, self.file.solver.linear_solver);
        let need = kind.memory_estimate(
            mesh.dim(),
            problem.dof_map().n_free(),
            mesh.n_nodes() as u64,
            mesh.n_cells() as u64,
        );
        if need <= limit {
            return Ok(());
        }
        let (field, value) = match &self.file.mesh.n {
            Some(n) if self.file.mesh.kind != MeshKind::Gmsh => ("mesh.n", format!("{n:?}")),
            _ => (
                "mesh.file",
                format!("{} nodes, {} cells", mesh.n_nodes(), mesh.n_cells()),
            ),
        };
        Err(self.err(
            field,
            value,
            &format!(
                "a mesh whose solve fits in memory: this one needs about {} (estimate) with \
                 linear_solver = \"{}\", {} are available; use --ignore-memory-limit to try \
                 anyway",
                crate::resources::gib(need),
                format!("{kind:?}").to_lowercase(),
                crate::resources::gib(limit)
            ),
        ))
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
