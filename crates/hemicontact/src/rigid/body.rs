//! The bodies of a mesh, the connected components of its cells, with their centroids, sizes
//! and boxes, and the rigid-mode basis on each (see [`super`]).

use crate::mesh::Mesh;

/// A connected component of the mesh (cells sharing a vertex are connected).
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// Its nodes, increasing.
    pub nodes: Vec<u32>,
    /// Centroid `x̄` of its nodes (m).
    pub centroid: [f64; 3],
    /// Largest distance `L` of a node from the centroid (m).
    pub size: f64,
    /// Bounding box (min, max) of its nodes (m).
    pub bounding_box: ([f64; 3], [f64; 3]),
    /// The names of the cell regions its cells are in, in the mesh's order (empty for a
    /// mesh without named regions).
    pub regions: Vec<String>,
}

impl Body {
    /// The same body in coordinates whose unit is `length` times that of its own (its
    /// centroid, size and bounding box times `length`).
    pub fn in_units(&self, length: f64) -> Body {
        Body {
            nodes: self.nodes.clone(),
            centroid: self.centroid.map(|x| x * length),
            size: self.size * length,
            bounding_box: (
                self.bounding_box.0.map(|x| x * length),
                self.bounding_box.1.map(|x| x * length),
            ),
            regions: self.regions.clone(),
        }
    }
}

/// Number of rigid modes in dimension `d`: 3 in 2D, 6 in 3D.
pub fn n_modes(d: usize) -> usize {
    if d == 2 {
        3
    } else {
        6
    }
}

/// The connected components of the cell graph: the body of each node (`u32::MAX` for a
/// node in no cell) and the bodies, ordered by their smallest node.
pub fn bodies(mesh: &Mesh) -> (Vec<u32>, Vec<Body>) {
    let n = mesh.n_nodes();
    let d = mesh.dim();
    // Union–find with path halving; the root of a set is its smallest node.
    let mut parent: Vec<u32> = (0..n as u32).collect();
    fn find(parent: &mut [u32], mut v: u32) -> u32 {
        while parent[v as usize] != v {
            parent[v as usize] = parent[parent[v as usize] as usize];
            v = parent[v as usize];
        }
        v
    }
    let mut used = vec![false; n];
    for c in 0..mesh.n_cells() {
        let cell = mesh.cell(c);
        used[cell[0] as usize] = true;
        for &v in &cell[1..] {
            used[v as usize] = true;
            let (r0, r) = (find(&mut parent, cell[0]), find(&mut parent, v));
            parent[r0.max(r) as usize] = r0.min(r);
        }
    }
    let mut body_of = vec![u32::MAX; n];
    let mut bodies: Vec<Body> = Vec::new();
    let mut index_of_root = vec![u32::MAX; n];
    for v in 0..n {
        if !used[v] {
            continue;
        }
        let r = find(&mut parent, v as u32) as usize;
        if index_of_root[r] == u32::MAX {
            index_of_root[r] = bodies.len() as u32;
            bodies.push(Body {
                nodes: Vec::new(),
                centroid: [0.0; 3],
                size: 0.0,
                bounding_box: ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
                regions: Vec::new(),
            });
        }
        body_of[v] = index_of_root[r];
        bodies[index_of_root[r] as usize].nodes.push(v as u32);
    }
    // The named regions of each body's cells.
    let names = mesh.region_names();
    if !names.is_empty() {
        let mut present = vec![vec![false; names.len()]; bodies.len()];
        for c in 0..mesh.n_cells() {
            let b = body_of[mesh.cell(c)[0] as usize] as usize;
            present[b][mesh.cell_region(c)] = true;
        }
        for (body, present) in bodies.iter_mut().zip(present) {
            body.regions = (0..names.len())
                .filter(|&r| present[r])
                .map(|r| names[r].clone())
                .collect();
        }
    }
    for body in &mut bodies {
        let k = body.nodes.len() as f64;
        for &v in &body.nodes {
            let x = mesh.node(v as usize);
            for i in 0..d {
                body.centroid[i] += x[i] / k;
                body.bounding_box.0[i] = body.bounding_box.0[i].min(x[i]);
                body.bounding_box.1[i] = body.bounding_box.1[i].max(x[i]);
            }
        }
        for i in d..3 {
            body.bounding_box = (
                {
                    let mut lo = body.bounding_box.0;
                    lo[i] = 0.0;
                    lo
                },
                {
                    let mut hi = body.bounding_box.1;
                    hi[i] = 0.0;
                    hi
                },
            );
        }
        body.size = body
            .nodes
            .iter()
            .map(|&v| {
                let x = mesh.node(v as usize);
                (0..d)
                    .map(|i| (x[i] - body.centroid[i]).powi(2))
                    .sum::<f64>()
                    .sqrt()
            })
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
    }
    (body_of, bodies)
}

/// The row `dir · φ_j(x)`, j = 1…m, of the rigid-mode basis of `body` (module
/// documentation): translations `e_i`, then rotations `e_k × (x − x̄) / L` (2D: the one
/// rotation about z).
pub(super) fn mode_row(d: usize, body: &Body, x: &[f64], dir: &[f64; 3]) -> [f64; 6] {
    let mut q = [0.0; 3];
    for i in 0..d {
        q[i] = (x[i] - body.centroid[i]) / body.size;
    }
    let mut row = [0.0; 6];
    row[..d].copy_from_slice(&dir[..d]);
    if d == 2 {
        // e_z × q = (−q_y, q_x).
        row[2] = -q[1] * dir[0] + q[0] * dir[1];
    } else {
        for k in 0..3 {
            let mut e = [0.0; 3];
            e[k] = 1.0;
            let w = crate::geometry::simplex::cross(&e, &q);
            row[3 + k] = (0..3).map(|i| w[i] * dir[i]).sum();
        }
    }
    row
}

pub(super) fn mode_row_norm2(row: &[f64; 6], m: usize) -> f64 {
    row[..m].iter().map(|x| x * x).sum()
}
