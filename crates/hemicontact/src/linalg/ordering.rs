//! Fill-reducing orderings for the sparse Cholesky factorization.
//!
//! Two choices, both computed on the **node** graph (d× smaller than the DOF graph) and
//! expanded to equations node by node, so the DOFs of a node stay together (good supernodes):
//!
//! - [`Ordering::NestedDissection`] (default): geometric nested dissection. The node set is
//!   split at the median coordinate along its longest bounding-box axis; the nodes of the
//!   lower half adjacent to the upper half form the separator, numbered last; both halves
//!   are ordered recursively. On the meshes of finite element problems this gives
//!   separators of size O(n^{(d−1)/d}), the optimal fill order O(n log n) in 2D, and needs
//!   no external library.
//! - [`Ordering::Amd`]: faer's approximate minimum degree on the node graph.
//!
//! `hemicontact bench` measures the factor size and time of both.

use serde::{Deserialize, Serialize};

/// Choice of fill-reducing ordering; see the module documentation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Ordering {
    /// Geometric nested dissection on the node graph.
    #[default]
    NestedDissection,
    /// Approximate minimum degree (faer) on the node graph.
    Amd,
}

/// Subsets of at most this many nodes are not dissected further.
const LEAF_SIZE: usize = 16;

/// Geometric nested dissection of the nodes `nodes` (coordinates `coords`, `n × dim`;
/// adjacency `ptr`/`adj` in CSR form). Returns the nodes in elimination order.
pub fn nested_dissection(
    coords: &[f64],
    dim: usize,
    ptr: &[usize],
    adj: &[u32],
    nodes: Vec<u32>,
) -> Vec<u32> {
    let small = nodes.clone();
    top_bisection(coords, dim, ptr, adj, nodes).map_or(small, Bisection::into_order)
}

/// The first bisection of a nested dissection: two parts that no edge joins, each in its
/// own nested-dissection order, and the separator between them. `[first, second,
/// separator]` is exactly the order [`nested_dissection`] returns for the same nodes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Bisection {
    /// Nodes of the first part, in elimination order.
    pub first: Vec<u32>,
    /// Nodes of the second part, in elimination order.
    pub second: Vec<u32>,
    /// Nodes of the separator: every edge from the first part to the second passes
    /// through it.
    pub separator: Vec<u32>,
}

impl Bisection {
    /// The whole elimination order `[first, second, separator]`.
    pub fn into_order(self) -> Vec<u32> {
        let mut order = self.first;
        order.extend_from_slice(&self.second);
        order.extend_from_slice(&self.separator);
        order
    }
}

/// The first bisection of the nested dissection of `nodes` (arguments as
/// [`nested_dissection`]); `None` when `nodes` is too small to be dissected.
pub fn top_bisection(
    coords: &[f64],
    dim: usize,
    ptr: &[usize],
    adj: &[u32],
    mut nodes: Vec<u32>,
) -> Option<Bisection> {
    if nodes.len() <= LEAF_SIZE {
        return None;
    }
    let mut mark = vec![0u8; ptr.len() - 1];
    let (n_interior, n_left) = bisect(coords, dim, ptr, adj, &mut nodes, &mut mark);
    let (left, right) = nodes.split_at_mut(n_left);
    let (interior, separator) = left.split_at_mut(n_interior);
    let mut first = Vec::with_capacity(interior.len());
    dissect(coords, dim, ptr, adj, interior, &mut mark, &mut first);
    let mut second = Vec::with_capacity(right.len());
    dissect(coords, dim, ptr, adj, right, &mut mark, &mut second);
    Some(Bisection {
        first,
        second,
        separator: separator.to_vec(),
    })
}

fn dissect(
    coords: &[f64],
    dim: usize,
    ptr: &[usize],
    adj: &[u32],
    set: &mut [u32],
    mark: &mut [u8],
    out: &mut Vec<u32>,
) {
    if set.len() <= LEAF_SIZE {
        out.extend_from_slice(set);
        return;
    }
    let (n_interior, n_left) = bisect(coords, dim, ptr, adj, set, mark);
    let (left, right) = set.split_at_mut(n_left);
    let (interior, separator) = left.split_at_mut(n_interior);
    dissect(coords, dim, ptr, adj, interior, mark, out);
    dissect(coords, dim, ptr, adj, right, mark, out);
    out.extend_from_slice(separator);
}

/// One bisection of `set` (more than [`LEAF_SIZE`] nodes) by a plane normal to its longest
/// axis, reordering it in place as `[left interior | separator | right]`: the separator is
/// the left nodes with a right neighbour, so no left-interior node is adjacent to a right
/// node. Returns `(n_interior, n_left)`: the left interior is `set[..n_interior]`, the
/// separator `set[n_interior..n_left]`, the right part `set[n_left..]`.
fn bisect(
    coords: &[f64],
    dim: usize,
    ptr: &[usize],
    adj: &[u32],
    set: &mut [u32],
    mark: &mut [u8],
) -> (usize, usize) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &v in set.iter() {
        for i in 0..dim {
            let x = coords[dim * v as usize + i];
            lo[i] = lo[i].min(x);
            hi[i] = hi[i].max(x);
        }
    }
    let axis = (0..dim)
        .max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
        .unwrap_or(0);
    let key = |v: u32| coords[dim * v as usize + axis];
    let mid = set.len() / 2;
    set.select_nth_unstable_by(mid, |&a, &b| key(a).total_cmp(&key(b)).then(a.cmp(&b)));
    let split = key(set[mid]);
    // Left: coordinate ≤ split value (whole grid lines stay together); right: the rest.
    let mut n_left = 0;
    for k in 0..set.len() {
        if key(set[k]) <= split {
            set.swap(k, n_left);
            n_left += 1;
        }
    }
    if n_left == set.len() {
        // All ties along the axis: split by position instead.
        n_left = mid;
    }
    for (k, &v) in set.iter().enumerate() {
        mark[v as usize] = if k < n_left { 1 } else { 2 };
    }
    // Separator: left nodes with a right neighbour; move them to the end of the left part.
    let mut n_sep = 0;
    let mut k = 0;
    while k < n_left - n_sep {
        let v = set[k] as usize;
        if adj[ptr[v]..ptr[v + 1]]
            .iter()
            .any(|&w| mark[w as usize] == 2)
        {
            set.swap(k, n_left - 1 - n_sep);
            n_sep += 1;
        } else {
            k += 1;
        }
    }
    for &v in set.iter() {
        mark[v as usize] = 0;
    }
    (n_left - n_sep, n_left)
}
