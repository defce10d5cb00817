//! Norms of displacement fields.

use crate::assembly::element;
use crate::fem::simplex;
use crate::material::{Hooke, StrainEnergy};
use crate::mesh::Mesh;

/// Energy norm of SPEC §5, `‖v‖_E = (1/√2) (A ε(v), ε(v))^{1/2}_{L²}` with A the Hooke
/// operator `hooke`; since `W(ε) = ½ Aε:ε`, this is `(Σ_T |T| W(ε_T(v)))^{1/2}`.
/// `v` is in DOF order (length `d · n_nodes`).
pub fn energy_norm(mesh: &Mesh, hooke: &Hooke, v: &[f64]) -> f64 {
    let d = mesh.dim();
    let mut sum = 0.0;
    for c in 0..mesh.n_cells() {
        let geo = simplex::geometry(d, &mesh.cell_coords(c));
        let b = element::b_matrix(d, &geo);
        let mut ve = [0.0; 12];
        for (a, &n) in mesh.cell(c).iter().enumerate() {
            ve[d * a..d * a + d].copy_from_slice(&v[d * n as usize..d * n as usize + d]);
        }
        sum += geo.measure * hooke.energy(&element::strain(d, &b, &ve));
    }
    sum.max(0.0).sqrt()
}
