//! Normal compliance: `−σ_ν = p(u_ν) = c_ν (u_ν − g)_+`, the reaction of
//! deformable asperities, with energy `P(u_ν) = (c_ν/2)(u_ν − g)_+²`; a user-defined
//! monotone compliance `p(u_ν − g)` ([`super::compliance_law`]); or the Signorini
//! condition of a rigid foundation.

use super::compliance_law::CustomCompliance;

/// Normal compliance with stiffness `c_nu` (Pa/m, i.e. pressure per penetration).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalCompliance {
    /// Stiffness c_ν > 0 of the asperities (Pa/m).
    pub c_nu: f64,
}

impl NormalCompliance {
    /// Energy density `P = (c_ν/2)(u_ν − g)_+²` per unit area.
    #[inline]
    pub fn energy(&self, u_nu: f64, gap: f64) -> f64 {
        let s = (u_nu - gap).max(0.0);
        0.5 * self.c_nu * s * s
    }

    /// Contact pressure `p = c_ν (u_ν − g)_+ ≥ 0`.
    #[inline]
    pub fn pressure(&self, u_nu: f64, gap: f64) -> f64 {
        self.c_nu * (u_nu - gap).max(0.0)
    }

    /// Generalized derivative `p'(u_ν) = c_ν H(u_ν − g)` (0 at the kink).
    #[inline]
    pub fn stiffness(&self, u_nu: f64, gap: f64) -> f64 {
        if u_nu > gap {
            self.c_nu
        } else {
            0.0
        }
    }
}

/// The normal contact law of a contact boundary.
#[derive(Clone, Debug, PartialEq)]
pub enum NormalLaw {
    /// Normal compliance `p = c_ν (u_ν − g)_+` (deformable asperities).
    Compliance(NormalCompliance),
    /// The Signorini condition of a rigid foundation: `u_ν ≤ g`, `p ≥ 0`, `p (u_ν − g) = 0`,
    /// the contact pressure p being the Lagrange multiplier of the constraint (imposed by
    /// the augmented Lagrangian of [`crate::solver::constraints`]).
    Signorini,
    /// A user-defined monotone compliance `p(u_ν − g)` with its derivative, evaluated in
    /// batches ([`super::compliance_law`]).
    Custom(CustomCompliance),
}

impl NormalLaw {
    /// The same law for dimensionless displacements and pressures, with the displacement
    /// unit `displacement` (m) and the traction unit `traction` (Pa): `ĉ_ν = c_ν / k` with
    /// the stiffness unit `k = traction/displacement` (Pa/m); a custom law gets the units.
    pub fn nondimensional(&self, displacement: f64, traction: f64) -> NormalLaw {
        match self {
            NormalLaw::Compliance(c) => NormalLaw::Compliance(NormalCompliance {
                c_nu: c.c_nu / (traction / displacement),
            }),
            NormalLaw::Signorini => NormalLaw::Signorini,
            NormalLaw::Custom(law) => NormalLaw::Custom(law.nondimensional(displacement, traction)),
        }
    }

    /// Whether the law is user-defined (its responses come from
    /// [`crate::assembly::contact::ContactAssembler::normal_responses`]).
    #[inline]
    pub fn is_custom(&self) -> bool {
        matches!(self, NormalLaw::Custom(_))
    }

    /// Whether the law is the exact (Signorini) constraint.
    #[inline]
    pub fn is_exact(&self) -> bool {
        matches!(self, NormalLaw::Signorini)
    }

    /// The compliance law that the augmented Lagrangian term of a Signorini point with
    /// multiplier `lambda` (Pa) and penalty `r` (Pa/m) amounts to, with the gap it applies
    /// at: `(λ + r (u_ν − g))_+ = r (u_ν − (g − λ/r))_+`. For a compliance law, the law and
    /// `gap` themselves. A user-defined law has no such form (a stiffness of NaN): its
    /// responses are computed in batches.
    #[inline]
    pub fn effective(&self, gap: f64, lambda: f64, r: f64) -> (NormalCompliance, f64) {
        match self {
            NormalLaw::Compliance(c) => (*c, gap),
            NormalLaw::Signorini => (NormalCompliance { c_nu: r }, gap - lambda / r),
            NormalLaw::Custom(_) => (NormalCompliance { c_nu: f64::NAN }, gap),
        }
    }
}

impl NormalLaw {
    /// Checks the law's parameters.
    ///
    /// # Errors
    /// [`crate::Error::Invalid`] for a compliance stiffness `c_nu` that is not finite and
    /// positive. A user-defined law is sampled by [`crate::problem::Problem::validate`],
    /// which knows the body's size.
    pub fn validate(&self) -> crate::Result<()> {
        match self {
            NormalLaw::Compliance(c) => crate::error::require(
                c.c_nu.is_finite() && c.c_nu > 0.0,
                "c_nu",
                c.c_nu,
                "a normal compliance stiffness c_ν (Pa/m) > 0",
            ),
            NormalLaw::Signorini | NormalLaw::Custom(_) => Ok(()),
        }
    }
}
