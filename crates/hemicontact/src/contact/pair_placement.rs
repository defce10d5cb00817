//! How the master part of a contact pair ([`super::pairing`]) sits against its slave part,
//! checked once when a problem is built ([`check`], from
//! [`crate::problem::Problem::validate`]), as [`super::placement`] checks an obstacle.
//!
//! A pair is refused when
//!
//! - **it has no contact point**: every node of the slave part is held by a support, is a
//!   node of the master part too, or lies beyond the edge of the master surface, so the
//!   pair could never act;
//! - **the master part faces away from the slave part**: at point i let `n_i` be the slave
//!   part's outward unit normal at the node (the measure-weighted average of its facets'
//!   normals there) and `ν_i` the pair's normal, from the slave node towards the master
//!   surface (the master facet's outward normal is `−ν_i`). The facing cosine
//!   `c_i = −ν_i·n_i` is −1 where the two faces are turned to each other and +1 where they
//!   point the same way (the slave part paired with the far face of the other body). Over
//!   the points nearest to the master surface,
//!
//!   ```text
//!   S = { i : g_i ≤ min_j g_j + h̄ },     c̄ = Σ_S w_i c_i / Σ_S w_i,
//!   ```
//!
//!   with `h̄` the mean diameter of the slave part's facets, the pair is refused when
//!   `c̄ > 0`, as an obstacle is;
//! - **the master surface lies inside the slave's body**: the master part is a face of the
//!   slave's own body (its far face: the two outward normals are then opposite, as for a
//!   proper pair), or of a body meshed through it. With `ν̄` the weighted mean of the
//!   normals over S and `T` the extent of the slave node's body along `ν̄` (the largest
//!   minus the smallest `x·ν̄` over its nodes), the pair is refused when the points of S
//!   start, on their weighted mean, deeper than `T/2` behind the master surface
//!   (`Σ_S w_i g_i / Σ_S w_i < −T/2`): the master surface is then nearer the body's far
//!   side than the slave part. An initial interference (a shrink fit meshed with its
//!   overlap, a negative gap small against the bodies) is accepted.

use super::placement::{facet_diameter, node_normals, points_of};
use super::{ContactBoundary, ContactNodes};
use crate::display::significant;
use crate::error::{Error, Result};
use crate::mesh::Mesh;

/// Refuses the pair of boundary `b` (`cb`, with a master part) when it has no contact
/// point, when its master part faces away from the slave part, or when the master surface
/// lies inside the slave's body (see the module documentation). `points` are the problem's
/// contact points ([`ContactNodes::new`]) and `body_of` the body of each mesh node
/// ([`crate::rigid::bodies`]). Nothing is checked for a boundary without a master
/// part.
///
/// # Errors
/// [`Error::Invalid`] with an empty field (the caller names `contact[b].against`), the two
/// parts as its value, and in `allowed` what is wrong, with the facing cosine `c̄` or the
/// depth and the slave body's extent (m).
pub fn check(
    mesh: &Mesh,
    b: usize,
    cb: &ContactBoundary,
    points: &ContactNodes,
    body_of: &[u32],
) -> Result<()> {
    let Some(master) = &cb.against else {
        return Ok(());
    };
    let names = mesh.part_names();
    let (slave_name, master_name) = (&names[cb.part], &names[master.part]);
    let value = format!("`{slave_name}` against `{master_name}`");
    let mine = points_of(points, b);
    if mine.is_empty() {
        return Err(Error::invalid(
            "",
            value,
            format!(
                "a pair with contact points; no node of the slave part `{slave_name}` faces \
                 the master part `{master_name}`: each is held by a support, is a node of the \
                 master part too, or lies beyond the edge of the master surface (where it can \
                 never touch it under small deformation), so the pair could never act. Check \
                 that `against` names the face of the other body that the slave part touches, \
                 and that the two faces overlap"
            ),
        ));
    }
    let facets: Vec<usize> = mesh.part_facets(cb.part).collect();
    let normals = node_normals(mesh, cb.part);
    let mean_h = facets.iter().map(|&f| facet_diameter(mesh, f)).sum::<f64>() / facets.len() as f64;
    // Gaps are in units of `gap_unit`, the mesh in units of `length_unit`.
    let to_length = master.gap_unit / master.length_unit;
    let g_min = mine
        .iter()
        .map(|&i| points.gap[i])
        .fold(f64::INFINITY, f64::min);
    let nearest: Vec<usize> = mine
        .iter()
        .copied()
        .filter(|&i| points.gap[i] * to_length <= g_min * to_length + mean_h)
        .collect();
    let (mut cos, mut gap, mut weight) = (0.0, 0.0, 0.0);
    let mut mean_normal = [0.0; 3];
    for &i in &nearest {
        let w = points.weight[i];
        if let Ok(k) = normals.binary_search_by_key(&points.node[i], |p| p.0) {
            let n = normals[k].1;
            cos -= w * (0..3).map(|a| points.normal[i][a] * n[a]).sum::<f64>();
        }
        gap += w * points.gap[i] * to_length;
        weight += w;
        for a in 0..3 {
            mean_normal[a] += w * points.normal[i][a];
        }
    }
    if weight <= 0.0 {
        return Ok(());
    }
    let (cos, gap) = (cos / weight, gap / weight);
    if cos > 0.0 {
        return Err(Error::invalid(
            "",
            value,
            format!(
                "a master part that faces the slave part; `{master_name}` faces away from \
                 `{slave_name}`: at the slave part's nodes nearest to it, the master facets' \
                 outward normal and the slave part's outward normal point the same way (mean \
                 cosine {}, where two faces turned to each other give −1), at a mean distance \
                 of {} m. Name in `against` the face of the other body that the slave part \
                 touches",
                significant(cos),
                significant(gap.abs())
            ),
        ));
    }
    let len = mean_normal.iter().map(|x| x * x).sum::<f64>().sqrt();
    if len <= 0.0 || gap >= 0.0 {
        return Ok(());
    }
    let axis = mean_normal.map(|x| x / len);
    let d = mesh.dim();
    let body = body_of[points.node[nearest[0]] as usize];
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in (0..mesh.n_nodes()).filter(|&v| body_of[v] == body) {
        let x: f64 = (0..d).map(|k| mesh.node(v)[k] * axis[k]).sum();
        lo = lo.min(x);
        hi = hi.max(x);
    }
    let extent = hi - lo;
    if -gap > 0.5 * extent {
        return Err(Error::invalid(
            "",
            value,
            format!(
                "a master part in front of the slave part; `{master_name}` lies inside the \
                 body of `{slave_name}`: the slave part's nodes nearest to it start {} m \
                 behind it (mean), more than half the extent of their body along the contact \
                 normal ({} m), as if `against` named a face of the slave's own body or of a \
                 body meshed through it. Name in `against` the face of the other body that \
                 the slave part touches",
                significant(-gap),
                significant(extent)
            ),
        ));
    }
    Ok(())
}
