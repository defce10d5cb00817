//! The contact laws in words (`Display`), for messages and `hemicontact check`: each law
//! names itself, its formula and its parameters with their units, numbers rounded to six
//! significant digits ([`crate::display::significant`]).
//!
//! μ carries no unit here: it is dimensionless under a Coulomb-type bound and a traction
//! (Pa) under a Tresca-type bound, which [`Friction`] says.

use super::friction::{Friction, FrictionBound, FrictionCoefficient};
use super::normal::NormalLaw;
use crate::display::significant as s;
use std::fmt;

/// Table points shown in full; longer tables show their first and last points.
const SHOWN_POINTS: usize = 6;

impl fmt::Display for FrictionCoefficient {
    /// E.g. `exponential slip weakening μ(r) = (a − b) e^(−βr) + b with a = 0.4, b = 0.1,
    /// β = 100 1/m`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FrictionCoefficient::Constant { mu } => write!(f, "constant μ = {}", s(*mu)),
            FrictionCoefficient::Exponential { a, b, beta } => write!(
                f,
                "exponential slip weakening μ(r) = (a − b) e^(−βr) + b with a = {}, b = {}, \
                 β = {} 1/m",
                s(*a),
                s(*b),
                s(*beta)
            ),
            FrictionCoefficient::Table { points } => {
                write!(
                    f,
                    "piecewise linear μ(r) through {} points (r in m, μ)",
                    points.len()
                )?;
                let point = |p: &[f64; 2]| format!("({}, {})", s(p[0]), s(p[1]));
                let shown: Vec<String> = if points.len() <= SHOWN_POINTS {
                    points.iter().map(point).collect()
                } else {
                    let mut v: Vec<String> = points[..SHOWN_POINTS - 1].iter().map(point).collect();
                    v.push("…".into());
                    v.extend(points.last().map(point));
                    v
                };
                write!(f, " {}, constant beyond the last", shown.join(", "))
            }
            FrictionCoefficient::Custom(law) => {
                write!(f, "user-defined μ(r) `{}` (r in m)", law.name)
            }
            FrictionCoefficient::Field(law) => {
                write!(
                    f,
                    "user-defined μ(x) `{}` of the position (x in m)",
                    law.name
                )
            }
        }
    }
}

impl fmt::Display for FrictionBound {
    /// The bound F with its formula.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FrictionBound::Tresca => write!(f, "Tresca-type bound F = μ(‖u_τ‖) (μ in Pa)"),
            FrictionBound::Coulomb => write!(
                f,
                "Coulomb-type bound F = μ(‖u_τ‖) p(u_ν) (μ dimensionless)"
            ),
        }
    }
}

impl fmt::Display for Friction {
    /// The bound, the coefficient and the potential, e.g. `Coulomb-type bound F = μ(‖u_τ‖)
    /// p(u_ν) (μ dimensionless), μ: constant μ = 0.3, j: norm (…)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}, μ: {}, j: {}", self.bound, self.mu, self.potential)
    }
}

impl fmt::Display for NormalLaw {
    /// E.g. `normal compliance p = c_ν (u_ν − g)_+ with c_ν = 10000 Pa/m`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NormalLaw::Compliance(c) => write!(
                f,
                "normal compliance p = c_ν (u_ν − g)_+ with c_ν = {} Pa/m",
                s(c.c_nu)
            ),
            NormalLaw::Signorini => {
                write!(f, "Signorini condition u_ν ≤ g (no penetration)")
            }
            NormalLaw::Custom(law) => write!(
                f,
                "user-defined normal compliance p(u_ν − g) `{}` (Pa, penetration in m)",
                law.name
            ),
        }
    }
}

impl fmt::Display for super::obstacle::ObstacleSpec {
    /// E.g. `rigid circle, centre (5, 14.99) m, radius 10 m, translated by (0, −0.02) m`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use super::obstacle::Obstacle;
        let v = |x: &[f64]| {
            let c: Vec<String> = x.iter().map(|&c| s(c)).collect();
            format!("({})", c.join(", "))
        };
        match &self.shape {
            Obstacle::Plane { point, normal } => write!(
                f,
                "rigid plane through {} m, normal {} (towards the body)",
                v(point),
                v(normal)
            )?,
            Obstacle::Circle { center, radius } | Obstacle::Sphere { center, radius } => write!(
                f,
                "rigid {}, centre {} m, radius {} m",
                self.shape.kind(),
                v(center),
                s(*radius)
            )?,
            Obstacle::Cylinder {
                point,
                axis,
                radius,
            } => write!(
                f,
                "rigid cylinder, axis through {} m along {}, radius {} m",
                v(point),
                v(axis),
                s(*radius)
            )?,
            Obstacle::Paraboloid { apex, axis, radius } => write!(
                f,
                "rigid paraboloid z = r²/(2R), apex {} m, axis {} (into the indenter), R = {} m",
                v(apex),
                v(axis),
                s(*radius)
            )?,
        }
        match &self.displacement {
            Some(t) => write!(f, ", translated by {} m", v(t)),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn laws_name_themselves_with_rounded_parameters() {
        let mu = FrictionCoefficient::Exponential {
            a: 0.4,
            b: 0.1,
            beta: 100.0,
        };
        assert_eq!(
            mu.to_string(),
            "exponential slip weakening μ(r) = (a − b) e^(−βr) + b with a = 0.4, b = 0.1, \
             β = 100 1/m"
        );
        let mu = FrictionCoefficient::Constant {
            mu: 0.1 + 0.2, // 0.30000000000000004
        };
        assert_eq!(mu.to_string(), "constant μ = 0.3");
        let table = FrictionCoefficient::Table {
            points: vec![[0.0, 0.4], [0.01, 0.1]],
        };
        assert_eq!(
            table.to_string(),
            "piecewise linear μ(r) through 2 points (r in m, μ) (0, 0.4), (0.01, 0.1), \
             constant beyond the last"
        );
        let long = FrictionCoefficient::Table {
            points: (0..10).map(|k| [k as f64, 0.5]).collect(),
        };
        let text = long.to_string();
        assert!(
            text.contains("10 points") && text.contains("…, (9, 0.5)"),
            "{text}"
        );
        let law = NormalLaw::Compliance(super::super::NormalCompliance { c_nu: 1e4 });
        assert_eq!(
            law.to_string(),
            "normal compliance p = c_ν (u_ν − g)_+ with c_ν = 10000 Pa/m"
        );
        assert!(!format!("{mu:?}").is_empty());
    }
}
