//! The fields of a solution on the cells, computed once for every output that shows them:
//! the VTU writer and the figures (`ε_T`, `σ_T = ∂W/∂ε(ε_T)` plus the locking stress, von
//! Mises, `tr ε_T` and the locking state of each cell T).

use crate::assembly::BulkAssembler;
use crate::material::Locking;
use crate::problem::Problem;
use crate::solver::Solution;
use crate::tensor::von_mises;

/// The cell data of a solution: strain and stress tensors (3 × 3, row-major; the stress
/// includes the locking stress), von Mises stress, trace of the strain, and the locking
/// state; written to `solution.vtu` by [`crate::io::vtu::solution_vtu`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CellFields {
    /// Strain ε per cell, 9 entries (dimensionless).
    pub strain: Vec<f64>,
    /// Stress σ per cell, 9 entries (Pa).
    pub stress: Vec<f64>,
    /// von Mises stress `√(3/2 σ^D : σ^D)` per cell (Pa).
    pub von_mises: Vec<f64>,
    /// `tr ε` per cell.
    pub trace_strain: Vec<f64>,
    /// 1 where the locking constraint acts, else 0.
    pub locking_active: Vec<i32>,
    /// Q(ε) of the locking set per cell (0 without locking).
    pub locking_q: Vec<f64>,
    /// Magnitude λ_T of the locking stress per cell (Pa).
    pub locking_multiplier: Vec<f64>,
    /// The index of each cell's material in [`Problem::materials`] (all 0 for one
    /// material).
    pub material: Vec<i32>,
}

/// The cell data of `solution`; see [`CellFields`].
pub fn cell_fields(problem: &Problem, solution: &Solution) -> CellFields {
    let mesh = &problem.mesh;
    let bulk = BulkAssembler::of(problem, mesh);
    let strains = bulk.cell_strains(&solution.u);
    let n_cells = strains.len();
    let mut eps9 = Vec::with_capacity(9 * n_cells);
    let mut sig9 = Vec::with_capacity(9 * n_cells);
    let mut vm = Vec::with_capacity(n_cells);
    let mut tr = Vec::with_capacity(n_cells);
    let mut active = Vec::with_capacity(n_cells);
    let mut q = Vec::with_capacity(n_cells);
    let mut multiplier = Vec::with_capacity(n_cells);
    let mut material = Vec::with_capacity(n_cells);
    for (c, e) in strains.iter().enumerate() {
        let law = bulk.material(c);
        let locking = &law.locking;
        let set = locking.set();
        let (act, lambda) = match locking {
            Locking::Ideal(_) => {
                let l = solution.locking_multiplier.get(c).copied().unwrap_or(0.0);
                (l > 0.0, l)
            }
            Locking::Penalty(p) => (p.is_active(e), p.c_kappa * p.set.q(e).max(0.0)),
            Locking::None => (false, 0.0),
        };
        let ideal_multiplier = if locking.ideal().is_some() {
            lambda
        } else {
            0.0
        };
        let s = law.stress_3x3(e, problem.plane, ideal_multiplier);
        material.push(problem.cell_material(c) as i32);
        eps9.extend(e.to_matrix().iter().flatten());
        sig9.extend(s.iter().flatten());
        vm.push(von_mises(&s));
        tr.push(e.trace());
        active.push(i32::from(act));
        multiplier.push(if lambda.is_finite() { lambda } else { 0.0 });
        let qv = set.map_or(0.0, |set| set.q(e));
        q.push(if qv.is_finite() { qv } else { 0.0 });
    }
    CellFields {
        strain: eps9,
        stress: sig9,
        von_mises: vm,
        trace_strain: tr,
        locking_active: active,
        locking_q: q,
        locking_multiplier: multiplier,
        material,
    }
}
