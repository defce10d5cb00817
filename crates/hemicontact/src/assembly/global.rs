//! The cell loop: bulk energy `Σ_T |T| W(ε_T(u))`, its gradient (internal forces) and its
//! Hessian (tangent stiffness) on the fixed pattern.

use super::element;
use super::pattern::SystemPattern;
use crate::geometry::simplex;
use crate::material::{AugmentedLocking, LockingSet, StrainEnergy};
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

/// How [`BulkAssembler::assemble_parallel`] splits the cell loop, and its work arrays: the
/// cells of its mesh (the whole, or a process's part when the run is several
/// processes), cut into `chunks` parallel tasks, each owning a range of nodes whose
/// gradient entries and Hessian columns it alone writes; the split is kept between calls so
/// that assembly does not allocate. A workspace serves one mesh, cell list and pattern (the
/// split is made again when their sizes change).
#[derive(Clone, Debug, Default)]
pub struct Workspace {
    /// Number of chunks (parallel tasks); 1 assembles serially.
    pub chunks: usize,
    /// When the mesh is one process's part of a distributed mesh
    /// ([`crate::parallel::Subdomain::local_mesh`]), how many of its first cells it owns:
    /// only those count their energy (the others are its ghost layer). `None`: every cell
    /// counts.
    pub owned_cells: Option<usize>,
    /// Fewest cells per task: a smaller loop runs on fewer tasks (default
    /// [`Workspace::CELLS_PER_CHUNK`]; below a few thousand cells a task costs more than it
    /// saves).
    pub cells_per_chunk: usize,
    plan: Option<TaskPlan>,
}

/// The split of one cell loop among parallel tasks. Task `t` owns the nodes
/// `bounds[t]..bounds[t + 1]`: their gradient entries and their columns of the Hessian,
/// which are contiguous stretches of both arrays, so every task writes its own slices and
/// no entry is written by two tasks. It assembles every cell with a node in its range, in
/// increasing position, so each entry receives its cells' terms in the order of the serial
/// loop: gradient and Hessian are bitwise the serial ones for any number of tasks. A cell
/// on a border between ranges is computed by each task it touches (the price of writing
/// no private copies); its energy is counted by the task of its lowest node, stored per
/// cell and added up in cell order afterwards, so the energy too is the serial one.
#[derive(Clone, Debug, Default)]
struct TaskPlan {
    /// What the plan was built for: cells assembled, cells counted, nodes, pattern entries,
    /// tasks.
    key: [usize; 5],
    /// Task `t` owns the nodes `bounds[t]..bounds[t + 1]`.
    bounds: Vec<usize>,
    /// The positions (in the pass's cell list) of the cells each task assembles.
    positions: Vec<Vec<u32>>,
    /// The task that counts the energy of the cell at each counted position.
    owner: Vec<u16>,
    /// Per task, the energy terms of the cells it counts, in position order (written by
    /// every pass).
    energies: Vec<Vec<f64>>,
    /// Per task, how many of its energy terms the sum in cell order has taken.
    taken: Vec<usize>,
}

impl Workspace {
    /// Cells per chunk below which a parallel assembly does not pay for its tasks.
    pub const CELLS_PER_CHUNK: usize = 4096;

    /// The number of chunks an assembly of `n_cells` cells splits into with `chunks`
    /// parallel tasks asked for and at least `per_chunk` cells each (at least one, at most
    /// 65 535).
    fn chunk_count(chunks: usize, n_cells: usize, per_chunk: usize) -> usize {
        chunks
            .min(n_cells / per_chunk.max(1))
            .clamp(1, u16::MAX as usize)
    }

    /// Bytes of the work arrays a parallel assembly of `n_cells` cells with `chunks` tasks
    /// keeps beside the system: per cell, the task that counts its energy (2 bytes), its
    /// energy terms (16 bytes with the two terms of ideal locking) and its position in the
    /// list of every task it touches (4 bytes each; counted as 2 tasks per cell, above the
    /// 1.03 to 1.55 measured on `hertz3d.toml` for 2 to 16 node ranges). Nothing on one
    /// task.
    pub fn buffer_bytes(chunks: usize, n_cells: usize) -> u64 {
        if Self::chunk_count(chunks, n_cells, Self::CELLS_PER_CHUNK) == 1 {
            return 0;
        }
        (2 + 16 + 2 * 4) * n_cells as u64
    }

    /// A workspace for `chunks` parallel chunks over every cell.
    pub fn new(chunks: usize) -> Self {
        Workspace {
            chunks: chunks.max(1),
            owned_cells: None,
            cells_per_chunk: Self::CELLS_PER_CHUNK,
            plan: None,
        }
    }
}

impl TaskPlan {
    /// The plan of `k` tasks for the cells of `mesh`, of which the first `counted` add their
    /// energy: node ranges of about equal numbers of cell–node incidences.
    fn new(mesh: &Mesh, counted: usize, nnz: usize, k: usize) -> TaskPlan {
        let n_cells = mesh.n_cells();
        let n_nodes = mesh.n_nodes();
        let mut weight = vec![0usize; n_nodes + 1];
        for p in 0..n_cells {
            for &v in mesh.cell(p) {
                weight[v as usize + 1] += 1;
            }
        }
        for v in 0..n_nodes {
            weight[v + 1] += weight[v];
        }
        let total = weight[n_nodes];
        let mut bounds: Vec<usize> = (0..=k)
            .map(|t| weight.partition_point(|&w| w < t * total / k))
            .collect();
        bounds[0] = 0;
        bounds[k] = n_nodes;
        for t in 1..=k {
            bounds[t] = bounds[t].max(bounds[t - 1]);
        }
        let task_of = |v: u32| bounds.partition_point(|&b| b <= v as usize) - 1;
        let mut positions = vec![Vec::new(); k];
        let key = [n_cells, counted, n_nodes, nnz, k];
        let counted = counted.min(n_cells);
        let mut owner = Vec::with_capacity(counted);
        let mut touched = [usize::MAX; 4];
        for p in 0..n_cells {
            let cell = mesh.cell(p);
            for (slot, &v) in touched.iter_mut().zip(cell) {
                *slot = task_of(v);
            }
            let tasks = &mut touched[..cell.len()];
            tasks.sort_unstable();
            for (i, &t) in tasks.iter().enumerate() {
                if i == 0 || tasks[i - 1] != t {
                    positions[t].push(p as u32);
                }
            }
            if p < counted {
                let lowest = cell.iter().min().copied().unwrap_or(0);
                owner.push(task_of(lowest) as u16);
            }
        }
        let mut counts = vec![0usize; k];
        for &t in &owner {
            counts[t as usize] += 1;
        }
        let energies = counts.iter().map(|&c| Vec::with_capacity(2 * c)).collect();
        TaskPlan {
            key,
            bounds,
            positions,
            owner,
            energies,
            taken: vec![0; k],
        }
    }
}

/// Where one pass of the cell loop writes: the gradient entries from `grad_start` on and
/// the Hessian values from `hess_start` on, as far as its slices reach (the whole arrays
/// for the serial loop, a task's own stretches in parallel), and where the energy goes.
struct Window<'w> {
    grad: &'w mut [f64],
    grad_start: usize,
    hess: Option<&'w mut [f64]>,
    hess_start: usize,
    /// In parallel: the task's number, the counting task of every counted position and
    /// the task's energy terms; `None`: the pass adds its energy up itself.
    energy: Option<(u16, &'w [u16], &'w mut Vec<f64>)>,
}

impl<'w> Window<'w> {
    /// The whole arrays, for a serial pass that adds its energy up itself.
    fn whole(grad: &'w mut [f64], hess: Option<&'w mut [f64]>) -> Self {
        Window {
            grad,
            grad_start: 0,
            hess,
            hess_start: 0,
            energy: None,
        }
    }
}

/// Ideal locking in the cell loop: the augmented Lagrangian term [`AugmentedLocking`] of
/// every cell, with its frozen multiplier.
#[derive(Clone, Copy, Debug)]
pub struct IdealLocking<'a> {
    /// The locking set B of each material (`None` for a material without ideal locking),
    /// indexed like [`BulkAssembler::materials`].
    pub sets: &'a [Option<LockingSet>],
    /// Penalty r > 0 of each material (Pa per unit of Q²).
    pub r: &'a [f64],
    /// Multiplier λ_T ≥ 0 per cell (Pa; 0 in the cells of the other materials).
    pub multipliers: &'a [f64],
}

impl IdealLocking<'_> {
    /// The augmented Lagrangian law of cell `c` of material `k`, if that material locks
    /// ideally.
    #[inline]
    pub fn cell(&self, c: usize, k: usize) -> Option<AugmentedLocking> {
        self.sets[k].map(|set| AugmentedLocking {
            set,
            r: self.r[k],
            lambda: self.multipliers[c],
        })
    }
}

/// Assembles the bulk energy of a mesh and its materials.
#[derive(Clone, Copy, Debug)]
pub struct BulkAssembler<'a, M: StrainEnergy> {
    /// The mesh.
    pub mesh: &'a Mesh,
    /// The material laws: cell `c` has `materials[of_region[mesh.cell_region(c)]]`, or
    /// `materials[0]` when `of_region` is empty.
    pub materials: &'a [M],
    /// The material of each cell region of the mesh (empty: one material everywhere).
    pub of_region: &'a [u16],
    /// Ideal locking (exact constraint), if any.
    pub ideal: Option<IdealLocking<'a>>,
}

impl<'a, M: StrainEnergy> BulkAssembler<'a, M> {
    /// The assembler of one `material` on all of `mesh`, without ideal locking.
    pub fn new(mesh: &'a Mesh, material: &'a M) -> Self {
        BulkAssembler {
            mesh,
            materials: std::slice::from_ref(material),
            of_region: &[],
            ideal: None,
        }
    }

    /// The index into [`BulkAssembler::materials`] of the law of cell `c`.
    #[inline]
    pub fn material_index(&self, c: usize) -> usize {
        if self.of_region.is_empty() {
            0
        } else {
            self.of_region[self.mesh.cell_region(c)] as usize
        }
    }

    /// The material law of cell `c`.
    #[inline]
    pub fn material(&self, c: usize) -> &'a M {
        &self.materials[self.material_index(c)]
    }
}

impl<'a> BulkAssembler<'a, crate::material::Material> {
    /// The assembler of the materials of `problem` on the mesh `mesh` (the problem's, or a
    /// mesh of the same cell regions), without ideal locking.
    pub fn of(problem: &'a crate::problem::Problem, mesh: &'a Mesh) -> Self {
        BulkAssembler {
            mesh,
            materials: &problem.materials,
            of_region: &problem.region_material,
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
        self.assemble_range(
            0..mesh.n_cells(),
            usize::MAX,
            u,
            pattern,
            Window::whole(grad, hess),
        )
    }

    /// As [`BulkAssembler::assemble`], with the cells split among `workspace.chunks`
    /// parallel tasks (rayon) by node ranges ([`Workspace`]): each task writes the gradient
    /// entries and Hessian columns of its own nodes, with no private copies to add up. The
    /// energy, gradient and Hessian are bitwise those of the serial loop over the same cells,
    /// whatever the number of tasks.
    ///
    /// On one process's part of a distributed mesh ([`Workspace::owned_cells`]) the energy
    /// is that of its owned cells, and the gradient entries and Hessian rows are exact at
    /// the DOFs of its own nodes only (partial at its ghost nodes).
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
        let n_cells = self.mesh.n_cells();
        let counted = workspace.owned_cells.unwrap_or(usize::MAX);
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
        let k = Workspace::chunk_count(workspace.chunks, n_cells, workspace.cells_per_chunk);
        if k == 1 {
            return self.assemble_range(0..n_cells, counted, u, pattern, Window::whole(grad, hess));
        }
        let key = [n_cells, counted, self.mesh.n_nodes(), pattern.nnz(), k];
        if workspace.plan.as_ref().is_none_or(|p| p.key != key) {
            workspace.plan = Some(TaskPlan::new(self.mesh, counted, pattern.nnz(), k));
        }
        let Some(plan) = workspace.plan.as_mut() else {
            unreachable!("the plan was just built")
        };
        // Every task's own stretches of the gradient and the Hessian.
        let d = self.mesh.dim();
        let col_ptr = pattern.col_ptr();
        let mut windows = Vec::with_capacity(k);
        let (mut grad_rest, mut hess_rest) = (grad, hess);
        let owner = plan.owner.as_slice();
        for (t, energies) in plan.energies.iter_mut().enumerate() {
            let nodes = plan.bounds[t]..plan.bounds[t + 1];
            let (g, rest) = std::mem::take(&mut grad_rest).split_at_mut(d * nodes.len());
            grad_rest = rest;
            let cols = pattern.node_columns(nodes.clone());
            let h = match hess_rest.take() {
                Some(h) => {
                    let (mine, rest) = h.split_at_mut(col_ptr[cols.end] - col_ptr[cols.start]);
                    hess_rest = Some(rest);
                    Some(mine)
                }
                None => None,
            };
            energies.clear();
            windows.push(Window {
                grad: g,
                grad_start: d * nodes.start,
                hess: h,
                hess_start: col_ptr[cols.start],
                energy: Some((t as u16, owner, energies)),
            });
        }
        use rayon::prelude::*;
        let positions = &plan.positions;
        windows
            .into_par_iter()
            .zip(positions.par_iter())
            .for_each(|(window, list)| {
                self.assemble_range(
                    list.iter().map(|&p| p as usize),
                    counted,
                    u,
                    pattern,
                    window,
                );
            });
        // The energy in cell order, as the serial loop adds it.
        let terms = if self.ideal.is_some() { 2 } else { 1 };
        plan.taken.fill(0);
        let mut energy = 0.0;
        for &t in &plan.owner {
            let t = t as usize;
            let first = plan.taken[t];
            for term in &plan.energies[t][first..first + terms] {
                energy += term;
            }
            plan.taken[t] = first + terms;
        }
        energy
    }

    /// Serial assembly of the cells `positions`, of which those below `counted` add their
    /// energy, into `window` (overwritten).
    fn assemble_range(
        &self,
        positions: impl Iterator<Item = usize>,
        counted: usize,
        u: &[f64],
        pattern: &SystemPattern,
        window: Window<'_>,
    ) -> f64 {
        if self.mesh.dim() == 2 {
            self.assemble_cells::<6>(positions, counted, u, pattern, window)
        } else {
            self.assemble_cells::<12>(positions, counted, u, pattern, window)
        }
    }

    /// [`BulkAssembler::assemble_range`] for cells with `LD` local DOFs.
    fn assemble_cells<const LD: usize>(
        &self,
        positions: impl Iterator<Item = usize>,
        counted: usize,
        u: &[f64],
        pattern: &SystemPattern,
        window: Window<'_>,
    ) -> f64 {
        let mesh = self.mesh;
        let d = element::dim_of(LD);
        let Window {
            grad,
            grad_start,
            mut hess,
            hess_start,
            energy: mut sink,
        } = window;
        grad.fill(0.0);
        if let Some(h) = hess.as_deref_mut() {
            h.fill(0.0);
        }
        let mut energy = 0.0;
        for p in positions {
            let c = p;
            let geo = simplex::geometry(d, &mesh.cell_coords(c));
            let b = element::b_matrix::<LD>(&geo);
            let eps = element::strain(&b, &element::gather::<LD>(mesh, u, c));
            let k = self.material_index(c);
            let al = self.ideal.and_then(|l| l.cell(c, k));
            // Ghost cells (of another process's subdomain) add no energy, nor in parallel
            // the cells of another task's lowest node.
            let counted = p < counted;
            let material = &self.materials[k];
            let mut sigma = material.stress(&eps);
            match &mut sink {
                None if counted => {
                    energy += geo.measure * material.energy(&eps);
                    if let Some(al) = &al {
                        energy += geo.measure * al.energy(&eps);
                    }
                }
                Some((task, owner, terms)) if counted && owner[p] == *task => {
                    terms.push(geo.measure * material.energy(&eps));
                    // Two terms per cell with ideal locking, the second 0 in the cells of
                    // a material without it (adding 0 leaves the serial sum's bits).
                    if self.ideal.is_some() {
                        terms.push(al.map_or(0.0, |al| geo.measure * al.energy(&eps)));
                    }
                }
                _ => {}
            }
            if let Some(al) = &al {
                sigma = sigma.add_scaled(1.0, &al.stress(&eps));
            }
            let ge = element::gradient(&b, &sigma, geo.measure);
            for (a, &v) in mesh.cell(c).iter().enumerate() {
                for i in 0..d {
                    let j = (d * v as usize + i).wrapping_sub(grad_start);
                    if j < grad.len() {
                        grad[j] += ge[d * a + i];
                    }
                }
            }
            if let Some(h) = hess.as_deref_mut() {
                let mut tangent = material.tangent(&eps);
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
                        // A prescribed pair (FIXED_SLOT, above every value's index) and
                        // another task's column fall outside the window.
                        let j = (slots[k] as usize).wrapping_sub(hess_start);
                        k += 1;
                        if j < h.len() {
                            h[j] += ke[p][q];
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
            let k = self.material_index(c);
            let mut sigma = self.materials[k].stress(&eps);
            if let Some(al) = self.ideal.and_then(|l| l.cell(c, k)) {
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
