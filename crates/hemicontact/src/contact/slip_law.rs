//! User-defined friction coefficients μ(r): a function of the slip evaluated in batches.
//!
//! A [`SlipFunction`] computes μ at many slips in one call. The solver calls it once per
//! contact part with the slips of all the part's points, never point by point: once at the
//! starting displacement, once per outer iteration (the friction data of the
//! convexification) and once for the certificate. This lets a caller in another language
//! (a Python callable on a numpy array) pay its calling cost a few times per solve.
//!
//! [`CustomCoefficient`] wraps the function with a name and the units of the dimensionless
//! rewrite of the solver ([`crate::solver::scaling`]): the solver works with slips
//! `r̂ = r/slip_unit` and values `μ̂ = μ/value_unit`, so `μ̂(r̂) = μ(r̂ · slip_unit) /
//! value_unit`. The function itself always receives slips in metres and returns μ in the
//! user's units: dimensionless for a Coulomb-type bound, a traction (Pa) for a Tresca-type
//! bound.
//!
//! The function's values are checked after every call: a non-finite or negative value is an
//! error naming the slip, and so is an error returned by the function
//! ([`crate::Error::Law`] once the solver names the contact part).
//!
//! # Sampled properties
//!
//! Validation, `sup μ` and the Lipschitz constant of a custom law come from samples on the
//! grid [`sample_slips`]: r = 0 and the geometric range `10^(k/10)` m, k = −100, …, 20
//! (1e-10 m to 100 m, ten points per decade). `sup μ` is the largest sampled value and the
//! Lipschitz constant the largest secant slope between neighbouring samples: both are
//! *estimates* (lower bounds of the true values, exact for a law monotone between the
//! samples with its steepest slope at r = 0, such as slip weakening), and the uniqueness
//! check says so.

use std::sync::Arc;

/// A friction coefficient μ(r) of the slip r = ‖u_τ‖, evaluated at many slips at once.
pub trait SlipFunction: Send + Sync + std::fmt::Debug {
    /// Writes μ(r) at every slip `slips[i]` (m, finite and ≥ 0) into `out[i]` (same
    /// length): dimensionless for a Coulomb-type bound, Pa for a Tresca-type bound. Every
    /// value must be finite and ≥ 0.
    ///
    /// # Errors
    /// A message saying what went wrong; the solve stops with it.
    fn evaluate(&self, slips: &[f64], out: &mut [f64]) -> Result<(), String>;
}

/// A user-defined friction coefficient: a named [`SlipFunction`] with the units of the
/// dimensionless rewrite (see the module documentation). Two custom coefficients are equal
/// when they share the same function object (`Arc::ptr_eq`), name and units.
#[derive(Clone)]
pub struct CustomCoefficient {
    /// The name shown in messages, e.g. `my_law`.
    pub name: String,
    /// The function μ(r), slips in metres.
    pub law: Arc<dyn SlipFunction>,
    /// Slip unit of the solver's variables (m): the function receives `r̂ · slip_unit`.
    /// 1 for a law in the user's units.
    pub slip_unit: f64,
    /// Value unit of the solver's variables: the solver uses `μ / value_unit` (1, or the
    /// traction unit in Pa for a Tresca-type bound). 1 for a law in the user's units.
    pub value_unit: f64,
}

impl CustomCoefficient {
    /// The law `law` named `name`, in the user's units (both units 1).
    pub fn new(name: impl Into<String>, law: Arc<dyn SlipFunction>) -> Self {
        CustomCoefficient {
            name: name.into(),
            law,
            slip_unit: 1.0,
            value_unit: 1.0,
        }
    }

    /// `out[i] = μ̂(r̂_i) = μ(r̂_i · slip_unit) / value_unit` for the slips `slips` in the
    /// solver's units, by one call of the function.
    ///
    /// # Errors
    /// The function's error, or a value that is not finite or negative, naming the slip
    /// (m).
    pub fn values(&self, slips: &[f64], out: &mut [f64]) -> Result<(), String> {
        let r: Vec<f64> = slips.iter().map(|s| s * self.slip_unit).collect();
        self.evaluate_checked(&r, out)?;
        if self.value_unit != 1.0 {
            out.iter_mut().for_each(|x| *x /= self.value_unit);
        }
        Ok(())
    }

    /// μ at slips `r` (m), in the user's units, checked: one call of the function. Entries
    /// the function leaves unwritten are NaN, hence an error.
    fn evaluate_checked(&self, r: &[f64], out: &mut [f64]) -> Result<(), String> {
        out.fill(f64::NAN);
        if let Err(e) = self.law.evaluate(r, out) {
            let (lo, hi) = r
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                    (a.min(x), b.max(x))
                });
            return Err(format!(
                "the function failed on the slips of {} points (r from {lo:e} to {hi:e} m): {e}",
                r.len()
            ));
        }
        match r
            .iter()
            .zip(out.iter())
            .find(|(_, mu)| !(mu.is_finite() && **mu >= 0.0))
        {
            Some((r, mu)) => Err(format!(
                "μ(r = {r:e} m) = {mu}: a friction coefficient must be finite and ≥ 0 at \
                 every slip"
            )),
            None => Ok(()),
        }
    }

    /// μ̂(r̂) at one slip (solver's units): one call of the function; NaN if it fails
    /// (prefer [`CustomCoefficient::values`], which says why).
    pub fn value(&self, r: f64) -> f64 {
        let mut out = [0.0];
        self.values(&[r], &mut out).map_or(f64::NAN, |()| out[0])
    }

    /// The samples `(r (m), μ(r) in the user's units)` on [`sample_slips`].
    ///
    /// # Errors
    /// As [`CustomCoefficient::values`].
    pub fn samples(&self) -> Result<(Vec<f64>, Vec<f64>), String> {
        let r = sample_slips();
        let mut mu = vec![0.0; r.len()];
        self.evaluate_checked(&r, &mut mu)?;
        Ok((r, mu))
    }

    /// Estimate of `sup μ̂` from the samples (see the module documentation); NaN if the
    /// function fails on them.
    pub fn sup(&self) -> f64 {
        self.samples().map_or(f64::NAN, |(_, mu)| {
            mu.iter().fold(0.0, |a: f64, &b| a.max(b)) / self.value_unit
        })
    }

    /// Estimate of the Lipschitz constant of μ̂ from the samples: the largest secant slope
    /// between neighbouring samples (see the module documentation); NaN if the function
    /// fails on them.
    pub fn lipschitz(&self) -> f64 {
        self.samples().map_or(f64::NAN, |(r, mu)| {
            let slope = (1..r.len())
                .map(|k| ((mu[k] - mu[k - 1]) / (r[k] - r[k - 1])).abs())
                .fold(0.0, f64::max);
            slope * self.slip_unit / self.value_unit
        })
    }

    /// The same law for slips in units of `displacement` (m) and values in units of
    /// `value`: the units are multiplied, the function is untouched.
    pub fn nondimensional(&self, displacement: f64, value: f64) -> Self {
        CustomCoefficient {
            slip_unit: self.slip_unit * displacement,
            value_unit: self.value_unit * value,
            ..self.clone()
        }
    }

    /// Checks the units and samples the law on [`sample_slips`].
    ///
    /// # Errors
    /// A message naming the law and the first sampled slip where μ is not finite or
    /// negative, or the function's error.
    pub fn validate(&self) -> Result<(), String> {
        check_units(
            &self.name,
            &[
                ("slip_unit", self.slip_unit),
                ("value_unit", self.value_unit),
            ],
        )?;
        self.samples().map(|_| ()).map_err(|e| {
            format!(
                "custom law `{}` sampled at 0 and 1e-10 … 100 m: {e}",
                self.name
            )
        })
    }
}

/// Checks the units of the dimensionless rewrite of the user-defined law `law`: each
/// `(name, value)` finite and > 0.
///
/// # Errors
/// A message naming the first unit that is not.
pub(crate) fn check_units(law: &str, units: &[(&str, f64)]) -> Result<(), String> {
    match units.iter().find(|(_, x)| !(x.is_finite() && *x > 0.0)) {
        Some((name, x)) => Err(format!("{name} = {x} of `{law}`: a finite unit > 0")),
        None => Ok(()),
    }
}

/// The slips (m) at which a custom law is sampled for validation and for the estimates of
/// `sup μ` and its Lipschitz constant: 0 and `10^(k/10)` m for k = −100, …, 20.
pub fn sample_slips() -> Vec<f64> {
    std::iter::once(0.0)
        .chain((-100..=20).map(|k| 10f64.powf(f64::from(k) / 10.0)))
        .collect()
}

impl PartialEq for CustomCoefficient {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.law, &other.law)
            && self.name == other.name
            && self.slip_unit == other.slip_unit
            && self.value_unit == other.value_unit
    }
}

impl std::fmt::Debug for CustomCoefficient {
    /// The name, with the units when they are not 1: `"my_law"` or
    /// `"my_law" (slip unit 1e-3 m, value unit 1)`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:?}", self.name)?;
        if self.slip_unit != 1.0 || self.value_unit != 1.0 {
            write!(
                f,
                " (slip unit {:e} m, value unit {:e})",
                self.slip_unit, self.value_unit
            )?;
        }
        Ok(())
    }
}
