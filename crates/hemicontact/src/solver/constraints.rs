//! Exact constraints by the augmented Lagrangian method: ideal locking `ε_T(u) ∈ B`,
//! Signorini contact `u_ν ≤ g`, and exact stick/slip for `j = ‖·‖` (the paper's Problem 5,
//! which the paper itself only computed in regularized form).
//!
//! # Method, and why
//! Each constraint gets a multiplier — the locking stress magnitude λ_T per cell, the
//! contact pressure λ_i and the friction traction τ_i per contact point — and its term of the
//! energy is replaced by the augmented Lagrangian with penalty r:
//!
//! | constraint | term | multiplier update |
//! |------------|------|-------------------|
//! | `Q(ε_T) ≤ 0` | `|T| (1/2r)[(λ_T + rQ)_+² − λ_T²]` | `λ_T ← (λ_T + rQ(ε_T))_+` |
//! | `u_ν ≤ g` | `w_i (1/2r)[(λ_i + r(u_ν − g))_+² − λ_i²]` | `λ_i ← (λ_i + r(u_ν − g))_+` |
//! | `F‖u_τ‖` | `w_i (1/r)[H_F(τ_i + r u_τ) − ‖τ_i‖²/2]` | `τ_i ← proj_{B_F}(τ_i + r u_τ)` |
//!
//! (H_F the Huber function, see [`crate::contact::friction`].) For fixed multipliers every
//! term is convex and C¹ with a piecewise smooth gradient — exactly the structure the
//! existing semismooth Newton solver with line search minimizes, on the same sparsity
//! pattern and symbolic factorization; with zero multipliers it *is* the nearly-locking
//! penalty and normal compliance with stiffness r. The multiplier updates are proximal-point
//! steps on the dual problem, which converge for every r > 0 (Rockafellar 1976), at a linear
//! rate that improves as r grows; they join the frozen vector of the convexification loop
//! ([`super::outer`]), so one Newton solve per outer iteration serves both the
//! convexification and the multipliers, and Anderson acceleration speeds up both.
//!
//! A primal–dual active-set method would converge in fewer iterations when it converges, but
//! it can cycle between active sets (the classic failure for friction), and needs an
//! indefinite saddle-point solve. Here every inner problem is the minimization of a convex
//! energy, globalized by the line search: the active sets inside a solve are found by a
//! descent method and cannot cycle, and the outer iteration is a contraction.
//!
//! # The penalty
//! r balances the constraint stiffness against the elastic one, `r = γ · S` with
//! `S = λ + 2G` (the P-wave modulus, Pa) and the dimensionless factor γ
//! ([`ConstraintSettings::locking_penalty`], default 10³;
//! [`ConstraintSettings::contact_penalty`], default 10²): per cell `r_T = γ S / |∂Q|²` at the
//! boundary of B (1 for limited compressibility per unit trace, `2κ²` for Prager, 1 for the
//! ball), per contact point `r_i = γ S / h_i` with `h_i = w_i^{1/(d−1)}` the local mesh size,
//! so that the penalty adds γ times the stiffness of the node or cell. Each outer iteration
//! then reduces the constraint violation about γ-fold: large enough for a few iterations,
//! small enough (10³ on top of the elastic condition number) not to hurt the direct solver.
//! The penalty is reached by continuation: the first outer iteration uses `γ₀ = 1`, each
//! next one ten times more, up to γ (the multipliers carry over, as the method of multipliers allows
//! any nondecreasing penalty sequence). Starting at the full penalty from the unloaded state
//! costs tens of damped Newton steps: the Hessian at a point cannot see the cells and nodes
//! that a step would push deep into the stiff penalty.
//!
//! # Certificate
//! At convergence the KKT conditions are checked ([`super::multipliers::KktCertificate`]): violation
//! `max Q(ε_T)_+` relative to the size of B, `max (u_ν − g)_+` relative to the largest
//! displacement, signs of the multipliers, complementarity, and (in
//! [`super::certificate`]) equilibrium and the friction law with the multipliers as forces.

use crate::contact::ContactNodes;
use crate::material::LockingSet;
use crate::problem::Problem;
use serde::{Deserialize, Serialize};

/// Settings of the exact-constraint (augmented Lagrangian) method.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ConstraintSettings {
    /// Dimensionless penalty factor γ > 0 of ideal locking: the augmented Lagrangian penalty
    /// of a cell is γ times its elastic stiffness (see the module documentation). Default
    /// 10³ (measured best on the paper example with ideal locking, 30 to 10⁵ tried).
    pub locking_penalty: f64,
    /// Dimensionless penalty factor γ > 0 of Signorini contact and exact friction, per
    /// contact node. Default 10² (measured best on the paper example with Signorini
    /// contact: 0.81 s against 0.97 s with 3·10² and 1.11 s with 10³ at n = 128).
    pub contact_penalty: f64,
    /// Penalty factor γ₀ > 0 of the first outer iteration; the factor grows tenfold per
    /// outer iteration up to γ (continuation). Default 1: the first problem is then as soft
    /// as the paper's nearly-locking one, which Newton solves in a few steps from the
    /// unloaded state, whereas with the full penalty at once it needs tens of damped steps.
    pub initial_penalty: f64,
}

impl Default for ConstraintSettings {
    fn default() -> Self {
        ConstraintSettings {
            locking_penalty: 1e3,
            contact_penalty: 1e2,
            initial_penalty: 1.0,
        }
    }
}

impl ConstraintSettings {
    /// Checks every penalty factor against its range.
    ///
    /// # Errors
    /// [`crate::Error::Invalid`] naming the factor: `locking_penalty` and
    /// `contact_penalty` from 1e-3 to 1e6, `initial_penalty` from 1e-6 to 1e6.
    pub fn validate(&self) -> crate::Result<()> {
        for (field, v, lo, hi) in [
            ("locking_penalty", self.locking_penalty, 1e-3, 1e6),
            ("contact_penalty", self.contact_penalty, 1e-3, 1e6),
            ("initial_penalty", self.initial_penalty, 1e-6, 1e6),
        ] {
            crate::error::require(
                v >= lo && v <= hi,
                field,
                v,
                &format!("a dimensionless penalty factor from {lo:e} to {hi:e}"),
            )?;
        }
        Ok(())
    }

    /// The penalty factor of outer iteration `k` for a constraint of full factor `gamma`:
    /// `min(γ, γ₀ 10^k)`.
    pub fn factor(&self, k: usize, gamma: f64) -> f64 {
        if self.initial_penalty <= 0.0 || self.initial_penalty >= gamma {
            gamma
        } else {
            gamma.min(self.initial_penalty * 10f64.powi(k.min(60) as i32))
        }
    }

    /// Number of continuation stages for a constraint of full factor `gamma`: the first
    /// outer iteration at which [`ConstraintSettings::factor`] reaches γ.
    pub fn stages(&self, gamma: f64) -> usize {
        (0..61)
            .find(|&k| self.factor(k, gamma) >= gamma)
            .unwrap_or(60)
    }
}

/// The penalties of the exact constraints: r_i of the contact points and r_T of ideal
/// locking, and their continuation over the first outer iterations. The multipliers, their
/// update and their KKT residuals are in [`super::multipliers`].
#[derive(Clone, Debug)]
pub struct AugmentedLagrangian {
    settings: ConstraintSettings,
    /// Full penalty r_i per contact point (Pa/m).
    full_contact: Vec<f64>,
    /// The set of ideal locking of each material (`None` without).
    locking_sets: Vec<Option<LockingSet>>,
    /// Full penalty r_T of ideal locking of each material (0 without).
    full_locking: Vec<f64>,
    /// Penalty r_i per contact point at the current stage (Pa/m).
    contact: Vec<f64>,
    /// Penalty r_T of each material at the current stage (Pa per unit of Q²).
    locking: Vec<f64>,
}

impl AugmentedLagrangian {
    /// The penalties of `problem` for the settings `settings` and the contact points of
    /// weights `weight` (see [`contact_penalties`], [`locking_penalty`]), at their full
    /// values until [`AugmentedLagrangian::set_stage`] is called.
    pub fn new(problem: &Problem, settings: &ConstraintSettings, points: &ContactNodes) -> Self {
        let contact = contact_penalties(problem, settings.contact_penalty, points);
        let locking_sets = problem.ideal_sets();
        let locking: Vec<f64> = locking_sets
            .iter()
            .zip(problem.moduli())
            .map(|(set, s)| {
                set.map_or(0.0, |set| {
                    locking_penalty(s, settings.locking_penalty, &set)
                })
            })
            .collect();
        AugmentedLagrangian {
            settings: settings.clone(),
            full_contact: contact.clone(),
            locking_sets,
            full_locking: locking.clone(),
            contact,
            locking,
        }
    }

    /// These penalties for the contact points `points` of the ones they were built for (a
    /// process's own points, in that order).
    pub(crate) fn restricted(&self, points: &[u32]) -> Self {
        let pick = |all: &[f64]| points.iter().map(|&i| all[i as usize]).collect();
        AugmentedLagrangian {
            settings: self.settings.clone(),
            full_contact: pick(&self.full_contact),
            locking_sets: self.locking_sets.clone(),
            full_locking: self.full_locking.clone(),
            contact: pick(&self.contact),
            locking: self.locking.clone(),
        }
    }

    /// Sets the penalties of outer iteration `k`: the full ones scaled by
    /// `factor(k, γ)/γ` ([`ConstraintSettings::factor`], continuation).
    pub fn set_stage(&mut self, k: usize) {
        let s = &self.settings;
        let contact = s.factor(k, s.contact_penalty) / s.contact_penalty;
        let locking = s.factor(k, s.locking_penalty) / s.locking_penalty;
        for (r, full) in self.contact.iter_mut().zip(&self.full_contact) {
            *r = contact * full;
        }
        for (r, full) in self.locking.iter_mut().zip(&self.full_locking) {
            *r = locking * full;
        }
    }

    /// The penalty r_i of every contact point at the current stage (Pa/m).
    pub fn contact(&self) -> &[f64] {
        &self.contact
    }

    /// The penalty r_T of ideal locking of each material at the current stage (0 for a
    /// material without).
    pub fn locking(&self) -> &[f64] {
        &self.locking
    }

    /// The set of ideal locking of each material (`None` for a material without).
    pub fn locking_sets(&self) -> &[Option<LockingSet>] {
        &self.locking_sets
    }

    /// The number of continuation stages of `problem` (see [`stages`]).
    pub fn stages(&self, problem: &Problem) -> usize {
        stages(problem, &self.settings)
    }
}

/// Whether the problem has exact constraints (ideal locking, Signorini contact, exact
/// stick/slip), whose KKT conditions the certificate checks.
pub fn has_exact_constraints(problem: &Problem) -> bool {
    problem.has_ideal_locking()
        || problem
            .contact
            .iter()
            .any(|c| c.normal.is_exact() || c.friction.as_ref().is_some_and(|f| f.is_exact()))
}

/// Whether the problem has multipliers to iterate on: exact constraints, or a friction
/// norm imposed through its multiplier with an elastic slip
/// ([`crate::contact::Friction::has_multiplier`]).
pub fn has_multipliers(problem: &Problem) -> bool {
    has_exact_constraints(problem)
        || problem
            .contact
            .iter()
            .any(|c| c.friction.as_ref().is_some_and(|f| f.has_multiplier()))
}

/// The stiffness `S_i` (Pa) of every contact point of `points`: the largest P-wave modulus
/// `λ + 2G` (at least G) of the small-strain Hooke laws of the cells around its node, the
/// material its surface deforms; [`Problem::stiffness`] for a body of one material. At a
/// point of a contact pair the relative displacement deforms both bodies, in series, and
/// the softer one governs: the smaller of its node's stiffness and the largest of its
/// master facet's nodes' (a stiff punch on a soft block has the block's stiffness, so that
/// the pair's penalty and slip scale are those of the body that gives way, not 10¹² times
/// theirs).
pub fn point_stiffness(problem: &Problem, points: &ContactNodes) -> Vec<f64> {
    if problem.materials.len() == 1 {
        return vec![problem.stiffness(); points.len()];
    }
    let at_node = node_stiffness(problem);
    let d = problem.mesh.dim();
    (0..points.len())
        .map(|i| {
            let (n, nodes, _) = points.stencil(d, i);
            let slave = at_node[nodes[0] as usize];
            if n == 1 {
                return slave;
            }
            let master = nodes[1..n]
                .iter()
                .map(|&m| at_node[m as usize])
                .fold(0.0f64, f64::max);
            slave.min(master)
        })
        .collect()
}

/// The stiffness of every node of the mesh (Pa): the largest P-wave modulus `λ + 2G` (at
/// least G) of the small-strain Hooke laws of the cells around it (0 at a node in no cell).
pub fn node_stiffness(problem: &Problem) -> Vec<f64> {
    let mesh = &problem.mesh;
    let modulus = problem.moduli();
    let mut at_node = vec![0.0f64; mesh.n_nodes()];
    for c in 0..mesh.n_cells() {
        let s = modulus[problem.cell_material(c)];
        for &v in mesh.cell(c) {
            at_node[v as usize] = at_node[v as usize].max(s);
        }
    }
    at_node
}

/// Penalty `r_T = γ S / |∂Q|²` of the ideal-locking set `set` of a material of P-wave
/// modulus `stiffness` (S, Pa; [`Problem::moduli`]) for the penalty factor `gamma`
/// ([`ConstraintSettings::locking_penalty`]; Pa per unit of Q², see
/// [`LockingSet::gradient_norm_sq_at_boundary`]).
pub fn locking_penalty(stiffness: f64, gamma: f64, set: &LockingSet) -> f64 {
    gamma * stiffness / set.gradient_norm_sq_at_boundary()
}

/// The elastic stiffness per unit area `k_i = S_i / h_i` (Pa/m) of every contact point of
/// `points`, with `S_i` the P-wave modulus of the material around it ([`point_stiffness`])
/// and `h_i = w_i^{1/(d−1)}` the local mesh size (`w_i` its weight): the contact traction that deforms the body around the point by a unit
/// displacement. `F_i / k_i` is the slip scale of a point of friction bound `F_i`: the
/// numerical regularization of its friction law and the thresholds of its certificate are
/// relative to it (see [`crate::contact::friction`], [`super::certificate`]).
pub fn contact_stiffness(problem: &Problem, points: &ContactNodes) -> Vec<f64> {
    let s = point_stiffness(problem, points);
    let d = problem.mesh.dim();
    points
        .weight
        .iter()
        .zip(&s)
        .map(|(&w, &s)| s / local_size(d, w))
        .collect()
}

/// The local mesh size `h = w^{1/(d−1)}` (m) of a contact point of weight `w` in dimension
/// `d`, at least the smallest positive number.
fn local_size(d: usize, w: f64) -> f64 {
    let h = if d == 2 { w } else { w.sqrt() };
    h.max(f64::MIN_POSITIVE)
}

/// Penalty `r_i = γ S_i / h_i` (Pa/m) of every contact point of `points` for the penalty
/// factor `gamma` ([`ConstraintSettings::contact_penalty`]; `S_i`, `h_i` as in
/// [`contact_stiffness`]).
pub fn contact_penalties(problem: &Problem, gamma: f64, points: &ContactNodes) -> Vec<f64> {
    let s = point_stiffness(problem, points);
    let d = problem.mesh.dim();
    points
        .weight
        .iter()
        .zip(&s)
        .map(|(&w, &s)| gamma * s / local_size(d, w))
        .collect()
}

/// The continuation of `problem` with the penalty settings `c`: the number of stages before
/// every exact constraint has its full penalty (0 without exact constraints).
pub fn stages(problem: &Problem, c: &ConstraintSettings) -> usize {
    let locking = if problem.has_ideal_locking() {
        c.stages(c.locking_penalty)
    } else {
        0
    };
    let contact = if problem
        .contact
        .iter()
        .any(|b| b.normal.is_exact() || b.friction.as_ref().is_some_and(|f| f.has_multiplier()))
    {
        c.stages(c.contact_penalty)
    } else {
        0
    };
    locking.max(contact)
}
