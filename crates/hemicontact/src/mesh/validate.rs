//! A mesh validated on construction: every cell positively oriented and non-degenerate,
//! every boundary facet carrying a part, and the cells covering the domain once (the
//! divergence-theorem check and its tolerance are described in [`crate::mesh`]).

use super::facets::{boundary_facets, cell_facets, sorted_key};
use super::listing::{list_cells, overlapping_pairs};
use super::Mesh;
use crate::error::{Error, Result};
use crate::geometry::simplex;

/// Relative tolerance below which a cell counts as degenerate: `|T| ≤ tol · h_T^d`.
pub(crate) const DEGENERATE_TOL: f64 = 1e-12;

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
    /// measures do not sum to the measure enclosed by the boundary; see the [`crate::mesh`]
    /// module documentation).
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
