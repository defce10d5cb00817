//! Bodies that pass through each other in the deformed configuration: a check of a solution
//! with contact pairs ([`super::pairing`]), whose notes say where one body lies inside the
//! other.
//!
//! Node-to-segment contact enforces the laws at the slave nodes, along normals and gaps of
//! the reference configuration. Between the slave nodes a master node may enter the slave
//! body (by the sag of the slave facets over a curved master surface, about h²/(8R), or by
//! the coarser side's corners), and a node that is no contact point (beyond the edge of the
//! master surface) is not kept out of the master body at all. After a solve, each pair is
//! checked both ways in the deformed configuration `x + u`: every node of the master part
//! is paired ([`super::pairing::MasterSurface`]) with the deformed slave part, and every
//! node of the slave part with the deformed master part; a negative gap is a node inside
//! the other body, by that depth. The deepest node of each pair and direction is reported
//! when its depth exceeds [`DEPTH_LIMIT`] times the mean diameter of the facets it passes
//! through (a node-to-segment pair on reasonable meshes stays well below it; the sag of a
//! circle's chords is an eighth of h/R of the element size).

use super::pairing::{MasterSurface, Pairing};
use super::ContactBoundary;
use crate::display::significant;
use crate::mesh::Mesh;
use serde::Serialize;

/// Depth of a node inside the other body of a pair, relative to the mean diameter of the
/// facets it passes through, above which the interpenetration is reported.
pub const DEPTH_LIMIT: f64 = 0.1;

/// The deepest node of one part of a contact pair inside the other body, in the deformed
/// configuration.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Interpenetration {
    /// The contact boundary of the pair (an index into the problem's list).
    pub contact: usize,
    /// The part whose node lies inside the other body.
    pub part: String,
    /// The part of the other body it passes through.
    pub through: String,
    /// The mesh node.
    pub node: u32,
    /// Its depth inside the other body (m).
    pub depth: f64,
    /// The mean diameter of the facets of `through` (m), the scale of [`DEPTH_LIMIT`].
    pub element_size: f64,
}

impl Interpenetration {
    /// The note in words.
    pub fn note(&self) -> String {
        format!(
            "bodies pass through each other: node {} of `{}` lies {} m inside the body of \
             `{}` in the deformed configuration x + u ({} of its elements' size; contact \
             pair contact[{}]). Contact between two bodies is enforced at the slave nodes \
             only: refine the coarser side, take the finer side as the slave, or check that \
             the pair names the faces that touch",
            self.node,
            self.part,
            significant(self.depth),
            self.through,
            significant(self.depth / self.element_size),
            self.contact
        )
    }
}

/// The interpenetrations of the contact pairs `contact` of `mesh` under the displacement
/// `u` (m, DOF order): for each pair and direction, its deepest node if deeper than
/// [`DEPTH_LIMIT`] (see the module documentation). Empty without pairs.
pub fn deepest(mesh: &Mesh, contact: &[ContactBoundary], u: &[f64]) -> Vec<Interpenetration> {
    let mut out = Vec::new();
    if contact.iter().all(|c| c.against.is_none()) || u.len() != mesh.dim() * mesh.n_nodes() {
        return out;
    }
    let moved = mesh.displaced(u);
    let names = mesh.part_names();
    for (k, cb) in contact.iter().enumerate() {
        let Some(master) = &cb.against else {
            continue;
        };
        for (part, through) in [(master.part, cb.part), (cb.part, master.part)] {
            let facets: Vec<usize> = moved.part_facets(through).collect();
            if facets.is_empty() {
                continue;
            }
            let size = facets
                .iter()
                .map(|&f| super::placement::facet_diameter(&moved, f))
                .sum::<f64>()
                / facets.len() as f64;
            let surface = MasterSurface::new(&moved, &facets);
            let shared = moved.part_nodes(through);
            let mut worst: Option<(u32, f64)> = None;
            for v in moved.part_nodes(part) {
                if shared.binary_search(&v).is_ok() {
                    continue;
                }
                if let Ok(Pairing::Paired(p)) = surface.pair(v) {
                    if p.gap < -DEPTH_LIMIT * size && worst.is_none_or(|w| p.gap < -w.1) {
                        worst = Some((v, -p.gap));
                    }
                }
            }
            if let Some((node, depth)) = worst {
                out.push(Interpenetration {
                    contact: k,
                    part: names[part].clone(),
                    through: names[through].clone(),
                    node,
                    depth,
                    element_size: size,
                });
            }
        }
    }
    out
}
