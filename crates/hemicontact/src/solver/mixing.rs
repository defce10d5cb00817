//! Mixing of the outer fixed-point iteration `z ↦ G(z)` on the frozen quantities (see
//! [`super::outer`]): the next `z` from the current one and its image.
//!
//! - **Anderson acceleration** (default, depth 5) mixes the last iterates to cancel the
//!   dominant error modes. It is safeguarded: when the fixed-point residual `‖G(z) − z‖`
//!   grows, the history is dropped and a damped step `z + ω (G(z) − z)` with `ω = ½` is
//!   taken instead. Bounds are projected to `F ≥ 0`, which keeps every `E_k` convex.
//! - With `acceleration = "none"`, oscillation or stagnation is *detected* (the residual
//!   fails to drop by 5 % over two iterations, three times in a row) and cured by halving
//!   the relaxation factor ω (down to 1/8); the report records it.

use super::settings::{Acceleration, OuterSettings};
use crate::parallel::Share;
use serde::{Serialize, Serializer};

/// How the frozen quantities of the next outer iteration were formed (or why there is no
/// next iteration). Written to the report as its description ([`std::fmt::Display`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Mixing {
    /// No next iteration: the loop stopped after a converged convex solve (or the problem
    /// is a single convex problem).
    None,
    /// No next iteration: the convex solve at the final Newton tolerance did not converge.
    NewtonFailed,
    /// Continuation (penalties, friction regularization): the image `G(z)` is taken as it
    /// is, since the map changes with each stage.
    Continuation {
        /// The stage of the next iteration (1-based count of stages done).
        next: usize,
        /// Stages in all.
        stages: usize,
    },
    /// The first iteration of a body held by friction alone was solved with the load along
    /// its sliding motions balanced by uniformly distributed friction forces (see
    /// [`super::held`]): its image `G(z)`, whose bound carries that load, is taken as it is.
    Relieved,
    /// The plain fixed-point step `z ← G(z)`.
    FixedPoint,
    /// The relaxed fixed-point step `z ← z + ω (G(z) − z)`.
    Relaxed {
        /// The relaxation factor ω.
        omega: f64,
    },
    /// Oscillation or stagnation of the relaxed iteration detected: ω was halved.
    Oscillation {
        /// The new relaxation factor ω.
        omega: f64,
    },
    /// The Anderson step with `depth` differences.
    Anderson {
        /// Differences used.
        depth: usize,
    },
    /// The Anderson least-squares system was singular: plain fixed-point step.
    AndersonSingular,
    /// Anderson history dropped, damped step `z + ½ (G(z) − z)`.
    AndersonRestart {
        /// Why: the residual grew (`true`), or the mixed iterate stagnated (`false`).
        residual_grew: bool,
    },
}

impl std::fmt::Display for Mixing {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Mixing::None => Ok(()),
            Mixing::NewtonFailed => write!(f, "stop: Newton did not converge"),
            Mixing::Continuation { next, stages } => {
                write!(f, "continuation: stage {next} of {stages} next")
            }
            Mixing::Relieved => write!(
                f,
                "load along the motions only friction carries held by uniform friction in \
                 this iteration: image taken as it is"
            ),
            Mixing::FixedPoint => write!(f, "fixed point"),
            Mixing::Relaxed { omega } => write!(f, "fixed point ω = {omega}"),
            Mixing::Oscillation { omega } => {
                write!(f, "oscillation/stagnation detected: relaxation ω = {omega}")
            }
            Mixing::Anderson { depth } => write!(f, "Anderson, depth {depth}"),
            Mixing::AndersonSingular => write!(f, "fixed point (singular Anderson system)"),
            Mixing::AndersonRestart { residual_grew } => write!(
                f,
                "{}: Anderson restart, damped step ω = 0.5",
                if residual_grew {
                    "residual did not decrease"
                } else {
                    "Anderson stagnated"
                }
            ),
        }
    }
}

impl Serialize for Mixing {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

/// What a process counts of the fixed-point vectors: the entries `counts` marks (every
/// entry if it is empty), the partial sums completed over the processes by `share`.
#[derive(Clone, Copy, Debug)]
pub struct Counted<'a> {
    /// Per entry of the fixed-point vector: counted here (empty: every entry).
    pub counts: &'a [bool],
    /// The completion of partial sums over the processes.
    pub share: &'a Share,
}

impl Counted<'_> {
    /// Every entry, on one process.
    pub const WHOLE: Counted<'static> = Counted {
        counts: &[],
        share: &Share::WHOLE,
    };

    /// `Σ a_k b_k` over the entries counted here, in order (not completed).
    fn local_dot(&self, a: &[f64], b: &[f64]) -> f64 {
        let all = self.counts.is_empty();
        a.iter()
            .zip(b)
            .enumerate()
            .filter(|&(k, _)| all || self.counts[k])
            .map(|(_, (x, y))| x * y)
            .sum()
    }

    /// The Euclidean norm of `x` over every process.
    fn norm(&self, x: &[f64]) -> f64 {
        let mut s = [self.local_dot(x, x)];
        self.share.sum(&mut s);
        s[0].sqrt()
    }
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

    /// Next iterate from `z` and `g = G(z)`, whose norms and inner products are over the
    /// entries `counted` (completed over the processes); returns it with the step taken.
    pub fn next(&mut self, z: &[f64], g: &[f64], counted: Counted<'_>) -> (Vec<f64>, Mixing) {
        let f: Vec<f64> = g.iter().zip(z).map(|(a, b)| a - b).collect();
        let res = counted.norm(&f);
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
                let mut note = Mixing::Relaxed { omega: self.omega };
                if self.stalls >= 3 && self.omega > 0.125 {
                    self.omega *= 0.5;
                    self.stalls = 0;
                    self.oscillations += 1;
                    note = Mixing::Oscillation { omega: self.omega };
                }
                let next = z.iter().zip(&f).map(|(a, b)| a + self.omega * b).collect();
                (next, note)
            }
            Acceleration::Anderson => {
                if prev.is_some_and(|p| res >= p) {
                    // Safeguard: the residual did not decrease.
                    return self.restart(z, &f, g, true);
                }
                self.f_hist.push(f.clone());
                self.g_hist.push(g.to_vec());
                if self.f_hist.len() > self.depth + 1 {
                    self.f_hist.remove(0);
                    self.g_hist.remove(0);
                }
                let m = self.f_hist.len() - 1;
                if m == 0 {
                    return (g.to_vec(), Mixing::FixedPoint);
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
                // The normal equations' entries, completed over the processes at once.
                let mut sums = vec![0.0; m * m + m];
                for i in 0..m {
                    for j in 0..m {
                        sums[m * i + j] = counted.local_dot(&df[i], &df[j]);
                    }
                    sums[m * m + i] = counted.local_dot(&df[i], &f);
                }
                counted.share.sum(&mut sums);
                let mut a: Vec<Vec<f64>> =
                    sums[..m * m].chunks_exact(m).map(<[f64]>::to_vec).collect();
                let rhs = sums[m * m..].to_vec();
                let trace: f64 = (0..m).map(|i| a[i][i]).sum();
                for (i, row) in a.iter_mut().enumerate() {
                    row[i] += 1e-12 * trace + f64::MIN_POSITIVE;
                }
                let Some(gamma) = solve_dense(a, rhs) else {
                    return (g.to_vec(), Mixing::AndersonSingular);
                };
                let mut next = g.to_vec();
                for (j, gj) in gamma.iter().enumerate() {
                    for (k, x) in next.iter_mut().enumerate() {
                        *x -= gj * (self.g_hist[j + 1][k] - self.g_hist[j][k]);
                    }
                }
                // Stagnation: the mixed iterate does not move although the residual is not
                // small. Restart from a damped step.
                let moved =
                    counted.norm(&next.iter().zip(z).map(|(a, b)| a - b).collect::<Vec<_>>());
                if moved < 1e-3 * res {
                    return self.restart(z, &f, g, false);
                }
                (next, Mixing::Anderson { depth: m })
            }
        }
    }
}

impl Mixer {
    /// Drops the Anderson history (keeping the current point) and takes the damped step
    /// `z + ½ (G(z) − z)`.
    fn restart(
        &mut self,
        z: &[f64],
        f: &[f64],
        g: &[f64],
        residual_grew: bool,
    ) -> (Vec<f64>, Mixing) {
        self.restarts += 1;
        self.f_hist.clear();
        self.g_hist.clear();
        self.f_hist.push(f.to_vec());
        self.g_hist.push(g.to_vec());
        let next = z.iter().zip(f).map(|(a, b)| a + 0.5 * b).collect();
        (next, Mixing::AndersonRestart { residual_grew })
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
        let whole = Counted::WHOLE;
        while whole.norm(&g(&z).iter().zip(&z).map(|(a, b)| a - b).collect::<Vec<_>>()) > 1e-12 {
            let gz = g(&z);
            z = mixer.next(&z, &gz, whole).0;
            iters += 1;
            assert!(iters < 20, "Anderson did not converge");
        }
    }
}
