//! What this process counts of the solver's arrays in a sum or maximum over the whole
//! problem, and the reductions that complete such a partial result over the processes.
//!
//! Every global quantity the outer loop, Newton and the certificate decide on (a norm, a
//! dot product, a largest residual) is computed in two steps: each process reduces the
//! entries it *counts* ([`Share::counts_dof`], [`Share::counts_cell`], …), then
//! [`Share::sum`] or [`Share::max`] completes the partial results over the processes. On
//! several processes the solver's arrays are those of the process's part of the mesh, and
//! it counts a prefix of each: its own nodes, their DOFs and equations, its own contact
//! points (those of its own nodes, before its ghost points) and its owned cells
//! ([`crate::parallel::Subdomain`]), so every entry of the whole problem is counted by
//! exactly one process. On one process (and whenever a process holds and solves the whole
//! system alone) it counts everything and the completions do nothing, so the serial solve
//! adds the same numbers in the same order as without this seam.
//!
//! [`Share::of_part`] picks a part's entries from an array of the whole problem (the
//! prescribed displacements, a starting displacement); [`Share::to_whole`] puts the
//! answer's arrays together from every process's own entries. A completion that fails
//! (MPI's error) leaves NaN and is recorded in the `Share` that made it, which belongs to
//! one solve; that solve then ends with the error ([`Share::failure`]), and the next solve,
//! with a `Share` of its own, starts clean.

use super::processes::Processes;
use super::subdomain::Subdomain;
use crate::fem::dofs::{DofMap, FIXED};
use std::sync::OnceLock;

/// The processes that complete a [`Share`]'s partial results, and the first failure of
/// one of its completions.
#[derive(Clone, Debug)]
struct Completion {
    /// The processes.
    processes: Processes,
    /// The first failure of a collective operation (MPI's error, in words), until the
    /// solve reports it ([`Share::failure`]).
    failure: OnceLock<String>,
}

/// Which entries of the solver's arrays this process counts; see the module documentation.
///
/// On several processes the solver's arrays are those of the process's part of the mesh
/// ([`Subdomain::local_mesh`]): its own nodes first, then its ghost nodes; the DOFs and
/// equations of its own nodes first; its own contact points first, then its ghost points
/// ([`crate::contact::ContactNodes::ghosts`]); its owned cells first, then its ghost cells.
/// What it counts is therefore a prefix of each.
#[derive(Clone, Debug)]
pub struct Share {
    /// The processes that complete a partial result, with the failure of a completion;
    /// `None`: this process counts every entry and completes nothing (and nothing fails).
    completion: Option<Completion>,
    /// The DOFs per node.
    dim: usize,
    /// Number of nodes counted here: the first ones of the part.
    own_nodes: usize,
    /// Number of equations (free DOFs) counted here: the first ones of the part.
    own_equations: usize,
    /// Number of cells counted here (owned): the first ones of the part.
    own_cells: usize,
    /// Number of contact points counted here (those of its own nodes): the first ones.
    own_points: usize,
    /// The whole mesh's number of every node of the part.
    node_ids: Vec<u32>,
    /// The whole problem's number of every contact point of the part.
    point_ids: Vec<u32>,
    /// The whole mesh's number of every cell of the part.
    cell_ids: Vec<u32>,
    /// Numbers of nodes, contact points and cells of the whole problem.
    whole: [usize; 3],
}

/// The kind of entry an array holds, for [`Share::to_whole`] and [`Share::of_part`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Entries {
    /// Mesh nodes (DOF-order vectors: `d` numbers per node).
    Nodes,
    /// Contact points.
    Points,
    /// Cells.
    Cells,
}

impl Share {
    /// Everything, completed by nothing: one process, or one that holds and solves the
    /// whole system alone.
    pub const WHOLE: Share = Share {
        completion: None,
        dim: 1,
        own_nodes: usize::MAX,
        own_equations: usize::MAX,
        own_cells: usize::MAX,
        own_points: usize::MAX,
        node_ids: Vec::new(),
        point_ids: Vec::new(),
        cell_ids: Vec::new(),
        whole: [0; 3],
    };

    /// [`Share::WHOLE`].
    pub fn whole() -> Share {
        Share::WHOLE
    }

    /// What the process of `sub` counts of its part of a mesh of dimension `dim`: the part's
    /// nodes are `nodes` (their whole numbers, its own first), its DOF map `dofs`
    /// ([`DofMap::restricted`]), its contact points the whole problem's `points` (its own
    /// `own_points` first, then its ghost points), its cells `sub.cells` (owned first); the
    /// whole problem has `whole` nodes, contact points and cells. Completed over
    /// `processes`.
    #[allow(clippy::too_many_arguments)]
    pub fn of(
        dim: usize,
        sub: &Subdomain,
        nodes: Vec<u32>,
        dofs: &DofMap,
        points: Vec<u32>,
        own_points: usize,
        whole: [usize; 3],
        processes: Processes,
    ) -> Share {
        let own_nodes = sub.nodes().len();
        let own_equations = dofs.equations()[..dim * own_nodes]
            .iter()
            .filter(|&&eq| eq != FIXED)
            .count();
        Share {
            completion: Some(Completion {
                processes,
                failure: OnceLock::new(),
            }),
            dim,
            own_nodes,
            own_equations,
            own_cells: sub.owned,
            own_points,
            node_ids: nodes,
            point_ids: points,
            cell_ids: sub.cells.clone(),
            whole,
        }
    }

    /// Whether the results are completed over several processes (`false`: this process
    /// counts every entry).
    pub fn is_split(&self) -> bool {
        self.completion.is_some()
    }

    /// The processes that complete the partial results; `None` on one process.
    fn processes(&self) -> Option<&Processes> {
        self.completion.as_ref().map(|c| &c.processes)
    }

    /// Records the failure `e` of a collective operation of this `Share` (the first one is
    /// kept); the operation's result is then NaN (or nothing, for a gather), and the solve
    /// ends with the error ([`Share::failure`]).
    fn fail(&self, e: crate::Error) {
        if let Some(c) = &self.completion {
            let _ = c.failure.set(e.to_string());
        }
    }

    /// The failure of a collective operation of this `Share`, if one failed:
    /// [`crate::Error::Breakdown`] with MPI's message. The solve that owns it checks it
    /// after every evaluation and before it returns, so that a failed reduction ends that
    /// solve with this error rather than with the NaN it left behind; a `Share` belongs to
    /// one solve, so no later solve sees it.
    pub fn failure(&self) -> Option<crate::Error> {
        let c = self.completion.as_ref()?;
        c.failure.get().map(|m| crate::Error::Breakdown(m.clone()))
    }

    /// Whether node `v` (of the part) is counted here.
    #[inline]
    pub fn counts_node(&self, v: usize) -> bool {
        v < self.own_nodes
    }

    /// Whether DOF `k` (DOF order) is counted here.
    #[inline]
    pub fn counts_dof(&self, k: usize) -> bool {
        k / self.dim < self.own_nodes
    }

    /// `v` (a DOF-order vector of the part) ← NaN at the DOFs not counted here: those of
    /// the ghost nodes, where a partial sum is unknown; nothing on one process, which
    /// counts every DOF.
    pub fn unknown_where_uncounted(&self, v: &mut [f64]) {
        // The DOFs counted here are the first ones: those of the own nodes.
        let counted = self.dim.saturating_mul(self.own_nodes).min(v.len());
        v[counted..].fill(f64::NAN);
    }

    /// Whether equation `e` (free DOF) is counted here.
    #[inline]
    pub fn counts_equation(&self, e: usize) -> bool {
        e < self.own_equations
    }

    /// Whether contact point `i` (of the part) is counted here.
    #[inline]
    pub fn counts_point(&self, i: usize) -> bool {
        i < self.own_points
    }

    /// Whether cell `c` (of the part) is counted here.
    #[inline]
    pub fn counts_cell(&self, c: usize) -> bool {
        c < self.own_cells
    }

    /// The whole mesh's number of node `v` of the part (for messages and results).
    pub fn whole_node(&self, v: u32) -> u32 {
        if self.node_ids.is_empty() {
            v
        } else {
            self.node_ids[v as usize]
        }
    }

    /// The part's entries of `whole`, an array of the whole problem with `width` numbers per
    /// entry of kind `of`: every node of the part (own and ghost), its contact points, its
    /// cells. `whole` itself on one process.
    pub fn of_part(&self, whole: Vec<f64>, width: usize, of: Entries) -> Vec<f64> {
        if self.completion.is_none() {
            return whole;
        }
        let ids = match of {
            Entries::Nodes => &self.node_ids,
            Entries::Points => &self.point_ids,
            Entries::Cells => &self.cell_ids,
        };
        let mut part = Vec::with_capacity(width * ids.len());
        for &i in ids {
            let i = i as usize;
            part.extend_from_slice(&whole[width * i..width * i + width]);
        }
        part
    }

    /// The array of the whole problem whose entries (of kind `of`, `width` numbers each)
    /// this process's `part` holds for its part: each process sends the entries it counts,
    /// tagged with their whole numbers, and every process receives all of them (one
    /// gather). `part` itself on one process.
    pub fn to_whole(&self, part: Vec<f64>, width: usize, of: Entries) -> Vec<f64> {
        if self.completion.is_none() || width == 0 {
            return part;
        }
        let (ids, counted, n) = match of {
            Entries::Nodes => (&self.node_ids, self.own_nodes, self.whole[0]),
            Entries::Points => (&self.point_ids, self.own_points, self.whole[1]),
            Entries::Cells => (&self.cell_ids, self.own_cells, self.whole[2]),
        };
        let counted = counted.min(part.len() / width);
        let mut mine = Vec::with_capacity((width + 1) * counted);
        for (i, &id) in ids[..counted].iter().enumerate() {
            // Entry numbers below 2^53 are exact in floating point.
            mine.push(f64::from(id));
            mine.extend_from_slice(&part[width * i..width * i + width]);
        }
        let mut whole = vec![f64::NAN; width * n];
        for entry in self.gather_varying(&mine).chunks_exact(width + 1) {
            let i = entry[0] as usize;
            whole[width * i..width * i + width].copy_from_slice(&entry[1..]);
        }
        whole
    }

    /// `values` ← their element-wise sum over the processes, added in rank order so that
    /// every process gets the same bits ([`Processes::sum`]); nothing on one process.
    pub fn sum(&self, values: &mut [f64]) {
        if let Some(p) = self.processes() {
            if let Err(e) = p.sum(values) {
                self.fail(e);
                values.fill(f64::NAN);
            }
        }
    }

    /// Each of `parts` ← its element-wise sum over the processes, all in one
    /// [`Share::sum`] (small arrays of one decision: normal equations and their right-hand
    /// side, a direction and its size); nothing on one process.
    pub fn sum_parts(&self, parts: &mut [&mut [f64]]) {
        if self.completion.is_none() {
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
        let Some(p) = self.processes() else {
            return;
        };
        let m = values.len();
        let mut both: Vec<f64> = values
            .iter()
            .map(|&x| if x.is_nan() { f64::NEG_INFINITY } else { x })
            .collect();
        both.extend(values.iter().map(|x| f64::from(u8::from(x.is_nan()))));
        if let Err(e) = p.max(&mut both) {
            self.fail(e);
            both.fill(f64::NAN);
        }
        for (k, v) in values.iter_mut().enumerate() {
            *v = if both[m + k] > 0.0 { f64::NAN } else { both[k] };
        }
    }

    /// `values` ← their element-wise minimum over the processes, a NaN on any process
    /// giving a NaN ([`Share::max`] of their negations: exact); nothing on one process.
    pub fn min(&self, values: &mut [f64]) {
        if self.completion.is_none() {
            return;
        }
        for v in values.iter_mut() {
            *v = -*v;
        }
        self.max(values);
        for v in values.iter_mut() {
            *v = -*v;
        }
    }

    /// Whether any process's `local` is true; `local` itself on one process.
    pub fn any(&self, local: bool) -> bool {
        let mut flags = [local];
        self.any_each(&mut flags);
        flags[0]
    }

    /// Each of `flags` ← whether it is true on any process (one completion for all of
    /// them); nothing on one process. A failed completion (recorded: it ends the solve)
    /// leaves them false.
    pub fn any_each(&self, flags: &mut [bool]) {
        if self.completion.is_none() {
            return;
        }
        // Each flag as 0 or 1, their maximum over the processes.
        let mut packed: Vec<f64> = flags.iter().map(|&b| f64::from(u8::from(b))).collect();
        self.max(&mut packed);
        for (b, p) in flags.iter_mut().zip(packed) {
            *b = p > 0.0;
        }
    }

    /// Whether `local` is true on every process; `local` itself on one process. A failed
    /// completion (recorded: it ends the solve) gives false.
    pub fn all(&self, local: bool) -> bool {
        if self.completion.is_none() {
            return local;
        }
        let mut packed = [f64::from(u8::from(!local))];
        self.max(&mut packed);
        packed[0] == 0.0
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
        match self.processes() {
            None => local.to_vec(),
            Some(p) => {
                let total = local.len() * p.size();
                p.all_gather(local, total).unwrap_or_else(|e| {
                    self.fail(e);
                    vec![f64::NAN; total]
                })
            }
        }
    }

    /// Every process's `local` values (any number on each), rank after rank; `local`
    /// itself on one process.
    pub fn gather_varying(&self, local: &[f64]) -> Vec<f64> {
        match self.processes() {
            None => local.to_vec(),
            Some(p) => {
                let gathered = p
                    .all_gather(&[local.len() as f64], p.size())
                    // Lengths below 2^53 add exactly in floating point.
                    .and_then(|counts| p.all_gather(local, counts.iter().sum::<f64>() as usize));
                gathered.unwrap_or_else(|e| {
                    self.fail(e);
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

#[cfg(all(test, not(feature = "petsc")))]
mod tests {
    use super::*;
    use crate::scenario::Scenario;
    use crate::solver::{solve, Solution};

    /// A block pressed onto a foundation with Coulomb friction: a solve with contact,
    /// whose sums and maxima go through its `Share`.
    const BLOCK: &str = r#"
[mesh]
kind = "rectangle"
size = [2.0, 1.0]
n = [8, 4]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "top"
value = [0.01, -0.02]
[[contact]]
part = "bottom"
c_nu = 1000.0
[contact.friction]
bound = "coulomb"
mu = { law = "constant", mu = 0.3 }
"#;

    /// A collective operation that fails (here: a share over two processes in a build
    /// without MPI, where every completion fails through `Processes`) leaves NaN and is
    /// recorded in that share alone: a solve before it and a solve after it in the same
    /// process converge to the same bits.
    #[test]
    fn a_failed_collective_ends_only_the_solve_whose_share_it_was() {
        let solved = || -> Solution {
            let scenario = Scenario::from_str(BLOCK, "<test>").unwrap();
            let problem = scenario.into_problem().unwrap();
            solve(&problem, &scenario.settings().unwrap()).unwrap()
        };
        let first = solved();
        assert!(first.report.converged, "{}", first.report.message);
        assert!(first.contact.iter().any(|c| c.pressure > 0.0));
        let failing = Share {
            completion: Some(Completion {
                processes: Processes {
                    rank: 0,
                    size: 2,
                    on_machine: 1,
                },
                failure: OnceLock::new(),
            }),
            ..Share::whole()
        };
        assert!(failing.failure().is_none());
        let mut x = [1.0, 2.0];
        failing.sum(&mut x);
        assert!(x.iter().all(|v| v.is_nan()), "{x:?}");
        let message = failing.failure().map(|e| e.to_string()).unwrap_or_default();
        assert!(
            message.contains("collective operation over 2 processes"),
            "{message}"
        );
        let second = solved();
        assert!(second.report.converged, "{}", second.report.message);
        assert_eq!(first.u, second.u);
        assert!(Share::whole().failure().is_none());
    }
}
