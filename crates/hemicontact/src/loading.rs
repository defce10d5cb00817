//! Load stepping: the problem solved along a path of load factors `0 < λ_1 < … < λ_N`.
//!
//! Step k solves the problem whose loads (surface tractions `f_N`, body force `f_0`) and
//! prescribed displacements (Dirichlet values) are those of the problem times `λ_k`
//! ([`Problem::with_load_factor`]), and so are the translations of rigid obstacles;
//! gaps and laws are not scaled. The model is static and
//! without history, so each step is a solution of its own problem: the path only supplies
//! starting points. Step k starts from the displacement of step k − 1 (the first from the
//! prescribed displacement, as [`crate::solver::solve`]); the prescribed DOFs take the new
//! step's values ([`crate::solver::solve_observed`] overwrites them). The multipliers and
//! the frozen friction data start afresh in every step.
//!
//! The path stops at the first step that does not converge: its solution is the last one
//! returned, marked `report.converged = false`.

use crate::error::{require, Result};
use crate::problem::Problem;
use crate::solver::{solve_observed, OuterProgress, Solution, SolverSettings};
use std::sync::atomic::AtomicBool;

/// Most load steps a path may have (`[loading] steps`, or entries of `factors`): far
/// above any useful path, low enough that a mistyped count does not run for days.
pub const MAX_STEPS: usize = 10_000;

impl Problem {
    /// This problem with every load and prescribed displacement multiplied by the load
    /// factor `factor` (dimensionless): surface tractions `λ f_N`, body force `λ f_0`,
    /// Dirichlet values `λ u_D`, and the translation `λ t` of each rigid obstacle (whose
    /// gaps and normals are projected anew at its new position). Gaps, shapes, laws and
    /// supports are unchanged. `factor = 1` gives
    /// a problem bitwise equal to this one.
    ///
    /// # Errors
    /// [`crate::Error::Invalid`] (field `load_factor`) unless `factor` is finite and > 0.
    pub fn with_load_factor(&self, factor: f64) -> Result<Problem> {
        require(
            factor.is_finite() && factor > 0.0,
            "load_factor",
            factor,
            "a finite load factor > 0",
        )?;
        let mut p = self.clone();
        for bc in &mut p.dirichlet {
            bc.value = bc.value.map(|x| factor * x);
        }
        for t in &mut p.tractions {
            t.value = t.value.map(|x| factor * x);
        }
        p.body_force = p.body_force.map(|x| factor * x);
        for c in &mut p.contact {
            c.obstacle = c.obstacle.as_ref().map(|o| o.with_load_factor(factor));
        }
        Ok(p)
    }
}

/// Checks a path of load factors: at least one and at most [`MAX_STEPS`], each finite and
/// > 0, strictly increasing.
///
/// # Errors
/// [`crate::Error::Invalid`] naming `factors` (the list) or `factors[k]` (an entry), the
/// value and what is allowed.
pub fn validate_factors(factors: &[f64]) -> Result<()> {
    require(
        !factors.is_empty() && factors.len() <= MAX_STEPS,
        "factors",
        format!("a list of {} factors", factors.len()),
        &format!("a list of 1 to {MAX_STEPS} load factors"),
    )?;
    let mut previous = 0.0;
    for (k, &f) in factors.iter().enumerate() {
        require(
            f.is_finite() && f > previous,
            &format!("factors[{k}]"),
            f,
            &if k == 0 {
                "a finite load factor > 0".to_string()
            } else {
                format!("a finite load factor greater than the one before ({previous})")
            },
        )?;
        previous = f;
    }
    Ok(())
}

/// The uniform path of `steps` steps: `λ_k = k / steps`, k = 1 … steps (the last is
/// exactly 1).
///
/// # Errors
/// [`crate::Error::Invalid`] (field `steps`) unless 1 ≤ `steps` ≤ [`MAX_STEPS`].
pub fn uniform_factors(steps: usize) -> Result<Vec<f64>> {
    require(
        (1..=MAX_STEPS).contains(&steps),
        "steps",
        steps,
        &format!("a number of load steps from 1 to {MAX_STEPS}"),
    )?;
    Ok((1..=steps).map(|k| k as f64 / steps as f64).collect())
}

/// One solved step of a load path.
#[derive(Clone, Debug)]
pub struct LoadStep {
    /// Step number, from 1.
    pub step: usize,
    /// Load factor λ (dimensionless).
    pub factor: f64,
    /// The problem of this step ([`Problem::with_load_factor`]).
    pub problem: Problem,
    /// Its solution; `report.converged` says whether it is one.
    pub solution: Solution,
}

/// Solves `problem` along the load factors `factors` (see the module documentation),
/// calling `observe(step, progress)` once per outer iteration and `on_step` once per
/// solved step (e.g. to write it). The path stops after the first step that does not
/// converge; the steps solved are returned in order.
///
/// Every step is kept; [`for_each_step`] hands each step over instead, for a caller that
/// writes the steps as they come and need not hold a long path in memory.
///
/// # Errors
/// Invalid factors ([`validate_factors`]); the errors of [`crate::solver::solve`] and
/// [`crate::Error::Interrupted`] once `stop` is raised; any error of `on_step`.
pub fn load_path(
    problem: &Problem,
    settings: &SolverSettings,
    factors: &[f64],
    stop: &AtomicBool,
    observe: &dyn Fn(usize, &OuterProgress),
    on_step: &mut dyn FnMut(&LoadStep) -> Result<()>,
) -> Result<Vec<LoadStep>> {
    let mut steps: Vec<LoadStep> = Vec::with_capacity(factors.len());
    for_each_step(problem, settings, factors, stop, observe, &mut |step| {
        on_step(&step)?;
        steps.push(step);
        Ok(())
    })?;
    Ok(steps)
}

/// [`load_path`] without keeping the steps: each solved step is handed to `on_step`, in
/// order, and only the last displacement (the next step's start) is kept. Returns the
/// number of steps solved; the last one handed over is the first that did not converge,
/// if any.
///
/// # Errors
/// As [`load_path`].
pub fn for_each_step(
    problem: &Problem,
    settings: &SolverSettings,
    factors: &[f64],
    stop: &AtomicBool,
    observe: &dyn Fn(usize, &OuterProgress),
    on_step: &mut dyn FnMut(LoadStep) -> Result<()>,
) -> Result<usize> {
    validate_factors(factors)?;
    // The last step's displacement and the translation its supports carried the bodies by.
    let mut last: Option<(Vec<f64>, Option<Vec<f64>>)> = None;
    for (k, &factor) in factors.iter().enumerate() {
        let scaled = problem.with_load_factor(factor)?;
        let carried = scaled.carried_displacement();
        // From the last step, with the bodies carried on to this step's translation.
        let start = match last.take() {
            Some((mut u, before)) => {
                let moved = carried.is_some() || before.is_some();
                for (k, x) in u.iter_mut().enumerate().filter(|_| moved) {
                    *x += carried.as_ref().map_or(0.0, |c| c[k])
                        - before.as_ref().map_or(0.0, |c| c[k]);
                }
                u
            }
            None => scaled.initial_displacement(),
        };
        let solution = solve_observed(&scaled, settings, start, stop, &|p| observe(k + 1, p))?;
        let converged = solution.report.converged;
        if converged {
            last = Some((solution.u.clone(), carried));
        }
        on_step(LoadStep {
            step: k + 1,
            factor,
            problem: scaled,
            solution,
        })?;
        if !converged {
            return Ok(k + 1);
        }
    }
    Ok(factors.len())
}

/// One row of a load path's table (`load_path.csv`).
#[derive(Clone, Debug, PartialEq)]
pub struct PathRow {
    /// Load factor λ.
    pub factor: f64,
    /// Total interface force on the body over all contact points, global coordinates
    /// (N in 3D, N/m in 2D): `Σ_i R_i` from equilibrium.
    pub contact_force: [f64; 3],
    /// Contact points in contact.
    pub n_contact: usize,
    /// Contact points slipping.
    pub n_slip: usize,
    /// Largest nodal displacement magnitude `max_v |u_v|` (m).
    pub max_displacement: f64,
    /// Outer iterations.
    pub outer: usize,
    /// Newton steps.
    pub newton: usize,
    /// Whether the step converged (with a passing certificate).
    pub converged: bool,
}

impl PathRow {
    /// The row of a solved step.
    pub fn of(step: &LoadStep) -> PathRow {
        let s = &step.solution;
        let mut contact_force = [0.0; 3];
        for c in &s.contact {
            for (total, f) in contact_force.iter_mut().zip(c.force) {
                *total += f;
            }
        }
        let d = step.problem.mesh().dim();
        PathRow {
            factor: step.factor,
            contact_force,
            n_contact: s.report.certificate.n_contact,
            n_slip: s.report.certificate.n_slip,
            max_displacement: crate::assembly::norms::max_nodal_norm(&s.u, d),
            outer: s.report.outer.len(),
            newton: s.report.newton.len(),
            converged: s.report.converged,
        }
    }
}

/// The text of `load_path.csv` for rows of a `dim`-dimensional problem: a header, then one
/// line per step with the load factor, the total contact force components (`Fx, Fy[, Fz]`,
/// N or N/m in 2D), contact and slip counts, `max |u|` (m), outer iterations, Newton steps
/// and `converged` (`true`/`false`). Numbers are written in full precision (shortest
/// round-trip form).
pub fn path_csv(rows: &[PathRow], dim: usize) -> String {
    use std::fmt::Write as _;
    let axes = ["x", "y", "z"];
    let mut out = String::from("load_factor");
    for a in &axes[..dim] {
        let _ = write!(out, ",contact_force_{a}");
    }
    out.push_str(",n_contact,n_slip,max_displacement,outer_iterations,newton_steps,converged\n");
    for r in rows {
        let _ = write!(out, "{:?}", r.factor);
        for f in &r.contact_force[..dim] {
            let _ = write!(out, ",{f:?}");
        }
        let _ = writeln!(
            out,
            ",{},{},{:?},{},{},{}",
            r.n_contact, r.n_slip, r.max_displacement, r.outer, r.newton, r.converged
        );
    }
    out
}
