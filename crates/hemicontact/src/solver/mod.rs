//! The solution method: a fixed-pattern system prepared once, the
//! convexification outer loop, and a globalized Newton method for each convex problem.
//!
//! The program reads like the method: [`solve`] builds the DOF map, the sparsity pattern
//! and the contact points, runs the symbolic analysis once, then iterates { freeze the
//! nonmonotone quantities at the contact points; minimize the convex energy by Newton
//! (assemble, refactorize, solve, line search); measure the change; mix } and finally
//! evaluates the certificate and returns the solution with its report.

pub mod certificate;
pub mod constraints;
pub mod newton;
pub mod outer;
pub mod report;
pub mod scaling;
pub mod system;
pub mod uniqueness;

pub use certificate::{Certificate, ContactResult, FrictionState, NormalState};
pub use constraints::{ConstraintSettings, KktCertificate};
pub use newton::NewtonSettings;
pub use outer::{Acceleration, OuterSettings};
pub use report::{NewtonStep, OuterStep, SolveReport, Timings};
pub use system::System;

use crate::assembly::contact::Frozen;
use crate::error::Result;
use crate::linalg::Ordering;
use crate::norms::energy_norm;
use crate::problem::Problem;
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// Solver settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SolverSettings {
    /// Fill-reducing ordering of the sparse Cholesky factorization. Default: nested
    /// dissection, which gives the smallest factor on the meshes measured by
    /// `hemicontact bench`.
    pub ordering: Ordering,
    /// Parallel tasks for the assembly (0: one per core). Default 0: on the 2-core target,
    /// two chunks assemble 1.6× faster than one (`examples`-free measurement in
    /// `hemicontact bench`).
    pub threads: usize,
    /// Threads for the sparse Cholesky factorization and solves (0: all cores). Default 1:
    /// faer's parallel supernodal factorization was measured *slower* than the sequential one
    /// on the 2-core target (paper square, n = 512: 1.5–1.7 s against 1.1 s; n = 128: 80 ms
    /// against 35 ms), the two cores contending for memory bandwidth.
    pub factorization_threads: usize,
    /// Linear solver of the Newton systems (`[solver] linear_solver = "direct"`,
    /// `"iterative"` or `"auto"`). Default `auto`; see [`LinearSolver`].
    pub linear_solver: LinearSolver,
    /// Newton method settings.
    pub newton: NewtonSettings,
    /// Outer (convexification) loop settings.
    pub outer: OuterSettings,
    /// Exact constraints (augmented Lagrangian) settings.
    pub constraints: ConstraintSettings,
    /// Tolerance of the certificate (dimensionless): every residual of the contact laws,
    /// of equilibrium and of the exact constraints, relative to the solution's own scales,
    /// must be at most this for a solve to count as converged. Default 1e-6; see
    /// [`certificate`].
    pub certificate_tolerance: f64,
}

impl Default for SolverSettings {
    fn default() -> Self {
        SolverSettings {
            ordering: Ordering::default(),
            threads: 0,
            factorization_threads: 1,
            linear_solver: LinearSolver::default(),
            newton: NewtonSettings::default(),
            outer: OuterSettings::default(),
            constraints: ConstraintSettings::default(),
            certificate_tolerance: 1e-6,
        }
    }
}

/// How the Newton systems `H x = b` are solved.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LinearSolver {
    /// Sparse Cholesky factorization, reused and used as a PCG preconditioner while the
    /// Hessian changes little (see [`System::linear_solve`]).
    Direct,
    /// Conjugate gradients preconditioned by geometric multigrid
    /// ([`crate::linalg::multigrid`]) to the Newton forcing term; no factorization of the
    /// fine system is ever formed, so memory stays proportional to the matrix.
    Iterative,
    /// Direct in 2D and in 3D below [`LinearSolver::AUTO_ITERATIVE_EQUATIONS`] equations,
    /// iterative above.
    #[default]
    Auto,
}

impl LinearSolver {
    /// Number of equations from which `auto` chooses the iterative solver in 3D. Measured
    /// on `scenarios/paper3d.toml` (README section "3D at scale", end-to-end solves on the
    /// 2-core target, direct / iterative): 14 739 equations 0.99 s / 0.66 s, 46 875
    /// equations 8.2 s / 2.3 s, 104 544 equations 45 s / 5.3 s. Below 30 000 the gain is
    /// small and the direct solver is kept for its robustness (exact-constraint penalties
    /// make the Hessian ill-conditioned, which costs PCG iterations but not a
    /// factorization).
    pub const AUTO_ITERATIVE_EQUATIONS: usize = 30_000;

    /// The solver used for a system of dimension `dim` with `n_equations` equations:
    /// [`LinearSolver::Direct`] or [`LinearSolver::Iterative`].
    pub fn resolve(self, dim: usize, n_equations: usize) -> LinearSolver {
        match self {
            LinearSolver::Auto if dim == 3 && n_equations >= Self::AUTO_ITERATIVE_EQUATIONS => {
                LinearSolver::Iterative
            }
            LinearSolver::Auto => LinearSolver::Direct,
            other => other,
        }
    }
}

/// A solved (or not converged) problem: displacement, reactions, contact results, report.
#[derive(Clone, Debug)]
pub struct Solution {
    /// Displacement at every DOF (m), DOF order, length `d · n_nodes`.
    pub u: Vec<f64>,
    /// Reaction forces at prescribed DOFs (N), zero at free DOFs; DOF order.
    pub reactions: Vec<f64>,
    /// Convexified energy `E_k(u)` of the last convex problem (J).
    pub energy: f64,
    /// Results at the contact points.
    pub contact: Vec<ContactResult>,
    /// Ideal-locking multiplier λ_T per cell (Pa; the magnitude of the locking stress
    /// `λ_T ∂Q`), empty without ideal locking.
    pub locking_multiplier: Vec<f64>,
    /// The frozen quantities of the last convex problem.
    pub frozen: Frozen,
    /// What the solver did; `report.converged` says whether `u` is a solution.
    pub report: SolveReport,
}

/// Whether the outer loop is needed: some friction law has a slip-dependent coefficient, a
/// Coulomb-type bound, or a nonconvex potential, or there are exact constraints (whose
/// multipliers are iterated). Otherwise one convex problem is the whole problem.
pub fn needs_outer_loop(problem: &Problem) -> bool {
    constraints::has_exact_constraints(problem)
        || problem
            .contact
            .iter()
            .filter_map(|c| c.friction.as_ref())
            .any(|f| {
                f.bound == crate::contact::FrictionBound::Coulomb
                    || f.mu.lipschitz() > 0.0
                    || f.potential.alpha_j() > 0.0
            })
}

/// Solves the problem from the prescribed displacement (zero elsewhere).
///
/// # Errors
/// Invalid problem data ([`Problem::validate`]), a matrix that is not positive definite
/// (rigid motions not blocked), a numerical breakdown, or memory exhaustion.
/// Non-convergence is not an error: see [`SolveReport::converged`].
pub fn solve(problem: &Problem) -> Result<Solution> {
    let u0 = problem.prescribed_displacement();
    solve_from(problem, u0)
}

/// Solves the problem starting from `u` (its prescribed DOFs are overwritten with the
/// Dirichlet values).
///
/// # Errors
/// As [`solve`].
pub fn solve_from(problem: &Problem, u: Vec<f64>) -> Result<Solution> {
    let start = Instant::now();
    problem.validate()?;
    let scales = scaling::Scales::of(problem)?;
    let scaled = scales.nondimensional(problem);
    let u = u.into_iter().map(|x| x / scales.displacement).collect();
    let solution = match solve_dimensionless(&scaled, u, scales.length / scales.displacement) {
        Ok(s) => s,
        // Described again in the user's coordinates.
        Err(crate::Error::ContactLost { .. }) => {
            return Err(crate::Error::ContactLost {
                motions: format!(
                    "{} (the body moved by more than its size)",
                    problem.rigid_motions().describe_all().join("; ")
                ),
            })
        }
        Err(e) => return Err(e),
    };
    let mut solution = scales.dimensional(solution);
    solution.report.free_rigid_motions = problem.rigid_motions().describe_all();
    solution.report.timings.total = start.elapsed().as_secs_f64();
    Ok(solution)
}

/// [`solve_from`] for a problem in dimensionless variables ([`scaling`]): every tolerance,
/// regularization and threshold below is a pure number relative to the problem's scales.
/// `length_unit` is the length scale in units of the displacement scale.
fn solve_dimensionless(problem: &Problem, mut u: Vec<f64>, length_unit: f64) -> Result<Solution> {
    let start = Instant::now();
    let mut system = System::new(problem)?;
    system.length_unit = length_unit;
    let prescribed = problem.prescribed_displacement();
    for (k, x) in u.iter_mut().enumerate() {
        if system.dofs.is_fixed(k) {
            *x = prescribed[k];
        }
    }
    let mut report = SolveReport::new(&system);
    let settings = &problem.solver;
    let dim = problem.mesh.dim();
    let hooke = problem.material.elasticity.small_strain_hooke(dim);
    let n_points = system.contact.len();
    let n_locking =
        problem.mesh.n_cells() * usize::from(problem.material.locking.ideal().is_some());
    let outer_loop = needs_outer_loop(problem);
    let final_tol = settings.newton.residual_tolerance;
    let mut frozen = system.initial_frozen(problem, &u);
    let mut z = outer::flatten(&frozen);
    let mut mixer = outer::Mixer::new(&settings.outer);
    let mut u_prev = u.clone();
    let mut change = f64::INFINITY;
    let mut last = newton::NewtonOutcome {
        converged: false,
        steps: 0,
        residual: f64::NAN,
        energy: f64::NAN,
        force_scale: f64::NAN,
    };
    report.converged = false;
    let stages = constraints::stages(problem).max(system::regularization_stages(problem));
    for k in 0..settings.outer.max_iterations.max(1) {
        system.set_penalty_stage(&settings.constraints, k);
        system.set_regularization_stage(k);
        let tol = if !outer_loop || !settings.outer.inexact {
            final_tol
        } else {
            (1e-2 * change).clamp(final_tol, 1e-3_f64.max(final_tol))
        };
        let steps_before = report.newton.len();
        last = match newton::minimize(
            &mut system,
            problem,
            &mut u,
            &frozen,
            &settings.newton,
            tol,
            k,
            &mut report,
        ) {
            Ok(outcome) => outcome,
            // The load pulls a body off the contact carrying its free rigid motions: no
            // solution to report.
            Err(e @ crate::Error::ContactLost { .. }) => return Err(e),
            // Before any step succeeded there is no iterate worth keeping: the problem
            // itself is at fault (e.g. rigid motions not blocked).
            Err(e) if steps_before == 0 && report.newton.is_empty() => return Err(e),
            // Later, a breakdown keeps the last good iterate (Newton only updates `u`
            // after an accepted step), reported as not converged with where it happened.
            Err(e) => {
                report.message = format!(
                    "not converged: numerical breakdown in outer iteration {k}, Newton step {}: {e}",
                    report.newton.len() - steps_before + 1
                );
                break;
            }
        };
        let diff: Vec<f64> = u.iter().zip(&u_prev).map(|(a, b)| a - b).collect();
        let norm_u = energy_norm(&problem.mesh, &hooke, &u);
        change = if k == 0 {
            f64::INFINITY
        } else {
            energy_norm(&problem.mesh, &hooke, &diff) / norm_u.max(f64::MIN_POSITIVE)
        };
        u_prev.copy_from_slice(&u);
        let next = system.freeze(problem, &u, &frozen);
        let g = outer::flatten(&next);
        let fp_rel = residual(problem, &system, &frozen, &next, &u);
        let mut step = report::OuterStep {
            change,
            fixed_point_residual: fp_rel,
            newton_steps: last.steps,
            newton_tolerance: tol,
            newton_converged: last.converged,
            mixing: String::new(),
        };
        if !last.converged && tol == final_tol {
            step.mixing = "stop: Newton did not converge".into();
            report.outer.push(step);
            report.message = format!(
                "Newton did not converge in outer iteration {k}: residual {:e} > tolerance {:e}",
                last.residual, report.residual_tolerance
            );
            break;
        }
        let at_final = tol == final_tol && last.converged;
        let tol_outer = settings.outer.tolerance;
        if at_final && k >= stages && (!outer_loop || (change <= tol_outer && fp_rel <= tol_outer))
        {
            report.outer.push(step);
            report.converged = true;
            report.message = format!(
                "converged: {} outer iterations, {} Newton steps{}",
                report.outer.len(),
                report.newton.len(),
                if report.round_off_floor > 0.0 {
                    format!(
                        " (a Newton solve stopped at the round-off floor, relative residual {:.1e})",
                        report.round_off_floor
                    )
                } else {
                    String::new()
                }
            );
            break;
        }
        if outer_loop && k + 1 < stages {
            // Continuation (penalties, friction regularization): the map changes with each
            // stage, so no mixing yet.
            step.mixing = format!("continuation: stage {} of {stages} next", k + 1);
            z = g;
            frozen = next;
        } else if outer_loop {
            let (mixed, note) = mixer.next(&z, &g);
            step.mixing = note;
            z = mixed;
            frozen = outer::unflatten(&z, n_points, n_locking);
        }
        report.outer.push(step);
    }
    if !report.converged && report.message == "not started" {
        report.message = format!(
            "not converged: {} outer iterations (cap); last relative change {:e}, fixed-point residual {:e} (tolerance {:e}){}",
            report.outer.len(),
            change,
            report.outer.last().map_or(f64::NAN, |o| o.fixed_point_residual),
            settings.outer.tolerance,
            if mixer.oscillations > 0 { "; oscillation was detected" } else { "" }
        );
    }
    // Final evaluation for the certificate and the reactions.
    let energy = system.evaluate(problem, &u, &frozen, false);
    let reactions = system.reactions();
    // The multipliers consistent with the last convex problem (its forces).
    let updated = system.freeze(problem, &u, &frozen);
    let ca = system.contact_assembler(problem);
    let equilibrium = last.residual / last.force_scale;
    let (contact, mut certificate) = certificate::evaluate(
        &ca,
        &certificate::Inputs {
            u: &u,
            grad_bulk: &system.grad_bulk,
            f_ext: &system.f_ext,
            fixed: &|k| system.dofs.is_fixed(k),
            equilibrium,
            frozen: &frozen,
            force_floor: system.force_floor,
            tolerance: settings.certificate_tolerance,
        },
    );
    if let Some(set) = problem.material.locking.ideal() {
        let kkt = certificate.kkt.get_or_insert_with(Default::default);
        constraints::locking_kkt(&problem.mesh, &set, &u, &updated.locking, kkt);
    }
    // A run counts as converged only with a passing certificate.
    if let Some(worst) = certificate.failures().first().filter(|_| report.converged) {
        report.converged = false;
        let at = worst.at.map_or(String::new(), |w| {
            let part = problem.contact[w.boundary].part;
            format!(
                " at node {} of contact part `{}`",
                w.node,
                problem.mesh.part_names()[part]
            )
        });
        let hint = match worst.law {
            "friction law" => {
                "; the friction regularization ([contact.friction] regularization) may be \
                 too large for this tolerance: lower it, or impose friction exactly \
                 ([contact.friction] exact = true)"
            }
            _ => "",
        };
        report.message = format!(
            "not certified: the {} residual {:.2e}{at} exceeds the certificate tolerance \
             {:.0e} after {} outer iterations and {} Newton steps{hint}",
            worst.law,
            worst.residual,
            certificate.tolerance,
            report.outer.len(),
            report.newton.len()
        );
    }
    report.certificate = certificate;
    // Equilibrium along the free rigid motions carried by contact, at the answer.
    report.rigid_residual =
        system.rigid.generalized_force(&problem.mesh, &system.grad) / last.force_scale;
    report.rigid_shift = system.rigid_shift;
    report.timings.total = start.elapsed().as_secs_f64();
    Ok(Solution {
        u,
        reactions,
        energy,
        contact,
        locking_multiplier: updated.locking,
        frozen,
        report,
    })
}

/// The relative fixed-point residual of the outer loop between the frozen quantities `z`
/// of the last convex problem and their image `g = G(z)` at its solution `u`: the larger of
///
/// - `‖(F, b)_g − (F, b)_z‖ / ‖(F, b)_g‖` for the friction data of the convexification, and
/// - the multiplier changes divided by their penalty — `|Δλ_i|/r_i` and `‖Δτ_i‖/r_i`
///   relative to `max|u|`, `|Δλ_T|/r_T` relative to the size of B (θ, κ², r). This is the
///   standard primal stopping test of the augmented Lagrangian method: for an active
///   constraint `Δλ/r` *is* the constraint violation, for a sticking point `Δτ/r` the slip.
///   (Measured in force units instead, the multiplier change has a floor of r times the
///   Newton tolerance, far above the tolerance for the large penalties used.)
fn residual(problem: &Problem, system: &System, z: &Frozen, g: &Frozen, u: &[f64]) -> f64 {
    let n = z.bound.len();
    let (mut diff, mut norm) = (0.0, 0.0);
    for i in 0..n {
        diff += (g.bound[i] - z.bound[i]).powi(2);
        norm += g.bound[i].powi(2);
        for a in 0..2 {
            diff += (g.linear[i][a] - z.linear[i][a]).powi(2);
            norm += g.linear[i][a].powi(2);
        }
    }
    let mut fp = if diff == 0.0 {
        0.0
    } else {
        (diff / norm.max(f64::MIN_POSITIVE)).sqrt()
    };
    let d = problem.mesh.dim();
    let u_scale = u
        .chunks(d)
        .map(|c| c.iter().map(|x| x * x).sum::<f64>().sqrt())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    for i in 0..n {
        let r = system.contact_penalty[i] * u_scale;
        let dt = ((g.traction[i][0] - z.traction[i][0]).powi(2)
            + (g.traction[i][1] - z.traction[i][1]).powi(2))
        .sqrt();
        fp = fp
            .max((g.pressure[i] - z.pressure[i]).abs() / r)
            .max(dt / r);
    }
    if let Some(set) = problem.material.locking.ideal() {
        let r = system.locking_penalty * set.size();
        for (a, b) in g.locking.iter().zip(&z.locking) {
            fp = fp.max((a - b).abs() / r);
        }
    }
    fp
}

/// Builds the faer parallelism for `threads` (0: all available cores).
pub fn parallelism(threads: usize) -> faer::Par {
    let threads = if threads == 0 {
        rayon::current_num_threads()
    } else {
        threads
    };
    if threads <= 1 {
        faer::Par::Seq
    } else {
        faer::Par::rayon(threads)
    }
}
