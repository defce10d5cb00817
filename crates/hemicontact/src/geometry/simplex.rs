//! P1 (linear Lagrange) basis on a simplex: measure and barycentric gradients.
//!
//! For a simplex with vertices `x_0 … x_d`, the Jacobian `J = [x_1 − x_0, …, x_d − x_0]`
//! maps the reference simplex onto it. The measure is `det J / d!` and the gradients of the
//! barycentric (hat) functions are the rows of `J^{-1}` for `k ≥ 1`, with
//! `∇φ_0 = −Σ_{k≥1} ∇φ_k`. Gradients are constant on the cell, so the strain of a P1 field
//! is constant per cell.

/// Measure and hat-function gradients of one simplex.
#[derive(Clone, Copy, Debug)]
pub struct SimplexGeometry {
    /// Signed measure (area in 2D, volume in 3D); positive for positively oriented cells.
    pub measure: f64,
    /// `grad[k][i] = ∂φ_k/∂x_i`, for the d + 1 vertices k (rows beyond d + 1 and columns
    /// beyond d are zero).
    pub grad: [[f64; 3]; 4],
}

/// Signed measure of the simplex with vertex coordinates `x` (d + 1 points of dimension d).
#[inline]
pub fn signed_measure(dim: usize, x: &[[f64; 3]; 4]) -> f64 {
    if dim == 2 {
        let (a, b) = (sub(&x[1], &x[0]), sub(&x[2], &x[0]));
        0.5 * (a[0] * b[1] - a[1] * b[0])
    } else {
        let (a, b, c) = (sub(&x[1], &x[0]), sub(&x[2], &x[0]), sub(&x[3], &x[0]));
        det3(&a, &b, &c) / 6.0
    }
}

/// Measure and hat-function gradients; see [`SimplexGeometry`].
///
/// The caller guarantees a non-degenerate cell (the mesh is validated on construction).
#[inline]
pub fn geometry(dim: usize, x: &[[f64; 3]; 4]) -> SimplexGeometry {
    let mut grad = [[0.0; 3]; 4];
    if dim == 2 {
        let (a, b) = (sub(&x[1], &x[0]), sub(&x[2], &x[0]));
        let det = a[0] * b[1] - a[1] * b[0];
        let inv = 1.0 / det;
        // J = [[a0, b0], [a1, b1]]; J^{-1} = [[b1, -b0], [-a1, a0]] / det.
        grad[1] = [b[1] * inv, -b[0] * inv, 0.0];
        grad[2] = [-a[1] * inv, a[0] * inv, 0.0];
        grad[0] = [-grad[1][0] - grad[2][0], -grad[1][1] - grad[2][1], 0.0];
        SimplexGeometry {
            measure: 0.5 * det,
            grad,
        }
    } else {
        let (a, b, c) = (sub(&x[1], &x[0]), sub(&x[2], &x[0]), sub(&x[3], &x[0]));
        let det = det3(&a, &b, &c);
        let inv = 1.0 / det;
        // Rows of J^{-1} are the cross products of the other two edge vectors over det.
        grad[1] = scale(&cross(&b, &c), inv);
        grad[2] = scale(&cross(&c, &a), inv);
        grad[3] = scale(&cross(&a, &b), inv);
        for i in 0..3 {
            grad[0][i] = -grad[1][i] - grad[2][i] - grad[3][i];
        }
        SimplexGeometry {
            measure: det / 6.0,
            grad,
        }
    }
}

#[inline]
fn sub(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline]
fn scale(a: &[f64; 3], s: f64) -> [f64; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// Cross product `a × b`.
#[inline]
pub fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline]
fn det3(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3]) -> f64 {
    let bc = cross(b, c);
    a[0] * bc[0] + a[1] * bc[1] + a[2] * bc[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The gradients reproduce every linear field exactly: Σ_k f(x_k) ∇φ_k = ∇f.
    #[test]
    fn gradients_reproduce_linear_fields() {
        let tri = [[0.3, 0.1, 0.0], [2.0, 0.4, 0.0], [0.7, 1.9, 0.0], [0.0; 3]];
        let tet = [
            [0.1, 0.2, 0.0],
            [1.5, 0.1, 0.3],
            [0.2, 1.3, 0.1],
            [0.4, 0.3, 1.7],
        ];
        for (dim, x) in [(2, tri), (3, tet)] {
            let g = geometry(dim, &x);
            assert!(g.measure > 0.0);
            assert!((g.measure - signed_measure(dim, &x)).abs() < 1e-14);
            let slope = [1.3, -0.7, 2.2];
            let f = |p: &[f64; 3]| 0.5 + (0..dim).map(|i| slope[i] * p[i]).sum::<f64>();
            for i in 0..dim {
                let gi: f64 = (0..=dim).map(|k| f(&x[k]) * g.grad[k][i]).sum();
                assert!((gi - slope[i]).abs() < 1e-13, "dim {dim} comp {i}: {gi}");
            }
        }
    }
}
