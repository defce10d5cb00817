//! A validated, fully resolved boundary value problem: mesh, material, boundary conditions,
//! loads and contact laws.

//!
//! The data and their builder are here; what is checked of them is in `validate`, what
//! follows from them (DOF map, contact points, rigid motions, prescribed displacements) in
//! `derived`, the warnings worth telling the user in `notes`, and the consistent nodal
//! loads of the tractions and body force in [`loads`].

mod derived;
pub mod loads;
mod notes;
mod validate;

use crate::contact::ContactBoundary;
use crate::error::Result;
use crate::material::Material;
use crate::mesh::Mesh;

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
}
