//! Friction laws: slip-dependent coefficient μ(r), friction bound F, and the
//! friction potential j with its difference-of-convex split `j = j_cvx − h`.
//!
//! The friction condition is `−σ_τ ∈ F ∂j(u_τ)` (Clarke subdifferential), with
//! `F = μ(‖u_τ‖)` (Tresca type) or `F = μ(‖u_τ‖) p(u_ν)` (Coulomb type).
//!
//! | potential | j(ξ), r = ‖ξ‖ | j_cvx | h |
//! |-----------|---------------|-------|---|
//! | norm | `r` | `r` | 0 |
//! | nonconvex (17), 0 < a < 1 | `r + (a−1)/(2a) r²` (r ≤ a), `a r + a(1−a)/2` (r > a) | `r` | `(1−a)/(2a) r²` (r ≤ a), `(1−a) r − a(1−a)/2` (r > a) |
//!
//! The paper states (17) with the slip r in metres; the law is `ℓ j₁₇(r/ℓ)` with the slip
//! unit ℓ = 1 m ([`FrictionPotential::Nonconvex::unit`]), which keeps its form when the
//! variables are made dimensionless (ℓ becomes ℓ/U for a displacement scale U).
//! | regularized (19) | `√(r² + ρ²) − ρ` | j | 0 |
//!
//! The norm is nonsmooth at 0. The solver works with its regularization
//! `√(r² + ρ_num²) − ρ_num`, with a numerical `ρ_num` far below every displacement of
//! interest (see [`crate::solver::OuterSettings::friction_regularization`]).

use serde::{Deserialize, Serialize};

/// The slip-dependent friction coefficient μ(r), r = ‖u_τ‖ ≥ 0 (dimensionless).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "law", rename_all = "kebab-case", deny_unknown_fields)]
pub enum FrictionCoefficient {
    /// μ(r) = μ.
    Constant {
        /// The coefficient.
        mu: f64,
    },
    /// Exponential slip weakening `μ(r) = (a − b) e^{−βr} + b` (paper eq. (41)).
    Exponential {
        /// Static value a = μ(0).
        a: f64,
        /// Limit b = μ(∞).
        b: f64,
        /// Decay rate β (1/m).
        beta: f64,
    },
    /// Piecewise linear interpolation of a table `[[r_0, μ_0], [r_1, μ_1], …]` with
    /// `0 = r_0 < r_1 < …`, constant beyond the last point.
    Table {
        /// The points `[r, μ]`.
        points: Vec<[f64; 2]>,
    },
}

impl FrictionCoefficient {
    /// μ(r).
    pub fn value(&self, r: f64) -> f64 {
        match self {
            FrictionCoefficient::Constant { mu } => *mu,
            FrictionCoefficient::Exponential { a, b, beta } => (a - b) * (-beta * r).exp() + b,
            FrictionCoefficient::Table { points } => {
                let k = points.partition_point(|p| p[0] <= r);
                if k == 0 {
                    points.first().map_or(0.0, |p| p[1])
                } else if k == points.len() {
                    points[k - 1][1]
                } else {
                    let (p, q) = (points[k - 1], points[k]);
                    p[1] + (q[1] - p[1]) * (r - p[0]) / (q[0] - p[0])
                }
            }
        }
    }

    /// Upper bound μ₀ = sup μ.
    pub fn sup(&self) -> f64 {
        match self {
            FrictionCoefficient::Constant { mu } => *mu,
            FrictionCoefficient::Exponential { a, b, .. } => a.max(*b),
            FrictionCoefficient::Table { points } => {
                points.iter().map(|p| p[1]).fold(0.0, f64::max)
            }
        }
    }

    /// Lipschitz constant L_μ.
    pub fn lipschitz(&self) -> f64 {
        match self {
            FrictionCoefficient::Constant { .. } => 0.0,
            FrictionCoefficient::Exponential { a, b, beta } => (a - b).abs() * beta,
            FrictionCoefficient::Table { points } => points
                .windows(2)
                .map(|w| ((w[1][1] - w[0][1]) / (w[1][0] - w[0][0])).abs())
                .fold(0.0, f64::max),
        }
    }

    /// The same law in dimensionless variables: slips in units of `displacement` (m) and
    /// values in units of `value` (1 for a Coulomb-type coefficient, the traction unit for a
    /// Tresca bound): `μ̂(r̂) = μ(U r̂)/value`, so β̂ = βU, table slips r/U and values
    /// μ/value.
    pub fn nondimensional(&self, displacement: f64, value: f64) -> Self {
        match self {
            FrictionCoefficient::Constant { mu } => {
                FrictionCoefficient::Constant { mu: mu / value }
            }
            FrictionCoefficient::Exponential { a, b, beta } => FrictionCoefficient::Exponential {
                a: a / value,
                b: b / value,
                beta: beta * displacement,
            },
            FrictionCoefficient::Table { points } => FrictionCoefficient::Table {
                points: points
                    .iter()
                    .map(|p| [p[0] / displacement, p[1] / value])
                    .collect(),
            },
        }
    }

    /// Checks the parameters; returns what is wrong.
    ///
    /// # Errors
    /// A message naming the parameter and what is allowed.
    pub fn validate(&self) -> Result<(), String> {
        let ok = |x: f64| x.is_finite() && x >= 0.0;
        match self {
            FrictionCoefficient::Constant { mu } if !ok(*mu) => {
                Err(format!("mu = {mu}: a finite coefficient ≥ 0"))
            }
            FrictionCoefficient::Exponential { a, b, beta } if !(ok(*a) && ok(*b) && ok(*beta)) => {
                Err(format!(
                    "a = {a}, b = {b}, beta = {beta}: finite values ≥ 0"
                ))
            }
            FrictionCoefficient::Table { points } => {
                if points.is_empty() || points[0][0] != 0.0 {
                    return Err("points: a non-empty table starting at r = 0".into());
                }
                if points.iter().any(|p| !ok(p[0]) || !ok(p[1])) {
                    return Err("points: finite values ≥ 0".into());
                }
                if points.windows(2).any(|w| w[1][0] <= w[0][0]) {
                    return Err("points: strictly increasing slips r".into());
                }
                Ok(())
            }
            _ => Ok(()),
        }
    }
}

/// How the friction bound F depends on the state.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FrictionBound {
    /// `F = μ(‖u_τ‖)` (the paper's theory, eq. (10)); μ is then a traction (Pa).
    Tresca,
    /// `F = μ(‖u_τ‖) p(u_ν)` (the paper's numerical example).
    Coulomb,
}

/// The friction potential j; see the module documentation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FrictionPotential {
    /// `j(ξ) = ‖ξ‖`.
    Norm,
    /// The paper's nonconvex example (17) with parameter `0 < a < 1`, for the slip measured
    /// in the unit ℓ: `j(r) = ℓ j₁₇(r/ℓ)`.
    Nonconvex {
        /// a_j (dimensionless).
        a: f64,
        /// The slip unit ℓ of the formula (m); 1 for the paper's law.
        unit: f64,
    },
    /// The regularized Coulomb law (19) `√(‖ξ‖² + ρ²) − ρ`.
    Regularized {
        /// ρ > 0 (m).
        rho: f64,
    },
}

impl FrictionPotential {
    /// Checks the potential's parameters.
    ///
    /// # Errors
    /// [`crate::Error::Invalid`]: the nonconvex potential needs `0 < a < 1` and a finite
    /// positive slip unit, the regularized one a finite `rho > 0` (m).
    pub fn validate(&self) -> crate::Result<()> {
        use crate::error::require;
        match *self {
            FrictionPotential::Norm => Ok(()),
            FrictionPotential::Nonconvex { a, unit } => {
                require(a > 0.0 && a < 1.0, "a", a, "a parameter with 0 < a < 1")?;
                require(
                    unit.is_finite() && unit > 0.0,
                    "unit",
                    unit,
                    "a slip unit ℓ > 0 (m)",
                )
            }
            FrictionPotential::Regularized { rho } => require(
                rho.is_finite() && rho > 0.0,
                "rho",
                rho,
                "a regularization length ρ (m) > 0",
            ),
        }
    }

    /// `j(ξ)` as a function of `r = ‖ξ‖` (the exact law, no numerical regularization).
    pub fn value(&self, r: f64) -> f64 {
        match *self {
            FrictionPotential::Norm => r,
            FrictionPotential::Nonconvex { a, unit } => {
                let x = r / unit;
                unit * if x <= a {
                    x + (a - 1.0) / (2.0 * a) * x * x
                } else {
                    a * x + a * (1.0 - a) / 2.0
                }
            }
            FrictionPotential::Regularized { rho } => (r * r + rho * rho).sqrt() - rho,
        }
    }

    /// `j'(r)` for r > 0: the magnitude of `∂j(ξ)`, which is `j'(r) ξ/r`. At r = 0 the norm
    /// and (17) have `∂j(0)` = the unit ball (returned value 1), the regularized law 0.
    pub fn slope(&self, r: f64) -> f64 {
        match *self {
            FrictionPotential::Norm => 1.0,
            FrictionPotential::Nonconvex { a, unit } => {
                let x = r / unit;
                if x <= a {
                    1.0 - (1.0 - a) * x / a
                } else {
                    a
                }
            }
            FrictionPotential::Regularized { rho } => {
                if r == 0.0 {
                    0.0
                } else {
                    r / (r * r + rho * rho).sqrt()
                }
            }
        }
    }

    /// `h'(r)` of the DC split `j = j_cvx − h` (so `∇h(ξ) = h'(r) ξ/r`); zero for the
    /// convex potentials.
    pub fn h_slope(&self, r: f64) -> f64 {
        match *self {
            FrictionPotential::Nonconvex { a, unit } => (1.0 - a) * (r / (a * unit)).min(1.0),
            _ => 0.0,
        }
    }

    /// The ρ of the convex part `j_cvx = √(r² + ρ²) − ρ`: the law's own ρ for (19), the
    /// numerical `rho_num` for the norm and (17).
    pub fn convex_rho(&self, rho_num: f64) -> f64 {
        match *self {
            FrictionPotential::Regularized { rho } => rho,
            _ => rho_num,
        }
    }

    /// Whether the convex part `j_cvx` is the (nonsmooth) norm, so that it can be imposed
    /// exactly; false for the smooth law (19).
    pub fn is_nonsmooth(&self) -> bool {
        !matches!(self, FrictionPotential::Regularized { .. })
    }

    /// Bound `c_j` of `∂j` (`|ζ| ≤ c_j` for `ζ ∈ ∂j(ξ)`): 1 for all three potentials.
    pub fn c_j(&self) -> f64 {
        1.0
    }

    /// Relaxed monotonicity constant `α_j ≥ 0` of ∂j:
    /// `(ζ₁ − ζ₂)·(ξ₁ − ξ₂) ≥ −α_j ‖ξ₁ − ξ₂‖²`. Zero for convex j; `(1 − a)/a` for (17)
    /// (the Lipschitz constant of ∇h; 1/m for ℓ = 1 m).
    pub fn alpha_j(&self) -> f64 {
        match *self {
            FrictionPotential::Nonconvex { a, unit } => (1.0 - a) / (a * unit),
            _ => 0.0,
        }
    }

    /// The same law for the dimensionless slip `r̂ = r/U` (U the displacement scale, m):
    /// `ĵ(r̂) = j(U r̂)/U`, so ρ̂ = ρ/U and ℓ̂ = ℓ/U.
    pub fn nondimensional(&self, displacement: f64) -> Self {
        match *self {
            FrictionPotential::Norm => FrictionPotential::Norm,
            FrictionPotential::Nonconvex { a, unit } => FrictionPotential::Nonconvex {
                a,
                unit: unit / displacement,
            },
            FrictionPotential::Regularized { rho } => FrictionPotential::Regularized {
                rho: rho / displacement,
            },
        }
    }
}

/// A friction law: bound type, coefficient, potential.
#[derive(Clone, Debug, PartialEq)]
pub struct Friction {
    /// Tresca- or Coulomb-type bound.
    pub bound: FrictionBound,
    /// The slip-dependent coefficient μ.
    pub mu: FrictionCoefficient,
    /// The potential j.
    pub potential: FrictionPotential,
    /// Exact stick/slip: the nonsmooth convex part `F ‖·‖` of the potential is imposed by
    /// an augmented Lagrangian with the friction traction as multiplier (sticking points
    /// then have zero slip to round-off, slipping points carry exactly the bound), instead
    /// of the numerical regularization ρ_num. Only for the potentials whose convex part is
    /// the norm (`norm`, `nonconvex`); the regularized law (19) is smooth already.
    pub exact: bool,
}

impl Friction {
    /// Checks the coefficient, the potential and the treatment of stick/slip.
    ///
    /// # Errors
    /// [`crate::Error::Invalid`] naming the parameter: `mu` as
    /// [`FrictionCoefficient::validate`], the potential's parameters as
    /// [`FrictionPotential::validate`], and `exact` only for a potential whose convex part
    /// is the norm.
    pub fn validate(&self) -> crate::Result<()> {
        self.mu
            .validate()
            .map_err(|msg| crate::Error::invalid("mu", format!("{:?}", self.mu), msg))?;
        self.potential.validate()?;
        crate::error::require(
            !self.exact || self.potential.is_nonsmooth(),
            "exact",
            true,
            "exact = true only with potential = \"norm\" or \"nonconvex\" (the \
             regularized law (19) is smooth)",
        )
    }

    /// The friction bound `F` at slip `r = ‖u_τ‖` and contact pressure `p`.
    #[inline]
    pub fn bound_value(&self, r: f64, pressure: f64) -> f64 {
        let mu = self.mu.value(r);
        match self.bound {
            FrictionBound::Tresca => mu,
            FrictionBound::Coulomb => mu * pressure,
        }
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
