//! The convexification outer loop and its acceleration.
//!
//! Outer iteration k freezes, at every contact point, the friction bound `F_i^k` (which
//! depends on the slip through μ, and for Coulomb-type bounds on the pressure) and the
//! linear term `b_i^k = F_i^k ∇h(u_τ,i^k)` of the difference-of-convex split, then minimizes
//! the convex energy `E_k` by Newton's method. This is a fixed-point iteration `z ↦ G(z)`
//! on the vector z of frozen quantities (`G(z)` = the quantities evaluated at the
//! minimizer of `E_z`). It converges only linearly, and for large friction coefficients
//! the plain iteration can fall into a two-state oscillation; therefore:
//!
//! - **Anderson acceleration** (default, depth 5) mixes the last iterates to cancel the
//!   dominant error modes. It is safeguarded: when the fixed-point residual `‖G(z) − z‖`
//!   grows, the history is dropped and a damped step `z + ω (G(z) − z)` with `ω = ½` is
//!   taken instead. Bounds are projected to `F ≥ 0`, which keeps every `E_k` convex.
//! - With `acceleration = "none"`, oscillation or stagnation is *detected* (the residual
//!   fails to drop by 5 % over two iterations, three times in a row) and cured by halving
//!   the relaxation factor ω (down to 1/8); the report records it.
//! - **Inexact inner solves**: early convex problems need not be solved to full accuracy.
//!   The Newton tolerance of iteration k is `clamp(10⁻² δ_{k−1}, tol_N, 10⁻³)` with
//!   `δ_{k−1}` the last relative change; convergence is only declared after a solve at the
//!   final Newton tolerance `tol_N`.
//!
//! The loop stops when the relative change `‖u^k − u^{k−1}‖_E / ‖u^k‖_E` falls below
//! `tolerance` (default 1e-10) *and* so does the relative fixed-point residual
//! `‖G(z) − z‖ / ‖G(z)‖` (a mixed iterate can stall — `u` stops changing while the frozen
//! quantities are still inconsistent with it — so the change of u alone is not a proof of
//! convergence); otherwise it reports non-convergence after `max_iterations`.

use crate::assembly::contact::Frozen;
use serde::{Deserialize, Serialize};

/// Acceleration of the outer fixed-point iteration; see the module documentation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Acceleration {
    /// Plain (relaxed) fixed point with oscillation detection.
    None,
    /// Safeguarded Anderson acceleration.
    #[default]
    Anderson,
}

/// Outer-loop settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OuterSettings {
    /// Maximum number of outer iterations (convex solves). Default 100.
    pub max_iterations: usize,
    /// Tolerance on the relative change of u in the energy norm. Default 1e-10.
    pub tolerance: f64,
    /// Acceleration. Default Anderson.
    pub acceleration: Acceleration,
    /// Anderson depth (number of differences kept). Default 5.
    pub depth: usize,
    /// Initial relaxation factor ω ∈ (0, 1] of the plain fixed point. Default 1.
    pub relaxation: f64,
    /// Deprecated: the numerical regularization of the norm in the friction potential of
    /// every contact part, now a parameter of the friction law
    /// ([`crate::contact::NormTreatment::Smoothed`], scenario key `[contact.friction]
    /// regularization`); read by the scenario loader only. `None` unless given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_regularization: Option<f64>,
    /// Solve early convex problems inexactly. Default true.
    pub inexact: bool,
}

impl Default for OuterSettings {
    fn default() -> Self {
        OuterSettings {
            max_iterations: 100,
            tolerance: 1e-10,
            acceleration: Acceleration::Anderson,
            depth: 5,
            relaxation: 1.0,
            friction_regularization: None,
            inexact: true,
        }
    }
}

/// Flattens frozen quantities into the fixed-point vector
/// `z = [F (n), b (2n), λ_contact (n), τ (2n), λ_locking (cells or 0)]`.
pub fn flatten(f: &Frozen) -> Vec<f64> {
    let n = f.bound.len();
    let mut z = Vec::with_capacity(6 * n + f.locking.len());
    z.extend_from_slice(&f.bound);
    for b in &f.linear {
        z.extend_from_slice(b);
    }
    z.extend_from_slice(&f.pressure);
    for t in &f.traction {
        z.extend_from_slice(t);
    }
    z.extend_from_slice(&f.locking);
    z
}

/// Inverse of [`flatten`] for `n` contact points and `n_cells` locking multipliers,
/// projecting bounds and multipliers onto their admissible sets (`F ≥ 0`, `λ ≥ 0`): a mixed
/// iterate then still defines convex subproblems.
pub fn unflatten(z: &[f64], n: usize, n_cells: usize) -> Frozen {
    let bound = z[..n].iter().map(|&x| x.max(0.0)).collect();
    let linear = (0..n).map(|i| [z[n + 2 * i], z[n + 2 * i + 1]]).collect();
    let pressure = z[3 * n..4 * n].iter().map(|&x| x.max(0.0)).collect();
    let traction = (0..n)
        .map(|i| [z[4 * n + 2 * i], z[4 * n + 2 * i + 1]])
        .collect();
    let locking = z[6 * n..6 * n + n_cells]
        .iter()
        .map(|&x| x.max(0.0))
        .collect();
    Frozen {
        bound,
        linear,
        pressure,
        traction,
        locking,
    }
}

fn norm(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// The fixed-point mixer: produces the next frozen vector from the current one and its
/// image; see the module documentation.
#[derive(Clone, Debug)]
pub struct Mixer {
    acceleration: Acceleration,
    depth: usize,
    /// Current relaxation factor ω.
    pub omega: f64,
    f_hist: Vec<Vec<f64>>,
    g_hist: Vec<Vec<f64>>,
    residuals: Vec<f64>,
    stalls: usize,
    /// Number of times oscillation or stagnation was detected.
    pub oscillations: usize,
    /// Number of Anderson restarts (residual increase).
    pub restarts: usize,
}

impl Mixer {
    /// A mixer for the given settings.
    pub fn new(s: &OuterSettings) -> Self {
        Mixer {
            acceleration: s.acceleration,
            depth: s.depth.max(1),
            omega: s.relaxation.clamp(1e-3, 1.0),
            f_hist: Vec::new(),
            g_hist: Vec::new(),
            residuals: Vec::new(),
            stalls: 0,
            oscillations: 0,
            restarts: 0,
        }
    }

    /// Next iterate from `z` and `g = G(z)`; returns it with a short description of the
    /// step taken.
    pub fn next(&mut self, z: &[f64], g: &[f64]) -> (Vec<f64>, String) {
        let f: Vec<f64> = g.iter().zip(z).map(|(a, b)| a - b).collect();
        let res = norm(&f);
        let prev = self.residuals.last().copied();
        self.residuals.push(res);
        match self.acceleration {
            Acceleration::None => {
                let k = self.residuals.len();
                if k >= 3 && res > 0.95 * self.residuals[k - 3] {
                    self.stalls += 1;
                } else {
                    self.stalls = 0;
                }
                let mut note = format!("fixed point ω = {}", self.omega);
                if self.stalls >= 3 && self.omega > 0.125 {
                    self.omega *= 0.5;
                    self.stalls = 0;
                    self.oscillations += 1;
                    note = format!(
                        "oscillation/stagnation detected: relaxation ω = {}",
                        self.omega
                    );
                }
                let next = z.iter().zip(&f).map(|(a, b)| a + self.omega * b).collect();
                (next, note)
            }
            Acceleration::Anderson => {
                if prev.is_some_and(|p| res >= p) {
                    // Safeguard: the residual did not decrease.
                    return self.restart(z, &f, g, "residual did not decrease");
                }
                self.f_hist.push(f.clone());
                self.g_hist.push(g.to_vec());
                if self.f_hist.len() > self.depth + 1 {
                    self.f_hist.remove(0);
                    self.g_hist.remove(0);
                }
                let m = self.f_hist.len() - 1;
                if m == 0 {
                    return (g.to_vec(), "fixed point".into());
                }
                // Differences ΔF_j = f_{j+1} − f_j, ΔG_j = g_{j+1} − g_j.
                let df: Vec<Vec<f64>> = (0..m)
                    .map(|j| {
                        self.f_hist[j + 1]
                            .iter()
                            .zip(&self.f_hist[j])
                            .map(|(a, b)| a - b)
                            .collect()
                    })
                    .collect();
                let mut a = vec![vec![0.0; m]; m];
                let mut rhs = vec![0.0; m];
                for i in 0..m {
                    for j in 0..m {
                        a[i][j] = df[i].iter().zip(&df[j]).map(|(x, y)| x * y).sum();
                    }
                    rhs[i] = df[i].iter().zip(&f).map(|(x, y)| x * y).sum();
                }
                let trace: f64 = (0..m).map(|i| a[i][i]).sum();
                for (i, row) in a.iter_mut().enumerate() {
                    row[i] += 1e-12 * trace + f64::MIN_POSITIVE;
                }
                let Some(gamma) = solve_dense(a, rhs) else {
                    return (g.to_vec(), "fixed point (singular Anderson system)".into());
                };
                let mut next = g.to_vec();
                for (j, gj) in gamma.iter().enumerate() {
                    for (k, x) in next.iter_mut().enumerate() {
                        *x -= gj * (self.g_hist[j + 1][k] - self.g_hist[j][k]);
                    }
                }
                // Stagnation: the mixed iterate does not move although the residual is not
                // small. Restart from a damped step.
                let moved = norm(&next.iter().zip(z).map(|(a, b)| a - b).collect::<Vec<_>>());
                if moved < 1e-3 * res {
                    return self.restart(z, &f, g, "Anderson stagnated");
                }
                (next, format!("Anderson, depth {m}"))
            }
        }
    }
}

impl Mixer {
    /// Drops the Anderson history (keeping the current point) and takes the damped step
    /// `z + ½ (G(z) − z)`.
    fn restart(&mut self, z: &[f64], f: &[f64], g: &[f64], why: &str) -> (Vec<f64>, String) {
        self.restarts += 1;
        self.f_hist.clear();
        self.g_hist.clear();
        self.f_hist.push(f.to_vec());
        self.g_hist.push(g.to_vec());
        let next = z.iter().zip(f).map(|(a, b)| a + 0.5 * b).collect();
        (
            next,
            format!("{why}: Anderson restart, damped step ω = 0.5"),
        )
    }
}

/// Solves the small dense SPD-ish system `a x = b` by Gaussian elimination with partial
/// pivoting; `None` if singular.
fn solve_dense(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    let n = b.len();
    for k in 0..n {
        let p = (k..n).max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))?;
        if a[p][k].abs() == 0.0 || !a[p][k].is_finite() {
            return None;
        }
        a.swap(k, p);
        b.swap(k, p);
        for i in k + 1..n {
            let l = a[i][k] / a[k][k];
            for j in k..n {
                a[i][j] -= l * a[k][j];
            }
            b[i] -= l * b[k];
        }
    }
    let mut x = vec![0.0; n];
    for k in (0..n).rev() {
        let s: f64 = (k + 1..n).map(|j| a[k][j] * x[j]).sum();
        x[k] = (b[k] - s) / a[k][k];
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Anderson acceleration solves a linear contraction (fixed point of `x ↦ Mx + c`)
    /// far faster than the plain iteration.
    #[test]
    fn anderson_accelerates_a_linear_contraction() {
        let m = [[0.9, 0.05], [-0.05, -0.85]];
        let c = [1.0, 2.0];
        let g = |z: &[f64]| {
            vec![
                m[0][0] * z[0] + m[0][1] * z[1] + c[0],
                m[1][0] * z[0] + m[1][1] * z[1] + c[1],
            ]
        };
        let s = OuterSettings::default();
        let mut mixer = Mixer::new(&s);
        let mut z = vec![0.0, 0.0];
        let mut iters = 0;
        while norm(&g(&z).iter().zip(&z).map(|(a, b)| a - b).collect::<Vec<_>>()) > 1e-12 {
            let gz = g(&z);
            z = mixer.next(&z, &gz).0;
            iters += 1;
            assert!(iters < 20, "Anderson did not converge");
        }
    }
}
