//! Pointwise constitutive laws: a constant strain in, energy density, stress and tangent out.
//!
//! The stored energy density of the body is `W(ε) + Ψ(ε)` (`A = ∂W`, Ψ the
//! nearly-locking penalty); the laws here know nothing of meshes or DOFs, so each is
//! testable on its own (finite-difference checks of stress against energy and of tangent
//! against stress live in `tests/`).
//!
//! ## Out-of-plane stress in plane strain
//!
//! In 2D every law here is an isotropic function of the two invariants of a symmetric 2×2
//! strain, `W(ε) = f(tr ε, ε:ε)`. Plane strain embeds ε in 3D with `ε_zz = ε_xz = ε_yz = 0`
//! and reads the law as the same function of the 3D invariants `tr ε`, `ε:ε` (the only
//! isotropic extension that does not involve det ε). The out-of-plane stress is then
//!
//! `σ_zz = ∂W/∂ε_zz = ∂f/∂(tr ε) + 2 ε_zz ∂f/∂(ε:ε) = ∂f/∂(tr ε)`,
//!
//! the coefficient `a` when the in-plane stress is written `σ = a I + b ε`
//! ([`StrainEnergy::plane_strain_stress_zz`]). For Hooke's law this extension is 3D Hooke with
//! the same λ, G (`σ_zz = λ tr ε`); for limited compressibility and the ball it is the 3D set
//! (`σ_zz = C_κ Q_+ sgn(tr ε)`, resp. 0). The 2D Hencky law and Prager's set are written with
//! the 2D deviator `ε − (tr ε/2) I`; they are *not* the plane-strain restrictions of their
//! 3D versions with the same constants, and their σ_zz is that of the extension above:
//! Hencky `(K − Φ'(s)) tr ε`, Prager `−C_κ Q_+ tr ε / 2`. Under plane stress `σ_zz = 0`.

mod energy;
pub mod hencky;
pub mod hooke;
pub mod locking;

pub use energy::StrainEnergy;
pub use hencky::Hencky;
pub use hooke::{Hooke, Plane};
pub use locking::{AugmentedLocking, LockingPenalty, LockingSet};

use crate::tensor::{Sym, Tangent};

/// The elasticity operator A = ∂W.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Elasticity {
    /// Isotropic Hooke's law.
    Hooke(Hooke),
    /// Strain-stiffening Hencky law.
    Hencky(Hencky),
}

impl Elasticity {
    /// Strong monotonicity constant `m_A` (Pa) in dimension `dim`.
    pub fn monotonicity(&self, dim: usize) -> f64 {
        match self {
            Elasticity::Hooke(h) => h.monotonicity(dim),
            Elasticity::Hencky(h) => h.monotonicity(dim),
        }
    }

    /// The Hooke operator used for the energy norm of the paper's example: Hooke's law itself, or the
    /// small-strain Hooke law of the Hencky model (`λ = K − 2G/d`, `G`).
    pub fn small_strain_hooke(&self, dim: usize) -> Hooke {
        match *self {
            Elasticity::Hooke(h) => h,
            Elasticity::Hencky(h) => Hooke {
                lambda: h.bulk - 2.0 * h.shear / dim as f64,
                mu: h.shear,
            },
        }
    }
}

impl Elasticity {
    /// Checks the constants in dimension `dim`: finite, a positive shear modulus and
    /// strong monotonicity (`m_A > 0`); for Hencky's law also `G_∞ ≥ G` finite, `K > 0`,
    /// and a transition `s₀` that is a positive normal number.
    ///
    /// # Errors
    /// [`crate::Error::Invalid`] naming the constant (`lambda`, `mu`, `bulk`, `shear`,
    /// `shear_inf`, `s0`).
    pub fn validate(&self, dim: usize) -> crate::Result<()> {
        use crate::error::require;
        match *self {
            Elasticity::Hooke(h) => {
                require(
                    h.lambda.is_finite(),
                    "lambda",
                    h.lambda,
                    "a finite Lamé constant λ (Pa)",
                )?;
                require(
                    h.mu.is_finite() && h.mu > 0.0,
                    "mu",
                    h.mu,
                    "a finite positive shear modulus G (Pa)",
                )?;
                let m = h.monotonicity(dim);
                require(
                    m > 0.0,
                    "lambda",
                    format!("{} (with G = {}: m_A = {m:e})", h.lambda, h.mu),
                    "a strongly monotone law: dλ + 2G > 0",
                )
            }
            Elasticity::Hencky(h) => {
                let usable = |v: f64| v.is_finite() && v > 0.0;
                require(
                    usable(h.shear),
                    "shear",
                    h.shear,
                    "a finite positive shear modulus G (Pa)",
                )?;
                require(
                    usable(h.bulk),
                    "bulk",
                    h.bulk,
                    "a finite positive bulk modulus K (Pa)",
                )?;
                require(
                    h.shear_inf.is_finite() && h.shear_inf >= h.shear,
                    "shear_inf",
                    h.shear_inf,
                    "a finite large-strain shear modulus G_∞ ≥ G (strain stiffening keeps Φ convex)",
                )?;
                require(
                    h.s0.is_normal() && h.s0 > 0.0,
                    "s0",
                    h.s0,
                    "a squared strain s₀ that is a positive normal number",
                )
            }
        }
    }

    /// The same law for the dimensionless strain `ε̂ = ε/e` and energy density `Ŵ = W/(S e²)`
    /// (S the stress scale, Pa): the moduli divided by S; the Hencky transition strain
    /// `s₀` (a squared strain) divided by e².
    pub fn nondimensional(&self, stress: f64, e: f64) -> Elasticity {
        match *self {
            Elasticity::Hooke(h) => Elasticity::Hooke(Hooke {
                lambda: h.lambda / stress,
                mu: h.mu / stress,
            }),
            Elasticity::Hencky(h) => Elasticity::Hencky(Hencky {
                bulk: h.bulk / stress,
                shear: h.shear / stress,
                shear_inf: h.shear_inf / stress,
                s0: h.s0 / (e * e),
            }),
        }
    }
}

impl StrainEnergy for Elasticity {
    #[inline]
    fn energy(&self, eps: &Sym) -> f64 {
        match self {
            Elasticity::Hooke(h) => h.energy(eps),
            Elasticity::Hencky(h) => h.energy(eps),
        }
    }
    #[inline]
    fn stress(&self, eps: &Sym) -> Sym {
        match self {
            Elasticity::Hooke(h) => h.stress(eps),
            Elasticity::Hencky(h) => h.stress(eps),
        }
    }
    #[inline]
    fn tangent(&self, eps: &Sym) -> Tangent {
        match self {
            Elasticity::Hooke(h) => h.tangent(eps),
            Elasticity::Hencky(h) => h.tangent(eps),
        }
    }
    #[inline]
    fn plane_strain_stress_zz(&self, eps: &Sym) -> f64 {
        match self {
            Elasticity::Hooke(h) => h.plane_strain_stress_zz(eps),
            Elasticity::Hencky(h) => h.plane_strain_stress_zz(eps),
        }
    }
}

/// How the body locks: not at all, nearly (the penalty Ψ) or ideally (the exact constraint).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Locking {
    /// No locking.
    None,
    /// Nearly locking: the penalty `Ψ(ε) = (C_κ/2) Q(ε)_+²` added to the stored energy.
    Penalty(LockingPenalty),
    /// Ideal locking: the exact constraint `ε_T ∈ B` in every cell, imposed by an augmented
    /// Lagrangian ([`AugmentedLocking`]) with a stress multiplier per cell.
    Ideal(LockingSet),
}

impl Locking {
    /// The nearly-locking penalty, if any.
    #[inline]
    pub fn penalty(&self) -> Option<&LockingPenalty> {
        match self {
            Locking::Penalty(p) => Some(p),
            _ => None,
        }
    }

    /// The set of ideal locking, if any.
    #[inline]
    pub fn ideal(&self) -> Option<LockingSet> {
        match *self {
            Locking::Ideal(set) => Some(set),
            _ => None,
        }
    }

    /// The locking set B (penalty or ideal), if any.
    #[inline]
    pub fn set(&self) -> Option<LockingSet> {
        match *self {
            Locking::None => None,
            Locking::Penalty(p) => Some(p.set),
            Locking::Ideal(set) => Some(set),
        }
    }

    /// Whether the penalty is active at `eps` (`C_κ > 0` and `Q(ε) > 0`); false without a
    /// penalty.
    #[inline]
    pub fn is_penalty_active(&self, eps: &Sym) -> bool {
        self.penalty().is_some_and(|p| p.is_active(eps))
    }
}

/// The bulk material of the body: elasticity plus locking.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Elasticity operator A = ∂W.
    pub elasticity: Elasticity,
    /// Locking: none, nearly (a penalty in the stored energy) or ideal (a constraint).
    pub locking: Locking,
}

impl Material {
    /// Checks the elasticity constants (under `elasticity.`) and the locking set and
    /// compliance (under `locking.`).
    ///
    /// # Errors
    /// [`crate::Error::Invalid`] naming the parameter.
    pub fn validate(&self, dim: usize) -> crate::Result<()> {
        self.elasticity
            .validate(dim)
            .map_err(|e| e.within("elasticity"))?;
        match &self.locking {
            Locking::None => Ok(()),
            Locking::Penalty(p) => p.validate(),
            Locking::Ideal(set) => set.validate(),
        }
        .map_err(|e| e.within("locking"))
    }

    /// A material with elasticity `elasticity` and no locking.
    pub fn elastic(elasticity: Elasticity) -> Self {
        Material {
            elasticity,
            locking: Locking::None,
        }
    }
}

impl Material {
    /// The same material for the dimensionless strain `ε̂ = ε/e` and energy density
    /// `Ŵ = W/(S e²)` (S the stress scale, Pa), with the unit of its ideal-locking
    /// multiplier `S e²/q` (Pa; q the unit of the locking function,
    /// [`LockingSet::nondimensional`]; `S e` without ideal locking). The penalty
    /// `Ψ = (C_κ/2) Q_+²` keeps its form with `Ĉ_κ = C_κ q²/(S e²)`.
    pub fn nondimensional(&self, stress: f64, e: f64) -> (Material, f64) {
        let (locking, multiplier_unit) = match self.locking {
            Locking::None => (Locking::None, stress * e),
            Locking::Penalty(p) => {
                let (set, q) = p.set.nondimensional(e);
                let penalty = LockingPenalty {
                    set,
                    c_kappa: p.c_kappa * (q / e) * (q / e) / stress,
                };
                (Locking::Penalty(penalty), stress * e)
            }
            Locking::Ideal(b) => {
                let (set, q) = b.nondimensional(e);
                (Locking::Ideal(set), stress * (e / q) * e)
            }
        };
        let material = Material {
            elasticity: self.elasticity.nondimensional(stress, e),
            locking,
        };
        (material, multiplier_unit)
    }
}

impl StrainEnergy for Material {
    #[inline]
    fn energy(&self, eps: &Sym) -> f64 {
        match &self.locking {
            Locking::Penalty(p) => self.elasticity.energy(eps) + p.energy(eps),
            _ => self.elasticity.energy(eps),
        }
    }
    #[inline]
    fn stress(&self, eps: &Sym) -> Sym {
        let s = self.elasticity.stress(eps);
        match &self.locking {
            Locking::Penalty(p) if p.c_kappa != 0.0 => s.add_scaled(1.0, &p.stress(eps)),
            _ => s,
        }
    }
    #[inline]
    fn tangent(&self, eps: &Sym) -> Tangent {
        let mut t = self.elasticity.tangent(eps);
        if let Locking::Penalty(penalty) = &self.locking {
            if penalty.is_active(eps) {
                let p = penalty.tangent(eps);
                for (row, prow) in t.iter_mut().zip(p.iter()) {
                    for (a, b) in row.iter_mut().zip(prow.iter()) {
                        *a += b;
                    }
                }
            }
        }
        t
    }
    #[inline]
    fn plane_strain_stress_zz(&self, eps: &Sym) -> f64 {
        let s = self.elasticity.plane_strain_stress_zz(eps);
        match &self.locking {
            Locking::Penalty(p) if p.c_kappa != 0.0 => s + p.plane_strain_stress_zz(eps),
            _ => s,
        }
    }
}

impl Material {
    /// The full 3×3 stress (Pa) of a cell with strain `eps`, including the ideal-locking
    /// stress `multiplier · ∂Q(ε)` (`multiplier` the cell's λ_T ≥ 0 in Pa; 0 without ideal
    /// locking). In 3D it is `σ(ε) + λ_T ∂Q`; in 2D the in-plane part is the same and the
    /// out-of-plane normal stress is `σ_zz = ∂W/∂ε_zz + λ_T ∂Q/∂ε_zz` under plane strain
    /// (see the module documentation; `λ tr ε` plus the locking part for Hooke's law) and
    /// 0 under plane stress. The out-of-plane shear stresses are 0.
    pub fn stress_3x3(&self, eps: &Sym, plane: Plane, multiplier: f64) -> [[f64; 3]; 3] {
        let mut s = self.stress(eps);
        let ideal = self.locking.ideal().filter(|_| multiplier > 0.0);
        if let Some(set) = ideal {
            s = s.add_scaled(multiplier, &set.dq(eps));
        }
        let zz = if eps.dim == 2 && plane == Plane::Strain {
            let mut zz = self.plane_strain_stress_zz(eps);
            if let Some(set) = ideal {
                zz += multiplier * set.dq_zz(eps);
            }
            zz
        } else {
            0.0
        };
        s.to_matrix_with_zz(zz)
    }
}
