//! The cell loop: bulk energy `Σ_T |T| W(ε_T(u))`, its gradient (internal forces) and its
//! Hessian (tangent stiffness) on the fixed pattern.

use super::element;
use super::pattern::{SystemPattern, FIXED_SLOT};
use crate::fem::simplex;
use crate::material::{AugmentedLocking, LockingSet, StrainEnergy};
use crate::mesh::Mesh;
use crate::parallel::Subdomain;
use crate::tensor::Sym;

/// What one pass of [`BulkAssembler::assemble`] computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Want {
    /// Energy and gradient.
    Gradient,
    /// Energy, gradient and Hessian.
    Hessian,
}

/// How [`BulkAssembler::assemble_parallel`] splits the cell loop, and its buffers: the
/// cells of this process (all of them, or its [`Subdomain`] when the run is several
/// processes), cut into `chunks` parallel tasks, with one gradient and one Hessian array per
/// chunk beyond the first, kept between calls so that assembly does not allocate.
#[derive(Clone, Debug, Default)]
pub struct Workspace {
    /// Number of chunks (parallel tasks); 1 assembles serially.
    pub chunks: usize,
    /// The cells this process assembles, when it is one of several (`None`: every cell).
    pub subdomain: Option<Subdomain>,
    grads: Vec<Vec<f64>>,
    hesses: Vec<Vec<f64>>,
}

impl Workspace {
    /// Cells per chunk below which a parallel assembly does not pay for its buffers.
    const CELLS_PER_CHUNK: usize = 4096;

    /// The number of chunks an assembly of `n_cells` cells splits into with `chunks`
    /// parallel tasks asked for (at least one).
    fn chunk_count(chunks: usize, n_cells: usize) -> usize {
        chunks.min(n_cells / Self::CELLS_PER_CHUNK).max(1)
    }

    /// Bytes of the buffers a parallel assembly of `n_cells` cells with `chunks` tasks
    /// keeps beside the system: each chunk after the first assembles into a gradient of
    /// `dofs` values and a Hessian of `nnz` values (8 bytes each) of its own, which are then
    /// added up. At 5 055 477 DOFs (113.8 million Hessian entries) that is 0.9 GB per task.
    pub fn buffer_bytes(chunks: usize, n_cells: usize, dofs: usize, nnz: usize) -> u64 {
        let copies = Self::chunk_count(chunks, n_cells) as u64 - 1;
        copies * 8 * (dofs as u64 + nnz as u64)
    }

    /// A workspace for `chunks` parallel chunks over every cell.
    pub fn new(chunks: usize) -> Self {
        Workspace {
            chunks: chunks.max(1),
            subdomain: None,
            grads: Vec::new(),
            hesses: Vec::new(),
        }
    }
}

/// The cells of one pass: positions `0..len` of either every cell (`list` empty) or of
/// `list`, of which the first `counted` add their energy.
#[derive(Clone, Copy, Debug)]
struct Cells<'c> {
    list: &'c [u32],
    counted: usize,
}

impl Cells<'_> {
    /// Every cell of a mesh.
    const ALL: Cells<'static> = Cells {
        list: &[],
        counted: usize::MAX,
    };

    /// The cell at position `p`.
    #[inline]
    fn at(&self, p: usize) -> usize {
        if self.list.is_empty() {
            p
        } else {
            self.list[p] as usize
        }
    }
}

/// One parallel assembly task: a cell range and its output buffers.
type Job<'b> = (std::ops::Range<usize>, &'b mut [f64], Option<&'b mut [f64]>);

/// Ideal locking in the cell loop: the augmented Lagrangian term [`AugmentedLocking`] of
/// every cell, with its frozen multiplier.
#[derive(Clone, Copy, Debug)]
pub struct IdealLocking<'a> {
    /// The locking set B.
    pub set: LockingSet,
    /// Penalty r > 0 (Pa per unit of Q²).
    pub r: f64,
    /// Multiplier λ_T ≥ 0 per cell (Pa).
    pub multipliers: &'a [f64],
}

impl IdealLocking<'_> {
    /// The augmented Lagrangian law of cell `c`.
    #[inline]
    pub fn cell(&self, c: usize) -> AugmentedLocking {
        AugmentedLocking {
            set: self.set,
            r: self.r,
            lambda: self.multipliers[c],
        }
    }
}

/// Assembles the bulk energy of a mesh and a material.
#[derive(Clone, Copy, Debug)]
pub struct BulkAssembler<'a, M: StrainEnergy> {
    /// The mesh.
    pub mesh: &'a Mesh,
    /// The material law.
    pub material: &'a M,
    /// Ideal locking (exact constraint), if any.
    pub ideal: Option<IdealLocking<'a>>,
}

impl<'a, M: StrainEnergy> BulkAssembler<'a, M> {
    /// The assembler of `material` on `mesh` without ideal locking.
    pub fn new(mesh: &'a Mesh, material: &'a M) -> Self {
        BulkAssembler {
            mesh,
            material,
            ideal: None,
        }
    }
}

impl<'a, M: StrainEnergy + Sync> BulkAssembler<'a, M> {
    /// One pass over the cells at displacement `u` (length `d · n_nodes`).
    ///
    /// Returns the bulk energy (J, or J/m for plane problems) and writes the gradient with
    /// respect to *all* DOFs into `grad` (length `d · n_nodes`, overwritten): its entries at
    /// prescribed DOFs are the reaction forces. With [`Want::Hessian`], the upper-triangular
    /// Hessian on the free DOFs is written into `hess` (length `pattern.nnz()`, overwritten).
    /// Serial; see [`BulkAssembler::assemble_parallel`].
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
        hess: Option<&mut [f64]>,
    ) -> f64 {
        let mesh = self.mesh;
        assert_eq!(u.len(), mesh.dim() * mesh.n_nodes());
        assert_eq!(grad.len(), u.len());
        if let Some(h) = hess.as_deref() {
            assert_eq!(h.len(), pattern.nnz());
            assert_eq!(pattern.n_cells(), mesh.n_cells(), "a pattern of every cell");
        }
        assert!(want == Want::Gradient || hess.is_some());
        let hess = if want == Want::Hessian { hess } else { None };
        self.assemble_range(0..mesh.n_cells(), Cells::ALL, u, grad, pattern, hess)
    }

    /// As [`BulkAssembler::assemble`], with the cells split into `workspace.chunks`
    /// contiguous ranges assembled in parallel (rayon) into private buffers that are then
    /// summed in range order. The result is deterministic for a given number of chunks and
    /// equal to the serial one up to the order of floating-point additions.
    ///
    /// With a [`Workspace::subdomain`], only its cells are assembled, on a `pattern` built on
    /// them ([`SystemPattern::on_cells`]): the energy is that of its owned cells, and the
    /// gradient entries and Hessian rows are exact at the DOFs of its nodes only (partial
    /// elsewhere).
    ///
    /// # Panics
    /// As [`BulkAssembler::assemble`].
    #[track_caller]
    pub fn assemble_parallel(
        &self,
        u: &[f64],
        grad: &mut [f64],
        want: Want,
        pattern: &SystemPattern,
        hess: Option<&mut [f64]>,
        workspace: &mut Workspace,
    ) -> f64 {
        let (n_cells, cells) = match &workspace.subdomain {
            None => (self.mesh.n_cells(), Cells::ALL),
            Some(sub) => (
                sub.cells.len(),
                Cells {
                    list: &sub.cells,
                    counted: sub.owned,
                },
            ),
        };
        assert_eq!(u.len(), self.mesh.dim() * self.mesh.n_nodes());
        assert_eq!(grad.len(), u.len());
        if let Some(h) = hess.as_deref() {
            assert_eq!(h.len(), pattern.nnz());
            assert_eq!(
                pattern.n_cells(),
                n_cells,
                "a pattern of the assembled cells"
            );
        }
        assert!(want == Want::Gradient || hess.is_some());
        let hess = if want == Want::Hessian { hess } else { None };
        // Below a few thousand cells per chunk the buffers cost more than they save.
        let k = Workspace::chunk_count(workspace.chunks, n_cells);
        if k == 1 {
            return self.assemble_range(0..n_cells, cells, u, grad, pattern, hess);
        }
        let with_hess = hess.is_some();
        workspace.grads.resize_with(k - 1, Vec::new);
        workspace.hesses.resize_with(k - 1, Vec::new);
        let mut jobs: Vec<Job<'_>> = Vec::with_capacity(k);
        let bounds: Vec<usize> = (0..=k).map(|i| i * n_cells / k).collect();
        jobs.push((bounds[0]..bounds[1], grad, hess));
        for (i, (g, h)) in workspace
            .grads
            .iter_mut()
            .zip(workspace.hesses.iter_mut())
            .enumerate()
        {
            g.resize(u.len(), 0.0);
            let h = if with_hess {
                h.resize(pattern.nnz(), 0.0);
                Some(h.as_mut_slice())
            } else {
                None
            };
            jobs.push((bounds[i + 1]..bounds[i + 2], g.as_mut_slice(), h));
        }
        use rayon::prelude::*;
        let energies: Vec<f64> = jobs
            .par_iter_mut()
            .map(|(r, g, h)| self.assemble_range(r.clone(), cells, u, g, pattern, h.as_deref_mut()))
            .collect();
        let (first, rest) = jobs.split_at_mut(1);
        let (_, grad, hess) = &mut first[0];
        for (_, g, h) in rest.iter() {
            for (a, b) in grad.iter_mut().zip(g.iter()) {
                *a += b;
            }
            if let (Some(dst), Some(src)) = (hess.as_deref_mut(), h.as_deref()) {
                for (a, b) in dst.iter_mut().zip(src.iter()) {
                    *a += b;
                }
            }
        }
        energies.iter().sum()
    }

    /// Serial assembly of the cells at positions `range` of `cells` into `grad` and `hess`
    /// (overwritten).
    fn assemble_range(
        &self,
        range: std::ops::Range<usize>,
        cells: Cells<'_>,
        u: &[f64],
        grad: &mut [f64],
        pattern: &SystemPattern,
        hess: Option<&mut [f64]>,
    ) -> f64 {
        if self.mesh.dim() == 2 {
            self.assemble_cells::<6>(range, cells, u, grad, pattern, hess)
        } else {
            self.assemble_cells::<12>(range, cells, u, grad, pattern, hess)
        }
    }

    /// [`BulkAssembler::assemble_range`] for cells with `LD` local DOFs.
    fn assemble_cells<const LD: usize>(
        &self,
        range: std::ops::Range<usize>,
        cells: Cells<'_>,
        u: &[f64],
        grad: &mut [f64],
        pattern: &SystemPattern,
        mut hess: Option<&mut [f64]>,
    ) -> f64 {
        let mesh = self.mesh;
        let d = element::dim_of(LD);
        grad.fill(0.0);
        if let Some(h) = hess.as_deref_mut() {
            h.fill(0.0);
        }
        let mut energy = 0.0;
        for p in range {
            let c = cells.at(p);
            let geo = simplex::geometry(d, &mesh.cell_coords(c));
            let b = element::b_matrix::<LD>(&geo);
            let eps = element::strain(&b, &element::gather::<LD>(mesh, u, c));
            let al = self.ideal.map(|l| l.cell(c));
            // Ghost cells (of another process's subdomain) add no energy.
            let counted = p < cells.counted;
            if counted {
                energy += geo.measure * self.material.energy(&eps);
            }
            let mut sigma = self.material.stress(&eps);
            if let Some(al) = &al {
                if counted {
                    energy += geo.measure * al.energy(&eps);
                }
                sigma = sigma.add_scaled(1.0, &al.stress(&eps));
            }
            let ge = element::gradient(&b, &sigma, geo.measure);
            for (a, &v) in mesh.cell(c).iter().enumerate() {
                for i in 0..d {
                    grad[d * v as usize + i] += ge[d * a + i];
                }
            }
            if let Some(h) = hess.as_deref_mut() {
                let mut tangent = self.material.tangent(&eps);
                if let Some(al) = al.filter(|al| al.multiplier(&eps) > 0.0) {
                    let t = al.tangent(&eps);
                    for (row, trow) in tangent.iter_mut().zip(t.iter()) {
                        for (a, b) in row.iter_mut().zip(trow.iter()) {
                            *a += b;
                        }
                    }
                }
                let ke = element::hessian(&b, &tangent, geo.measure);
                let slots = pattern.cell_slots(p);
                let mut k = 0;
                for p in 0..LD {
                    for q in p..LD {
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

    /// The sum over the cells `cells` around node `v` of the magnitudes of their element
    /// forces at `v`, `Σ_T ‖|T| B_vᵀ σ_T‖` (N), at displacement `u`: the scale of the
    /// forces balanced at the node, whose round-off is about the machine epsilon times this.
    pub fn nodal_force_sum(&self, u: &[f64], v: u32, cells: &[u32]) -> f64 {
        if self.mesh.dim() == 2 {
            self.nodal_force_sum_cells::<6>(u, v, cells)
        } else {
            self.nodal_force_sum_cells::<12>(u, v, cells)
        }
    }

    /// [`BulkAssembler::nodal_force_sum`] for cells with `LD` local DOFs.
    fn nodal_force_sum_cells<const LD: usize>(&self, u: &[f64], v: u32, cells: &[u32]) -> f64 {
        let mesh = self.mesh;
        let d = element::dim_of(LD);
        let mut sum = 0.0;
        for &c in cells {
            let c = c as usize;
            let geo = simplex::geometry(d, &mesh.cell_coords(c));
            let b = element::b_matrix::<LD>(&geo);
            let eps = element::strain(&b, &element::gather::<LD>(mesh, u, c));
            let mut sigma = self.material.stress(&eps);
            if let Some(al) = self.ideal.map(|l| l.cell(c)) {
                sigma = sigma.add_scaled(1.0, &al.stress(&eps));
            }
            let ge = element::gradient(&b, &sigma, geo.measure);
            if let Some(a) = mesh.cell(c).iter().position(|&w| w == v) {
                sum += ge[d * a..d * a + d]
                    .iter()
                    .map(|x| x * x)
                    .sum::<f64>()
                    .sqrt();
            }
        }
        sum
    }

    /// Constant strain of every cell at displacement `u`.
    pub fn cell_strains(&self, u: &[f64]) -> Vec<Sym> {
        (0..self.mesh.n_cells())
            .map(|c| element::cell_strain(self.mesh, u, c).1)
            .collect()
    }
}
