//! The line search of the Newton method: a step length t along the Newton direction Δ for
//! `φ(t) = Π(x + tΔ)`, convex and piecewise smooth.
//!
//! The full step is taken if it satisfies the Armijo condition `φ(1) ≤ φ(0) + c φ'(0)`.
//! Otherwise a bracketing secant search (safeguarded by bisection) on `φ'` — exact for the
//! piecewise quadratic energies here once the kinks on the line are passed — looks for a
//! step with sufficient decrease (Armijo) that is no longer steeply descending (weak Wolfe
//! curvature condition `φ'(t) ≥ 0.9 φ'(0)`). Halving would stop at the first power of two
//! below the kink where a stiff penalty or contact term switches on, one Newton step per
//! halving.

use super::convex_energy::ConvexEnergy;

/// Settings of the line search.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineSearch {
    /// Armijo sufficient-decrease constant c in (0, ½).
    pub armijo: f64,
    /// Trial steps beyond the full step.
    pub max_trials: usize,
}

/// The step found by [`LineSearch::search`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Found {
    /// The step length, `None` if no acceptable step was found.
    pub step: Option<f64>,
    /// If the accepted step is the full one and the energy was left evaluated there: its
    /// value and whether the evaluation included the Hessian (the next Newton step reuses
    /// it).
    pub evaluated: Option<(f64, bool)>,
}

impl LineSearch {
    /// Searches a step along `delta` from `x` (energy `value`, slope `φ'(0) = slope < 0`),
    /// evaluating the trial points in `trial`; the full step is evaluated with the Hessian
    /// if `hessian_at_full`. On return the energy is left evaluated at the last trial.
    #[allow(clippy::too_many_arguments)]
    pub fn search<E: ConvexEnergy + ?Sized>(
        &self,
        energy: &mut E,
        x: &[f64],
        delta: &[f64],
        trial: &mut [f64],
        value: f64,
        slope: f64,
        hessian_at_full: bool,
    ) -> Found {
        let negligible = -slope <= 1e-14 * value.abs();
        let mut step = 1.0;
        let mut evaluated = None;
        let (mut a, mut da) = (0.0, slope);
        let (mut b, mut db) = (1.0, f64::NAN);
        let mut side = 0i8;
        let mut best: Option<f64> = None;
        for iter in 0..=self.max_trials {
            for ((t, xi), di) in trial.iter_mut().zip(x).zip(delta) {
                *t = xi + step * di;
            }
            let full = iter == 0;
            let hessian = full && hessian_at_full;
            let e_trial = energy.evaluate(trial, hessian);
            // Below round-off of the energy the Armijo test is meaningless (it holds
            // whatever the step): the directional derivative decides alone.
            let armijo = e_trial <= value + self.armijo * step * slope && !negligible;
            if full && armijo {
                return Found {
                    step: Some(step),
                    evaluated: Some((e_trial, hessian)),
                };
            }
            let d = energy.dot(energy.gradient(), delta);
            // Near the solution the energy change drowns in the round-off of the energy (a
            // sum over all cells with cancellation): then the directional derivative decides
            // — the step is accepted if it at least halves |φ'|.
            let noise = negligible || (e_trial - value).abs() <= 1e-12 * value.abs();
            if noise && d.abs() <= 0.5 * slope.abs() {
                if full {
                    evaluated = Some((e_trial, hessian));
                }
                return Found {
                    step: Some(step),
                    evaluated,
                };
            }
            if !e_trial.is_finite() || !d.is_finite() {
                // Outside the domain of finite energy: shrink blindly.
                b = step;
                db = f64::NAN;
                step = a + 0.5 * (b - a);
                continue;
            }
            if armijo && d >= 0.9 * slope {
                return Found {
                    step: Some(step),
                    evaluated: None,
                };
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
        // The longest step with sufficient decrease found, if any; where the energy could
        // not tell and the derivative did not settle either (both at round-off), the full
        // step.
        Found {
            step: best.or(negligible.then_some(1.0)),
            evaluated: None,
        }
    }
}
