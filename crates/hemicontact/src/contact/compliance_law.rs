//! User-defined normal compliance laws: a contact pressure `p(δ)` of the penetration
//! `δ = u_ν − g` with its derivative `p'(δ)`, evaluated in batches.
//!
//! The law is `−σ_ν = p(δ)` for `δ > 0` and 0 for `δ ≤ 0`, with `p` nondecreasing (a
//! monotone law, so the contact energy `P(δ) = ∫₀^δ p` is convex and the convex problems of
//! the solver stay convex), `p(0) = 0` (no pressure at first contact) and `p ≥ 0`.
//!
//! Unlike a friction coefficient, the normal law is not frozen within an outer iteration:
//! the solver needs `p`, `p'` and `P` at every evaluation of the energy (each Newton step and
//! each line-search trial). [`CustomCompliance::responses`] computes them for all the
//! penetrating points of a contact part in two calls: one of `p` (at the penetrations and at
//! the [`GAUSS_POINTS`] Gauss–Legendre nodes of every interval `[0, δ]`, from which `P`
//! follows) and, when the Hessian is wanted, one of `p'`. The quadrature is exact for `p` a
//! polynomial of degree ≤ 15; for other laws `P` carries the quadrature error, which only
//! the line search's sufficient-decrease test sees (the gradient and the Hessian use `p`
//! and `p'` themselves).
//!
//! [`CustomCompliance`] wraps the functions with a name and the units of the solver's
//! dimensionless variables ([`crate::solver::scaling`]): the solver works with
//! `δ̂ = δ/displacement_unit` and `p̂ = p/pressure_unit`. The functions always receive
//! penetrations in metres and return Pa (p) and Pa/m (p'). Every value is checked: a
//! non-finite or negative value is an error naming the penetration.

use std::sync::Arc;

/// A normal compliance law `p(δ)` with its derivative, evaluated at many penetrations at
/// once.
pub trait ComplianceFunction: Send + Sync + std::fmt::Debug {
    /// Writes the contact pressure `p(δ)` (Pa) at every penetration `penetration[i]` (m,
    /// ≥ 0) into `out[i]`.
    ///
    /// # Errors
    /// A message saying what went wrong; the solve stops with it.
    fn pressure(&self, penetration: &[f64], out: &mut [f64]) -> Result<(), String>;

    /// Writes the derivative `p'(δ)` (Pa/m) at every penetration `penetration[i]` (m, ≥ 0)
    /// into `out[i]`.
    ///
    /// # Errors
    /// A message saying what went wrong; the solve stops with it.
    fn stiffness(&self, penetration: &[f64], out: &mut [f64]) -> Result<(), String>;
}

/// Number of Gauss–Legendre nodes of the energy quadrature `P(δ) = ∫₀^δ p`.
pub const GAUSS_POINTS: usize = 8;

/// Gauss–Legendre nodes on [−1, 1] (positive half; the rule is symmetric) and weights.
const GAUSS_LEGENDRE_8: [(f64, f64); 4] = [
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
];

/// The normal response of one contact point: energy, pressure and stiffness, in the
/// solver's units.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NormalResponse {
    /// Energy density `P(δ) = ∫₀^δ p` per unit area (J/m², N/m in 2D per unit thickness).
    pub energy: f64,
    /// Contact pressure `p(δ) ≥ 0` (Pa).
    pub pressure: f64,
    /// Derivative `p'(δ) ≥ 0` (Pa/m), 0 when not asked for.
    pub stiffness: f64,
}

/// A user-defined normal compliance: a named [`ComplianceFunction`] with the units of the
/// dimensionless rewrite (see the module documentation). Two are equal when they share the
/// same function object (`Arc::ptr_eq`), name and units.
#[derive(Clone)]
pub struct CustomCompliance {
    /// The name shown in messages, e.g. `contact[0].normal (power_law)`.
    pub name: String,
    /// The functions p and p', penetrations in metres.
    pub law: Arc<dyn ComplianceFunction>,
    /// Displacement unit of the solver's penetrations (m).
    pub displacement_unit: f64,
    /// Pressure unit of the solver's pressures (Pa).
    pub pressure_unit: f64,
}

impl CustomCompliance {
    /// The law `law` named `name`, in the user's units (both units 1).
    pub fn new(name: impl Into<String>, law: Arc<dyn ComplianceFunction>) -> Self {
        CustomCompliance {
            name: name.into(),
            law,
            displacement_unit: 1.0,
            pressure_unit: 1.0,
        }
    }

    /// The responses at the penetrations `penetration` (solver's units; entries ≤ 0 give
    /// zero response without a call) into `out` (same length): pressure and energy always,
    /// the stiffness if `stiffness`. At most two calls of the functions.
    ///
    /// # Errors
    /// A function's error, or a value that is not finite or negative, naming the
    /// penetration (m).
    pub fn responses(
        &self,
        penetration: &[f64],
        stiffness: bool,
        out: &mut [NormalResponse],
    ) -> Result<(), String> {
        out.fill(NormalResponse::default());
        let active: Vec<usize> = (0..penetration.len())
            .filter(|&i| penetration[i] > 0.0)
            .collect();
        if active.is_empty() {
            return Ok(());
        }
        let (u, t) = (self.displacement_unit, self.pressure_unit);
        // The penetrations (m), then the quadrature nodes of each interval [0, δ].
        let m = active.len();
        let mut x = Vec::with_capacity(m * (1 + GAUSS_POINTS));
        x.extend(active.iter().map(|&i| penetration[i] * u));
        for &i in &active {
            let half = 0.5 * penetration[i] * u;
            for &(s, _) in &GAUSS_LEGENDRE_8 {
                x.push(half * (1.0 - s));
                x.push(half * (1.0 + s));
            }
        }
        let mut p = vec![0.0; x.len()];
        self.call("p", &x, &mut p, |law, x, out| law.pressure(x, out))?;
        for (k, &i) in active.iter().enumerate() {
            let nodes = &p[m + k * GAUSS_POINTS..m + (k + 1) * GAUSS_POINTS];
            let integral: f64 = GAUSS_LEGENDRE_8
                .iter()
                .enumerate()
                .map(|(j, &(_, w))| w * (nodes[2 * j] + nodes[2 * j + 1]))
                .sum::<f64>()
                * 0.5
                * x[k];
            out[i].pressure = p[k] / t;
            out[i].energy = integral / (t * u);
        }
        if stiffness {
            let mut dp = vec![0.0; m];
            self.call("dp", &x[..m], &mut dp, |law, x, out| law.stiffness(x, out))?;
            for (k, &i) in active.iter().enumerate() {
                out[i].stiffness = dp[k] * u / t;
            }
        }
        Ok(())
    }

    /// One checked call of `which` (`p` or `dp`) at penetrations `x` (m).
    fn call(
        &self,
        which: &str,
        x: &[f64],
        out: &mut [f64],
        f: impl Fn(&dyn ComplianceFunction, &[f64], &mut [f64]) -> Result<(), String>,
    ) -> Result<(), String> {
        out.fill(f64::NAN);
        f(self.law.as_ref(), x, out)
            .map_err(|e| format!("{which} failed at {} penetrations: {e}", x.len()))?;
        match x
            .iter()
            .zip(out.iter())
            .find(|(_, v)| !(v.is_finite() && **v >= 0.0))
        {
            Some((x, v)) => Err(format!(
                "{which}(δ = {x:e} m) = {v}: must be finite and ≥ 0 at every penetration"
            )),
            None => Ok(()),
        }
    }

    /// The same law for penetrations in units of `displacement` (m) and pressures in units
    /// of `pressure` (Pa): the units are multiplied, the functions are untouched.
    pub fn nondimensional(&self, displacement: f64, pressure: f64) -> Self {
        CustomCompliance {
            displacement_unit: self.displacement_unit * displacement,
            pressure_unit: self.pressure_unit * pressure,
            ..self.clone()
        }
    }

    /// Checks the units and samples the law at δ = 0 and at `δ_k = length · 10^(−k/10)`,
    /// k = 0, …, 100 (from the body's size `length` (m) down to 1e-10 of it): `p(0) = 0`,
    /// `p` and `p'` finite and ≥ 0, `p` nondecreasing, and `p'` the slope of `p` (within
    /// 1e-3 of the centred difference quotient with relative step 1e-6, relative to
    /// `|p'| + p/δ`).
    ///
    /// # Errors
    /// A message naming the first sample where a check fails, or a function's error.
    pub fn validate(&self, length: f64) -> Result<(), String> {
        super::slip_law::check_units(
            &self.name,
            &[
                ("displacement_unit", self.displacement_unit),
                ("pressure_unit", self.pressure_unit),
            ],
        )?;
        let mut x: Vec<f64> = vec![0.0];
        x.extend(
            (0..=100)
                .rev()
                .map(|k| length * 10f64.powf(-f64::from(k) / 10.0)),
        );
        let h = 1e-6;
        let plus: Vec<f64> = x.iter().map(|d| d * (1.0 + h)).collect();
        let minus: Vec<f64> = x.iter().map(|d| d * (1.0 - h)).collect();
        let all: Vec<f64> = [x.as_slice(), &plus, &minus].concat();
        let mut p = vec![0.0; all.len()];
        self.call("p", &all, &mut p, |law, x, out| law.pressure(x, out))?;
        let mut dp = vec![0.0; x.len()];
        self.call("dp", &x, &mut dp, |law, x, out| law.stiffness(x, out))?;
        let n = x.len();
        if p[0] != 0.0 {
            return Err(format!(
                "p(0) = {:e} Pa: the pressure must vanish at first contact, p(0) = 0",
                p[0]
            ));
        }
        if let Some(k) = (1..n).find(|&k| p[k] < p[k - 1]) {
            return Err(format!(
                "p({:e} m) = {:e} Pa < p({:e} m) = {:e} Pa: the law must be monotone (p \
                 nondecreasing)",
                x[k],
                p[k],
                x[k - 1],
                p[k - 1]
            ));
        }
        for k in 1..n {
            let slope = (p[n + k] - p[2 * n + k]) / (plus[k] - minus[k]);
            let scale = dp[k].abs() + p[k] / x[k];
            if (dp[k] - slope).abs() > 1e-3 * scale {
                return Err(format!(
                    "dp({:e} m) = {:e} Pa/m, but the slope of p there is {slope:e} Pa/m: dp \
                     must be the derivative of p",
                    x[k], dp[k]
                ));
            }
        }
        Ok(())
    }
}

impl PartialEq for CustomCompliance {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.law, &other.law)
            && self.name == other.name
            && self.displacement_unit == other.displacement_unit
            && self.pressure_unit == other.pressure_unit
    }
}

impl std::fmt::Debug for CustomCompliance {
    /// The name, with the units when they are not 1.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:?}", self.name)?;
        if self.displacement_unit != 1.0 || self.pressure_unit != 1.0 {
            write!(
                f,
                " (displacement unit {:e} m, pressure unit {:e} Pa)",
                self.displacement_unit, self.pressure_unit
            )?;
        }
        Ok(())
    }
}
