//! The sparsity pattern of the reduced system, built once per mesh and DOF map.
//!
//! The matrix acts on the free DOFs (equation numbers, see [`crate::fem::dofs`]). Only the
//! **upper triangle** (row ≤ column) is stored, in compressed sparse column form: the rows of
//! column `j` are `row_idx[col_ptr[j]..col_ptr[j+1]]`, sorted, and the diagonal is the last
//! entry of every column. Two equations are coupled when their nodes share a cell.
//!
//! For each cell the pattern also stores the *slot* (index into the value array) of every
//! local pair `(p, q)`, `p ≤ q`, so that assembly is a gather-free scatter with no search:
//! `cell_slots[c · n_pairs + pair(p, q)]`, with [`FIXED_SLOT`] when either DOF is
//! prescribed. Pairs are enumerated row by row of the local upper triangle.

use crate::error::{Error, Result};
use crate::fem::dofs::{DofMap, FIXED};
use crate::mesh::Mesh;

/// Slot marker for a local pair that touches a prescribed DOF.
pub const FIXED_SLOT: u32 = u32::MAX;

/// Upper-triangular CSC pattern of the reduced system with per-cell scatter slots.
#[derive(Clone, Debug)]
pub struct SystemPattern {
    n: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    local_dofs: usize,
    cell_slots: Vec<u32>,
    node_cols: Vec<u32>,
}

impl SystemPattern {
    /// Builds the pattern of `mesh` with the DOF map `dofs`: the couplings of nodes that
    /// share a cell, and a diagonal entry for every free equation (so that
    /// [`SystemPattern::diagonal_slot`] holds for all).
    ///
    /// A process of a distributed run builds it on its part of the mesh
    /// ([`crate::parallel::Subdomain::local_mesh`]): the rows of its own nodes' equations
    /// are then those of the whole mesh's pattern, and the rest holds only what its cells
    /// touch.
    ///
    /// # Errors
    /// [`Error::OutOfMemory`] if the pattern has more than `u32::MAX` entries.
    pub fn new(mesh: &Mesh, dofs: &DofMap) -> Result<Self> {
        let d = mesh.dim();
        let n = dofs.n_free();
        let (ptr, adj) = mesh.node_adjacency();
        let n_cells = mesh.n_cells();
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0usize);
        let mut row_idx = Vec::with_capacity((adj.len() + mesh.n_nodes()) * d * d / 2 + n);
        let mut node_cols = Vec::with_capacity(mesh.n_nodes() + 1);
        for node in 0..mesh.n_nodes() {
            node_cols.push((col_ptr.len() - 1) as u32);
            for i in 0..d {
                let col = dofs.equation(d * node + i);
                if col == FIXED {
                    continue;
                }
                // Neighbours (sorted) with the node itself inserted in order.
                let nb = &adj[ptr[node]..ptr[node + 1]];
                let split = nb.partition_point(|&m| (m as usize) < node);
                let ordered = nb[..split]
                    .iter()
                    .copied()
                    .chain(std::iter::once(node as u32))
                    .chain(nb[split..].iter().copied());
                for m in ordered {
                    for k in 0..d {
                        let row = dofs.equation(d * m as usize + k);
                        if row != FIXED && row <= col {
                            row_idx.push(row as usize);
                        }
                    }
                }
                col_ptr.push(row_idx.len());
            }
        }
        node_cols.push(n as u32);
        debug_assert_eq!(col_ptr.len(), n + 1);
        if row_idx.len() >= FIXED_SLOT as usize {
            return Err(Error::OutOfMemory(format!(
                "the stiffness pattern has {} entries, more than supported",
                row_idx.len()
            )));
        }
        let ld = d * (d + 1);
        let n_pairs = ld * (ld + 1) / 2;
        let mut cell_slots = Vec::with_capacity(n_cells * n_pairs);
        let mut eq = [0u32; 12];
        for c in 0..n_cells {
            for (a, &v) in mesh.cell(c).iter().enumerate() {
                for i in 0..d {
                    eq[d * a + i] = dofs.equation(d * v as usize + i);
                }
            }
            for p in 0..ld {
                for q in p..ld {
                    let (ep, eq_) = (eq[p], eq[q]);
                    if ep == FIXED || eq_ == FIXED {
                        cell_slots.push(FIXED_SLOT);
                        continue;
                    }
                    let (row, col) = (ep.min(eq_) as usize, ep.max(eq_) as usize);
                    let rows = &row_idx[col_ptr[col]..col_ptr[col + 1]];
                    // The pattern contains every coupling by construction.
                    let k = rows.binary_search(&row).unwrap_or(0);
                    cell_slots.push((col_ptr[col] + k) as u32);
                }
            }
        }
        Ok(SystemPattern {
            n,
            col_ptr,
            row_idx,
            local_dofs: ld,
            cell_slots,
            node_cols,
        })
    }

    /// Number of equations (rows = columns).
    #[inline]
    pub fn n(&self) -> usize {
        self.n
    }

    /// Number of stored entries (upper triangle).
    #[inline]
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Column pointers (length `n + 1`).
    #[inline]
    pub fn col_ptr(&self) -> &[usize] {
        &self.col_ptr
    }

    /// Row indices (length `nnz`).
    #[inline]
    pub fn row_idx(&self) -> &[usize] {
        &self.row_idx
    }

    /// Number of local DOFs per cell, `d(d+1)`.
    #[inline]
    pub fn local_dofs(&self) -> usize {
        self.local_dofs
    }

    /// Number of cells the pattern was built on.
    #[inline]
    pub fn n_cells(&self) -> usize {
        let np = self.local_dofs * (self.local_dofs + 1) / 2;
        self.cell_slots.len() / np
    }

    /// Scatter slots of the `c`-th cell the pattern was built on (cell `c` of the mesh for
    /// [`SystemPattern::new`]; local upper-triangle pairs, row by row).
    #[inline]
    pub fn cell_slots(&self, c: usize) -> &[u32] {
        let np = self.local_dofs * (self.local_dofs + 1) / 2;
        &self.cell_slots[c * np..(c + 1) * np]
    }

    /// The columns (equations) of the nodes `nodes`: equations are numbered node by node,
    /// so those of a range of nodes are a range too, and their stored entries are the
    /// contiguous values `col_ptr()[start]..col_ptr()[end]`.
    #[inline]
    pub fn node_columns(&self, nodes: std::ops::Range<usize>) -> std::ops::Range<usize> {
        self.node_cols[nodes.start] as usize..self.node_cols[nodes.end] as usize
    }

    /// Slot of the diagonal entry of equation `j`.
    #[inline]
    pub fn diagonal_slot(&self, j: usize) -> usize {
        self.col_ptr[j + 1] - 1
    }

    /// Position of entry `(row, col)` (upper triangle, `row ≤ col`) in the value array.
    pub fn find(&self, row: usize, col: usize) -> Option<usize> {
        let (r, c) = (row.min(col), row.max(col));
        let rows = &self.row_idx[self.col_ptr[c]..self.col_ptr[c + 1]];
        rows.binary_search(&r).ok().map(|k| self.col_ptr[c] + k)
    }

    /// `y = A x` for the symmetric matrix whose upper triangle has the given `values`.
    ///
    /// # Panics
    /// If the lengths do not match the pattern.
    #[track_caller]
    pub fn sym_matvec(&self, values: &[f64], x: &[f64], y: &mut [f64]) {
        assert!(values.len() == self.nnz() && x.len() == self.n && y.len() == self.n);
        y.fill(0.0);
        for j in 0..self.n {
            let mut acc = 0.0;
            for k in self.col_ptr[j]..self.col_ptr[j + 1] {
                let i = self.row_idx[k];
                let v = values[k];
                acc += v * x[i];
                if i != j {
                    y[i] += v * x[j];
                }
            }
            y[j] += acc;
        }
    }
}
