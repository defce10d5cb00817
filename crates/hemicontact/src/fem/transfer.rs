//! P1 interpolation of a field from one mesh onto the nodes of another.
//!
//! For every target node the source cell containing it is found with a uniform bucket grid
//! over the source cells' bounding boxes, and the field is evaluated there with the
//! barycentric coordinates (exact for nested meshes, where the source P1 field is itself a
//! P1 field on the target mesh). Target nodes outside the source mesh (curved or
//! non-matching boundaries) take the value at the nearest cell's closest barycentric point
//! (the barycentric coordinates clamped to the simplex), which is the natural extension.

use crate::geometry::simplex;
use crate::mesh::Mesh;

/// Interpolates the vector field `u` (`d` components per source node, DOF order) from
/// `source` onto the nodes of `target`; returns the field on `target` in DOF order.
///
/// # Panics
/// If the meshes have different dimensions or `u` has the wrong length.
#[track_caller]
pub fn interpolate(source: &Mesh, u: &[f64], target: &Mesh) -> Vec<f64> {
    let d = source.dim();
    assert_eq!(d, target.dim());
    assert_eq!(u.len(), d * source.n_nodes());
    let grid = BucketGrid::new(source);
    let mut out = vec![0.0; d * target.n_nodes()];
    let mut last = 0usize;
    for n in 0..target.n_nodes() {
        let mut x = [0.0; 3];
        x[..d].copy_from_slice(target.node(n));
        // Neighbouring target nodes usually fall into the same source cell: try it first.
        let (cell, lambda) = match barycentric_inside(source, last, &x) {
            Some(l) => (last, l),
            None => grid.locate(source, &x),
        };
        last = cell;
        for (a, &v) in source.cell(cell).iter().enumerate() {
            for i in 0..d {
                out[d * n + i] += lambda[a] * u[d * v as usize + i];
            }
        }
    }
    out
}

/// Barycentric coordinates of `x` in cell `c`.
fn barycentric(mesh: &Mesh, c: usize, x: &[f64; 3]) -> [f64; 4] {
    let d = mesh.dim();
    let p = mesh.cell_coords(c);
    let geo = simplex::geometry(d, &p);
    let mut l = [0.0; 4];
    for a in 0..=d {
        // λ_a(x) = λ_a(x_b) + ∇λ_a · (x − x_b) for a vertex b ≠ a (λ_a(x_b) = 0).
        let b = if a == 0 { 1 } else { 0 };
        l[a] = (0..d).map(|i| geo.grad[a][i] * (x[i] - p[b][i])).sum();
    }
    l
}

fn barycentric_inside(mesh: &Mesh, c: usize, x: &[f64; 3]) -> Option<[f64; 4]> {
    let l = barycentric(mesh, c, x);
    let tol = 1e-10;
    if l[..=mesh.dim()].iter().all(|&v| v >= -tol) {
        Some(l)
    } else {
        None
    }
}

/// A uniform grid of buckets listing the cells whose bounding boxes overlap them.
struct BucketGrid {
    lo: [f64; 3],
    size: [f64; 3],
    n: [usize; 3],
    start: Vec<usize>,
    cells: Vec<u32>,
}

impl BucketGrid {
    fn new(mesh: &Mesh) -> Self {
        let d = mesh.dim();
        let (lo, hi) = mesh.bounding_box();
        // About one cell per bucket.
        let per_axis = (mesh.n_cells() as f64).powf(1.0 / d as f64).ceil().max(1.0) as usize;
        let mut n = [1usize; 3];
        let mut size = [1.0; 3];
        for i in 0..d {
            n[i] = per_axis;
            size[i] = ((hi[i] - lo[i]) / per_axis as f64).max(f64::MIN_POSITIVE);
        }
        let index = |b: [usize; 3]| (b[2] * n[1] + b[1]) * n[0] + b[0];
        let total = n[0] * n[1] * n[2];
        let range = |c: usize| {
            let p = mesh.cell_coords(c);
            let mut bl = [0usize; 3];
            let mut bh = [0usize; 3];
            for i in 0..d {
                let (mut a, mut b) = (f64::INFINITY, f64::NEG_INFINITY);
                for v in p.iter().take(d + 1) {
                    a = a.min(v[i]);
                    b = b.max(v[i]);
                }
                bl[i] = (((a - lo[i]) / size[i]).floor().max(0.0) as usize).min(n[i] - 1);
                bh[i] = (((b - lo[i]) / size[i]).floor().max(0.0) as usize).min(n[i] - 1);
            }
            (bl, bh)
        };
        let mut count = vec![0usize; total + 1];
        let visit = |c: usize, f: &mut dyn FnMut(usize)| {
            let (bl, bh) = range(c);
            for k in bl[2]..=bh[2] {
                for j in bl[1]..=bh[1] {
                    for i in bl[0]..=bh[0] {
                        f(index([i, j, k]));
                    }
                }
            }
        };
        for c in 0..mesh.n_cells() {
            visit(c, &mut |b| count[b + 1] += 1);
        }
        for b in 0..total {
            count[b + 1] += count[b];
        }
        let start = count.clone();
        let mut fill = count;
        let mut cells = vec![0u32; start[total]];
        for c in 0..mesh.n_cells() {
            visit(c, &mut |b| {
                cells[fill[b]] = c as u32;
                fill[b] += 1;
            });
        }
        BucketGrid {
            lo,
            size,
            n,
            start,
            cells,
        }
    }

    /// The cell containing `x` with its barycentric coordinates; for a point outside the
    /// mesh, the cell whose clamped barycentric point is closest.
    fn locate(&self, mesh: &Mesh, x: &[f64; 3]) -> (usize, [f64; 4]) {
        let d = mesh.dim();
        let mut b = [0usize; 3];
        for i in 0..d {
            b[i] =
                (((x[i] - self.lo[i]) / self.size[i]).floor().max(0.0) as usize).min(self.n[i] - 1);
        }
        let bucket = (b[2] * self.n[1] + b[1]) * self.n[0] + b[0];
        for &c in &self.cells[self.start[bucket]..self.start[bucket + 1]] {
            if let Some(l) = barycentric_inside(mesh, c as usize, x) {
                return (c as usize, l);
            }
        }
        // Outside the mesh (or in a gap of a non-matching boundary): the closest cell.
        let mut best = (0usize, [0.0; 4], f64::INFINITY);
        for c in 0..mesh.n_cells() {
            let mut l = barycentric(mesh, c, x);
            let outside: f64 = l[..=d].iter().map(|v| v.min(0.0).powi(2)).sum();
            if outside < best.2 {
                for v in l[..=d].iter_mut() {
                    *v = v.max(0.0);
                }
                let s: f64 = l[..=d].iter().sum();
                for v in l[..=d].iter_mut() {
                    *v /= s;
                }
                best = (c, l, outside);
            }
        }
        (best.0, best.1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate::{rectangle, CutPattern, Rectangle};

    fn mesh(n: usize, pattern: CutPattern) -> Mesh {
        rectangle(&Rectangle {
            origin: [0.0, 0.0],
            size: [2.0, 1.0],
            n: [2 * n, n],
            pattern,
            progression: [1.0; 2],
        })
        .unwrap()
    }

    /// An affine field is a P1 field on every mesh: interpolation reproduces it exactly,
    /// onto nested and non-nested meshes alike.
    #[test]
    fn affine_fields_are_transferred_exactly() {
        let f = |x: &[f64]| {
            [
                0.3 + 1.2 * x[0] - 0.4 * x[1],
                -0.1 + 0.5 * x[0] + 2.0 * x[1],
            ]
        };
        let coarse = mesh(3, CutPattern::Uniform);
        let u: Vec<f64> = (0..coarse.n_nodes())
            .flat_map(|n| f(coarse.node(n)))
            .collect();
        for target in [mesh(6, CutPattern::Uniform), mesh(5, CutPattern::Symmetric)] {
            let v = interpolate(&coarse, &u, &target);
            for n in 0..target.n_nodes() {
                let e = f(target.node(n));
                assert!((v[2 * n] - e[0]).abs() < 1e-12 && (v[2 * n + 1] - e[1]).abs() < 1e-12);
            }
        }
    }

    /// On nested meshes the coarse P1 field is reproduced at the fine nodes: the coarse
    /// nodal values come back unchanged at coinciding nodes, for any (non-affine) field.
    #[test]
    fn nested_transfer_keeps_nodal_values() {
        let coarse = mesh(4, CutPattern::Symmetric);
        let fine = mesh(8, CutPattern::Symmetric);
        let u: Vec<f64> = (0..2 * coarse.n_nodes())
            .map(|k| ((k * 37) % 11) as f64)
            .collect();
        let v = interpolate(&coarse, &u, &fine);
        for n in 0..coarse.n_nodes() {
            let x = coarse.node(n);
            let m = (0..fine.n_nodes()).find(|&m| fine.node(m) == x).unwrap();
            assert!(
                (v[2 * m] - u[2 * n]).abs() < 1e-12 && (v[2 * m + 1] - u[2 * n + 1]).abs() < 1e-12
            );
        }
    }
}
