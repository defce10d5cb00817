//! A mesh from plain arrays with named boundary parts, as a scripting user builds one
//! (numpy arrays, meshio's cell blocks): the parts list only the facets the user names, and
//! the boundary facets in none of them form the part [`super::gmsh::UNTAGGED`], as for a
//! Gmsh file. Nothing is reoriented or dropped: [`Mesh::try_new`] checks the result.

use super::facets::{boundary_facets, sorted_key};
use super::gmsh::UNTAGGED;
use super::Mesh;
use crate::error::{Error, Result};
use std::collections::HashSet;

impl Mesh {
    /// The mesh of dimension `dim` (2: triangles, 3: tetrahedra) with the node coordinates
    /// `coords` (m, `dim` per node), the cells `cells` (`dim + 1` node indices each,
    /// positively oriented) and the named boundary parts `parts` (each a list of facets of
    /// `dim` node indices). Boundary facets in no part form the part `untagged` (added last,
    /// only if there are any; a part named `untagged` receives them).
    ///
    /// # Errors
    /// [`Error::Mesh`] naming the part and facet for an empty or repeated part name or a
    /// facet of the wrong length, and every error of [`Mesh::try_new`] (inverted cells,
    /// facets not on the boundary, overlaps, …).
    pub fn from_parts(
        dim: usize,
        coords: Vec<f64>,
        cells: Vec<u32>,
        parts: &[(String, Vec<u32>)],
    ) -> Result<Mesh> {
        if dim != 2 && dim != 3 {
            return Err(Error::Mesh(format!(
                "dimension {dim} is not supported (2 or 3)"
            )));
        }
        if !cells.len().is_multiple_of(dim + 1) {
            return Err(Error::Mesh(format!(
                "{} cell indices: not a multiple of {} (nodes per cell)",
                cells.len(),
                dim + 1
            )));
        }
        let n_nodes = coords.len() / dim;
        if let Some(i) = cells.iter().position(|&v| v as usize >= n_nodes) {
            return Err(Error::Mesh(format!(
                "cell {}: node index {} is out of range (there are {n_nodes} nodes)",
                i / (dim + 1),
                cells[i]
            )));
        }
        let mut names: Vec<String> = Vec::with_capacity(parts.len() + 1);
        let mut facets = Vec::new();
        let mut facet_part = Vec::new();
        let mut tagged = HashSet::new();
        for (name, list) in parts {
            if name.is_empty() || names.contains(name) {
                return Err(Error::Mesh(format!(
                    "boundary part {name:?}: part names must be non-empty and distinct"
                )));
            }
            if !list.len().is_multiple_of(dim) {
                return Err(Error::Mesh(format!(
                    "boundary part {name:?}: {} node indices, not a multiple of {dim} (nodes \
                     per facet)",
                    list.len()
                )));
            }
            let index = u16::try_from(names.len())
                .map_err(|_| Error::Mesh(format!("{} boundary parts: too many", parts.len())))?;
            names.push(name.clone());
            for f in list.chunks(dim) {
                tagged.insert(sorted_key(f));
                facets.extend_from_slice(f);
                facet_part.push(index);
            }
        }
        let boundary = boundary_facets(dim, &cells).map_err(|s| {
            Error::Mesh(format!(
                "the facet with nodes {:?} is shared by {} cells (at most 2 in a mesh): {}; \
                 cells must not overlap",
                &s.facet[..dim],
                s.cells,
                s.describe(dim, &cells, &|c| format!("cell {c}"))
            ))
        })?;
        let untagged: Vec<[u32; 3]> = boundary
            .iter()
            .map(|(key, _)| *key)
            .filter(|key| !tagged.contains(key))
            .collect();
        if !untagged.is_empty() {
            let index = match names.iter().position(|n| n == UNTAGGED) {
                Some(i) => i,
                None => {
                    names.push(UNTAGGED.to_string());
                    names.len() - 1
                }
            };
            let index = u16::try_from(index)
                .map_err(|_| Error::Mesh(format!("{} boundary parts: too many", names.len())))?;
            for key in untagged {
                facets.extend_from_slice(&key[..dim]);
                facet_part.push(index);
            }
        }
        Mesh::try_new(dim, coords, cells, facets, facet_part, names)
    }
}
