//! Solves and their results: the displacement, cell fields, contact table and summary of a
//! solution, and its result files, as `hemicontact solve` writes them.

use crate::errors::to_py;
use crate::interrupt;
use crate::mesh::{f64_bytes, i64_bytes};
use crate::scenario::NativeScenario;
use hemicontact::fields::cell_fields;
use hemicontact::io::result_set::ResultSet;
use hemicontact::io::results::{solution_figures, write_results};
use hemicontact::io::summary::Summary;
use hemicontact::io::vtu::solution_vtu;
use hemicontact::problem::Problem;
use hemicontact::scenario::schema::OutputSpec;
use hemicontact::solver::{solve_interruptible, Solution};
use hemicontact::study::{self, StudySettings};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use std::path::PathBuf;

/// A solution with its problem and summary.
#[pyclass(module = "hemicontact._core", name = "Solution", frozen)]
pub struct NativeSolution {
    problem: Problem,
    solution: Solution,
    summary: Summary,
    title: String,
    output: OutputSpec,
    /// The load factor of the solve (1 for a plain solve; the step's for a load path).
    load_factor: f64,
    /// The notes that question the input or the result, raised as warnings in Python: an
    /// obstacle the mesh does not resolve, a deformation too large for the model.
    flagged: Vec<String>,
}

/// The notes of a solve that Python raises as warnings: those on the obstacles of the
/// (unscaled) problem `problem`, then those of the small-deformation check in `summary`.
fn flagged_notes(problem: &Problem, summary: &Summary) -> Vec<String> {
    let mut notes = problem.obstacle_notes();
    notes.extend(summary.small_deformation.notes());
    notes
}

/// Solves the scenario (GIL released, Ctrl-C honoured). A solve that does not converge
/// returns its last iterate, marked `converged == False`. With `[loading]`, solves the
/// load path and returns its last step solved.
#[pyfunction]
pub fn solve(py: Python<'_>, scenario: &NativeScenario) -> PyResult<NativeSolution> {
    let s = &scenario.inner;
    if s.load_factors().map_err(|e| scenario.error(e))?.is_some() {
        return load_path(py, scenario)?.pop().ok_or_else(|| {
            pyo3::exceptions::PyRuntimeError::new_err("internal error: a load path without steps")
        });
    }
    let (problem, notes, settings) = py
        .detach(|| {
            let settings = s.settings()?;
            let (problem, notes) = s.into_problem_with_notes()?;
            Ok::<_, hemicontact::Error>((problem, notes, settings))
        })
        .map_err(|e| scenario.error(e))?;
    let solution = interrupt::run(py, |stop| {
        solve_interruptible(&problem, &settings, problem.initial_displacement(), stop)
    })?
    .map_err(|e| scenario.error(e))?;
    let mut summary = Summary::new(
        &problem,
        &settings,
        &solution,
        s.file.title.clone(),
        &s.source,
    );
    let flagged = flagged_notes(&problem, &summary);
    summary.prepend_notes(notes);
    Ok(NativeSolution {
        title: s
            .file
            .title
            .clone()
            .unwrap_or_else(|| "scenario".to_string()),
        output: s.output().clone(),
        problem,
        solution,
        summary,
        load_factor: 1.0,
        flagged,
    })
}

/// Solves the scenario along its `[loading]` path (a plain solve at load factor 1 without
/// one; GIL released, Ctrl-C honoured): each step warm-started from the last, stopping
/// after the first step that does not converge. Returns the steps solved, in order.
#[pyfunction]
pub fn load_path(py: Python<'_>, scenario: &NativeScenario) -> PyResult<Vec<NativeSolution>> {
    let s = &scenario.inner;
    let (problem, notes, settings, factors) = py
        .detach(|| {
            let settings = s.settings()?;
            let factors = s.load_factors()?.unwrap_or_else(|| vec![1.0]);
            let (problem, notes) = s.into_problem_with_notes()?;
            Ok::<_, hemicontact::Error>((problem, notes, settings, factors))
        })
        .map_err(|e| scenario.error(e))?;
    let steps = interrupt::run(py, |stop| {
        hemicontact::loading::load_path(
            &problem,
            &settings,
            &factors,
            stop,
            &|_, _| {},
            &mut |_| Ok(()),
        )
    })?
    .map_err(|e| scenario.error(e))?;
    let title = s
        .file
        .title
        .clone()
        .unwrap_or_else(|| "scenario".to_string());
    let obstacle_notes = problem.obstacle_notes();
    Ok(steps
        .into_iter()
        .map(|step| {
            let mut summary = Summary::new(
                &step.problem,
                &settings,
                &step.solution,
                s.file.title.clone(),
                &s.source,
            );
            let mut flagged = obstacle_notes.clone();
            flagged.extend(summary.small_deformation.notes());
            summary.prepend_notes(notes.clone());
            NativeSolution {
                title: format!(
                    "{title}, load factor {}",
                    hemicontact::display::significant(step.factor)
                ),
                output: s.output().clone(),
                problem: step.problem,
                solution: step.solution,
                summary,
                load_factor: step.factor,
                flagged,
            }
        })
        .collect())
}

/// The convergence study of the scenario (a generated mesh) on the levels `levels`
/// (squares along x) against a reference solution with `reference` squares along x, with
/// nested iteration; the study as JSON (see the library's `study::Study`). The GIL is
/// released while it runs, and Ctrl-C interrupts it.
#[pyfunction]
pub fn convergence(
    py: Python<'_>,
    scenario: &NativeScenario,
    levels: Vec<usize>,
    reference: usize,
) -> PyResult<String> {
    let s = &scenario.inner;
    let settings = StudySettings {
        levels,
        reference,
        nested_iteration: true,
    };
    let label = s
        .file
        .title
        .clone()
        .unwrap_or_else(|| "scenario".to_string());
    let study = interrupt::run(py, |stop| {
        study::run_interruptible(s, &label, &settings, &mut |_| {}, stop)
    })?
    .map_err(|e| scenario.error(e))?;
    serde_json::to_string(&study)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))
}

#[pymethods]
impl NativeSolution {
    /// Whether the solve converged with a passing certificate.
    #[getter]
    fn converged(&self) -> bool {
        self.solution.report.converged
    }

    /// The solver's message: how it converged, or why not.
    #[getter]
    fn message(&self) -> String {
        self.solution.report.message.clone()
    }

    /// The title of the result (the scenario's, else `scenario`).
    #[getter]
    fn title(&self) -> String {
        self.title.clone()
    }

    /// Spatial dimension.
    #[getter]
    fn dim(&self) -> usize {
        self.problem.mesh().dim()
    }

    /// Node coordinates (float64 bytes, `n_nodes × dim`, m).
    fn points<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        f64_bytes(py, self.problem.mesh().coords())
    }

    /// Cells (int64 bytes, `n_cells × (dim + 1)`).
    fn cells<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        i64_bytes(
            py,
            self.problem.mesh().cells().iter().map(|&v| i64::from(v)),
        )
    }

    /// Nodal displacement (float64 bytes, `n_nodes × dim`, m).
    fn displacement<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        f64_bytes(py, &self.solution.u)
    }

    /// The body of each node (int64 bytes, `n_nodes`): the connected components of the
    /// mesh numbered by their smallest node, as `summary.json`'s `bodies`; −1 for a node in
    /// no cell.
    fn body<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        let (body_of, _) = hemicontact::rigid::bodies(self.problem.mesh());
        i64_bytes(
            py,
            body_of
                .iter()
                .map(|&b| if b == u32::MAX { -1 } else { i64::from(b) }),
        )
    }

    /// Reaction forces at prescribed DOFs, zero elsewhere (float64 bytes, `n_nodes × dim`,
    /// N; N/m in 2D).
    fn reactions<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        f64_bytes(py, &self.solution.reactions)
    }

    /// The cell fields: (name, components, float64 bytes) for `strain` (9, row-major 3 × 3),
    /// `stress` (9, Pa), `von_mises` (1, Pa), `trace_strain` (1), `locking_active` (1, 0 or
    /// 1), `locking_q` (1), `locking_multiplier` (1, Pa), `material` (1, the index of the
    /// cell's material).
    fn cell_fields<'py>(&self, py: Python<'py>) -> Vec<(&'static str, usize, Bound<'py, PyBytes>)> {
        let c = cell_fields(&self.problem, &self.solution);
        let active: Vec<f64> = c.locking_active.iter().map(|&a| f64::from(a)).collect();
        let material: Vec<f64> = c.material.iter().map(|&k| f64::from(k)).collect();
        vec![
            ("strain", 9, f64_bytes(py, &c.strain)),
            ("stress", 9, f64_bytes(py, &c.stress)),
            ("von_mises", 1, f64_bytes(py, &c.von_mises)),
            ("trace_strain", 1, f64_bytes(py, &c.trace_strain)),
            ("locking_active", 1, f64_bytes(py, &active)),
            ("locking_q", 1, f64_bytes(py, &c.locking_q)),
            (
                "locking_multiplier",
                1,
                f64_bytes(py, &c.locking_multiplier),
            ),
            ("material", 1, f64_bytes(py, &material)),
        ]
    }

    /// The contact table, one entry per contact point: numeric columns as (name,
    /// components, float64 bytes) — those of `contact.csv` and the unit `normal`, the
    /// interface force `force` (N) and the friction traction `friction_traction` (Pa), 3
    /// components each — and text columns (`boundary`, `normal_state`, `friction_state`)
    /// as lists of str.
    #[allow(clippy::type_complexity)]
    fn contact_columns<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(
        Vec<(&'static str, usize, Bound<'py, PyBytes>)>,
        Vec<(&'static str, Vec<String>)>,
    )> {
        let mesh = self.problem.mesh();
        let nodes = self.problem.contact_nodes().map_err(to_py)?;
        let rows = &self.solution.contact;
        let column = |f: &dyn Fn(usize) -> f64| -> Vec<f64> { (0..rows.len()).map(f).collect() };
        let coord = |k: usize| {
            column(&|i| {
                mesh.node(rows[i].node as usize)
                    .get(k)
                    .copied()
                    .unwrap_or(0.0)
            })
        };
        let vector =
            |f: &dyn Fn(usize) -> [f64; 3]| -> Vec<f64> { (0..rows.len()).flat_map(f).collect() };
        let numeric: Vec<(&'static str, usize, Vec<f64>)> = vec![
            ("node", 1, column(&|i| f64::from(rows[i].node))),
            ("x", 1, coord(0)),
            ("y", 1, coord(1)),
            ("z", 1, coord(2)),
            ("weight", 1, column(&|i| rows[i].weight)),
            ("u_nu", 1, column(&|i| rows[i].u_nu)),
            ("gap", 1, column(&|i| rows[i].gap)),
            ("u_tau_1", 1, column(&|i| rows[i].u_tau[0])),
            ("u_tau_2", 1, column(&|i| rows[i].u_tau[1])),
            ("slip", 1, column(&|i| rows[i].slip)),
            ("pressure", 1, column(&|i| rows[i].pressure)),
            ("bound", 1, column(&|i| rows[i].bound)),
            ("force_normal", 1, column(&|i| rows[i].force_normal)),
            (
                "force_tangential_1",
                1,
                column(&|i| rows[i].force_tangential[0]),
            ),
            (
                "force_tangential_2",
                1,
                column(&|i| rows[i].force_tangential[1]),
            ),
            ("normal_residual", 1, column(&|i| rows[i].normal_residual)),
            (
                "friction_residual",
                1,
                column(&|i| rows[i].friction_residual),
            ),
            ("force_scale", 1, column(&|i| rows[i].force_scale)),
            ("slip_scale", 1, column(&|i| rows[i].slip_scale)),
            ("normal", 3, vector(&|i| nodes.normal[i])),
            ("force", 3, vector(&|i| rows[i].force)),
            (
                "friction_traction",
                3,
                vector(&|i| rows[i].friction_traction),
            ),
        ];
        let part =
            |i: usize| mesh.part_names()[self.problem.contact()[rows[i].boundary].part].clone();
        let text = vec![
            ("boundary", (0..rows.len()).map(part).collect()),
            (
                "normal_state",
                rows.iter()
                    .map(|r| r.normal_state.name().to_string())
                    .collect(),
            ),
            (
                "friction_state",
                rows.iter()
                    .map(|r| r.friction_state.name().to_string())
                    .collect(),
            ),
        ];
        let numeric = numeric
            .into_iter()
            .map(|(name, k, v)| (name, k, f64_bytes(py, &v)))
            .collect();
        Ok((numeric, text))
    }

    /// The load factor λ of this solve (1 for a plain solve).
    #[getter]
    fn load_factor(&self) -> f64 {
        self.load_factor
    }

    /// The notes that question the input or the result (among the summary's `notes`),
    /// which Python raises as warnings: an obstacle the contact part's mesh does not
    /// resolve, a deformation too large for the small-deformation model.
    #[getter]
    fn flagged_notes(&self) -> Vec<String> {
        self.flagged.clone()
    }

    /// The summary (`summary.json` without its file list) as JSON.
    fn summary_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.summary)
            .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))
    }

    /// Writes the files `hemicontact solve` writes (`solution.vtu`, `contact.csv`, the
    /// figures, `summary.json`, as the scenario's `[output]` asks) into `folder`, as one
    /// result set: in place only once complete. Returns the paths written.
    fn write(&self, py: Python<'_>, folder: PathBuf) -> PyResult<Vec<PathBuf>> {
        py.detach(|| {
            let mut set = ResultSet::begin(&folder)?;
            let mut extra = Vec::new();
            // A step of a load path: its load factor as the file's TimeValue (a plain
            // solve's file, with TimeValue 1, is written by `write_results`).
            let step = self.load_factor != 1.0;
            if self.output.vtu && step {
                let vtu =
                    solution_vtu(&self.problem, &self.solution, &self.title, self.load_factor)?;
                extra.push(("solution.vtu", vtu.to_bytes()));
            }
            extra.extend(solution_figures(
                &self.problem,
                &self.solution,
                &self.title,
            )?);
            write_results(
                &mut set,
                "",
                &self.problem,
                &self.solution,
                &self.title,
                self.output.summary.then_some(&self.summary),
                self.output.vtu && !step,
                &extra,
            )?;
            set.commit()
        })
        .map_err(to_py)
    }
}
