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
    let (sliding, mut relieved) = held_by_friction(system, problem, u, &frozen, outer_loop)?;
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
    let mut last = no_convex_solve();
    let mut stop = StopReason::IterationCap;
    let stages = system.continuation.stages();
    for k in 0..settings.outer.max_iterations.max(1) {
        system.continuation.set_stage(k);
        if k > 0 && at_rest.enter(&sliding, system, problem, u, &mut frozen)? {
            z = frozen.flatten();
            mixer = restarted(mixer, &settings.outer);
        }
        let relieved_now = k == 0 && relieved_first;
        let tol = newton_tolerance(settings, outer_loop, relieved_now, change);
        // The tolerance never falls below the final one: at it, this solve can conclude.
        let final_solve = tol <= final_tol;
        let (convex_solve, result) = ConvexSolve::solve(
            (k, tol),
            system,
            eval,
            problem,
            &frozen,
            &settings.newton,
            u,
            interrupt,
            report,
        )?;
        if let Some(f_ext) = relieved.take() {
            system.f_ext = f_ext;
        }
        // A user-defined compliance law that fails ends the solve with its error.
        if let Some(e) = eval.law_error.take() {
            return Err(e);
        }
        last = match convex_solve
            .outcome(result, &sliding, system, problem, &u_prev, &frozen, report)?
        {
            Ok(outcome) => outcome,
            Err(breakdown) => {
                stop = breakdown;
                break;
            }
        };
        change = if k == 0 {
            f64::INFINITY
        } else {
            let norms = (&mut norm_u, &mut norm_diff);
            relative_change(system, problem, &hooke, u, &u_prev, norms, &settings.outer)
        };
        u_prev.copy_from_slice(u);
        let held = (&sliding, &at_rest, relieved_now);
        let next = image(held, system, problem, u, &mut u_prev, &frozen)?;
        let g = next.flatten();
        let fp_rel = fixed_point_residual(system, problem, eval, &frozen, &next, &mut point_scale);
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
        let counted = Counted {
            counts: &z_counts,
            share: system.share(),
        };
        let stage = (k, stages, relieved_now, outer_loop);
        let sizes = (n_points, n_locking);
        let (mixing, mixed) = next_iterate(stage, &mut mixer, &z, g, next, counted, sizes);
        step.mixing = mixing;
        if let Some((mixed_z, mixed_frozen)) = mixed {
            z = mixed_z;
            frozen = mixed_frozen;
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

/// The outcome before any convex solve: not converged, no step, no residual.
fn no_convex_solve() -> NewtonOutcome {
    NewtonOutcome {
        converged: false,
        steps: 0,
        residual: f64::NAN,
        energy: f64::NAN,
        force_scale: f64::NAN,
    }
}

/// The image `G(z)` of the frozen quantities `frozen` at the iterate `u`, for the bodies
/// held by friction `held` (their sliding motions, those at rest, and whether this
/// iteration was relieved: then the friction limit is checked, the slips recentred on the
/// contact, `u` and `u_prev` with them, and the bound of a Signorini point takes the
/// updated pressure).
///
/// # Errors
/// A user-defined friction law that fails, and those of [`held::Sliding::check`].
fn image(
    (sliding, at_rest, relieved): (&held::Sliding, &held::AtRest, bool),
    system: &System,
    problem: &Problem,
    u: &mut [f64],
    u_prev: &mut [f64],
    frozen: &Frozen,
) -> Result<Frozen> {
    if relieved {
        // The pressures of the relieved iteration give the friction limit; the slips
        // start from its answer centred on the contact.
        sliding.check(system, problem, u, frozen)?;
        sliding.recenter(system, problem, u);
        u_prev.copy_from_slice(u);
    }
    // A user-defined friction law that fails ends the solve with its error.
    let mut next = frozen.image(system, problem, u)?;
    if relieved {
        // A Coulomb bound at a Signorini point takes its pressure from the multiplier,
        // zero in this first iteration: take the updated one.
        next.friction = system
            .contact_assembler(problem)
            .convexify(u, &next.contact())?;
    }
    at_rest.apply(sliding, system, problem, u, &mut next)?;
    Ok(next)
}

/// Bodies held by friction alone (see `held`): a first bound that cannot carry the load
/// along their sliding motions (a Coulomb bound at zero pressure) is given one iteration
/// with that load balanced by uniform friction (`system.f_ext` relieved; the external
/// forces to restore after it are returned); a fixed bound (no outer loop) is checked now.
///
/// # Errors
/// Those of [`held::Sliding::check`].
fn held_by_friction(
    system: &mut System,
    problem: &Problem,
    u: &[f64],
    frozen: &Frozen,
    outer_loop: bool,
) -> Result<(held::Sliding, Option<Vec<f64>>)> {
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
            sliding.check(system, problem, u, frozen)?;
        }
    }
    Ok((sliding, relieved))
}

/// The relative residual tolerance of the convex solve after a relative change `change`:
/// the final one without an outer loop, without inexact solves, or in a relieved first
/// iteration (`relieved`: it gives the friction limit, solved accurately); else a hundredth
/// of the change, between the final tolerance and 1e-3.
fn newton_tolerance(
    settings: &SolverSettings,
    outer_loop: bool,
    relieved: bool,
    change: f64,
) -> f64 {
    let final_tol = settings.newton.residual_tolerance;
    // A relieved first iteration gives the friction limit: solved accurately.
    if !outer_loop || !settings.outer.inexact || relieved {
        final_tol
    } else {
        (1e-2 * change).clamp(final_tol, 1e-3_f64.max(final_tol))
    }
}

/// Which convex solve an outcome is of: the outer iteration `k`, the Newton steps before
/// it, and the body that ran away along a free rigid motion, if one did.
struct ConvexSolve {
    /// The outer iteration.
    k: usize,
    /// Newton steps of the solve before this convex solve.
    steps_before: usize,
    /// The runaway the convex solve stopped at, if any.
    runaway: Option<crate::rigid::Runaway>,
}

impl ConvexSolve {
    /// Minimizes the convex energy of the frozen quantities `frozen` by Newton from `u`,
    /// in outer iteration `k` to the relative residual `tol`, the steps recorded in
    /// `report`: the solve, and its result.
    ///
    /// # Errors
    /// [`crate::Error::Interrupted`] if `interrupt` is raised before it.
    #[allow(clippy::too_many_arguments)]
    fn solve(
        (k, tol): (usize, f64),
        system: &mut System,
        eval: &mut Evaluation,
        problem: &Problem,
        frozen: &Frozen,
        settings: &super::settings::NewtonSettings,
        u: &mut [f64],
        interrupt: &AtomicBool,
        report: &mut SolveReport,
    ) -> Result<(ConvexSolve, Result<NewtonOutcome>)> {
        let steps_before = report.newton.len();
        let mut record = NewtonRecord {
            outer: k,
            first_step: steps_before,
            ..NewtonRecord::default()
        };
        if interrupt.load(Ordering::Relaxed) {
            return Err(crate::Error::Interrupted);
        }
        let mut energy = convex::ConvexProblem::new(system, eval, problem, frozen, settings, u)
            .with_stop(interrupt);
        let result = convex::minimize(&mut energy, tol, u, &mut record);
        let runaway = energy.runaway;
        report.add_newton(record);
        let solve = ConvexSolve {
            k,
            steps_before,
            runaway,
        };
        Ok((solve, result))
    }

    /// The outcome of the convex solve, `Ok(Err(stop))` for a breakdown after some step
    /// succeeded (the last good iterate is kept: Newton only updates `u` after an
    /// accepted step).
    ///
    /// # Errors
    /// A body pulled off the contact carrying its free rigid motions, or slid beyond what
    /// friction holds ([`held::Sliding::slid_away`]); an interruption; an error before any
    /// step succeeded (the problem itself is at fault, e.g. rigid motions not blocked).
    #[allow(clippy::too_many_arguments)]
    fn outcome(
        &self,
        result: Result<NewtonOutcome>,
        sliding: &held::Sliding,
        system: &System,
        problem: &Problem,
        u_prev: &[f64],
        frozen: &Frozen,
        report: &SolveReport,
    ) -> Result<std::result::Result<NewtonOutcome, StopReason>> {
        let (k, steps_before) = (self.k, self.steps_before);
        match result {
            Ok(outcome) => Ok(Ok(outcome)),
            // The load pulls a body off the contact carrying its free rigid motions, or
            // slides it beyond what friction holds: no solution to report.
            Err(e @ crate::Error::ContactLost { .. }) => {
                let slid = match &self.runaway {
                    Some(r) => sliding.slid_away(system, problem, r, u_prev, frozen, k)?,
                    None => None,
                };
                Err(slid.unwrap_or(e))
            }
            // The caller asked to stop: no result.
            Err(crate::Error::Interrupted) => Err(crate::Error::Interrupted),
            // Before any step succeeded there is no iterate worth keeping: the problem
            // itself is at fault (e.g. rigid motions not blocked).
            Err(e) if steps_before == 0 && report.newton.is_empty() => Err(e),
            // Later, a breakdown keeps the last good iterate (Newton only updates `u`
            // after an accepted step), reported as not converged with where it happened.
            Err(e) => Ok(Err(StopReason::Breakdown {
                outer: k,
                step: report.newton.len() - steps_before + 1,
                error: e.to_string(),
            })),
        }
    }
}

/// The relative change of `u` since `u_prev`, body by body: the largest over the bodies of
/// `‖u − u_prev‖_E / ‖u‖_E` in the energy norm of the small-strain Hooke laws `hooke`
/// (the work arrays `norms` hold the bodies' norms of u and of the change); beyond the
/// outer tolerance, a change within the round-off of u itself counts as none.
fn relative_change(
    system: &System,
    problem: &Problem,
    hooke: &dyn Fn(usize) -> crate::material::Hooke,
    u: &[f64],
    u_prev: &[f64],
    norms: (&mut Vec<f64>, &mut Vec<f64>),
    settings: &OuterSettings,
) -> f64 {
    let (norm_u, norm_diff) = norms;
    let diff: Vec<f64> = u.iter().zip(u_prev).map(|(a, b)| a - b).collect();
    // Body by body: the largest relative change of a body.
    system
        .bodies
        .energy_norms(system.share(), &problem.mesh, hooke, u, norm_u);
    system
        .bodies
        .energy_norms(system.share(), &problem.mesh, hooke, &diff, norm_diff);
    let relative = |floor: &[f64]| {
        norm_diff
            .iter()
            .zip(norm_u.iter())
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
    if plain > settings.tolerance {
        // A change within the round-off of u itself is no change.
        let mut floor = Vec::new();
        let (share, mesh) = (system.share(), &problem.mesh);
        super::round_off::change_floors(&system.bodies, share, mesh, hooke, u, &mut floor);
        relative(&floor)
    } else {
        plain
    }
}

/// The relative fixed-point residual of the frozen quantities `next` (the image) against
/// `frozen`, each contact point on its own scale (see `local_scales`: the larger of its
/// force and its floor at the last evaluation `eval`, into the work array `point_scale`).
fn fixed_point_residual(
    system: &System,
    problem: &Problem,
    eval: &Evaluation,
    frozen: &Frozen,
    next: &Frozen,
    point_scale: &mut Vec<f64>,
) -> f64 {
    // Each contact point on its own scale (see `local_scales`).
    point_scale.clear();
    point_scale.extend(
        eval.point_force
            .iter()
            .zip(&eval.point_floor)
            .map(|(f, floor)| f.max(*floor).max(f64::MIN_POSITIVE)),
    );
    frozen.residual(next, system, problem, point_scale)
}

/// How the next iterate is formed after outer iteration `k` of `stages` continuation
/// stages (`relieved`: a relieved first iteration; `outer_loop`: whether the outer loop is
/// needed), from the current `z` and its image `g` (the frozen quantities `next`): the
/// image itself after a relieved iteration and during continuation (the map changes with
/// each stage, so no mixing yet), else `mixer`'s next iterate; `None` without an outer
/// loop (the iterate stays). `n_points` contact points and `n_locking` cell multipliers
/// make up an iterate.
fn next_iterate(
    (k, stages, relieved, outer_loop): (usize, usize, bool, bool),
    mixer: &mut Mixer,
    z: &[f64],
    g: Vec<f64>,
    next: Frozen,
    counted: Counted<'_>,
    (n_points, n_locking): (usize, usize),
) -> (Mixing, Option<(Vec<f64>, Frozen)>) {
    if relieved {
        (Mixing::Relieved, Some((g, next)))
    } else if outer_loop && k + 1 < stages {
        // Continuation (penalties, friction regularization): the map changes with each
        // stage, so no mixing yet.
        let mixing = Mixing::Continuation {
            next: k + 1,
            stages,
        };
        (mixing, Some((g, next)))
    } else if outer_loop {
        let (mixed, how) = mixer.next(z, &g, counted);
        let frozen = Frozen::unflatten(&mixed, n_points, n_locking);
        (how, Some((mixed, frozen)))
    } else {
        (Mixing::None, None)
    }
}

/// A mixer with no history, keeping the counts of `mixer` (the map of the fixed point has
/// changed: a group of bodies was put at rest or released, see [`held::AtRest`]).
fn restarted(mixer: Mixer, settings: &OuterSettings) -> Mixer {
    let mut fresh = Mixer::new(settings);
    fresh.oscillations = mixer.oscillations;
    fresh.restarts = mixer.restarts;
    fresh
}
