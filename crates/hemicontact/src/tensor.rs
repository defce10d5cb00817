//! Symmetric second-order tensors in Mandel notation.
//!
//! Strain and stress are symmetric d×d tensors (d = 2 or 3). They are stored as Mandel
//! vectors, in which the Euclidean inner product of two vectors equals the tensor double
//! contraction `a : b`, so norms, gradients and tangents need no engineering-shear factors:
//!
//! | d | length | components |
//! |---|--------|------------|
//! | 2 | 3 | `[a_xx, a_yy, √2 a_xy]` |
//! | 3 | 6 | `[a_xx, a_yy, a_zz, √2 a_yz, √2 a_xz, √2 a_xy]` |
//!
//! The first `d` components are always the diagonal, so `tr a = Σ_{k<d} c[k]`.
//! A fourth-order tangent `∂σ/∂ε` is a [`Tangent`], an `n × n` block (n = 3 or 6) of a
//! 6 × 6 array, again in Mandel notation (so it is symmetric for hyperelastic laws).

/// √2, the Mandel factor of off-diagonal components.
pub const SQRT2: f64 = std::f64::consts::SQRT_2;

/// A symmetric d×d tensor (d = 2 or 3) in Mandel notation; see the module documentation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sym {
    /// Spatial dimension d (2 or 3).
    pub dim: usize,
    /// Mandel components; only the first [`Sym::len`] are meaningful, the rest are zero.
    pub c: [f64; 6],
}

/// Fourth-order tangent `∂σ/∂ε` in Mandel notation: the leading `n × n` block is used,
/// with n = 3 (d = 2) or 6 (d = 3).
pub type Tangent = [[f64; 6]; 6];

/// Number of Mandel components of a symmetric d×d tensor: 3 for d = 2, 6 for d = 3.
#[inline]
pub const fn mandel_len(dim: usize) -> usize {
    if dim == 2 {
        3
    } else {
        6
    }
}

impl Sym {
    /// The zero tensor of dimension `dim`.
    #[inline]
    pub fn zero(dim: usize) -> Self {
        Self { dim, c: [0.0; 6] }
    }

    /// The identity tensor of dimension `dim`.
    #[inline]
    pub fn identity(dim: usize) -> Self {
        let mut c = [0.0; 6];
        c[..dim].fill(1.0);
        Self { dim, c }
    }

    /// Builds the tensor from a full d×d matrix `m[i][j]` (only the upper triangle is read).
    pub fn from_matrix(dim: usize, m: &[[f64; 3]; 3]) -> Self {
        let mut c = [0.0; 6];
        for (k, ck) in c.iter_mut().enumerate().take(dim) {
            *ck = m[k][k];
        }
        if dim == 2 {
            c[2] = SQRT2 * m[0][1];
        } else {
            c[3] = SQRT2 * m[1][2];
            c[4] = SQRT2 * m[0][2];
            c[5] = SQRT2 * m[0][1];
        }
        Self { dim, c }
    }

    /// The full 3×3 matrix of the tensor (for d = 2 the third row and column are zero).
    pub fn to_matrix(&self) -> [[f64; 3]; 3] {
        let mut m = [[0.0; 3]; 3];
        for k in 0..self.dim {
            m[k][k] = self.c[k];
        }
        let s = 1.0 / SQRT2;
        if self.dim == 2 {
            m[0][1] = s * self.c[2];
            m[1][0] = m[0][1];
        } else {
            m[1][2] = s * self.c[3];
            m[2][1] = m[1][2];
            m[0][2] = s * self.c[4];
            m[2][0] = m[0][2];
            m[0][1] = s * self.c[5];
            m[1][0] = m[0][1];
        }
        m
    }

    /// Number of Mandel components (3 or 6).
    #[inline]
    pub fn len(&self) -> usize {
        mandel_len(self.dim)
    }

    /// Always false: a tensor has at least three components. Present for API symmetry.
    #[inline]
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Trace `tr a = Σ_k a_kk`.
    #[inline]
    pub fn trace(&self) -> f64 {
        self.c[..self.dim].iter().sum()
    }

    /// Double contraction `a : b`.
    #[inline]
    pub fn dot(&self, other: &Sym) -> f64 {
        self.c.iter().zip(other.c.iter()).map(|(a, b)| a * b).sum()
    }

    /// Frobenius norm `‖a‖ = (a : a)^{1/2}`.
    #[inline]
    pub fn norm(&self) -> f64 {
        self.dot(self).sqrt()
    }

    /// Deviator `a^D = a − (tr a / d) I`.
    #[inline]
    pub fn deviator(&self) -> Sym {
        let m = self.trace() / self.dim as f64;
        let mut out = *self;
        for ck in out.c[..self.dim].iter_mut() {
            *ck -= m;
        }
        out
    }

    /// `self * s`.
    #[inline]
    pub fn scaled(&self, s: f64) -> Sym {
        let mut out = *self;
        for ck in out.c.iter_mut() {
            *ck *= s;
        }
        out
    }

    /// `self + s * other`.
    #[inline]
    pub fn add_scaled(&self, s: f64, other: &Sym) -> Sym {
        let mut out = *self;
        for (a, b) in out.c.iter_mut().zip(other.c.iter()) {
            *a += s * b;
        }
        out
    }

    /// The full 3×3 matrix of the tensor with out-of-plane normal component `zz` (for
    /// d = 2: `[[a_xx, a_xy, 0], [a_xy, a_yy, 0], [0, 0, zz]]`; for d = 3 `zz` is ignored
    /// and this is [`Sym::to_matrix`]).
    pub fn to_matrix_with_zz(&self, zz: f64) -> [[f64; 3]; 3] {
        let mut m = self.to_matrix();
        if self.dim == 2 {
            m[2][2] = zz;
        }
        m
    }
}

/// Von Mises equivalent of a full 3×3 symmetric tensor `m`: `√(3/2 s:s)` with
/// `s = m − (tr m / 3) I` its three-dimensional deviator (the unit of `m`, Pa for a stress).
pub fn von_mises(m: &[[f64; 3]; 3]) -> f64 {
    let mean = (m[0][0] + m[1][1] + m[2][2]) / 3.0;
    let mut ss = 0.0;
    for (i, row) in m.iter().enumerate() {
        for (j, &v) in row.iter().enumerate() {
            let s = if i == j { v - mean } else { v };
            ss += s * s;
        }
    }
    (1.5 * ss).sqrt()
}

/// The zero tangent.
#[inline]
pub fn zero_tangent() -> Tangent {
    [[0.0; 6]; 6]
}

/// Adds `s · a ⊗ b` to the tangent `t`.
#[inline]
pub fn add_outer(t: &mut Tangent, s: f64, a: &Sym, b: &Sym) {
    let n = a.len();
    for i in 0..n {
        let ai = s * a.c[i];
        for j in 0..n {
            t[i][j] += ai * b.c[j];
        }
    }
}

/// Adds `s · 𝕀` (the fourth-order identity on symmetric tensors) to the tangent `t`.
#[inline]
pub fn add_identity(t: &mut Tangent, dim: usize, s: f64) {
    for (i, row) in t.iter_mut().enumerate().take(mandel_len(dim)) {
        row[i] += s;
    }
}

/// Applies the tangent: returns `t : a`.
#[inline]
pub fn apply(t: &Tangent, a: &Sym) -> Sym {
    let n = a.len();
    let mut out = Sym::zero(a.dim);
    for i in 0..n {
        out.c[i] = (0..n).map(|j| t[i][j] * a.c[j]).sum();
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mandel_dot_is_double_contraction() {
        let m = [[1.0, 2.0, 3.0], [2.0, 5.0, 6.0], [3.0, 6.0, 9.0]];
        let a = Sym::from_matrix(3, &m);
        let full: f64 = m.iter().flatten().map(|x| x * x).sum();
        assert!((a.dot(&a) - full).abs() < 1e-12);
        assert_eq!(a.to_matrix(), m);
        let b = Sym::from_matrix(2, &m);
        assert!((b.dot(&b) - (1.0 + 4.0 + 4.0 + 25.0)).abs() < 1e-12);
        assert!((b.deviator().trace()).abs() < 1e-15);
    }
}
