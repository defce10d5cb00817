//! Facet topology of a simplicial mesh: the facets of its cells, sorted so that the two
//! cells of an interior facet are neighbours, and the boundary facets (the facets of exactly
//! one cell). A facet is keyed by its d vertex indices, sorted and padded with `u32::MAX`.

/// A facet shared by more than two cells, which makes a mesh non-manifold.
pub(crate) struct SharedFacet {
    /// Vertices of the facet, sorted, padded with `u32::MAX`.
    pub facet: [u32; 3],
    /// Number of cells it belongs to (3 or more).
    pub cells: usize,
    /// The cells it belongs to, in increasing order.
    pub owners: Vec<u32>,
}

impl SharedFacet {
    /// The cells sharing the facet in words, `name` naming cell `c`, and the pairs among
    /// them with the same vertices (a repeated cell): "cell 0, cell 1 and cell 2; cell 2
    /// repeats cell 0 (the same nodes)". `cells` are the mesh's cells (d + 1 vertices
    /// each).
    pub fn describe(&self, d: usize, cells: &[u32], name: &dyn Fn(usize) -> String) -> String {
        let owners: Vec<usize> = self.owners.iter().map(|&c| c as usize).collect();
        let mut text = super::listing::list_cells(&owners, name);
        let vertices = |c: usize| {
            let mut v = [u32::MAX; 4];
            v[..=d].copy_from_slice(&cells[(d + 1) * c..(d + 1) * (c + 1)]);
            v[..=d].sort_unstable();
            v
        };
        for (k, &b) in owners.iter().enumerate() {
            if let Some(&a) = owners[..k].iter().find(|&&a| vertices(a) == vertices(b)) {
                text.push_str(&format!(
                    "; {} repeats {} (the same nodes)",
                    name(b),
                    name(a)
                ));
            }
        }
        text
    }
}

/// Every facet of every cell of a mesh of dimension `d` (`cells`: d + 1 vertices each), as
/// `(sorted vertices padded with u32::MAX, cell)`, sorted: the two cells of an interior facet
/// are neighbours in the list.
pub(crate) fn cell_facets(d: usize, cells: &[u32]) -> Vec<([u32; 3], u32)> {
    let nv = d + 1;
    let n_cells = cells.len() / nv;
    let mut all: Vec<([u32; 3], u32)> = Vec::with_capacity(n_cells * nv);
    for (c, cell) in cells.chunks_exact(nv).enumerate() {
        for skip in 0..nv {
            all.push((facet_key(cell, skip), c as u32));
        }
    }
    all.sort_unstable();
    all
}

/// The boundary facets of the cells `cells` (d + 1 vertex indices each) of a mesh of
/// dimension `d`: the facets of exactly one cell, as `(sorted vertices padded with u32::MAX,
/// cell)`, in increasing order of their vertices (so that [`sorted_key`] of a facet can be
/// looked up by binary search).
///
/// # Errors
/// The first facet (in that order) shared by more than two cells.
pub(crate) fn boundary_facets(
    d: usize,
    cells: &[u32],
) -> std::result::Result<Vec<([u32; 3], u32)>, SharedFacet> {
    let all = cell_facets(d, cells);
    let mut boundary: Vec<([u32; 3], u32)> = Vec::new();
    let mut i = 0;
    while i < all.len() {
        let mut j = i + 1;
        while j < all.len() && all[j].0 == all[i].0 {
            j += 1;
        }
        match j - i {
            1 => boundary.push(all[i]),
            2 => {}
            k => {
                return Err(SharedFacet {
                    facet: all[i].0,
                    cells: k,
                    owners: all[i..j].iter().map(|x| x.1).collect(),
                })
            }
        }
        i = j;
    }
    Ok(boundary)
}

/// The vertices `v` of a facet (d of them), sorted and padded with `u32::MAX`: the key by
/// which [`boundary_facets`] lists it.
pub(crate) fn sorted_key(v: &[u32]) -> [u32; 3] {
    let mut k = [u32::MAX; 3];
    k[..v.len()].copy_from_slice(v);
    k[..v.len()].sort_unstable();
    k
}

/// The key of the facet of `cell` opposite its vertex `skip`.
fn facet_key(cell: &[u32], skip: usize) -> [u32; 3] {
    let mut k = [u32::MAX; 3];
    let mut j = 0;
    for (a, &v) in cell.iter().enumerate() {
        if a != skip {
            k[j] = v;
            j += 1;
        }
    }
    k[..j].sort_unstable();
    k
}
