//! Norms of displacement fields.

use crate::assembly::element;
use crate::material::{Hooke, StrainEnergy};
use crate::mesh::Mesh;

/// Energy norm of SPEC §5, `‖v‖_E = (1/√2) (A ε(v), ε(v))^{1/2}_{L²}` with A the Hooke
/// operator `hooke`; since `W(ε) = ½ Aε:ε`, this is `(Σ_T |T| W(ε_T(v)))^{1/2}`.
/// `v` is in DOF order (length `d · n_nodes`).
pub fn energy_norm(mesh: &Mesh, hooke: &Hooke, v: &[f64]) -> f64 {
    let sum: f64 = (0..mesh.n_cells())
        .map(|c| {
            let (measure, eps) = element::cell_strain(mesh, v, c);
            measure * hooke.energy(&eps)
        })
        .sum();
    sum.max(0.0).sqrt()
}
