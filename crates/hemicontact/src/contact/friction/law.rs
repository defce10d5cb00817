//! A friction law ([`Friction`]): the type of its bound, its coefficient, and its potential
//! with the treatment of the norm; their validation and dimensionless forms, the bound
//! at a point and the compliance of its elastic slip.

use super::coefficient::FrictionCoefficient;
use serde::{Deserialize, Serialize};

/// How the friction bound F depends on the state.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FrictionBound {
    /// `F = μ(‖u_τ‖)` (the paper's theory, eq. (10)); μ is then a traction (Pa).
    Tresca,
    /// `F = μ(‖u_τ‖) p(u_ν)` (the paper's numerical example).
    Coulomb,
}

/// The default numerical regularization ε of the norm, relative to each contact point's
/// own slip scale `F_i / k_i` (see the module documentation): a sticking point slips
/// elastically by at most `10⁻⁸ F_i / k_i`, a hundredth of the certificate's stick
/// threshold `10⁻⁶ max(F_i, p_i) / k_i` at its default tolerance; slipping points carry the
/// bound exactly.
pub const DEFAULT_REGULARIZATION: f64 = 1e-8;

/// How the nonsmooth convex part `F ‖·‖` of the potentials `norm` and `nonconvex` is
/// imposed: exactly, or with an elastic slip (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NormTreatment {
    /// Exact friction in series with an elastic slip of compliance `regularization / k_i`
    /// at contact point i: a sticking point slips elastically by at most
    /// `regularization · F_i / k_i`, relative to the point's own slip scale (see the module
    /// documentation; the law keeps this relative value when it is made dimensionless).
    Smoothed {
        /// ε, dimensionless, in (0, 10⁻²).
        regularization: f64,
    },
    /// Exact stick/slip: `F ‖·‖` is imposed by an augmented Lagrangian with the friction
    /// traction as multiplier (sticking points then have zero slip to round-off, slipping
    /// points carry exactly the bound); see the module documentation.
    Exact,
}

impl Default for NormTreatment {
    fn default() -> Self {
        NormTreatment::Smoothed {
            regularization: DEFAULT_REGULARIZATION,
        }
    }
}

impl NormTreatment {
    /// Checks the parameters; returns what is wrong.
    ///
    /// # Errors
    /// A message naming the parameter and what is allowed.
    pub fn validate(&self) -> Result<(), String> {
        match *self {
            NormTreatment::Smoothed { regularization }
                if !(regularization.is_finite()
                    && regularization > 0.0
                    && regularization < 1e-2) =>
            {
                Err(format!(
                    "regularization = {regularization}: a number in (0, 0.01) (relative to each \
                     contact point's slip scale F/k)"
                ))
            }
            _ => Ok(()),
        }
    }
}

/// The friction potential j; see the module documentation. The potentials whose convex part
/// is the norm carry its [`NormTreatment`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FrictionPotential {
    /// `j(ξ) = ‖ξ‖`.
    Norm {
        /// How the norm is imposed.
        treatment: NormTreatment,
    },
    /// The paper's nonconvex example (17) with parameter `0 < a < 1`, for the slip measured
    /// in the unit ℓ: `j(r) = ℓ j₁₇(r/ℓ)`.
    Nonconvex {
        /// a_j (dimensionless).
        a: f64,
        /// The slip unit ℓ of the formula (m); 1 for the paper's law.
        unit: f64,
        /// How the convex part, the norm, is imposed.
        treatment: NormTreatment,
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
    /// positive slip unit, the regularized one a finite `rho > 0` (m), a smoothed norm a
    /// `regularization` in (0, 0.01) ([`NormTreatment::validate`]).
    pub fn validate(&self) -> crate::Result<()> {
        use crate::error::require;
        if let Some(treatment) = self.treatment() {
            if let (Err(msg), NormTreatment::Smoothed { regularization }) =
                (treatment.validate(), treatment)
            {
                return Err(crate::Error::invalid("regularization", regularization, msg));
            }
        }
        match *self {
            FrictionPotential::Norm { .. } => Ok(()),
            FrictionPotential::Nonconvex { a, unit, .. } => {
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
            FrictionPotential::Norm { .. } => r,
            FrictionPotential::Nonconvex { a, unit, .. } => {
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
            FrictionPotential::Norm { .. } => 1.0,
            FrictionPotential::Nonconvex { a, unit, .. } => {
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
            FrictionPotential::Nonconvex { a, unit, .. } => (1.0 - a) * (r / (a * unit)).min(1.0),
            _ => 0.0,
        }
    }

    /// How the norm of the convex part is imposed; `None` for the smooth law (19).
    pub fn treatment(&self) -> Option<NormTreatment> {
        match *self {
            FrictionPotential::Norm { treatment }
            | FrictionPotential::Nonconvex { treatment, .. } => Some(treatment),
            FrictionPotential::Regularized { .. } => None,
        }
    }

    /// The relative numerical regularization ε of the smoothed norm (its elastic slip over
    /// the point's slip scale `F/k`); `None` for exact stick/slip and for the smooth law
    /// (19).
    pub fn regularization(&self) -> Option<f64> {
        match self.treatment() {
            Some(NormTreatment::Smoothed { regularization }) => Some(regularization),
            _ => None,
        }
    }

    /// The ρ (m) of the smooth law (19) `√(r² + ρ²) − ρ`; 0 for the other potentials.
    pub fn rho(&self) -> f64 {
        match *self {
            FrictionPotential::Regularized { rho } => rho,
            _ => 0.0,
        }
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
            FrictionPotential::Nonconvex { a, unit, .. } => (1.0 - a) / (a * unit),
            _ => 0.0,
        }
    }

    /// The same law for the dimensionless slip `r̂ = r/U` (U the displacement scale, m):
    /// `ĵ(r̂) = j(U r̂)/U`, so ρ̂ = ρ/U and ℓ̂ = ℓ/U. The treatment of the norm is unchanged:
    /// its regularization is relative to each point's slip scale already.
    pub fn nondimensional(&self, displacement: f64) -> Self {
        match *self {
            FrictionPotential::Norm { treatment } => FrictionPotential::Norm { treatment },
            FrictionPotential::Nonconvex { a, unit, treatment } => FrictionPotential::Nonconvex {
                a,
                unit: unit / displacement,
                treatment,
            },
            FrictionPotential::Regularized { rho } => FrictionPotential::Regularized {
                rho: rho / displacement,
            },
        }
    }
}

impl std::fmt::Display for FrictionPotential {
    /// The potential as the scenario names it, with its parameters and the treatment of its
    /// norm, e.g. `nonconvex, a = 0.5 (elastic slip ≤ 1e-8 F/k)`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let treatment = |f: &mut std::fmt::Formatter<'_>, t: NormTreatment| match t {
            NormTreatment::Smoothed { regularization } => {
                write!(
                    f,
                    " (elastic slip ≤ {} F/k)",
                    crate::display::significant(regularization)
                )
            }
            NormTreatment::Exact => write!(f, " (exact stick/slip)"),
        };
        match *self {
            FrictionPotential::Norm { treatment: t } => {
                write!(f, "norm")?;
                treatment(f, t)
            }
            FrictionPotential::Nonconvex {
                a,
                unit,
                treatment: t,
            } => {
                write!(f, "nonconvex, a = {}", crate::display::significant(a))?;
                if unit != 1.0 {
                    write!(f, ", slip unit {} m", crate::display::significant(unit))?;
                }
                treatment(f, t)
            }
            FrictionPotential::Regularized { rho } => {
                write!(f, "regularized, ρ = {} m", crate::display::significant(rho))
            }
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
    /// The potential j, with the treatment of its norm.
    pub potential: FrictionPotential,
}

impl Friction {
    /// Checks the coefficient and the potential (exact stick/slip with a potential whose
    /// convex part is not the norm cannot be represented).
    ///
    /// # Errors
    /// [`crate::Error::Invalid`] naming the parameter: `mu` as
    /// [`FrictionCoefficient::validate`], the potential's parameters as
    /// [`FrictionPotential::validate`].
    pub fn validate(&self) -> crate::Result<()> {
        self.mu
            .validate()
            .map_err(|msg| crate::Error::invalid("mu", format!("{:?}", self.mu), msg))?;
        self.potential.validate()
    }

    /// The friction bound `F` at slip `r = ‖u_τ‖` and contact pressure `p` (one evaluation
    /// of μ; the solver evaluates μ in batches and uses [`Friction::bound_of`]).
    #[inline]
    pub fn bound_value(&self, r: f64, pressure: f64) -> f64 {
        self.bound_of(self.mu.value(r), pressure)
    }

    /// The friction bound `F` for the coefficient `mu = μ(r)` and contact pressure `p`:
    /// `μ` (Tresca) or `μ p` (Coulomb).
    #[inline]
    pub fn bound_of(&self, mu: f64, pressure: f64) -> f64 {
        match self.bound {
            FrictionBound::Tresca => mu,
            FrictionBound::Coulomb => mu * pressure,
        }
    }

    /// Whether stick/slip is exact (the norm imposed by an augmented Lagrangian).
    #[inline]
    pub fn is_exact(&self) -> bool {
        self.potential.treatment() == Some(NormTreatment::Exact)
    }

    /// Whether the law's norm is imposed through a friction multiplier τ, exactly or with
    /// an elastic slip: the potentials `norm` and `nonconvex` (not the smooth law (19)).
    #[inline]
    pub fn has_multiplier(&self) -> bool {
        self.potential.treatment().is_some()
    }

    /// The compliance `c` (m/Pa) of the elastic slip of the norm at a contact point of
    /// elastic stiffness per unit area `stiffness` (k_i, Pa/m): `ε / k_i` for a smoothed
    /// norm of relative regularization ε (a sticking point slips elastically by `c τ`),
    /// 0 for exact stick/slip, `None` for the smooth law (19).
    #[inline]
    pub fn compliance(&self, stiffness: f64) -> Option<f64> {
        match self.potential.treatment()? {
            NormTreatment::Exact => Some(0.0),
            NormTreatment::Smoothed { regularization } => Some(regularization / stiffness),
        }
    }
}
