//! Simplicial meshes with named boundary parts.
//!
//! A [`Mesh`] holds triangles (d = 2) or tetrahedra (d = 3) in flat arrays:
//!
//! | array | shape | content |
//! |-------|-------|---------|
//! | `coords` | `n_nodes × d` | node coordinates, node-major |
//! | `cells` | `n_cells × (d+1)` | vertex indices, positively oriented |
//! | `facets` | `n_facets × d` | vertex indices of tagged boundary facets |
//! | `facet_part` | `n_facets` | index into `part_names` |
//! | `facet_cell` | `n_facets` | the cell a boundary facet belongs to (for outward normals) |
//!
//! | `cell_region` | `n_cells` (or empty) | index into `region_names` |
//!
//! Boundary parts carry names (`bottom`, `top`, `left`, `right` for generated rectangles,
//! Gmsh physical-group names for read meshes) which a scenario maps to Γ_D, Γ_N and Γ_C.
//! A mesh is validated on construction ([`Mesh::try_new`]) and immutable afterwards: every
//! cell is positively oriented and non-degenerate, every boundary facet carries a part, and
//! the cells cover the domain once.
//!
//! Cells may carry named regions too ([`Mesh::with_regions`]: Gmsh physical groups of
//! cells, boxes of a generated mesh, a tag array from a script), to which a scenario
//! assigns materials. A mesh without regions has one unnamed region, index 0.
//!
//! # The cells cover the domain once
//!
//! Cells that are each positively oriented may still overlap: a mesh folded over itself (a
//! node moved past its neighbour, the cells around it reoriented by hand or by a tool) has
//! interior facets with both of their cells on the same side. Such a mesh is caught by the
//! divergence theorem applied to the position field `x` (`div x = d`):
//!
//! ```text
//! Σ_T |T|  =  |Ω|  =  (1/d) ∮_∂Ω x·n dS  =  (1/d) Σ_F (x_F − o)·n_F |F|
//! ```
//!
//! over the boundary facets F with their outward normals n_F (away from the opposite vertex
//! of their cell), x_F any vertex of F and o the centre of the bounding box (the identity
//! holds for any o; the centre keeps the terms small). For a mesh whose cells tile the
//! domain the two sides are equal up to round-off, as the contributions of each interior
//! facet cancel; each interior facet whose two cells lie on the same side adds
//! `(2/d) (x_F − o)·n_F |F|` instead, and a folded region R changes the cell sum by `2 |R|`.
//!
//! Tolerance: each term is a determinant of coordinate differences (a 2 × 2 or 3 × 3
//! determinant for a cell, a cross product dotted with `x_F − o` for a facet). Standard
//! floating-point error analysis bounds its rounding error by a few (at most 4d) units of
//! round-off ε times its *scale*: `h_T^d` for a cell of diameter h_T, `|x_F − o| h_F^{d−1}`
//! for a facet (h_F its longest edge). Both sums are compensated (Neumaier), so summation
//! adds only ε relative. The mesh is accepted when
//! `|Σ_T |T| − (1/d) Σ_F (x_F − o)·n_F |F|| ≤ 8d ε (Σ_T h_T^d + Σ_F |x_F − o| h_F^{d−1})`,
//! twice the rounding bound; since `h_T^d > |T|`, this is at least `8d ε |Ω|`. A fold is
//! missed only when `2 |R|` is below that tolerance, about `8d ε N h^d` for N cells of size h:
//! a region of the order of the round-off of the whole domain's measure. (Folds with cells
//! of both orientations, the usual tangle, are refused before, as inverted cells.)

mod arrays;
pub(crate) mod facets;
pub mod generate;
pub mod gmsh;
pub(crate) mod listing;
mod regions;
mod submesh;
pub(crate) mod validate;

use crate::geometry::simplex;

/// A validated simplicial mesh; see the module documentation for the array layout.
#[derive(Clone, Debug)]
pub struct Mesh {
    dim: usize,
    coords: Vec<f64>,
    cells: Vec<u32>,
    facets: Vec<u32>,
    facet_part: Vec<u16>,
    facet_cell: Vec<u32>,
    part_names: Vec<String>,
    cell_region: Vec<u16>,
    region_names: Vec<String>,
    couplings: Vec<[u32; 2]>,
}

impl Mesh {
    /// Spatial dimension d (2 or 3).
    #[inline]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Number of nodes.
    #[inline]
    pub fn n_nodes(&self) -> usize {
        self.coords.len() / self.dim
    }

    /// Number of cells.
    #[inline]
    pub fn n_cells(&self) -> usize {
        self.cells.len() / (self.dim + 1)
    }

    /// Number of tagged boundary facets.
    #[inline]
    pub fn n_facets(&self) -> usize {
        self.facet_part.len()
    }

    /// Coordinates of node `n` (length d).
    #[inline]
    pub fn node(&self, n: usize) -> &[f64] {
        &self.coords[n * self.dim..(n + 1) * self.dim]
    }

    /// All coordinates, `n_nodes × d`, node-major.
    #[inline]
    pub fn coords(&self) -> &[f64] {
        &self.coords
    }

    /// Vertex indices of cell `c` (length d + 1).
    #[inline]
    pub fn cell(&self, c: usize) -> &[u32] {
        let nv = self.dim + 1;
        &self.cells[c * nv..(c + 1) * nv]
    }

    /// All cells, `n_cells × (d+1)`.
    #[inline]
    pub fn cells(&self) -> &[u32] {
        &self.cells
    }

    /// Vertex coordinates of cell `c`, padded to 4 points of 3 coordinates.
    #[inline]
    pub fn cell_coords(&self, c: usize) -> [[f64; 3]; 4] {
        let mut x = [[0.0; 3]; 4];
        for (a, &v) in self.cell(c).iter().enumerate() {
            x[a][..self.dim].copy_from_slice(self.node(v as usize));
        }
        x
    }

    /// Vertex indices of boundary facet `f` (length d).
    #[inline]
    pub fn facet(&self, f: usize) -> &[u32] {
        &self.facets[f * self.dim..(f + 1) * self.dim]
    }

    /// Part index of boundary facet `f`.
    #[inline]
    pub fn facet_part(&self, f: usize) -> usize {
        self.facet_part[f] as usize
    }

    /// The cell boundary facet `f` belongs to.
    #[inline]
    pub fn facet_cell(&self, f: usize) -> usize {
        self.facet_cell[f] as usize
    }

    /// Names of the boundary parts.
    pub fn part_names(&self) -> &[String] {
        &self.part_names
    }

    /// Index of the part named `name`, if any.
    pub fn part_index(&self, name: &str) -> Option<usize> {
        self.part_names.iter().position(|p| p == name)
    }

    /// Facets of part `part`.
    pub fn part_facets(&self, part: usize) -> impl Iterator<Item = usize> + '_ {
        (0..self.n_facets()).filter(move |&f| self.facet_part(f) == part)
    }

    /// Sorted, unique nodes of the facets of part `part`.
    pub fn part_nodes(&self, part: usize) -> Vec<u32> {
        let mut nodes: Vec<u32> = self
            .part_facets(part)
            .flat_map(|f| self.facet(f).iter().copied())
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }

    /// Measure of boundary facet `f` (length in 2D, area in 3D) and its outward unit normal.
    pub fn facet_measure_normal(&self, f: usize) -> (f64, [f64; 3]) {
        let v = self.facet(f);
        let mut p = [[0.0; 3]; 3];
        for (a, &n) in v.iter().enumerate() {
            p[a][..self.dim].copy_from_slice(self.node(n as usize));
        }
        let mut nrm = if self.dim == 2 {
            [p[1][1] - p[0][1], p[0][0] - p[1][0], 0.0]
        } else {
            let a = [p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]];
            let b = [p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]];
            simplex::cross(&a, &b)
        };
        let len = nrm.iter().map(|x| x * x).sum::<f64>().sqrt();
        let measure = if self.dim == 2 { len } else { 0.5 * len };
        for x in nrm.iter_mut() {
            *x /= len;
        }
        // Orient outward: away from the opposite vertex of the owning cell.
        let cell = self.cell(self.facet_cell(f));
        if let Some(&opp) = cell.iter().find(|n| !v.contains(n)) {
            let q = self.node(opp as usize);
            let dot: f64 = (0..self.dim).map(|i| (p[0][i] - q[i]) * nrm[i]).sum();
            if dot < 0.0 {
                for x in nrm.iter_mut() {
                    *x = -*x;
                }
            }
        }
        (measure, nrm)
    }

    /// Total measure of the mesh (area or volume).
    pub fn measure(&self) -> f64 {
        (0..self.n_cells())
            .map(|c| simplex::signed_measure(self.dim, &self.cell_coords(c)))
            .sum()
    }

    /// The same mesh with every coordinate divided by `length` (m): the mesh in units of
    /// `length`, as used to make the problem dimensionless.
    pub fn in_units_of(&self, length: f64) -> Mesh {
        let mut m = self.clone();
        for x in m.coords.iter_mut() {
            *x /= length;
        }
        m
    }

    /// The same mesh with every node moved by the displacement `u` (m, DOF order: d
    /// entries per node): the deformed configuration `x + u`, for geometric checks of a
    /// solution. It is not validated again (a displacement may invert cells).
    pub fn displaced(&self, u: &[f64]) -> Mesh {
        let mut m = self.clone();
        for (x, du) in m.coords.iter_mut().zip(u) {
            *x += du;
        }
        m
    }

    /// Bounding box `(min, max)` of the nodes (unused coordinates are zero).
    pub fn bounding_box(&self) -> ([f64; 3], [f64; 3]) {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for n in 0..self.n_nodes() {
            for (i, &x) in self.node(n).iter().enumerate() {
                lo[i] = lo[i].min(x);
                hi[i] = hi[i].max(x);
            }
        }
        for i in self.dim..3 {
            lo[i] = 0.0;
            hi[i] = 0.0;
        }
        (lo, hi)
    }

    /// Node-to-node adjacency (nodes sharing a cell, or coupled by
    /// [`Mesh::with_couplings`]; excluding the node itself) in CSR form: the neighbours of
    /// node `n` are `adj[ptr[n]..ptr[n+1]]`, sorted. It is the graph of the system's matrix
    /// (its pattern, its fill-reducing ordering and its partition among processes).
    pub fn node_adjacency(&self) -> (Vec<usize>, Vec<u32>) {
        let (ptr, adj) = self.node_adjacency_of(0..self.n_cells());
        if self.couplings.is_empty() {
            return (ptr, adj);
        }
        let n = self.n_nodes();
        let mut extra: Vec<Vec<u32>> = vec![Vec::new(); n];
        for &[a, b] in &self.couplings {
            extra[a as usize].push(b);
            extra[b as usize].push(a);
        }
        let mut out_ptr = Vec::with_capacity(n + 1);
        out_ptr.push(0);
        let mut out = Vec::with_capacity(adj.len() + 2 * self.couplings.len());
        for (a, more) in extra.iter_mut().enumerate() {
            more.extend_from_slice(&adj[ptr[a]..ptr[a + 1]]);
            more.sort_unstable();
            more.dedup();
            out.extend_from_slice(more);
            out_ptr.push(out.len());
        }
        (out_ptr, out)
    }

    /// The same mesh with the node pairs `couplings` coupled outside the cells: the slave
    /// node of a contact pair and the nodes of its master facet, whose equations the
    /// contact term couples ([`Mesh::node_adjacency`]). Pairs of a node with itself are
    /// ignored.
    pub fn with_couplings(mut self, couplings: Vec<[u32; 2]>) -> Mesh {
        self.couplings = couplings.into_iter().filter(|p| p[0] != p[1]).collect();
        self
    }

    /// The node pairs coupled outside the cells ([`Mesh::with_couplings`]); empty for a mesh
    /// read or generated.
    pub fn couplings(&self) -> &[[u32; 2]] {
        &self.couplings
    }

    /// As [`Mesh::node_adjacency`], counting only the cells `cells` (each at most once): two
    /// nodes are neighbours when one of these cells holds both, and a node of none of them
    /// has no neighbours.
    pub fn node_adjacency_of<I>(&self, cells: I) -> (Vec<usize>, Vec<u32>)
    where
        I: Iterator<Item = usize> + Clone,
    {
        let n = self.n_nodes();
        let nv = self.dim + 1;
        // Bucket the other vertices of every cell by node (counting sort), then sort and
        // deduplicate each node's short list: linear in the cells, where one sort of all
        // vertex pairs was not.
        let mut start = vec![0usize; n + 1];
        for c in cells.clone() {
            for &a in self.cell(c) {
                start[a as usize + 1] += nv - 1;
            }
        }
        for i in 0..n {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut bucket = vec![0u32; start[n]];
        for c in cells {
            let cell = self.cell(c);
            for &a in cell {
                for &b in cell {
                    if a != b {
                        bucket[fill[a as usize]] = b;
                        fill[a as usize] += 1;
                    }
                }
            }
        }
        let mut ptr = Vec::with_capacity(n + 1);
        ptr.push(0);
        let mut adj = Vec::with_capacity(bucket.len() / 2);
        for a in 0..n {
            let list = &mut bucket[start[a]..fill[a]];
            list.sort_unstable();
            let first = adj.len();
            for &b in list.iter() {
                if adj.len() == first || adj[adj.len() - 1] != b {
                    adj.push(b);
                }
            }
            ptr.push(adj.len());
        }
        (ptr, adj)
    }
}
