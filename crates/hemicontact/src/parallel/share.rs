//! What this process counts of the solver's arrays in a sum or maximum over the whole
//! problem, and the reductions that complete such a partial result over the processes.
//!
//! Every global quantity the outer loop, Newton and the certificate decide on (a norm, a
//! dot product, a largest residual) is computed in two steps: each process reduces the
//! entries it *counts* ([`Share::counts_dof`], [`Share::counts_point`], …), then
//! [`Share::sum`] or [`Share::max`] completes the partial results over the processes. A
//! process counts the DOFs and equations of its own nodes, the contact points on them and
//! the cells it owns ([`crate::parallel::Subdomain`]), so every entry is counted by exactly
//! one process. On one process (and whenever every process holds and solves the whole
//! system alone) it counts everything and the completions do nothing, so the serial solve
//! adds the same numbers in the same order as without this seam.
//!
//! The per-point and per-cell quantities of the outer loop (frozen friction data, force
//! scales, certificate results, ideal-locking multipliers) are likewise computed only for
//! the points a process counts and the cells of its part ([`Share::holds_cell`]); the
//! answer's are completed by [`Share::complete_entries`]. A completion that fails (MPI's
//! error) leaves NaN and is recorded; the solve then ends with that error ([`failure`]).

use crate::contact::ContactNodes;
use crate::fem::dofs::{DofMap, FIXED};
use crate::mesh::Mesh;
use crate::parallel::{Processes, Subdomain};
use std::sync::OnceLock;

/// Which entries of the solver's arrays this process counts; see the module documentation.
#[derive(Clone, Debug)]
pub struct Share {
    /// The processes that complete a partial result; `None`: this process counts every
    /// entry and completes nothing.
    processes: Option<Processes>,
    /// The DOFs per node.
    dim: usize,
    /// Per node of the whole mesh: counted here.
    nodes: Vec<bool>,
    /// Per equation (free DOF): counted here.
    equations: Vec<bool>,
    /// Per contact point: counted here.
    points: Vec<bool>,
    /// Per cell of the whole mesh: counted here.
    cells: Vec<bool>,
    /// Per cell of the whole mesh: in this process's part (its owned and ghost cells), whose
    /// per-cell quantities it computes.
    held_cells: Vec<bool>,
}

impl Share {
    /// Everything, completed by nothing: one process, or one that holds and solves the
    /// whole system alone.
    pub const WHOLE: Share = Share {
        processes: None,
        dim: 1,
        nodes: Vec::new(),
        equations: Vec::new(),
        points: Vec::new(),
        cells: Vec::new(),
        held_cells: Vec::new(),
    };

    /// [`Share::WHOLE`].
    pub fn whole() -> Share {
        Share::WHOLE
    }

    /// What the process of `sub` counts of `mesh` (whose DOF map is `dofs` and contact
    /// points `contact`): its own nodes and their DOFs and equations, the contact points on
    /// them and its owned cells; completed over `processes`.
    pub fn of(
        mesh: &Mesh,
        dofs: &DofMap,
        contact: &ContactNodes,
        sub: &Subdomain,
        processes: Processes,
    ) -> Share {
        let d = mesh.dim();
        let rank = sub.rank;
        let nodes: Vec<bool> = sub
            .partition
            .rank_of
            .iter()
            .map(|&r| r as usize == rank)
            .collect();
        let mut equations = vec![false; dofs.n_free()];
        for (k, &eq) in dofs.equations().iter().enumerate() {
            if eq != FIXED {
                equations[eq as usize] = nodes[k / d];
            }
        }
        let points = contact.node.iter().map(|&v| nodes[v as usize]).collect();
        let mut cells = vec![false; mesh.n_cells()];
        for &c in &sub.cells[..sub.owned] {
            cells[c as usize] = true;
        }
        let mut held_cells = vec![false; mesh.n_cells()];
        for &c in &sub.cells {
            held_cells[c as usize] = true;
        }
        Share {
            processes: Some(processes),
            dim: d,
            nodes,
            equations,
            points,
            cells,
            held_cells,
        }
    }

    /// Whether the results are completed over several processes (`false`: this process
    /// counts every entry).
    pub fn is_split(&self) -> bool {
        self.processes.is_some()
    }

    /// Whether node `v` is counted here.
    #[inline]
    pub fn counts_node(&self, v: usize) -> bool {
        self.nodes.is_empty() || self.nodes[v]
    }

    /// Whether DOF `k` (DOF order) is counted here.
    #[inline]
    pub fn counts_dof(&self, k: usize) -> bool {
        self.nodes.is_empty() || self.nodes[k / self.dim]
    }

    /// Whether equation `e` (free DOF) is counted here.
    #[inline]
    pub fn counts_equation(&self, e: usize) -> bool {
        self.equations.is_empty() || self.equations[e]
    }

    /// Whether contact point `i` is counted here.
    #[inline]
    pub fn counts_point(&self, i: usize) -> bool {
        self.points.is_empty() || self.points[i]
    }

    /// Whether cell `c` is counted here.
    #[inline]
    pub fn counts_cell(&self, c: usize) -> bool {
        self.cells.is_empty() || self.cells[c]
    }

    /// Whether cell `c` is in this process's part: its per-cell quantities are computed
    /// here (those of the other cells are not, and read as NaN).
    #[inline]
    pub fn holds_cell(&self, c: usize) -> bool {
        self.held_cells.is_empty() || self.held_cells[c]
    }

    /// Completes `values`, `width` numbers per entry, over the processes: each process sends
    /// the entries it counts (`counted(i)`), and every process receives each entry from the
    /// one that counts it. For per-point and per-cell results that every process computes
    /// for its own entries only; nothing on one process.
    pub fn complete_entries(
        &self,
        values: &mut [f64],
        width: usize,
        counted: impl Fn(usize) -> bool,
    ) {
        if self.processes.is_none() || width == 0 {
            return;
        }
        let mut mine = Vec::new();
        for i in (0..values.len() / width).filter(|&i| counted(i)) {
            // Entry numbers below 2^53 are exact in floating point.
            mine.push(i as f64);
            mine.extend_from_slice(&values[width * i..width * i + width]);
        }
        for entry in self.gather_varying(&mine).chunks_exact(width + 1) {
            let i = entry[0] as usize;
            values[width * i..width * i + width].copy_from_slice(&entry[1..]);
        }
    }

    /// `values` ← their element-wise sum over the processes, added in rank order so that
    /// every process gets the same bits ([`Processes::sum`]); nothing on one process.
    pub fn sum(&self, values: &mut [f64]) {
        if let Some(p) = &self.processes {
            if let Err(e) = p.sum(values) {
                fail(e);
                values.fill(f64::NAN);
            }
        }
    }

    /// Each of `parts` ← its element-wise sum over the processes, all in one
    /// [`Share::sum`] (small arrays of one decision: normal equations and their right-hand
    /// side, a direction and its size); nothing on one process.
    pub fn sum_parts(&self, parts: &mut [&mut [f64]]) {
        if self.processes.is_none() {
            return;
        }
        let mut all: Vec<f64> = parts.iter().flat_map(|p| p.iter().copied()).collect();
        self.sum(&mut all);
        let mut at = 0;
        for part in parts.iter_mut() {
            part.copy_from_slice(&all[at..at + part.len()]);
            at += part.len();
        }
    }

    /// `values` ← their element-wise maximum over the processes, a NaN on any process
    /// giving a NaN (an MPI maximum leaves NaNs to the implementation); nothing on one
    /// process.
    pub fn max(&self, values: &mut [f64]) {
        let Some(p) = &self.processes else {
            return;
        };
        let m = values.len();
        let mut both: Vec<f64> = values
            .iter()
            .map(|&x| if x.is_nan() { f64::NEG_INFINITY } else { x })
            .collect();
        both.extend(values.iter().map(|x| f64::from(u8::from(x.is_nan()))));
        if let Err(e) = p.max(&mut both) {
            fail(e);
            both.fill(f64::NAN);
        }
        for (k, v) in values.iter_mut().enumerate() {
            *v = if both[m + k] > 0.0 { f64::NAN } else { both[k] };
        }
    }

    /// The sum over the processes of a count (`local` here).
    pub fn count(&self, local: usize) -> usize {
        // Counts below 2^53 add exactly in floating point.
        let mut n = [local as f64];
        self.sum(&mut n);
        n[0] as usize
    }

    /// Every process's `local` values (the same number on each), rank after rank; `local`
    /// itself on one process.
    pub fn gather(&self, local: &[f64]) -> Vec<f64> {
        match &self.processes {
            None => local.to_vec(),
            Some(p) => {
                let total = local.len() * p.size();
                p.all_gather(local, total).unwrap_or_else(|e| {
                    fail(e);
                    vec![f64::NAN; total]
                })
            }
        }
    }

    /// Every process's `local` values (any number on each), rank after rank; `local`
    /// itself on one process.
    pub fn gather_varying(&self, local: &[f64]) -> Vec<f64> {
        match &self.processes {
            None => local.to_vec(),
            Some(p) => {
                let gathered = p
                    .all_gather(&[local.len() as f64], p.size())
                    // Lengths below 2^53 add exactly in floating point.
                    .and_then(|counts| p.all_gather(local, counts.iter().sum::<f64>() as usize));
                gathered.unwrap_or_else(|e| {
                    fail(e);
                    Vec::new()
                })
            }
        }
    }

    /// The sum over the processes of the dot product `Σ a_e b_e` over the equations each
    /// counts (free-DOF vectors); on one process the plain dot product in order.
    pub fn dot_equations(&self, a: &[f64], b: &[f64]) -> f64 {
        self.dot(a, b, |e| self.counts_equation(e))
    }

    /// The sum over the processes of the dot product `Σ a_k b_k` over the DOFs each counts
    /// (DOF-order vectors); on one process the plain dot product in order.
    pub fn dot_dofs(&self, a: &[f64], b: &[f64]) -> f64 {
        self.dot(a, b, |k| self.counts_dof(k))
    }

    /// `Σ a_k b_k` over the entries `counted`, in order, completed over the processes.
    fn dot(&self, a: &[f64], b: &[f64], counted: impl Fn(usize) -> bool) -> f64 {
        let mut s = [a
            .iter()
            .zip(b)
            .enumerate()
            .filter(|&(k, _)| counted(k))
            .map(|(_, (x, y))| x * y)
            .sum::<f64>()];
        self.sum(&mut s);
        s[0]
    }
}

/// The first failure of a collective operation of a [`Share`] (MPI's error, in words),
/// until the solve reports it ([`failure`]).
static FAILURE: OnceLock<String> = OnceLock::new();

/// Records the failure `e` of a collective operation; the operation's result is then NaN
/// (or nothing, for a gather), and the solve ends with the error ([`failure`]).
fn fail(e: crate::Error) {
    let _ = FAILURE.set(e.to_string());
}

/// The failure of a collective operation of a [`Share`] in this process, if one failed:
/// [`crate::Error::Breakdown`] with MPI's message. The solve checks it after every
/// evaluation and before it returns, so that a failed reduction ends it with this error
/// rather than with the NaN it left behind.
pub fn failure() -> Option<crate::Error> {
    FAILURE.get().map(|m| crate::Error::Breakdown(m.clone()))
}
