//! The convexification outer loop: its settings, its body, its stopping test and the
//! reasons it stops.
//!
//! Outer iteration k freezes, at every contact point, the friction bound `F_i^k` (which
//! depends on the slip through μ, and for Coulomb-type bounds on the pressure) and the
//! linear term `b_i^k = F_i^k ∇h(u_τ,i^k)` of the difference-of-convex split, and the
//! multipliers of the exact constraints, then minimizes the convex energy `E_k` by Newton's
//! method ([`super::newton`]). This is a fixed-point iteration `z ↦ G(z)` on the vector z of
//! frozen quantities (`G(z)` = the quantities evaluated at the minimizer of `E_z`). It
//! converges only linearly, and for large friction coefficients the plain iteration can
//! fall into a two-state oscillation; the next z is therefore mixed from the last ones
//! ([`super::mixing`]: Anderson acceleration, or relaxation with oscillation detection).
//!
//! - **Continuation.** Penalties of exact constraints and the friction regularization
//!   start soft and reach their values over the first outer iterations (stages); no mixing
//!   before the last stage, since the map changes with each.
//! - **Inexact inner solves**: early convex problems need not be solved to full accuracy.
//!   The Newton tolerance of iteration k is `clamp(10⁻² δ_{k−1}, tol_N, 10⁻³)` with
//!   `δ_{k−1}` the last relative change; convergence is only declared after a solve at the
//!   final Newton tolerance `tol_N`.
//!
//! The loop stops ([`StopReason`]) when the relative change `‖u^k − u^{k−1}‖_E / ‖u^k‖_E`
//! falls below `tolerance` (default 1e-10) *and* so does the relative fixed-point residual
//! ([`Frozen::residual`]; a mixed iterate can stall — `u` stops changing while the
//! frozen quantities are still inconsistent with it — so the change of u alone is not a
//! proof of convergence), after every continuation stage; or when a convex solve at the
//! final tolerance fails, a numerical breakdown occurs, or `max_iterations` is reached.

use super::convex;
use super::frozen::Frozen;
use super::held;
use super::mixing::{Counted, Mixer, Mixing};
use super::newton::{NewtonOutcome, NewtonRecord};
pub use super::report::StopReason;
use super::report::{OuterStep, SolveReport};
use super::settings::SolverSettings;
pub use super::settings::{Acceleration, OuterSettings, MAX_DEPTH};
use super::system::Evaluation;
use super::{constraints, System};
use crate::error::Result;
use crate::problem::Problem;
use std::sync::atomic::{AtomicBool, Ordering};

/// What the outer loop leaves for the certificate and the solution.
#[derive(Clone, Debug)]
pub struct OuterOutcome {
    /// Why it stopped.
    pub stop: StopReason,
    /// The frozen quantities of the last convex problem solved.
    pub frozen: Frozen,
    /// The outcome of the last convex solve.
    pub last: NewtonOutcome,
    /// Number of oscillation detections of the mixer.
    pub oscillations: usize,
}

/// Whether the outer loop is needed: some friction law has a slip-dependent coefficient, a
/// Coulomb-type bound, or a nonconvex potential, or there are exact constraints (whose
/// multipliers are iterated). Otherwise one convex problem is the whole problem.
pub fn needs_outer_loop(problem: &Problem) -> bool {
    constraints::has_multipliers(problem)
        || problem
            .contact
            .iter()
            .filter_map(|c| c.friction.as_ref())
            .any(|f| {
                f.bound == crate::contact::FrictionBound::Coulomb
                    || f.mu.is_slip_dependent()
                    || f.potential.alpha_j() > 0.0
            })
}

/// The state of a solve after one outer iteration, handed to an observer (see
/// [`super::solve_observed`]) for a progress display. Plain numbers: observing a solve
/// allocates nothing and changes nothing in it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OuterProgress {
    /// Outer iteration k, from 0.
    pub iteration: usize,
    /// Relative change `‖u^k − u^{k−1}‖_E / ‖u^k‖_E` (∞ at the first iteration).
    pub change: f64,
    /// Relative fixed-point residual `‖G(z) − z‖ / ‖G(z)‖` of the frozen quantities.
    pub fixed_point_residual: f64,
    /// Newton steps of all outer iterations so far.
    pub newton_steps: usize,
    /// The outer tolerance that both the change and the fixed-point residual must reach.
    pub tolerance: f64,
}

impl OuterProgress {
    /// The residual of the stopping test: the larger of the relative change of u and the
    /// fixed-point residual (the fixed-point residual alone at the first iteration, where
    /// the change is undefined).
    pub fn residual(&self) -> f64 {
        if self.change.is_finite() {
            self.change.max(self.fixed_point_residual)
        } else {
            self.fixed_point_residual
        }
    }
}

/// Runs the outer loop on `system` (evaluating into the work arrays `eval`) from `u` (whose prescribed DOFs hold the Dirichlet
/// values): each iteration sets the continuation stage, minimizes the convex energy of the
/// frozen quantities by Newton, measures the change of u and the fixed-point residual,
/// applies the stopping test, and mixes the next frozen quantities. On return `u` is the
/// last iterate and `report` holds every Newton and outer step. `observe` is called once
/// per completed outer iteration with its [`OuterProgress`].
///
/// # Errors
/// A Newton error before any step succeeded (the problem itself is at fault, e.g. rigid
/// motions not blocked), and [`crate::Error::ContactLost`] and
/// [`crate::Error::Interrupted`] (once `interrupt` is raised) and [`crate::Error::Law`] (a
/// user-defined friction law failed) at any time; later breakdowns stop the loop with
/// [`StopReason::Breakdown`] instead.
pub fn run(
    problem: &Problem,
    settings: &SolverSettings,
    system: &mut System,
    eval: &mut Evaluation,
    u: &mut [f64],
    report: &mut SolveReport,
    interrupt: &AtomicBool,
    observe: &dyn Fn(&OuterProgress),
) -> Result<OuterOutcome> {
    let dim = problem.mesh.dim();
    let hookes: Vec<_> = problem
        .materials
        .iter()
        .map(|m| m.elasticity.small_strain_hooke(dim))
        .collect();
    let hooke = |c: usize| hookes[problem.cell_material(c)];
    let n_points = system.contact.len();
    let n_locking = problem.mesh.n_cells() * usize::from(problem.has_ideal_locking());
    let outer_loop = needs_outer_loop(problem);
    let final_tol = settings.newton.residual_tolerance;
    let mut frozen = Frozen::initial(system, problem, u)?;
    // Bodies held by friction alone (see `held`): a first bound that cannot carry the load
    // along their sliding motions (a Coulomb bound at zero pressure) is given one iteration
    // with that load balanced by uniform friction; a fixed bound is checked now.
    let sliding = held::Sliding::of(system, problem);
    let mut relieved = None;
    if !sliding.is_empty() && sliding.exceeds(system, &frozen.friction.bound) {
        if outer_loop {
            let relief = sliding.relief(system, problem);
            relieved = Some(system.f_ext.clone());
            for (f, r) in system.f_ext.iter_mut().zip(&relief) {
                *f += r;
            }
        } else {
            sliding.check(system, problem, u, &frozen)?;
        }
    }
    let relieved_first = relieved.is_some();
    // A friction-held body whose frozen bound cannot carry its load is first brought to
    // rest with the static coefficient (see `held::AtRest`).
    let mut at_rest = held::AtRest::default();
    let mut z = frozen.flatten();
    let z_counts = Frozen::counted(system.share(), n_points, n_locking);
    let mut mixer = Mixer::new(&settings.outer);
    let mut u_prev = u.to_vec();
    let (mut norm_u, mut norm_diff, mut point_scale) = (Vec::new(), Vec::new(), Vec::new());
    let mut change = f64::INFINITY;
    let mut last = NewtonOutcome {
        converged: false,
        steps: 0,
        residual: f64::NAN,
        energy: f64::NAN,
        force_scale: f64::NAN,
    };
    let mut stop = StopReason::IterationCap;
    let stages = system.continuation.stages();
    for k in 0..settings.outer.max_iterations.max(1) {
        system.continuation.set_stage(k);
        if k > 0 && at_rest.enter(&sliding, system, problem, u, &mut frozen)? {
            z = frozen.flatten();
            mixer = restarted(mixer, &settings.outer);
        }
        // A relieved first iteration gives the friction limit: solved accurately.
        let tol = if !outer_loop || !settings.outer.inexact || (k == 0 && relieved_first) {
            final_tol
        } else {
            (1e-2 * change).clamp(final_tol, 1e-3_f64.max(final_tol))
        };
        // The tolerance never falls below the final one: at it, this solve can conclude.
        let final_solve = tol <= final_tol;
        let steps_before = report.newton.len();
        let mut record = NewtonRecord {
            outer: k,
            first_step: steps_before,
            ..NewtonRecord::default()
        };
        if interrupt.load(Ordering::Relaxed) {
            return Err(crate::Error::Interrupted);
        }
        let mut energy =
            convex::ConvexProblem::new(system, eval, problem, &frozen, &settings.newton, u)
                .with_stop(interrupt);
        let result = convex::minimize(&mut energy, tol, u, &mut record);
        let runaway = energy.runaway;
        report.add_newton(record);
        if let Some(f_ext) = relieved.take() {
            system.f_ext = f_ext;
        }
        // A user-defined compliance law that fails ends the solve with its error.
        if let Some(e) = eval.law_error.take() {
            return Err(e);
        }
        last = match result {
            Ok(outcome) => outcome,
            // The load pulls a body off the contact carrying its free rigid motions, or
            // slides it beyond what friction holds: no solution to report.
            Err(e @ crate::Error::ContactLost { .. }) => {
                let slid = match runaway {
                    Some(r) => sliding.slid_away(system, problem, &r, &u_prev, &frozen, k)?,
                    None => None,
                };
                return Err(slid.unwrap_or(e));
            }
            // The caller asked to stop: no result.
            Err(crate::Error::Interrupted) => return Err(crate::Error::Interrupted),
            // Before any step succeeded there is no iterate worth keeping: the problem
            // itself is at fault (e.g. rigid motions not blocked).
            Err(e) if steps_before == 0 && report.newton.is_empty() => return Err(e),
            // Later, a breakdown keeps the last good iterate (Newton only updates `u`
            // after an accepted step), reported as not converged with where it happened.
            Err(e) => {
                stop = StopReason::Breakdown {
                    outer: k,
                    step: report.newton.len() - steps_before + 1,
                    error: e.to_string(),
                };
                break;
            }
        };
        let diff: Vec<f64> = u.iter().zip(&u_prev).map(|(a, b)| a - b).collect();
        change = if k == 0 {
            f64::INFINITY
        } else {
            // Body by body: the largest relative change of a body.
            system
                .bodies
                .energy_norms(system.share(), &problem.mesh, &hooke, u, &mut norm_u);
            system.bodies.energy_norms(
                system.share(),
                &problem.mesh,
                &hooke,
                &diff,
                &mut norm_diff,
            );
            let relative = |floor: &[f64]| {
                norm_diff
                    .iter()
                    .zip(&norm_u)
                    .enumerate()
                    .map(|(b, (d, n))| {
                        let d = if floor.get(b).is_some_and(|f| d <= f) {
                            0.0
                        } else {
                            *d
                        };
                        d / n.max(f64::MIN_POSITIVE)
                    })
                    .fold(0.0, |c: f64, x| if x.is_nan() { x } else { c.max(x) })
            };
            let plain = relative(&[]);
            if plain > settings.outer.tolerance {
                // A change within the round-off of u itself is no change.
                let mut floor = Vec::new();
                let (share, mesh) = (system.share(), &problem.mesh);
                super::round_off::change_floors(&system.bodies, share, mesh, &hooke, u, &mut floor);
                relative(&floor)
            } else {
                plain
            }
        };
        u_prev.copy_from_slice(u);
        if k == 0 && relieved_first {
            // The pressures of the relieved iteration give the friction limit; the slips
            // start from its answer centred on the contact.
            sliding.check(system, problem, u, &frozen)?;
            sliding.recenter(system, problem, u);
            u_prev.copy_from_slice(u);
        }
        // A user-defined friction law that fails ends the solve with its error.
        let mut next = frozen.image(system, problem, u)?;
        if k == 0 && relieved_first {
            // A Coulomb bound at a Signorini point takes its pressure from the multiplier,
            // zero in this first iteration: take the updated one.
            next.friction = system
                .contact_assembler(problem)
                .convexify(u, &next.contact())?;
        }
        at_rest.apply(&sliding, system, problem, u, &mut next)?;
        let g = next.flatten();
        // Each contact point on its own scale (see `local_scales`).
        point_scale.clear();
        point_scale.extend(
            eval.point_force
                .iter()
                .zip(&eval.point_floor)
                .map(|(f, floor)| f.max(*floor).max(f64::MIN_POSITIVE)),
        );
        let fp_rel = frozen.residual(&next, system, problem, &point_scale);
        let mut step = OuterStep {
            change,
            fixed_point_residual: fp_rel,
            newton_steps: last.steps,
            newton_tolerance: tol,
            newton_converged: last.converged,
            mixing: Mixing::None,
        };
        observe(&OuterProgress {
            iteration: k,
            change,
            fixed_point_residual: fp_rel,
            newton_steps: report.newton.len(),
            tolerance: settings.outer.tolerance,
        });
        if !last.converged && final_solve {
            step.mixing = Mixing::NewtonFailed;
            report.outer.push(step);
            stop = StopReason::NewtonNotConverged {
                outer: k,
                residual: last.residual,
                tolerance: report.residual_tolerance,
            };
            break;
        }
        let tol_outer = settings.outer.tolerance;
        if final_solve
            && last.converged
            && k >= stages
            && (!outer_loop || (change <= tol_outer && fp_rel <= tol_outer))
        {
            if at_rest.release() {
                // The problem at rest has converged: the slip-dependent law takes over
                // from its answer.
                frozen = frozen.image(system, problem, u)?;
                z = frozen.flatten();
                mixer = restarted(mixer, &settings.outer);
                step.mixing = Mixing::FixedPoint;
                report.outer.push(step);
                continue;
            }
            report.outer.push(step);
            stop = StopReason::Converged;
            break;
        }
        if k == 0 && relieved_first {
            step.mixing = Mixing::Relieved;
            z = g;
            frozen = next;
        } else if outer_loop && k + 1 < stages {
            // Continuation (penalties, friction regularization): the map changes with each
            // stage, so no mixing yet.
            step.mixing = Mixing::Continuation {
                next: k + 1,
                stages,
            };
            z = g;
            frozen = next;
        } else if outer_loop {
            let counted = Counted {
                counts: &z_counts,
                share: system.share(),
            };
            let (mixed, how) = mixer.next(&z, &g, counted);
            step.mixing = how;
            z = mixed;
            frozen = Frozen::unflatten(&z, n_points, n_locking);
        }
        report.outer.push(step);
    }
    Ok(OuterOutcome {
        stop,
        frozen,
        last,
        oscillations: mixer.oscillations,
    })
}

/// A mixer with no history, keeping the counts of `mixer` (the map of the fixed point has
/// changed: a group of bodies was put at rest or released, see [`held::AtRest`]).
fn restarted(mixer: Mixer, settings: &OuterSettings) -> Mixer {
    let mut fresh = Mixer::new(settings);
    fresh.oscillations = mixer.oscillations;
    fresh.restarts = mixer.restarts;
    fresh
}
