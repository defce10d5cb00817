//! The rigid drop: bodies resting across a gap moved along their pressed motions onto their
//! contact before Newton (see the module documentation of [`super`]).

use super::motions::{describe, load_along, norm, ROUND_OFF};
use crate::contact::FrictionBound;
use crate::display::significant;
use crate::error::{Error, Result};
use crate::problem::Problem;
use crate::rigid::{solve_symmetric, Motion};
use crate::solver::System;

/// Most steps of the rigid drop of one body; each adds a touching contact point (a body
/// rests on at most 6 in general position, many more at once on a flat foundation).
pub const MAX_DROP_STEPS: usize = 100;

/// A rigid placement of the bodies before Newton ([`rigid_drop`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Placement {
    /// The rigid displacement `u_R` (DOF order, in the units of the solve's displacements),
    /// zero outside the bodies moved and at prescribed DOFs.
    pub u: Vec<f64>,
    /// Per body moved: its index and the coefficients of its motion (first m entries; see
    /// [`crate::rigid`]).
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
    for (g, group) in rigid.groups.iter().enumerate() {
        let basis = &group.pressed;
        if basis.is_empty() {
            continue;
        }
        let k = basis.len();
        // The load along each pressed motion, and the size of the group's load.
        let mut load = load_along(system, mesh, group, basis);
        let mut total = 0.0;
        for &b in &group.bodies {
            let nodes = rigid.bodies[b].nodes.iter();
            for &v in nodes.filter(|&&v| share.counts_node(v as usize)) {
                for i in 0..d {
                    total += f[d * v as usize + i].abs();
                }
            }
        }
        share.sum_parts(&mut [&mut load, std::slice::from_mut(&mut total)]);
        let load_norm = norm(&load);
        if load_norm.is_nan() || load_norm <= ROUND_OFF * total {
            continue;
        }
        // The contact points of the group: rows a_i and gaps h_i.
        let mut rows: Vec<Vec<f64>> = Vec::new();
        let mut gaps = Vec::new();
        let mut tresca = false;
        for i in 0..contact.owned() {
            // The point's node, or (a contact pair) its master point, on the group's bodies.
            let on = rigid.group_sides(contact, mesh, i, g);
            if on.is_empty() {
                continue;
            }
            let cb = &problem.contact[contact.boundary[i] as usize];
            tresca |= cb
                .friction
                .as_ref()
                .is_some_and(|fr| fr.bound == FrictionBound::Tresca);
            let n = &contact.normal[i];
            let along = |b: usize, c: &[f64; 6], x: &[f64; 3]| {
                let r = rigid.displacement(b, c, &x[..d]);
                (0..d).map(|j| r[j] * n[j]).sum::<f64>()
            };
            let row: Vec<f64> = basis
                .iter()
                .map(|c| match &on[..] {
                    [(j, s)] => s.sign * along(group.bodies[*j], &c[*j], &s.x),
                    sides => sides
                        .iter()
                        .map(|(j, s)| s.sign * along(group.bodies[*j], &c[*j], &s.x))
                        .sum(),
                })
                .collect();
            let (u_nu, _) = contact.kinematics(d, u, i);
            rows.push(row);
            gaps.push(contact.gap[i] - u_nu);
        }
        // Every process's points, rank after rank (this process's own on one): k
        // coefficients and a gap each.
        let mine: Vec<f64> = rows
            .iter()
            .zip(&gaps)
            .flat_map(|(r, &h)| r.iter().copied().chain([h]))
            .collect();
        let all = share.gather_varying(&mine);
        rows = all.chunks_exact(k + 1).map(|p| p[..k].to_vec()).collect();
        gaps = all.chunks_exact(k + 1).map(|p| p[k]).collect();
        tresca = share.any(tresca);
        // A group already pressed into its contact has nothing to drop.
        if gaps.iter().any(|&h| h < 0.0) {
            continue;
        }
        let combined = |y: &[f64]| -> Motion {
            let mut motion = vec![[0.0; 6]; group.bodies.len()];
            for (l, bl) in basis.iter().enumerate() {
                for (mj, bj) in motion.iter_mut().zip(bl) {
                    for i in 0..6 {
                        mj[i] += y[l] * bj[i];
                    }
                }
            }
            motion
        };
        let c = match rest(&load, &rows, &gaps) {
            Ok(c) => c,
            Err(_) if tresca => continue,
            Err(away) => {
                let units = system.user_units();
                return Err(Error::ContactLost {
                    motions: format!(
                        "{} (the load moves the body away from every contact point)",
                        rigid.describe_group_in(g, &combined(&away), units.length)
                    ),
                });
            }
        };
        let mut coefficients = combined(&c);
        // Components at round-off level (a tilt of 10⁻¹⁶ from a load's moment that the
        // rest has cancelled) would turn a translation into a rotation about a far point.
        let reach = norm(coefficients.as_flattened());
        for x in coefficients.as_flattened_mut() {
            if x.abs() <= ROUND_OFF * reach {
                *x = 0.0;
            }
        }
        let mut largest = [0.0f64];
        for (j, &b) in group.bodies.iter().enumerate() {
            let nodes = rigid.bodies[b].nodes.iter();
            for &v in nodes.filter(|&&v| share.counts_node(v as usize)) {
                let r = rigid.displacement(b, &coefficients[j], mesh.node(v as usize));
                largest[0] = largest[0].max(norm(&r[..d]));
            }
        }
        share.max(&mut largest);
        if largest[0] <= 1.0 {
            continue;
        }
        for (j, &b) in group.bodies.iter().enumerate() {
            if coefficients[j].iter().all(|&x| x == 0.0) {
                continue;
            }
            for &v in &rigid.bodies[b].nodes {
                let r = rigid.displacement(b, &coefficients[j], mesh.node(v as usize));
                for i in 0..d {
                    let dof = d * v as usize + i;
                    if !system.dofs.is_fixed(dof) {
                        placed[dof] = r[i];
                    }
                }
            }
            moves.push((b, coefficients[j]));
        }
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
    let m = crate::rigid::n_modes(d);
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

/// The maximizer of `F·c` over `c ∈ ℝ^k` (k = `load.len()`) subject to `rows[i]·c ≤
/// gaps[i]` (all gaps ≥ 0) by steepest ascent on the feasible cone (module documentation),
/// from `c = 0`; if the programme is unbounded, the error is the unit direction along which
/// nothing stops the bodies. Stops after [`MAX_DROP_STEPS`] steps at the last point reached
/// (a placement need not be optimal, only feasible).
fn rest(load: &[f64], rows: &[Vec<f64>], gaps: &[f64]) -> std::result::Result<Vec<f64>, Vec<f64>> {
    let k = load.len();
    let mut c = vec![0.0; k];
    let load_norm = norm(load);
    let gap_scale = gaps.iter().fold(0.0f64, |m, &h| m.max(h));
    for _ in 0..MAX_DROP_STEPS {
        let reach = norm(&c);
        let tolerance = ROUND_OFF * gap_scale.max(reach);
        let slack: Vec<f64> = rows
            .iter()
            .zip(gaps)
            .map(|(a, &h)| h - (0..k).map(|l| a[l] * c[l]).sum::<f64>())
            .collect();
        let touching: Vec<usize> = (0..rows.len()).filter(|&i| slack[i] <= tolerance).collect();
        let columns: Vec<&[f64]> = touching.iter().map(|&i| &rows[i][..]).collect();
        let mut rho = cone_residual(load, &columns);
        let rho_norm = norm(&rho);
        if rho_norm <= ROUND_OFF * load_norm {
            return Ok(c);
        }
        // Components at round-off level would tilt an axis-aligned drop.
        for x in rho.iter_mut() {
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

/// `F − A λ` with `λ = argmin_{λ ≥ 0} ‖F − Σ_j λ_j a_j‖` over the columns `a_j` (k =
/// `load.len()` entries each): the projection of F onto the polar of their cone
/// (Lawson–Hanson non-negative least squares; at most `3k + 10` passes, the passive set
/// never exceeds k independent columns).
fn cone_residual(load: &[f64], columns: &[&[f64]]) -> Vec<f64> {
    let k = load.len();
    let n = columns.len();
    let mut lambda = vec![0.0; n];
    let mut passive = vec![false; n];
    let residual = |lambda: &[f64]| {
        let mut r = load.to_vec();
        for (j, a) in columns.iter().enumerate() {
            for l in 0..k {
                r[l] -= lambda[j] * a[l];
            }
        }
        r
    };
    let scale = norm(load);
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
            let z = least_squares(load, &set.iter().map(|&j| columns[j]).collect::<Vec<_>>());
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

/// The least-squares coefficients `z` of `F ≈ Σ_j z_j a_j` over the columns `a_j` (k =
/// `load.len()` entries each), of least norm when they are dependent.
fn least_squares(load: &[f64], columns: &[&[f64]]) -> Vec<f64> {
    let k = load.len();
    // Least norm: z = Aᵀ y with (A Aᵀ) y = F, a k × k system.
    let mut gram = vec![0.0; k * k];
    for a in columns {
        for l in 0..k {
            for m in 0..k {
                gram[l * k + m] += a[l] * a[m];
            }
        }
    }
    let y = solve_symmetric(&gram, load);
    columns
        .iter()
        .map(|a| (0..k).map(|l| a[l] * y[l]).sum())
        .collect()
}
