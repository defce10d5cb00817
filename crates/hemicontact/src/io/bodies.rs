//! The forces on each body of a solution (the `bodies` of `summary.json`).
//!
//! The bodies are the connected components of the mesh (cells sharing nodes), numbered by
//! their smallest node, as [`crate::rigid::bodies`] finds them. The resultants on body
//! B, each a sum over its nodes of a nodal force vector:
//!
//! - `load`: the external loads `f` (tractions and body force);
//! - `reaction`: the supports' reactions (the force of each prescribed DOF);
//! - `contact_force`: the interface forces of contact, `R_i` at its contact points (the
//!   force of the foundation, obstacle or other body on it), and `−N_j R_i` at its nodes
//!   that are master nodes of a pair's point i (the reaction of the other body, spread with
//!   the shape functions of the master facet at the projection).
//!
//! Equilibrium of B is `load + reaction + contact_force = 0` (the internal forces of a body
//! sum to zero under any rigid translation), which `imbalance` measures; across a pair, the
//! contact forces on the two bodies are equal and opposite.

use crate::problem::Problem;
use crate::solver::Solution;
use serde::Serialize;
use std::collections::HashMap;

/// The resultant forces on one body of the mesh.
///
/// Forces are in N in 3D and N/m (per unit thickness) in 2D, one component per spatial
/// dimension, in global coordinates.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BodySummary {
    /// Number of nodes of the body.
    pub nodes: usize,
    /// Number of cells of the body.
    pub cells: usize,
    /// The cell regions its cells belong to (names; `untagged` for cells in none, empty
    /// for a mesh without regions).
    pub regions: Vec<String>,
    /// The boundary parts with a facet on the body (names).
    pub parts: Vec<String>,
    /// Resultant of the external loads on it, `Σ f` over its nodes (N; N/m in 2D).
    pub load: Vec<f64>,
    /// Resultant of the supports' reactions on it (N; N/m in 2D).
    pub reaction: Vec<f64>,
    /// Resultant of the interface forces of contact on it: `Σ R_i` over its contact points
    /// and `Σ −N_j R_i` over its master nodes (N; N/m in 2D).
    pub contact_force: Vec<f64>,
    /// `‖load + reaction + contact_force‖ / max(‖load‖, ‖reaction‖, ‖contact_force‖)`
    /// (dimensionless; 0 for a body on which no force acts): its equilibrium.
    pub imbalance: f64,
}

/// The force resultants on each body of `problem`'s mesh in `solution`, in the order of
/// the bodies (by smallest node). Contact results whose point `problem` does not have are
/// ignored (none in a solution of `problem`).
pub fn bodies(problem: &Problem, solution: &Solution) -> Vec<BodySummary> {
    let mesh = &problem.mesh;
    let d = mesh.dim();
    let (body_of, found) = crate::rigid::bodies(mesh);
    let mut out: Vec<BodySummary> = found
        .iter()
        .map(|b| BodySummary {
            nodes: b.nodes.len(),
            cells: 0,
            regions: Vec::new(),
            parts: Vec::new(),
            load: vec![0.0; d],
            reaction: vec![0.0; d],
            contact_force: vec![0.0; d],
            imbalance: 0.0,
        })
        .collect();
    let body = |v: u32| body_of[v as usize] as usize;
    let mut region_seen = vec![vec![false; mesh.region_names().len()]; out.len()];
    for c in 0..mesh.n_cells() {
        let b = body(mesh.cell(c)[0]);
        out[b].cells += 1;
        if let Some(seen) = region_seen[b].get_mut(mesh.cell_region(c)) {
            *seen = true;
        }
    }
    for (b, seen) in region_seen.iter().enumerate() {
        out[b].regions = mesh
            .region_names()
            .iter()
            .zip(seen)
            .filter(|&(_, &s)| s)
            .map(|(name, _)| name.clone())
            .collect();
    }
    for (p, name) in mesh.part_names().iter().enumerate() {
        let mut on: Vec<usize> = mesh.part_nodes(p).iter().map(|&v| body(v)).collect();
        on.sort_unstable();
        on.dedup();
        for b in on {
            out[b].parts.push(name.clone());
        }
    }
    // Nodal vectors (DOF order) summed per body.
    let add =
        |field: &[f64], pick: fn(&mut BodySummary) -> &mut Vec<f64>, out: &mut [BodySummary]| {
            for (k, value) in field.iter().enumerate() {
                let v = (k / d) as u32;
                if body_of[v as usize] != u32::MAX {
                    pick(&mut out[body(v)])[k % d] += value;
                }
            }
        };
    let mut f = vec![0.0; d * mesh.n_nodes()];
    crate::assembly::loads::add_body_force(mesh, &problem.body_force[..d], &mut f);
    for t in &problem.tractions {
        crate::assembly::loads::add_traction(mesh, t.part, &t.value[..d], &mut f);
    }
    add(&f, |b| &mut b.load, &mut out);
    add(&solution.reactions, |b| &mut b.reaction, &mut out);
    // The interface forces, spread over each point's stencil (the node, and a pair's
    // master nodes with −N_j).
    if let Ok(points) = problem.contact_nodes() {
        let index: HashMap<(u32, u16), usize> = (0..points.len())
            .map(|i| ((points.node[i], points.boundary[i]), i))
            .collect();
        for r in &solution.contact {
            let Ok(boundary) = u16::try_from(r.boundary) else {
                continue;
            };
            let Some(&i) = index.get(&(r.node, boundary)) else {
                continue;
            };
            let (len, nodes, coef) = points.stencil(d, i);
            for a in 0..len {
                let force = &mut out[body(nodes[a])].contact_force;
                for k in 0..d {
                    force[k] += coef[a] * r.force[k];
                }
            }
        }
    }
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    for b in &mut out {
        let sum: Vec<f64> = (0..d)
            .map(|k| b.load[k] + b.reaction[k] + b.contact_force[k])
            .collect();
        let scale = norm(&b.load)
            .max(norm(&b.reaction))
            .max(norm(&b.contact_force));
        b.imbalance = if scale > 0.0 { norm(&sum) / scale } else { 0.0 };
    }
    out
}
