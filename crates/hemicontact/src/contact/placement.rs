//! How a rigid obstacle ([`super::obstacle`]) sits against its contact part, checked once
//! when a problem is built: an obstacle on the wrong side of the part is refused
//! ([`check_facing`], from [`crate::problem::Problem::validate`]); an obstacle the part's
//! mesh cannot resolve is noted ([`resolution_notes`], from
//! [`crate::problem::Problem::notes`]).
//!
//! # Facing
//!
//! The body lies outside the obstacle, and the part faces it. At contact point i (node
//! `X_i`, weight `w_i`, gap `g_i`), let `n_i` be the outward unit normal of the part at the
//! node (the measure-weighted average of the normals of the part's facets around it) and
//! `ν_i` the obstacle's outward unit normal at the node's closest point (the contact
//! normal is `−ν_i`). The **facing cosine** `c_i = ν_i·n_i` is −1 where the obstacle faces
//! the boundary head-on and +1 where it lies behind it. Over the points nearest to the
//! obstacle,
//!
//! ```text
//! S = { i : g_i ≤ min_j g_j + h̄ },     c̄ = Σ_S w_i c_i / Σ_S w_i,
//! ```
//!
//! with `h̄` the mean diameter of the part's facets, the part **faces away** from the
//! obstacle when `c̄ > 0`, and the obstacle is refused. The points of `S` are those that
//! come into contact first, or that start out inside the obstacle deepest: at the closest
//! pair of points of a smooth body and a convex obstacle the two outward normals are
//! opposite, so a body resting on an obstacle, or pressed into it (a displacement-driven
//! indentation, with negative gaps), has `c̄` near −1. Points farther away may face away
//! legitimately (a contact part around a whole round body has its far side turned away from
//! a plane below it) and are not counted. Refused: a plane whose `normal` points out of the
//! body (the body then lies inside the half-space), a paraboloid whose `axis` points into the
//! body, an obstacle inside the body. The error says on which side the body is: inside the
//! obstacle when more than half of its nodes are, else the obstacle behind the part.
//!
//! # Resolution
//!
//! Contact is enforced at the nodes only. Two notes (warnings that do not stop a run):
//!
//! - **curvature**: the obstacle's smallest radius of curvature R
//!   ([`super::obstacle::Obstacle::curvature_radius`]) is below the size h of the part's
//!   elements where the obstacle is nearest (the largest diameter of the part's facets
//!   around the point of smallest gap): the nodes cannot follow its shape.
//! - **penetration between nodes**: every point of the part is apart from the obstacle
//!   (`g_i > 0`), yet a facet of the part reaches into it. On a facet (a segment or a
//!   triangle) the obstacle's implicit function φ ([`super::obstacle::ObstacleSpec::implicit`],
//!   negative inside) is a convex quadratic; its values at the facet's vertices and edge
//!   midpoints determine it exactly (the P2 interpolant of a quadratic is the quadratic), so
//!   its minimum over the facet is found in closed form: at the stationary point if that
//!   lies inside, else on an edge. Where the minimum is negative the obstacle crosses the
//!   facet; the depth reported is the obstacle's signed distance `−g(y*)` at the minimizer
//!   `y*` (a lower bound of the deepest penetration), counted only beyond `10⁻⁹` of the
//!   mesh's size (round-off of an obstacle touching a facet).

use super::{ContactBoundary, ContactNodes};
use crate::display::significant;
use crate::error::{Error, Result};
use crate::mesh::Mesh;

/// Depth of penetration between nodes, relative to the diameter of the mesh's bounding
/// box, below which it counts as round-off of an obstacle touching a facet.
const TOUCH_TOLERANCE: f64 = 1e-9;

/// The outward unit normal of part `part` at each of its nodes: the measure-weighted
/// average of the outward normals of its facets there, as `(node, normal)` sorted by node.
pub(super) fn node_normals(mesh: &Mesh, part: usize) -> Vec<(u32, [f64; 3])> {
    let mut pairs: Vec<(u32, [f64; 3])> = mesh
        .part_facets(part)
        .flat_map(|f| {
            let (measure, n) = mesh.facet_measure_normal(f);
            mesh.facet(f)
                .iter()
                .map(move |&v| (v, n.map(|c| c * measure)))
        })
        .collect();
    pairs.sort_unstable_by_key(|p| p.0);
    pairs
        .chunk_by(|a, b| a.0 == b.0)
        .map(|run| {
            let mut n = [0.0; 3];
            for (_, m) in run {
                for k in 0..3 {
                    n[k] += m[k];
                }
            }
            let len = n.iter().map(|x| x * x).sum::<f64>().sqrt();
            if len > 0.0 {
                n = n.map(|x| x / len);
            }
            (run[0].0, n)
        })
        .collect()
}

/// The largest distance between two vertices of facet `f` (its diameter, in the mesh's
/// length unit).
pub(super) fn facet_diameter(mesh: &Mesh, f: usize) -> f64 {
    let v = mesh.facet(f);
    let mut h = 0.0f64;
    for a in 0..v.len() {
        for b in a + 1..v.len() {
            let (x, y) = (mesh.node(v[a] as usize), mesh.node(v[b] as usize));
            let d2: f64 = x.iter().zip(y).map(|(p, q)| (p - q) * (p - q)).sum();
            h = h.max(d2.sqrt());
        }
    }
    h
}

/// The contact points of boundary `b`.
pub(super) fn points_of(points: &ContactNodes, b: usize) -> Vec<usize> {
    (0..points.len())
        .filter(|&i| points.boundary[i] as usize == b)
        .collect()
}

/// Refuses an obstacle that the contact part faces away from (see the module
/// documentation): `b` is the index of the boundary `cb` in the problem, `points` the
/// problem's contact points ([`ContactNodes::new`]). Nothing is checked for a flat
/// foundation or a part without contact points.
///
/// # Errors
/// [`Error::Invalid`] with an empty field (the caller names `contact[b].obstacle`), the
/// obstacle in words as its value, and in `allowed` the side the body is on, the mean
/// facing cosine `c̄` and how the obstacle's orientation is given.
pub fn check_facing(
    mesh: &Mesh,
    b: usize,
    cb: &ContactBoundary,
    points: &ContactNodes,
) -> Result<()> {
    let Some(obstacle) = &cb.obstacle else {
        return Ok(());
    };
    let mine = points_of(points, b);
    let facets: Vec<usize> = mesh.part_facets(cb.part).collect();
    if mine.is_empty() || facets.is_empty() {
        return Ok(());
    }
    let normals = node_normals(mesh, cb.part);
    let mean_h = facets.iter().map(|&f| facet_diameter(mesh, f)).sum::<f64>() / facets.len() as f64;
    // Gaps are in units of `gap_unit`, the mesh in units of `length_unit`.
    let reach = mean_h * obstacle.length_unit / obstacle.gap_unit;
    let g_min = mine
        .iter()
        .map(|&i| points.gap[i])
        .fold(f64::INFINITY, f64::min);
    let (mut sum, mut weight) = (0.0, 0.0);
    for &i in mine.iter().filter(|&&i| points.gap[i] <= g_min + reach) {
        let Ok(k) = normals.binary_search_by_key(&points.node[i], |p| p.0) else {
            continue;
        };
        let n = normals[k].1;
        // ν_i = −(contact normal).
        let c = -(0..3).map(|a| points.normal[i][a] * n[a]).sum::<f64>();
        sum += points.weight[i] * c;
        weight += points.weight[i];
    }
    if !(weight > 0.0 && sum / weight > 0.0) {
        return Ok(());
    }
    let mean = sum / weight;
    let d = mesh.dim();
    let inside = (0..mesh.n_nodes())
        .filter(|&v| {
            let mut x = [0.0; 3];
            x[..d].copy_from_slice(mesh.node(v));
            obstacle.project(x, d).is_ok_and(|p| p.gap < 0.0)
        })
        .count();
    let n = mesh.n_nodes();
    let part = &mesh.part_names()[cb.part];
    let side = if 2 * inside > n {
        format!("the body lies inside the obstacle ({inside} of its {n} nodes are)")
    } else {
        format!(
            "the obstacle lies behind the part, on the body's side of it ({inside} of the \
             body's {n} nodes are inside the obstacle)"
        )
    };
    let hint = match obstacle.spec.shape {
        super::Obstacle::Plane { .. } => {
            "; a plane's `normal` points from the obstacle into the body (reverse it, or move \
             the plane's `point` to the other side of the body)"
        }
        super::Obstacle::Paraboloid { .. } => {
            "; a paraboloid's `axis` points from its apex into the indenter, away from the \
             body"
        }
        _ => "; a circle, sphere or cylinder must lie outside the body, in front of the part",
    };
    Err(Error::invalid(
        "",
        &obstacle.spec,
        format!(
            "an obstacle in front of contact part `{part}`, outside the body; this one is on \
             the wrong side: {side}, and the part faces away from it (at the part's nodes \
             nearest to it, the obstacle's outward normal ν and the part's outward normal n \
             point the same way: mean ν·n = {}, where an obstacle in front of the part gives \
             −1){hint}",
            significant(mean)
        ),
    ))
}

/// The notes on how well the contact part of boundary `b` (`cb`) resolves its obstacle:
/// a radius of curvature below the part's element size, and a penetration between nodes
/// while every contact point is apart (see the module documentation). Empty for a flat
/// foundation. `points` are the problem's contact points ([`ContactNodes::new`]), and
/// `carried` the translation by which the supports carry each body (DOF order, in units of
/// the gaps; [`crate::rigid::carry`]), where the part's facets meet the obstacle.
pub fn resolution_notes(
    mesh: &Mesh,
    b: usize,
    cb: &ContactBoundary,
    points: &ContactNodes,
    carried: Option<&[f64]>,
) -> Vec<String> {
    let mut notes = Vec::new();
    let Some(obstacle) = &cb.obstacle else {
        return notes;
    };
    let mine = points_of(points, b);
    let Some(&nearest) = mine
        .iter()
        .min_by(|&&i, &&j| points.gap[i].total_cmp(&points.gap[j]))
    else {
        return notes;
    };
    let d = mesh.dim();
    let unit = obstacle.length_unit;
    let part = &mesh.part_names()[cb.part];
    let facets: Vec<usize> = mesh.part_facets(cb.part).collect();
    let v = points.node[nearest];
    let h_near = facets
        .iter()
        .filter(|&&f| mesh.facet(f).contains(&v))
        .map(|&f| facet_diameter(mesh, f))
        .fold(0.0f64, f64::max)
        * unit;
    if let Some(r) = obstacle.spec.shape.curvature_radius() {
        if r < h_near {
            notes.push(format!(
                "contact[{b}] (part `{part}`): the obstacle's radius of curvature R = {} m is \
                 smaller than the part's elements where the obstacle is nearest ({} m across, \
                 at node {v}): contact is enforced at the nodes only, which cannot follow the \
                 obstacle's shape; refine the part to elements well below R",
                significant(r),
                significant(h_near)
            ));
        }
    }
    if !mine.iter().all(|&i| points.gap[i] > 0.0) {
        return notes;
    }
    let (lo, hi) = mesh.bounding_box();
    let size = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt() * unit;
    let phi = |x: [f64; 3]| {
        obstacle
            .spec
            .implicit(x.map(|c| c * unit), d)
            .unwrap_or(f64::INFINITY)
    };
    // (depth in m, point in m, facet)
    let mut deepest: Option<(f64, [f64; 3], usize)> = None;
    for &f in &facets {
        let mut p = [[0.0; 3]; 3];
        for (a, &w) in mesh.facet(f).iter().enumerate() {
            p[a][..d].copy_from_slice(mesh.node(w as usize));
            // Where a carried body meets the obstacle.
            if let Some(c) = carried {
                for k in 0..d {
                    p[a][k] += c[d * w as usize + k] * obstacle.gap_unit / unit;
                }
            }
        }
        let Some((y, value)) = facet_minimum(&p[..d], &phi) else {
            continue;
        };
        if value >= 0.0 {
            continue;
        }
        let y_m = y.map(|c| c * unit);
        let Ok(projection) = obstacle.spec.project(y_m, d) else {
            continue;
        };
        let depth = -projection.gap;
        if depth > TOUCH_TOLERANCE * size && deepest.is_none_or(|(best, _, _)| depth > best) {
            deepest = Some((depth, y_m, f));
        }
    }
    if let Some((depth, y, f)) = deepest {
        let g_min = points.gap[nearest] * obstacle.gap_unit;
        let at: Vec<String> = y[..d].iter().map(|&c| significant(c)).collect();
        notes.push(format!(
            "contact[{b}] (part `{part}`): the obstacle reaches {} m into the body between \
             the part's nodes (at [{}] m, on the facet of nodes {:?}) although every contact \
             node is apart from it (smallest gap {} m): contact is enforced at the nodes \
             only, so this penetration goes unseen; refine the part there",
            significant(depth),
            at.join(", "),
            mesh.facet(f),
            significant(g_min)
        ));
    }
    notes
}

/// The minimum of the convex quadratic `phi` over the simplex with vertices `p` (2: a
/// segment, 3: a triangle), from its values at the vertices and edge midpoints (exact for
/// a polynomial of degree ≤ 2; see the module documentation): the minimizer and the value.
/// `None` if a value is not finite.
fn facet_minimum(p: &[[f64; 3]], phi: &dyn Fn([f64; 3]) -> f64) -> Option<([f64; 3], f64)> {
    let mid = |a: [f64; 3], b: [f64; 3]| [0, 1, 2].map(|k| 0.5 * (a[k] + b[k]));
    let along = |a: [f64; 3], b: [f64; 3], t: f64| [0, 1, 2].map(|k| a[k] + t * (b[k] - a[k]));
    let values: Vec<f64> = match p.len() {
        2 => vec![phi(p[0]), phi(mid(p[0], p[1])), phi(p[1])],
        _ => vec![
            phi(p[0]),
            phi(p[1]),
            phi(p[2]),
            phi(mid(p[0], p[1])),
            phi(mid(p[0], p[2])),
            phi(mid(p[1], p[2])),
        ],
    };
    if !values.iter().all(|x| x.is_finite()) {
        return None;
    }
    if p.len() == 2 {
        let (t, value) = segment_minimum(values[0], values[1], values[2]);
        return Some((along(p[0], p[1], t), value));
    }
    let (f00, f10, f01, fs, ft, fm) = (
        values[0], values[1], values[2], values[3], values[4], values[5],
    );
    // q(s, t) = a + b s + c t + d s² + e s t + f t² with p0 + s (p1 − p0) + t (p2 − p0).
    let a = f00;
    let dd = 2.0 * (f10 - 2.0 * fs + f00);
    let b = f10 - a - dd;
    let ff = 2.0 * (f01 - 2.0 * ft + f00);
    let c = f01 - a - ff;
    let e = 4.0 * (fm - a - 0.5 * b - 0.5 * c) - dd - ff;
    let q = |s: f64, t: f64| a + b * s + c * t + dd * s * s + e * s * t + ff * t * t;
    let point = |s: f64, t: f64| {
        [0, 1, 2].map(|k| p[0][k] + s * (p[1][k] - p[0][k]) + t * (p[2][k] - p[0][k]))
    };
    let mut best: Option<((f64, f64), f64)> = None;
    let mut consider = |s: f64, t: f64| {
        let value = q(s, t);
        if best.is_none_or(|(_, v)| value < v) {
            best = Some(((s, t), value));
        }
    };
    let det = 4.0 * dd * ff - e * e;
    if det > 0.0 {
        let s = (-2.0 * b * ff + c * e) / det;
        let t = (-2.0 * c * dd + b * e) / det;
        if s >= 0.0 && t >= 0.0 && s + t <= 1.0 {
            consider(s, t);
        }
    }
    let (t01, _) = segment_minimum(f00, fs, f10);
    consider(t01, 0.0);
    let (t02, _) = segment_minimum(f00, ft, f01);
    consider(0.0, t02);
    let (t12, _) = segment_minimum(f10, fm, f01);
    consider(1.0 - t12, t12);
    best.map(|((s, t), value)| (point(s, t), value))
}

/// The minimum over `t ∈ [0, 1]` of the quadratic with values `f0`, `fm`, `f1` at 0, ½ and
/// 1: the minimizer and the value.
fn segment_minimum(f0: f64, fm: f64, f1: f64) -> (f64, f64) {
    let alpha = 2.0 * (f1 - 2.0 * fm + f0);
    let beta = f1 - f0 - alpha;
    let q = |t: f64| f0 + beta * t + alpha * t * t;
    let mut best = if f0 <= f1 { (0.0, f0) } else { (1.0, f1) };
    if alpha > 0.0 {
        let t = -beta / (2.0 * alpha);
        if t > 0.0 && t < 1.0 && q(t) < best.1 {
            best = (t, q(t));
        }
    }
    best
}
