//! Bodies held by contact alone: the free rigid motions of a body (those the Dirichlet
//! conditions leave free, [`crate::fem::rigid`]) that contact carries.
//!
//! The free motions of a body split into *pressed* ones, which move some contact point
//! along its normal (normal contact carries them), and *sliding* ones, which move every
//! contact point within its tangent plane (only friction can carry them). Two things
//! follow.
//!
//! # The rigid drop
//!
//! A body resting across a gap (a block above its foundation) first moves rigidly until
//! it touches, then deforms. When the load is small the deformation is many orders of
//! magnitude below the gap: the displacement scale U of [`super::scaling`] follows the
//! load, the gap is `g/U` in its units, and Newton's method would cross it in steps of
//! the size the shift of the Newton matrix allows ([`crate::fem::rigid::NEWTON_SHIFT`]),
//! thousands of them; worse, a displacement `g + δ` with `δ ≪ g` cannot even carry the
//! digits of δ. So before Newton ([`rigid_drop`]), every such body is moved along its
//! pressed motions to where it rests on its contact points: the rigid motion `u_R` that
//! maximizes the work of the load `f·u_R` without any contact point crossing its gap,
//!
//! ```text
//!     maximize  F·c   subject to  a_i·c ≤ h_i  for every contact point i of the body,
//! ```
//!
//! with c the coefficients of `u_R` in an orthonormal basis of the pressed motions, `F_l =
//! f·r_l` the load along basis motion l, `a_{il} = ν_i·r_l(x_i)` the normal displacement
//! of point i under it and `h_i = g_i − u_ν,i ≥ 0` its gap. This linear programme is
//! solved by steepest ascent on the cone of feasible directions: at c, with `A` the rows
//! of the touching points, the direction `ρ = F − A λ` with `λ = argmin_{λ ≥ 0} ‖F −
//! Aλ‖` (non-negative least squares) is the projection of F onto the feasible cone (so
//! `a_i·ρ ≤ 0` for every touching point and `F·ρ = ‖ρ‖² > 0`); the body moves along ρ
//! until the next point touches; it rests when `ρ = 0` (the load lies in the cone of the
//! touching points' normals). A body with no point ahead is pulled off its contact:
//! [`crate::Error::ContactLost`], before any Newton step. The solve then goes on for the
//! displacement relative to `u_R` ([`super::System::place`]): the gaps become `g_i −
//! ν_i·u_R(x_i)`, the closed part subtracted once and exactly (for a translation along an
//! axis and axis-aligned normals, bit for bit), and the answer is `u_R` plus the relative
//! displacement. Only drops of more than the displacement scale U are made: a gap that
//! the deformation itself closes, or one of the order of U, is left to Newton.
//!
//! # The friction limit
//!
//! Along a sliding motion r, friction alone balances the load: with friction forces
//! `|t_i| ≤ w_i F_i`, equilibrium along r needs
//!
//! ```text
//!     f·r  ≤  Σ_i w_i F_i ‖r_τ(x_i)‖,
//! ```
//!
//! the *friction limit* along r, `r_τ` the tangential part of r at contact point i and
//! `F_i` the largest bound friction can reach there: `μ₀ p_i` for a Coulomb bound (p_i the
//! pressure), `μ₀` for a Tresca bound, with `μ₀ = sup_r μ(r)` the largest coefficient —
//! the static value μ(0) for a slip-weakening law (a sticking body), the value at the
//! point for a law of the position — since the force of a slipping point, `F j'(r)`,
//! never exceeds F (`j' ≤ 1` for every potential). For a translation along a flat
//! foundation `‖r_τ‖ = 1` and the limit is `μ₀ × normal force` (Coulomb; the normal force
//! `Σ w_i p_i` balances the normal load) or `μ₀ × contact area` (Tresca). The check is
//! made along the direction r of the load within the body's sliding motions ([`Sliding`]);
//! a load above the limit is refused with [`crate::Error::FrictionLimit`], naming the
//! motion, the load and the limit in the user's units.
//!
//! The outer loop freezes the bound F at the last iterate. A Coulomb bound starts from the
//! pressure of the unloaded state, zero, so its first convex problem cannot hold the body
//! and the body would slide away. That iteration is therefore solved with the load along
//! the sliding motions balanced by tangential forces at the frictional contact points,
//! proportional to their weights (as if friction were uniformly mobilized:
//! [`Sliding::relief`]); its pressures give the friction limit, which is checked, and the
//! bound of the next iteration, which carries the load when the load is below the limit.
//! Mixing conserves the total: for a constant μ on a flat foundation every image has
//! `Σ w_i F_i = μ × normal force`, and the affine combinations of the Anderson step keep
//! it. A slip-dependent μ may still lose the body in a later iteration (the slips of the
//! early, strongly regularized, stages weaken μ); the error then says what the bound of
//! that iteration carried and the limit.

use super::frozen::Frozen;
use super::System;
use crate::contact::FrictionBound;
use crate::display::significant;
use crate::error::{Error, Result};
use crate::fem::rigid::{solve_small, RigidMotions, Runaway};
use crate::problem::Problem;

/// Most steps of the rigid drop of one body; each adds a touching contact point (a body
/// rests on at most 6 in general position, many more at once on a flat foundation).
pub const MAX_DROP_STEPS: usize = 100;

/// Relative size below which a load, a direction component or a slack counts as round-off
/// in the rigid drop and the friction limit.
const ROUND_OFF: f64 = 1e-12;

/// A rigid placement of the bodies before Newton ([`rigid_drop`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Placement {
    /// The rigid displacement `u_R` (DOF order, in the units of the solve's displacements),
    /// zero outside the bodies moved and at prescribed DOFs.
    pub u: Vec<f64>,
    /// Per body moved: its index and the coefficients of its motion (first m entries; see
    /// [`crate::fem::rigid`]).
    pub moves: Vec<(usize, [f64; 6])>,
}

/// The rigid drop of the bodies of `system` (see the module documentation) from the
/// displacement `u`, under the external forces of `system`: `None` if no body moves by
/// more than the displacement unit of the solve (1: the solver works in units of U).
///
/// # Errors
/// [`Error::ContactLost`] if the load pulls a body away from every contact point (the
/// linear programme is unbounded), unless a Tresca bound, which acts on separated points,
/// might hold it.
pub fn rigid_drop(system: &System, problem: &Problem, u: &[f64]) -> Result<Option<Placement>> {
    let rigid = &system.rigid;
    let mesh = &problem.mesh;
    let d = rigid.dim;
    let f = &system.f_ext;
    let contact = &system.contact;
    let share = system.share();
    let mut placed = vec![0.0; u.len()];
    let mut moves = Vec::new();
    for b in 0..rigid.bodies.len() {
        let basis = &rigid.pressed[b];
        if basis.is_empty() {
            continue;
        }
        let k = basis.len();
        let nodes = &rigid.bodies[b].nodes;
        // The load along each pressed motion, and the size of the body's load.
        let mut load = [0.0; 6];
        let mut total = 0.0;
        for &v in nodes.iter().filter(|&&v| share.counts_node(v as usize)) {
            let x = mesh.node(v as usize);
            for (l, c) in basis.iter().enumerate() {
                let r = rigid.displacement(b, c, x);
                for i in 0..d {
                    let dof = d * v as usize + i;
                    if !system.dofs.is_fixed(dof) {
                        load[l] += r[i] * f[dof];
                    }
                }
            }
            for i in 0..d {
                total += f[d * v as usize + i].abs();
            }
        }
        share.sum_parts(&mut [&mut load, std::slice::from_mut(&mut total)]);
        let load_norm = norm(&load[..k]);
        if load_norm.is_nan() || load_norm <= ROUND_OFF * total {
            continue;
        }
        // The contact points of the body: rows a_i and gaps h_i.
        let mut rows = Vec::new();
        let mut gaps = Vec::new();
        let mut tresca = false;
        for i in 0..contact.owned() {
            // The point's node in this body, or (a contact pair) its master point.
            let Some((x, sign, _)) = contact.on_body(mesh, i, &rigid.body_of, b) else {
                continue;
            };
            let cb = &problem.contact[contact.boundary[i] as usize];
            tresca |= cb
                .friction
                .as_ref()
                .is_some_and(|fr| fr.bound == FrictionBound::Tresca);
            let mut row = [0.0; 6];
            for (l, c) in basis.iter().enumerate() {
                let r = rigid.displacement(b, c, &x[..d]);
                row[l] = sign * (0..d).map(|j| r[j] * contact.normal[i][j]).sum::<f64>();
            }
            let (u_nu, _) = contact.kinematics(d, u, i);
            rows.push(row);
            gaps.push(contact.gap[i] - u_nu);
        }
        if share.is_split() {
            // Every process's points, rank after rank: 6 coefficients and a gap each.
            let mine: Vec<f64> = rows
                .iter()
                .zip(&gaps)
                .flat_map(|(r, &h)| r.iter().copied().chain([h]))
                .collect();
            let all = share.gather_varying(&mine);
            rows = all
                .chunks_exact(7)
                .map(|p| std::array::from_fn(|l| p[l]))
                .collect();
            gaps = all.chunks_exact(7).map(|p| p[6]).collect();
            let mut any = [f64::from(u8::from(tresca))];
            share.max(&mut any);
            tresca = any[0] > 0.0;
        }
        // A body already pressed into its contact has nothing to drop.
        if gaps.iter().any(|&h| h < 0.0) {
            continue;
        }
        let c = match rest(&load, k, &rows, &gaps) {
            Ok(c) => c,
            Err(_) if tresca => continue,
            Err(away) => {
                let mut motion = [0.0; 6];
                for (l, bl) in basis.iter().enumerate() {
                    for j in 0..6 {
                        motion[j] += away[l] * bl[j];
                    }
                }
                let units = system.user_units();
                return Err(Error::ContactLost {
                    motions: format!(
                        "{} (the load moves the body away from every contact point)",
                        describe(rigid, b, &motion, units.length)
                    ),
                });
            }
        };
        let mut coefficients = [0.0; 6];
        for (l, bl) in basis.iter().enumerate() {
            for j in 0..6 {
                coefficients[j] += c[l] * bl[j];
            }
        }
        // Components at round-off level (a tilt of 10⁻¹⁶ from a load's moment that the
        // rest has cancelled) would turn a translation into a rotation about a far point.
        let reach = norm(&coefficients);
        for x in coefficients.iter_mut() {
            if x.abs() <= ROUND_OFF * reach {
                *x = 0.0;
            }
        }
        let mut largest = [0.0f64];
        for &v in nodes.iter().filter(|&&v| share.counts_node(v as usize)) {
            let r = rigid.displacement(b, &coefficients, mesh.node(v as usize));
            largest[0] = largest[0].max(norm(&r[..d]));
        }
        share.max(&mut largest);
        if largest[0] <= 1.0 {
            continue;
        }
        for &v in nodes {
            let r = rigid.displacement(b, &coefficients, mesh.node(v as usize));
            for i in 0..d {
                let dof = d * v as usize + i;
                if !system.dofs.is_fixed(dof) {
                    placed[dof] = r[i];
                }
            }
        }
        moves.push((b, coefficients));
    }
    Ok((!moves.is_empty()).then_some(Placement { u: placed, moves }))
}

/// The rigid motions of a placement in words, in the user's units: "translation along y
/// by up to 0.001 m".
pub fn describe_placement(
    system: &System,
    problem: &Problem,
    placement: &Placement,
) -> Vec<String> {
    let rigid = &system.rigid;
    let units = system.user_units();
    let d = rigid.dim;
    let m = crate::fem::rigid::n_modes(d);
    placement
        .moves
        .iter()
        .map(|(b, c)| {
            let size = norm(&c[..m]);
            let unit = c.map(|x| x / size);
            let share = system.share();
            let nodes = rigid.bodies[*b].nodes.iter();
            let mut largest = [nodes
                .filter(|&&v| share.counts_node(v as usize))
                .map(|&v| norm(&rigid.displacement(*b, c, problem.mesh.node(v as usize))[..d]))
                .fold(0.0f64, f64::max)];
            share.max(&mut largest);
            let largest = largest[0];
            format!(
                "{} by up to {} m",
                describe(rigid, *b, &unit, units.length),
                significant(largest * units.displacement)
            )
        })
        .collect()
}

/// The motion `c` of body `b` in words in the user's coordinates, with its mesh component
/// when there are several.
fn describe(rigid: &RigidMotions, b: usize, c: &[f64; 6], length: f64) -> String {
    let motion = rigid.describe_in(b, c, length);
    if rigid.bodies.len() > 1 {
        format!(
            "mesh component {} of {}: {motion}",
            b + 1,
            rigid.bodies.len()
        )
    } else {
        motion
    }
}

/// The Euclidean norm of `x` by `hypot`, so that no square overflows or underflows (a drop
/// across a gap of 10^300 displacement units, a load of 10^-300 in them).
fn norm(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |n, v| n.hypot(*v))
}

/// The maximizer of `F·c` over `c ∈ ℝ^k` subject to `rows[i]·c ≤ gaps[i]` (all gaps ≥ 0)
/// by steepest ascent on the feasible cone (module documentation), from `c = 0`; if the
/// programme is unbounded, the error is the unit direction along which nothing stops the
/// body. Stops after [`MAX_DROP_STEPS`] steps at the last point reached (a placement need
/// not be optimal, only feasible).
fn rest(
    load: &[f64; 6],
    k: usize,
    rows: &[[f64; 6]],
    gaps: &[f64],
) -> std::result::Result<[f64; 6], [f64; 6]> {
    let mut c = [0.0; 6];
    let load_norm = norm(&load[..k]);
    let gap_scale = gaps.iter().fold(0.0f64, |m, &h| m.max(h));
    for _ in 0..MAX_DROP_STEPS {
        let reach = norm(&c[..k]);
        let tolerance = ROUND_OFF * gap_scale.max(reach);
        let slack: Vec<f64> = rows
            .iter()
            .zip(gaps)
            .map(|(a, &h)| h - (0..k).map(|l| a[l] * c[l]).sum::<f64>())
            .collect();
        let touching: Vec<usize> = (0..rows.len()).filter(|&i| slack[i] <= tolerance).collect();
        let columns: Vec<[f64; 6]> = touching.iter().map(|&i| rows[i]).collect();
        let mut rho = cone_residual(load, k, &columns);
        let rho_norm = norm(&rho[..k]);
        if rho_norm <= ROUND_OFF * load_norm {
            return Ok(c);
        }
        // Components at round-off level would tilt an axis-aligned drop.
        for x in rho.iter_mut().take(k) {
            *x = if x.abs() <= ROUND_OFF * rho_norm {
                0.0
            } else {
                *x / rho_norm
            };
        }
        let mut step = f64::INFINITY;
        for i in 0..rows.len() {
            if slack[i] <= tolerance {
                continue;
            }
            let a = &rows[i];
            let along: f64 = (0..k).map(|l| a[l] * rho[l]).sum();
            if along > ROUND_OFF * norm(&a[..k]) {
                step = step.min(slack[i] / along);
            }
        }
        if !step.is_finite() {
            return Err(rho);
        }
        for l in 0..k {
            c[l] += step * rho[l];
        }
    }
    Ok(c)
}

/// `F − A λ` with `λ = argmin_{λ ≥ 0} ‖F − Σ_j λ_j a_j‖` over the columns `a_j` (k
/// entries each): the projection of F onto the polar of their cone (Lawson–Hanson
/// non-negative least squares; at most `3k + 10` passes, the passive set never exceeds k
/// independent columns).
fn cone_residual(load: &[f64; 6], k: usize, columns: &[[f64; 6]]) -> [f64; 6] {
    let n = columns.len();
    let mut lambda = vec![0.0; n];
    let mut passive = vec![false; n];
    let residual = |lambda: &[f64]| {
        let mut r = *load;
        for (j, a) in columns.iter().enumerate() {
            for l in 0..k {
                r[l] -= lambda[j] * a[l];
            }
        }
        r
    };
    let scale = norm(&load[..k]);
    for _ in 0..3 * k + 10 {
        let r = residual(&lambda);
        // The most promising column outside the passive set.
        let mut best = None;
        let mut best_w = ROUND_OFF * scale;
        for j in 0..n {
            if passive[j] {
                continue;
            }
            let w: f64 = (0..k).map(|l| columns[j][l] * r[l]).sum::<f64>() / norm(&columns[j][..k]);
            if w > best_w {
                best_w = w;
                best = Some(j);
            }
        }
        let Some(j) = best else { break };
        passive[j] = true;
        // Least squares on the passive columns, stepping back while some coefficient is
        // negative.
        loop {
            let set: Vec<usize> = (0..n).filter(|&j| passive[j]).collect();
            let z = least_squares(
                load,
                k,
                &set.iter().map(|&j| columns[j]).collect::<Vec<_>>(),
            );
            if z.iter().all(|&x| x > 0.0) {
                for (&j, &x) in set.iter().zip(&z) {
                    lambda[j] = x;
                }
                break;
            }
            // Move from λ towards z until the first coefficient reaches zero.
            let mut alpha = 1.0f64;
            for (&j, &x) in set.iter().zip(&z) {
                if x <= 0.0 {
                    alpha = alpha.min(lambda[j] / (lambda[j] - x));
                }
            }
            for (&j, &x) in set.iter().zip(&z) {
                lambda[j] += alpha * (x - lambda[j]);
                if lambda[j] <= ROUND_OFF * scale {
                    lambda[j] = 0.0;
                    passive[j] = false;
                }
            }
            if !passive.iter().any(|&p| p) {
                break;
            }
        }
    }
    residual(&lambda)
}

/// The least-squares coefficients `z` of `F ≈ Σ_j z_j a_j` over the columns `a_j` (k
/// entries each), of least norm when they are dependent.
fn least_squares(load: &[f64; 6], k: usize, columns: &[[f64; 6]]) -> Vec<f64> {
    let n = columns.len();
    // Least norm: z = Aᵀ y with (A Aᵀ) y = F, a k × k system.
    let mut gram = [[0.0; 6]; 6];
    for a in columns {
        for l in 0..k {
            for m in 0..k {
                gram[l][m] += a[l] * a[m];
            }
        }
    }
    let y = solve_small(&gram, load, k);
    (0..n)
        .map(|j| (0..k).map(|l| columns[j][l] * y[l]).sum())
        .collect()
}

/// The load along the sliding motions of the bodies that carry some (see the module
/// documentation): per body, the direction of that load and its size.
#[derive(Clone, Debug, Default)]
pub struct Sliding {
    bodies: Vec<SlidingLoad>,
}

/// The load along the sliding motions of one body.
#[derive(Clone, Debug)]
struct SlidingLoad {
    body: usize,
    /// Unit coefficient vector of the direction r of the load within the sliding motions.
    direction: [f64; 6],
    /// Whether r is a rotation (the load is then a moment) rather than a translation.
    rotation: bool,
    /// The load along r, `f·r / s` (a force or moment, solver's units), with `s` the size
    /// of r per unit coefficient: `|a|` for a translation, `|ω|` for a rotation.
    load: f64,
    /// The contact points of the body with friction (the process's ghost points too), with
    /// `‖r_τ(x_i)‖ / s` (each sum over them runs over the points this process counts,
    /// completed over the processes; the relief, a force at the points' nodes, takes them
    /// all, so that it is complete at this process's own nodes).
    points: Vec<(usize, f64)>,
}

/// The friction limit of one body at some bounds, and how it is made up.
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
    /// Whether `‖r_τ‖ / s = 1` at every point (a translation along a flat contact).
    flat: bool,
}

impl Sliding {
    /// The sliding loads of `problem` on `system`: for each body with sliding motions
    /// carried by friction ([`RigidMotions::sliding`] not in
    /// [`RigidMotions::uncarried`]), the projection of the load onto them, if it is more
    /// than round-off of the body's load.
    pub fn of(system: &System, problem: &Problem) -> Sliding {
        let rigid = &system.rigid;
        let mesh = &problem.mesh;
        let d = rigid.dim;
        let m = crate::fem::rigid::n_modes(d);
        let f = &system.f_ext;
        let share = system.share();
        let mut bodies = Vec::new();
        for b in 0..rigid.bodies.len() {
            if rigid.sliding[b].is_empty() || !rigid.uncarried[b].is_empty() {
                continue;
            }
            let nodes = &rigid.bodies[b].nodes;
            let mut direction = [0.0; 6];
            let mut size = 0.0;
            for &v in nodes.iter().filter(|&&v| share.counts_node(v as usize)) {
                let x = mesh.node(v as usize);
                for c in &rigid.sliding[b] {
                    let r = rigid.displacement(b, c, x);
                    let along: f64 = (0..d)
                        .filter(|&i| !system.dofs.is_fixed(d * v as usize + i))
                        .map(|i| r[i] * f[d * v as usize + i])
                        .sum();
                    for j in 0..6 {
                        direction[j] += along * c[j];
                    }
                }
                for i in 0..d {
                    size += f[d * v as usize + i].abs();
                }
            }
            share.sum_parts(&mut [&mut direction, std::slice::from_mut(&mut size)]);
            let along = norm(&direction[..m]);
            if along.is_nan() || along <= ROUND_OFF * size {
                continue;
            }
            for x in direction.iter_mut() {
                *x = if x.abs() <= 1e-9 * along {
                    0.0
                } else {
                    *x / along
                };
            }
            let body = &rigid.bodies[b];
            let translation = norm(&direction[..d]);
            let omega = norm(&direction[d..m]) / body.size;
            let rotation = omega * body.size > 1e-9 * translation;
            let per_unit = if rotation { omega } else { translation };
            // The load along the unit direction is its norm `along` (f·r = F·direction).
            let load = along / per_unit;
            let mut points = Vec::new();
            for i in 0..system.contact.len() {
                let boundary = &problem.contact[system.contact.boundary[i] as usize];
                if boundary.friction.is_none() {
                    continue;
                }
                // The point's node in this body, or (a contact pair) its master point.
                let Some((x, ..)) = system.contact.on_body(mesh, i, &rigid.body_of, b) else {
                    continue;
                };
                let r = rigid.displacement(b, &direction, &x[..d]);
                let n = &system.contact.normal[i];
                let along_normal: f64 = (0..d).map(|j| r[j] * n[j]).sum();
                let tangential: Vec<f64> = (0..d).map(|j| r[j] - along_normal * n[j]).collect();
                points.push((i, norm(&tangential) / per_unit));
            }
            bodies.push(SlidingLoad {
                body: b,
                direction,
                rotation,
                load,
                points,
            });
        }
        Sliding { bodies }
    }

    /// Whether no body has a load along motions only friction carries.
    pub fn is_empty(&self) -> bool {
        self.bodies.is_empty()
    }

    /// Whether the friction bounds `bound` (per contact point) cannot carry the load of
    /// some body: its load is above `Σ w_i F_i ‖r_τ‖`.
    pub fn exceeds(&self, system: &System, bound: &[f64]) -> bool {
        self.bodies
            .iter()
            .any(|s| s.load > capacity(system, s, bound))
    }

    /// The relief of the first outer iteration (see the module documentation): nodal
    /// forces (DOF order) at the frictional contact points of each body, tangential and
    /// proportional to the points' weights, whose load along every sliding motion of the
    /// body is minus that of the external forces.
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
            let b = s.body;
            let basis = &rigid.sliding[b];
            let k = basis.len();
            // The load along each sliding motion.
            let mut load = [0.0; 6];
            for &v in rigid.bodies[b].nodes.iter().filter(counted) {
                let x = mesh.node(v as usize);
                for (l, c) in basis.iter().enumerate() {
                    let r = rigid.displacement(b, c, x);
                    for i in 0..d {
                        let dof = d * v as usize + i;
                        if !system.dofs.is_fixed(dof) {
                            load[l] += r[i] * f[dof];
                        }
                    }
                }
            }
            // ψ_l: w_i (r_l)_τ(x_i) at the frictional points, free DOFs only (at a master
            // point, spread onto its facet's nodes by N_j).
            let mut psi = vec![vec![0.0; f.len()]; k];
            for &(i, _) in &s.points {
                let Some((x, _, on)) = contact.on_body(mesh, i, &rigid.body_of, b) else {
                    continue;
                };
                let (_, nodes, coef) = contact.stencil(d, i);
                let n = &contact.normal[i];
                let w = contact.weight[i];
                for (l, c) in basis.iter().enumerate() {
                    let r = rigid.displacement(b, c, &x[..d]);
                    let along: f64 = (0..d).map(|j| r[j] * n[j]).sum();
                    for a in on.clone() {
                        let v = nodes[a] as usize;
                        for j in 0..d {
                            let dof = d * v + j;
                            if !system.dofs.is_fixed(dof) {
                                psi[l][dof] += coef[a].abs() * w * (r[j] - along * n[j]);
                            }
                        }
                    }
                }
            }
            // M β = −F with M_lm = ψ_l · r_m.
            let mut gram = [[0.0; 6]; 6];
            for &v in rigid.bodies[b].nodes.iter().filter(counted) {
                let x = mesh.node(v as usize);
                for (m_, c) in basis.iter().enumerate() {
                    let r = rigid.displacement(b, c, x);
                    for (l, p) in psi.iter().enumerate() {
                        gram[l][m_] += (0..d).map(|i| p[d * v as usize + i] * r[i]).sum::<f64>();
                    }
                }
            }
            share.sum_parts(&mut [gram.as_flattened_mut(), &mut load]);
            let minus = load.map(|x| -x);
            let beta = solve_small(&gram, &minus, k);
            for (l, p) in psi.iter().enumerate() {
                for (x, y) in relief.iter_mut().zip(p) {
                    *x += beta[l] * y;
                }
            }
        }
        relief
    }

    /// Removes from `u` (DOF order, free DOFs) the sliding rigid motion of each body that
    /// best fits the tangential displacements of its frictional contact points (weighted
    /// least squares with the points' weights), so that their slips are centred on zero.
    /// The relieved first iteration has no friction: its energy is the same along every
    /// sliding motion, and its Newton steps may leave the body anywhere along them (a
    /// tilt about the centroid slides the contact); the friction of the next iteration
    /// then starts from slips of the order of the displacements instead of from rest.
    pub fn recenter(&self, system: &System, problem: &Problem, u: &mut [f64]) {
        let rigid = &system.rigid;
        let mesh = &problem.mesh;
        let d = rigid.dim;
        let contact = &system.contact;
        let share = system.share();
        for s in &self.bodies {
            let b = s.body;
            let basis = &rigid.sliding[b];
            let k = basis.len();
            let mut gram = [[0.0; 6]; 6];
            let mut rhs = [0.0; 6];
            for &(i, _) in s.points.iter().filter(|&&(i, _)| i < contact.owned()) {
                let Some((x, _, on)) = contact.on_body(mesh, i, &rigid.body_of, b) else {
                    continue;
                };
                let (_, nodes, coef) = contact.stencil(d, i);
                let n = &contact.normal[i];
                let w = contact.weight[i];
                let tangential = |r: [f64; 3]| {
                    let along: f64 = (0..d).map(|j| r[j] * n[j]).sum();
                    let mut t = [0.0; 3];
                    for j in 0..d {
                        t[j] = r[j] - along * n[j];
                    }
                    t
                };
                // The displacement of the body at the point (at a master point, Σ N_j u(m_j)).
                let mut uv = [0.0; 3];
                for a in on {
                    let v = nodes[a] as usize;
                    for j in 0..d {
                        uv[j] += coef[a].abs() * u[d * v + j];
                    }
                }
                let ut = tangential(uv);
                let fields: Vec<[f64; 3]> = basis
                    .iter()
                    .map(|c| tangential(rigid.displacement(b, c, &x[..d])))
                    .collect();
                for l in 0..k {
                    rhs[l] += w * (0..d).map(|j| fields[l][j] * ut[j]).sum::<f64>();
                    for m in 0..k {
                        gram[l][m] += w * (0..d).map(|j| fields[l][j] * fields[m][j]).sum::<f64>();
                    }
                }
            }
            share.sum_parts(&mut [gram.as_flattened_mut(), &mut rhs]);
            let y = solve_small(&gram, &rhs, k);
            let mut c = [0.0; 6];
            for (l, bl) in basis.iter().enumerate() {
                for j in 0..6 {
                    c[j] += y[l] * bl[j];
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
        let Some(s) = self.bodies.iter().find(|s| s.body == r.body) else {
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
            motion: describe(&system.rigid, s.body, &s.direction, units.length),
            load: with_unit(s.load * unit.0, unit.1),
            limit,
        }
    }
}

/// The friction force the bounds `bound` (per contact point) can exert along the direction
/// of the sliding load `s`: `Σ w_i F_i ‖r_τ(x_i)‖` over its frictional points, in the units
/// of [`SlidingLoad::load`].
fn capacity(system: &System, s: &SlidingLoad, bound: &[f64]) -> f64 {
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
    if share.is_split() {
        let mut sums = [normal_force, area];
        share.sum(&mut sums);
        [normal_force, area] = sums;
        let flag = |b: bool| f64::from(u8::from(b));
        let mut most = [-lo, hi, flag(coulomb), flag(tresca), flag(!flat)];
        share.max(&mut most);
        (lo, hi) = (-most[0], most[1]);
        (coulomb, tresca, flat) = (most[2] > 0.0, most[3] > 0.0, most[4] == 0.0);
    }
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
            if !fr.mu.is_field() && sup.is_finite() {
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
