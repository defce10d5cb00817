//! The largest eigenvalue of a Jacobi-scaled operator `D⁻¹A` (A symmetric positive
//! definite, D its diagonal) by the Lanczos method, for the upper end of a Chebyshev
//! smoother's interval.
//!
//! `D⁻¹A` is self-adjoint in the D-inner product `(x, y)_D = xᵀ D y`, so Lanczos in that
//! inner product builds, after k products, the tridiagonal `T_k = Vᵀ A V` (V D-orthonormal)
//! whose largest eigenvalue θ_k (a Ritz value) increases with k towards `λ_max` and never
//! exceeds it. It converges much faster than the power iteration, whose estimate after k
//! steps depends on the ratio of the two largest eigenvalues: on graded meshes that ratio is
//! near 1 and twelve power steps fell 10–37 % short of `λ_max`, where the smoother's
//! interval must cover the spectrum. No reorthogonalization: its loss only duplicates
//! converged Ritz values, it does not move θ_k above `λ_max`.

use super::csr::Csr;

/// Work vectors of [`largest_eigenvalue`] (three of the operator's size).
#[derive(Clone, Debug, Default)]
pub struct LanczosWork {
    v: Vec<f64>,
    v_prev: Vec<f64>,
    w: Vec<f64>,
    av: Vec<f64>,
}

/// The largest Ritz value of `D⁻¹A` after at most `steps` Lanczos steps (`inv_diag` =
/// the entries of `D⁻¹`, all positive), from a fixed non-smooth start (deterministic).
/// Returns a lower bound of `λ_max(D⁻¹A)` (up to round-off) that converges to it; `None`
/// if the iteration breaks down (a product that is not finite or not positive).
pub fn largest_eigenvalue(
    a: &Csr,
    inv_diag: &[f64],
    steps: usize,
    work: &mut LanczosWork,
) -> Option<f64> {
    let n = inv_diag.len();
    let LanczosWork { v, v_prev, w, av } = work;
    for x in [&mut *v, &mut *v_prev, &mut *w, &mut *av] {
        x.clear();
        x.resize(n, 0.0);
    }
    // Start: a fixed non-smooth vector, normalized in the D-norm.
    for (i, x) in v.iter_mut().enumerate() {
        *x = 1.0 + ((i * 7919) % 13) as f64 / 13.0;
    }
    let d_norm = |x: &[f64]| -> f64 {
        x.iter()
            .zip(inv_diag)
            .map(|(xi, di)| xi * xi / di)
            .sum::<f64>()
            .sqrt()
    };
    let norm = d_norm(v);
    if !(norm > 0.0 && norm.is_finite()) {
        return None;
    }
    v.iter_mut().for_each(|x| *x /= norm);
    let (mut alpha, mut beta) = (Vec::with_capacity(steps), Vec::with_capacity(steps));
    let mut beta_prev = 0.0;
    for _ in 0..steps.max(1) {
        a.matvec(v, av);
        // α = (D⁻¹A v, v)_D = vᵀ A v; w = D⁻¹A v − α v − β v_prev.
        let a_j: f64 = av.iter().zip(v.iter()).map(|(p, q)| p * q).sum();
        if !(a_j > 0.0 && a_j.is_finite()) {
            return None;
        }
        alpha.push(a_j);
        for i in 0..n {
            w[i] = inv_diag[i] * av[i] - a_j * v[i] - beta_prev * v_prev[i];
        }
        let b = d_norm(w);
        if !b.is_finite() {
            return None;
        }
        // An invariant subspace: T is exact.
        if b <= 1e-14 * a_j {
            break;
        }
        beta.push(b);
        std::mem::swap(v_prev, v);
        for i in 0..n {
            v[i] = w[i] / b;
        }
        beta_prev = b;
    }
    beta.truncate(alpha.len() - 1);
    Some(tridiagonal_largest(&alpha, &beta))
}

/// Largest eigenvalue of the symmetric tridiagonal matrix with diagonal `alpha` and
/// off-diagonal `beta` (`beta.len() = alpha.len() − 1`), by bisection on Sturm counts
/// between Gershgorin bounds, to round-off.
pub fn tridiagonal_largest(alpha: &[f64], beta: &[f64]) -> f64 {
    let k = alpha.len();
    let off = |i: usize| -> f64 {
        let left = if i > 0 { beta[i - 1].abs() } else { 0.0 };
        let right = if i + 1 < k { beta[i].abs() } else { 0.0 };
        left + right
    };
    let mut lo = (0..k)
        .map(|i| alpha[i] - off(i))
        .fold(f64::INFINITY, f64::min);
    let mut hi = (0..k)
        .map(|i| alpha[i] + off(i))
        .fold(f64::NEG_INFINITY, f64::max);
    // Number of eigenvalues below x: sign changes of the Sturm sequence (LDLᵀ pivots).
    let below = |x: f64| -> usize {
        let mut count = 0;
        let mut q = 1.0f64;
        for i in 0..k {
            let b2 = if i > 0 {
                beta[i - 1] * beta[i - 1]
            } else {
                0.0
            };
            q = alpha[i] - x - if i > 0 { b2 / q } else { 0.0 };
            if q == 0.0 {
                q = -f64::EPSILON * (x.abs() + 1.0);
            }
            if q < 0.0 {
                count += 1;
            }
        }
        count
    };
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if below(mid) == k {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A symmetric matrix in CSR form from its rows' `(column, value)` entries.
    fn csr(rows: &[Vec<(usize, f64)>]) -> Csr {
        let mut m = Csr {
            n_cols: rows.len(),
            ptr: vec![0],
            col: Vec::new(),
            val: Vec::new(),
        };
        for row in rows {
            for &(c, v) in row {
                m.col.push(c as u32);
                m.val.push(v);
            }
            m.ptr.push(m.col.len());
        }
        m
    }

    /// The 1D stiffness matrix of springs `k[i]` between nodes `i` and `i + 1`, both ends
    /// held: `n = k.len() − 1` unknowns.
    fn springs(k: &[f64]) -> Csr {
        let n = k.len() - 1;
        let rows: Vec<Vec<(usize, f64)>> = (0..n)
            .map(|i| {
                let mut r = Vec::new();
                if i > 0 {
                    r.push((i - 1, -k[i]));
                }
                r.push((i, k[i] + k[i + 1]));
                if i + 1 < n {
                    r.push((i + 1, -k[i + 1]));
                }
                r
            })
            .collect();
        csr(&rows)
    }

    fn inv_diag(a: &Csr) -> Vec<f64> {
        let mut d = vec![0.0; a.n_rows()];
        a.diagonal(&mut d);
        d.iter().map(|x| 1.0 / x).collect()
    }

    /// `λ_max(D⁻¹A)` of a small matrix by dense eigenvalues of `D^{-1/2} A D^{-1/2}`.
    fn dense_largest(a: &Csr) -> f64 {
        let n = a.n_rows();
        let d = inv_diag(a);
        let mut m = faer::Mat::<f64>::zeros(n, n);
        for i in 0..n {
            for (j, v) in a.row(i) {
                m[(i, j)] = v * (d[i] * d[j]).sqrt();
            }
        }
        let eig = m.self_adjoint_eigenvalues(faer::Side::Lower).unwrap();
        eig.into_iter().fold(f64::NEG_INFINITY, f64::max)
    }

    #[test]
    fn tridiagonal_largest_matches_the_closed_form_of_the_discrete_laplacian() {
        // tridiag(−1, 2, −1) of size k: eigenvalues 2 − 2 cos(jπ/(k+1)).
        for k in [1usize, 2, 5, 40] {
            let alpha = vec![2.0; k];
            let beta = vec![-1.0; k - 1];
            let exact = 2.0 - 2.0 * (k as f64 * std::f64::consts::PI / (k + 1) as f64).cos();
            let got = tridiagonal_largest(&alpha, &beta);
            assert!(
                (got - exact).abs() <= 1e-13 * exact,
                "k = {k}: {got} vs {exact}"
            );
        }
    }

    #[test]
    fn lanczos_is_exact_once_it_has_spanned_the_space() {
        // A diagonal D⁻¹A = A/diag: use a non-diagonal 6 × 6 spring chain; 6 steps span it.
        let a = springs(&[1.0, 3.0, 0.5, 2.0, 7.0, 1.0, 4.0]);
        let exact = dense_largest(&a);
        let got = largest_eigenvalue(&a, &inv_diag(&a), 6, &mut LanczosWork::default()).unwrap();
        assert!((got - exact).abs() <= 1e-12 * exact, "{got} vs {exact}");
    }

    #[test]
    fn twelve_lanczos_steps_find_the_largest_eigenvalue_of_a_graded_chain_from_below() {
        // Springs graded geometrically by 1.02 per element over 800 elements (a ratio of
        // about 8 · 10⁶ between the ends), the 1D analogue of a mesh graded towards a hole.
        let k: Vec<f64> = (0..801).map(|i| 1.02f64.powi(i)).collect();
        let a = springs(&k);
        let exact = dense_largest(&a);
        let got = largest_eigenvalue(&a, &inv_diag(&a), 12, &mut LanczosWork::default()).unwrap();
        // A Ritz value: below λ_max (to round-off), and here within 2 % of it.
        assert!(got <= exact * (1.0 + 1e-12), "{got} above λ_max = {exact}");
        assert!(got >= 0.98 * exact, "{got} short of λ_max = {exact}");
    }

    #[test]
    fn a_matrix_that_is_not_positive_breaks_down() {
        let a = csr(&[vec![(0, -1.0)]]);
        assert!(largest_eigenvalue(&a, &[1.0], 4, &mut LanczosWork::default()).is_none());
    }
}
