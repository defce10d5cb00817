//! The pairing of two deformable parts in contact (node-to-segment): each node of the
//! *slave* part is paired once, in the reference configuration (small deformation, as for
//! rigid obstacles), with its closest point on the facets of the *master* part.
//!
//! For a slave node at x and a master facet F with vertices m_j and outward unit normal
//! n_F, the candidate point is the closest point c of F to x, written with the facet's
//! shape functions at c, `c = Σ_j N_j m_j` (`N_j ≥ 0`, `Σ N_j = 1`). The pair's
//!
//! - **normal** is `ν = −n_F`: the outward normal of the slave side, from the slave node
//!   towards the master body;
//! - **gap** is `g = (c − x)·ν = (x − c)·n_F`: positive when the node is outside the
//!   master body, negative when it starts inside it;
//! - **relative displacement** is `u_s − Σ_j N_j u_{m_j}`, whose normal part
//!   `u_ν = (u_s − Σ N_j u_{m_j})·ν` enters every normal law through `u_ν ≤ g` and whose
//!   tangential part is the slip relative to the master body.
//!
//! Which facet: among the facets onto which x projects orthogonally (its projection on
//! the facet's line or plane inside the facet, or outside it by at most 5 % of its size,
//! the point then taken on its edge), the nearest.
//! Two such facets at the same distance with distinct closest points make the pairing
//! ambiguous: it is refused, naming the node, unless the two are neighbours whose normals
//! differ by less than the corner angle ([`super::nodes::CORNER_ANGLE_DEG`], 30°): above
//! the nearly flat crease between two triangles of a curved surface either point is as
//! good, and the one of the lower facet index is taken. A node that projects onto no facet lies
//! beyond the edge of the master surface, or above a convex corner between facets. Above
//! a corner (the closest point is a vertex or edge shared by several master facets) it is
//! paired with that point, with the mean of the facets' normals there. Beyond the master
//! surface's own edge (the closest point is on the boundary of the master part) it is
//! *separated*: it can never touch the master under small deformation, and is not a
//! contact point.

use crate::mesh::Mesh;

/// The closest point of a slave node on a master surface; see the module documentation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projection {
    /// The master facet holding the closest point (an index into the mesh's facets).
    pub facet: usize,
    /// The nodes of that facet (first d entries).
    pub nodes: [u32; 3],
    /// The shape functions N_j of the facet at the closest point (first d entries; ≥ 0,
    /// summing to 1).
    pub shape: [f64; 3],
    /// The unit normal ν of the pair, from the slave node towards the master body.
    pub normal: [f64; 3],
    /// The gap g (m): positive when the node is outside the master body.
    pub gap: f64,
}

/// The outcome of pairing one slave node.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Pairing {
    /// The node's closest point on the master surface.
    Paired(Projection),
    /// The node lies beyond the edge of the master surface: not a contact point.
    Separated,
}

/// Relative tolerance (of the facet's size) of the inside test of a projection and of the
/// comparison of distances and points.
const TOLERANCE: f64 = 1e-9;

/// How far outside a facet (relative to its size: the edge parameter in 2D, the
/// barycentric coordinates in 3D) an orthogonal projection still counts as inside it. On a
/// triangulated curved surface cut by a symmetry plane, the slave nodes on that plane
/// project just outside the master facets along it (by the gap times the facets' tilt, up
/// to about 1 % of their size on a sphere's quarter), and must not be taken for nodes beyond
/// the master surface's edge.
const INSIDE: f64 = 0.05;

/// The closest point of facet `f` of `mesh` to `x`: its shape functions and whether the
/// orthogonal projection of x on the facet's line or plane falls inside the facet.
fn closest_on_facet(mesh: &Mesh, f: usize, x: &[f64; 3]) -> ([f64; 3], bool) {
    let d = mesh.dim();
    let v = mesh.facet(f);
    let mut p = [[0.0; 3]; 3];
    for (a, &n) in v.iter().enumerate() {
        p[a][..d].copy_from_slice(mesh.node(n as usize));
    }
    let sub = |a: &[f64; 3], b: &[f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: &[f64; 3], b: &[f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    if d == 2 {
        let e = sub(&p[1], &p[0]);
        let t = dot(&sub(x, &p[0]), &e) / dot(&e, &e);
        let inside = (-INSIDE..=1.0 + INSIDE).contains(&t);
        let t = t.clamp(0.0, 1.0);
        return ([1.0 - t, t, 0.0], inside);
    }
    // The barycentric coordinates of the orthogonal projection on the plane.
    let (e1, e2, r) = (sub(&p[1], &p[0]), sub(&p[2], &p[0]), sub(x, &p[0]));
    let (a11, a12, a22) = (dot(&e1, &e1), dot(&e1, &e2), dot(&e2, &e2));
    let (b1, b2) = (dot(&r, &e1), dot(&r, &e2));
    let det = a11 * a22 - a12 * a12;
    let s = (a22 * b1 - a12 * b2) / det;
    let t = (a11 * b2 - a12 * b1) / det;
    let lambda = [1.0 - s - t, s, t];
    if lambda.iter().all(|&l| l >= -INSIDE) {
        let clamp = lambda.map(|l| l.max(0.0));
        let sum: f64 = clamp.iter().sum();
        return (clamp.map(|l| l / sum), true);
    }
    // Outside: the closest point is on one of the three edges.
    let mut best = ([0.0; 3], f64::INFINITY);
    for (i, j) in [(0, 1), (1, 2), (2, 0)] {
        let e = sub(&p[j], &p[i]);
        let t = (dot(&sub(x, &p[i]), &e) / dot(&e, &e)).clamp(0.0, 1.0);
        let c = [0, 1, 2].map(|k| p[i][k] + t * e[k]);
        let dist = dot(&sub(x, &c), &sub(x, &c));
        if dist < best.1 {
            let mut shape = [0.0; 3];
            shape[i] = 1.0 - t;
            shape[j] = t;
            best = (shape, dist);
        }
    }
    (best.0, false)
}

/// The closest point of one master facet to a slave node.
#[derive(Clone, Copy, Debug)]
struct Candidate {
    /// The facet.
    facet: usize,
    /// Its shape functions at the closest point.
    shape: [f64; 3],
    /// Whether the node projects orthogonally inside the facet.
    inside: bool,
    /// The closest point (m).
    point: [f64; 3],
    /// Its distance to the node (m).
    distance: f64,
}

/// The point `Σ N_j m_j` of facet `f` with shape functions `shape`.
fn point_of(mesh: &Mesh, f: usize, shape: &[f64; 3]) -> [f64; 3] {
    let d = mesh.dim();
    let mut c = [0.0; 3];
    for (a, &n) in mesh.facet(f).iter().enumerate() {
        for k in 0..d {
            c[k] += shape[a] * mesh.node(n as usize)[k];
        }
    }
    c
}

/// The master facets of a pair, with a uniform grid over their bounding boxes, built once
/// per contact boundary: a slave node's candidate facets are found by searching the grid
/// outwards from the node's cell until no unexamined facet can be nearer than the nearest
/// one onto which it projects, so that pairing n slave nodes costs about n times the
/// facets near a node rather than n times all of them. The outcome is that of examining
/// every facet (see [`MasterSurface::pair`]).
#[derive(Clone, Debug)]
pub struct MasterSurface<'a> {
    mesh: &'a Mesh,
    /// The master facets (indices into the mesh's facets).
    facets: Vec<usize>,
    /// The largest facet size (the length of a 2D facet, √area of a 3D one) (m): the scale
    /// of the tolerances.
    size: f64,
    /// The grid's lower corner (m), cell size (m) and cells per axis.
    lo: [f64; 3],
    cell: f64,
    dims: [usize; 3],
    /// The facets (positions in `facets`) of each grid cell, in compressed rows.
    start: Vec<u32>,
    items: Vec<u32>,
}

/// Rings of grid cells searched around a slave node before every facet is examined
/// instead (a node beyond the master surface's edge or far from it has no near facet to
/// stop the search).
const RINGS: i64 = 3;

impl<'a> MasterSurface<'a> {
    /// The master surface of the facets `master` of `mesh` (indices into its facets).
    pub fn new(mesh: &'a Mesh, master: &[usize]) -> Self {
        let d = mesh.dim();
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        let mut size = 0.0f64;
        let mut mean = 0.0;
        let boxes: Vec<([f64; 3], [f64; 3])> = master
            .iter()
            .map(|&f| {
                size = size.max(mesh.facet_measure_normal(f).0.powf(1.0 / (d - 1) as f64));
                let mut b = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
                for &v in mesh.facet(f) {
                    for (k, &x) in mesh.node(v as usize).iter().enumerate() {
                        b.0[k] = b.0[k].min(x);
                        b.1[k] = b.1[k].max(x);
                    }
                }
                for k in 0..d {
                    lo[k] = lo[k].min(b.0[k]);
                    hi[k] = hi[k].max(b.1[k]);
                    mean += (b.1[k] - b.0[k]) / (d * master.len()) as f64;
                }
                b
            })
            .collect();
        if master.is_empty() {
            lo = [0.0; 3];
            hi = [0.0; 3];
        }
        // Cells about the mean facet extent, no more than a few per facet.
        let extent = (0..d).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        let mut cell = if mean > 0.0 { mean } else { extent.max(1.0) };
        let count = |cell: f64| -> ([usize; 3], usize) {
            let mut dims = [1usize; 3];
            for k in 0..d {
                dims[k] = (((hi[k] - lo[k]) / cell).floor() as usize + 1).min(1 << 20);
            }
            (dims, dims.iter().product())
        };
        while count(cell).1 > 8 * master.len() + 64 {
            cell *= 2.0;
        }
        let dims = count(cell).0;
        let index = |x: f64, k: usize| (((x - lo[k]) / cell).floor() as usize).min(dims[k] - 1);
        let flat = |i: [usize; 3]| (i[2] * dims[1] + i[1]) * dims[0] + i[0];
        let mut lists: Vec<Vec<u32>> = vec![Vec::new(); count(cell).1];
        for (pos, b) in boxes.iter().enumerate() {
            let mut from = [0usize; 3];
            let mut to = [0usize; 3];
            for k in 0..d {
                from[k] = index(b.0[k], k);
                to[k] = index(b.1[k], k);
            }
            for i2 in from[2]..=to[2] {
                for i1 in from[1]..=to[1] {
                    for i0 in from[0]..=to[0] {
                        lists[flat([i0, i1, i2])].push(pos as u32);
                    }
                }
            }
        }
        let mut start = Vec::with_capacity(lists.len() + 1);
        let mut items = Vec::new();
        start.push(0);
        for l in &lists {
            items.extend_from_slice(l);
            start.push(items.len() as u32);
        }
        MasterSurface {
            mesh,
            facets: master.to_vec(),
            size,
            lo,
            cell,
            dims,
            start,
            items,
        }
    }

    /// The candidate of facet position `pos` for the slave node at `x`.
    fn candidate(&self, pos: usize, x: &[f64; 3]) -> Candidate {
        let f = self.facets[pos];
        let (shape, inside) = closest_on_facet(self.mesh, f, x);
        let point = point_of(self.mesh, f, &shape);
        Candidate {
            facet: f,
            shape,
            inside,
            point,
            distance: (0..3)
                .map(|k| (x[k] - point[k]).powi(2))
                .sum::<f64>()
                .sqrt(),
        }
    }

    /// The candidates of the slave node at `x` that decide its pairing: every facet within
    /// the distance of the nearest one onto which x projects (plus the tolerance `tol`),
    /// found ring by ring in the grid; every facet when no ring within [`RINGS`] holds such
    /// a facet.
    fn candidates(&self, x: &[f64; 3], tol: f64) -> Vec<Candidate> {
        let d = self.mesh.dim();
        let mut c = [0i64; 3];
        for k in 0..d {
            c[k] = ((x[k] - self.lo[k]) / self.cell).floor() as i64;
        }
        let mut seen = std::collections::HashSet::new();
        let mut out: Vec<(u32, Candidate)> = Vec::new();
        for r in 0..=RINGS {
            // The cells of the block |i − c| ≤ r (within the grid) on its shell.
            let mut from = [0i64; 3];
            let mut to = [0i64; 3];
            let mut whole = true;
            for k in 0..3 {
                let n = self.dims[k] as i64;
                from[k] = (c[k] - r).max(0);
                to[k] = (c[k] + r).min(n - 1);
                whole &= c[k] - r <= 0 && c[k] + r >= n - 1;
            }
            for i2 in from[2]..=to[2] {
                for i1 in from[1]..=to[1] {
                    for i0 in from[0]..=to[0] {
                        let i = [i0, i1, i2];
                        if (0..d).all(|k| (i[k] - c[k]).abs() < r) {
                            continue;
                        }
                        let flat = ((i2 as usize * self.dims[1] + i1 as usize) * self.dims[0])
                            + i0 as usize;
                        let (a, b) = (self.start[flat] as usize, self.start[flat + 1] as usize);
                        for &pos in &self.items[a..b] {
                            if seen.insert(pos) {
                                out.push((pos, self.candidate(pos as usize, x)));
                            }
                        }
                    }
                }
            }
            // No unexamined facet is nearer than r cells.
            let reach = r as f64 * self.cell;
            let nearest_inside = out
                .iter()
                .filter(|c| c.1.inside)
                .map(|c| c.1.distance)
                .fold(f64::INFINITY, f64::min);
            if whole || nearest_inside + 2.0 * tol < reach {
                // In the facets' order, as a scan of every facet would list them.
                out.sort_unstable_by_key(|c| c.0);
                return out.into_iter().map(|c| c.1).collect();
            }
        }
        (0..self.facets.len())
            .map(|pos| self.candidate(pos, x))
            .collect()
    }

    /// Pairs the node `slave` of the mesh with its closest point on the master surface;
    /// see the module documentation.
    ///
    /// # Errors
    /// The reason, in words naming the node, when two master facets are equally near with
    /// distinct closest points (an ambiguous pairing), or when the surface has no facets.
    pub fn pair(&self, slave: u32) -> std::result::Result<Pairing, String> {
        let mesh = self.mesh;
        let d = mesh.dim();
        let mut x = [0.0; 3];
        x[..d].copy_from_slice(mesh.node(slave as usize));
        if self.facets.is_empty() {
            return Err(format!("node {slave}: the master part has no facets"));
        }
        let tol = TOLERANCE * self.size.max(f64::MIN_POSITIVE);
        let candidates = self.candidates(&x, tol);
        decide(mesh, slave, &x, &candidates, tol)
    }
}

/// Pairs the node `slave` of `mesh` with its closest point on the master facets `master`
/// (indices into the mesh's facets); see the module documentation. Builds the
/// [`MasterSurface`] for this one node: pair many nodes through one surface instead.
///
/// # Errors
/// Those of [`MasterSurface::pair`].
pub fn pair(mesh: &Mesh, master: &[usize], slave: u32) -> std::result::Result<Pairing, String> {
    MasterSurface::new(mesh, master).pair(slave)
}

/// The pairing of the slave node `slave` at `x` from its candidate facets (those that
/// decide it: [`MasterSurface::candidates`]), `tol` the tolerance of distances and points.
fn decide(
    mesh: &Mesh,
    slave: u32,
    x: &[f64; 3],
    candidates: &[Candidate],
    tol: f64,
) -> std::result::Result<Pairing, String> {
    let apart =
        |a: &[f64; 3], b: &[f64; 3]| (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt();
    let nearest = |inside_only: bool| {
        candidates
            .iter()
            .filter(|c| c.inside || !inside_only)
            .min_by(|a, b| {
                a.distance
                    .total_cmp(&b.distance)
                    .then(a.facet.cmp(&b.facet))
            })
    };
    if let Some(best) = nearest(true) {
        // Another facet as near with a different closest point: ambiguous, unless the two
        // facets are neighbours that meet at a nearly flat crease (a triangulated curved
        // surface), where either closest point is as good.
        let (_, best_normal) = mesh.facet_measure_normal(best.facet);
        let cos_crease = super::nodes::CORNER_ANGLE_DEG.to_radians().cos();
        let flat_neighbour = |c: &Candidate| {
            let (_, n) = mesh.facet_measure_normal(c.facet);
            let cos: f64 = (0..3).map(|k| n[k] * best_normal[k]).sum();
            let shared = mesh
                .facet(c.facet)
                .iter()
                .any(|v| mesh.facet(best.facet).contains(v));
            shared && cos >= cos_crease
        };
        if let Some(other) = candidates.iter().find(|c| {
            c.inside
                && c.facet != best.facet
                && (c.distance - best.distance).abs() <= tol
                && apart(&c.point, &best.point) > tol
                && !flat_neighbour(c)
        }) {
            return Err(format!(
                "node {slave}: its closest points on master facets {} and {} are distinct and \
                 equally near ({:e} m); the pairing is ambiguous (refine the master side, or \
                 make the other part the slave)",
                best.facet, other.facet, best.distance
            ));
        }
        let (_, n) = mesh.facet_measure_normal(best.facet);
        return Ok(Pairing::Paired(projection(mesh, best, n, x)));
    }
    // No orthogonal projection: above a corner shared by master facets, or beyond the edge.
    let Some(best) = nearest(false) else {
        return Ok(Pairing::Separated);
    };
    let sharing: Vec<&Candidate> = candidates
        .iter()
        .filter(|c| apart(&c.point, &best.point) <= tol)
        .collect();
    if sharing.len() < 2 {
        return Ok(Pairing::Separated);
    }
    let mut n = [0.0; 3];
    for c in &sharing {
        let (_, nf) = mesh.facet_measure_normal(c.facet);
        for k in 0..3 {
            n[k] += nf[k];
        }
    }
    let len = n.iter().map(|v| v * v).sum::<f64>().sqrt();
    if len <= TOLERANCE {
        return Ok(Pairing::Separated);
    }
    let n = n.map(|v| v / len);
    Ok(Pairing::Paired(projection(mesh, best, n, x)))
}

/// The projection of the slave node at `x` on its closest point `c`, with the master
/// normal `n` there.
fn projection(mesh: &Mesh, c: &Candidate, n: [f64; 3], x: &[f64; 3]) -> Projection {
    let mut nodes = [u32::MAX; 3];
    for (a, &v) in mesh.facet(c.facet).iter().enumerate() {
        nodes[a] = v;
    }
    Projection {
        facet: c.facet,
        nodes,
        shape: c.shape,
        normal: n.map(|v| -v),
        gap: (0..3).map(|k| (x[k] - c.point[k]) * n[k]).sum(),
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    /// Two unit squares (2D) side by side along y, separated by `gap`, each of two
    /// triangles, with the parts `lower_top` (the lower square's top) and `upper_bottom`.
    fn two_squares(gap: f64, shift: f64) -> Mesh {
        let coords = vec![
            0.0,
            0.0,
            1.0,
            0.0,
            1.0,
            1.0,
            0.0,
            1.0, // lower
            shift,
            1.0 + gap,
            1.0 + shift,
            1.0 + gap,
            1.0 + shift,
            2.0 + gap,
            shift,
            2.0 + gap,
        ];
        let cells = vec![0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7];
        Mesh::from_parts(
            2,
            coords,
            cells,
            &[
                ("lower_top".into(), vec![2, 3]),
                ("upper_bottom".into(), vec![4, 5]),
            ],
        )
        .unwrap()
    }

    fn facets_of(m: &Mesh, part: &str) -> Vec<usize> {
        m.part_facets(m.part_index(part).unwrap()).collect()
    }

    #[test]
    fn a_node_above_a_facet_gets_its_gap_normal_and_shape_functions() {
        let m = two_squares(0.1, 0.25);
        let master = facets_of(&m, "lower_top");
        // Slave node 4 at (0.25, 1.1): above the lower square's top, a quarter along it.
        let Pairing::Paired(p) = pair(&m, &master, 4).unwrap() else {
            panic!("separated")
        };
        assert!((p.gap - 0.1).abs() < 1e-14, "gap {}", p.gap);
        assert!((p.normal[1] + 1.0).abs() < 1e-14 && p.normal[0].abs() < 1e-14);
        // Facet nodes (2, 3) at x = 1 and x = 0: N = (0.25, 0.75).
        let n_of = |v: u32| p.shape[p.nodes.iter().position(|&w| w == v).unwrap()];
        assert!((n_of(2) - 0.25).abs() < 1e-14 && (n_of(3) - 0.75).abs() < 1e-14);
    }

    #[test]
    fn a_node_beyond_the_edge_of_the_master_surface_is_separated() {
        let m = two_squares(0.1, 0.25);
        let master = facets_of(&m, "lower_top");
        // Slave node 5 at (1.25, 1.1): beyond the master's right end.
        assert_eq!(pair(&m, &master, 5).unwrap(), Pairing::Separated);
    }

    #[test]
    fn a_penetrating_node_has_a_negative_gap() {
        let m = two_squares(-0.05, 0.5);
        let master = facets_of(&m, "lower_top");
        let Pairing::Paired(p) = pair(&m, &master, 4).unwrap() else {
            panic!("separated")
        };
        assert!((p.gap + 0.05).abs() < 1e-14, "gap {}", p.gap);
    }

    /// A lower body of `coords`/`cells` with its top facets in the part `master`, and a
    /// slave triangle `slave` (its first node the one paired).
    fn with_slave(
        mut coords: Vec<f64>,
        mut cells: Vec<u32>,
        master: Vec<u32>,
        slave: [f64; 6],
    ) -> (Mesh, u32) {
        let first = (coords.len() / 2) as u32;
        coords.extend_from_slice(&slave);
        cells.extend_from_slice(&[first, first + 1, first + 2]);
        let m = Mesh::from_parts(2, coords, cells, &[("master".into(), master)]).unwrap();
        (m, first)
    }

    #[test]
    fn a_node_above_a_convex_corner_is_paired_with_the_corner() {
        // A roof: the triangle (0, 0), (2, 0), (1, 1), its apex a convex corner.
        let (m, node) = with_slave(
            vec![0.0, 0.0, 2.0, 0.0, 1.0, 1.0],
            vec![0, 1, 2],
            vec![1, 2, 2, 0],
            [1.0, 1.5, 1.5, 2.0, 0.5, 2.0],
        );
        let Pairing::Paired(p) = pair(&m, &facets_of(&m, "master"), node).unwrap() else {
            panic!("separated")
        };
        assert!((p.gap - 0.5).abs() < 1e-14, "gap {}", p.gap);
        assert!(p.normal[0].abs() < 1e-14 && (p.normal[1] + 1.0).abs() < 1e-14);
        let at_apex = p.nodes.iter().position(|&v| v == 2).unwrap();
        assert!((p.shape[at_apex] - 1.0).abs() < 1e-14);
    }

    #[test]
    fn a_node_equally_near_two_facets_of_a_notch_is_refused_naming_it() {
        // A pentagon with a V notch at its top, the notch's two facets the master part.
        let (m, node) = with_slave(
            vec![0.0, -1.0, 2.0, -1.0, 2.0, 1.0, 1.0, 0.0, 0.0, 1.0],
            vec![0, 1, 3, 1, 2, 3, 0, 3, 4],
            vec![2, 3, 3, 4],
            [1.0, 0.8, 1.2, 1.5, 0.8, 1.5],
        );
        let e = pair(&m, &facets_of(&m, "master"), node).unwrap_err();
        assert!(
            e.contains(&format!("node {node}")) && e.contains("ambiguous"),
            "{e}"
        );
    }

    #[test]
    fn a_node_above_a_triangle_gets_its_barycentric_shape_functions() {
        // The lower tetrahedron's face z = 0 is the master; the slave tetrahedron's first
        // node is at (0.2, 0.3, 0.1).
        let coords = vec![
            0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -1.0, //
            0.2, 0.3, 0.1, 1.2, 0.3, 0.1, 0.2, 1.3, 0.1, 0.2, 0.3, 1.1,
        ];
        let m = Mesh::from_parts(
            3,
            coords,
            vec![0, 1, 2, 3, 4, 5, 6, 7],
            &[("master".into(), vec![0, 1, 2])],
        )
        .unwrap();
        let Pairing::Paired(p) = pair(&m, &facets_of(&m, "master"), 4).unwrap() else {
            panic!("separated")
        };
        assert!((p.gap - 0.1).abs() < 1e-14, "gap {}", p.gap);
        assert!((p.normal[2] + 1.0).abs() < 1e-14);
        let n_of = |v: u32| p.shape[p.nodes.iter().position(|&w| w == v).unwrap()];
        for (v, exact) in [(0, 0.5), (1, 0.3), (2, 0.2)] {
            assert!(
                (n_of(v) - exact).abs() < 1e-14,
                "N at node {v}: {}",
                n_of(v)
            );
        }
    }

    /// The grid search decides every slave node as examining every facet does: a curved
    /// 3D master surface (a box's top lifted onto a sphere) under a finer, shifted and
    /// wider slave surface (some of its nodes beyond the master's edge, some above it far
    /// from its facets), each slave node paired through [`MasterSurface::pair`] and through
    /// [`decide`] over all facets.
    #[test]
    fn the_grid_search_pairs_as_the_scan_of_every_facet() {
        use crate::mesh::generate::{cuboid, BoxSpec, CutPattern};
        let block = |origin: [f64; 3], size: [f64; 3], n: usize| {
            cuboid(&BoxSpec {
                origin,
                size,
                n: [n, n, 2],
                pattern: CutPattern::Uniform,
                progression: [1.0; 3],
            })
            .unwrap()
        };
        let lower = block([0.0, 0.0, -0.5], [1.0, 1.0, 0.5], 7);
        let upper = block([-0.2, -0.1, 0.05], [1.5, 1.3, 0.5], 11);
        let offset = lower.n_nodes() as u32;
        let mut coords = lower.coords().to_vec();
        for x in coords.chunks_exact_mut(3) {
            x[2] -= 0.1 * (x[0] * x[0] + x[1] * x[1]) * (1.0 + 2.0 * x[2]);
        }
        coords.extend_from_slice(upper.coords());
        let mut cells = lower.cells().to_vec();
        cells.extend(upper.cells().iter().map(|&v| v + offset));
        let part = |m: &Mesh, name: &str, shift: u32| -> Vec<u32> {
            let p = m.part_index(name).unwrap();
            m.part_facets(p)
                .flat_map(|f| m.facet(f).iter().map(move |&v| v + shift))
                .collect()
        };
        let mesh = Mesh::from_parts(
            3,
            coords,
            cells,
            &[
                ("lower_top".into(), part(&lower, "top", 0)),
                ("upper_bottom".into(), part(&upper, "bottom", offset)),
            ],
        )
        .unwrap();
        let master = facets_of(&mesh, "lower_top");
        let surface = MasterSurface::new(&mesh, &master);
        let slaves = mesh.part_nodes(mesh.part_index("upper_bottom").unwrap());
        let (mut paired, mut separated) = (0, 0);
        for &v in &slaves {
            let mut x = [0.0; 3];
            x.copy_from_slice(mesh.node(v as usize));
            let tol = TOLERANCE * surface.size;
            let all: Vec<Candidate> = (0..master.len())
                .map(|pos| surface.candidate(pos, &x))
                .collect();
            let scan = decide(&mesh, v, &x, &all, tol);
            let grid = surface.pair(v);
            assert_eq!(grid, scan, "node {v}");
            match grid {
                Ok(Pairing::Paired(_)) => paired += 1,
                _ => separated += 1,
            }
        }
        // Both outcomes were exercised.
        assert!(
            paired > 50 && separated > 10,
            "{paired} paired, {separated} separated"
        );
    }
}
