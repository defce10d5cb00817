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
//! differ by less than the corner angle ([`super::directions::CORNER_ANGLE_DEG`], 30°): above
//! the nearly flat crease between two triangles of a curved surface either point is as
//! good, and the one of the lower facet index is taken. Two facets at the same distance with
//! the same closest point (a slave node at a concave corner of the master surface) are not
//! ambiguous: the lower facet index is taken, or, for one face of a slave corner
//! ([`MasterSurface::pair_facing`]), the facet that faces that face most nearly head-on.
//!
//! # The edge of the master surface
//!
//! The master part's facets end somewhere: at the edge of the master surface, where the
//! master body's boundary continues in facets of other parts (its *sides*: the side of a
//! block whose top is the master part, or a symmetry plane that cuts the interface). A slave
//! node *beyond* that edge can never touch the master under small deformation and is not a
//! contact point. A closest point c on the edge (an orthogonal projection clamped there, or
//! the end of the surface) is beyond it when the node lies on the outer side of a side facet
//! that contains c's support (the facet's vertices where the shape functions at c are not
//! zero): `(x − c)·n_S > 10⁻⁹ h` for such a side facet S with outward normal n_S, h the
//! largest master facet size. So the 5 % by which a projection may fall outside a facet
//! reaches across the master surface's interior edges (a crease of a curved surface) and
//! onto a symmetry plane (the slave nodes on the plane lie in the plane of the side facets
//! there), but never to a node that stands beside the master body.
//!
//! A node that projects onto no facet lies above a convex corner between master facets, or
//! beyond the edge. Above a corner (the closest point is a vertex or edge shared by several
//! master facets, and not beyond the edge as above) it is paired with that point, with the
//! mean of the facets' normals there. Otherwise it is *separated*: not a contact point.

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

/// The sides of the master surface of the facets `master` of `mesh`: `(node, facet)` for
/// every boundary facet of the mesh other than the master facets (and other than a facet
/// with the vertices of a master facet, listed in a second part) at each of its vertices
/// that is a vertex of a master facet, sorted.
fn sides_of(mesh: &Mesh, master: &[usize]) -> Vec<(u32, u32)> {
    let key = |f: usize| {
        let mut k = [u32::MAX; 3];
        k[..mesh.dim()].copy_from_slice(mesh.facet(f));
        k.sort_unstable();
        k
    };
    let mut on_surface = vec![false; mesh.n_nodes()];
    let mut keys: Vec<[u32; 3]> = master.iter().map(|&f| key(f)).collect();
    keys.sort_unstable();
    for &f in master {
        for &v in mesh.facet(f) {
            on_surface[v as usize] = true;
        }
    }
    let mut sides = Vec::new();
    for f in 0..mesh.n_facets() {
        let vertices = mesh.facet(f);
        if !vertices.iter().any(|&v| on_surface[v as usize]) || keys.binary_search(&key(f)).is_ok()
        {
            continue;
        }
        for &v in vertices.iter().filter(|&&v| on_surface[v as usize]) {
            sides.push((v, f as u32));
        }
    }
    sides.sort_unstable();
    sides
}

/// The closest point of one master facet to a slave node.
#[derive(Clone, Copy, Debug)]
struct Candidate {
    /// The facet.
    facet: usize,
    /// Its shape functions at the closest point.
    shape: [f64; 3],
    /// Whether the node projects orthogonally inside the facet (and not beyond the edge of
    /// the master surface).
    inside: bool,
    /// Whether the closest point is on the edge of the master surface with the node beyond
    /// it (see the module documentation).
    beyond: bool,
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
    /// The sides of the master surface: `(node, facet)` for each boundary facet of the mesh
    /// that is not a master facet (nor one with a master facet's vertices) and has a vertex
    /// `node` of the master surface, sorted.
    sides: Vec<(u32, u32)>,
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
            sides: sides_of(mesh, master),
        }
    }

    /// Whether the node at `x` lies beyond the edge of the master surface at the point `c`
    /// of facet `f` with shape functions `shape`: on the outer side of a side facet that
    /// contains every vertex of `f` where `shape` is not zero (see the module
    /// documentation). False for a point inside the facet.
    fn beyond_edge(&self, f: usize, shape: &[f64; 3], c: &[f64; 3], x: &[f64; 3]) -> bool {
        let mesh = self.mesh;
        let d = mesh.dim();
        let vertices = mesh.facet(f);
        if shape[..d].iter().all(|&n| n > 0.0) {
            return false;
        }
        let support: Vec<u32> = (0..d)
            .filter(|&a| shape[a] > 0.0)
            .map(|a| vertices[a])
            .collect();
        let Some(&first) = support.first() else {
            return false;
        };
        let from = self.sides.partition_point(|s| s.0 < first);
        let tol = TOLERANCE * self.size;
        self.sides[from..]
            .iter()
            .take_while(|s| s.0 == first)
            .any(|&(_, side)| {
                let side = side as usize;
                let around = mesh.facet(side);
                if !support.iter().all(|v| around.contains(v)) {
                    return false;
                }
                let (_, n) = mesh.facet_measure_normal(side);
                (0..d).map(|k| (x[k] - c[k]) * n[k]).sum::<f64>() > tol
            })
    }

    /// The candidate of facet position `pos` for the slave node at `x`.
    fn candidate(&self, pos: usize, x: &[f64; 3]) -> Candidate {
        let f = self.facets[pos];
        let (shape, inside) = closest_on_facet(self.mesh, f, x);
        let point = point_of(self.mesh, f, &shape);
        let beyond = self.beyond_edge(f, &shape, &point, x);
        Candidate {
            facet: f,
            shape,
            inside: inside && !beyond,
            beyond,
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
        self.pair_facing(slave, None)
    }

    /// [`MasterSurface::pair`] for one face of a corner of the slave part, of outward unit
    /// normal `facing` (`None`: the node's whole boundary): among master facets equally
    /// near with the same closest point (a concave corner of the master surface), the one
    /// whose outward normal n_F is most nearly opposite, the least `n_F·facing`, is taken.
    ///
    /// # Errors
    /// Those of [`MasterSurface::pair`].
    pub fn pair_facing(
        &self,
        slave: u32,
        facing: Option<[f64; 3]>,
    ) -> std::result::Result<Pairing, String> {
        let mesh = self.mesh;
        let d = mesh.dim();
        let mut x = [0.0; 3];
        x[..d].copy_from_slice(mesh.node(slave as usize));
        if self.facets.is_empty() {
            return Err(format!("node {slave}: the master part has no facets"));
        }
        let tol = TOLERANCE * self.size.max(f64::MIN_POSITIVE);
        let candidates = self.candidates(&x, tol);
        decide(mesh, slave, &x, &candidates, tol, facing)
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
    facing: Option<[f64; 3]>,
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
    if let Some(nearest) = nearest(true) {
        // For one face of a slave corner, the facet with the same closest point that faces
        // it most nearly head-on.
        let best = match facing {
            None => nearest,
            Some(n) => {
                let cos = |c: &Candidate| {
                    let (_, nf) = mesh.facet_measure_normal(c.facet);
                    (0..3).map(|k| nf[k] * n[k]).sum::<f64>()
                };
                candidates
                    .iter()
                    .filter(|c| {
                        c.inside
                            && (c.distance - nearest.distance).abs() <= tol
                            && apart(&c.point, &nearest.point) <= tol
                    })
                    .min_by(|a, b| cos(a).total_cmp(&cos(b)).then(a.facet.cmp(&b.facet)))
                    .unwrap_or(nearest)
            }
        };
        // Another facet as near with a different closest point: ambiguous, unless the two
        // facets are neighbours that meet at a nearly flat crease (a triangulated curved
        // surface), where either closest point is as good.
        let (_, best_normal) = mesh.facet_measure_normal(best.facet);
        let cos_crease = super::directions::CORNER_ANGLE_DEG.to_radians().cos();
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
    let Some(best) = nearest(false).filter(|c| !c.beyond) else {
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
mod tests;
