//! The cell loop: bulk energy `Σ_T |T| W(ε_T(u))`, its gradient (internal forces) and its
//! Hessian (tangent stiffness) on the fixed pattern.

use super::element;
use super::pattern::{SystemPattern, FIXED_SLOT};
use crate::fem::simplex;
use crate::material::StrainEnergy;
use crate::mesh::Mesh;
use crate::tensor::Sym;

/// What one pass of [`BulkAssembler::assemble`] computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Want {
    /// Energy and gradient.
    Gradient,
    /// Energy, gradient and Hessian.
    Hessian,
}

/// Assembles the bulk energy of a mesh and a material.
#[derive(Clone, Copy, Debug)]
pub struct BulkAssembler<'a, M: StrainEnergy> {
    /// The mesh.
    pub mesh: &'a Mesh,
    /// The material law.
    pub material: &'a M,
}

impl<'a, M: StrainEnergy> BulkAssembler<'a, M> {
    /// Local displacement vector of cell `c` from the global vector `u` (DOF order).
    #[inline]
    fn gather(&self, u: &[f64], c: usize) -> [f64; 12] {
        let d = self.mesh.dim();
        let mut ue = [0.0; 12];
        for (a, &v) in self.mesh.cell(c).iter().enumerate() {
            ue[d * a..d * a + d].copy_from_slice(&u[d * v as usize..d * v as usize + d]);
        }
        ue
    }

    /// One pass over the cells at displacement `u` (length `d · n_nodes`).
    ///
    /// Returns the bulk energy (J, or J/m for plane problems) and writes the gradient with
    /// respect to *all* DOFs into `grad` (length `d · n_nodes`, overwritten): its entries at
    /// prescribed DOFs are the reaction forces. With [`Want::Hessian`], the upper-triangular
    /// Hessian on the free DOFs is written into `hess` (length `pattern.nnz()`, overwritten).
    ///
    /// # Panics
    /// If a length does not match, or `Want::Hessian` is asked without `hess`.
    #[track_caller]
    pub fn assemble(
        &self,
        u: &[f64],
        grad: &mut [f64],
        want: Want,
        pattern: &SystemPattern,
        mut hess: Option<&mut [f64]>,
    ) -> f64 {
        let mesh = self.mesh;
        let d = mesh.dim();
        let ld = d * (d + 1);
        assert_eq!(u.len(), d * mesh.n_nodes());
        assert_eq!(grad.len(), u.len());
        grad.fill(0.0);
        if let Some(h) = hess.as_deref_mut() {
            assert_eq!(h.len(), pattern.nnz());
            h.fill(0.0);
        }
        assert!(want == Want::Gradient || hess.is_some());
        let mut energy = 0.0;
        for c in 0..mesh.n_cells() {
            let geo = simplex::geometry(d, &mesh.cell_coords(c));
            let b = element::b_matrix(d, &geo);
            let ue = self.gather(u, c);
            let eps = element::strain(d, &b, &ue);
            energy += geo.measure * self.material.energy(&eps);
            let sigma = self.material.stress(&eps);
            let ge = element::gradient(d, &b, &sigma, geo.measure);
            for (a, &v) in mesh.cell(c).iter().enumerate() {
                for i in 0..d {
                    grad[d * v as usize + i] += ge[d * a + i];
                }
            }
            if let Some(h) = hess.as_deref_mut() {
                let ke = element::hessian(d, &b, &self.material.tangent(&eps), geo.measure);
                let slots = pattern.cell_slots(c);
                let mut k = 0;
                for p in 0..ld {
                    for q in p..ld {
                        let s = slots[k];
                        k += 1;
                        if s != FIXED_SLOT {
                            h[s as usize] += ke[p][q];
                        }
                    }
                }
            }
        }
        energy
    }

    /// Constant strain of every cell at displacement `u`.
    pub fn cell_strains(&self, u: &[f64]) -> Vec<Sym> {
        let d = self.mesh.dim();
        (0..self.mesh.n_cells())
            .map(|c| {
                let geo = simplex::geometry(d, &self.mesh.cell_coords(c));
                let b = element::b_matrix(d, &geo);
                element::strain(d, &b, &self.gather(u, c))
            })
            .collect()
    }
}
