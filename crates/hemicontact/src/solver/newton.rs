//! Globalized Newton method for the minimization of a convex total energy.
//!
//! Each step assembles gradient and Hessian, solves for the Newton direction Δ (see
//! [`System::linear_solve`]: the last factorization is reused when the Hessian is unchanged,
//! used as a PCG preconditioner when it changed a little, and refactorized otherwise), and
//! takes the full step if it satisfies the Armijo condition `Π(u + tΔ) ≤ Π(u) + c t ∇Π·Δ`,
//! else a step found by a bracketing secant search on the directional derivative that
//! satisfies the Armijo and the weak Wolfe curvature conditions.
//! It stops when the residual (gradient on the free DOFs) is below `residual_tolerance`
//! times the force scale `max(‖f_ext‖, ‖∇W‖, f_D)` (‖∇W‖: internal forces over all DOFs,
//! reactions included; f_D the force unit of the prescribed displacements, see
//! [`System::force_floor`]), so the criterion is dimensionless and meaningful for
//! load-driven and displacement-driven problems alike, including stress-free ones.

use super::report::{NewtonStep, SolveReport};
use super::System;
use crate::assembly::contact::Frozen;
use crate::error::{Error, Result};
use crate::problem::Problem;
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// Newton method settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct NewtonSettings {
    /// Maximum number of Newton steps. Default 50: a convex piecewise-quadratic energy
    /// converges in far fewer; hitting the cap signals a modelling problem.
    pub max_iterations: usize,
    /// Relative residual tolerance (dimensionless, relative to the force scale).
    /// Default 1e-10, a few orders above round-off for the systems solved here.
    pub residual_tolerance: f64,
    /// Armijo sufficient-decrease constant in (0, ½). Default 1e-4 (Nocedal–Wright).
    pub armijo: f64,
    /// Maximum number of trial steps per line search beyond the full step. Default 40.
    pub max_backtracks: usize,
    /// Maximum conjugate-gradient iterations preconditioned by the last factorization
    /// before the Hessian is refactorized. Default 8: one triangular solve costs about a
    /// tenth of a factorization, and changes of the active sets (locking cells, contact and
    /// stick nodes) are low-rank updates that PCG resolves in about as many iterations as
    /// their rank. 0 disables PCG (every changed Hessian is refactorized).
    pub pcg_iterations: usize,
    /// Largest relative residual PCG may stop at (the loosest forcing term of the inexact
    /// Newton method; the actual one is `min(pcg_tolerance, 0.1 · tolerance / residual)`, so
    /// the last steps are solved as accurately as the convergence criterion needs). Default
    /// 1e-3: near the solution Newton then still gains three digits per step.
    pub pcg_tolerance: f64,
}

impl Default for NewtonSettings {
    fn default() -> Self {
        NewtonSettings {
            max_iterations: 50,
            residual_tolerance: 1e-10,
            armijo: 1e-4,
            max_backtracks: 40,
            pcg_iterations: 8,
            pcg_tolerance: 1e-3,
        }
    }
}

impl NewtonSettings {
    /// Checks every setting against its range.
    ///
    /// # Errors
    /// [`Error::Invalid`] naming the setting (`residual_tolerance` in (0, 1), `armijo` in
    /// (0, ½), `pcg_tolerance` in [1e-12, 1), `max_iterations` ≥ 1).
    pub fn validate(&self) -> Result<()> {
        use crate::error::require;
        let tol = self.residual_tolerance;
        require(
            tol.is_finite() && tol > 0.0 && tol < 1.0,
            "residual_tolerance",
            tol,
            "a number in (0, 1)",
        )?;
        require(
            self.armijo > 0.0 && self.armijo < 0.5,
            "armijo",
            self.armijo,
            "a number in (0, 0.5)",
        )?;
        require(
            self.pcg_tolerance >= 1e-12 && self.pcg_tolerance < 1.0,
            "pcg_tolerance",
            self.pcg_tolerance,
            "a number in [1e-12, 1)",
        )?;
        require(
            self.max_iterations > 0,
            "max_iterations",
            0,
            "a positive integer",
        )
    }
}

/// `∇Π·Δ` on the free DOFs, from the gradient of the last evaluation.
fn directional_derivative(system: &System, delta: &[f64]) -> f64 {
    system
        .dofs
        .equations()
        .iter()
        .zip(&system.grad)
        .filter(|(&eq, _)| eq != crate::fem::dofs::FIXED)
        .map(|(&eq, g)| g * delta[eq as usize])
        .sum()
}

/// How far above the tolerance a stagnating residual may be taken as the round-off floor.
const ROUND_OFF_MARGIN: f64 = 1e3;

fn norm(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

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
    /// Force scale of the residual criterion, `max(‖f_ext‖, ‖∇W‖)` (N).
    pub force_scale: f64,
}

/// Minimizes the convexified energy of `problem` for the frozen quantities `frozen`,
/// starting from `u` (which must hold the prescribed Dirichlet values), to the relative
/// residual tolerance `tolerance`. On return `u` is the last iterate; the steps are appended
/// to `report.newton` (tagged with `outer`), and timings accumulated.
///
/// # Errors
/// [`Error::NotPositiveDefinite`] if a Hessian cannot be factorized, [`Error::Breakdown`] if
/// the energy or residual is not finite, [`Error::ContactLost`] if a body whose free rigid
/// motions only contact carries leaves its contact.
#[allow(clippy::too_many_arguments)]
pub fn minimize(
    system: &mut System,
    problem: &Problem,
    u: &mut [f64],
    frozen: &Frozen,
    settings: &NewtonSettings,
    tolerance: f64,
    outer: usize,
    report: &mut SolveReport,
) -> Result<NewtonOutcome> {
    let n = system.dofs.n_free();
    let mut r = vec![0.0; n];
    let mut delta = vec![0.0; n];
    let mut r_neg = vec![0.0; n];
    let mut trial = u.to_vec();
    let f_scale = norm(&system.f_ext);
    let mut steps = 0;
    let mut prev_res = f64::INFINITY;
    let mut last_full = false;
    // Energy of an evaluation at `u` left by the line search, if any, and whether it
    // included the Hessian.
    let mut evaluated: Option<(f64, bool)> = None;
    loop {
        let t = Instant::now();
        let (energy, with_hessian) = match evaluated.take() {
            Some(e) => e,
            None => (system.evaluate(problem, u, frozen, true), true),
        };
        report.timings.assembly += t.elapsed().as_secs_f64();
        system.reduce(&system.grad, &mut r);
        let res = norm(&r);
        // Internal forces over all DOFs: gradient + f_ext.
        let internal = system
            .grad_bulk
            .iter()
            .zip(&system.f_ext)
            .map(|(g, f)| (g + f).powi(2))
            .sum::<f64>()
            .sqrt();
        let force_scale = f_scale
            .max(internal)
            .max(system.force_floor)
            .max(f64::MIN_POSITIVE);
        let tol = tolerance * force_scale;
        report.residual = res;
        report.residual_tolerance = tol;
        if !energy.is_finite() || !res.is_finite() {
            return Err(Error::Breakdown(format!(
                "energy {energy:e} / residual {res:e} at Newton step {}",
                report.newton.len()
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
            && res <= ROUND_OFF_MARGIN * settings.residual_tolerance * force_scale
            && res > 0.5 * prev_res;
        if res <= tol || floor || steps == settings.max_iterations {
            if floor && res > tol {
                report.round_off_floor = report.round_off_floor.max(res / force_scale);
            }
            return Ok(NewtonOutcome {
                converged: res <= tol || floor,
                steps,
                residual: res,
                energy,
                force_scale,
            });
        }
        prev_res = res;
        if !with_hessian {
            // The line search evaluated this point without the Hessian (it expected the
            // step to converge): assemble it now.
            let t = Instant::now();
            system.evaluate(problem, u, frozen, true);
            report.timings.assembly += t.elapsed().as_secs_f64();
        }
        for (d, ri) in r_neg.iter_mut().zip(&r) {
            *d = -ri;
        }
        // Forcing term: accurate enough to reach the tolerance in one step if the problem
        // were quadratic, never looser than `pcg_tolerance`.
        let eta = (0.1 * tol / res).clamp(1e-12, settings.pcg_tolerance);
        let linear = system.linear_solve(&r_neg, &mut delta, eta, settings, &mut report.timings)?;
        let slope: f64 = r.iter().zip(&delta).map(|(a, b)| a * b).sum();
        let t = Instant::now();
        // Line search on φ(t) = Π(u + tΔ), convex and piecewise smooth: the full step with
        // the Hessian (so the next Newton step can reuse the evaluation), else a bracketing
        // secant search (safeguarded by bisection) on φ'(t) — exact for the piecewise quadratic energies here
        // once the kinks on the line are passed — for a step with sufficient decrease
        // (Armijo) that is no longer steeply descending (weak Wolfe curvature condition
        // φ'(t) ≥ 0.9 φ'(0)). Halving would stop at the first power of two below the kink
        // where a stiff penalty or contact term switches on, one Newton step per halving.
        let negligible = -slope <= 1e-14 * energy.abs();
        let mut step = 1.0;
        let mut accepted = false;
        let (mut a, mut da) = (0.0, slope);
        let (mut b, mut db) = (1.0, f64::NAN);
        let mut side = 0i8;
        let mut best: Option<f64> = None;
        for iter in 0..=settings.max_backtracks {
            for (dof, &eq) in system.dofs.equations().iter().enumerate() {
                if eq != crate::fem::dofs::FIXED {
                    trial[dof] = u[dof] + step * delta[eq as usize];
                }
            }
            let full = iter == 0;
            // The full step is evaluated with the Hessian, for the next Newton step — unless
            // the factorization was reused unchanged (the active sets are settled, so the
            // full step of the piecewise quadratic energy most likely converges and the
            // Hessian would be wasted).
            let hessian = full && (linear.refactorized || linear.pcg_iterations > 0);
            let e_trial = system.evaluate(problem, &trial, frozen, hessian);
            let armijo = e_trial <= energy + settings.armijo * step * slope;
            // Below round-off of the energy, the Armijo test is meaningless: accept.
            if full && (armijo || negligible) {
                accepted = true;
                evaluated = Some((e_trial, hessian));
                break;
            }
            let d = directional_derivative(system, &delta);
            // Near the solution the energy change drowns in the round-off of the energy (a
            // sum over all cells with cancellation): then the directional derivative decides
            // — the step is accepted if it at least halves |φ'|.
            let noise = (e_trial - energy).abs() <= 1e-12 * energy.abs();
            if noise && d.abs() <= 0.5 * slope.abs() {
                accepted = true;
                if full {
                    evaluated = Some((e_trial, hessian));
                }
                break;
            }
            if !e_trial.is_finite() || !d.is_finite() {
                // Outside the domain of finite energy: shrink blindly.
                b = step;
                db = f64::NAN;
                step = a + 0.5 * (b - a);
                continue;
            }
            if armijo && (d >= 0.9 * slope || negligible) {
                accepted = true;
                break;
            }
            if armijo {
                best = Some(best.map_or(step, |s: f64| s.max(step)));
            }
            // Update the bracket [a, b] of the zero of φ' (φ'(a) < 0). When the same end
            // moves twice in a row, the secant is stuck against a steep kink (a stiff penalty
            // switching on): bisect, so the bracket at least halves every other trial.
            let repeated = (d < 0.0 && side == -1) || (d >= 0.0 && side == 1);
            if d < 0.0 {
                a = step;
                da = d;
                side = -1;
            } else {
                b = step;
                db = d;
                side = 1;
            }
            step = if repeated {
                side = 0;
                a + 0.5 * (b - a)
            } else if db.is_finite() && db > da {
                let t = a - da * (b - a) / (db - da);
                t.clamp(a + 1e-3 * (b - a), b - 1e-3 * (b - a))
            } else {
                a + 0.5 * (b - a)
            };
            if b - a <= 1e-12 {
                break;
            }
        }
        if !accepted {
            if let Some(s) = best {
                // The longest step with sufficient decrease found.
                step = s;
                accepted = true;
            }
        }
        report.timings.line_search += t.elapsed().as_secs_f64();
        steps += 1;
        last_full = accepted && step == 1.0;
        report.newton.push(NewtonStep {
            outer,
            residual: res,
            energy,
            step_length: if accepted { step } else { 0.0 },
            refactorized: linear.refactorized,
            pcg_iterations: linear.pcg_iterations,
        });
        if !accepted {
            return Ok(NewtonOutcome {
                converged: false,
                steps,
                residual: res,
                energy,
                force_scale,
            });
        }
        for (dof, &eq) in system.dofs.equations().iter().enumerate() {
            if eq != crate::fem::dofs::FIXED {
                u[dof] += step * delta[eq as usize];
            }
        }
        // A body whose free rigid motions only contact carries, pulled off that contact,
        // moves without bound: stop with `Error::ContactLost`.
        if system.rigid_shift > 0.0 {
            system.rigid.check_runaway(u, system.length_unit)?;
        }
    }
}
