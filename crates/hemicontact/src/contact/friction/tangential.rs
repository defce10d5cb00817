//! The tangential term of one contact point under a friction law with its bound frozen:
//! energy, gradient and Hessian, the update of the friction multiplier, and the projection
//! onto the ball and the regularized norm they are made of (see the module documentation of
//! [`crate::contact::friction`]).

use super::law::Friction;

/// The frozen data of the tangential term of one contact point (see the module
/// documentation).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TangentialData {
    /// Friction bound F ≥ 0 (Pa, or N/m in 2D).
    pub bound: f64,
    /// Linear term b (Pa), tangential coordinates.
    pub linear: [f64; 2],
    /// Exact stick/slip: the multiplier τ (Pa, tangential coordinates).
    pub traction: [f64; 2],
    /// Exact stick/slip: the augmented-Lagrangian penalty r > 0 (Pa/m).
    pub penalty: f64,
    /// Smoothed norm: the elastic stiffness per unit area `k_i = S / h_i` of the point (Pa/m),
    /// which with the bound sets its slip scale `F / k` (see the module documentation).
    pub stiffness: f64,
}

/// Energy density (Pa·m), gradient (Pa) and Hessian (Pa/m) of the tangential term with
/// respect to the tangential displacement ξ, in tangential coordinates (first m entries).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TangentialTerm {
    /// Energy.
    pub energy: f64,
    /// Gradient (the friction traction `−σ_τ` of the term).
    pub gradient: [f64; 2],
    /// (Generalized) Hessian.
    pub hessian: [[f64; 2]; 2],
}

/// Projection of the `m`-vector `z` onto the ball of radius `f ≥ 0`; returns it with
/// whether `z` was inside (stick).
#[inline]
pub fn project_ball(z: &[f64; 2], m: usize, f: f64) -> ([f64; 2], bool) {
    let nz = z[..m].iter().map(|x| x * x).sum::<f64>().sqrt();
    if nz <= f {
        (*z, true)
    } else {
        let s = f / nz;
        ([z[0] * s, z[1] * s], false)
    }
}

impl Friction {
    /// The effective penalty `r' = r / (1 + r c)` and the argument
    /// `z = r' ξ + (r'/r) τ` of the envelope of a point with penalty r, compliance c,
    /// multiplier τ and slip ξ (see the module documentation); `z = τ + r ξ` when c = 0.
    #[inline]
    fn envelope_argument(xi: &[f64; 2], tau: &[f64; 2], r: f64, c: f64) -> (f64, [f64; 2]) {
        if c == 0.0 {
            return (r, [tau[0] + r * xi[0], tau[1] + r * xi[1]]);
        }
        let r_eff = r / (1.0 + r * c);
        let s = r_eff / r;
        (
            r_eff,
            [s * tau[0] + r_eff * xi[0], s * tau[1] + r_eff * xi[1]],
        )
    }

    /// The tangential term at the tangential displacement ξ (`m` = d − 1 components) with
    /// the frozen data `data` (see the module documentation): `F φ_ρ(ξ) − b·ξ` for the
    /// smooth law (19), or for the norm (exact, or smoothed with the compliance c) the
    /// augmented Lagrangian `H_F(z)/r' − ‖τ‖²/(2r) − b·ξ`, `z = r'ξ + (r'/r)τ`,
    /// `r' = r/(1 + rc)` ([`Friction::compliance`]; `z = τ + rξ` and `r' = r` when exact),
    /// with gradient `proj_{B_F}(z) − b` and Hessian `r' I` (stick, ‖z‖ ≤ F, F > 0) or
    /// `r' F/‖z‖ (I − z zᵀ/‖z‖²)` (slip).
    #[inline]
    pub fn tangential_term(
        &self,
        xi: &[f64; 2],
        m: usize,
        data: &TangentialData,
    ) -> TangentialTerm {
        let f = data.bound;
        let b = data.linear;
        let mut gt = [0.0; 2];
        let mut ht = [[0.0; 2]; 2];
        let energy;
        if let Some(c) = self.compliance(data.stiffness) {
            let tau = data.traction;
            let (r, z) = Self::envelope_argument(xi, &tau, data.penalty, c);
            // τ enters the energy as ‖τ‖²/(2 r_penalty) = (r'/r_penalty) ‖τ‖²/(2r').
            let tau_weight = r / data.penalty;
            let nz = z[..m].iter().map(|x| x * x).sum::<f64>().sqrt();
            let tau2: f64 = tau[..m].iter().map(|x| x * x).sum();
            let (g, _) = project_ball(&z, m, f);
            let huber = if f > 0.0 && nz <= f {
                for a in 0..m {
                    ht[a][a] = r;
                }
                0.5 * nz * nz
            } else if nz == 0.0 {
                // F = 0 and z = 0: the envelope is flat (zero curvature).
                0.0
            } else {
                for a in 0..m {
                    for c in 0..m {
                        let delta = if a == c { 1.0 } else { 0.0 };
                        ht[a][c] = r * f / nz * (delta - z[a] * z[c] / (nz * nz));
                    }
                }
                f * nz - 0.5 * f * f
            };
            energy =
                (huber - 0.5 * tau2 * tau_weight) / r - (0..m).map(|a| b[a] * xi[a]).sum::<f64>();
            for a in 0..m {
                gt[a] = g[a] - b[a];
            }
        } else {
            let rho = self.potential.rho();
            let (phi, g, h) = regularized_norm(xi, m, rho);
            energy = f * phi - (0..m).map(|a| b[a] * xi[a]).sum::<f64>();
            for a in 0..m {
                gt[a] = f * g[a] - b[a];
                for c in 0..m {
                    ht[a][c] = f * h[a][c];
                }
            }
        }
        TangentialTerm {
            energy,
            gradient: gt,
            hessian: ht,
        }
    }

    /// The multiplier update of the norm, `τ ← proj_{B_F}(z)` with `z = τ + r ξ` for exact
    /// stick/slip and `z = r'ξ + (r'/r)τ` for a smoothed norm (see
    /// [`Friction::tangential_term`]), for the tangential displacement ξ (`m` components),
    /// multiplier `traction`, penalty `penalty`, the point's elastic stiffness per unit area
    /// `stiffness` and frozen bound `bound`; `None` for the smooth law (19).
    #[inline]
    pub fn updated_traction(
        &self,
        xi: &[f64; 2],
        m: usize,
        traction: &[f64; 2],
        penalty: f64,
        stiffness: f64,
        bound: f64,
    ) -> Option<[f64; 2]> {
        let c = self.compliance(stiffness)?;
        let (_, z) = Self::envelope_argument(xi, traction, penalty, c);
        Some(project_ball(&z, m, bound).0)
    }
}

/// Value, gradient and Hessian of the regularized norm `φ(ξ) = √(‖ξ‖² + ρ²) − ρ` for a
/// tangential vector ξ of `m` components (m = 1 or 2). Returns `(φ, ∇φ, ∇²φ)`.
#[inline]
pub fn regularized_norm(xi: &[f64; 2], m: usize, rho: f64) -> (f64, [f64; 2], [[f64; 2]; 2]) {
    let r2: f64 = xi[..m].iter().map(|x| x * x).sum();
    let s = (r2 + rho * rho).sqrt();
    if s == 0.0 {
        // ρ = 0 and ξ = 0: the subgradient 0 and an infinite curvature; callers use ρ > 0.
        return (0.0, [0.0; 2], [[0.0; 2]; 2]);
    }
    let mut g = [0.0; 2];
    let mut h = [[0.0; 2]; 2];
    for a in 0..m {
        g[a] = xi[a] / s;
    }
    for a in 0..m {
        for b in 0..m {
            h[a][b] = (if a == b { 1.0 } else { 0.0 } - g[a] * g[b]) / s;
        }
    }
    (s - rho, g, h)
}
