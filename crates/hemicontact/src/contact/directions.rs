//! The directions of a contact boundary at a node: its facets grouped by direction where
//! the boundary turns a corner, the lumped weight and averaged normal of each group, and
//! the tangent basis of a normal ([`super::nodes`] makes the contact points from them).
//!
//! Two facets around a node are in the same group when their normals differ by at most
//! [`CORNER_ANGLE_DEG`] (30°), and groups are closed under this relation (single linkage):
//! one group on a smooth boundary, one per face at a corner. Why 30° is in
//! [`super::nodes`] (*Corners*).

use crate::geometry::simplex::cross;

/// Angle between facet normals above which one contact boundary is split at a node into
/// one contact point per direction (degrees); see [`super::nodes`] (*Corners*).
pub const CORNER_ANGLE_DEG: f64 = 30.0;

/// The facets `around` a node ((node, facet) pairs; `facets` the measures and outward
/// normals of the part's facets) grouped by direction (see the module documentation): the
/// lumped weight `Σ |F| / d` and the averaged unit normal of each group, in the order of
/// each group's first facet. `group` is scratch space (the group of each facet).
pub(super) fn direction_groups(
    around: &[(u32, u32)],
    facets: &[(f64, [f64; 3])],
    d: usize,
    group: &mut Vec<usize>,
) -> Vec<(f64, [f64; 3])> {
    let cos_corner = CORNER_ANGLE_DEG.to_radians().cos();
    let normal = |k: usize| &facets[around[k].1 as usize].1;
    group.clear();
    group.resize(around.len(), usize::MAX);
    let mut n_groups = 0;
    let mut stack = Vec::new();
    for seed in 0..around.len() {
        if group[seed] != usize::MAX {
            continue;
        }
        group[seed] = n_groups;
        stack.push(seed);
        while let Some(k) = stack.pop() {
            for m in 0..around.len() {
                let cos: f64 = (0..3).map(|i| normal(k)[i] * normal(m)[i]).sum();
                if group[m] == usize::MAX && cos >= cos_corner {
                    group[m] = n_groups;
                    stack.push(m);
                }
            }
        }
        n_groups += 1;
    }
    (0..n_groups)
        .map(|g| {
            let mut w = 0.0;
            let mut n = [0.0; 3];
            for (&(_, f), _) in around.iter().zip(group.iter()).filter(|(_, &k)| k == g) {
                let (measure, nf) = &facets[f as usize];
                w += measure / d as f64;
                for i in 0..3 {
                    n[i] += measure * nf[i];
                }
            }
            let len = n.iter().map(|x| x * x).sum::<f64>().sqrt();
            (w, n.map(|x| x / len))
        })
        .collect()
}

/// The lumped weight `Σ |F| / d` of a node over all its facets `around` ((node, facet)
/// pairs; `facets` the measures and normals of the part's facets).
pub(super) fn lumped_weight(around: &[(u32, u32)], facets: &[(f64, [f64; 3])], d: usize) -> f64 {
    around
        .iter()
        .map(|&(_, f)| facets[f as usize].0)
        .sum::<f64>()
        / d as f64
}

/// Orthonormal tangent basis of the unit normal `n`: 2D, `τ = (−ν_y, ν_x)` (counter-clockwise
/// along the boundary); 3D, `τ₁ = e × ν / ‖e × ν‖` with `e` the axis least aligned with ν,
/// `τ₂ = ν × τ₁`.
pub fn tangent_basis(dim: usize, n: &[f64; 3]) -> [[f64; 3]; 2] {
    if dim == 2 {
        return [[-n[1], n[0], 0.0], [0.0; 3]];
    }
    let k = (0..3)
        .min_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
        .unwrap_or(0);
    let mut e = [0.0; 3];
    e[k] = 1.0;
    let mut t1 = cross(&e, n);
    let len = t1.iter().map(|x| x * x).sum::<f64>().sqrt();
    for x in t1.iter_mut() {
        *x /= len;
    }
    let t2 = cross(n, &t1);
    [t1, t2]
}
