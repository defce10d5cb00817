//! Preconditioned conjugate gradients, the one implementation shared by every linear
//! solver of the crate: the direct solver's reuse path (preconditioned by a stale Cholesky
//! factor) and multigrid-preconditioned CG.
//!
//! For `A x = b` with `A` symmetric positive definite and a symmetric positive definite
//! preconditioner `M⁻¹`: from `x₀`, `r₀ = b − A x₀`, `z₀ = M⁻¹ r₀`, `p₀ = z₀`, iterate
//! `α = rᵀz / pᵀAp`, `x += α p`, `r −= α Ap`, `z = M⁻¹ r`, `β = r_newᵀz_new / rᵀz`,
//! `p = z + β p`, until `‖r‖ ≤ tol ‖b‖` (tested as [`Stop`] says) or the iteration cap.
//! The callers differ only in the start vector ([`Start`]) and in how the stopping test is
//! evaluated in floating point ([`Stop`]); both are parameters so that each caller keeps
//! its exact operations.

/// The matrix and the preconditioner of a PCG solve.
pub trait PcgOperator {
    /// `y = A x`.
    fn matvec(&mut self, x: &[f64], y: &mut [f64]);
    /// `z = M⁻¹ r`, the preconditioner applied to the residual `r`.
    fn precondition(&mut self, r: &[f64], z: &mut [f64]);
}

/// The start vector of PCG.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Start {
    /// `x₀ = 0`, so `r₀ = b` (multigrid-preconditioned CG).
    Zero,
    /// `x₀ = M⁻¹ b`, `r₀ = b − A x₀` (a preconditioner that is an old factor of a nearby
    /// matrix, for which `M⁻¹ b` is already a good approximation).
    Preconditioned,
}

/// How the stopping test `‖r‖ ≤ tol ‖b‖` is evaluated (the two forms can differ in the
/// last bit of the comparison).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// `‖r‖ ≤ tol · ‖b‖`.
    Scaled,
    /// `‖r‖ / ‖b‖ ≤ tol`.
    Relative,
}

/// Parameters of one PCG solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pcg {
    /// Relative residual to reach (dimensionless).
    pub tol: f64,
    /// Iteration cap.
    pub max_iter: usize,
    /// Start vector.
    pub start: Start,
    /// Form of the stopping test.
    pub stop: Stop,
}

/// Result of a PCG solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PcgOutcome {
    /// Iterations done.
    pub iterations: usize,
    /// Final relative residual `‖b − A x‖ / ‖b‖` (recursively updated).
    pub relative_residual: f64,
    /// Whether the tolerance was reached.
    pub converged: bool,
    /// The iteration and the curvature `pᵀAp` (not positive, or not finite) at which PCG
    /// broke down, if it did.
    pub breakdown: Option<(usize, f64)>,
}

/// Work vectors of PCG (residual, preconditioned residual, direction, product), sized on
/// first use and reused afterwards (no allocation in later solves of the same size).
#[derive(Clone, Debug, Default)]
pub struct PcgWork {
    r: Vec<f64>,
    z: Vec<f64>,
    p: Vec<f64>,
    ap: Vec<f64>,
}

impl PcgWork {
    /// Work vectors for systems of `n` equations.
    pub fn new(n: usize) -> Self {
        PcgWork {
            r: vec![0.0; n],
            z: vec![0.0; n],
            p: vec![0.0; n],
            ap: vec![0.0; n],
        }
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>()
}

/// Solves `A x = b` by preconditioned conjugate gradients (see the module documentation)
/// with the operator and preconditioner of `op`. `b = 0` gives `x = 0`, converged in 0
/// iterations. A curvature `pᵀAp` that is not positive and finite stops the iteration
/// (reported in [`PcgOutcome::breakdown`], not converged).
///
/// # Panics
/// If `x` and `b` differ in length.
#[track_caller]
pub fn pcg(
    op: &mut impl PcgOperator,
    b: &[f64],
    x: &mut [f64],
    work: &mut PcgWork,
    params: &Pcg,
) -> PcgOutcome {
    let n = b.len();
    assert_eq!(x.len(), n);
    let PcgWork { r, z, p, ap } = work;
    for v in [&mut *r, &mut *z, &mut *p, &mut *ap] {
        v.resize(n, 0.0);
    }
    let mut outcome = PcgOutcome {
        iterations: 0,
        relative_residual: 0.0,
        converged: true,
        breakdown: None,
    };
    let b_norm = dot(b, b).sqrt();
    if b_norm == 0.0 {
        x.fill(0.0);
        return outcome;
    }
    match params.start {
        Start::Zero => {
            x.fill(0.0);
            r.copy_from_slice(b);
        }
        Start::Preconditioned => {
            op.precondition(b, x);
            op.matvec(x, ap);
            for i in 0..n {
                r[i] = b[i] - ap[i];
            }
        }
    }
    op.precondition(r, z);
    p.copy_from_slice(z);
    let mut rz = dot(r, z);
    outcome.converged = false;
    outcome.relative_residual = 1.0;
    for k in 1..=params.max_iter {
        op.matvec(p, ap);
        let pap = dot(p, ap);
        if !(pap > 0.0 && pap.is_finite()) {
            outcome.breakdown = Some((k, pap));
            return outcome;
        }
        let alpha = rz / pap;
        for i in 0..n {
            x[i] += alpha * p[i];
            r[i] -= alpha * ap[i];
        }
        let r_norm = dot(r, r).sqrt();
        outcome.iterations = k;
        outcome.relative_residual = r_norm / b_norm;
        outcome.converged = match params.stop {
            Stop::Scaled => r_norm <= params.tol * b_norm,
            Stop::Relative => outcome.relative_residual <= params.tol,
        };
        if outcome.converged {
            return outcome;
        }
        op.precondition(r, z);
        let rz_next = dot(r, z);
        let beta = rz_next / rz;
        rz = rz_next;
        for i in 0..n {
            p[i] = z[i] + beta * p[i];
        }
    }
    outcome
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The 1D Laplacian tridiag(−1, 2, −1) with the Jacobi preconditioner.
    struct Laplacian;

    impl PcgOperator for Laplacian {
        fn matvec(&mut self, x: &[f64], y: &mut [f64]) {
            let n = x.len();
            for i in 0..n {
                let left = if i > 0 { x[i - 1] } else { 0.0 };
                let right = if i + 1 < n { x[i + 1] } else { 0.0 };
                y[i] = 2.0 * x[i] - left - right;
            }
        }
        fn precondition(&mut self, r: &[f64], z: &mut [f64]) {
            for (z, r) in z.iter_mut().zip(r) {
                *z = 0.5 * r;
            }
        }
    }

    /// CG in exact arithmetic ends in at most n iterations; for the Laplacian with
    /// `b = (1, …, 1)` the solution is `x_i = (i + 1)(n − i) / 2`.
    #[test]
    fn solves_the_laplacian_in_n_iterations() {
        let n = 20;
        let b = vec![1.0; n];
        for start in [Start::Zero, Start::Preconditioned] {
            for stop in [Stop::Scaled, Stop::Relative] {
                let mut x = vec![0.0; n];
                let params = Pcg {
                    tol: 1e-12,
                    max_iter: n,
                    start,
                    stop,
                };
                let out = pcg(&mut Laplacian, &b, &mut x, &mut PcgWork::default(), &params);
                assert!(out.converged && out.iterations <= n, "{out:?}");
                for (i, xi) in x.iter().enumerate() {
                    let exact = ((i + 1) * (n - i)) as f64 / 2.0;
                    assert!(
                        (xi - exact).abs() <= 1e-9 * exact,
                        "x[{i}] = {xi} vs {exact}"
                    );
                }
            }
        }
    }

    /// A zero right-hand side gives x = 0 without iterating; a negative definite operator
    /// breaks down in the first iteration.
    #[test]
    fn zero_rhs_and_breakdown() {
        let params = Pcg {
            tol: 1e-8,
            max_iter: 10,
            start: Start::Zero,
            stop: Stop::Relative,
        };
        let mut x = vec![3.0; 4];
        let out = pcg(
            &mut Laplacian,
            &[0.0; 4],
            &mut x,
            &mut PcgWork::new(4),
            &params,
        );
        assert!(out.converged && out.iterations == 0 && x == [0.0; 4]);

        struct Negative;
        impl PcgOperator for Negative {
            fn matvec(&mut self, x: &[f64], y: &mut [f64]) {
                for (y, x) in y.iter_mut().zip(x) {
                    *y = -x;
                }
            }
            fn precondition(&mut self, r: &[f64], z: &mut [f64]) {
                z.copy_from_slice(r);
            }
        }
        let out = pcg(
            &mut Negative,
            &[1.0; 4],
            &mut x,
            &mut PcgWork::new(4),
            &params,
        );
        assert!(!out.converged);
        assert_eq!(out.breakdown, Some((1, -4.0)));
    }
}
