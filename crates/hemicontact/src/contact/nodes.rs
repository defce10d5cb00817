//! Contact nodes: the nodes of Γ_C with their lumped weights, averaged normals and
//! tangent bases.
//!
//! A *contact point* is a node of a contact boundary with one direction of contact: a node on
//! two contact boundaries (an edge between two faces facing two foundations) is two points,
//! one per foundation, and so is a node where one contact boundary turns a corner (below).
//! Nodes on Γ_D are never contact nodes. For point `i`, with `𝓕_i` its facets:
//!
//! - weight `w_i = Σ_{F ∈ 𝓕_i} |F| / d` (the integral of the hat function over those
//!   facets);
//! - normal `ν_i`: the weighted average `Σ_{F ∈ 𝓕_i} |F| ν_F` of the facets' outward
//!   normals, normalized;
//! - tangents: 2D, `τ = (−ν_y, ν_x)` (counter-clockwise along the boundary); 3D,
//!   `τ₁ = e × ν / ‖e × ν‖` with `e` the axis least aligned with ν, `τ₂ = ν × τ₁`.
//!
//! # Corners
//!
//! The facets of one boundary around a node are grouped by direction: two facets are in
//! the same group when their normals differ by at most [`CORNER_ANGLE_DEG`] (30°), and
//! groups are closed under this relation (single linkage). Each group is one contact point,
//! with the weight and averaged normal of its own facets, exactly as if the boundary were
//! split into several parts at the node. On a smooth boundary every node is one point; at a
//! corner (the bottom and the side of a square in one part) the law is imposed along each
//! side's normal instead of along an average of them, which would let the body penetrate
//! the foundation of each side.
//!
//! Why 30°: consecutive facets of a curve of radius R with facets of length h turn by h/R
//! radians, so 30° is h ≈ R/2: any resolution that represents a curve (12 facets or more
//! per full circle) stays below it and keeps one point per node, while a corner keeps its
//! angle under refinement and is split at any resolution: the corner of a square (normals
//! 90° apart), and any kink that turns the boundary by more than 30°.
//!
//! Points are ordered by boundary, then by node number, then (at a corner) by the first
//! facet of each group.
//!
//! # Obstacles
//!
//! A boundary facing a rigid obstacle ([`super::obstacle`]) has one point per node, with
//! the weight of all its facets: the obstacle, not the boundary's facets, gives the
//! direction of contact. Its normal is `ν_i = −n_i`, with `n_i` the obstacle's outward
//! normal at the closest point `P(X_i)` of the node's reference position `X_i`, and its
//! gap is the signed distance `g_i = g(X_i)` (negative where the obstacle starts out inside
//! the body). A flat foundation gives every point of its boundary the same gap `g`.
//!
//! # Slip relative to the foundation
//!
//! Friction resists the motion of the body *relative to the foundation's material point*.
//! A flat foundation is at rest; an obstacle translated rigidly by `t` carries its material
//! points with it, so the slip of point i is `u_τ − t_τ`, with `t_τ` the tangential part of
//! `t` at the point: its tangential coordinates `t·τ_a` are stored per point
//! ([`ContactNodes::foundation_motion`]) and subtracted by [`ContactNodes::kinematics`],
//! which every friction term, label, certificate and output reads. Moving the obstacle by
//! `t` is then the same problem as moving every support by `−t` (Galilean invariance), with
//! `u` shifted by `t`.
//!
//! # Carried bodies
//!
//! A body whose supports carry it by a translation c ([`crate::rigid::carry`]) is solved for
//! its displacement beyond c (the solver's placement, [`ContactNodes::place`]). Its points
//! are made in the carried configuration: against a flat foundation or another body, the
//! gap less `ν_i·c` and the slip plus `τ_a·c` (a placement; exact for a flat foundation);
//! against an obstacle exactly, by projecting the node onto the obstacle translated by
//! `t − c` (its own translation t less the body's), which gives the gap, normal, tangents
//! and `foundation_motion = (t − c)·τ_a`. The relative translation is formed once, so an
//! obstacle moved by t and a body whose supports are moved by −t give the same points, bit
//! for bit. A translation `t − c` so large that double precision cannot place the nodes
//! against the obstacle ([`TRANSLATION_RESOLUTION`]) is refused.
//!
//! # Two bodies
//!
//! A boundary with a master part (`against`) has one point per slave node paired with the
//! master surface ([`super::pairing`]), with the weight of all its facets, the pair's normal
//! and gap, and the master facet's nodes m_j and shape functions N_j at the projection
//! ([`ContactNodes::master`], [`ContactNodes::master_shape`]). A node beyond the edge of the
//! master surface is no point. Where the slave part turns a corner (its facets around the
//! node fall into several direction groups, as under *Corners*), each face of the corner is
//! paired on its own ([`super::pairing::MasterSurface::pair_facing`]: at a concave corner of
//! the master surface, with the master facet that faces it) and is one point with its own
//! weight, if it faces its master point; a face whose outward normal makes a right angle or
//! more with the pair's normal ([`FACING_COSINE`]: the side of a block standing on the
//! master) is none, so that the corner node carries the weight of the faces in contact only. Every law then reads the displacement relative to the master
//! point, `u(x_i) − Σ_j N_j u(m_j)` ([`ContactNodes::relative`]), and the point's force acts
//! on its stencil: its node with coefficient 1 and the master nodes with −N_j
//! ([`ContactNodes::stencil`]).

use super::directions::{direction_groups, lumped_weight};
pub use super::directions::{tangent_basis, CORNER_ANGLE_DEG};
use super::{ContactBoundary, ContactObstacle};
use crate::mesh::Mesh;

/// The contact points of a mesh; see the module documentation.
#[derive(Clone, Debug, Default)]
pub struct ContactNodes {
    /// Mesh node of each point.
    pub node: Vec<u32>,
    /// Contact boundary (index into the problem's list) of each point.
    pub boundary: Vec<u16>,
    /// Lumped weight w_i (m² in 3D, m in 2D).
    pub weight: Vec<f64>,
    /// Unit normal ν_i of contact (outward from the body): the boundary's averaged normal,
    /// or against an obstacle the opposite of the obstacle's normal.
    pub normal: Vec<[f64; 3]>,
    /// Initial gap g_i along ν_i (m; the solver's displacement unit in its dimensionless
    /// problem): the boundary's `gap`, or the signed distance to the obstacle.
    pub gap: Vec<f64>,
    /// Orthonormal tangent basis (first d − 1 vectors used).
    pub tangent: Vec<[[f64; 3]; 2]>,
    /// Tangential coordinates `t·τ_a` of the displacement of the foundation's material
    /// point (m; the solver's displacement unit in its dimensionless problem): the rigid
    /// translation t of an obstacle, zero for a flat foundation. The slip is measured
    /// relative to it (see the module documentation).
    pub foundation_motion: Vec<[f64; 2]>,
    /// Position of the node in the reference configuration (m; unused coordinates 0), where
    /// a friction law of the position is evaluated.
    pub position: Vec<[f64; 3]>,
    /// Normal component `ν_i·u_R` (m) of a rigid placement `u_R` of the body applied
    /// before the solve (the translation its supports carry it by, and a rigid drop:
    /// [`ContactNodes::new`], [`ContactNodes::place`]), already accounted for in `gap`;
    /// empty without placement.
    pub placed_normal: Vec<f64>,
    /// Tangential coordinates `τ_a·u_R` (m) of that placement, added to the tangential
    /// displacement of every evaluation ([`ContactNodes::kinematics`]; zero for a carried
    /// translation at a point facing an obstacle, whose [`ContactNodes::foundation_motion`]
    /// is relative to the carried body); empty without placement.
    pub placed_tangential: Vec<[f64; 2]>,
    /// The nodes m_j of the master facet of each point of a contact pair (first d entries),
    /// `u32::MAX` at a point facing a foundation or an obstacle; empty when no contact part
    /// has a master part (see *Two bodies* in the module documentation).
    pub master: Vec<[u32; 3]>,
    /// The master facet's shape functions N_j at the point's projection (first d entries,
    /// ≥ 0, summing to 1), zero at a point facing a foundation or an obstacle; empty with
    /// [`ContactNodes::master`].
    pub master_shape: Vec<[f64; 3]>,
    /// How many of the last points are *ghost* points of a process's part: points of
    /// contact pairs whose slave node another process owns but whose master facet has a
    /// node of this one ([`ContactNodes::restricted`]). Their terms are assembled again here
    /// so that the rows of this process's master nodes are complete, but they are counted
    /// (energy, residuals, results) by the slave node's owner only. Zero on one process.
    pub ghosts: usize,
}

/// How finely a rigid obstacle must place the nodes of a body, relative to the body's size
/// (the diagonal of the mesh's bounding box): an obstacle's translation relative to the
/// body, `t − c` (its displacement less the translation the body's supports carry it by),
/// is refused when its round-off `ε‖t − c‖_∞` exceeds this fraction of the size, about
/// 4.5·10⁷ sizes.
pub const TRANSLATION_RESOLUTION: f64 = 1e-8;

/// The cosine between the normal of one face of a corner of a slave part and its pair's
/// normal at or below which the face does not face the master surface (a right angle, to
/// round-off): that face of the corner is no contact point (see *Two bodies* in the module
/// documentation).
pub const FACING_COSINE: f64 = 1e-9;

impl ContactNodes {
    /// Builds the contact points of `boundaries` on `mesh`, skipping nodes where
    /// `excluded[node]` is true (nodes with all components prescribed), for bodies carried
    /// by the translations `carried` (DOF order, in the units of the gaps; `None`: none; see
    /// *Carried bodies* in the module documentation).
    ///
    /// # Errors
    /// [`crate::Error::Invalid`] under `contact[b].obstacle` if an obstacle is invalid for
    /// the mesh's dimension, the closest point of a node on it is not unique (the error
    /// names the node and its position), or its translation relative to the body is beyond
    /// what double precision resolves against the body's size ([`TRANSLATION_RESOLUTION`]).
    pub fn new(
        mesh: &Mesh,
        boundaries: &[ContactBoundary],
        excluded: &[bool],
        carried: Option<&[f64]>,
    ) -> crate::Result<Self> {
        let d = mesh.dim();
        let mut out = ContactNodes::default();
        let mut on_obstacle = Vec::new();
        for (b, cb) in boundaries.iter().enumerate() {
            let facets: Vec<(f64, [f64; 3])> = mesh
                .part_facets(cb.part)
                .map(|f| mesh.facet_measure_normal(f))
                .collect();
            // (node, facet of the part) pairs, by node.
            let mut incidence: Vec<(u32, u32)> = mesh
                .part_facets(cb.part)
                .enumerate()
                .flat_map(|(k, f)| mesh.facet(f).iter().map(move |&v| (v, k as u32)))
                .collect();
            incidence.sort_unstable();
            if let Some(obstacle) = &cb.obstacle {
                let first = out.len();
                obstacle_points(
                    &mut out, mesh, b, obstacle, &facets, &incidence, excluded, carried,
                )
                .map_err(|e| e.within(&format!("contact[{b}].obstacle")))?;
                on_obstacle.extend(first..out.len());
                continue;
            }
            if let Some(master) = &cb.against {
                paired_points(&mut out, mesh, b, master, &facets, &incidence, excluded)
                    .map_err(|e| e.within(&format!("contact[{b}].against")))?;
                continue;
            }
            let mut group = Vec::new();
            for around in incidence.chunk_by(|a, b| a.0 == b.0) {
                let v = around[0].0;
                if excluded[v as usize] {
                    continue;
                }
                for (w, n) in direction_groups(around, &facets, d, &mut group) {
                    out.node.push(v);
                    out.boundary.push(b as u16);
                    out.weight.push(w);
                    out.normal.push(n);
                    out.gap.push(cb.gap);
                    out.tangent.push(tangent_basis(d, &n));
                    out.foundation_motion.push([0.0; 2]);
                    let mut x = [0.0; 3];
                    x[..d].copy_from_slice(mesh.node(v as usize));
                    out.position.push(x);
                }
            }
        }
        if !out.master.is_empty() {
            out.master.resize(out.node.len(), [u32::MAX; 3]);
            out.master_shape.resize(out.node.len(), [0.0; 3]);
        }
        if let Some(c) = carried {
            out.carry(d, c, &on_obstacle);
        }
        Ok(out)
    }

    /// Takes the carried translation `c` (DOF order) into the points: at a point facing a
    /// flat foundation or of a pair, as a placement ([`ContactNodes::place`]: the gap less
    /// the normal part of `c`, its tangential part added to the slips, linear and, for a
    /// flat foundation, exact); at the points `on_obstacle` (sorted indices), which
    /// [`obstacle_points`] made against the obstacle as the carried body meets it, only the
    /// normal part `ν_i·c`, for the normal displacement reported.
    fn carry(&mut self, dim: usize, c: &[f64], on_obstacle: &[usize]) {
        let n = self.len();
        self.placed_normal = vec![0.0; n];
        self.placed_tangential = vec![[0.0; 2]; n];
        for i in 0..n {
            let x = self.relative(dim, c, i);
            let dot = |a: &[f64; 3]| (0..dim).map(|k| a[k] * x[k]).sum::<f64>();
            self.placed_normal[i] = dot(&self.normal[i]);
            if on_obstacle.binary_search(&i).is_ok() {
                continue;
            }
            self.gap[i] -= self.placed_normal[i];
            for a in 0..dim - 1 {
                self.placed_tangential[i][a] = dot(&self.tangent[i][a]);
            }
        }
    }

    /// Whether some points are paired with a master surface (contact between two bodies).
    pub fn has_pairs(&self) -> bool {
        !self.master.is_empty()
    }

    /// The stencil of point `i`: its node with coefficient 1, then the nodes of its master
    /// facet with coefficients −N_j (a point facing a foundation or an obstacle has its node
    /// alone). The relative displacement of the point is `Σ_a c_a u(v_a)`; its contact force
    /// on node `v_a` is `c_a` times the force on the point. Returns the number of entries
    /// (1, or 1 + d), the nodes and the coefficients.
    #[inline]
    pub fn stencil(&self, dim: usize, i: usize) -> (usize, [u32; 4], [f64; 4]) {
        let mut nodes = [self.node[i], u32::MAX, u32::MAX, u32::MAX];
        let mut coef = [1.0, 0.0, 0.0, 0.0];
        match self.master.get(i) {
            Some(m) if m[0] != u32::MAX => {
                for j in 0..dim {
                    nodes[j + 1] = m[j];
                    coef[j + 1] = -self.master_shape[i][j];
                }
                (dim + 1, nodes, coef)
            }
            _ => (1, nodes, coef),
        }
    }

    /// The node pairs each point's contact term couples beyond the cells: its node with
    /// each node of its master facet ([`crate::mesh::Mesh::with_couplings`]).
    pub fn couplings(&self, dim: usize) -> Vec<[u32; 2]> {
        let mut out = Vec::new();
        for i in 0..self.len() {
            let (n, nodes, _) = self.stencil(dim, i);
            out.extend(nodes[1..n].iter().map(|&m| [nodes[0], m]));
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Where point `i` acts on the body `b` (the bodies of the mesh's nodes `body_of`), and
    /// with which sign: at its node with sign 1 if its node is in `b`; at its master point
    /// `Σ_j N_j x(m_j)` with sign −1 if its master facet is in `b` (a contact pair, the
    /// point's own node in another body); `None` if it does not touch `b`. A rigid motion
    /// `r` of `b` alone changes the point's relative displacement by `sign · r(x)`
    /// ([`ContactNodes::relative`]): the row of the point in the analysis of `b`'s free
    /// rigid motions. Returns the position (m, first `dim` entries), the sign, and the
    /// stencil entries ([`ContactNodes::stencil`]) on `b`.
    pub fn on_body(
        &self,
        mesh: &Mesh,
        i: usize,
        body_of: &[u32],
        b: usize,
    ) -> Option<([f64; 3], f64, std::ops::Range<usize>)> {
        let d = mesh.dim();
        let node = self.node[i] as usize;
        let mut x = [0.0; 3];
        if body_of[node] as usize == b {
            x[..d].copy_from_slice(mesh.node(node));
            return Some((x, 1.0, 0..1));
        }
        let (n, nodes, coef) = self.stencil(d, i);
        if n == 1 || body_of[nodes[1] as usize] as usize != b {
            return None;
        }
        for a in 1..n {
            let y = mesh.node(nodes[a] as usize);
            for k in 0..d {
                x[k] -= coef[a] * y[k];
            }
        }
        Some((x, -1.0, 1..n))
    }

    /// Number of contact points.
    pub fn len(&self) -> usize {
        self.node.len()
    }

    /// Number of the points counted here: the first ones, all but the ghost points of a
    /// process's part ([`ContactNodes::ghosts`]); [`ContactNodes::len`] on one process.
    /// Every per-point result, residual, count and sum runs over these.
    pub fn owned(&self) -> usize {
        self.node.len() - self.ghosts
    }

    /// The points `points` of these (indices, in the order given) with the mesh node `v` of
    /// each renumbered `local(v)`, the last `ghosts` of them ghost points
    /// ([`ContactNodes::ghosts`]): a process's contact points on its part of the mesh
    /// ([`crate::parallel::Subdomain::local_mesh`]), every datum copied bit for bit.
    pub fn restricted(
        &self,
        points: &[u32],
        ghosts: usize,
        local: impl Fn(u32) -> u32,
    ) -> ContactNodes {
        fn pick<T: Copy>(all: &[T], points: &[u32]) -> Vec<T> {
            if all.is_empty() {
                return Vec::new();
            }
            points.iter().map(|&i| all[i as usize]).collect()
        }
        ContactNodes {
            node: points
                .iter()
                .map(|&i| local(self.node[i as usize]))
                .collect(),
            boundary: pick(&self.boundary, points),
            weight: pick(&self.weight, points),
            normal: pick(&self.normal, points),
            gap: pick(&self.gap, points),
            tangent: pick(&self.tangent, points),
            foundation_motion: pick(&self.foundation_motion, points),
            position: pick(&self.position, points),
            placed_normal: pick(&self.placed_normal, points),
            placed_tangential: pick(&self.placed_tangential, points),
            master: pick(&self.master, points)
                .into_iter()
                .map(|m: [u32; 3]| m.map(|v| if v == u32::MAX { v } else { local(v) }))
                .collect(),
            master_shape: pick(&self.master_shape, points),
            ghosts,
        }
    }

    /// Whether there are no contact points.
    pub fn is_empty(&self) -> bool {
        self.node.is_empty()
    }

    /// Normal displacement `u_ν = u·ν` and tangential coordinates of the slip
    /// `ξ_a = u·τ_a − t_a` of point `i` for the displacement `u` (DOF order), relative to
    /// the foundation's material point ([`ContactNodes::foundation_motion`] `t_a`). After a
    /// rigid placement `u_R` ([`ContactNodes::place`]), `u` is the displacement relative to
    /// it: `u_ν` is then relative too (to be compared with the remaining `gap`), and
    /// `ξ_a = (u + u_R)·τ_a − t_a` is the whole slip, which the friction law sees.
    ///
    /// At a point of a contact pair, `u` at the node is replaced by the relative displacement
    /// `u(x_i) − Σ_j N_j u(m_j)` ([`ContactNodes::stencil`]).
    #[inline]
    pub fn kinematics(&self, dim: usize, u: &[f64], i: usize) -> (f64, [f64; 2]) {
        let x = self.relative(dim, u, i);
        let dot = |a: &[f64; 3]| (0..dim).map(|k| a[k] * x[k]).sum::<f64>();
        let mut xi = [0.0; 2];
        for (a, t) in self.tangent[i].iter().enumerate().take(dim - 1) {
            xi[a] = dot(t) - self.foundation_motion[i][a];
        }
        if let Some(placed) = self.placed_tangential.get(i) {
            for a in 0..dim - 1 {
                xi[a] += placed[a];
            }
        }
        (dot(&self.normal[i]), xi)
    }

    /// The displacement of point `i`'s node relative to its master point,
    /// `Σ_a c_a u(v_a)` over its stencil ([`ContactNodes::stencil`]): the node's
    /// displacement alone at a point facing a foundation or an obstacle (m; first d
    /// entries).
    #[inline]
    pub fn relative(&self, dim: usize, u: &[f64], i: usize) -> [f64; 3] {
        let v = self.node[i] as usize;
        let mut x = [0.0; 3];
        x[..dim].copy_from_slice(&u[dim * v..dim * v + dim]);
        if let Some(m) = self.master.get(i).filter(|m| m[0] != u32::MAX) {
            for (j, &mj) in m.iter().enumerate().take(dim) {
                let (c, mj) = (self.master_shape[i][j], mj as usize);
                for k in 0..dim {
                    x[k] -= c * u[dim * mj + k];
                }
            }
        }
        x
    }

    /// Moves the bodies rigidly by `u_r` (DOF order, m) before a solve, which then solves
    /// for the displacement `u − u_r` relative to this placement: each point's gap becomes
    /// `g_i − ν_i·u_r(x_i)` (the part of the gap the placement has closed is subtracted
    /// once, exactly, instead of being carried through every evaluation of `u_ν − g`), and
    /// its tangential coordinates `τ_a·u_r(x_i)` are kept in
    /// [`ContactNodes::placed_tangential`] and added back by
    /// [`ContactNodes::kinematics`]. A placement adds to an earlier one (the carried
    /// translations of [`ContactNodes::new`]).
    pub fn place(&mut self, dim: usize, u_r: &[f64]) {
        let n = self.len();
        if self.placed_normal.len() != n {
            self.placed_normal = vec![0.0; n];
            self.placed_tangential = vec![[0.0; 2]; n];
        }
        for i in 0..n {
            let x = self.relative(dim, u_r, i);
            let dot = |a: &[f64; 3]| (0..dim).map(|k| a[k] * x[k]).sum::<f64>();
            let normal = dot(&self.normal[i]);
            self.placed_normal[i] += normal;
            self.gap[i] -= normal;
            for a in 0..dim - 1 {
                self.placed_tangential[i][a] += dot(&self.tangent[i][a]);
            }
        }
    }
}

/// Appends the points of boundary `b` facing `obstacle`: one per node of `incidence`
/// (sorted (node, facet) pairs) not `excluded`, weighted by all its facets, with the gap and
/// the reversed normal of its closest-point projection and the tangential part of the
/// obstacle's translation (see the module documentation).
#[allow(clippy::too_many_arguments)]
fn obstacle_points(
    out: &mut ContactNodes,
    mesh: &Mesh,
    b: usize,
    obstacle: &ContactObstacle,
    facets: &[(f64, [f64; 3])],
    incidence: &[(u32, u32)],
    excluded: &[bool],
    carried: Option<&[f64]>,
) -> crate::Result<()> {
    let d = mesh.dim();
    let (lo, hi) = mesh.bounding_box();
    let size = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt() * obstacle.length_unit;
    for around in incidence.chunk_by(|a, b| a.0 == b.0) {
        let v = around[0].0;
        if excluded[v as usize] {
            continue;
        }
        let mut x = [0.0; 3];
        x[..d].copy_from_slice(mesh.node(v as usize));
        let mut c = [0.0; 3];
        if let Some(carried) = carried {
            c[..d].copy_from_slice(&carried[d * v as usize..d * v as usize + d]);
        }
        let (projection, relative) = obstacle.project_carried(x, d, c).map_err(|e| match e {
            crate::Error::Invalid {
                field,
                value,
                allowed,
            } if field == "position" => crate::Error::Invalid {
                field: String::new(),
                value: format!("node {v} at {value}"),
                allowed: format!(
                    "an obstacle on which every contact node has a unique \
                                      closest point: {allowed}"
                ),
            },
            e => e,
        })?;
        let far = relative.iter().map(|t| t.abs()).fold(0.0f64, f64::max) * obstacle.gap_unit;
        if !(far * f64::EPSILON <= TRANSLATION_RESOLUTION * size
            && relative.iter().all(|t| t.is_finite()))
        {
            return Err(crate::Error::Invalid {
                field: "displacement".into(),
                value: format!(
                    "{} m relative to the body at node {v} (the obstacle's displacement less \
                     the translation the body's supports carry it by)",
                    crate::display::significant(far)
                ),
                allowed: format!(
                    "a translation of the obstacle relative to the body of at most {} m, \
                     {:.1e} times the body's size ({} m): beyond it double precision cannot \
                     place the body's nodes against the obstacle to {:.0e} of the body's size",
                    crate::display::significant(TRANSLATION_RESOLUTION * size / f64::EPSILON),
                    TRANSLATION_RESOLUTION / f64::EPSILON,
                    crate::display::significant(size),
                    TRANSLATION_RESOLUTION
                ),
            });
        }
        let n = projection.normal.map(|c| -c);
        let tangent = tangent_basis(d, &n);
        let mut motion = [0.0; 2];
        for (m, t) in motion.iter_mut().zip(&tangent).take(d - 1) {
            *m = (0..d).map(|k| t[k] * relative[k]).sum();
        }
        out.node.push(v);
        out.boundary.push(b as u16);
        out.weight.push(lumped_weight(around, facets, d));
        out.normal.push(n);
        out.gap.push(projection.gap);
        out.tangent.push(tangent);
        out.foundation_motion.push(motion);
        out.position.push(x);
    }
    Ok(())
}

/// Appends the points of the slave boundary `b` paired with the master part `master`: one
/// per node of `incidence` (sorted (node, facet) pairs) not `excluded`, not a node of the
/// master part too (a crack's tip, which joins its two faces) and not separated from the
/// master surface, weighted by all its facets, with the normal, gap (in the master's gap
/// unit), facet nodes and shape functions of its closest-point projection
/// ([`super::pairing::MasterSurface::pair`]).
fn paired_points(
    out: &mut ContactNodes,
    mesh: &Mesh,
    b: usize,
    master: &super::MasterPart,
    facets: &[(f64, [f64; 3])],
    incidence: &[(u32, u32)],
    excluded: &[bool],
) -> crate::Result<()> {
    use super::pairing::{MasterSurface, Pairing};
    let d = mesh.dim();
    let master_facets: Vec<usize> = mesh.part_facets(master.part).collect();
    // A node of both parts (the tip of a crack whose two faces are the parts) joins them:
    // no contact point there.
    let mut on_master = vec![false; mesh.n_nodes()];
    for &f in &master_facets {
        for &v in mesh.facet(f) {
            on_master[v as usize] = true;
        }
    }
    let surface = MasterSurface::new(mesh, &master_facets);
    let n_before = out.node.len();
    out.master.resize(n_before, [u32::MAX; 3]);
    out.master_shape.resize(n_before, [0.0; 3]);
    let mut group = Vec::new();
    for around in incidence.chunk_by(|a, b| a.0 == b.0) {
        let v = around[0].0;
        if excluded[v as usize] || on_master[v as usize] {
            continue;
        }
        let faces = direction_groups(around, facets, d, &mut group);
        // One point per face of a corner of the slave part that faces its master point;
        // one point with the weight of all its facets on a smooth part.
        let corner = faces.len() > 1;
        for (w, n_face) in faces {
            let (weight, facing) = if corner {
                (w, Some(n_face))
            } else {
                (lumped_weight(around, facets, d), None)
            };
            let projection = match surface.pair_facing(v, facing) {
                Ok(Pairing::Paired(p)) => p,
                Ok(Pairing::Separated) => continue,
                Err(message) => {
                    return Err(crate::Error::Invalid {
                        field: String::new(),
                        value: message,
                        allowed: "a master part on which every node of the slave part has \
                                  one closest point"
                            .into(),
                    })
                }
            };
            let n = projection.normal;
            if corner && (0..3).map(|k| n[k] * n_face[k]).sum::<f64>() <= FACING_COSINE {
                continue;
            }
            let mut x = [0.0; 3];
            x[..d].copy_from_slice(mesh.node(v as usize));
            out.node.push(v);
            out.boundary.push(b as u16);
            out.weight.push(weight);
            out.normal.push(n);
            out.gap.push(master.gap(projection.gap));
            out.tangent.push(tangent_basis(d, &n));
            out.foundation_motion.push([0.0; 2]);
            out.position.push(x);
            let mut nodes = [u32::MAX; 3];
            let mut shape = [0.0; 3];
            nodes[..d].copy_from_slice(&projection.nodes[..d]);
            shape[..d].copy_from_slice(&projection.shape[..d]);
            out.master.push(nodes);
            out.master_shape.push(shape);
        }
    }
    Ok(())
}
