//! Geometric multigrid on virtual Q1 grids: a symmetric positive definite preconditioner
//! for conjugate gradients on the reduced system `H x = b` of any P1 mesh.
//!
//! **Hierarchy.** Level 0 is the system itself (free equations of the mesh). The coarse
//! levels are regular grids of trilinear (bilinear in 2D) Q1 "virtual" nodes covering the
//! mesh's bounding box: level 1 has spacing ≈ 2h, with h the typical edge length
//! `(|Ω| / #cells)^{1/d} · c_d` (`c_3 = 6^{1/3}`, `c_2 = √2`: the edge of the cube or square
//! that a Kuhn subdivision splits into 6 tetrahedra or 2 triangles), and every further level
//! doubles the spacing (`⌈m/2⌉` intervals per direction). The prolongation `P_l` interpolates
//! the coarse Q1 function at the points of level `l` (the mesh nodes for `l = 0`, the grid
//! nodes above), each displacement component separately (block structure `I_d`). A coarse
//! component that interpolates to no free DOF of the finer level is dropped, so the
//! Dirichlet elimination carries over. Q1 interpolation reproduces linear fields, so rigid
//! translations and (linearized) rotations are represented on every level.
//!
//! **Operators.** Galerkin products `A_{l+1} = P_lᵀ A_l P_l`, computed with two
//! row-by-row (Gustavson) sparse products `B = A P`, `Pᵀ B` whenever the Hessian changes
//! ([`Multigrid::update`]); the coarsest level (at most [`COARSE_MAX`] equations) is
//! factorized by a dense Cholesky.
//!
//! **Smoother.** Chebyshev iteration of degree [`CHEBYSHEV_DEGREE`] on the Jacobi-scaled
//! operator `D⁻¹A`, targeting the interval `[λ̂/SMOOTHING_RANGE, λ̂]` with `λ̂` 1.1 times
//! the largest eigenvalue estimated by [`LANCZOS_STEPS`] Lanczos steps
//! ([`super::lanczos`]; twelve power steps fell 10–37 % short on graded meshes). Chosen over
//! Gauss–Seidel because it needs only matrix–vector products, which run in parallel and in
//! the same order on every run (deterministic), and because a fixed polynomial `p(D⁻¹A)D⁻¹`
//! is a symmetric smoother, so that the V-cycle with the same pre- and post-smoothing is a
//! symmetric positive definite preconditioner (its error propagation
//! `(I − SA)(I − P A_c⁻¹ Pᵀ A)(I − SA)` is A-self-adjoint with spectrum in `[0, 1)` when the
//! smoother converges, which the eigenvalue margin ensures). Jacobi scaling also absorbs the
//! large diagonal entries of stiff contact penalties.
//!
//! **Use.** [`Multigrid::new`] builds the grids and prolongations once per mesh and DOF
//! map; [`Multigrid::update`] refills the operators from new Hessian values on the same
//! [`SystemPattern`] ([`Multigrid::update_fine`] only the fine one); [`Multigrid::solve`]
//! runs preconditioned conjugate gradients ([`super::pcg`]).

use super::csr::multiply;
pub use super::csr::Csr;
use super::lanczos::{largest_eigenvalue, LanczosWork};
pub use super::pcg::PcgOutcome;
use super::pcg::{pcg, Pcg, PcgOperator, PcgWork, Start, Stop};
use crate::assembly::SystemPattern;
use crate::error::{Error, Result};
use crate::fem::dofs::FIXED;
use crate::mesh::Mesh;
use faer::linalg::solvers::Solve;

/// Largest number of equations of the coarsest level, which is solved by dense Cholesky.
pub const COARSE_MAX: usize = 1500;
/// Degree of the Chebyshev smoother (matrix–vector products per smoothing sweep, plus one
/// for the residual of a nonzero start).
pub const CHEBYSHEV_DEGREE: usize = 3;
/// Ratio of the upper to the lower end of the Chebyshev smoothing interval.
pub const SMOOTHING_RANGE: f64 = 15.0;
/// Lanczos steps estimating the largest eigenvalue of `D⁻¹A` per level.
pub const LANCZOS_STEPS: usize = 12;
/// Safety factor on the estimated largest eigenvalue (a Ritz value, which lies below it).
pub const EIGENVALUE_SAFETY: f64 = 1.1;

/// A regular grid of Q1 nodes: `m[a]` intervals of width `h[a]` from `lo[a]` along each of
/// the first `dim` axes. Node `(i, j, k)` has index `i + (m₀+1)(j + (m₁+1) k)`.
#[derive(Clone, Copy, Debug)]
struct Grid {
    dim: usize,
    lo: [f64; 3],
    h: [f64; 3],
    m: [usize; 3],
}

impl Grid {
    /// Nodes per axis (1 on unused axes).
    fn nodes_per_axis(&self) -> [usize; 3] {
        let mut n = [1; 3];
        for (a, n) in n.iter_mut().enumerate().take(self.dim) {
            *n = self.m[a] + 1;
        }
        n
    }

    /// Number of nodes.
    fn n_nodes(&self) -> usize {
        self.nodes_per_axis().iter().product()
    }

    /// Node coordinates, `dim` per node.
    fn coords(&self) -> Vec<f64> {
        let n = self.nodes_per_axis();
        let mut out = Vec::with_capacity(self.n_nodes() * self.dim);
        for k in 0..n[2] {
            for j in 0..n[1] {
                for i in 0..n[0] {
                    let idx = [i, j, k];
                    for a in 0..self.dim {
                        out.push(self.lo[a] + idx[a] as f64 * self.h[a]);
                    }
                }
            }
        }
        out
    }

    /// The grid with twice the spacing and `⌈m/2⌉` intervals per axis.
    fn coarsen(&self) -> Grid {
        let mut g = *self;
        for a in 0..self.dim {
            g.m[a] = self.m[a].div_ceil(2).max(1);
            g.h[a] = 2.0 * self.h[a];
        }
        g
    }

    /// Q1 interpolation weights at point `x` into `out` (`(node, weight)`, nonzero weights
    /// only); returns their number. Points outside the grid are clamped to its cells.
    fn weights(&self, x: &[f64], out: &mut [(usize, f64); 8]) -> usize {
        let n = self.nodes_per_axis();
        let mut base = [0usize; 3];
        let mut f = [0.0f64; 3];
        for a in 0..self.dim {
            let t = (x[a] - self.lo[a]) / self.h[a];
            let i = (t.floor().max(0.0) as usize).min(self.m[a] - 1);
            let mut s = (t - i as f64).clamp(0.0, 1.0);
            // Snap round-off so that nodes on grid lines get exact weights 0 and 1.
            if s < 1e-10 {
                s = 0.0;
            } else if s > 1.0 - 1e-10 {
                s = 1.0;
            }
            base[a] = i;
            f[a] = s;
        }
        let mut count = 0;
        for corner in 0..(1usize << self.dim) {
            let mut w = 1.0;
            let mut idx = [0usize; 3];
            for a in 0..self.dim {
                let bit = (corner >> a) & 1;
                w *= if bit == 1 { f[a] } else { 1.0 - f[a] };
                idx[a] = base[a] + bit;
            }
            if w != 0.0 {
                out[count] = (idx[0] + n[0] * (idx[1] + n[1] * idx[2]), w);
                count += 1;
            }
        }
        count
    }
}

/// The prolongation from `grid` to the points `coords` (`dim` per point) whose DOFs have
/// the equation numbers `fine_eq` (DOF `d·point + component`, [`FIXED`] if none): returns
/// `P` (rows: fine equations, columns: kept coarse equations) and the coarse equation
/// numbers of the grid's DOFs.
fn prolongation(coords: &[f64], fine_eq: &[u32], grid: &Grid) -> (Csr, Vec<u32>) {
    let d = grid.dim;
    let n_points = fine_eq.len() / d;
    let mut coarse_eq = vec![FIXED; d * grid.n_nodes()];
    let mut w = [(0usize, 0.0f64); 8];
    // Pass 1: which coarse DOFs receive a free fine DOF.
    for p in 0..n_points {
        let count = grid.weights(&coords[d * p..d * p + d], &mut w);
        for i in 0..d {
            if fine_eq[d * p + i] != FIXED {
                for &(node, _) in &w[..count] {
                    coarse_eq[d * node + i] = 0;
                }
            }
        }
    }
    let mut n_coarse = 0u32;
    for e in coarse_eq.iter_mut().filter(|e| **e != FIXED) {
        *e = n_coarse;
        n_coarse += 1;
    }
    // Pass 2: rows in fine equation order (equations increase with the DOF index).
    let mut ptr = vec![0usize];
    let mut col = Vec::new();
    let mut val = Vec::new();
    for p in 0..n_points {
        let count = grid.weights(&coords[d * p..d * p + d], &mut w);
        for i in 0..d {
            if fine_eq[d * p + i] == FIXED {
                continue;
            }
            for &(node, weight) in &w[..count] {
                col.push(coarse_eq[d * node + i]);
                val.push(weight);
            }
            ptr.push(col.len());
        }
    }
    (
        Csr {
            n_cols: n_coarse as usize,
            ptr,
            col,
            val,
        },
        coarse_eq,
    )
}

/// One level of the hierarchy: its operator, the prolongation from the next coarser level,
/// the smoother data and work vectors.
#[derive(Debug)]
struct Level {
    /// Operator `A_l`.
    a: Csr,
    /// Prolongation from level `l + 1` (empty on the coarsest level).
    p: Csr,
    /// Its transpose (restriction).
    pt: Csr,
    /// Inverse diagonal of `A_l`.
    inv_diag: Vec<f64>,
    /// Upper end of the Chebyshev interval.
    lambda: f64,
    /// Work vectors of the eigenvalue estimate.
    lanczos: LanczosWork,
    /// Right-hand side, iterate, residual, correction, product.
    b: Vec<f64>,
    x: Vec<f64>,
    r: Vec<f64>,
    d: Vec<f64>,
    t: Vec<f64>,
}

impl Level {
    fn new(a: Csr, p: Csr) -> Self {
        let n = a.n_rows();
        let pt = p.transpose();
        Level {
            a,
            p,
            pt,
            inv_diag: vec![0.0; n],
            lambda: 1.0,
            lanczos: LanczosWork::default(),
            b: vec![0.0; n],
            x: vec![0.0; n],
            r: vec![0.0; n],
            d: vec![0.0; n],
            t: vec![0.0; n],
        }
    }

    /// Jacobi scaling and the Chebyshev interval from the current operator values.
    fn prepare_smoother(&mut self) -> Result<()> {
        self.jacobi()?;
        // Lanczos on D⁻¹A from a fixed, non-smooth start (deterministic).
        let lambda = largest_eigenvalue(&self.a, &self.inv_diag, LANCZOS_STEPS, &mut self.lanczos)
            .filter(|l| *l > 0.0 && l.is_finite())
            .ok_or_else(|| {
                Error::Breakdown("multigrid: eigenvalue estimate of the smoother failed".into())
            })?;
        self.lambda = EIGENVALUE_SAFETY * lambda;
        Ok(())
    }

    /// The Jacobi scaling `D⁻¹` from the current operator values.
    fn jacobi(&mut self) -> Result<()> {
        self.a.diagonal(&mut self.inv_diag);
        for v in self.inv_diag.iter_mut() {
            if !(*v > 0.0 && v.is_finite()) {
                return Err(Error::NotPositiveDefinite {
                    context: "multigrid: nonpositive diagonal entry".into(),
                });
            }
            *v = 1.0 / *v;
        }
        Ok(())
    }

    /// Chebyshev smoothing of `A x = b` from the current `x` (`zero`: x = 0, saving a
    /// product), `CHEBYSHEV_DEGREE` steps on the interval `[λ/SMOOTHING_RANGE, λ]` of
    /// `D⁻¹A`.
    fn smooth(&mut self, zero: bool) {
        let n = self.b.len();
        if zero {
            self.x.fill(0.0);
            self.r.copy_from_slice(&self.b);
        } else {
            self.a.matvec(&self.x, &mut self.t);
            for i in 0..n {
                self.r[i] = self.b[i] - self.t[i];
            }
        }
        let upper = self.lambda;
        let lower = upper / SMOOTHING_RANGE;
        let theta = 0.5 * (upper + lower);
        let delta = 0.5 * (upper - lower);
        let sigma = theta / delta;
        let mut rho = 1.0 / sigma;
        for i in 0..n {
            self.d[i] = self.inv_diag[i] * self.r[i] / theta;
        }
        for k in 1..=CHEBYSHEV_DEGREE {
            for i in 0..n {
                self.x[i] += self.d[i];
            }
            if k == CHEBYSHEV_DEGREE {
                break;
            }
            self.a.matvec(&self.d, &mut self.t);
            let rho_next = 1.0 / (2.0 * sigma - rho);
            let (c1, c2) = (rho_next * rho, 2.0 * rho_next / delta);
            for i in 0..n {
                self.r[i] -= self.t[i];
                self.d[i] = c1 * self.d[i] + c2 * self.inv_diag[i] * self.r[i];
            }
            rho = rho_next;
        }
    }

    /// `r = b − A x`.
    fn residual(&mut self) {
        self.a.matvec(&self.x, &mut self.t);
        for i in 0..self.b.len() {
            self.r[i] = self.b[i] - self.t[i];
        }
    }
}

/// The multigrid hierarchy of a mesh and DOF map; see the module documentation.
pub struct Multigrid {
    /// Levels, finest first; the last one is solved directly.
    levels: Vec<Level>,
    /// For each entry of the fine operator (full CSR), its slot in the upper-triangular
    /// value array of the [`SystemPattern`].
    fine_slots: Vec<u32>,
    /// Dense Cholesky factor of the coarsest operator.
    coarse: Option<faer::linalg::solvers::Llt<f64>>,
    /// PCG work vectors.
    work: PcgWork,
}

impl std::fmt::Debug for Multigrid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Multigrid")
            .field("level_sizes", &self.level_sizes())
            .finish()
    }
}

/// The full (both triangles) CSR structure of the symmetric matrix on `pattern`, with the
/// upper-triangle slot of every entry.
fn fine_structure(pattern: &SystemPattern) -> (Csr, Vec<u32>) {
    let n = pattern.n();
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    let mut ptr = vec![0usize; n + 1];
    for j in 0..n {
        for &i in &ri[cp[j]..cp[j + 1]] {
            ptr[j + 1] += 1;
            if i != j {
                ptr[i + 1] += 1;
            }
        }
    }
    for j in 0..n {
        ptr[j + 1] += ptr[j];
    }
    let mut next = ptr.clone();
    let nnz = ptr[n];
    let mut col = vec![0u32; nnz];
    let mut slots = vec![0u32; nnz];
    // Column j of the upper triangle lists row j's entries left of and on the diagonal, in
    // increasing order; entries right of the diagonal come from later columns, also in
    // increasing order: every row ends up sorted.
    for j in 0..n {
        for (k, &i) in ri.iter().enumerate().take(cp[j + 1]).skip(cp[j]) {
            col[next[j]] = i as u32;
            slots[next[j]] = k as u32;
            next[j] += 1;
        }
        for k in cp[j]..cp[j + 1] {
            let i = ri[k];
            if i != j {
                col[next[i]] = j as u32;
                slots[next[i]] = k as u32;
                next[i] += 1;
            }
        }
    }
    (
        Csr {
            n_cols: n,
            ptr,
            col,
            val: vec![0.0; nnz],
        },
        slots,
    )
}

/// The first coarse grid of `mesh`: its bounding box with spacing ≈ 2h.
fn first_grid(mesh: &Mesh) -> Grid {
    let d = mesh.dim();
    let (lo, hi) = mesh.bounding_box();
    let c = if d == 3 { 6f64.cbrt() } else { 2f64.sqrt() };
    let cells = mesh.n_cells().max(1) as f64;
    let h = (mesh.measure() / cells).powf(1.0 / d as f64) * c;
    let mut g = Grid {
        dim: d,
        lo,
        h: [1.0; 3],
        m: [0; 3],
    };
    for a in 0..d {
        let len = hi[a] - lo[a];
        let m = if h > 0.0 && len > 0.0 {
            ((len / (2.0 * h)).round() as usize).max(1)
        } else {
            1
        };
        g.m[a] = m;
        g.h[a] = if len > 0.0 { len / m as f64 } else { 1.0 };
    }
    g
}

impl Multigrid {
    /// Builds the grids and prolongations for `mesh` with equation numbers `equations`
    /// (see [`crate::fem::dofs::DofMap::equations`]) and the system pattern `pattern`.
    /// The operators are filled by [`Multigrid::update`].
    pub fn new(mesh: &Mesh, equations: &[u32], pattern: &SystemPattern) -> Self {
        let (a0, fine_slots) = fine_structure(pattern);
        let mut levels = Vec::new();
        let mut a = a0;
        let mut coords = mesh.coords().to_vec();
        let mut eq = equations.to_vec();
        let mut grid = first_grid(mesh);
        while a.n_rows() > COARSE_MAX && levels.len() < 30 {
            let (p, coarse_eq) = prolongation(&coords, &eq, &grid);
            if p.n_cols() == 0 || p.n_cols() as f64 > 0.8 * a.n_rows() as f64 {
                break;
            }
            let next = Csr {
                n_cols: p.n_cols(),
                ptr: vec![0; p.n_cols() + 1],
                col: Vec::new(),
                val: Vec::new(),
            };
            levels.push(Level::new(a, p));
            a = next;
            coords = grid.coords();
            eq = coarse_eq;
            grid = grid.coarsen();
        }
        levels.push(Level::new(a, Csr::default()));
        let n0 = levels[0].b.len();
        Multigrid {
            levels,
            fine_slots,
            coarse: None,
            work: PcgWork::new(n0),
        }
    }

    /// Number of equations per level, finest first.
    pub fn level_sizes(&self) -> Vec<usize> {
        self.levels.iter().map(|l| l.b.len()).collect()
    }

    /// Stored entries of all operators and prolongations (a memory measure).
    pub fn nnz(&self) -> usize {
        self.levels.iter().map(|l| l.a.nnz() + 2 * l.p.nnz()).sum()
    }

    /// The fine operator (full CSR) with the values of the last [`Multigrid::update`].
    pub fn operator(&self) -> &Csr {
        &self.levels[0].a
    }

    /// Refills every level from the upper-triangle values `hess` on the pattern given to
    /// [`Multigrid::new`]: fine operator, Galerkin coarse operators, smoother intervals,
    /// and the dense Cholesky factor of the coarsest operator.
    ///
    /// # Errors
    /// [`Error::NotPositiveDefinite`] if a diagonal entry is not positive or the coarsest
    /// operator cannot be factorized; [`Error::Breakdown`] on non-finite values.
    pub fn update(&mut self, hess: &[f64]) -> Result<()> {
        let a0 = &mut self.levels[0].a;
        for (v, &s) in a0.val.iter_mut().zip(&self.fine_slots) {
            *v = hess[s as usize];
        }
        for l in 0..self.levels.len() - 1 {
            let (lo, hi) = self.levels.split_at_mut(l + 1);
            let fine = &lo[l];
            let ap = multiply(&fine.a, &fine.p);
            hi[0].a = multiply(&fine.pt, &ap);
        }
        let last = self.levels.len() - 1;
        for level in &mut self.levels[..last] {
            level.prepare_smoother()?;
        }
        self.coarse = Some(coarse_factor(&self.levels[last].a)?);
        Ok(())
    }

    /// The lagged set-up: refills the fine operator from the upper-triangle values `hess`
    /// and its Jacobi scaling, keeping the Chebyshev interval, the coarse operators and the
    /// coarsest factor of the last [`Multigrid::update`]. The V-cycle then smooths the
    /// current matrix and corrects with the coarse levels of an earlier one: still
    /// symmetric, and a good preconditioner while the matrix changed little (contact nodes
    /// and locked cells between Newton steps), for the price of one pass over the fine
    /// operator instead of the Galerkin products and eigenvalue estimates. It is no longer
    /// guaranteed to be positive definite (a new stiff term may lift the top of the
    /// spectrum of `D⁻¹A` above the smoothing interval): its caller
    /// ([`super::MultigridCg`]) caps the iterations and sets up fully when they run out.
    /// Keeping the interval was measured against a new Lanczos estimate: the same PCG
    /// iterations on `paper3d.toml` (n = 24) and its graded variant (n = 32), 2 % more on
    /// the frictional Hertz problem (n = 32), for a third of the lagged set-up's time.
    ///
    /// # Errors
    /// As [`Multigrid::update`]; and [`Error::Breakdown`] if there was no update before.
    pub fn update_fine(&mut self, hess: &[f64]) -> Result<()> {
        if self.coarse.is_none() {
            return Err(Error::Breakdown(
                "multigrid: lagged set-up before the first set-up".into(),
            ));
        }
        let last = self.levels.len() - 1;
        let a0 = &mut self.levels[0].a;
        for (v, &s) in a0.val.iter_mut().zip(&self.fine_slots) {
            *v = hess[s as usize];
        }
        if last > 0 {
            self.levels[0].jacobi()?;
        } else {
            self.coarse = Some(coarse_factor(&self.levels[0].a)?);
        }
        Ok(())
    }

    /// One V-cycle: `z = M⁻¹ r` (symmetric positive definite in `r`).
    ///
    /// Before the first [`Multigrid::update`] there are no operators: then `z = r`.
    ///
    /// # Panics
    /// If the lengths do not match the fine level.
    #[track_caller]
    pub fn apply(&mut self, r: &[f64], z: &mut [f64]) {
        let last = self.levels.len() - 1;
        let Some(llt) = self.coarse.as_ref() else {
            z.copy_from_slice(r);
            return;
        };
        self.levels[0].b.copy_from_slice(r);
        for l in 0..last {
            let (lo, hi) = self.levels.split_at_mut(l + 1);
            let level = &mut lo[l];
            level.smooth(true);
            level.residual();
            level.pt.matvec(&level.r, &mut hi[0].b);
        }
        {
            let c = &mut self.levels[last];
            c.x.copy_from_slice(&c.b);
            let n = c.x.len();
            llt.solve_in_place(faer::MatMut::from_column_major_slice_mut(&mut c.x, n, 1));
        }
        for l in (0..last).rev() {
            let (lo, hi) = self.levels.split_at_mut(l + 1);
            let level = &mut lo[l];
            level.p.matvec(&hi[0].x, &mut level.t);
            for (x, t) in level.x.iter_mut().zip(&level.t) {
                *x += t;
            }
            level.smooth(false);
        }
        z.copy_from_slice(&self.levels[0].x);
    }

    /// Preconditioned conjugate gradients ([`super::pcg`]) on the fine operator with the
    /// V-cycle, from `x = 0`, to the relative residual `tol` (tested as `‖r‖/‖b‖ ≤ tol`)
    /// within `max_iter` iterations.
    ///
    /// # Errors
    /// [`Error::Breakdown`] if a curvature `pᵀAp` is not positive or not finite.
    pub fn solve(
        &mut self,
        b: &[f64],
        x: &mut [f64],
        tol: f64,
        max_iter: usize,
    ) -> Result<PcgOutcome> {
        let mut work = std::mem::take(&mut self.work);
        let params = Pcg {
            tol,
            max_iter,
            start: Start::Zero,
            stop: Stop::Relative,
        };
        let outcome = pcg(self, b, x, &mut work, &params);
        self.work = work;
        if let Some((k, pap)) = outcome.breakdown {
            return Err(Error::Breakdown(format!(
                "multigrid-preconditioned CG: curvature pᵀAp = {pap:e} in iteration {k}"
            )));
        }
        Ok(outcome)
    }
}

/// The fine operator preconditioned by one V-cycle.
impl PcgOperator for Multigrid {
    fn matvec(&mut self, x: &[f64], y: &mut [f64]) {
        self.levels[0].a.matvec(x, y);
    }
    fn precondition(&mut self, r: &[f64], z: &mut [f64]) {
        Multigrid::apply(self, r, z);
    }
}

/// Dense Cholesky factor of the coarsest operator `a`. A coarse operator is singular when
/// its grid resolves more than its finer level (e.g. few fine nodes in a coarse cell); then
/// a diagonal shift of 1e-10 of the largest diagonal entry keeps the V-cycle positive
/// definite.
fn coarse_factor(a: &Csr) -> Result<faer::linalg::solvers::Llt<f64>> {
    let n = a.n_rows();
    let mut m = faer::Mat::<f64>::zeros(n, n);
    let mut max_diag = 0.0f64;
    for i in 0..n {
        for (j, v) in a.row(i) {
            m[(i, j)] += v;
            if i == j {
                max_diag = max_diag.max(v);
            }
        }
    }
    if let Ok(llt) = m.llt(faer::Side::Lower) {
        return Ok(llt);
    }
    for i in 0..n {
        m[(i, i)] += 1e-10 * max_diag;
    }
    m.llt(faer::Side::Lower)
        .map_err(|e| Error::NotPositiveDefinite {
            context: format!("multigrid coarsest operator ({n} equations): {e:?}"),
        })
}
