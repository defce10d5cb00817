//! The JSON summary of a solve, and the writer of all result files of a solution into a
//! [`ResultSet`].

use super::result_set::ResultSet;
use super::vtu::{pad_vector, VtuWriter};
use crate::assembly::BulkAssembler;
use crate::error::Result;
use crate::material::Locking;
use crate::norms::energy_norm;
use crate::problem::Problem;
use crate::solver::{Solution, SolveReport};
use crate::tensor::von_mises;
use serde::Serialize;
use std::path::PathBuf;

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
    /// Energy norm `‖u‖_E` of the paper's example (√J).
    pub energy_norm: f64,
    /// Largest displacement magnitude over the nodes (m).
    pub max_displacement: f64,
    /// Sum of the reaction forces (N).
    pub total_reaction: Vec<f64>,
    /// Number of contact points.
    pub contact_points: usize,
    /// Number of contact points in contact (normal state `contact`: positive pressure).
    pub contact_active: usize,
    /// Number of sticking contact points (friction state `stick`).
    pub contact_stick: usize,
    /// Number of slipping contact points (friction state `slip`).
    pub contact_slip: usize,
    /// Number of cells where the locking penalty acts (Q(ε) > 0).
    pub locked_cells: usize,
    /// Largest |tr ε| over the cells.
    pub max_abs_trace_strain: f64,
    /// The uniqueness condition of the paper's Theorem 4,
    /// `(μ₀ α_j + c_j L_μ) ‖γ‖² < m_A`, as [`crate::solver::uniqueness::evaluate`] gives it:
    /// evaluated for contact with Tresca-type bounds (`applies`, `holds`, `margin`), or
    /// `applies: false` with the reason in `note`.
    pub uniqueness: crate::solver::uniqueness::Uniqueness,
    /// Notes raised while resolving the scenario (see
    /// [`crate::scenario::Scenario::into_problem_with_notes`]); empty from [`Summary::new`].
    pub notes: Vec<String>,
    /// The solver report (iterations, residuals, timings).
    pub report: SolveReport,
    /// The names of the files of this summary's result folder, `summary.json` included:
    /// the folder holds exactly these (filled in by [`write_results`]; empty from
    /// [`Summary::new`]).
    pub files: Vec<String>,
}

impl Summary {
    /// Builds the summary of `solution`. Evaluating the uniqueness condition may cost one
    /// Cholesky factorization of the ε–ε stiffness and a power iteration (see
    /// [`crate::solver::uniqueness::evaluate`]).
    pub fn new(
        problem: &Problem,
        solution: &Solution,
        title: Option<String>,
        scenario: &str,
    ) -> Self {
        let mesh = &problem.mesh;
        let d = mesh.dim();
        let max_displacement = crate::norms::max_nodal_norm(&solution.u, d);
        let mut total_reaction = vec![0.0; d];
        for (k, r) in solution.reactions.iter().enumerate() {
            total_reaction[k % d] += r;
        }
        let h = &problem.material.elasticity.small_strain_hooke(d);
        let strains = BulkAssembler::new(mesh, &problem.material).cell_strains(&solution.u);
        let locked_cells = if problem.material.locking.ideal().is_some() {
            solution
                .locking_multiplier
                .iter()
                .filter(|&&l| l > 0.0)
                .count()
        } else {
            strains
                .iter()
                .filter(|e| problem.material.locking.is_penalty_active(e))
                .count()
        };
        let max_abs_trace_strain = strains.iter().map(|e| e.trace().abs()).fold(0.0, f64::max);
        let cert = &solution.report.certificate;
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
            contact_points: solution.contact.len(),
            contact_active: cert.n_contact,
            contact_stick: cert.n_stick,
            contact_slip: cert.n_slip,
            locked_cells,
            max_abs_trace_strain,
            uniqueness: crate::solver::uniqueness::evaluate(problem),
            notes: Vec::new(),
            report: solution.report.clone(),
            files: Vec::new(),
        }
    }
}

/// Writes the result files of a solution into the sub-folder `folder` of the result set
/// `set` (`""`: its root): `solution.vtu` (if `vtu`), `contact.csv` (if the problem has
/// contact), the `extra` files (name within the folder, content), and last, if `summary` is
/// given, `summary.json`, whose `files` lists every file of the folder, itself included.
/// Returns the final paths written.
///
/// # Errors
/// [`crate::Error::Io`] if a file cannot be written.
pub fn write_results(
    set: &mut ResultSet,
    folder: &str,
    problem: &Problem,
    solution: &Solution,
    summary: Option<&Summary>,
    vtu: bool,
    extra: &[(&str, Vec<u8>)],
) -> Result<Vec<PathBuf>> {
    let name = |file: &str| {
        if folder.is_empty() {
            file.to_string()
        } else {
            format!("{}/{file}", folder.trim_end_matches('/'))
        }
    };
    let mut written = Vec::new();
    if vtu {
        written.push(set.write(
            &name("solution.vtu"),
            &solution_vtu(problem, solution).to_bytes(),
        )?);
    }
    if !problem.contact.is_empty() {
        written.push(set.write(
            &name("contact.csv"),
            contact_csv(problem, solution).as_bytes(),
        )?);
    }
    for (file, bytes) in extra {
        written.push(set.write(&name(file), bytes)?);
    }
    if let Some(summary) = summary {
        let mut summary = summary.clone();
        summary.files = set.files_in(folder);
        summary.files.push(SUMMARY_FILE.to_string());
        summary.files.dedup();
        let text = serde_json::to_string_pretty(&summary)
            .map_err(|e| crate::Error::Breakdown(format!("summary serialization: {e}")))?;
        written.push(set.write(&name(SUMMARY_FILE), text.as_bytes())?);
    }
    Ok(written)
}

/// The name of the summary file of a result folder.
pub const SUMMARY_FILE: &str = "summary.json";

/// The `.vtu` content of a solution: displacement, reactions and contact data at points;
/// strain, stress, von Mises stress, tr ε and locking activity per cell.
///
/// `stress` is the full 3×3 tensor ([`crate::material::Material::stress_3x3`]): in 2D plane
/// strain with `σ_zz = ∂W/∂ε_zz` (Hooke: `λ tr ε`) plus the zz part of the locking stress,
/// in plane stress with `σ_zz = 0`; `von_mises` is `√(3/2 s:s)` of its 3D deviator s
/// ([`crate::tensor::von_mises`]). `strain` is the strain of the model: in 2D its
/// out-of-plane components are written as 0 (exact in plane strain; in plane stress the
/// thickness strain ε_zz is not computed).
///
/// Contact point data (for nodes that are not contact nodes: states −1, zeros elsewhere):
/// `contact_state` (the normal state: 0 separated, 1 contact), `friction_state` (0 none,
/// 1 stick, 2 slip), `contact_pressure`, `slip`,
/// `interface_force` (the force of the foundation on the node, N), and the contact
/// multipliers `contact_multiplier` (the pressure p = −σ_ν, for Signorini the multiplier of
/// `u_ν ≤ g`) and `friction_traction` (−σ_τ, global coordinates). Where a node is several
/// contact points (on two contact boundaries, or at a corner of one), the last point's
/// values are shown and the forces are summed.
/// Cell data: `locking_active` is 1 where the locking constraint acts (nearly locking:
/// `Q(ε) > 0`; ideal locking: multiplier > 0), `locking_q` is Q(ε), `locking_multiplier`
/// the magnitude λ_T of the locking stress `λ_T ∂Q` (ideal locking: the multiplier; nearly
/// locking: its penalty approximation `C_κ Q_+`). The stress includes the locking stress.
pub fn solution_vtu<'a>(problem: &'a Problem, solution: &Solution) -> VtuWriter<'a> {
    let mesh = &problem.mesh;
    let d = mesh.dim();
    let bulk = BulkAssembler::new(mesh, &problem.material);
    let strains = bulk.cell_strains(&solution.u);
    let n_cells = strains.len();
    let mut eps9 = Vec::with_capacity(9 * n_cells);
    let mut sig9 = Vec::with_capacity(9 * n_cells);
    let mut vm = Vec::with_capacity(n_cells);
    let mut tr = Vec::with_capacity(n_cells);
    let mut active = Vec::with_capacity(n_cells);
    let mut q = Vec::with_capacity(n_cells);
    let mut multiplier = Vec::with_capacity(n_cells);
    let locking = &problem.material.locking;
    let set = locking.set();
    for (c, e) in strains.iter().enumerate() {
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
        let s = problem
            .material
            .stress_3x3(e, problem.plane, ideal_multiplier);
        eps9.extend(e.to_matrix().iter().flatten());
        sig9.extend(s.iter().flatten());
        vm.push(von_mises(&s));
        tr.push(e.trace());
        active.push(i32::from(act));
        multiplier.push(if lambda.is_finite() { lambda } else { 0.0 });
        let qv = set.map_or(0.0, |set| set.q(e));
        q.push(if qv.is_finite() { qv } else { 0.0 });
    }
    let n = mesh.n_nodes();
    let mut normal_state = vec![-1i32; n];
    let mut friction_state = vec![-1i32; n];
    let mut pressure = vec![0.0; n];
    let mut slip = vec![0.0; n];
    let mut force = vec![0.0; 3 * n];
    let mut traction = vec![0.0; 3 * n];
    for c in &solution.contact {
        let v = c.node as usize;
        normal_state[v] = c.normal_state.code();
        friction_state[v] = c.friction_state.code();
        pressure[v] = c.pressure;
        slip[v] = c.slip;
        for k in 0..3 {
            force[3 * v + k] += c.force[k];
            traction[3 * v + k] = c.friction_traction[k];
        }
    }
    let mut w = VtuWriter::new(mesh);
    w.point_f64("displacement", 3, pad_vector(d, &solution.u))
        .point_f64("reaction", 3, pad_vector(d, &solution.reactions))
        .point_i32("contact_state", normal_state)
        .point_i32("friction_state", friction_state)
        .point_f64("contact_pressure", 1, pressure.clone())
        .point_f64("contact_multiplier", 1, pressure)
        .point_f64("friction_traction", 3, traction)
        .point_f64("slip", 1, slip)
        .point_f64("interface_force", 3, force)
        .cell_f64("strain", 9, eps9)
        .cell_f64("stress", 9, sig9)
        .cell_f64("von_mises", 1, vm)
        .cell_f64("trace_strain", 1, tr)
        .cell_i32("locking_active", active)
        .cell_f64("locking_q", 1, q)
        .cell_f64("locking_multiplier", 1, multiplier);
    w
}

/// The contact-node table: one row per contact point, comma-separated, with a header.
///
/// Columns: node, boundary (part name), x, y, z, weight, u_nu, gap, u_tau_1, u_tau_2, slip,
/// pressure, bound, force_normal, force_tangential_1, force_tangential_2, normal_state
/// (separated/contact), friction_state (none/stick/slip), normal_residual,
/// friction_residual.
pub fn contact_csv(problem: &Problem, solution: &Solution) -> String {
    let mesh = &problem.mesh;
    let mut out = String::from(
        "node,boundary,x,y,z,weight,u_nu,gap,u_tau_1,u_tau_2,slip,pressure,bound,\
         force_normal,force_tangential_1,force_tangential_2,normal_state,friction_state,normal_residual,friction_residual\n",
    );
    for c in &solution.contact {
        let x = mesh.node(c.node as usize);
        let xyz: Vec<f64> = (0..3).map(|i| x.get(i).copied().unwrap_or(0.0)).collect();
        let part = &mesh.part_names()[problem.contact[c.boundary].part];
        out.push_str(&format!(
            "{},{},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{},{},{:e},{:e}\n",
            c.node,
            part,
            xyz[0],
            xyz[1],
            xyz[2],
            c.weight,
            c.u_nu,
            c.gap,
            c.u_tau[0],
            c.u_tau[1],
            c.slip,
            c.pressure,
            c.bound,
            c.force_normal,
            c.force_tangential[0],
            c.force_tangential[1],
            c.normal_state.name(),
            c.friction_state.name(),
            c.normal_residual,
            c.friction_residual
        ));
    }
    out
}
