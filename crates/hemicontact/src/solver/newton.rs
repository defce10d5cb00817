//! Globalized Newton method for the minimization of a convex energy `Π(x)` of the free
//! unknowns x, generic over the energy ([`ConvexEnergy`]).
//!
//! Each step evaluates gradient and Hessian, solves for the Newton direction Δ (the
//! energy's linear solver: for the convex problems of the outer loop, see
//! [`super::convex`]), and takes a step along it found by the line search
//! ([`super::line_search`]: the full step if it satisfies the Armijo condition, else a
//! bracketing secant search).
//! It stops when the residual ‖∇Π(x)‖ is below `residual_tolerance` times the energy's
//! force scale ([`ConvexEnergy::residual`]: body by body), so the criterion is
//! dimensionless. Once the residual stops falling (or a line search fails), it is measured
//! above the round-off floors of its entries ([`ConvexEnergy::discount_round_off`],
//! [`super::round_off`]).

pub use super::convex_energy::ConvexEnergy;
use super::line_search::LineSearch;
pub use super::settings::{NewtonSettings, MAX_BACKTRACKS, MAX_PCG_ITERATIONS};
use super::timings::Timings;
use crate::error::{Error, Result};
use serde::Serialize;
use std::time::Instant;

/// One Newton step.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NewtonStep {
    /// Outer iteration this step belongs to.
    pub outer: usize,
    /// Euclidean norm of the residual (gradient on free DOFs) before the step (N).
    pub residual: f64,
    /// Energy before the step (J).
    pub energy: f64,
    /// Line-search step length taken (1 = full Newton step).
    pub step_length: f64,
    /// Whether the Hessian was refactorized for this step.
    pub refactorized: bool,
    /// Conjugate-gradient iterations (0: direct solve with the factorization).
    pub pcg_iterations: usize,
}

/// How far above the tolerance a stagnating residual may be taken as the round-off floor.
const ROUND_OFF_MARGIN: f64 = 1e3;

/// Outcome of one Newton solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonOutcome {
    /// Whether the residual criterion was met.
    pub converged: bool,
    /// Newton steps taken.
    pub steps: usize,
    /// Final residual (N).
    pub residual: f64,
    /// Energy at the final iterate (J).
    pub energy: f64,
    /// Force scale of the residual criterion (N).
    pub force_scale: f64,
}

/// What a Newton solve records as it goes, for the caller's report: its steps, its
/// timings, the last residual and tolerance, and the round-off floor if it stopped at one.
#[derive(Clone, Debug, Default)]
pub struct NewtonRecord {
    /// Outer iteration the steps are tagged with.
    pub outer: usize,
    /// Steps taken before this solve (in earlier outer iterations), for messages that
    /// count steps over the whole run.
    pub first_step: usize,
    /// The steps taken.
    pub steps: Vec<NewtonStep>,
    /// Time per phase (assembly, factorization, solve, line search).
    pub timings: Timings,
    /// Residual norm at the last evaluation (N).
    pub residual: f64,
    /// Residual tolerance applied at the last evaluation (N).
    pub residual_tolerance: f64,
    /// Relative residual at which the solve stopped at the round-off floor above the
    /// tolerance (0: it did not).
    pub round_off_floor: f64,
}

/// Minimizes `energy` from `x` to the relative residual tolerance `tolerance`; on return
/// `x` is the last iterate. Steps and timings go to `record`.
///
/// # Errors
/// [`Error::Breakdown`] if the energy or residual is not finite, and the errors of
/// [`ConvexEnergy::newton_direction`] and [`ConvexEnergy::accept`].
pub fn minimize<E: ConvexEnergy + ?Sized>(
    energy: &mut E,
    x: &mut [f64],
    settings: &NewtonSettings,
    tolerance: f64,
    record: &mut NewtonRecord,
) -> Result<NewtonOutcome> {
    let n = energy.dimension();
    let mut delta = vec![0.0; n];
    let mut r_neg = vec![0.0; n];
    let mut trial = x.to_vec();
    let line_search = LineSearch {
        armijo: settings.armijo,
        max_trials: settings.max_backtracks,
    };
    let mut steps = 0;
    let mut prev_res = f64::INFINITY;
    let mut last_full = false;
    // Energy of an evaluation at `x` left by the line search, if any, and whether it
    // included the Hessian.
    let mut evaluated: Option<(f64, bool)> = None;
    // Whether the last line search failed at this iterate, which may be round-off.
    let mut retry = false;
    loop {
        let t = Instant::now();
        let (value, with_hessian) = match evaluated.take() {
            Some(e) => e,
            None => (energy.evaluate(x, true), true),
        };
        record.timings.assembly += t.elapsed().as_secs_f64();
        let (raw, raw_scale) = energy.residual();
        // A residual that stopped falling may be round-off: then the entries at their
        // round-off floor count as zero, and the regions' resultants count
        // (`discount_round_off`, see `super::round_off`).
        let stalled = retry || (steps > 0 && raw > 0.5 * prev_res);
        let discounted = stalled && raw > tolerance * raw_scale;
        let (res, force_scale) = if discounted {
            energy.discount_round_off();
            energy.residual()
        } else {
            (raw, raw_scale)
        };
        let tol = tolerance * force_scale;
        record.residual = res;
        record.residual_tolerance = tol;
        if !value.is_finite() || !res.is_finite() || !raw.is_finite() {
            return Err(Error::Breakdown(format!(
                "energy {value:e} / residual {raw:e} at Newton step {}",
                record.first_step + record.steps.len()
            )));
        }
        // The round-off floor: with stiff penalties (exact constraints on fine meshes) the
        // gradient's own round-off, which grows like √N, can exceed the tolerance. A full
        // Newton step from a residual within 10³ of the tolerance that fails to halve it
        // shows that floor (a genuine Newton step near the solution gains digits); the solve
        // then counts as converged at the residual reached, which the report and the
        // certificate state.
        let floor = steps > 0
            && last_full
            && raw <= ROUND_OFF_MARGIN * settings.residual_tolerance * raw_scale
            && raw > 0.5 * prev_res;
        if res <= tol || floor || steps == settings.max_iterations {
            if floor && res > tol {
                record.round_off_floor = record.round_off_floor.max(raw / raw_scale);
            }
            return Ok(NewtonOutcome {
                converged: res <= tol || floor,
                steps,
                residual: res,
                energy: value,
                force_scale,
            });
        }
        prev_res = raw;
        if !with_hessian {
            // The line search evaluated this point without the Hessian (it expected the
            // step to converge): evaluate it now.
            let t = Instant::now();
            energy.evaluate(x, true);
            if discounted {
                energy.discount_round_off();
            }
            record.timings.assembly += t.elapsed().as_secs_f64();
        }
        for (d, ri) in r_neg.iter_mut().zip(energy.gradient()) {
            *d = -ri;
        }
        // Forcing term: accurate enough to reach the tolerance in one step if the problem
        // were quadratic, never looser than `pcg_tolerance`.
        let (res_f, scale_f) = energy.forcing_residual();
        let eta = (0.1 * tolerance * scale_f / res_f).clamp(1e-12, settings.pcg_tolerance);
        let linear = energy.newton_direction(&r_neg, &mut delta, eta, &mut record.timings)?;
        let slope = energy.dot(energy.gradient(), &delta);
        let t = Instant::now();
        // The full step is evaluated with the Hessian, for the next Newton step — unless
        // the factorization was reused unchanged (the active sets are settled, so the full
        // step of the piecewise quadratic energy most likely converges and the Hessian
        // would be wasted).
        let hessian_at_full = linear.refactorized || linear.pcg_iterations > 0;
        let found =
            line_search.search(energy, x, &delta, &mut trial, value, slope, hessian_at_full);
        record.timings.line_search += t.elapsed().as_secs_f64();
        // A line search that fails may fail on round-off (another body's, moved by it): once
        // more from this iterate with the round-off discounted.
        retry = found.step.is_none() && !discounted;
        if retry {
            evaluated = None;
            continue;
        }
        evaluated = found.evaluated;
        steps += 1;
        last_full = found.step == Some(1.0);
        record.steps.push(NewtonStep {
            outer: record.outer,
            residual: res,
            energy: value,
            step_length: found.step.unwrap_or(0.0),
            refactorized: linear.refactorized,
            pcg_iterations: linear.pcg_iterations,
        });
        let Some(step) = found.step else {
            return Ok(NewtonOutcome {
                converged: false,
                steps,
                residual: res,
                energy: value,
                force_scale,
            });
        };
        for (xi, di) in x.iter_mut().zip(&delta) {
            *xi += step * di;
        }
        energy.accept(x)?;
    }
}
