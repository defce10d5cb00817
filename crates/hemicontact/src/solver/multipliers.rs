//! The multipliers of the exact constraints (see [`super::constraints`] for the method):
//! the contact pressure λ_i and the friction traction τ_i per contact point, and the locking
//! stress magnitude λ_T per cell. This module owns their update (one proximal step of the
//! dual problem per outer iteration), the size of an update as a primal residual, and the
//! KKT residuals of the certificate. The penalties the updates use, and their continuation,
//! are [`AugmentedLagrangian`]'s.

use super::certificate::ContactResult;
use super::constraints::AugmentedLagrangian;
use crate::assembly::contact::{ContactAssembler, ContactData};
use crate::assembly::element;
use crate::material::LockingSet;
use crate::parallel::Share;
use crate::problem::Problem;
use serde::Serialize;

/// The multipliers of the exact constraints at one outer iterate.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Multipliers {
    /// Signorini multiplier λ_i ≥ 0 per contact point: the contact pressure (Pa); zero at
    /// normal-compliance points.
    pub pressure: Vec<f64>,
    /// Exact-friction multiplier τ_i = −σ_τ per contact point (Pa, tangential coordinates):
    /// the friction traction; zero where friction is regularized.
    pub traction: Vec<[f64; 2]>,
    /// Ideal-locking multiplier λ_T ≥ 0 per cell (Pa); empty without ideal locking.
    pub locking: Vec<f64>,
}

impl Multipliers {
    /// All multipliers zero, for `n_points` contact points and `n_cells` locking
    /// multipliers (0 without ideal locking): the first convex problem is then the penalty
    /// problem with the penalties r.
    pub fn zero(n_points: usize, n_cells: usize) -> Self {
        Multipliers {
            pressure: vec![0.0; n_points],
            traction: vec![[0.0; 2]; n_points],
            locking: vec![0.0; n_cells],
        }
    }

    /// The updated multipliers at the solution `u` of the convex problem of these
    /// multipliers with the contact data `data` (whose multiplier slices are `self`'s):
    ///
    /// - `λ_i ← (λ_i + r_i(u_ν − g))_+` at Signorini points,
    /// - `τ_i ← proj_{B_F}(τ_i + r_i u_τ)` at exact-friction points, with the frozen bound F
    ///   of `data` (so that τ_i is the friction traction of the problem just solved),
    /// - `λ_T ← (λ_T + r_T Q(ε_T(u)))_+` per cell with ideal locking,
    ///
    /// with the penalties of `penalties` at their current stage.
    pub fn updated(
        &self,
        ca: &ContactAssembler<'_>,
        data: &ContactData<'_>,
        penalties: &AugmentedLagrangian,
        problem: &Problem,
        u: &[f64],
    ) -> Multipliers {
        let n = ca.nodes.len();
        let m = ca.dim - 1;
        let mut next = Multipliers::zero(n, 0);
        for i in 0..n {
            let cb = &ca.boundaries[ca.nodes.boundary[i] as usize];
            let s = ca.state(u, i, data);
            if cb.normal.is_exact() {
                next.pressure[i] = s.pressure;
            }
            let Some(fr) = &cb.friction else { continue };
            if let Some(tau) = fr.updated_traction(
                &s.u_tau,
                m,
                &self.traction[i],
                ca.penalty[i],
                ca.stiffness[i],
                data.bound[i],
            ) {
                next.traction[i] = tau;
            }
        }
        next.locking = if problem.has_ideal_locking() {
            update_locking(
                problem,
                penalties.locking_sets(),
                penalties.locking(),
                u,
                &self.locking,
            )
        } else {
            self.locking.clone()
        };
        next
    }

    /// The size of the update `self → next` as a primal residual, relative: the changes
    /// divided by their penalty, `|Δλ_i|/r_i` and `‖Δτ_i‖/r_i` relative to the point's own
    /// slip scale `δ_i = scale_i / (w_i k_i)` (`scale` its force scale, N, `stiffness` its
    /// k_i, `weight` its w_i; see [`super::local_scales`]), `|Δλ_T|/r_T` relative to the
    /// size of B (θ, κ², r). For an active constraint `Δλ/r` *is* the constraint violation,
    /// for a sticking point `Δτ/r` the slip: the standard primal stopping test of the
    /// augmented Lagrangian method. (Measured in force units instead, the change has a floor
    /// of r times the Newton tolerance, far above the tolerance for the large penalties
    /// used.) Over the points and cells `share` counts: the caller completes the maximum.
    pub fn change(
        &self,
        next: &Multipliers,
        penalties: &AugmentedLagrangian,
        stiffness: &[f64],
        weight: &[f64],
        problem: &Problem,
        scale: &[f64],
        share: &Share,
    ) -> f64 {
        let mut fp = 0.0f64;
        // The points `share` counts: the first ones (`scale` has those only).
        for i in (0..self.pressure.len()).take_while(|&i| share.counts_point(i)) {
            let slip_scale = scale[i] / (weight[i] * stiffness[i]);
            let r = penalties.contact()[i] * slip_scale;
            let dt = ((next.traction[i][0] - self.traction[i][0]).powi(2)
                + (next.traction[i][1] - self.traction[i][1]).powi(2))
            .sqrt();
            fp = fp
                .max((next.pressure[i] - self.pressure[i]).abs() / r)
                .max(dt / r);
        }
        if problem.has_ideal_locking() {
            let sets = penalties.locking_sets();
            let counted = next.locking.iter().zip(&self.locking).enumerate();
            for (c, (a, b)) in counted.filter(|&(c, _)| share.counts_cell(c)) {
                let k = problem.cell_material(c);
                if let Some(set) = sets[k] {
                    fp = fp.max((a - b).abs() / (penalties.locking()[k] * set.size()));
                }
            }
        }
        fp
    }

    /// The KKT residuals of Signorini contact and ideal locking for these multipliers (the
    /// updated ones, consistent with the forces of the last convex problem) at `u`, written
    /// into `kkt`: violation, sign of the multipliers and complementarity, each at a contact
    /// point relative to that point's own scales (`slip_scale` δ_i and `force_scale` f_i of
    /// its certificate results `points`, see [`super::certificate`]): the penetration
    /// `(u_ν − g)_+ / δ_i` and `λ_i |g − u_ν| w_i / (f_i δ_i)`. The stick/slip residual of
    /// exact friction is the certificate's, which classifies the points. Over the points
    /// and cells `share` counts, then over the processes.
    pub fn kkt(
        &self,
        ca: &ContactAssembler<'_>,
        problem: &Problem,
        u: &[f64],
        points: &[ContactResult],
        share: &Share,
        kkt: &mut KktCertificate,
    ) {
        let exact = |i: usize| {
            ca.boundaries[ca.nodes.boundary[i] as usize]
                .normal
                .is_exact()
        };
        let (mut max_pressure, mut min_pressure) = (0.0f64, f64::INFINITY);
        let mut n_points = 0;
        for i in (0..ca.nodes.owned()).filter(|&i| exact(i)) {
            let gap = ca.nodes.gap[i];
            let (u_nu, _) = ca.nodes.kinematics(ca.dim, u, i);
            let p = self.pressure[i];
            let (f, delta) = (points[i].force_scale, points[i].slip_scale);
            n_points += 1;
            max_pressure = max_pressure.max(p);
            min_pressure = min_pressure.min(p);
            kkt.contact_violation = kkt.contact_violation.max((u_nu - gap).max(0.0) / delta);
            kkt.contact_complementarity = kkt
                .contact_complementarity
                .max(p * (gap - u_nu).abs() * ca.nodes.weight[i] / (f * delta));
        }
        let mut worst = [
            max_pressure,
            -min_pressure,
            kkt.contact_violation,
            kkt.contact_complementarity,
        ];
        share.max(&mut worst);
        [max_pressure, min_pressure] = [worst[0], -worst[1]];
        [kkt.contact_violation, kkt.contact_complementarity] = [worst[2], worst[3]];
        kkt.n_constraints.1 += share.count(n_points);
        if max_pressure > 0.0 {
            kkt.contact_min_multiplier = min_pressure / max_pressure;
        }
        if problem.has_ideal_locking() {
            locking_kkt(problem, u, &self.locking, share, kkt);
        }
    }
}

/// The updated cell multipliers `λ_T ← (λ_T + r_k Q_k(ε_T(u)))_+` of every cell of
/// `problem`'s mesh whose material k locks ideally, with the set `sets[k]` and penalty
/// `r[k]` of its material (0 in the cells of the other materials). On several processes,
/// of this process's part: a ghost cell's update is computed alike by each process that
/// holds it.
pub fn update_locking(
    problem: &Problem,
    sets: &[Option<LockingSet>],
    r: &[f64],
    u: &[f64],
    current: &[f64],
) -> Vec<f64> {
    let mesh = &problem.mesh;
    (0..mesh.n_cells())
        .map(|c| {
            let k = problem.cell_material(c);
            sets[k].map_or(0.0, |set| {
                let (_, eps) = element::cell_strain(mesh, u, c);
                (current[c] + r[k] * set.q(&eps)).max(0.0)
            })
        })
        .collect()
}

/// KKT residuals of the exact constraints at a solution (all dimensionless).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct KktCertificate {
    /// Ideal locking: `max_T Q(ε_T)_+ / q` with q = θ, κ² or r (the size of B).
    pub locking_violation: f64,
    /// Smallest locking multiplier divided by the largest (≥ 0: signs correct).
    pub locking_min_multiplier: f64,
    /// `max_T λ_T |Q(ε_T)| / (max λ · q)`.
    pub locking_complementarity: f64,
    /// Cells where the locking constraint is active (λ_T > 0).
    pub n_locked: usize,
    /// Signorini: `max_i (u_ν − g)_+ / δ_i`, δ_i the point's slip scale.
    pub contact_violation: f64,
    /// Smallest Signorini multiplier (pressure) divided by the largest.
    pub contact_min_multiplier: f64,
    /// `max_i λ_i |g − u_ν,i| w_i / (f_i δ_i)`, f_i and δ_i the point's force and slip
    /// scales.
    pub contact_complementarity: f64,
    /// Exact friction: largest slip of a sticking point relative to its slip scale δ_i
    /// (zero to round-off when stick is exact).
    pub stick_slip: f64,
    /// Number of constraints of each kind checked: (cells, Signorini points, exact-friction
    /// points).
    pub n_constraints: (usize, usize, usize),
}

impl KktCertificate {
    /// The largest violation or complementarity residual (the number the certificate
    /// compares with its tolerance, `certificate_tolerance`).
    pub fn worst(&self) -> f64 {
        [
            self.locking_violation,
            self.locking_complementarity,
            self.contact_violation,
            self.contact_complementarity,
            self.stick_slip,
        ]
        .into_iter()
        .fold(0.0, f64::max)
    }
}

/// The locking part of the KKT certificate for the multipliers `lambda` (the updated
/// ones) at `u`, over the cells `share` counts and then over the processes: in every cell
/// of a material that locks ideally, the violation `Q_+/size(B)` and the complementarity
/// `λ_T |Q| / (λ_max size(B))`, each relative to its material's set and largest multiplier
/// (multipliers of different sets have different units).
fn locking_kkt(
    problem: &Problem,
    u: &[f64],
    lambda: &[f64],
    share: &Share,
    kkt: &mut KktCertificate,
) {
    let mesh = &problem.mesh;
    let sets = problem.ideal_sets();
    let nm = sets.len();
    let counted = || {
        lambda
            .iter()
            .enumerate()
            .filter(|&(c, _)| share.counts_cell(c))
            .filter_map(|(c, &l)| {
                let k = problem.cell_material(c);
                sets[k].map(|set| (c, k, set, l))
            })
    };
    // Per material: the largest |λ_T| and minus the smallest λ_T.
    let mut extremes = vec![0.0f64; 2 * nm];
    extremes[nm..].fill(f64::NEG_INFINITY);
    for (_, k, _, l) in counted() {
        extremes[k] = extremes[k].max(l.abs());
        extremes[nm + k] = extremes[nm + k].max(-l);
    }
    share.max(&mut extremes);
    let lmax = &extremes[..nm];
    kkt.locking_min_multiplier = (0..nm)
        .filter(|&k| lmax[k] > 0.0)
        .map(|k| -extremes[nm + k] / lmax[k])
        .reduce(f64::min)
        .unwrap_or(0.0);
    kkt.n_locked = share.count(counted().filter(|&(.., l)| l > 0.0).count());
    kkt.n_constraints.0 = share.count(counted().count());
    for (c, k, set, l) in counted() {
        let q_ref = set.size();
        let (_, eps) = element::cell_strain(mesh, u, c);
        let q = set.q(&eps);
        kkt.locking_violation = kkt.locking_violation.max(q.max(0.0) / q_ref);
        if lmax[k] > 0.0 {
            kkt.locking_complementarity = kkt
                .locking_complementarity
                .max(l * q.abs() / (lmax[k] * q_ref));
        }
    }
    let mut worst = [kkt.locking_violation, kkt.locking_complementarity];
    share.max(&mut worst);
    [kkt.locking_violation, kkt.locking_complementarity] = worst;
}
