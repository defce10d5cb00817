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
pub mod continuation;
pub mod convex;
pub mod convex_energy;
pub mod frozen;
pub mod held;
pub mod line_search;
pub mod local_scales;
pub mod mixing;
pub mod multipliers;
pub mod newton;
pub mod outer;
pub mod regions;
pub mod report;
pub mod round_off;
pub mod scaling;
pub mod settings;
pub mod system;
pub mod timings;
pub mod uniqueness;
pub mod whole;

pub use crate::linalg::{LinearSolver, PetscSettings};
pub use certificate::{Certificate, ContactResult, FrictionState, NormalState};
pub use constraints::ConstraintSettings;
pub use frozen::Frozen;
pub use mixing::Mixing;
pub use multipliers::{KktCertificate, Multipliers};
pub use newton::NewtonStep;
pub use outer::{needs_outer_loop, OuterProgress};
pub use report::StopReason;
pub use report::{OuterStep, SolveReport};
pub use settings::{parallelism, NewtonSettings, SolverSettings, MAX_THREADS};
pub use settings::{Acceleration, OuterSettings};
pub use system::{Evaluation, System};
pub use timings::Timings;

use crate::error::Result;
use crate::parallel::share::Entries;
use crate::problem::Problem;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

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
    /// How the nodes were split among the processes that solved it: `Some` when several
    /// MPI processes solved it with the distributed solver (its `solution.pvtu` then has
    /// one piece per process), `None` on one process.
    pub partition: Option<crate::parallel::Partition>,
}

/// Solves the problem with the given settings, from the prescribed displacement (zero
/// elsewhere).
///
/// # Errors
/// Invalid settings ([`SolverSettings::validate`]), a matrix that is not positive definite,
/// a numerical breakdown, memory exhaustion, or a user-defined friction law that fails
/// ([`crate::Error::Law`]). Non-convergence is not an error: see
/// [`SolveReport::converged`].
pub fn solve(problem: &Problem, settings: &SolverSettings) -> Result<Solution> {
    let u0 = problem.initial_displacement();
    solve_from(problem, settings, u0)
}

/// Solves the problem starting from `u` (its prescribed DOFs are overwritten with the
/// Dirichlet values).
///
/// # Errors
/// As [`solve`].
pub fn solve_from(problem: &Problem, settings: &SolverSettings, u: Vec<f64>) -> Result<Solution> {
    solve_interruptible(problem, settings, u, &AtomicBool::new(false))
}

/// [`solve_from`], interrupted once another thread raises `stop`: the solve then returns
/// [`crate::Error::Interrupted`] at the next Newton iterate (within one Newton step).
///
/// # Errors
/// As [`solve`], and [`crate::Error::Interrupted`].
pub fn solve_interruptible(
    problem: &Problem,
    settings: &SolverSettings,
    u: Vec<f64>,
    stop: &AtomicBool,
) -> Result<Solution> {
    solve_observed(problem, settings, u, stop, &|_| {})
}

/// [`solve_interruptible`] that calls `observe` once per outer iteration with its
/// [`OuterProgress`] (iteration, residuals, Newton steps so far), for a progress display.
/// The observer only reads: the solution is bitwise the same with any observer.
///
/// # Errors
/// As [`solve_interruptible`].
pub fn solve_observed(
    problem: &Problem,
    settings: &SolverSettings,
    u: Vec<f64>,
    stop: &AtomicBool,
    observe: &dyn Fn(&OuterProgress),
) -> Result<Solution> {
    let start = Instant::now();
    // A `Problem` exists only validated; the settings are checked here.
    settings.validate()?;
    let scales = scaling::Scales::of(problem)?;
    let scaled = scales.nondimensional(problem);
    let u = u.into_iter().map(|x| x / scales.displacement).collect();
    let solution = solve_dimensionless(scaled, settings, u, &scales, stop, observe)?;
    let mut solution = scales.dimensional(problem, solution);
    solution.report.free_rigid_motions = problem.rigid_motions()?.describe_all();
    solution.report.timings.total = start.elapsed().as_secs_f64();
    Ok(solution)
}

/// [`solve_from`] for a problem in dimensionless variables ([`scaling`]): every tolerance,
/// regularization and threshold below is a pure number relative to the problem's scales,
/// `scales` (which messages use to speak in the user's units).
///
/// The solve is for the displacement beyond the translation the supports carry each body
/// by ([`crate::rigid::carry`]), and a body resting across a gap is first dropped onto its
/// contact ([`held::rigid_drop`]); the outer loop solves for the displacement relative to
/// that placement, and the answer is the placement plus it.
fn solve_dimensionless(
    problem: Problem,
    settings: &SolverSettings,
    u: Vec<f64>,
    scales: &scaling::Scales,
    stop: &AtomicBool,
    observe: &dyn Fn(&OuterProgress),
) -> Result<Solution> {
    let start = Instant::now();
    // On several processes, this process's part of the system and of the problem: every
    // array below is the part's, until the answer is put together.
    let (mut system, part) = System::for_solve(&problem, settings)?;
    system.scales = Some(*scales);
    let (d, share) = (problem.mesh.dim(), system.share());
    let prescribed = share.of_part(problem.prescribed_displacement(), d, Entries::Nodes);
    let mut u = share.of_part(u, d, Entries::Nodes);
    // On several processes the whole problem is not needed any more.
    let problem = &part.unwrap_or(problem);
    for (k, x) in u.iter_mut().enumerate() {
        if system.dofs.is_fixed(k) {
            *x = prescribed[k];
        }
    }
    // The unknown is the displacement beyond the translation the supports carry each body
    // by (zero at the DOFs it prescribes).
    let u = system.relative_to_placement(u);
    let solution = solve_scaled(problem, &mut system, settings, u, start, stop, observe);
    // A reduction over the processes that failed left NaNs behind: its error, not theirs.
    // The failure is this solve's (its system's `Share`): the next solve starts clean.
    match system.share().failure() {
        Some(e) => Err(e),
        None => solution,
    }
}

/// The body of [`solve_dimensionless`], on the system of this solve (this process's part
/// of it) and `problem` (the part's), from `u` (its prescribed DOFs set); `start` is when
/// the solve began.
fn solve_scaled(
    problem: &Problem,
    system: &mut System,
    settings: &SolverSettings,
    mut u: Vec<f64>,
    start: Instant,
    stop: &AtomicBool,
    observe: &dyn Fn(&OuterProgress),
) -> Result<Solution> {
    let d = problem.mesh.dim();
    let drop = held::rigid_drop(system, problem, &u)?;
    let drop_words = drop
        .as_ref()
        .map(|p| held::describe_placement(system, problem, p))
        .unwrap_or_default();
    if let Some(p) = drop {
        system.place(p.u);
    }
    let mut report = SolveReport::new(system, &settings.processes);
    report.rigid_drop = drop_words;
    let mut eval = system::Evaluation::new(system);
    let outcome = outer::run(
        problem,
        settings,
        system,
        &mut eval,
        &mut u,
        &mut report,
        stop,
        observe,
    )?;
    report.converged = outcome.stop == outer::StopReason::Converged;
    report.message = outcome
        .stop
        .message(&report, &settings.outer, outcome.oscillations);
    report.stop = outcome.stop;
    let frozen = outcome.frozen;
    // Final evaluation for the certificate and the reactions.
    let energy = system.evaluate(problem, &u, &frozen, &mut eval, false);
    if let Some(e) = eval.law_error.take() {
        return Err(e);
    }
    let reactions = system.reactions(&eval.grad);
    let mut ca = system.contact_assembler(problem);
    // User-defined compliance laws: their responses at the answer, from the evaluation.
    ca.responses = &eval.normal;
    // The friction coefficients at the answer, one evaluation per contact part.
    let mu = ca.friction_coefficients(&u)?;
    // The multipliers consistent with the last convex problem (its forces).
    let updated = frozen.multipliers.updated(
        &ca,
        &frozen.contact(),
        &system.continuation.penalties,
        problem,
        &u,
    );
    let (contact, mut certificate) = system.certificate(
        problem,
        &u,
        &frozen,
        &eval,
        &eval.body_scale,
        &mu,
        settings.certificate_tolerance,
    );
    if constraints::has_exact_constraints(problem) {
        let kkt = certificate.kkt.get_or_insert_with(Default::default);
        updated.kkt(&ca, problem, &u, &contact, system.share(), kkt);
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
    let body_scale = eval
        .body_scale
        .iter()
        .fold(f64::MIN_POSITIVE, |m, &s| m.max(s));
    report.rigid_residual =
        system
            .rigid
            .generalized_force(&problem.mesh, &eval.grad, system.share())
            / body_scale;
    report.rigid_shift = eval.rigid_shift;
    // The answer is the rigid drop plus the displacement relative to it.
    let mut energy = energy;
    let mut contact = contact;
    if let Some(placed) = &system.placement {
        for (x, p) in u.iter_mut().zip(placed) {
            *x += p;
        }
        energy -= system.share().dot_dofs(&system.f_ext, placed);
        for (c, p) in contact.iter_mut().zip(&system.contact.placed_normal) {
            c.u_nu += p;
        }
    }
    // Each process knows the displacements, reactions, contact results and multipliers of
    // its own nodes, points and cells: the whole of them on every process.
    let share = system.share();
    let u = share.to_whole(u, d, Entries::Nodes);
    let reactions = share.to_whole(reactions, d, Entries::Nodes);
    let contact = certificate::whole_results(share, contact);
    let ideal = problem.has_ideal_locking();
    let locking_multiplier = match ideal {
        true => share.to_whole(updated.locking, 1, Entries::Cells),
        false => Vec::new(),
    };
    let frozen = frozen.to_whole(share, ideal);
    report.timings.total = start.elapsed().as_secs_f64();
    Ok(Solution {
        u,
        reactions,
        energy,
        contact,
        locking_multiplier,
        frozen,
        report,
        partition: system.partition().cloned(),
    })
}

/// The certificate of a given displacement `u` (m, DOF order, length `d · n_nodes`; its
/// prescribed DOFs are replaced by the Dirichlet values) as an answer of `problem`,
/// whoever computed it: its contact results and the residuals of every law at `u`
/// ([`certificate`]), with the tolerance of `settings`. The interface forces come from the
/// equilibrium of the body alone, so the check does not trust the solver's model; the
/// friction bound is the one at `u`.
///
/// # Errors
/// Invalid settings or a `u` of the wrong length or not finite; a problem with exact
/// constraints (ideal locking, Signorini contact, exact stick/slip), whose forces are
/// multipliers that `u` alone does not give (certify the solver's own answer instead,
/// [`Solution::report`]); the errors of [`solve`] while setting the problem up.
pub fn certify(
    problem: &Problem,
    settings: &SolverSettings,
    u: &[f64],
) -> Result<(Vec<ContactResult>, Certificate)> {
    settings.validate()?;
    let n = problem.mesh.dim() * problem.mesh.n_nodes();
    if u.len() != n || u.iter().any(|x| !x.is_finite()) {
        return Err(crate::Error::invalid(
            "u",
            format!("{} values", u.len()),
            format!("{n} finite displacements (d per node)"),
        ));
    }
    if constraints::has_exact_constraints(problem) {
        return Err(crate::Error::invalid(
            "problem",
            "exact constraints (ideal locking, Signorini contact or exact stick/slip)",
            "laws whose forces are functions of the displacement: the forces of exact \
             constraints are multipliers, certified with the solver's own answer",
        ));
    }
    let scales = scaling::Scales::of(problem)?;
    let scaled = scales.nondimensional(problem);
    let mut system = System::new(&scaled, settings)?;
    let prescribed = scaled.prescribed_displacement();
    let u: Vec<f64> = u
        .iter()
        .enumerate()
        .map(|(k, x)| {
            if system.dofs.is_fixed(k) {
                prescribed[k]
            } else {
                x / scales.displacement
            }
        })
        .collect();
    let u = system.relative_to_placement(u);
    let frozen = Frozen::initial(&system, &scaled, &u)?;
    let mut eval = system::Evaluation::new(&system);
    system.evaluate(&scaled, &u, &frozen, &mut eval, false);
    if let Some(e) = eval.law_error.take() {
        return Err(e);
    }
    let (mut external, mut body_scale) = (Vec::new(), Vec::new());
    let (d, f) = (scaled.mesh.dim(), &system.f_ext);
    let share = system.share();
    system
        .bodies
        .norms(share, d, f.len(), |k| f[k], &mut external);
    system
        .bodies
        .force_scales(share, d, &eval.grad_bulk, f, &external, &mut body_scale);
    let mu = system
        .contact_assembler(&scaled)
        .friction_coefficients(&u)?;
    let (contact, certificate) = system.certificate(
        &scaled,
        &u,
        &frozen,
        &eval,
        &body_scale,
        &mu,
        settings.certificate_tolerance,
    );
    let placed = &system.contact.placed_normal;
    let contact = contact
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let mut c = *c;
            c.u_nu += placed.get(i).copied().unwrap_or(0.0);
            scales.dimensional_contact(&c)
        })
        .collect();
    Ok((contact, certificate))
}
