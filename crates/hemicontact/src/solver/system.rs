//! The discrete system, prepared once per problem: DOF map, sparsity pattern, symbolic
//! factorization, external forces, and the work arrays of the Newton iteration.

use crate::assembly::global::Want;
use crate::assembly::{BulkAssembler, SystemPattern};
use crate::error::Result;
use crate::fem::dofs::DofMap;
use crate::linalg::Cholesky;
use crate::problem::Problem;
use std::time::Instant;

/// Everything that depends only on the mesh and the boundary-condition *pattern*.
#[derive(Debug)]
pub struct System {
    /// DOF map (Dirichlet DOFs eliminated).
    pub dofs: DofMap,
    /// Upper-triangular pattern of the reduced system.
    pub pattern: SystemPattern,
    /// Cholesky factorization (symbolic analysis done).
    pub cholesky: Cholesky,
    /// External force vector (N), DOF order.
    pub f_ext: Vec<f64>,
    /// Gradient of the total energy at the last evaluation, DOF order.
    pub grad: Vec<f64>,
    /// Hessian values at the last evaluation with a Hessian (upper triangle).
    pub hess: Vec<f64>,
    /// Seconds spent on (pattern, symbolic analysis).
    pub setup_time: (f64, f64),
}

impl System {
    /// Builds the DOF map and pattern, and runs the symbolic analysis.
    ///
    /// # Errors
    /// [`crate::Error::OutOfMemory`] if the pattern or factor cannot be allocated.
    pub fn new(problem: &Problem) -> Result<Self> {
        let t0 = Instant::now();
        let dofs = problem.dof_map();
        let pattern = SystemPattern::new(&problem.mesh, &dofs)?;
        let t1 = Instant::now();
        let cholesky = Cholesky::analyze(
            &problem.mesh,
            dofs.equations(),
            &pattern,
            problem.solver.ordering,
            super::parallelism(problem.solver.threads),
        )?;
        let t2 = Instant::now();
        let f_ext = problem.external_forces();
        let n = dofs.n_dofs();
        let hess = vec![0.0; pattern.nnz()];
        Ok(System {
            dofs,
            pattern,
            cholesky,
            f_ext,
            grad: vec![0.0; n],
            hess,
            setup_time: ((t1 - t0).as_secs_f64(), (t2 - t1).as_secs_f64()),
        })
    }

    /// Total energy `Π(u) = Σ_T |T| W(ε_T(u)) − f·u` at `u`; the gradient goes to
    /// `self.grad`, and with `hessian` the Hessian to `self.hess`.
    pub fn evaluate(&mut self, problem: &Problem, u: &[f64], hessian: bool) -> f64 {
        let bulk = BulkAssembler {
            mesh: &problem.mesh,
            material: &problem.material,
        };
        let want = if hessian {
            Want::Hessian
        } else {
            Want::Gradient
        };
        let hess = if hessian {
            Some(self.hess.as_mut_slice())
        } else {
            None
        };
        let e = bulk.assemble(u, &mut self.grad, want, &self.pattern, hess);
        let mut work = 0.0;
        for ((g, f), x) in self.grad.iter_mut().zip(&self.f_ext).zip(u) {
            *g -= f;
            work += f * x;
        }
        e - work
    }

    /// Gradient restricted to the free DOFs (equation order) into `r`.
    pub fn reduce(&self, full: &[f64], r: &mut [f64]) {
        for (dof, &eq) in self.dofs.equations().iter().enumerate() {
            if eq != crate::fem::dofs::FIXED {
                r[eq as usize] = full[dof];
            }
        }
    }

    /// Energy at `u` and the reaction forces (gradient at prescribed DOFs, zero elsewhere).
    pub fn energy_and_reactions(&mut self, problem: &Problem, u: &[f64]) -> (f64, Vec<f64>) {
        let e = self.evaluate(problem, u, false);
        let reactions = (0..self.dofs.n_dofs())
            .map(|k| {
                if self.dofs.is_fixed(k) {
                    self.grad[k]
                } else {
                    0.0
                }
            })
            .collect();
        (e, reactions)
    }
}
