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
mod regions;
mod submesh;

use crate::error::{Error, Result};
use crate::geometry::simplex;
use facets::{boundary_facets, cell_facets, sorted_key};

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

/// Relative tolerance below which a cell counts as degenerate: `|T| ≤ tol · h_T^d`.
pub(crate) const DEGENERATE_TOL: f64 = 1e-12;

/// Cells named in one error message at most (then "and N more").
const LISTED: usize = 10;

/// Names of at most [`LISTED`] cells, then how many more: "cell 3, cell 7 and 2 more".
pub(crate) fn list_cells(cells: &[usize], name: &dyn Fn(usize) -> String) -> String {
    let mut out: Vec<String> = cells.iter().take(LISTED).map(|&c| name(c)).collect();
    if cells.len() > LISTED {
        out.push(format!("{} more", cells.len() - LISTED));
    }
    match out.len() {
        0 => String::new(),
        1 => out.remove(0),
        n => format!("{} and {}", out[..n - 1].join(", "), out[n - 1]),
    }
}

/// The pairs of cells `folds` (the two cells of an interior facet, on the same side of it)
/// in words: "the cells on both sides of N interior facet(s) lie on the same side of it
/// (they overlap): cell 0 and cell 2; …", at most [`LISTED`] pairs, then how many more.
fn overlapping_pairs(folds: &[(usize, usize)], name: &dyn Fn(usize) -> String) -> String {
    let pairs: Vec<String> = folds
        .iter()
        .take(LISTED)
        .map(|&(a, b)| format!("{} and {}", name(a), name(b)))
        .collect();
    format!(
        "the cells on both sides of {} interior facet(s) lie on the same side of it (they \
         overlap): {}{}",
        folds.len(),
        pairs.join("; "),
        if folds.len() > LISTED {
            format!(" and {} more", folds.len() - LISTED)
        } else {
            String::new()
        }
    )
}

/// Compensated (Neumaier) sum: the rounding error of the sum is ε relative to its value
/// plus ε² relative to the sum of absolute values, whatever the number of terms.
#[derive(Clone, Copy, Default)]
struct CompensatedSum {
    sum: f64,
    carry: f64,
}

impl CompensatedSum {
    fn add(&mut self, x: f64) {
        let t = self.sum + x;
        if self.sum.abs() >= x.abs() {
            self.carry += (self.sum - t) + x;
        } else {
            self.carry += (x - t) + self.sum;
        }
        self.sum = t;
    }

    fn value(self) -> f64 {
        self.sum + self.carry
    }
}

impl Mesh {
    /// Builds and validates a mesh.
    ///
    /// `facets` lists boundary facets (d vertices each) with their part index `facet_part`
    /// into `part_names`.
    ///
    /// # Errors
    /// [`Error::Mesh`] if the dimension is not 2 or 3, array lengths do not match, a vertex
    /// index is out of range, a coordinate is not finite, a cell is inverted (negatively
    /// oriented: a clockwise triangle, a left-handed tetrahedron) or degenerate, a tagged
    /// facet is not on the boundary, a boundary facet has no part, or the cells overlap (their
    /// measures do not sum to the measure enclosed by the boundary; see the module
    /// documentation).
    pub fn try_new(
        dim: usize,
        coords: Vec<f64>,
        cells: Vec<u32>,
        facets: Vec<u32>,
        facet_part: Vec<u16>,
        part_names: Vec<String>,
    ) -> Result<Self> {
        Self::try_new_named(dim, coords, cells, facets, facet_part, part_names, &|c| {
            format!("cell {c}")
        })
    }

    /// [`Mesh::try_new`], naming cell `c` in error messages by `name(c)` (a file reader names
    /// its elements by their tags).
    pub(crate) fn try_new_named(
        dim: usize,
        coords: Vec<f64>,
        cells: Vec<u32>,
        facets: Vec<u32>,
        facet_part: Vec<u16>,
        part_names: Vec<String>,
        name: &dyn Fn(usize) -> String,
    ) -> Result<Self> {
        if dim != 2 && dim != 3 {
            return Err(Error::Mesh(format!(
                "dimension {dim} is not supported (2 or 3)"
            )));
        }
        let nv = dim + 1;
        if !coords.len().is_multiple_of(dim)
            || !cells.len().is_multiple_of(nv)
            || !facets.len().is_multiple_of(dim)
        {
            return Err(Error::Mesh(
                "array lengths do not match the dimension".into(),
            ));
        }
        if facet_part.len() * dim != facets.len() {
            return Err(Error::Mesh(
                "one part index per boundary facet is required".into(),
            ));
        }
        let n_nodes = coords.len() / dim;
        if n_nodes > u32::MAX as usize / 2 {
            return Err(Error::Mesh(format!(
                "{n_nodes} nodes exceed the supported maximum"
            )));
        }
        if let Some(i) = coords.iter().position(|x| !x.is_finite()) {
            return Err(Error::Mesh(format!(
                "node {} has a non-finite coordinate",
                i / dim
            )));
        }
        if let Some(i) = cells
            .iter()
            .chain(facets.iter())
            .position(|&v| v as usize >= n_nodes)
        {
            return Err(Error::Mesh(format!(
                "vertex index {} out of range (mesh has {n_nodes} nodes)",
                cells
                    .iter()
                    .chain(facets.iter())
                    .nth(i)
                    .copied()
                    .unwrap_or(0)
            )));
        }
        if let Some(&p) = facet_part.iter().find(|&&p| p as usize >= part_names.len()) {
            return Err(Error::Mesh(format!("facet part index {p} has no name")));
        }
        if cells.is_empty() {
            return Err(Error::Mesh("the mesh has no cells".into()));
        }
        let mut mesh = Mesh {
            dim,
            coords,
            cells,
            facets,
            facet_part,
            facet_cell: Vec::new(),
            part_names,
            cell_region: Vec::new(),
            region_names: Vec::new(),
            couplings: Vec::new(),
        };
        mesh.check_cells(name)?;
        mesh.facet_cell = mesh.match_boundary_facets(name)?;
        mesh.check_cover(name)?;
        Ok(mesh)
    }

    fn check_cells(&self, name: &dyn Fn(usize) -> String) -> Result<()> {
        let mut inverted = Vec::new();
        for c in 0..self.n_cells() {
            let x = self.cell_coords(c);
            let m = simplex::signed_measure(self.dim, &x);
            let h = diameter(self.dim, &x[..=self.dim]);
            if !m.is_finite() || !h.is_finite() {
                return Err(Error::Mesh(format!(
                    "{} (vertices {:?}) has a non-finite measure: coordinates too large",
                    name(c),
                    self.cell(c)
                )));
            }
            // (NaN measures were rejected just above.)
            if m.abs() <= DEGENERATE_TOL * h.powi(self.dim as i32) {
                return Err(Error::Mesh(format!(
                    "{} (vertices {:?}) is degenerate: measure {m:e}",
                    name(c),
                    self.cell(c)
                )));
            }
            if m < 0.0 {
                inverted.push(c);
            }
        }
        if let Some(&first) = inverted.first() {
            let (negative, positive) = if self.dim == 2 {
                ("clockwise", "counterclockwise triangles")
            } else {
                ("left-handed", "right-handed tetrahedra")
            };
            return Err(Error::Mesh(format!(
                "{} of {} cells are inverted ({negative}, negative signed measure): {} (the \
                 first has vertices {:?} and signed measure {:e}); every cell must be positively \
                 oriented ({positive})",
                inverted.len(),
                self.n_cells(),
                list_cells(&inverted, name),
                self.cell(first),
                simplex::signed_measure(self.dim, &self.cell_coords(first))
            )));
        }
        Ok(())
    }

    /// Checks that the cells cover the domain once: their measures sum to the measure
    /// enclosed by the boundary (see the module documentation). Requires `facet_cell`.
    fn check_cover(&self, name: &dyn Fn(usize) -> String) -> Result<()> {
        let d = self.dim;
        let (lo, hi) = self.bounding_box();
        let o: [f64; 3] = std::array::from_fn(|i| 0.5 * (lo[i] + hi[i]));
        let mut cells = CompensatedSum::default();
        let mut scale = CompensatedSum::default();
        for c in 0..self.n_cells() {
            let x = self.cell_coords(c);
            cells.add(simplex::signed_measure(d, &x));
            scale.add(diameter(d, &x[..=d]).powi(d as i32));
        }
        let mut enclosed = CompensatedSum::default();
        for f in 0..self.n_facets() {
            let (measure, n) = self.facet_measure_normal(f);
            let v = self.facet(f);
            let x0 = self.node(v[0] as usize);
            let r: [f64; 3] = std::array::from_fn(|i| if i < d { x0[i] - o[i] } else { 0.0 });
            let dot: f64 = (0..d).map(|i| r[i] * n[i]).sum();
            enclosed.add(dot * measure / d as f64);
            let mut p = [[0.0; 3]; 3];
            for (a, &w) in v.iter().enumerate() {
                p[a][..d].copy_from_slice(self.node(w as usize));
            }
            let len = (0..d).map(|i| r[i] * r[i]).sum::<f64>().sqrt();
            scale.add(len * diameter(d, &p[..d]).powi(d as i32 - 1));
        }
        let (sum, enclosed) = (cells.value(), enclosed.value());
        let tol = 8.0 * d as f64 * f64::EPSILON * scale.value();
        if (sum - enclosed).abs() <= tol {
            return Ok(());
        }
        let folds = self.folded_facets();
        let (what, measure) = if d == 2 {
            ("areas", "an area")
        } else {
            ("volumes", "a volume")
        };
        let located = if folds.is_empty() {
            String::new()
        } else {
            format!("; {}", overlapping_pairs(&folds, name))
        };
        Err(Error::Mesh(format!(
            "the cell {what} sum to {sum:e} but the boundary encloses {measure} of {enclosed:e} \
             (divergence theorem, (1/d) ∮ x·n dS over the boundary facets; round-off allows a \
             difference of {tol:.1e}): cells overlap or the mesh is folded over \
             itself{located}; every point of the domain must be covered by exactly one cell"
        )))
    }

    /// Interior facets whose two cells lie on the same side of them (a fold), as pairs of
    /// cells.
    fn folded_facets(&self) -> Vec<(usize, usize)> {
        let d = self.dim;
        let all = cell_facets(d, &self.cells);
        // The side of the facet `key` (vertices in sorted order) that vertex `v` is on: the
        // sign of the simplex (facet, v).
        let side = |key: &[u32; 3], v: u32| -> bool {
            let mut x = [[0.0; 3]; 4];
            for (a, &w) in key[..d].iter().enumerate() {
                x[a][..d].copy_from_slice(self.node(w as usize));
            }
            x[d][..d].copy_from_slice(self.node(v as usize));
            simplex::signed_measure(d, &x) > 0.0
        };
        let opposite = |c: u32, key: &[u32; 3]| -> u32 {
            self.cell(c as usize)
                .iter()
                .copied()
                .find(|v| !key[..d].contains(v))
                .unwrap_or(0)
        };
        all.windows(2)
            .filter(|w| w[0].0 == w[1].0)
            .filter(|w| {
                let key = &w[0].0;
                side(key, opposite(w[0].1, key)) == side(key, opposite(w[1].1, key))
            })
            .map(|w| (w[0].1 as usize, w[1].1 as usize))
            .collect()
    }

    /// Finds the boundary facets (facets of exactly one cell) and matches them against the
    /// tagged facets. Returns the owning cell of each tagged facet. A tagged facet that is
    /// not on the boundary because cells overlap is reported as the overlap, naming the
    /// cells by `name`.
    fn match_boundary_facets(&self, name: &dyn Fn(usize) -> String) -> Result<Vec<u32>> {
        let d = self.dim;
        let boundary = boundary_facets(d, &self.cells).map_err(|shared| {
            Error::Mesh(format!(
                "facet {:?} is shared by {} cells (non-manifold mesh): {}",
                &shared.facet[..d],
                shared.cells,
                shared.describe(d, &self.cells, name)
            ))
        })?;
        let mut facet_cell = vec![u32::MAX; self.n_facets()];
        let mut tagged: Vec<([u32; 3], usize)> = (0..self.n_facets())
            .map(|f| (sorted_key(self.facet(f)), f))
            .collect();
        tagged.sort_unstable();
        for w in tagged.windows(2) {
            if w[0].0 == w[1].0 {
                return Err(Error::Mesh(format!(
                    "boundary facet {:?} is tagged twice (parts `{}` and `{}`)",
                    &w[0].0[..d],
                    self.part_names[self.facet_part[w[0].1] as usize],
                    self.part_names[self.facet_part[w[1].1] as usize]
                )));
            }
        }
        for (key, cell) in &boundary {
            match tagged.binary_search_by(|(k, _)| k.cmp(key)) {
                Ok(pos) => facet_cell[tagged[pos].1] = *cell,
                Err(_) => {
                    let untagged =
                        format!("boundary facet {:?} belongs to no boundary part", &key[..d]);
                    let folds = self.folded_facets();
                    if !folds.is_empty() {
                        return Err(Error::Mesh(format!(
                            "{untagged}: cells overlap: {}; every point of the domain must be \
                             covered by exactly one cell",
                            overlapping_pairs(&folds, name)
                        )));
                    }
                    return Err(Error::Mesh(untagged));
                }
            }
        }
        if let Some(f) = facet_cell.iter().position(|&c| c == u32::MAX) {
            let tagged = format!(
                "tagged facet {:?} (part `{}`) is not on the boundary",
                self.facet(f),
                self.part_names[self.facet_part[f] as usize]
            );
            // Overlapping cells make boundary facets interior: say so, naming them.
            let folds = self.folded_facets();
            if !folds.is_empty() {
                return Err(Error::Mesh(format!(
                    "{tagged}: cells overlap: {}; every point of the domain must be covered \
                     by exactly one cell",
                    overlapping_pairs(&folds, name)
                )));
            }
            return Err(Error::Mesh(tagged));
        }
        Ok(facet_cell)
    }

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

/// Largest distance between two of the points `x` (the first d coordinates).
pub(crate) fn diameter(d: usize, x: &[[f64; 3]]) -> f64 {
    let mut h: f64 = 0.0;
    for a in 0..x.len() {
        for b in 0..a {
            let e: f64 = (0..d).map(|i| (x[a][i] - x[b][i]).powi(2)).sum();
            h = h.max(e);
        }
    }
    h.sqrt()
}
