//! User-defined friction coefficients that vary along the interface: μ(x), a function of
//! the position x of a contact point in the reference configuration, evaluated in batches.
//!
//! The typical use is a Tresca bound `F(x)` (Pa) that changes along Γ_C (a weaker patch, a
//! graded interface); with a Coulomb-type bound it is a coefficient μ(x) varying in space.
//! The law does not depend on the slip, so it adds no nonmonotone term: its Lipschitz
//! constant in the slip is 0 and `μ₀ = sup μ` is its largest value at the contact points.
//!
//! A [`PositionFunction`] computes μ at many points in one call. The solver calls it once
//! per contact part with the positions of all the part's points: once at the starting
//! displacement, once per outer iteration and once for the certificate.
//!
//! [`CustomField`] wraps the function with a name and the units of the solver's
//! dimensionless variables ([`crate::solver::scaling`]): the solver works with positions
//! `x̂ = x/length_unit` and values `μ̂ = μ/value_unit`. The function itself always receives
//! positions in metres and returns μ in the user's units: dimensionless for a Coulomb-type
//! bound, Pa for a Tresca-type bound. Its values are checked after every call: a
//! non-finite or negative value is an error naming the point.

use std::sync::Arc;

/// A friction coefficient μ(x) of the position x, evaluated at many points at once.
pub trait PositionFunction: Send + Sync + std::fmt::Debug {
    /// Writes μ(x) at every point `points[i]` (m; the first `dim` coordinates are used, the
    /// others are 0) into `out[i]` (same length): dimensionless for a Coulomb-type bound, Pa
    /// for a Tresca-type bound. Every value must be finite and ≥ 0.
    ///
    /// # Errors
    /// A message saying what went wrong; the solve stops with it.
    fn evaluate(&self, points: &[[f64; 3]], dim: usize, out: &mut [f64]) -> Result<(), String>;
}

/// A user-defined friction coefficient of the position: a named [`PositionFunction`] with
/// the units of the dimensionless rewrite (see the module documentation). Two are equal when
/// they share the same function object (`Arc::ptr_eq`), name and units.
#[derive(Clone)]
pub struct CustomField {
    /// The name shown in messages, e.g. `weak_patch`.
    pub name: String,
    /// The function μ(x), positions in metres.
    pub law: Arc<dyn PositionFunction>,
    /// Length unit of the solver's positions (m): the function receives `x̂ · length_unit`.
    pub length_unit: f64,
    /// Value unit of the solver's variables: the solver uses `μ / value_unit`.
    pub value_unit: f64,
}

impl CustomField {
    /// The law `law` named `name`, in the user's units (both units 1).
    pub fn new(name: impl Into<String>, law: Arc<dyn PositionFunction>) -> Self {
        CustomField {
            name: name.into(),
            law,
            length_unit: 1.0,
            value_unit: 1.0,
        }
    }

    /// `out[i] = μ̂(x̂_i) = μ(x̂_i · length_unit) / value_unit` at the points `points` (solver's
    /// units), by one call of the function.
    ///
    /// # Errors
    /// The function's error, or a value that is not finite or negative, naming the point
    /// (m).
    pub fn values(&self, points: &[[f64; 3]], dim: usize, out: &mut [f64]) -> Result<(), String> {
        let x: Vec<[f64; 3]> = points
            .iter()
            .map(|p| p.map(|c| c * self.length_unit))
            .collect();
        out.fill(f64::NAN);
        self.law
            .evaluate(&x, dim, out)
            .map_err(|e| format!("the function failed at {} points: {e}", x.len()))?;
        if let Some((p, mu)) = x
            .iter()
            .zip(out.iter())
            .find(|(_, mu)| !(mu.is_finite() && **mu >= 0.0))
        {
            return Err(format!(
                "μ(x = {:?} m) = {mu}: a friction coefficient or bound must be finite and ≥ 0 \
                 at every contact point",
                &p[..dim]
            ));
        }
        if self.value_unit != 1.0 {
            out.iter_mut().for_each(|v| *v /= self.value_unit);
        }
        Ok(())
    }

    /// The same law for positions in units of `length` (m) and values in units of `value`:
    /// the units are multiplied, the function is untouched.
    pub fn nondimensional(&self, length: f64, value: f64) -> Self {
        CustomField {
            length_unit: self.length_unit * length,
            value_unit: self.value_unit * value,
            ..self.clone()
        }
    }

    /// Checks the units (the values are checked at the contact points, which only a
    /// [`crate::problem::Problem`] knows).
    ///
    /// # Errors
    /// A message naming the unit that is not finite and > 0.
    pub fn validate(&self) -> Result<(), String> {
        super::slip_law::check_units(
            &self.name,
            &[
                ("length_unit", self.length_unit),
                ("value_unit", self.value_unit),
            ],
        )
    }
}

impl PartialEq for CustomField {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.law, &other.law)
            && self.name == other.name
            && self.length_unit == other.length_unit
            && self.value_unit == other.value_unit
    }
}

impl std::fmt::Debug for CustomField {
    /// The name, with the units when they are not 1.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:?} of the position", self.name)?;
        if self.length_unit != 1.0 || self.value_unit != 1.0 {
            write!(
                f,
                " (length unit {:e} m, value unit {:e})",
                self.length_unit, self.value_unit
            )?;
        }
        Ok(())
    }
}
