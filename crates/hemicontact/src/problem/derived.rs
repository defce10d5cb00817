//! What follows from a problem's data: the DOF map with the Dirichlet DOFs eliminated, the
//! contact points, the free rigid motions, the prescribed and carried displacements and
//! the length scale.

use super::Problem;
use crate::contact::ContactNodes;
use crate::error::Result;
use crate::fem::dofs::DofMap;
use crate::rigid::RigidMotions;

impl Problem {
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
    /// order of [`crate::mesh::Mesh::part_nodes`].
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
}
