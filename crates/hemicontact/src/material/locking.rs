//! Locking sets `B = {ε : Q(ε) ≤ 0}` and the nearly-locking penalty (paper eq. (40)).
//!
//! | set | Q(ε) | ∂Q | ∂²Q |
//! |-----|------|----|-----|
//! | limited compressibility | `|tr ε| − θ` | `sgn(tr ε) I` | 0 |
//! | Prager | `½‖ε^D‖² − κ²` | `ε^D` | `𝕀^D = 𝕀 − (1/d) I⊗I` |
//! | ball | `‖ε‖ − r` | `ε/‖ε‖` | `(𝕀 − n⊗n)/‖ε‖`, `n = ε/‖ε‖` |
//!
//! The penalty energy `Ψ(ε) = (C_κ/2) Q(ε)_+²` has stress `C_κ Q_+ ∂Q` (for limited
//! compressibility `C_κ (|tr ε| − θ)_+ sgn(tr ε) I`) and generalized tangent
//! `C_κ (H(Q) ∂Q⊗∂Q + Q_+ ∂²Q)` with `H` the Heaviside step (taken 0 at Q = 0). Ψ is convex
//! (Q convex, `t ↦ t_+²` convex and nondecreasing) and C¹ with a piecewise smooth gradient,
//! which is what the semismooth Newton method needs. `C_κ = 0` adds nothing.

use super::StrainEnergy;
use crate::tensor::{add_identity, add_outer, zero_tangent, Sym, Tangent};

/// A locking set B; see the module documentation. (A material without locking has no set:
/// [`super::Locking::None`].)
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LockingSet {
    /// `|tr ε| ≤ θ` (the paper's example, θ = κ²).
    LimitedCompressibility {
        /// Threshold θ > 0 on the volumetric strain.
        theta: f64,
    },
    /// Prager's ideal locking `½‖ε^D‖² ≤ κ²`.
    Prager {
        /// κ > 0.
        kappa: f64,
    },
    /// `‖ε‖ ≤ r`.
    Ball {
        /// Radius r > 0.
        r: f64,
    },
}

impl std::fmt::Display for LockingSet {
    /// The set with its inequality and parameter (strains dimensionless), e.g. `limited
    /// compressibility |tr ε| ≤ θ with θ = 0.16`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        use crate::display::significant as s;
        match *self {
            LockingSet::LimitedCompressibility { theta } => {
                write!(
                    f,
                    "limited compressibility |tr ε| ≤ θ with θ = {}",
                    s(theta)
                )
            }
            LockingSet::Prager { kappa } => {
                write!(f, "Prager ½‖ε^D‖² ≤ κ² with κ = {}", s(kappa))
            }
            LockingSet::Ball { r } => write!(f, "ball ‖ε‖ ≤ r with r = {}", s(r)),
        }
    }
}

impl LockingSet {
    /// The same set for the dimensionless strain `ε̂ = ε/e` (e the strain unit), with the
    /// unit q of its function: `Q(e ε̂) = q Q̂(ε̂)`. Limited compressibility and the ball
    /// scale like a strain (θ̂ = θ/e, r̂ = r/e, q = e), Prager's set like its square (κ̂ = κ/e,
    /// q = e²).
    pub fn nondimensional(&self, e: f64) -> (LockingSet, f64) {
        match *self {
            LockingSet::LimitedCompressibility { theta } => {
                (LockingSet::LimitedCompressibility { theta: theta / e }, e)
            }
            LockingSet::Prager { kappa } => (LockingSet::Prager { kappa: kappa / e }, e * e),
            LockingSet::Ball { r } => (LockingSet::Ball { r: r / e }, e),
        }
    }

    /// Checks the set's threshold.
    ///
    /// # Errors
    /// [`crate::Error::Invalid`] for a threshold (`theta`, `kappa`, `r`) that is not
    /// finite and positive.
    pub fn validate(&self) -> crate::Result<()> {
        let (field, v, what) = match *self {
            LockingSet::LimitedCompressibility { theta } => {
                ("theta", theta, "a volumetric strain threshold θ > 0")
            }
            LockingSet::Prager { kappa } => ("kappa", kappa, "a deviatoric threshold κ > 0"),
            LockingSet::Ball { r } => ("r", r, "a strain radius r > 0"),
        };
        crate::error::require(v.is_finite() && v > 0.0, field, v, what)
    }

    /// The size of B, the unit in which a value of Q is small or large: θ for limited
    /// compressibility, κ² for Prager's set, r for the ball (so that `Q/size` is a relative
    /// violation of the constraint).
    #[inline]
    pub fn size(&self) -> f64 {
        match *self {
            LockingSet::LimitedCompressibility { theta } => theta,
            LockingSet::Prager { kappa } => kappa * kappa,
            LockingSet::Ball { r } => r,
        }
    }

    /// `|∂Q|²` on the boundary ∂B = {Q = 0}, which turns a stiffness per unit of strain
    /// into one per unit of Q: 1 for limited compressibility (measured per unit trace,
    /// `|∂Q/∂(tr ε)| = 1`), `‖ε^D‖² = 2κ²` for Prager's set (`½‖ε^D‖² = κ²` on ∂B), and
    /// `‖ε/‖ε‖‖² = 1` for the ball.
    #[inline]
    pub fn gradient_norm_sq_at_boundary(&self) -> f64 {
        match *self {
            LockingSet::Prager { kappa } => 2.0 * kappa * kappa,
            LockingSet::LimitedCompressibility { .. } | LockingSet::Ball { .. } => 1.0,
        }
    }

    /// `Q(ε)`: negative inside B, zero on its boundary, positive outside.
    #[inline]
    pub fn q(&self, eps: &Sym) -> f64 {
        match *self {
            LockingSet::LimitedCompressibility { theta } => eps.trace().abs() - theta,
            LockingSet::Prager { kappa } => {
                let dev = eps.deviator();
                0.5 * dev.dot(&dev) - kappa * kappa
            }
            LockingSet::Ball { r } => eps.norm() - r,
        }
    }

    /// `∂Q(ε)` (where Q > 0, so that the kinks of the table are never evaluated).
    #[inline]
    pub fn dq(&self, eps: &Sym) -> Sym {
        match *self {
            LockingSet::LimitedCompressibility { .. } => {
                Sym::identity(eps.dim).scaled(eps.trace().signum())
            }
            LockingSet::Prager { .. } => eps.deviator(),
            LockingSet::Ball { .. } => {
                let n = eps.norm();
                if n > 0.0 {
                    eps.scaled(1.0 / n)
                } else {
                    Sym::zero(eps.dim)
                }
            }
        }
    }

    /// Out-of-plane component `∂Q/∂ε_zz` of a two-dimensional strain `eps` under plane
    /// strain (`ε_zz = 0`, Q read as a function of `tr ε` and `ε:ε`, see
    /// [`crate::material`]): `sgn(tr ε)` for limited compressibility, `−tr ε / 2` for
    /// Prager's set (the zz entry of `ε − (tr ε/2) I`), 0 for the ball.
    #[inline]
    pub fn dq_zz(&self, eps: &Sym) -> f64 {
        match *self {
            LockingSet::Ball { .. } => 0.0,
            LockingSet::LimitedCompressibility { .. } => eps.trace().signum(),
            LockingSet::Prager { .. } => -eps.trace() / eps.dim as f64,
        }
    }

    /// Adds `s ∂²Q(ε)` to the tangent `t`.
    #[inline]
    fn add_d2q(&self, t: &mut Tangent, eps: &Sym, s: f64) {
        let d = eps.dim;
        match *self {
            LockingSet::LimitedCompressibility { .. } => {}
            LockingSet::Prager { .. } => {
                let i = Sym::identity(d);
                add_identity(t, d, s);
                add_outer(t, -s / d as f64, &i, &i);
            }
            LockingSet::Ball { .. } => {
                let norm = eps.norm();
                if norm > 0.0 {
                    let n = eps.scaled(1.0 / norm);
                    add_identity(t, d, s / norm);
                    add_outer(t, -s / norm, &n, &n);
                }
            }
        }
    }
}

/// The nearly-locking penalty `Ψ(ε) = (C_κ/2) Q(ε)_+²`; see the module documentation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LockingPenalty {
    /// The locking set B.
    pub set: LockingSet,
    /// Compliance C_κ ≥ 0 (Pa).
    pub c_kappa: f64,
}

impl LockingPenalty {
    /// Checks the set and the compliance.
    ///
    /// # Errors
    /// [`crate::Error::Invalid`]: the set as [`LockingSet::validate`], `c_kappa` finite and
    /// ≥ 0.
    pub fn validate(&self) -> crate::Result<()> {
        self.set.validate()?;
        let c = self.c_kappa;
        crate::error::require(
            c.is_finite() && c >= 0.0,
            "c_kappa",
            c,
            "a compliance C_κ ≥ 0 (Pa)",
        )
    }

    /// Whether the penalty is active (`Q(ε) > 0` and `C_κ > 0`).
    #[inline]
    pub fn is_active(&self, eps: &Sym) -> bool {
        self.c_kappa > 0.0 && self.set.q(eps) > 0.0
    }
}

impl StrainEnergy for LockingPenalty {
    #[inline]
    fn energy(&self, eps: &Sym) -> f64 {
        if self.c_kappa == 0.0 {
            return 0.0;
        }
        let q = self.set.q(eps).max(0.0);
        0.5 * self.c_kappa * q * q
    }

    #[inline]
    fn stress(&self, eps: &Sym) -> Sym {
        let q = if self.c_kappa == 0.0 {
            0.0
        } else {
            self.set.q(eps)
        };
        if q <= 0.0 {
            return Sym::zero(eps.dim);
        }
        self.set.dq(eps).scaled(self.c_kappa * q)
    }

    #[inline]
    fn tangent(&self, eps: &Sym) -> Tangent {
        let mut t = zero_tangent();
        let q = if self.c_kappa == 0.0 {
            0.0
        } else {
            self.set.q(eps)
        };
        if q > 0.0 {
            let dq = self.set.dq(eps);
            add_outer(&mut t, self.c_kappa, &dq, &dq);
            self.set.add_d2q(&mut t, eps, self.c_kappa * q);
        }
        t
    }
    /// `σ_zz = C_κ Q_+ ∂Q/∂ε_zz` ([`LockingSet::dq_zz`]).
    #[inline]
    fn plane_strain_stress_zz(&self, eps: &Sym) -> f64 {
        if self.c_kappa == 0.0 {
            return 0.0;
        }
        let q = self.set.q(eps);
        if q <= 0.0 {
            return 0.0;
        }
        self.c_kappa * q * self.set.dq_zz(eps)
    }
}

/// The augmented Lagrangian term of *ideal* locking in one cell (the constraint
/// `ε_T ∈ B`): with multiplier `λ ≥ 0` (Pa) and penalty `r > 0` (Pa per unit of Q²),
///
/// `Ψ_λ(ε) = (1/2r) [ (λ + r Q(ε))_+² − λ² ]`,
///
/// stress `(λ + r Q)_+ ∂Q`, tangent `r H(λ + rQ) ∂Q⊗∂Q + (λ + rQ)_+ ∂²Q`. It is the
/// nearly-locking penalty with `C_κ = r` and Q shifted by `λ/r` (plus a constant), so with
/// `λ = 0` it *is* the penalty; the multiplier update `λ ← (λ + r Q(ε_T))_+` of
/// [`crate::solver::constraints`] drives `Q(ε_T)_+` to zero while the penalty stays finite.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AugmentedLocking {
    /// The locking set B.
    pub set: LockingSet,
    /// Penalty r > 0.
    pub r: f64,
    /// Multiplier λ of the cell.
    pub lambda: f64,
}

impl AugmentedLocking {
    /// `(λ + r Q(ε))_+`: the updated multiplier, and the magnitude of the locking stress.
    #[inline]
    pub fn multiplier(&self, eps: &Sym) -> f64 {
        (self.lambda + self.r * self.set.q(eps)).max(0.0)
    }
}

impl StrainEnergy for AugmentedLocking {
    #[inline]
    fn energy(&self, eps: &Sym) -> f64 {
        let m = self.multiplier(eps);
        (m * m - self.lambda * self.lambda) / (2.0 * self.r)
    }

    #[inline]
    fn stress(&self, eps: &Sym) -> Sym {
        let m = self.multiplier(eps);
        if m <= 0.0 {
            return Sym::zero(eps.dim);
        }
        self.set.dq(eps).scaled(m)
    }

    #[inline]
    fn tangent(&self, eps: &Sym) -> Tangent {
        let mut t = zero_tangent();
        let m = self.multiplier(eps);
        if m > 0.0 {
            let dq = self.set.dq(eps);
            add_outer(&mut t, self.r, &dq, &dq);
            self.set.add_d2q(&mut t, eps, m);
        }
        t
    }
    /// `σ_zz = (λ + r Q)_+ ∂Q/∂ε_zz` ([`LockingSet::dq_zz`]).
    #[inline]
    fn plane_strain_stress_zz(&self, eps: &Sym) -> f64 {
        let m = self.multiplier(eps);
        if m <= 0.0 {
            return 0.0;
        }
        m * self.set.dq_zz(eps)
    }
}
