//! Consistent nodal loads for constant data (exact integration of P1 hat functions).
//!
//! A constant body force `f_0` on a cell T gives `f_0 |T| / (d+1)` to each vertex; a constant
//! traction `f_N` on a boundary facet F gives `f_N |F| / d` to each of its vertices (since
//! `∫_T φ_a = |T|/(d+1)` and `∫_F φ_a = |F|/d`). [`Problem::external_forces`] sums them
//! over the problem's body force and tractions. (Also at [`crate::assembly::loads`].)

use super::Problem;
use crate::mesh::Mesh;

/// Adds the consistent load of a constant body force `f0` (N/m³; length ≥ d) to `f`
/// (length `d · n_nodes`, DOF order).
pub fn add_body_force(mesh: &Mesh, f0: &[f64], f: &mut [f64]) {
    let d = mesh.dim();
    for c in 0..mesh.n_cells() {
        let w = crate::geometry::simplex::signed_measure(d, &mesh.cell_coords(c)) / (d + 1) as f64;
        for &v in mesh.cell(c) {
            for i in 0..d {
                f[d * v as usize + i] += w * f0[i];
            }
        }
    }
}

/// Adds the consistent load of a constant traction `t` (N/m²; length ≥ d) on the facets of
/// boundary part `part` to `f` (length `d · n_nodes`, DOF order).
pub fn add_traction(mesh: &Mesh, part: usize, t: &[f64], f: &mut [f64]) {
    let d = mesh.dim();
    for facet in mesh.part_facets(part) {
        let (measure, _) = mesh.facet_measure_normal(facet);
        let w = measure / d as f64;
        for &v in mesh.facet(facet) {
            for i in 0..d {
                f[d * v as usize + i] += w * t[i];
            }
        }
    }
}

impl Problem {
    /// The consistent external force vector `f` (DOF order, length `d · n_nodes`).
    pub fn external_forces(&self) -> Vec<f64> {
        let d = self.mesh.dim();
        let mut f = vec![0.0; d * self.mesh.n_nodes()];
        if self.body_force.iter().any(|&x| x != 0.0) {
            add_body_force(&self.mesh, &self.body_force, &mut f);
        }
        for t in &self.tractions {
            add_traction(&self.mesh, t.part, &t.value, &mut f);
        }
        f
    }
}
