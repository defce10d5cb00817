//! The mesh of a scenario: `[mesh]` generated (rectangle, box) or read from a Gmsh file,
//! refined for convergence studies, and checked against the memory available.

use super::schema::{MeshKind, MeshSpec, RegionSpec};
use super::Scenario;
use crate::error::{Error, Result};
use crate::mesh::generate::{self, Rectangle};
use crate::mesh::Mesh;
use crate::problem::Problem;

impl Scenario {
    /// The same scenario with `n` squares along x (and proportionally many along y), for
    /// mesh-refinement studies.
    ///
    /// A graded mesh (`mesh.progression`) keeps its total grading `R = r^cells` on every
    /// axis: all counts scale by `n/n_x` (`n_x` the current count along x), so each ratio
    /// `r` becomes `r^(n_x/n)`. Every mesh then samples the same map
    /// `ξ ↦ x0 + L (R^ξ − 1)/(R − 1)` at `ξ = i/cells`, and refining by an integer factor `s`
    /// splits each cell into `s` (nested meshes, as convergence studies need): doubling `n`
    /// takes `r` to `√r`.
    ///
    /// # Errors
    /// [`Error::Scenario`] if the mesh is read from a file (it cannot be refined), if `n` is
    /// zero or the y count would not be an integer.
    pub fn with_resolution(&self, n: usize) -> Result<Scenario> {
        if self.given_mesh.is_some() {
            return Err(self.err(
                "mesh",
                "a mesh given in memory",
                "a generated mesh (\"rectangle\" or \"box\"): a given mesh cannot be \
                 refined; use a generated mesh for convergence studies",
            ));
        }
        let m = self.mesh_spec()?;
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
        if let Some(spec) = out.file.mesh.as_mut() {
            spec.n = Some(scaled);
            // Same total grading r^cells on every axis (all counts scale by n / nx).
            let exponent = nx as f64 / n as f64;
            if let Some(ratios) = spec.progression.as_mut() {
                for r in ratios.iter_mut().filter(|r| **r != 1.0) {
                    *r = r.powf(exponent);
                }
            }
        }
        Ok(out)
    }

    /// The `[mesh]` table.
    ///
    /// # Errors
    /// [`Error::Scenario`] naming `mesh` if the file has none.
    pub fn mesh_spec(&self) -> Result<&MeshSpec> {
        self.file.mesh.as_ref().ok_or_else(|| {
            self.err(
                "mesh",
                "missing",
                "a [mesh] table: a generator (kind = \"rectangle\" or \"box\") or a Gmsh file \
                 (kind = \"gmsh\") (required)",
            )
        })
    }

    /// The mesh given in memory or of `[mesh]`, and the notes of the Gmsh reader.
    pub(super) fn build_mesh(&self) -> Result<(Mesh, Vec<String>)> {
        if let Some(mesh) = &self.given_mesh {
            if self.file.mesh.is_some() {
                return Err(self.err(
                    "mesh",
                    "a [mesh] table and a mesh given in memory",
                    "one of them: the table describes a mesh to build, the given mesh is one",
                ));
            }
            return Ok((mesh.clone(), Vec::new()));
        }
        let m = self.mesh_spec()?;
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
    pub(super) fn read_mesh(&self) -> Result<(Mesh, Vec<String>)> {
        let m = self.mesh_spec()?;
        let given = [
            ("mesh.origin", m.origin.is_some()),
            ("mesh.size", m.size.is_some()),
            ("mesh.n", m.n.is_some()),
            ("mesh.pattern", m.pattern.is_some()),
            ("mesh.progression", m.progression.is_some()),
            ("mesh.region", !m.region.is_empty()),
        ];
        if let Some((field, _)) = given.iter().find(|(_, g)| *g) {
            return Err(self.err(
                field,
                "given",
                "nothing with kind = \"gmsh\": the mesh comes from mesh.file (origin, size, n, \
                 pattern, progression and region are for generated meshes; a Gmsh file's \
                 cell regions are its physical groups)",
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
                &self.file.solver.processes,
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
    pub(super) fn generate_mesh(&self) -> Result<Mesh> {
        let m = self.mesh_spec()?;
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
        let progression = self.progression(m, counts)?;
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
                &self.file.solver.processes,
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
                progression: [progression[0], progression[1]],
            })
        } else {
            generate::cuboid(&generate::BoxSpec {
                origin,
                size: [size[0], size[1], size[2]],
                n: [n(0), n(1), n(2)],
                pattern: m.pattern(),
                progression,
            })
        };
        // A generated mesh can only be invalid through the numbers of [mesh]: name them.
        let mesh = generated.map_err(|e| match e {
            Error::Mesh(msg) => self.err(
                "mesh.size / mesh.origin / mesh.n",
                format!("size {size:?}, origin {:?}, n {counts:?}", m.origin),
                &format!("sizes and an origin for which the cells are representable ({msg})"),
            ),
            other => other,
        })?;
        self.with_regions(mesh, &m.region)
    }

    /// The generated `mesh` with the cell regions `regions` (`[[mesh.region]]`): each cell in
    /// the first box holding its centroid.
    fn with_regions(&self, mesh: Mesh, regions: &[RegionSpec]) -> Result<Mesh> {
        if regions.is_empty() {
            return Ok(mesh);
        }
        let d = mesh.dim();
        let mut region = vec![u16::MAX; mesh.n_cells()];
        let mut names = Vec::with_capacity(regions.len());
        for (k, r) in regions.iter().enumerate() {
            let at = format!("mesh.region[{k}]");
            if r.name.is_empty() || names.contains(&r.name) {
                return Err(self.err(
                    &format!("{at}.name"),
                    format!("{:?}", r.name),
                    "a non-empty name given to no other region",
                ));
            }
            let lo = self.finite(&format!("{at}.min"), &r.min, d)?;
            let hi = self.finite(&format!("{at}.max"), &r.max, d)?;
            if let Some(i) = (0..d).find(|&i| lo[i] > hi[i]) {
                return Err(self.err(
                    &format!("{at}.max"),
                    format!("{:?}", r.max),
                    &format!(
                        "a corner with max ≥ min on every axis (axis {i}: {} < {})",
                        hi[i], lo[i]
                    ),
                ));
            }
            let cells = mesh.cells_in_box(lo, hi);
            let mut taken = 0;
            for c in cells {
                if region[c] == u16::MAX {
                    region[c] = k as u16;
                    taken += 1;
                }
            }
            if taken == 0 {
                return Err(self.err(
                    &at,
                    format!("min {:?}, max {:?}", r.min, r.max),
                    "a box holding the centroid of some cell not in an earlier region",
                ));
            }
            names.push(r.name.clone());
        }
        if let Some(c) = region.iter().position(|&r| r == u16::MAX) {
            let x = mesh.cell_coords(c);
            let centroid: Vec<f64> = (0..d)
                .map(|i| x[..=d].iter().map(|p| p[i]).sum::<f64>() / (d + 1) as f64)
                .collect();
            return Err(self.err(
                "mesh.region",
                format!("cell {c} (centroid {centroid:?}) is in no box"),
                "boxes that together hold every cell's centroid",
            ));
        }
        mesh.with_regions(region, names)
    }

    /// The progression ratios of a generated `[mesh]` with `counts` cells per axis (all 1 if
    /// `mesh.progression` is absent), checked with [`generate::check_progression`] and
    /// against the symmetric pattern, which needs 1 along x.
    fn progression(&self, m: &MeshSpec, counts: &[u64]) -> Result<[f64; 3]> {
        let mut out = [1.0; 3];
        let Some(ratios) = &m.progression else {
            return Ok(out);
        };
        let dim = counts.len();
        if ratios.len() != dim {
            return Err(self.err(
                "mesh.progression",
                format!("{ratios:?}"),
                &format!("{dim} ratios, one per axis"),
            ));
        }
        for (k, (&r, &n)) in ratios.iter().zip(counts).enumerate() {
            generate::check_progression(r, n as usize)
                .map_err(|allowed| self.err(&format!("mesh.progression[{k}]"), r, &allowed))?;
            out[k] = r;
        }
        if m.pattern() == generate::CutPattern::Symmetric && out[0] != 1.0 {
            return Err(self.err(
                "mesh.progression[0]",
                out[0],
                "1 with pattern = \"symmetric\" (the default; a graded x axis is not \
                 mirror-symmetric about its centre): set pattern = \"uniform\" to grade along x",
            ));
        }
        Ok(out)
    }

    /// Checks the estimated memory of a solve of `problem` against
    /// [`Scenario::memory_limit`], for the linear solver the solve will use
    /// ([`crate::solver::system::resolved_linear_solver`]).
    pub(super) fn check_solve_memory(&self, problem: &Problem) -> Result<()> {
        let Some(limit) = self.memory_limit else {
            return Ok(());
        };
        let mesh = &problem.mesh;
        // An MPI launch: what all its processes on this machine need together.
        let processes = self.file.solver.processes;
        let kind = crate::solver::system::resolved_linear_solver(
            problem,
            self.file.solver.linear_solver,
            &processes,
        );
        // Plus the work arrays of the parallel assembly (per cell, a few bytes).
        let need = kind.memory_estimate(
            mesh.dim(),
            problem.dof_map().n_free(),
            mesh.n_nodes() as u64,
            mesh.n_cells() as u64,
            &processes,
        ) + crate::assembly::global::Workspace::buffer_bytes(
            rayon::current_num_threads(),
            mesh.n_cells(),
        );
        let need = if processes.size() > 1 {
            crate::resources::estimate_machine(
                need,
                mesh.dim(),
                mesh.n_nodes() as u64,
                mesh.n_cells() as u64,
                processes.size(),
                processes.on_this_machine(),
            )
        } else {
            need
        };
        if need <= limit {
            return Ok(());
        }
        let processes_here = match processes.on_this_machine() {
            _ if processes.size() == 1 => String::new(),
            1 => " for the one process of this launch on this machine".to_string(),
            n => format!(" for the {n} processes of this launch on this machine"),
        };
        let (field, value) = match &self.file.mesh {
            Some(m) if m.kind != MeshKind::Gmsh && m.n.is_some() => (
                "mesh.n",
                format!("{:?}", m.n.as_deref().unwrap_or_default()),
            ),
            _ => (
                if self.file.mesh.is_some() {
                    "mesh.file"
                } else {
                    "mesh"
                },
                format!("{} nodes, {} cells", mesh.n_nodes(), mesh.n_cells()),
            ),
        };
        Err(self.err(
            field,
            value,
            &format!(
                "a mesh whose solve fits in memory: this one needs about {}{processes_here} \
                 (estimate) with linear_solver = \"{}\", {} are available; use \
                 --ignore-memory-limit to try anyway",
                crate::resources::gib(need),
                format!("{kind:?}").to_lowercase(),
                crate::resources::gib(limit)
            ),
        ))
    }
}
