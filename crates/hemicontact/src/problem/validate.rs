//! The checks of a problem's data ([`Problem::validate`]): every law and datum, the part
//! indices, the contradictions between conditions, the placement of obstacles and pairs,
//! and the free rigid motions.

use super::Problem;
use crate::error::{require, Error, Result};

impl Problem {
    /// Checks the consistency of the problem data. Field paths of the errors are those of
    /// this type: `material.…`, `plane`, `dirichlet[k].…`, `tractions[k].…`,
    /// `body_force`, `contact[k].…`.
    ///
    /// - every law's parameters ([`crate::material::Material::validate`],
    ///   [`crate::contact::ContactBoundary::validate`]);
    /// - every part index in range and naming a part with facets;
    /// - finite loads and prescribed values;
    /// - no contradiction: two Dirichlet conditions prescribing one component of a node
    ///   with different values; a traction component on a part where that component is
    ///   prescribed (it would vanish into the reaction); a contact part that is also a
    ///   Dirichlet part, or given twice;
    /// - every rigid obstacle in front of its contact part, not facing away from it
    ///   ([`crate::contact::placement::check_facing`]);
    /// - no rigid motion of a mesh component left free by the Dirichlet conditions and not
    ///   carried by a contact part ([`crate::rigid::RigidMotions::check`]).
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

    /// A part index in range, naming a part with facets.
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
}
