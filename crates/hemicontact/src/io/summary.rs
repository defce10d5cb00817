//! The JSON summary of a solve, and the writer of all result files of a solution.

use super::vtu::{pad_vector, VtuWriter};
use crate::assembly::BulkAssembler;
use crate::error::Result;
use crate::material::StrainEnergy;
use crate::norms::energy_norm;
use crate::problem::Problem;
use crate::solver::{Solution, SolveReport};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Sizes of the discrete problem.
#[derive(Clone, Debug, Serialize)]
pub struct Sizes {
    /// Spatial dimension.
    pub dim: usize,
    /// Number of nodes.
    pub nodes: usize,
    /// Number of cells.
    pub cells: usize,
    /// Number of DOFs (d · nodes).
    pub dofs: usize,
    /// Number of free DOFs (equations).
    pub equations: usize,
}

/// The summary written to `summary.json`.
#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    /// Program version.
    pub version: String,
    /// Scenario title, if any.
    pub title: Option<String>,
    /// Scenario source (file path or built-in name).
    pub scenario: String,
    /// Whether the solve converged.
    pub converged: bool,
    /// Problem sizes.
    pub sizes: Sizes,
    /// Lamé constants (λ, G) of the elasticity law (Pa).
    pub lame: [f64; 2],
    /// Total potential energy at the solution (J).
    pub energy: f64,
    /// Energy norm `‖u‖_E` of SPEC §5 (√J).
    pub energy_norm: f64,
    /// Largest displacement magnitude over the nodes (m).
    pub max_displacement: f64,
    /// Sum of the reaction forces (N).
    pub total_reaction: Vec<f64>,
    /// The solver report (iterations, residuals, timings).
    pub report: SolveReport,
}

impl Summary {
    /// Builds the summary of `solution`.
    pub fn new(
        problem: &Problem,
        solution: &Solution,
        title: Option<String>,
        scenario: &str,
    ) -> Self {
        let mesh = &problem.mesh;
        let d = mesh.dim();
        let max_displacement = solution
            .u
            .chunks(d)
            .map(|c| c.iter().map(|x| x * x).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        let mut total_reaction = vec![0.0; d];
        for (k, r) in solution.reactions.iter().enumerate() {
            total_reaction[k % d] += r;
        }
        let h = &problem.material.elasticity;
        Summary {
            version: env!("CARGO_PKG_VERSION").to_string(),
            title,
            scenario: scenario.to_string(),
            converged: solution.report.converged,
            sizes: Sizes {
                dim: d,
                nodes: mesh.n_nodes(),
                cells: mesh.n_cells(),
                dofs: solution.report.n_dofs,
                equations: solution.report.n_equations,
            },
            lame: [h.lambda, h.mu],
            energy: solution.energy,
            energy_norm: energy_norm(mesh, h, &solution.u),
            max_displacement,
            total_reaction,
            report: solution.report.clone(),
        }
    }
}

/// Writes `solution.vtu` (if `vtu`) and `summary.json` (if `summary`) into `dir`, which
/// must exist. Returns the paths written.
///
/// # Errors
/// [`crate::Error::Io`] if a file cannot be written.
pub fn write_results(
    dir: &Path,
    problem: &Problem,
    solution: &Solution,
    summary: &Summary,
    vtu: bool,
    json: bool,
) -> Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    if vtu {
        let path = dir.join("solution.vtu");
        solution_vtu(problem, solution).write(&path)?;
        written.push(path);
    }
    if json {
        let path = dir.join("summary.json");
        let text = serde_json::to_string_pretty(summary)
            .map_err(|e| crate::Error::Breakdown(format!("summary serialization: {e}")))?;
        super::atomic::write(&path, text.as_bytes())?;
        written.push(path);
    }
    Ok(written)
}

/// The `.vtu` content of a solution: displacement and reactions at points; strain, stress,
/// von Mises stress and tr ε per cell.
pub fn solution_vtu<'a>(problem: &'a Problem, solution: &Solution) -> VtuWriter<'a> {
    let mesh = &problem.mesh;
    let d = mesh.dim();
    let bulk = BulkAssembler {
        mesh,
        material: &problem.material,
    };
    let strains = bulk.cell_strains(&solution.u);
    let mut eps9 = Vec::with_capacity(9 * strains.len());
    let mut sig9 = Vec::with_capacity(9 * strains.len());
    let mut vm = Vec::with_capacity(strains.len());
    let mut tr = Vec::with_capacity(strains.len());
    for e in &strains {
        let s = problem.material.stress(e);
        eps9.extend(e.to_matrix().iter().flatten());
        sig9.extend(s.to_matrix().iter().flatten());
        vm.push(s.von_mises());
        tr.push(e.trace());
    }
    let mut w = VtuWriter::new(mesh);
    w.point_f64("displacement", 3, pad_vector(d, &solution.u))
        .point_f64("reaction", 3, pad_vector(d, &solution.reactions))
        .cell_f64("strain", 9, eps9)
        .cell_f64("stress", 9, sig9)
        .cell_f64("von_mises", 1, vm)
        .cell_f64("trace_strain", 1, tr);
    w
}
