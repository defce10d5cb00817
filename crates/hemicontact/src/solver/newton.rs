//! Globalized Newton method for the minimization of a convex total energy.
//!
//! Each step assembles gradient and Hessian, refactorizes the Hessian numerically on the
//! fixed pattern, solves for the Newton direction Δ, and takes the largest step `t ∈
//! {1, ½, ¼, …}` that satisfies the Armijo condition `Π(u + tΔ) ≤ Π(u) + c t ∇Π·Δ`.
//! It stops when the residual (gradient on the free DOFs) is below `residual_tolerance`
//! times the force scale `max(‖f_ext‖, ‖∇W‖)` (‖∇W‖: internal forces over all DOFs,
//! reactions included), so the criterion is dimensionless and meaningful for load-driven
//! and displacement-driven problems alike.

use super::report::{NewtonStep, SolveReport};
use super::System;
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
    /// Maximum number of step halvings per line search. Default 40 (t ≥ 1e-12).
    pub max_backtracks: usize,
}

impl Default for NewtonSettings {
    fn default() -> Self {
        NewtonSettings {
            max_iterations: 50,
            residual_tolerance: 1e-10,
            armijo: 1e-4,
            max_backtracks: 40,
        }
    }
}

fn norm(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// Minimizes the total energy of `problem` starting from `u` (which must hold the prescribed
/// Dirichlet values). On return `u` is the last iterate and `report` says whether it
/// converged.
///
/// # Errors
/// [`Error::NotPositiveDefinite`] if a Hessian cannot be factorized, [`Error::Breakdown`] if
/// the energy or residual is not finite.
pub fn minimize(
    system: &mut System,
    problem: &Problem,
    u: &mut [f64],
    settings: &NewtonSettings,
    report: &mut SolveReport,
) -> Result<()> {
    let n = system.dofs.n_free();
    let mut r = vec![0.0; n];
    let mut delta = vec![0.0; n];
    let mut trial = u.to_vec();
    let f_scale = norm(&system.f_ext);
    report.converged = false;
    for _ in 0..=settings.max_iterations {
        let t = Instant::now();
        let energy = system.evaluate(problem, u, true);
        report.timings.assembly += t.elapsed().as_secs_f64();
        system.reduce(&system.grad, &mut r);
        let res = norm(&r);
        // Internal forces over all DOFs: gradient + f_ext.
        let internal = system
            .grad
            .iter()
            .zip(&system.f_ext)
            .map(|(g, f)| (g + f).powi(2))
            .sum::<f64>()
            .sqrt();
        let tol = settings.residual_tolerance * f_scale.max(internal).max(f64::MIN_POSITIVE);
        report.residual = res;
        report.residual_tolerance = tol;
        if !energy.is_finite() || !res.is_finite() {
            return Err(Error::Breakdown(format!(
                "energy {energy} / residual {res} at Newton step {}",
                report.newton.len()
            )));
        }
        if res <= tol {
            report.converged = true;
            report.message = format!("converged in {} Newton steps", report.newton.len());
            return Ok(());
        }
        if report.newton.len() == settings.max_iterations {
            break;
        }
        let t = Instant::now();
        system.cholesky.factorize(&system.pattern, &system.hess)?;
        report.timings.factorization += t.elapsed().as_secs_f64();
        let t = Instant::now();
        for (d, ri) in delta.iter_mut().zip(&r) {
            *d = -ri;
        }
        system.cholesky.solve_in_place(&mut delta);
        report.timings.solve += t.elapsed().as_secs_f64();
        let slope: f64 = r.iter().zip(&delta).map(|(a, b)| a * b).sum();
        let t = Instant::now();
        let mut step = 1.0;
        let mut accepted = false;
        for _ in 0..=settings.max_backtracks {
            for (dof, &eq) in system.dofs.equations().iter().enumerate() {
                if eq != crate::fem::dofs::FIXED {
                    trial[dof] = u[dof] + step * delta[eq as usize];
                }
            }
            let e_trial = system.evaluate(problem, &trial, false);
            // Below round-off of the energy, the Armijo test is meaningless: accept.
            let negligible = -slope <= 1e-14 * energy.abs();
            if e_trial <= energy + settings.armijo * step * slope || negligible {
                accepted = true;
                break;
            }
            step *= 0.5;
        }
        report.timings.line_search += t.elapsed().as_secs_f64();
        report.newton.push(NewtonStep {
            residual: res,
            energy,
            step_length: if accepted { step } else { 0.0 },
        });
        if !accepted {
            report.message = format!(
                "line search failed at Newton step {} (residual {res:e}, tolerance {tol:e})",
                report.newton.len()
            );
            return Ok(());
        }
        for (dof, &eq) in system.dofs.equations().iter().enumerate() {
            if eq != crate::fem::dofs::FIXED {
                u[dof] = trial[dof];
            }
        }
    }
    report.message = format!(
        "not converged: {} Newton steps, residual {:e} > tolerance {:e}",
        settings.max_iterations, report.residual, report.residual_tolerance
    );
    Ok(())
}
