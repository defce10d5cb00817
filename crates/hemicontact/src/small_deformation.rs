//! The small-deformation check of a solution.
//!
//! The model is linearized: the strain is `ε = ½ (∇u + ∇uᵀ)`, equilibrium is written in
//! the reference configuration, and the contact gaps and normals are those of the
//! reference configuration. A solution is a solution of that model whatever its size, but
//! it describes a physical body only while the deformation stays small. After a solve the
//! displacement is checked once, in one pass over the cells (O(cells), no assembly):
//!
//! - the largest strain `max_T ‖ε_T‖`, with `‖ε‖ = (ε : ε)^{1/2}` the Frobenius norm
//!   (≥ the largest principal strain in magnitude), against [`STRAIN_LIMIT`] = 0.1;
//! - the largest displacement relative to the body's size, `max_v |u_v| / D` with D the
//!   diagonal of the mesh's bounding box (m), against [`DISPLACEMENT_LIMIT`] = 0.1 (a
//!   rigid rotation strains nothing, but moves the body by about θ D);
//! - the cells the displacement inverts: those whose signed measure in the deformed
//!   configuration `x + u` is ≤ 0 (a triangle or tetrahedron turned inside out, which no
//!   deformation of a body does; every cell is positive in the reference configuration).
//!
//! - with contact pairs between bodies, the nodes of one body that the displacement puts
//!   inside the other ([`crate::contact::interpenetration`]: the deepest of each pair and
//!   direction, when deeper than a tenth of the element size there).
//!
//! Each limit exceeded, any inverted cell and any interpenetration gives a note
//! ([`SmallDeformation::notes`]),
//! which `summary.json` lists among its `notes`, the command line prints and the Python
//! package raises as a `RuntimeWarning`. The limits are where the neglected terms reach
//! the order of 10 % of the kept ones: the quadratic term `½ ∇uᵀ∇u` of the Green–Lagrange
//! strain against `ε`, and a change of the contact geometry by the displacement against
//! the body's size.

use crate::geometry::simplex;
use crate::mesh::Mesh;
use crate::tensor::Sym;
use serde::Serialize;

/// Largest strain norm `‖ε‖ = (ε : ε)^{1/2}` (dimensionless) for which the deformation
/// counts as small.
pub const STRAIN_LIMIT: f64 = 0.1;

/// Largest displacement relative to the body's size (the diagonal of its bounding box)
/// for which the deformation counts as small.
pub const DISPLACEMENT_LIMIT: f64 = 0.1;

/// Inverted cells named in a note at most.
const LISTED: usize = 10;

/// The small-deformation check of a displacement field; see the module documentation.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SmallDeformation {
    /// Largest strain norm `max_T ‖ε_T‖` over the cells (dimensionless).
    pub max_strain: f64,
    /// The cell where the largest strain is reached (the first, among equal ones).
    pub max_strain_cell: usize,
    /// The largest nodal displacement over the body's size, `max_v |u_v| / D`
    /// (dimensionless).
    pub max_displacement_ratio: f64,
    /// The body's size D (m): the diagonal of the mesh's bounding box.
    pub body_size: f64,
    /// Number of cells inverted by the displacement (signed measure of `x + u` ≤ 0).
    pub inverted_cells: usize,
    /// The first inverted cells, at most 10.
    pub inverted: Vec<usize>,
    /// The strain limit applied, [`STRAIN_LIMIT`].
    pub strain_limit: f64,
    /// The displacement limit applied, [`DISPLACEMENT_LIMIT`].
    pub displacement_limit: f64,
    /// The contact pairs whose bodies pass through each other in the deformed
    /// configuration: the deepest node of each pair and direction beyond the limit
    /// ([`crate::contact::interpenetration::deepest`]); empty without pairs.
    pub interpenetration: Vec<crate::contact::interpenetration::Interpenetration>,
}

impl SmallDeformation {
    /// The check of the displacement `u` (m, DOF order) on `mesh`, whose cell strains are
    /// `strains` (one per cell, as [`crate::assembly::BulkAssembler::cell_strains`] gives
    /// them), with the contact boundaries `contact` (their pairs checked for
    /// interpenetration).
    pub fn of(
        mesh: &Mesh,
        u: &[f64],
        strains: &[Sym],
        contact: &[crate::contact::ContactBoundary],
    ) -> Self {
        let d = mesh.dim();
        let (mut max_strain, mut max_strain_cell) = (0.0f64, 0);
        for (c, e) in strains.iter().enumerate() {
            let norm = e.norm();
            if norm > max_strain {
                (max_strain, max_strain_cell) = (norm, c);
            }
        }
        let (lo, hi) = mesh.bounding_box();
        let body_size = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
        let max_displacement = crate::assembly::norms::max_nodal_norm(u, d);
        let mut inverted = Vec::new();
        let mut inverted_cells = 0;
        for c in 0..mesh.n_cells() {
            let mut x = mesh.cell_coords(c);
            for (a, &v) in mesh.cell(c).iter().enumerate() {
                for k in 0..d {
                    x[a][k] += u[d * v as usize + k];
                }
            }
            // A NaN measure (a displacement that is not finite) is not counted.
            if simplex::signed_measure(d, &x) <= 0.0 {
                inverted_cells += 1;
                if inverted.len() < LISTED {
                    inverted.push(c);
                }
            }
        }
        SmallDeformation {
            max_strain,
            max_strain_cell,
            max_displacement_ratio: max_displacement / body_size,
            body_size,
            inverted_cells,
            inverted,
            strain_limit: STRAIN_LIMIT,
            displacement_limit: DISPLACEMENT_LIMIT,
            interpenetration: crate::contact::interpenetration::deepest(mesh, contact, u),
        }
    }

    /// Whether the deformation is small: both limits kept, no cell inverted.
    pub fn holds(&self) -> bool {
        self.notes().is_empty()
    }

    /// One note per limit exceeded and for the inverted cells, in words; empty when the
    /// deformation is small.
    pub fn notes(&self) -> Vec<String> {
        use crate::display::significant as s;
        let mut notes = Vec::new();
        let model = "the solution is that of the small-deformation (linearized) model, \
                     which does not describe the body at this size of deformation; reduce \
                     the loads or prescribed displacements (or check their units and the \
                     obstacle's position)";
        if self.max_strain > self.strain_limit {
            notes.push(format!(
                "small deformation: the largest strain ‖ε‖ = {} (cell {}) exceeds {}: {model}",
                s(self.max_strain),
                self.max_strain_cell,
                s(self.strain_limit)
            ));
        }
        if self.max_displacement_ratio > self.displacement_limit {
            notes.push(format!(
                "small deformation: the largest displacement, {} m, is {} times the body's \
                 size ({} m, the diagonal of its bounding box), above {}: {model}",
                s(self.max_displacement_ratio * self.body_size),
                s(self.max_displacement_ratio),
                s(self.body_size),
                s(self.displacement_limit)
            ));
        }
        if self.inverted_cells > 0 {
            let mut listed: Vec<String> =
                self.inverted.iter().map(|c| format!("cell {c}")).collect();
            if self.inverted_cells > listed.len() {
                listed.push(format!("{} more", self.inverted_cells - listed.len()));
            }
            notes.push(format!(
                "small deformation: the displacement turns {} cell(s) inside out ({}): their \
                 signed measure in the deformed configuration x + u is ≤ 0, which no \
                 deformation of a body does; {model}",
                self.inverted_cells,
                listed.join(", ")
            ));
        }
        notes.extend(self.interpenetration.iter().map(|i| i.note()));
        notes
    }
}
