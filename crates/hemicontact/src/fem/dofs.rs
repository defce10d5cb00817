//! Degree-of-freedom numbering and Dirichlet elimination.
//!
//! DOFs are interleaved node-major: component `i` of the displacement at node `n` is DOF
//! `d·n + i` (so a node's DOFs are contiguous, which suits nodal contact blocks). DOFs fixed
//! by a Dirichlet condition are eliminated: the free DOFs get a compact *equation* number
//! `0 … n_free − 1` in increasing DOF order, and fixed DOFs map to [`FIXED`].
//!
//! Example (d = 2, 3 nodes, node 0 clamped): DOFs `0 1 | 2 3 | 4 5` have equation numbers
//! `F F | 0 1 | 2 3`.

/// Marker for a DOF without equation number (it is prescribed).
pub const FIXED: u32 = u32::MAX;

/// The map from DOFs to equation numbers; see the module documentation.
#[derive(Clone, Debug)]
pub struct DofMap {
    dim: usize,
    equation: Vec<u32>,
    n_free: usize,
}

impl DofMap {
    /// Builds the map for `n_nodes` nodes in dimension `dim`; `fixed[dof]` is true for
    /// prescribed DOFs.
    ///
    /// # Panics
    /// If `fixed.len() != dim * n_nodes`.
    #[track_caller]
    pub fn new(dim: usize, n_nodes: usize, fixed: &[bool]) -> Self {
        assert_eq!(fixed.len(), dim * n_nodes);
        let mut n_free = 0usize;
        let equation = fixed
            .iter()
            .map(|&f| {
                if f {
                    FIXED
                } else {
                    n_free += 1;
                    (n_free - 1) as u32
                }
            })
            .collect();
        DofMap {
            dim,
            equation,
            n_free,
        }
    }

    /// Spatial dimension d.
    #[inline]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Total number of DOFs, `d · n_nodes`.
    #[inline]
    pub fn n_dofs(&self) -> usize {
        self.equation.len()
    }

    /// Number of free DOFs (equations).
    #[inline]
    pub fn n_free(&self) -> usize {
        self.n_free
    }

    /// Equation number of DOF `dof`, or [`FIXED`].
    #[inline]
    pub fn equation(&self, dof: usize) -> u32 {
        self.equation[dof]
    }

    /// Equation numbers of all DOFs (length [`DofMap::n_dofs`]).
    #[inline]
    pub fn equations(&self) -> &[u32] {
        &self.equation
    }

    /// Whether DOF `dof` is prescribed.
    #[inline]
    pub fn is_fixed(&self, dof: usize) -> bool {
        self.equation[dof] == FIXED
    }

    /// The map of the nodes `nodes` (local node `l` is node `nodes[l]` of this map): each
    /// local DOF prescribed exactly when its DOF here is, the free ones numbered afresh in
    /// local order. What a process of a distributed run holds of the whole problem's map, so
    /// that nodes at the border of its part keep the prescriptions made outside it.
    ///
    /// # Panics
    /// If a node is not one of this map's.
    #[track_caller]
    pub fn restricted(&self, nodes: &[u32]) -> DofMap {
        let d = self.dim;
        let fixed: Vec<bool> = nodes
            .iter()
            .flat_map(|&v| (0..d).map(move |k| self.is_fixed(d * v as usize + k)))
            .collect();
        DofMap::new(d, nodes.len(), &fixed)
    }
}
