//! The part of a mesh that one process of a distributed run holds: a subset of its cells
//! over a subset of its nodes, renumbered, as a mesh of its own
//! ([`crate::parallel::Subdomain`]).

use super::Mesh;
use crate::error::{Error, Result};

/// Marks a node of the whole mesh that the part does not hold.
const ABSENT: u32 = u32::MAX;

impl Mesh {
    /// The mesh of the cells `cells` of this one (local cell `p` is cell `cells[p]`), over
    /// the nodes `nodes` (local node `l` is node `nodes[l]`), which must include every node
    /// of those cells: the coordinates, the cells with their vertices renumbered (each in
    /// its own vertex order, so orientation and measure are unchanged), and the tagged
    /// boundary facets of those cells with their parts. The border between the parts of a
    /// distributed run is not a boundary and carries no facets, so the result is not a
    /// valid mesh on its own and is not validated: it is only ever assembled.
    ///
    /// # Errors
    /// [`Error::Breakdown`] if a node of the cells is missing from `nodes`, or a listed
    /// node or cell does not exist.
    pub(crate) fn restricted(&self, cells: &[u32], nodes: &[u32]) -> Result<Mesh> {
        let d = self.dim;
        let mut local_of = vec![ABSENT; self.n_nodes()];
        let mut coords = Vec::with_capacity(d * nodes.len());
        for (l, &v) in nodes.iter().enumerate() {
            let v = v as usize;
            if v >= self.n_nodes() {
                return Err(Error::Breakdown(format!("no node {v} to restrict to")));
            }
            local_of[v] = l as u32;
            coords.extend_from_slice(&self.coords[d * v..d * v + d]);
        }
        let mut local_cell = vec![ABSENT; self.n_cells()];
        let mut vertices = Vec::with_capacity((d + 1) * cells.len());
        for (p, &c) in cells.iter().enumerate() {
            let c = c as usize;
            if c >= self.n_cells() {
                return Err(Error::Breakdown(format!("no cell {c} to restrict to")));
            }
            local_cell[c] = p as u32;
            for &v in self.cell(c) {
                let l = local_of[v as usize];
                if l == ABSENT {
                    return Err(Error::Breakdown(format!(
                        "node {v} of cell {c} is not among the part's nodes"
                    )));
                }
                vertices.push(l);
            }
        }
        let (mut facets, mut facet_part, mut facet_cell) = (Vec::new(), Vec::new(), Vec::new());
        for f in 0..self.n_facets() {
            let p = local_cell[self.facet_cell[f] as usize];
            if p == ABSENT {
                continue;
            }
            // The facet's nodes are nodes of its cell, so all of them are held.
            facets.extend(
                self.facets[d * f..d * f + d]
                    .iter()
                    .map(|&v| local_of[v as usize]),
            );
            facet_part.push(self.facet_part[f]);
            facet_cell.push(p);
        }
        Ok(Mesh {
            dim: d,
            coords,
            cells: vertices,
            facets,
            facet_part,
            facet_cell,
            part_names: self.part_names.clone(),
            cell_region: if self.cell_region.is_empty() {
                Vec::new()
            } else {
                cells
                    .iter()
                    .map(|&c| self.cell_region[c as usize])
                    .collect()
            },
            region_names: self.region_names.clone(),
            couplings: Vec::new(),
        })
    }
}
