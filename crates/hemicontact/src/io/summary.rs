//! The JSON summary of a solve (`summary.json`): sizes, energies, contact and locking
//! counts, the uniqueness condition, the solver report and the files of its result folder.

use crate::assembly::norms::energy_norm_by_cell;
use crate::assembly::BulkAssembler;
use crate::material::StrainEnergy;
use crate::problem::Problem;
use crate::solver::{Solution, SolveReport};
use serde::Serialize;

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

/// One material of a body of several materials in `summary.json`.
#[derive(Clone, Debug, Serialize)]
pub struct MaterialSummary {
    /// The cell regions it fills (their names in the mesh).
    pub parts: Vec<String>,
    /// Lamé constants (λ, G) of its elasticity law (Pa; of its small-strain Hooke law for
    /// Hencky's).
    pub lame: [f64; 2],
    /// Number of its cells.
    pub cells: usize,
    /// Its volume (m³; area in m² in 2D).
    pub volume: f64,
    /// Stored energy of its cells `Σ_T |T| (W + Ψ)(ε_T)` at the solution (J; J/m in 2D),
    /// without the ideal-locking term.
    pub strain_energy: f64,
}

impl MaterialSummary {
    /// The materials of `problem` with the cell strains `strains` of the solution; empty
    /// for a problem of one material.
    fn of(problem: &Problem, strains: &[crate::tensor::Sym]) -> Vec<MaterialSummary> {
        if problem.region_material.is_empty() {
            return Vec::new();
        }
        let mesh = &problem.mesh;
        let d = mesh.dim();
        let mut out: Vec<MaterialSummary> = problem
            .materials
            .iter()
            .map(|m| {
                let h = m.elasticity.small_strain_hooke(d);
                MaterialSummary {
                    parts: Vec::new(),
                    lame: [h.lambda, h.mu],
                    cells: 0,
                    volume: 0.0,
                    strain_energy: 0.0,
                }
            })
            .collect();
        for (r, &k) in problem.region_material.iter().enumerate() {
            let name = mesh.region_names().get(r).cloned().unwrap_or_default();
            out[k as usize].parts.push(name);
        }
        for (c, eps) in strains.iter().enumerate() {
            let k = problem.cell_material(c);
            let measure = crate::geometry::simplex::geometry(d, &mesh.cell_coords(c)).measure;
            let m = &mut out[k];
            m.cells += 1;
            m.volume += measure;
            m.strain_energy += measure * problem.materials[k].energy(eps);
        }
        out
    }
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
    /// Lamé constants (λ, G) of the elasticity law (Pa; of its small-strain Hooke law for
    /// Hencky's); `null` for a body of several materials (see `materials`).
    pub lame: Option<[f64; 2]>,
    /// Each material of a body of several materials, with the cells it fills and their
    /// share of the energy (absent for one material).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub materials: Vec<MaterialSummary>,
    /// Energy of the last convex problem at the solution (J; J/m in 2D): the total
    /// potential energy when the problem is a single convex problem (no slip-dependent or
    /// Coulomb friction, no exact constraints), else its convexified energy with the frozen
    /// friction data and multipliers of the last outer iteration.
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
    /// Totals over each contact boundary, in the order of the scenario's `[[contact]]`
    /// entries: resultant interface force, counts, contact length or area, peak pressure
    /// ([`super::contact_totals::contact_totals`]).
    pub contact_totals: Vec<super::contact_totals::ContactTotals>,
    /// The forces on each body of the mesh (its connected components, by smallest node):
    /// loads, reactions and interface forces, and their balance ([`super::bodies`]).
    pub bodies: Vec<super::bodies::BodySummary>,
    /// Number of cells where the locking penalty acts (Q(ε) > 0).
    pub locked_cells: usize,
    /// Largest |tr ε| over the cells.
    pub max_abs_trace_strain: f64,
    /// The uniqueness condition of the paper's Theorem 4,
    /// `(μ₀ α_j + c_j L_μ) ‖γ‖² < m_A`, as [`crate::solver::uniqueness::evaluate`] gives it:
    /// evaluated for contact with Tresca-type bounds (`applies`, `holds`, `margin`), or
    /// `applies: false` with the reason in `note`.
    pub uniqueness: crate::solver::uniqueness::Uniqueness,
    /// The small-deformation check of the solution
    /// ([`crate::small_deformation::SmallDeformation`]): largest strain, largest
    /// displacement over the body's size, inverted cells, and the limits.
    pub small_deformation: crate::small_deformation::SmallDeformation,
    /// Notes: those raised while resolving the scenario (see
    /// [`crate::scenario::Scenario::into_problem_with_notes`]; added by
    /// [`Summary::prepend_notes`]), then those of the solution (the small-deformation check,
    /// [`crate::small_deformation::SmallDeformation::notes`]; the only ones from
    /// [`Summary::new`]).
    pub notes: Vec<String>,
    /// The solver report (iterations, residuals, timings).
    pub report: SolveReport,
    /// The names of the files of this summary's result folder, `summary.json` included:
    /// the folder holds exactly these (filled in by [`super::results::write_results`]; empty from
    /// [`Summary::new`]).
    pub files: Vec<String>,
}

impl Summary {
    /// Builds the summary of `solution` of `problem` solved with `settings`. Evaluating the uniqueness condition may cost one
    /// Cholesky factorization of the ε–ε stiffness and a power iteration (see
    /// [`crate::solver::uniqueness::evaluate`]).
    pub fn new(
        problem: &Problem,
        settings: &crate::solver::SolverSettings,
        solution: &Solution,
        title: Option<String>,
        scenario: &str,
    ) -> Self {
        let mesh = &problem.mesh;
        let d = mesh.dim();
        let max_displacement = crate::assembly::norms::max_nodal_norm(&solution.u, d);
        let mut total_reaction = vec![0.0; d];
        for (k, r) in solution.reactions.iter().enumerate() {
            total_reaction[k % d] += r;
        }
        let hooke: Vec<_> = problem
            .materials
            .iter()
            .map(|m| m.elasticity.small_strain_hooke(d))
            .collect();
        let bulk = BulkAssembler::of(problem, mesh);
        let strains = bulk.cell_strains(&solution.u);
        // Ideal locking acts where the multiplier is positive, nearly locking where Q > 0.
        let locked_cells = strains
            .iter()
            .enumerate()
            .filter(|&(c, e)| match bulk.material(c).locking.ideal() {
                Some(_) => solution.locking_multiplier.get(c).is_some_and(|&l| l > 0.0),
                None => bulk.material(c).locking.is_penalty_active(e),
            })
            .count();
        let max_abs_trace_strain = strains.iter().map(|e| e.trace().abs()).fold(0.0, f64::max);
        let small_deformation = crate::small_deformation::SmallDeformation::of(
            mesh,
            &solution.u,
            &strains,
            &problem.contact,
        );
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
            lame: (hooke.len() == 1).then(|| [hooke[0].lambda, hooke[0].mu]),
            materials: MaterialSummary::of(problem, &strains),
            energy: solution.energy,
            energy_norm: energy_norm_by_cell(
                mesh,
                &|c| hooke[problem.cell_material(c)],
                &solution.u,
            ),
            max_displacement,
            total_reaction,
            contact_points: solution.contact.len(),
            contact_active: cert.n_contact,
            contact_stick: cert.n_stick,
            contact_slip: cert.n_slip,
            contact_totals: super::contact_totals::contact_totals(problem, &solution.contact),
            bodies: super::bodies::bodies(problem, solution),
            locked_cells,
            max_abs_trace_strain,
            uniqueness: crate::solver::uniqueness::evaluate(problem, settings),
            notes: small_deformation.notes(),
            small_deformation,
            report: solution.report.clone(),
            files: Vec::new(),
        }
    }
}

impl Summary {
    /// Puts `notes` (those of the scenario) before the notes of the solution.
    pub fn prepend_notes(&mut self, notes: Vec<String>) {
        self.notes.splice(0..0, notes);
    }
}

/// The name of the summary file of a result folder.
pub const SUMMARY_FILE: &str = "summary.json";
