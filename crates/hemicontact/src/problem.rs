//! A validated, fully resolved boundary value problem: mesh, material, boundary conditions,
//! loads and contact laws.

use crate::assembly::loads;
use crate::contact::{ContactBoundary, ContactNodes};
use crate::error::{require, Error, Result};
use crate::fem::dofs::DofMap;
use crate::material::Material;
use crate::mesh::Mesh;
use crate::rigid::RigidMotions;

/// A Dirichlet condition: the selected displacement components are prescribed on a part.
#[derive(Clone, Debug, PartialEq)]
pub struct Dirichlet {
    /// Boundary part index (see [`Mesh::part_names`]).
    pub part: usize,
    /// Which components are prescribed (`[x, y, z]`; entries beyond d are ignored).
    pub components: [bool; 3],
    /// Prescribed value of each component (m).
    pub value: [f64; 3],
}

/// A constant surface traction `f_N` (N/m² in 3D, N/m in 2D) on a part (Γ_N).
#[derive(Clone, Debug, PartialEq)]
pub struct Traction {
    /// Boundary part index.
    pub part: usize,
    /// Traction vector in global coordinates.
    pub value: [f64; 3],
}

/// The problem: find the displacement minimizing the total energy under the given data.
///
/// A `Problem` is built by [`Problem::builder`] … [`ProblemBuilder::build`], which checks
/// every law and datum, and cannot be changed afterwards (derive a changed one with
/// [`Problem::to_builder`]): a `Problem` is always valid. The solver settings are separate
/// ([`crate::solver::solve`]).
#[derive(Clone, Debug)]
pub struct Problem {
    /// The mesh.
    pub(crate) mesh: Mesh,
    /// The bulk materials: cell `c` has `materials[region_material[mesh.cell_region(c)]]`,
    /// or `materials[0]` when `region_material` is empty (one material everywhere).
    pub(crate) materials: Vec<Material>,
    /// The material of each cell region of the mesh (empty with one material).
    pub(crate) region_material: Vec<u16>,
    /// The plane idealization of a 2D problem: plane strain (`ε_zz = 0`, the out-of-plane
    /// stress follows from the law) or plane stress (`σ_zz = 0`); `Strain` in 3D. The
    /// material's constants already reflect it; the stress output uses it for σ_zz.
    pub(crate) plane: crate::material::Plane,
    /// Dirichlet conditions (Γ_D).
    pub(crate) dirichlet: Vec<Dirichlet>,
    /// Surface tractions (Γ_N).
    pub(crate) tractions: Vec<Traction>,
    /// Constant body force `f_0` (N/m³).
    pub(crate) body_force: [f64; 3],
    /// Contact boundaries (Γ_C), each facing a rigid foundation.
    pub(crate) contact: Vec<ContactBoundary>,
}

/// The data of a [`Problem`] under construction; [`ProblemBuilder::build`] checks them.
#[derive(Clone, Debug)]
pub struct ProblemBuilder {
    problem: Problem,
}

impl ProblemBuilder {
    /// The plane idealization of a 2D problem (default plane strain; must be strain in 3D).
    pub fn plane(mut self, plane: crate::material::Plane) -> Self {
        self.problem.plane = plane;
        self
    }

    /// Adds a Dirichlet condition (`dirichlet[k]`, k in the order of the calls).
    pub fn dirichlet(mut self, bc: Dirichlet) -> Self {
        self.problem.dirichlet.push(bc);
        self
    }

    /// Adds a surface traction (`tractions[k]`); tractions on one part add up.
    pub fn traction(mut self, t: Traction) -> Self {
        self.problem.tractions.push(t);
        self
    }

    /// Sets the constant body force `f_0` (N/m³).
    pub fn body_force(mut self, f: [f64; 3]) -> Self {
        self.problem.body_force = f;
        self
    }

    /// Replaces the mesh (the part indices of the conditions must fit it).
    pub fn mesh(mut self, mesh: Mesh) -> Self {
        self.problem.mesh = mesh;
        self
    }

    /// Replaces the materials by one `material` for the whole mesh.
    pub fn material(mut self, material: Material) -> Self {
        self.problem.materials = vec![material];
        self.problem.region_material.clear();
        self
    }

    /// Replaces the materials: the cells of the mesh's region `r` get
    /// `materials[region_material[r]]` (one entry per region of the mesh,
    /// [`Mesh::region_names`]; every material used).
    pub fn materials(mut self, materials: Vec<Material>, region_material: Vec<u16>) -> Self {
        self.problem.materials = materials;
        self.problem.region_material = region_material;
        self
    }

    /// Removes every contact boundary.
    pub fn without_contact(mut self) -> Self {
        self.problem.contact.clear();
        self
    }

    /// Adds a contact boundary (`contact[k]`).
    pub fn contact(mut self, c: ContactBoundary) -> Self {
        self.problem.contact.push(c);
        self
    }

    /// The problem, if its data are consistent; see [`Problem::validate`].
    ///
    /// # Errors
    /// As [`Problem::validate`].
    pub fn build(self) -> Result<Problem> {
        self.problem.validate()?;
        Ok(self.problem)
    }
}

impl Problem {
    /// Starts a problem on `mesh` with `material` everywhere: plane strain, no boundary
    /// conditions, no loads, no contact.
    pub fn builder(mesh: Mesh, material: Material) -> ProblemBuilder {
        ProblemBuilder {
            problem: Problem {
                mesh,
                materials: vec![material],
                region_material: Vec::new(),
                plane: crate::material::Plane::Strain,
                dirichlet: Vec::new(),
                tractions: Vec::new(),
                body_force: [0.0; 3],
                contact: Vec::new(),
            },
        }
    }

    /// The mesh.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// The bulk materials (one, or one per group of cell regions; see
    /// [`Problem::cell_material`]).
    pub fn materials(&self) -> &[Material] {
        &self.materials
    }

    /// The index into [`Problem::materials`] of the material of each cell region of the
    /// mesh (empty when there is one material).
    pub fn region_material(&self) -> &[u16] {
        &self.region_material
    }

    /// The index into [`Problem::materials`] of the material of cell `c`.
    #[inline]
    pub fn cell_material(&self, c: usize) -> usize {
        self.region_material
            .get(self.mesh.cell_region(c))
            .map_or(0, |&k| k as usize)
    }

    /// Whether some material locks ideally (the exact constraint `ε_T ∈ B`, imposed with a
    /// multiplier per cell).
    pub fn has_ideal_locking(&self) -> bool {
        self.materials.iter().any(|m| m.locking.ideal().is_some())
    }

    /// The set of ideal locking of each material (`None` for a material that does not lock
    /// ideally), in the order of [`Problem::materials`].
    pub fn ideal_sets(&self) -> Vec<Option<crate::material::LockingSet>> {
        self.materials.iter().map(|m| m.locking.ideal()).collect()
    }

    /// The stiffness of the body (Pa): the largest P-wave modulus `λ + 2G` of the
    /// small-strain Hooke laws of its materials (at least G), which sets the stress scale
    /// of the solve and the stiffness of the contact points.
    pub fn stiffness(&self) -> f64 {
        self.moduli().into_iter().fold(0.0, f64::max)
    }

    /// The P-wave modulus `λ + 2G` (at least G) of the small-strain Hooke law of each
    /// material (Pa), in the order of [`Problem::materials`].
    pub fn moduli(&self) -> Vec<f64> {
        let d = self.mesh.dim();
        self.materials
            .iter()
            .map(|m| {
                let h = m.elasticity.small_strain_hooke(d);
                (h.lambda + 2.0 * h.mu).max(h.mu)
            })
            .collect()
    }

    /// The plane idealization of a 2D problem (`Strain` in 3D).
    pub fn plane(&self) -> crate::material::Plane {
        self.plane
    }

    /// The Dirichlet conditions (Γ_D), in the order given.
    pub fn dirichlet(&self) -> &[Dirichlet] {
        &self.dirichlet
    }

    /// The surface tractions (Γ_N), in the order given.
    pub fn tractions(&self) -> &[Traction] {
        &self.tractions
    }

    /// The constant body force `f_0` (N/m³).
    pub fn body_force(&self) -> [f64; 3] {
        self.body_force
    }

    /// The contact boundaries (Γ_C), in the order given.
    pub fn contact(&self) -> &[ContactBoundary] {
        &self.contact
    }

    /// A builder holding this problem's data, to derive a changed problem from it.
    pub fn to_builder(&self) -> ProblemBuilder {
        ProblemBuilder {
            problem: self.clone(),
        }
    }

    /// Checks the consistency of the problem data. Field paths of the errors are those of
    /// this type: `material.…`, `plane`, `dirichlet[k].…`, `tractions[k].…`,
    /// `body_force`, `contact[k].…`.
    ///
    /// - every law's parameters ([`Material::validate`], [`ContactBoundary::validate`]);
    /// - every part index in range and naming a part with facets;
    /// - finite loads and prescribed values;
    /// - no contradiction: two Dirichlet conditions prescribing one component of a node
    ///   with different values; a traction component on a part where that component is
    ///   prescribed (it would vanish into the reaction); a contact part that is also a
    ///   Dirichlet part, or given twice;
    /// - every rigid obstacle in front of its contact part, not facing away from it
    ///   ([`crate::contact::placement::check_facing`]);
    /// - no rigid motion of a mesh component left free by the Dirichlet conditions and not
    ///   carried by a contact part ([`RigidMotions::check`]).
    ///
    /// # Errors
    /// [`Error::Invalid`] naming the field, value and what is allowed;
    /// [`Error::RigidMotion`] for a free rigid motion.
    pub fn validate(&self) -> Result<()> {
        let dim = self.mesh.dim();
        self.check_materials()?;
        require(
            dim == 2 || self.plane == crate::material::Plane::Strain,
            "plane",
            "\"stress\"",
            "\"strain\" in 3D",
        )?;
        for (k, b) in self.dirichlet.iter().enumerate() {
            self.check_part(&format!("dirichlet[{k}].part"), b.part)?;
            self.check_finite(&format!("dirichlet[{k}].value"), &b.value)?;
        }
        for (k, t) in self.tractions.iter().enumerate() {
            self.check_part(&format!("tractions[{k}].part"), t.part)?;
            self.check_finite(&format!("tractions[{k}].value"), &t.value)?;
        }
        self.check_finite("body_force", &self.body_force)?;
        for (k, c) in self.contact.iter().enumerate() {
            let field = format!("contact[{k}]");
            self.check_part(&format!("{field}.part"), c.part)?;
            c.validate().map_err(|e| e.within(&field))?;
            if let Some(m) = c.against.map(|a| a.part) {
                let f = format!("{field}.against");
                self.check_part(&f, m)?;
                let names = self.mesh.part_names();
                require(
                    m != c.part,
                    &f,
                    format!("`{}`", names[m]),
                    "a part other than the contact part itself (the master side)",
                )?;
                require(
                    c.obstacle.is_none(),
                    &f,
                    format!("`{}`", names[m]),
                    "either a master part or an obstacle, not both",
                )?;
            }
            if let Some(o) = &c.obstacle {
                o.spec
                    .validate(dim)
                    .map_err(|e| e.within(&format!("{field}.obstacle")))?;
            }
            if let crate::contact::NormalLaw::Custom(law) = &c.normal {
                law.validate(self.diameter())
                    .map_err(|message| Error::Law {
                        law: format!("{field}.normal ({})", law.name),
                        message: format!(
                            "sampled at 0 and 1e-10 … 1 times the body's size: {message}"
                        ),
                    })?;
            }
            if let Some(f) = c.friction.as_ref().filter(|f| f.mu.is_field()) {
                let x = self.part_positions(c.part);
                let mut mu = vec![0.0; x.len()];
                f.mu.values(&vec![0.0; x.len()], &x, dim, &mut mu)
                    .map_err(|message| Error::Law {
                        law: format!("{field}.friction.mu ({})", f.mu.name()),
                        message: format!("evaluated at the nodes of the contact part: {message}"),
                    })?;
            }
        }
        self.check_contradictions()?;
        if self.contact.iter().any(|c| c.obstacle.is_some()) {
            let points = self.contact_nodes()?;
            for (k, c) in self.contact.iter().enumerate() {
                crate::contact::placement::check_facing(&self.mesh, k, c, &points)
                    .map_err(|e| e.within(&format!("contact[{k}].obstacle")))?;
            }
        }
        if self.contact.iter().any(|c| c.against.is_some()) {
            let points = self.contact_nodes()?;
            let (body_of, _) = crate::rigid::bodies(&self.mesh);
            for (k, c) in self.contact.iter().enumerate() {
                crate::contact::pair_placement::check(&self.mesh, k, c, &points, &body_of)
                    .map_err(|e| e.within(&format!("contact[{k}].against")))?;
            }
            self.check_pair_bodies()?;
        }
        self.rigid_motions()?.check("problem")?;
        Ok(())
    }

    /// A body in contact with itself (a pair between two parts of one body, a crack) must
    /// be held by its own supports: its pair points would enter the analysis of its free
    /// motions with the rows `r(x_s) − r(x_m)` (which vanish where the faces coincide), but
    /// that case is not verified, and is refused. Two different bodies may both have free
    /// rigid motions: their motions are analysed together ([`crate::rigid::groups`]).
    fn check_pair_bodies(&self) -> Result<()> {
        let points = self.contact_nodes()?;
        let rigid = self.rigid_motions()?;
        let d = self.mesh.dim();
        for i in 0..points.len() {
            let (n, nodes, _) = points.stencil(d, i);
            if n == 1 {
                continue;
            }
            let b = rigid.body_of[nodes[0] as usize] as usize;
            let free = rigid.free.get(b).map_or(0, Vec::len);
            if free > 0 && rigid.body_of[nodes[1] as usize] as usize == b {
                let k = points.boundary[i] as usize;
                let names = self.mesh.part_names();
                let body = match rigid.label(b) {
                    l if l.is_empty() => "the body".to_string(),
                    l => format!("the body {l}"),
                };
                return Err(Error::Invalid {
                    field: format!("contact[{k}].against"),
                    value: format!(
                        "`{}` against `{}`: both parts of {body}, which has {free} free rigid \
                         motion(s)",
                        names[self.contact[k].part],
                        names[self.contact[k].against.map_or(0, |a| a.part)]
                    ),
                    allowed: "a pair between two parts of one body (a crack) in a body held by \
                              its own supports (Dirichlet conditions that leave no rigid motion \
                              free)"
                        .into(),
                });
            }
        }
        Ok(())
    }

    /// A part index in range, naming a part with facets.
    /// Checks every material's law (`material.…` for one, `materials[k].…` for several) and
    /// the map from cell regions to materials: one entry per region of the mesh, each
    /// naming a material, every material used.
    fn check_materials(&self) -> Result<()> {
        let dim = self.mesh.dim();
        let several = self.materials.len() > 1;
        let field = |k: usize| {
            if several {
                format!("materials[{k}]")
            } else {
                "material".to_string()
            }
        };
        require(
            !self.materials.is_empty(),
            "materials",
            "[]",
            "at least one material",
        )?;
        for (k, m) in self.materials.iter().enumerate() {
            m.validate(dim).map_err(|e| e.within(&field(k)))?;
        }
        if self.region_material.is_empty() {
            return require(
                !several,
                "region_material",
                "[]",
                "the material of each cell region when there are several materials",
            );
        }
        let regions = self.mesh.n_regions();
        require(
            self.region_material.len() == regions,
            "region_material",
            format!("{} entries", self.region_material.len()),
            &format!("one material per cell region of the mesh ({regions})"),
        )?;
        let mut used = vec![false; self.materials.len()];
        for (r, &k) in self.region_material.iter().enumerate() {
            require(
                (k as usize) < self.materials.len(),
                &format!("region_material[{r}]"),
                k,
                &format!("an index below {} (the materials)", self.materials.len()),
            )?;
            used[k as usize] = true;
        }
        match used.iter().position(|&u| !u) {
            Some(k) => require(
                false,
                &field(k),
                "applies to no cell",
                "every material applied to a cell region",
            ),
            None => Ok(()),
        }
    }

    fn check_part(&self, field: &str, part: usize) -> Result<()> {
        let names = self.mesh.part_names();
        require(
            part < names.len(),
            field,
            part,
            &format!(
                "the index of one of the mesh's {} boundary parts",
                names.len()
            ),
        )?;
        require(
            self.mesh.part_facets(part).next().is_some(),
            field,
            format!("`{}`", names[part]),
            "a boundary part with facets",
        )
    }

    /// Finite components (the first d are used).
    fn check_finite(&self, field: &str, v: &[f64; 3]) -> Result<()> {
        let v = &v[..self.mesh.dim()];
        require(
            v.iter().all(|x| x.is_finite()),
            field,
            format!("{v:?}"),
            "finite numbers",
        )
    }

    /// The contradictions listed in [`Problem::validate`], naming both entries. Equal
    /// prescribed values on shared nodes are consistent; tractions on the free
    /// components of a roller are accepted; several tractions on one part add up.
    fn check_contradictions(&self) -> Result<()> {
        let mesh = &self.mesh;
        let dim = mesh.dim();
        let axes = ["x", "y", "z"];
        let names = mesh.part_names();
        let vector = |v: &[f64; 3]| format!("{:?}", &v[..dim]);
        let dirichlet = &self.dirichlet;
        let nodes: Vec<Vec<u32>> = dirichlet.iter().map(|d| mesh.part_nodes(d.part)).collect();
        for (k, b) in dirichlet.iter().enumerate() {
            for (j, a) in dirichlet[..k].iter().enumerate() {
                let Some(i) = (0..dim)
                    .find(|&i| a.components[i] && b.components[i] && a.value[i] != b.value[i])
                else {
                    continue;
                };
                let Some(&shared) = nodes[k].iter().find(|v| nodes[j].binary_search(v).is_ok())
                else {
                    continue;
                };
                let at = format!("{:?}", mesh.node(shared as usize));
                let place = if a.part == b.part {
                    format!("on the same part `{}`", names[b.part])
                } else {
                    format!(
                        "at the node {at} shared by parts `{}` and `{}`",
                        names[a.part], names[b.part]
                    )
                };
                return Err(Error::invalid(
                    format!("dirichlet[{k}].value"),
                    format!("{} (part `{}`)", vector(&b.value), names[b.part]),
                    format!(
                        "a value that agrees with dirichlet[{j}].value = {} (part `{}`): both \
                         prescribe u_{} {place}, as {} and {}; a node has one displacement",
                        vector(&a.value),
                        names[a.part],
                        axes[i],
                        a.value[i],
                        b.value[i]
                    ),
                ));
            }
        }
        for (k, t) in self.tractions.iter().enumerate() {
            for (j, b) in dirichlet.iter().enumerate() {
                if b.part != t.part {
                    continue;
                }
                if let Some(i) = (0..dim).find(|&i| b.components[i] && t.value[i] != 0.0) {
                    return Err(Error::invalid(
                        format!("tractions[{k}].value"),
                        format!("{} (part `{}`)", vector(&t.value), names[t.part]),
                        format!(
                            "zero in the components that dirichlet[{j}] prescribes on the same \
                             part: u_{} is prescribed there, so a traction {} in that direction \
                             would do no work and vanish into the reaction",
                            axes[i], t.value[i]
                        ),
                    ));
                }
            }
        }
        for (k, c) in self.contact.iter().enumerate() {
            let name = &names[c.part];
            if let Some(j) = dirichlet.iter().position(|d| d.part == c.part) {
                return Err(Error::invalid(
                    format!("contact[{k}].part"),
                    format!("\"{name}\""),
                    format!(
                        "a part that is not also a Dirichlet part: dirichlet[{j}] prescribes \
                         part `{name}` (nodes on Γ_D are never contact nodes)"
                    ),
                ));
            }
            if let Some(j) = self.contact[..k].iter().position(|o| o.part == c.part) {
                return Err(Error::invalid(
                    format!("contact[{k}].part"),
                    format!("\"{name}\""),
                    format!(
                        "a part not already given by contact[{j}]: one contact entry per \
                         part (two laws on one boundary contradict each other)"
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The rigid motions of each mesh component that the Dirichlet conditions leave free,
    /// and those of them that no contact point carries (see [`crate::rigid`]).
    ///
    /// # Errors
    /// Those of [`Problem::contact_nodes`].
    pub fn rigid_motions(&self) -> Result<RigidMotions> {
        let dofs = self.dof_map();
        let frictional: Vec<bool> = self.contact.iter().map(|c| c.friction.is_some()).collect();
        Ok(RigidMotions::new(
            &self.mesh,
            |k| dofs.is_fixed(k),
            &self.contact_nodes()?,
            &frictional,
        ))
    }

    /// The DOF map with the Dirichlet DOFs eliminated.
    pub fn dof_map(&self) -> DofMap {
        let d = self.mesh.dim();
        let mut fixed = vec![false; d * self.mesh.n_nodes()];
        for bc in &self.dirichlet {
            for v in self.mesh.part_nodes(bc.part) {
                for i in 0..d {
                    if bc.components[i] {
                        fixed[d * v as usize + i] = true;
                    }
                }
            }
        }
        DofMap::new(d, self.mesh.n_nodes(), &fixed)
    }

    /// Whether each node has all its displacement components prescribed (a node of Γ_D in
    /// the model's sense, `u = 0` on Γ_D; such nodes are never contact nodes). A node on a
    /// roller (some components free) stays a contact node: the foundation acts on its free
    /// components.
    pub fn fully_prescribed(&self) -> Vec<bool> {
        let d = self.mesh.dim();
        let dofs = self.dof_map();
        (0..self.mesh.n_nodes())
            .map(|v| (0..d).all(|i| dofs.is_fixed(d * v + i)))
            .collect()
    }

    /// Notes worth telling the user, warnings that do not stop a run: each contact part that
    /// shares nodes with a Dirichlet part (nodes with every displacement component
    /// prescribed are not contact nodes (a node on Γ_D is never a contact node);
    /// nodes on a roller keep contact on their free components), and each contact part that
    /// turns corners (nodes split into one contact point per direction; see
    /// [`crate::contact::nodes`]), and each rigid obstacle that its contact part's mesh does
    /// not resolve: smaller than the part's elements, or reaching into the body between its
    /// nodes ([`crate::contact::placement::resolution_notes`]).
    pub fn notes(&self) -> Vec<String> {
        let names = self.mesh.part_names();
        let full = self.fully_prescribed();
        let mut notes = Vec::new();
        for c in &self.contact {
            let contact = self.mesh.part_nodes(c.part);
            for b in self.dirichlet.iter().filter(|b| b.part != c.part) {
                let shared: Vec<u32> = self
                    .mesh
                    .part_nodes(b.part)
                    .into_iter()
                    .filter(|v| contact.binary_search(v).is_ok())
                    .collect();
                if shared.is_empty() {
                    continue;
                }
                let excluded = shared.iter().filter(|&&v| full[v as usize]).count();
                let others = if excluded < shared.len() {
                    "; the others keep contact on their free components"
                } else {
                    ""
                };
                notes.push(format!(
                    "contact part `{}` shares {} node(s) with Dirichlet part `{}`: {excluded} of \
                     them, with every displacement component prescribed, are not contact nodes{others}",
                    names[c.part],
                    shared.len(),
                    names[b.part]
                ));
            }
        }
        let Ok(points) = self.contact_nodes() else {
            return notes;
        };
        for (b, c) in self.contact.iter().enumerate() {
            let nodes: Vec<u32> = (0..points.len())
                .filter(|&i| points.boundary[i] as usize == b)
                .map(|i| points.node[i])
                .collect();
            // Points of one boundary are ordered by node: corners are runs of equal nodes.
            let corners = nodes.chunk_by(|a, b| a == b).filter(|r| r.len() > 1);
            let (n_corners, n_points) = corners.fold((0, 0), |(n, p), r| (n + 1, p + r.len()));
            if n_corners > 0 {
                notes.push(format!(
                    "contact part `{}` turns corners (facet normals more than {}° apart) at \
                     {n_corners} node(s): they are {n_points} contact points, one per \
                     direction, as if the part were split there",
                    names[c.part],
                    crate::contact::nodes::CORNER_ANGLE_DEG,
                ));
            }
        }
        notes.extend(self.obstacle_notes());
        notes
    }

    /// The notes on the rigid obstacles that their contact part's mesh does not resolve
    /// (part of [`Problem::notes`]): an obstacle smaller than the part's elements, or one
    /// reaching into the body between the part's nodes
    /// ([`crate::contact::placement::resolution_notes`]). Empty without obstacles.
    pub fn obstacle_notes(&self) -> Vec<String> {
        if self.contact.iter().all(|c| c.obstacle.is_none()) {
            return Vec::new();
        }
        let Ok(points) = self.contact_nodes() else {
            return Vec::new();
        };
        let carried = self.carried_displacement();
        self.contact
            .iter()
            .enumerate()
            .flat_map(|(b, c)| {
                crate::contact::placement::resolution_notes(
                    &self.mesh,
                    b,
                    c,
                    &points,
                    carried.as_deref(),
                )
            })
            .collect()
    }

    /// The contact points of the problem.
    ///
    /// # Errors
    /// Those of [`ContactNodes::new`]: an invalid obstacle, or a node whose closest point on
    /// its obstacle is not unique.
    pub fn contact_nodes(&self) -> Result<ContactNodes> {
        let carried = self.carried_displacement();
        ContactNodes::new(
            &self.mesh,
            &self.contact,
            &self.fully_prescribed(),
            carried.as_deref(),
        )
    }

    /// The start of a solve from scratch (m, DOF order): the prescribed values at the
    /// prescribed DOFs ([`Problem::prescribed_displacement`]) and the translation the
    /// supports carry each body by ([`Problem::carried_displacement`]) at the others, so
    /// that the solve starts from each body moved rigidly where its supports put it.
    pub fn initial_displacement(&self) -> Vec<f64> {
        let mut u = self.prescribed_displacement();
        if let Some(c) = self.carried_displacement() {
            let dofs = self.dof_map();
            for (k, x) in u.iter_mut().enumerate() {
                if !dofs.is_fixed(k) {
                    *x = c[k];
                }
            }
        }
        u
    }

    /// The translation by which its supports carry each body, as a displacement (m, DOF
    /// order; [`crate::rigid::carry`]); `None` when no body is carried.
    pub fn carried_displacement(&self) -> Option<Vec<f64>> {
        let dofs = self.dof_map();
        crate::rigid::carry::carried_translation(&self.mesh, &self.prescribed_displacement(), |k| {
            dofs.is_fixed(k)
        })
    }

    /// The positions of the nodes of boundary part `part` (m, unused coordinates 0), in the
    /// order of [`Mesh::part_nodes`].
    pub fn part_positions(&self, part: usize) -> Vec<[f64; 3]> {
        let d = self.mesh.dim();
        self.mesh
            .part_nodes(part)
            .iter()
            .map(|&v| {
                let mut x = [0.0; 3];
                x[..d].copy_from_slice(self.mesh.node(v as usize));
                x
            })
            .collect()
    }

    /// Diameter of the mesh's bounding box (m): the length scale of the problem.
    pub fn diameter(&self) -> f64 {
        let (lo, hi) = self.mesh.bounding_box();
        (0..3).map(|i| (hi[i] - lo[i]).powi(2)).sum::<f64>().sqrt()
    }

    /// The initial displacement: prescribed values on Dirichlet DOFs, zero elsewhere (DOF
    /// order, length `d · n_nodes`). Where parts overlap, the later condition wins.
    pub fn prescribed_displacement(&self) -> Vec<f64> {
        let d = self.mesh.dim();
        let mut u = vec![0.0; d * self.mesh.n_nodes()];
        for bc in &self.dirichlet {
            for v in self.mesh.part_nodes(bc.part) {
                for i in 0..d {
                    if bc.components[i] {
                        u[d * v as usize + i] = bc.value[i];
                    }
                }
            }
        }
        u
    }

    /// The largest prescribed motion (m): the largest component of a Dirichlet value beyond
    /// the translation its body is carried by ([`Problem::carried_displacement`]). The
    /// displacement these data ask of the bodies, for the displacement scale of the solver
    /// (the carried translations, and an obstacle's own translation, move the bodies
    /// rigidly and are taken exactly, not through the displacement).
    pub fn largest_prescribed_motion(&self) -> f64 {
        let carried = self.carried_displacement();
        let dofs = self.dof_map();
        self.prescribed_displacement()
            .iter()
            .enumerate()
            .filter(|&(k, _)| dofs.is_fixed(k))
            .map(|(k, &x)| (x - carried.as_ref().map_or(0.0, |c| c[k])).abs())
            .fold(0.0f64, f64::max)
    }

    /// The consistent external force vector `f` (DOF order, length `d · n_nodes`).
    pub fn external_forces(&self) -> Vec<f64> {
        let d = self.mesh.dim();
        let mut f = vec![0.0; d * self.mesh.n_nodes()];
        if self.body_force.iter().any(|&x| x != 0.0) {
            loads::add_body_force(&self.mesh, &self.body_force, &mut f);
        }
        for t in &self.tractions {
            loads::add_traction(&self.mesh, t.part, &t.value, &mut f);
        }
        f
    }
}
