//! A validated, fully resolved boundary value problem: mesh, material, boundary conditions,
//! loads, and solver settings.

use crate::assembly::loads;
use crate::contact::{ContactBoundary, ContactNodes};
use crate::error::{Error, Result};
use crate::fem::dofs::DofMap;
use crate::fem::rigid::RigidMotions;
use crate::material::Material;
use crate::mesh::Mesh;
use crate::solver::SolverSettings;

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
#[derive(Clone, Debug)]
pub struct Problem {
    /// The mesh.
    pub mesh: Mesh,
    /// The bulk material.
    pub material: Material,
    /// The plane idealization of a 2D problem: plane strain (`ε_zz = 0`, the out-of-plane
    /// stress follows from the law) or plane stress (`σ_zz = 0`); `Strain` in 3D. The
    /// material's constants already reflect it; the stress output uses it for σ_zz.
    pub plane: crate::material::Plane,
    /// Dirichlet conditions (Γ_D).
    pub dirichlet: Vec<Dirichlet>,
    /// Surface tractions (Γ_N).
    pub tractions: Vec<Traction>,
    /// Constant body force `f_0` (N/m³).
    pub body_force: [f64; 3],
    /// Contact boundaries (Γ_C), each facing a rigid foundation.
    pub contact: Vec<ContactBoundary>,
    /// Solver settings.
    pub solver: SolverSettings,
}

impl Problem {
    /// Checks the consistency of the problem data.
    ///
    /// # Errors
    /// [`Error::Mesh`] if a part index is out of range or a part has no facets;
    /// [`Error::Breakdown`] if a datum is not finite; [`Error::RigidMotion`] if a rigid motion
    /// of some mesh component is neither prescribed nor carried by a contact part (see
    /// [`RigidMotions::check`]).
    pub fn validate(&self) -> Result<()> {
        let n_parts = self.mesh.part_names().len();
        let parts = self
            .dirichlet
            .iter()
            .map(|b| b.part)
            .chain(self.tractions.iter().map(|t| t.part));
        for p in parts {
            if p >= n_parts {
                return Err(Error::Mesh(format!("boundary part index {p} out of range")));
            }
            if self.mesh.part_facets(p).next().is_none() {
                return Err(Error::Mesh(format!(
                    "boundary part `{}` has no facets",
                    self.mesh.part_names()[p]
                )));
            }
        }
        let data = self
            .dirichlet
            .iter()
            .flat_map(|b| b.value)
            .chain(self.tractions.iter().flat_map(|t| t.value))
            .chain(self.body_force);
        if data.into_iter().any(|x| !x.is_finite()) {
            return Err(Error::Breakdown(
                "a load or prescribed value is not finite".into(),
            ));
        }
        self.rigid_motions().check("problem")?;
        Ok(())
    }

    /// The rigid motions of each mesh component that the Dirichlet conditions leave free,
    /// and those of them that no contact point carries (see [`crate::fem::rigid`]).
    pub fn rigid_motions(&self) -> RigidMotions {
        let dofs = self.dof_map();
        let frictional: Vec<bool> = self.contact.iter().map(|c| c.friction.is_some()).collect();
        RigidMotions::new(
            &self.mesh,
            |k| dofs.is_fixed(k),
            &self.contact_nodes(),
            &frictional,
        )
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
    /// [`crate::contact::nodes`]).
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
        let points = self.contact_nodes();
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
        notes
    }

    /// The contact points of the problem.
    pub fn contact_nodes(&self) -> ContactNodes {
        ContactNodes::new(&self.mesh, &self.contact, &self.fully_prescribed())
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
