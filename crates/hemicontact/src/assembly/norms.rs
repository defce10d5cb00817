//! Norms of displacement fields: the energy norm (a sum of the element kernels' strain
//! energies over the cells) and the largest nodal displacement.

use super::element;
use crate::material::{Hooke, StrainEnergy};
use crate::mesh::Mesh;

/// Energy norm of the paper's example, `‖v‖_E = (1/√2) (A ε(v), ε(v))^{1/2}_{L²}` with A
/// the Hooke operator `hooke`; since `W(ε) = ½ Aε:ε`, this is `(Σ_T |T| W(ε_T(v)))^{1/2}`.
/// `v` is in DOF order (length `d · n_nodes`).
///
/// The norm is homogeneous, `‖s v‖_E = s ‖v‖_E`, and is computed as such with `s` the
/// power of two at or above `max|v_k|` (an exact scaling: the result is bit-identical to the
/// unscaled sum wherever that does not overflow or underflow), so that it neither overflows
/// nor underflows for displacements and moduli anywhere in the range of double precision
/// (the square of a displacement of 1e-200 m, or of 1e200 m, would).
pub fn energy_norm(mesh: &Mesh, hooke: &Hooke, v: &[f64]) -> f64 {
    energy_norm_by_cell(mesh, &|_| *hooke, v)
}

/// [`energy_norm`] with the Hooke operator `hooke(c)` in cell `c` (a body of several
/// materials): `(Σ_T |T| W_T(ε_T(v)))^{1/2}`.
pub fn energy_norm_by_cell(mesh: &Mesh, hooke: &dyn Fn(usize) -> Hooke, v: &[f64]) -> f64 {
    let s = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if s == 0.0 || !s.is_finite() {
        return if s == 0.0 { 0.0 } else { f64::INFINITY };
    }
    let s = s.log2().ceil().min(1023.0).exp2();
    // ε(v/s) = ε(v)/s exactly: s is a power of two.
    let sum: f64 = (0..mesh.n_cells())
        .map(|c| {
            let (measure, eps) = element::cell_strain(mesh, v, c);
            measure * hooke(c).energy(&eps.scaled(1.0 / s))
        })
        .sum();
    s * sum.max(0.0).sqrt()
}

/// Largest Euclidean norm of the `d`-vectors of `v` (DOF order: the largest nodal
/// displacement), computed without overflow or underflow of the squares.
pub fn max_nodal_norm(v: &[f64], d: usize) -> f64 {
    let s = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if s == 0.0 || !s.is_finite() {
        return s;
    }
    s * v
        .chunks(d)
        .map(|c| c.iter().map(|x| (x / s) * (x / s)).sum::<f64>().sqrt())
        .fold(0.0, f64::max)
}
