//! How the deformed-mesh figure scales what it draws: the displacement magnification,
//! which contact points get a traction arrow and how long the arrows are, the size of the
//! contact markers, whether the mesh is fine enough to draw edge by edge, and the boundary
//! as chains of edges (for dashed lines that run on around corners).

use super::interface::{along, traction_floor};
use super::layout::round_down_125;
use crate::mesh::Mesh;
use crate::problem::Problem;
use crate::solver::{NormalState, Solution};

/// The displacement magnification: the largest `m · 10^k` (m ∈ {1, 2, 5}) not above
/// `0.1 · size / max_u`, at least 1 (displacements are never shrunk); 1 when nothing moves.
/// `size` is the body's largest extent and `max_u` its largest displacement (m).
pub fn magnification(size: f64, max_u: f64) -> f64 {
    if !(max_u > 0.0 && size > 0.0 && max_u.is_finite()) {
        return 1.0;
    }
    round_down_125(0.1 * size / max_u).max(1.0)
}

/// The contact points that get an arrow: per contact boundary, of its points in contact
/// at a `visible` node (a flag per mesh node), at most `cap` evenly spaced along it, and in
/// 2D no more than one per `min_gap` (m) of the stretch they cover. Returns a flag per
/// contact point.
pub fn arrow_points(
    problem: &Problem,
    solution: &Solution,
    visible: &[bool],
    cap: usize,
    min_gap: f64,
) -> Vec<bool> {
    let touching = |k: &usize| {
        let c = &solution.contact[*k];
        c.normal_state == NormalState::Contact && visible.get(c.node as usize) == Some(&true)
    };
    let mut chosen = vec![false; solution.contact.len()];
    for b in 0..problem.contact.len() {
        let (rows, cap) = if problem.mesh.dim() == 2 {
            let al = along(problem, solution, b);
            let (rows, s): (Vec<usize>, Vec<f64>) = al
                .rows
                .iter()
                .zip(&al.s)
                .filter(|(k, _)| touching(k))
                .map(|(k, s)| (*k, *s))
                .unzip();
            let stretch = s.last().copied().unwrap_or(0.0) - s.first().copied().unwrap_or(0.0);
            let room = if min_gap > 0.0 {
                (stretch / min_gap).floor() as usize + 1
            } else {
                cap
            };
            (rows, cap.min(room))
        } else {
            let rows = (0..solution.contact.len())
                .filter(|&k| solution.contact[k].boundary == b)
                .filter(touching)
                .collect();
            (rows, cap)
        };
        for k in thin(rows.len(), cap) {
            chosen[rows[k]] = true;
        }
    }
    chosen
}

/// Indices of `cap` of `n` items evenly spaced from the first to the last (all if n ≤ cap).
pub fn thin(n: usize, cap: usize) -> Vec<usize> {
    if n <= cap {
        return (0..n).collect();
    }
    if cap <= 1 {
        return vec![0; cap.min(n)];
    }
    let mut out: Vec<usize> = (0..cap)
        .map(|k| ((k * (n - 1)) as f64 / (cap - 1) as f64).round() as usize)
        .collect();
    out.dedup();
    out
}

/// The largest traction magnitude ‖R_i‖/w_i (Pa) over touching points, 0 if below the
/// round-off floor of equilibrium ([`traction_floor`]).
pub fn max_traction(solution: &Solution) -> f64 {
    let norm = |f: &[f64; 3]| (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
    let max = solution
        .contact
        .iter()
        .filter(|c| c.normal_state == NormalState::Contact && c.weight > 0.0)
        .map(|c| norm(&c.force) / c.weight)
        .fold(0.0, f64::max);
    if max <= traction_floor(solution) {
        0.0
    } else {
        max
    }
}

/// The smallest mean distance (m) between neighbouring contact points of a contact part
/// (2D; infinity in 3D, whose markers keep their size).
pub fn contact_spacing(problem: &Problem, solution: &Solution) -> f64 {
    if problem.mesh.dim() != 2 {
        return f64::INFINITY;
    }
    (0..problem.contact.len())
        .map(|b| along(problem, solution, b))
        .filter(|al| al.s.len() > 1)
        .map(|al| (al.s[al.s.len() - 1] - al.s[0]) / (al.s.len() - 1) as f64)
        .fold(f64::INFINITY, f64::min)
}

/// Whether a mesh is drawn edge by edge: when its typical cell edge, `√(2 |Ω| / cells)` in
/// 2D, is at least 5 px at `scale` px/m (3D meshes, drawn by their front facets only, are
/// always drawn).
pub fn mesh_drawn(mesh: &Mesh, scale: f64, d: usize) -> bool {
    d != 2
        || mesh.n_cells() == 0
        || scale * (2.0 * mesh.measure() / mesh.n_cells() as f64).sqrt() >= 5.0
}

/// The boundary of a 2D mesh as chains of nodes along its edges (a closed loop ends with
/// its first node again), so that a dashed line runs on around corners.
pub fn chains(mesh: &Mesh) -> Vec<Vec<u32>> {
    let mut nbrs: std::collections::BTreeMap<u32, Vec<u32>> = Default::default();
    for f in 0..mesh.n_facets() {
        let v = mesh.facet(f);
        nbrs.entry(v[0]).or_default().push(v[1]);
        nbrs.entry(v[1]).or_default().push(v[0]);
    }
    let mut used = std::collections::HashSet::new();
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    let mut out = Vec::new();
    // Open chains from their ends first, then the closed loops.
    let mut starts: Vec<u32> = nbrs
        .iter()
        .filter(|(_, m)| m.len() != 2)
        .map(|(n, _)| *n)
        .collect();
    starts.extend(nbrs.keys().copied());
    for s in starts {
        while let Some(&next) = nbrs[&s].iter().find(|&&m| !used.contains(&key(s, m))) {
            used.insert(key(s, next));
            let mut chain = vec![s, next];
            loop {
                let last = chain[chain.len() - 1];
                match nbrs[&last].iter().find(|&&m| !used.contains(&key(last, m))) {
                    Some(&m) => {
                        used.insert(key(last, m));
                        chain.push(m);
                    }
                    None => break,
                }
            }
            out.push(chain);
        }
    }
    out
}
