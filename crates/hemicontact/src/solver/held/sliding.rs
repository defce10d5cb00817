//! The friction limit along the motions only friction carries: the sliding loads, the
//! relief of the first outer iteration, the recentring of its answer and the check of the
//! load against the largest friction force (see the module documentation of [`super`]).

use super::motions::{load_along, norm, ROUND_OFF};
use crate::contact::FrictionBound;
use crate::display::significant;
use crate::error::{Error, Result};
use crate::problem::Problem;
use crate::rigid::{solve_symmetric, Group, Motion, Runaway};
use crate::solver::frozen::Frozen;
use crate::solver::System;

/// The load along the sliding motions of the groups of bodies that carry some (see the
/// module documentation): per group, the direction of that load and its size.
#[derive(Clone, Debug, Default)]
pub struct Sliding {
    pub(super) bodies: Vec<SlidingLoad>,
}

/// The load along the sliding motions of one group of bodies ([`crate::rigid::Group`]).
#[derive(Clone, Debug)]
pub(super) struct SlidingLoad {
    /// The group (index into [`crate::rigid::RigidMotions::groups`]).
    group: usize,
    /// Unit coefficient vector (of the group's bodies together) of the direction r of the
    /// load within the sliding motions.
    direction: Motion,
    /// Whether r rotates some body (the load is then a moment) rather than translating them.
    rotation: bool,
    /// The load along r, `f·r / s` (a force or moment, solver's units), with `s` the size
    /// of r per unit coefficient: the largest `|a|` of a body for a translation, the
    /// largest `|ω|` for a rotation.
    pub(super) load: f64,
    /// The contact points of the group with friction (the process's ghost points too),
    /// with `‖ρ_τ(x_i)‖ / s`, ρ the change of the point's relative displacement under r
    /// (each sum over them runs over the points this process counts, completed over the
    /// processes; the relief, a force at the points' nodes, takes them all, so that it is
    /// complete at this process's own nodes).
    pub(super) points: Vec<(usize, f64)>,
}

/// The friction limit of one group at some bounds, and how it is made up.
struct Limit {
    /// The friction force the bounds can exert along the load's direction, in the units
    /// of [`SlidingLoad::load`] ([`capacity`]).
    value: f64,
    /// `Σ w_i p_i` over its Coulomb points (solver's force unit).
    normal_force: f64,
    /// `Σ w_i` over its Tresca points.
    area: f64,
    /// The largest coefficient μ₀ if it is the same at all its points.
    mu: Option<f64>,
    /// Whether every point is of Coulomb type (false: every point of Tresca type; None:
    /// mixed).
    coulomb: Option<bool>,
    /// Whether `‖ρ_τ‖ / s = 1` at every point (a translation along a flat contact).
    flat: bool,
}

/// The tangential part `r − (r·n) n` of `r` at a point of normal `n` (first d entries).
fn tangential(d: usize, r: &[f64; 3], n: &[f64; 3]) -> [f64; 3] {
    let along: f64 = (0..d).map(|j| r[j] * n[j]).sum();
    let mut t = [0.0; 3];
    for j in 0..d {
        t[j] = r[j] - along * n[j];
    }
    t
}

impl Sliding {
    /// The sliding loads of `problem` on `system`: for each group of bodies with sliding
    /// motions carried by friction ([`crate::rigid::Group::sliding`], and no
    /// uncarried motion), the projection of the load onto them, if it is more than
    /// round-off of the group's load.
    pub fn of(system: &System, problem: &Problem) -> Sliding {
        let rigid = &system.rigid;
        let mesh = &problem.mesh;
        let d = rigid.dim;
        let m = crate::rigid::n_modes(d);
        let f = &system.f_ext;
        let share = system.share();
        let mut bodies = Vec::new();
        for (g, group) in rigid.groups.iter().enumerate() {
            if group.sliding.is_empty() || !group.uncarried.is_empty() {
                continue;
            }
            let mut direction = vec![[0.0; 6]; group.bodies.len()];
            let mut size = 0.0;
            for (j, &b) in group.bodies.iter().enumerate() {
                let nodes = rigid.bodies[b].nodes.iter();
                for &v in nodes.filter(|&&v| share.counts_node(v as usize)) {
                    let x = mesh.node(v as usize);
                    for c in &group.sliding {
                        let r = rigid.displacement(b, &c[j], x);
                        let along: f64 = (0..d)
                            .filter(|&i| !system.dofs.is_fixed(d * v as usize + i))
                            .map(|i| r[i] * f[d * v as usize + i])
                            .sum();
                        for (dj, cj) in direction.iter_mut().zip(c) {
                            for i in 0..6 {
                                dj[i] += along * cj[i];
                            }
                        }
                    }
                    for i in 0..d {
                        size += f[d * v as usize + i].abs();
                    }
                }
            }
            share.sum_parts(&mut [
                direction.as_flattened_mut(),
                std::slice::from_mut(&mut size),
            ]);
            let used: Vec<f64> = direction.iter().flat_map(|c| c[..m].to_vec()).collect();
            let along = norm(&used);
            if along.is_nan() || along <= ROUND_OFF * size {
                continue;
            }
            for x in direction.as_flattened_mut() {
                *x = if x.abs() <= 1e-9 * along {
                    0.0
                } else {
                    *x / along
                };
            }
            let (mut translation, mut omega, mut rotation) = (0.0f64, 0.0f64, false);
            for (c, &b) in direction.iter().zip(&group.bodies) {
                let size = rigid.bodies[b].size;
                let (t, w) = (norm(&c[..d]), norm(&c[d..m]) / size);
                rotation |= w * size > 1e-9 * t;
                translation = translation.max(t);
                omega = omega.max(w);
            }
            let per_unit = if rotation { omega } else { translation };
            // The load along the unit direction is its norm `along` (f·r = F·direction).
            let load = along / per_unit;
            let mut points = Vec::new();
            for i in 0..system.contact.len() {
                let boundary = &problem.contact[system.contact.boundary[i] as usize];
                if boundary.friction.is_none() {
                    continue;
                }
                // The point's node, or (a contact pair) its master point, on the group.
                let on = rigid.group_sides(&system.contact, mesh, i, g);
                let r = match &on[..] {
                    [] => continue,
                    [(j, side)] => {
                        rigid.displacement(b_of(group, *j), &direction[*j], &side.x[..d])
                    }
                    _ => rigid.relative_motion(g, &direction, &on),
                };
                let n = &system.contact.normal[i];
                let along_normal: f64 = (0..d).map(|j| r[j] * n[j]).sum();
                let tangential: Vec<f64> = (0..d).map(|j| r[j] - along_normal * n[j]).collect();
                points.push((i, norm(&tangential) / per_unit));
            }
            bodies.push(SlidingLoad {
                group: g,
                direction,
                rotation,
                load,
                points,
            });
        }
        Sliding { bodies }
    }

    /// Whether no group of bodies has a load along motions only friction carries.
    pub fn is_empty(&self) -> bool {
        self.bodies.is_empty()
    }

    /// Whether the friction bounds `bound` (per contact point) cannot carry the load of
    /// some group: its load is above `Σ w_i F_i ‖ρ_τ‖`.
    pub fn exceeds(&self, system: &System, bound: &[f64]) -> bool {
        self.bodies
            .iter()
            .any(|s| s.load > capacity(system, s, bound))
    }

    /// The relief of the first outer iteration (see the module documentation): nodal
    /// forces (DOF order) at the frictional contact points of each group, tangential and
    /// proportional to the points' weights, whose load along every sliding motion of the
    /// group is minus that of the external forces. At a point between two bodies of the
    /// group the force acts on both, as a contact force does (`+t` on the slave node,
    /// `−N_j t` on the master facet's nodes).
    pub fn relief(&self, system: &System, problem: &Problem) -> Vec<f64> {
        let rigid = &system.rigid;
        let mesh = &problem.mesh;
        let d = rigid.dim;
        let contact = &system.contact;
        let f = &system.f_ext;
        let share = system.share();
        let counted = |v: &&u32| share.counts_node(**v as usize);
        let mut relief = vec![0.0; f.len()];
        for s in &self.bodies {
            let g = s.group;
            let group = &rigid.groups[g];
            let basis = &group.sliding;
            let k = basis.len();
            // The load along each sliding motion.
            let mut load = load_along(system, mesh, group, basis);
            // ψ_l: w_i (ρ_l)_τ(x_i) at the frictional points, free DOFs only (at a master
            // point, spread onto its facet's nodes by N_j).
            let mut psi = vec![vec![0.0; f.len()]; k];
            for &(i, _) in &s.points {
                let on = rigid.group_sides(contact, mesh, i, g);
                let (_, nodes, coef) = contact.stencil(d, i);
                let n = &contact.normal[i];
                let w = contact.weight[i];
                for (l, c) in basis.iter().enumerate() {
                    // One side: the force on the body along its own motion's tangential
                    // part; two: the contact force along the relative motion's.
                    let (t, signed) = match &on[..] {
                        [(j, side)] => {
                            let r = rigid.displacement(b_of(group, *j), &c[*j], &side.x[..d]);
                            (tangential(d, &r, n), false)
                        }
                        _ => (tangential(d, &rigid.relative_motion(g, c, &on), n), true),
                    };
                    for (_, side) in &on {
                        for a in side.stencil.clone() {
                            let v = nodes[a] as usize;
                            let ca = if signed { coef[a] } else { coef[a].abs() };
                            for j in 0..d {
                                let dof = d * v + j;
                                if !system.dofs.is_fixed(dof) {
                                    psi[l][dof] += ca * w * t[j];
                                }
                            }
                        }
                    }
                }
            }
            // M β = −F with M_lm = ψ_l · r_m.
            let mut gram = vec![0.0; k * k];
            for (j, &b) in group.bodies.iter().enumerate() {
                for &v in rigid.bodies[b].nodes.iter().filter(counted) {
                    let x = mesh.node(v as usize);
                    for (m_, c) in basis.iter().enumerate() {
                        let r = rigid.displacement(b, &c[j], x);
                        for (l, p) in psi.iter().enumerate() {
                            gram[l * k + m_] +=
                                (0..d).map(|i| p[d * v as usize + i] * r[i]).sum::<f64>();
                        }
                    }
                }
            }
            share.sum_parts(&mut [&mut gram, &mut load]);
            let minus: Vec<f64> = load.iter().map(|x| -x).collect();
            let beta = solve_symmetric(&gram, &minus);
            for (l, p) in psi.iter().enumerate() {
                for (x, y) in relief.iter_mut().zip(p) {
                    *x += beta[l] * y;
                }
            }
        }
        relief
    }

    /// Removes from `u` (DOF order, free DOFs) the sliding rigid motion of each group that
    /// best fits the tangential displacements of its frictional contact points (weighted
    /// least squares with the points' weights; at a point between two of its bodies, the
    /// relative displacement), so that their slips are centred on zero. The relieved
    /// first iteration has no friction: its energy is the same along every sliding
    /// motion, and its Newton steps may leave the bodies anywhere along them (a tilt about
    /// the centroid slides the contact); the friction of the next iteration then starts
    /// from slips of the order of the displacements instead of from rest.
    pub fn recenter(&self, system: &System, problem: &Problem, u: &mut [f64]) {
        let rigid = &system.rigid;
        let mesh = &problem.mesh;
        let d = rigid.dim;
        let contact = &system.contact;
        let share = system.share();
        for s in &self.bodies {
            let g = s.group;
            let group = &rigid.groups[g];
            let basis = &group.sliding;
            let k = basis.len();
            let mut gram = vec![0.0; k * k];
            let mut rhs = vec![0.0; k];
            for &(i, _) in s.points.iter().filter(|&&(i, _)| i < contact.owned()) {
                let on = rigid.group_sides(contact, mesh, i, g);
                let (_, nodes, coef) = contact.stencil(d, i);
                let n = &contact.normal[i];
                let w = contact.weight[i];
                // The displacement of the body at the point (at a master point,
                // Σ N_j u(m_j)); between two bodies of the group, the relative one.
                let signed = on.len() > 1;
                let mut uv = [0.0; 3];
                for (_, side) in &on {
                    for a in side.stencil.clone() {
                        let v = nodes[a] as usize;
                        let ca = if signed { coef[a] } else { coef[a].abs() };
                        for j in 0..d {
                            uv[j] += ca * u[d * v + j];
                        }
                    }
                }
                let ut = tangential(d, &uv, n);
                let fields: Vec<[f64; 3]> = basis
                    .iter()
                    .map(|c| match &on[..] {
                        [(j, side)] => tangential(
                            d,
                            &rigid.displacement(b_of(group, *j), &c[*j], &side.x[..d]),
                            n,
                        ),
                        _ => tangential(d, &rigid.relative_motion(g, c, &on), n),
                    })
                    .collect();
                for l in 0..k {
                    rhs[l] += w * (0..d).map(|j| fields[l][j] * ut[j]).sum::<f64>();
                    for m in 0..k {
                        gram[l * k + m] +=
                            w * (0..d).map(|j| fields[l][j] * fields[m][j]).sum::<f64>();
                    }
                }
            }
            share.sum_parts(&mut [&mut gram, &mut rhs]);
            let y = solve_symmetric(&gram, &rhs);
            for (j, &b) in group.bodies.iter().enumerate() {
                let mut c = [0.0; 6];
                for (l, bl) in basis.iter().enumerate() {
                    for i in 0..6 {
                        c[i] += y[l] * bl[j][i];
                    }
                }
                for &v in &rigid.bodies[b].nodes {
                    let r = rigid.displacement(b, &c, mesh.node(v as usize));
                    for i in 0..d {
                        let dof = d * v as usize + i;
                        if !system.dofs.is_fixed(dof) {
                            u[dof] -= r[i];
                        }
                    }
                }
            }
        }
    }

    /// # Errors
    /// [`Error::FrictionLimit`] if the load of some body exceeds its friction limit at the
    /// largest bounds at `u` ([`largest_bounds`]: the pressures of `u` with the frozen
    /// multipliers of `frozen`); [`Error::Law`] if a user-defined law fails.
    pub fn check(
        &self,
        system: &System,
        problem: &Problem,
        u: &[f64],
        frozen: &Frozen,
    ) -> Result<()> {
        let (bounds, pressures, mu) = largest_bounds(system, problem, u, frozen, false)?;
        for s in &self.bodies {
            let limit = limit(system, problem, s, &bounds, &pressures, &mu);
            if s.load > limit.value {
                return Err(self.error(system, s, limit.words(system, s)));
            }
        }
        Ok(())
    }

    /// The error for a body that slid away in outer iteration `iteration` with the frozen
    /// bounds `frozen` (see the module documentation), if the runaway `r` is along its
    /// sliding motions and the body has a sliding load; `u` is the last iterate before it.
    ///
    /// # Errors
    /// [`Error::Law`] if a user-defined law fails.
    pub fn slid_away(
        &self,
        system: &System,
        problem: &Problem,
        r: &Runaway,
        u: &[f64],
        frozen: &Frozen,
        iteration: usize,
    ) -> Result<Option<Error>> {
        let group = system.rigid.group_of[r.body];
        let Some(s) = self.bodies.iter().find(|s| s.group as u32 == group) else {
            return Ok(None);
        };
        if system.rigid.sliding_share(r.body, &r.motion) < 0.5 {
            return Ok(None);
        }
        let (bounds, pressures, mu) = largest_bounds(system, problem, u, frozen, true)?;
        let largest = limit(system, problem, s, &bounds, &pressures, &mu);
        let words = largest.words(system, s);
        if s.load > largest.value {
            return Ok(Some(self.error(system, s, words)));
        }
        // Below the largest limit: the bound of this iteration, weakened by the slips it
        // was built on, could not carry the load.
        let carried = capacity(system, s, &frozen.friction.bound);
        let (scale, unit) = force_unit(system, s);
        let limit = format!(
            "of outer iteration {iteration}, {} (the slips reached weaken μ below its \
             static limit {words})",
            with_unit(carried * scale, unit)
        );
        Ok(Some(self.error(system, s, limit)))
    }

    fn error(&self, system: &System, s: &SlidingLoad, limit: String) -> Error {
        let units = system.user_units();
        let unit = force_unit(system, s);
        Error::FrictionLimit {
            motion: system
                .rigid
                .describe_group_in(s.group, &s.direction, units.length),
            load: with_unit(s.load * unit.0, unit.1),
            limit,
        }
    }
}

/// The friction force the bounds `bound` (per contact point) can exert along the direction
/// of the sliding load `s`: `Σ w_i F_i ‖r_τ(x_i)‖` over its frictional points, in the units
/// of [`SlidingLoad::load`].
pub(super) fn capacity(system: &System, s: &SlidingLoad, bound: &[f64]) -> f64 {
    let share = system.share();
    let owned = system.contact.owned();
    let mut sum = [s
        .points
        .iter()
        .filter(|&&(i, _)| i < owned)
        .map(|&(i, t)| system.contact.weight[i] * bound[i] * t)
        .sum()];
    share.sum(&mut sum);
    sum[0]
}

/// The friction limit of body `s` at the largest bounds `bounds`, with the pressures and
/// coefficients they are made of.
fn limit(
    system: &System,
    problem: &Problem,
    s: &SlidingLoad,
    bounds: &[f64],
    pressures: &[f64],
    mu: &[f64],
) -> Limit {
    let mut normal_force = 0.0;
    let mut area = 0.0;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    let (mut coulomb, mut tresca) = (false, false);
    let mut flat = !s.rotation;
    let share = system.share();
    let owned = system.contact.owned();
    for &(i, t) in s.points.iter().filter(|&&(i, _)| i < owned) {
        let w = system.contact.weight[i];
        let boundary = &problem.contact[system.contact.boundary[i] as usize];
        let is_coulomb = boundary
            .friction
            .as_ref()
            .is_some_and(|f| f.bound == FrictionBound::Coulomb);
        if is_coulomb {
            coulomb = true;
            normal_force += w * pressures[i];
        } else {
            tresca = true;
            area += w;
        }
        lo = lo.min(mu[i]);
        hi = hi.max(mu[i]);
        flat &= (t - 1.0).abs() <= 1e-9;
    }
    // Over the processes (nothing to complete on one).
    let mut sums = [normal_force, area];
    share.sum(&mut sums);
    [normal_force, area] = sums;
    let (mut lows, mut highs) = ([lo], [hi]);
    share.min(&mut lows);
    share.max(&mut highs);
    (lo, hi) = (lows[0], highs[0]);
    let mut kinds = [coulomb, tresca];
    share.any_each(&mut kinds);
    [coulomb, tresca] = kinds;
    flat = share.all(flat);
    Limit {
        value: capacity(system, s, bounds),
        normal_force,
        area,
        mu: (hi - lo <= 1e-12 * hi.abs()).then_some(hi),
        coulomb: match (coulomb, tresca) {
            (true, false) => Some(true),
            (false, true) => Some(false),
            _ => None,
        },
        flat,
    }
}

impl Limit {
    /// The limit in words with its numbers in the user's units, e.g.
    /// `6 N/m (μ × normal force = 0.3 × 20 N/m)`.
    fn words(&self, system: &System, s: &SlidingLoad) -> String {
        let units = system.user_units();
        let (scale, unit) = force_unit(system, s);
        let value = with_unit(self.value * scale, unit);
        let d = system.rigid.dim;
        match (self.coulomb, self.mu, self.flat) {
            (Some(true), Some(mu), true) => format!(
                "μ × normal force = {} × {} = {value}",
                significant(mu),
                with_unit(self.normal_force * units.force, force_name(d))
            ),
            (Some(false), Some(mu), true) => format!(
                "bound × contact {} = {} Pa × {} = {value}",
                if d == 2 { "length" } else { "area" },
                significant(mu * units.traction),
                with_unit(
                    self.area * units.length.powi(d as i32 - 1),
                    if d == 2 { "m" } else { "m²" }
                )
            ),
            _ => format!(
                "{value} (Σ w_i F_i ‖r_τ‖ over the contact points, F_i the largest friction \
                 bound: μ₀ p_i for a Coulomb bound, μ₀ for a Tresca bound, μ₀ = sup μ; \
                 normal force {})",
                with_unit(self.normal_force * units.force, force_name(d))
            ),
        }
    }
}

/// The unit conversion (factor and name) of the loads and limits of `s`: a force, or a
/// moment for a rotation.
fn force_unit(system: &System, s: &SlidingLoad) -> (f64, &'static str) {
    let units = system.user_units();
    let d = system.rigid.dim;
    if s.rotation {
        (
            units.force * units.length,
            if d == 2 { "N·m/m" } else { "N·m" },
        )
    } else {
        (units.force, force_name(d))
    }
}

fn force_name(d: usize) -> &'static str {
    if d == 2 {
        "N/m"
    } else {
        "N"
    }
}

fn with_unit(x: f64, unit: &str) -> String {
    format!("{} {unit}", significant(x))
}

/// The largest friction bound each contact point can reach at `u`, with its pressure and
/// its largest coefficient μ₀ (see the module documentation): `μ₀ p` for a Coulomb bound,
/// `μ₀` for a Tresca bound, 0 without friction. The pressure is `p(u)`; at a Signorini
/// point the multiplier of `frozen` itself if `frozen_multipliers` (the pressure the
/// bound of its convex problem was built on), else its update `(λ + r (u_ν − g))_+` at u
/// (after a first iteration, whose multipliers are still zero).
///
/// # Errors
/// [`Error::Law`] if a user-defined law fails.
pub fn largest_bounds(
    system: &System,
    problem: &Problem,
    u: &[f64],
    frozen: &Frozen,
    frozen_multipliers: bool,
) -> Result<(Vec<f64>, Vec<f64>, Vec<f64>)> {
    bounds_at(system, problem, u, frozen, frozen_multipliers, true)
}

/// The friction bound of each contact point at rest at `u`, with its pressure and
/// coefficient, as [`largest_bounds`]: with the coefficient `μ₀ = sup μ` if `largest`,
/// else with its value at zero slip μ(0) (the state at rest, [`super::AtRest`]).
///
/// # Errors
/// [`Error::Law`] if a user-defined law fails.
pub(super) fn bounds_at(
    system: &System,
    problem: &Problem,
    u: &[f64],
    frozen: &Frozen,
    frozen_multipliers: bool,
    largest: bool,
) -> Result<(Vec<f64>, Vec<f64>, Vec<f64>)> {
    let ca = system.contact_assembler(problem);
    let mut responses = Vec::new();
    ca.normal_responses(u, false, &mut responses)?;
    let ca = crate::assembly::contact::ContactAssembler {
        responses: &responses,
        ..ca
    };
    let data = frozen.contact();
    let contact = &system.contact;
    let n = contact.len();
    let d = system.rigid.dim;
    let mut bounds = vec![0.0; n];
    let mut pressures = vec![0.0; n];
    let mut mu = vec![0.0; n];
    let mut start = 0;
    for run in contact.boundary.chunk_by(|a, b| a == b) {
        let range = start..start + run.len();
        start = range.end;
        let b = run[0] as usize;
        let Some(fr) = &problem.contact[b].friction else {
            continue;
        };
        let zeros = vec![0.0; range.len()];
        fr.mu
            .values(
                &zeros,
                &contact.position[range.clone()],
                d,
                &mut mu[range.clone()],
            )
            .map_err(|message| Error::Law {
                law: format!("contact[{b}].friction.mu ({})", fr.mu.name()),
                message,
            })?;
        let sup = fr.mu.sup();
        for i in range {
            if largest && !fr.mu.is_field() && sup.is_finite() {
                mu[i] = mu[i].max(sup);
            }
            pressures[i] = if frozen_multipliers && problem.contact[b].normal.is_exact() {
                data.pressure[i]
            } else {
                ca.state(u, i, &data).pressure
            };
            bounds[i] = fr.bound_of(mu[i], pressures[i]);
        }
    }
    Ok((bounds, pressures, mu))
}

/// The body at place `j` of `group`.
fn b_of(group: &Group, j: usize) -> usize {
    group.bodies[j]
}
