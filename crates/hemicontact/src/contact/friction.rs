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
//! The norm is nonsmooth at 0. For the potentials whose convex part is the norm (`norm`,
//! `nonconvex`) the law says how the term `F ‖·‖` is treated ([`NormTreatment`]): exactly,
//! or with a small elastic slip; both through the friction multiplier τ. The regularized
//! law (19) is smooth already and carries no treatment, so exact stick/slip of a smooth law
//! cannot be expressed.
//!
//! ## The smoothed norm: an elastic slip on the point's own scale
//!
//! The smoothed norm of contact point i is exact friction in series with an elastic slip
//! of compliance `c_i = ε / k_i` (m/Pa): ε the law's `regularization`, `k_i = S / h_i` the
//! point's elastic stiffness per unit area (S the P-wave modulus, `h_i` the local mesh size;
//! [`crate::solver::constraints::contact_stiffness`]). Its friction traction is
//! `τ = proj_{B_F}(ξ / c_i)`: a sticking point slips elastically by `c_i ‖τ‖ ≤ ε F_i / k_i`,
//! a slipping point carries exactly the bound. `F_i / k_i` is the slip over which the
//! friction bound deforms the body around the point, so the regularization is relative to
//! the point's own scales, whatever the loads or displacements elsewhere. The law is the
//! Moreau–Yosida regularization of `F‖·‖`, and it is solved like exact friction: the
//! augmented Lagrangian of the series law is the Moreau envelope with the compliances
//! added, `1/r' = 1/r + c_i`, so the Newton matrix never sees a stiffness above the penalty
//! r, however small ε.
//!
//! ## The tangential term of one contact point
//!
//! With the frozen bound `F ≥ 0`, linear term `b` (the linearized concave part), the
//! tangential energy at slip ξ is ([`Friction::tangential_term`])
//!
//! - law (19): `F φ_ρ(ξ) − b·ξ`, `φ_ρ(ξ) = √(‖ξ‖² + ρ²) − ρ`;
//! - the norm, multiplier τ (the friction traction), penalty r and compliance c (0 when
//!   exact): the augmented Lagrangian `H_F(z)/r' − ‖τ‖²/(2r) − b·ξ` with
//!   `z = r'ξ + (r'/r)τ`, `r' = r/(1 + rc)` (`z = τ + rξ` when exact), the Huber function
//!   `H_F(z) = ‖z‖²/2` (‖z‖ ≤ F), `F‖z‖ − F²/2` (‖z‖ > F), whose gradient is the projection
//!   `proj_{B_F}(z)` onto the ball of radius F; the multiplier update is
//!   `τ ← proj_{B_F}(z)` ([`Friction::updated_traction`]), whose fixed point is the law.

use super::field_law::CustomField;
use super::slip_law::CustomCoefficient;
use serde::{Deserialize, Serialize};

/// The slip-dependent friction coefficient μ(r), r = ‖u_τ‖ ≥ 0 (dimensionless for a
/// Coulomb-type bound, Pa for a Tresca-type bound).
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
    /// A user-defined function of the slip, evaluated in batches
    /// ([`super::slip_law`]); not representable in a scenario file.
    #[serde(skip)]
    Custom(CustomCoefficient),
    /// A user-defined function of the position x of the contact point (reference
    /// configuration), independent of the slip, evaluated in batches
    /// ([`super::field_law`]); not representable in a scenario file.
    #[serde(skip)]
    Field(CustomField),
}

impl FrictionCoefficient {
    /// μ(r). A custom law is called with this one slip (NaN if it fails); a law of the
    /// position has no value without a point (NaN). The solver uses
    /// [`FrictionCoefficient::values`].
    pub fn value(&self, r: f64) -> f64 {
        match self {
            FrictionCoefficient::Custom(law) => law.value(r),
            FrictionCoefficient::Field(_) => f64::NAN,
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

    /// `out[i] = μ(slips[i])` (at the point `positions[i]`, in `dim` dimensions) for all
    /// points at once: the built-in laws point by point with [`FrictionCoefficient::value`],
    /// a custom law by one call of its function, of the slips or of the positions.
    ///
    /// # Errors
    /// Only a custom law: its function's error, or a value not finite or negative, naming
    /// the slip or the point ([`CustomCoefficient::values`], [`CustomField::values`]).
    pub fn values(
        &self,
        slips: &[f64],
        positions: &[[f64; 3]],
        dim: usize,
        out: &mut [f64],
    ) -> Result<(), String> {
        match self {
            FrictionCoefficient::Custom(law) => law.values(slips, out),
            FrictionCoefficient::Field(law) => law.values(positions, dim, out),
            _ => {
                for (mu, &r) in out.iter_mut().zip(slips) {
                    *mu = self.value(r);
                }
                Ok(())
            }
        }
    }

    /// The law's name for messages: `constant`, `exponential`, `table` or the custom
    /// law's name.
    pub fn name(&self) -> &str {
        match self {
            FrictionCoefficient::Constant { .. } => "constant",
            FrictionCoefficient::Exponential { .. } => "exponential",
            FrictionCoefficient::Table { .. } => "table",
            FrictionCoefficient::Custom(law) => &law.name,
            FrictionCoefficient::Field(law) => &law.name,
        }
    }

    /// Whether μ depends on the slip: a nonzero Lipschitz constant, or a custom law
    /// (always taken as slip-dependent).
    pub fn is_slip_dependent(&self) -> bool {
        matches!(self, FrictionCoefficient::Custom(_)) || self.lipschitz() > 0.0
    }

    /// Whether μ is a function of the position ([`FrictionCoefficient::Field`]).
    pub fn is_field(&self) -> bool {
        matches!(self, FrictionCoefficient::Field(_))
    }

    /// Whether `sup μ` and the Lipschitz constant are estimates from samples (a custom
    /// law) rather than exact.
    pub fn is_estimated(&self) -> bool {
        matches!(self, FrictionCoefficient::Custom(_))
    }

    /// Upper bound μ₀ = sup μ; for a custom law of the slip an estimate from samples
    /// ([`CustomCoefficient::sup`]); NaN for a law of the position, whose supremum is its
    /// largest value at the contact points (the uniqueness check evaluates it there).
    pub fn sup(&self) -> f64 {
        match self {
            FrictionCoefficient::Custom(law) => law.sup(),
            FrictionCoefficient::Field(_) => f64::NAN,
            FrictionCoefficient::Constant { mu } => *mu,
            FrictionCoefficient::Exponential { a, b, .. } => a.max(*b),
            FrictionCoefficient::Table { points } => {
                points.iter().map(|p| p[1]).fold(0.0, f64::max)
            }
        }
    }

    /// Lipschitz constant L_μ in the slip; for a custom law of the slip an estimate from
    /// samples ([`CustomCoefficient::lipschitz`]); 0 for a law of the position.
    pub fn lipschitz(&self) -> f64 {
        match self {
            FrictionCoefficient::Custom(law) => law.lipschitz(),
            FrictionCoefficient::Field(_) => 0.0,
            FrictionCoefficient::Constant { .. } => 0.0,
            FrictionCoefficient::Exponential { a, b, beta } => (a - b).abs() * beta,
            FrictionCoefficient::Table { points } => points
                .windows(2)
                .map(|w| ((w[1][1] - w[0][1]) / (w[1][0] - w[0][0])).abs())
                .fold(0.0, f64::max),
        }
    }

    /// The same law in dimensionless variables: slips in units of `displacement` (m),
    /// positions in units of `length` (m) and values in units of `value` (1 for a
    /// Coulomb-type coefficient, the traction unit for a Tresca bound):
    /// `μ̂(r̂) = μ(U r̂)/value`, so β̂ = βU, table slips r/U and values μ/value; a custom law
    /// gets these units, its function is untouched.
    pub fn nondimensional(&self, displacement: f64, length: f64, value: f64) -> Self {
        match self {
            FrictionCoefficient::Custom(law) => {
                FrictionCoefficient::Custom(law.nondimensional(displacement, value))
            }
            FrictionCoefficient::Field(law) => {
                FrictionCoefficient::Field(law.nondimensional(length, value))
            }
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

    /// Checks the parameters; returns what is wrong. A custom law is sampled
    /// ([`CustomCoefficient::validate`]).
    ///
    /// # Errors
    /// A message naming the parameter (or the custom law and the slip) and what is allowed.
    pub fn validate(&self) -> Result<(), String> {
        let ok = |x: f64| x.is_finite() && x >= 0.0;
        match self {
            FrictionCoefficient::Custom(law) => law.validate(),
            FrictionCoefficient::Field(law) => law.validate(),
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
