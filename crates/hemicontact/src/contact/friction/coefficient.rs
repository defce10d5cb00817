//! The slip-dependent friction coefficient μ(r) of a friction law: built-in laws, a law of
//! the slip given in code, a field of the position given in code; its validation and its
//! dimensionless form.

use crate::contact::field_law::CustomField;
use crate::contact::slip_law::CustomCoefficient;
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
    /// ([`crate::contact::slip_law`]); not representable in a scenario file.
    #[serde(skip)]
    Custom(CustomCoefficient),
    /// A user-defined function of the position x of the contact point (reference
    /// configuration), independent of the slip, evaluated in batches
    /// ([`crate::contact::field_law`]); not representable in a scenario file.
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
