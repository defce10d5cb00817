//! Rigid motions left free by the Dirichlet conditions, found algebraically from the mesh
//! and the pattern of prescribed components (independent of loads and of the linear solver).
//!
//! The linear elastic energy of a connected body vanishes exactly on its rigid motions. On
//! each connected component of the cell graph (a *body*) these are, in coefficients
//! `c ∈ ℝ^m` (m = 3 in 2D, 6 in 3D),
//!
//! ```text
//!     r(x) = a + ω × (x − x̄),   a = (c_1, …, c_d),   ω = (c_{d+1}, …, c_m) / L
//! ```
//!
//! about the body's centroid `x̄` (mean of its node coordinates), with `L` the largest
//! distance of a node from `x̄`; so every basis field has components of size at most 1 at
//! every node, and the matrices below are well scaled whatever the units and the size.
//!
//! Each prescribed DOF (node `v`, component `i`) is a row `C_{·j} = φ_j(x_v)_i` of the
//! constraint matrix acting on `c`; the free motions are the null space of the normal
//! matrix `N = CᵀC` (m × m), computed by a Jacobi eigendecomposition. An eigenvalue counts
//! as zero when it is at most [`NULL_TOLERANCE`] times `tr N`. Every row has norm between 1
//! (its translation entry) and √2, so `tr N` lies between the row count and twice it, the
//! round-off of `N` is about `10⁻¹⁶ tr N`, and the tolerance `10⁻¹⁰ tr N` sits six orders
//! above it; the price is that a rotation held only by lever arms below about `10⁻⁵ L`
//! counts as free — such a constraint would leave the stiffness matrix with a condition
//! number above 10¹⁰ anyway.
//!
//! A free motion is *carried* by contact when a contact point's normal (or, on a part with
//! friction, a tangent) moves under it: the same construction with one row `ν_i · r(x_i)`
//! per contact point (and `τ_i · r(x_i)` with friction), restricted to the free motions,
//! has no null space. A contact pair's point acts on the slave body at its node and on the
//! master body at its master point `x_m = Σ_j N_j x(m_j)` ([`ContactNodes::on_body`]); when
//! both bodies of a pair have free motions, the bodies so linked are analysed together, a
//! *group* whose unknowns are their stacked coefficients and whose pair rows are
//! `ν_i · (r_s(x_s) − r_m(x_m))` ([`groups`]; a body in no such pair is a group of one).
//! Motions neither prescribed nor carried make the problem singular: [`RigidMotions::check`]
//! turns them into an [`Error::RigidMotion`] that names the bodies and the motion
//! (translation along x, rotation about z through a point, …) and what would block it.
//!
//! The free motions of a group split into two orthogonal subspaces (in the coefficients
//! `c`): the *sliding* motions, which move no contact point along its normal (the null
//! space of the normal rows alone: friction, if anything, carries them), and the *pressed*
//! motions, which move some contact point along its normal (normal contact carries them).
//! A block resting on a flat foundation without supports slides along the foundation's
//! plane (2D: translation along it; 3D: two translations and the rotation about the
//! normal) and is pressed along the normal and by the tilts. The solver treats them
//! differently ([`crate::solver::held`]): the rigid drop before Newton moves along the
//! pressed motions only, and the load along the sliding ones is checked against the
//! friction limit.

pub mod carry;
mod dense;
pub mod groups;
mod words;

pub use dense::{solve_small, solve_symmetric};
pub use groups::{Group, Motion, Side};
pub use words::describe;

use crate::contact::ContactNodes;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::parallel::Share;
use dense::Normal;

/// Relative tolerance on the eigenvalues of the normal matrices: an eigenvalue at most
/// `NULL_TOLERANCE · tr N` spans a free motion (see the module documentation).
pub const NULL_TOLERANCE: f64 = 1e-10;

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

/// The rigid motions of every body of a mesh that the Dirichlet conditions leave free.
#[derive(Clone, Debug, PartialEq)]
pub struct RigidMotions {
    /// Dimension d.
    pub dim: usize,
    /// The bodies (connected components), ordered by their smallest node.
    pub bodies: Vec<Body>,
    /// Per body: orthonormal basis of the free motions, as coefficient vectors `c` (first
    /// m = 3 or 6 entries used; see the module documentation).
    pub free: Vec<Vec<[f64; 6]>>,
    /// The groups of the bodies with free motions, ordered by their smallest body: bodies
    /// linked by contact pairs between two of them, each with the motions of its bodies
    /// that contact does not carry, those only friction carries and those normal contact
    /// carries ([`Group`]; a body in no such pair is a group of one).
    pub groups: Vec<Group>,
    /// The group of each body (`u32::MAX` for a body without free motions).
    pub group_of: Vec<u32>,
    /// The body of each mesh node (`u32::MAX` for a node in no cell).
    pub body_of: Vec<u32>,
}

impl RigidMotions {
    /// Finds the free and uncarried rigid motions of every body of `mesh`: `fixed(k)` tells
    /// whether DOF `k = d·node + i` is prescribed, `contact` are the contact points and
    /// `frictional[b]` whether contact boundary `b` has friction.
    pub fn new(
        mesh: &Mesh,
        fixed: impl Fn(usize) -> bool,
        contact: &ContactNodes,
        frictional: &[bool],
    ) -> Self {
        let d = mesh.dim();
        let m = n_modes(d);
        let (body_of, bodies) = bodies(mesh);
        let mut free = Vec::with_capacity(bodies.len());
        for body in &bodies {
            // Constraint rows of the prescribed DOFs.
            let mut normal = Normal::new(m);
            for &v in &body.nodes {
                let x = mesh.node(v as usize);
                for i in 0..d {
                    if fixed(d * v as usize + i) {
                        let mut dir = [0.0; 3];
                        dir[i] = 1.0;
                        normal.add(&mode_row(d, body, x, &dir));
                    }
                }
            }
            let z: Vec<[f64; 6]> = normal
                .null_space()
                .into_iter()
                .map(|c| {
                    let mut a = [0.0; 6];
                    a[..m].copy_from_slice(&c);
                    a
                })
                .collect();
            free.push(z);
        }
        let (groups, group_of) =
            groups::analyse(mesh, &bodies, &body_of, &free, contact, frictional);
        RigidMotions {
            dim: d,
            bodies,
            free,
            groups,
            group_of,
            body_of,
        }
    }

    /// Whether some body has a free rigid motion (carried by contact or not).
    pub fn any_free(&self) -> bool {
        self.free.iter().any(|f| !f.is_empty())
    }

    /// The displacement (m) at `x` of the rigid motion with coefficients `c` of body `b`.
    pub fn displacement(&self, b: usize, c: &[f64; 6], x: &[f64]) -> [f64; 3] {
        let body = &self.bodies[b];
        let mut r = [0.0; 3];
        for (i, ri) in r.iter_mut().enumerate().take(self.dim) {
            let mut dir = [0.0; 3];
            dir[i] = 1.0;
            let row = mode_row(self.dim, body, x, &dir);
            *ri = (0..n_modes(self.dim)).map(|j| row[j] * c[j]).sum();
        }
        r
    }

    /// The free motions of body `b` in words, one per basis vector (see [`describe`]).
    pub fn describe_free(&self, b: usize) -> Vec<String> {
        let one: Vec<Motion> = self.free[b].iter().map(|c| vec![*c]).collect();
        words::reduced(self.dim, &one)
            .iter()
            .map(|c| describe(self.dim, &self.bodies[b], &c[0]))
            .collect()
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
fn mode_row(d: usize, body: &Body, x: &[f64], dir: &[f64; 3]) -> [f64; 6] {
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

fn mode_row_norm2(row: &[f64; 6], m: usize) -> f64 {
    row[..m].iter().map(|x| x * x).sum()
}

/// Relative size of the shift added to the diagonal of the Newton matrix on bodies with
/// free rigid motions carried by contact: `α = NEWTON_SHIFT · max_k H_kk` over their free
/// equations, at the first assembly.
///
/// While the contact holding such a body is not yet active (a gap, or the kink at zero
/// gap), its rigid motions have no stiffness and the Newton matrix is singular. The shift
/// `α I` (Levenberg–Marquardt) makes it definite; it enters the Newton *matrix* only, never
/// the energy or its gradient, so the line search, the convergence test, the certificate
/// and therefore the converged displacement are those of the unmodified problem — the
/// stabilizing force is identically zero. Along an unloaded rigid motion the step is
/// `f_r / (α n)`: far beyond the contact, where the line search stops it at the first
/// contact kink (exactly: the energy is linear until the kink). Once contact is active,
/// the shift slows Newton's convergence to the linear rate `α / λ_min(H)`, negligible for
/// `10⁻⁸` against the smallest stiffness of any mesh solved here (`λ_min / max H_kk ≳ h²`).
pub const NEWTON_SHIFT: f64 = 1e-8;

impl RigidMotions {
    /// These motions on a part of the mesh whose node `l` is the whole mesh's `nodes[l]`
    /// ([`crate::parallel::Subdomain::local_mesh`]): each body lists the part's nodes in it
    /// (increasing), and [`RigidMotions::body_of`] is the part's; the bodies' motions,
    /// centroids, sizes and boxes are the whole bodies'.
    pub(crate) fn restricted(&self, nodes: &[u32]) -> RigidMotions {
        let body_of: Vec<u32> = nodes.iter().map(|&v| self.body_of[v as usize]).collect();
        let mut bodies: Vec<Body> = self
            .bodies
            .iter()
            .map(|b| Body {
                nodes: Vec::new(),
                centroid: b.centroid,
                size: b.size,
                bounding_box: b.bounding_box,
                regions: b.regions.clone(),
            })
            .collect();
        for (l, &b) in body_of.iter().enumerate() {
            if b != u32::MAX {
                bodies[b as usize].nodes.push(l as u32);
            }
        }
        RigidMotions {
            dim: self.dim,
            bodies,
            free: self.free.clone(),
            groups: self.groups.clone(),
            group_of: self.group_of.clone(),
            body_of,
        }
    }

    /// The DOFs (`d·node + i`) of the bodies that have a free rigid motion: where the
    /// Newton matrix is shifted (see [`NEWTON_SHIFT`]).
    pub fn shifted_dofs(&self) -> Vec<usize> {
        let d = self.dim;
        let mut dofs = Vec::new();
        for (body, free) in self.bodies.iter().zip(&self.free) {
            if !free.is_empty() {
                dofs.extend(
                    body.nodes
                        .iter()
                        .flat_map(|&v| (0..d).map(move |i| d * v as usize + i)),
                );
            }
        }
        dofs.sort_unstable();
        dofs
    }

    /// The free rigid motions of all bodies in words (empty if none), each prefixed with
    /// its mesh component when the mesh has several.
    pub fn describe_all(&self) -> Vec<String> {
        let several = self.bodies.len() > 1;
        (0..self.bodies.len())
            .flat_map(|b| {
                self.describe_free(b).into_iter().map(move |s| {
                    if several {
                        format!("mesh component {}: {s}", b + 1)
                    } else {
                        s
                    }
                })
            })
            .collect()
    }

    /// The largest generalized force `|Σ_v r(x_v) · g_v| / max_v |r(x_v)|` (N) over the
    /// orthonormal free motions `r` of every body, for the nodal force vector `g` (DOF
    /// order): for a translation the net force along it, for a rotation the moment about
    /// its axis divided by the body's size. Zero without free motions.
    ///
    /// The sums and maxima run over the nodes `share` counts and are completed over the
    /// processes.
    pub fn generalized_force(&self, mesh: &Mesh, g: &[f64], share: &Share) -> f64 {
        let d = self.dim;
        let (mut forces, mut reaches) = (Vec::new(), Vec::new());
        for (b, body) in self.bodies.iter().enumerate() {
            for c in &self.free[b] {
                let (mut force, mut reach) = (0.0, 0.0f64);
                for &v in body
                    .nodes
                    .iter()
                    .filter(|&&v| share.counts_node(v as usize))
                {
                    let r = self.displacement(b, c, mesh.node(v as usize));
                    let n = (0..d).map(|i| r[i] * r[i]).sum::<f64>().sqrt();
                    reach = reach.max(n);
                    force += (0..d).map(|i| r[i] * g[d * v as usize + i]).sum::<f64>();
                }
                forces.push(force);
                reaches.push(reach);
            }
        }
        share.sum(&mut forces);
        share.max(&mut reaches);
        let mut worst = 0.0f64;
        for (force, reach) in forces.iter().zip(&reaches) {
            if *reach > 0.0 {
                worst = worst.max(force.abs() / reach);
            }
        }
        worst
    }

    /// The free rigid motion of body `b` closest to the displacement `u` (DOF order) on
    /// that body, in the least-squares sense over its nodes: its coefficients (first m
    /// entries; see the module documentation), with components below 10⁻⁹ of the largest
    /// set to zero so that a motion along an axis reads as such. Zero if `b` has no free
    /// motion. The sums run over the nodes `share` counts and are completed over the
    /// processes.
    pub fn fitted_motion(&self, mesh: &Mesh, b: usize, u: &[f64], share: &Share) -> [f64; 6] {
        let d = self.dim;
        let basis = &self.free[b];
        let k = basis.len();
        let mut gram = [[0.0; 6]; 6];
        let mut rhs = [0.0; 6];
        let nodes = self.bodies[b].nodes.iter();
        for &v in nodes.filter(|&&v| share.counts_node(v as usize)) {
            let x = mesh.node(v as usize);
            let fields: Vec<[f64; 3]> = basis.iter().map(|c| self.displacement(b, c, x)).collect();
            for l in 0..k {
                rhs[l] += (0..d)
                    .map(|i| fields[l][i] * u[d * v as usize + i])
                    .sum::<f64>();
                for j in 0..k {
                    gram[l][j] += (0..d).map(|i| fields[l][i] * fields[j][i]).sum::<f64>();
                }
            }
        }
        share.sum_parts(&mut [gram.as_flattened_mut(), &mut rhs]);
        let y = solve_small(&gram, &rhs, k);
        let mut c = [0.0; 6];
        for (l, zl) in basis.iter().enumerate() {
            for j in 0..6 {
                c[j] += y[l] * zl[j];
            }
        }
        let largest = c.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        for x in &mut c {
            if x.abs() <= 1e-9 * largest {
                *x = 0.0;
            }
        }
        c
    }

    /// The rigid motion with coefficients `c` of body `b` in words, in coordinates whose
    /// unit is `length` times that of the mesh (1 for a mesh in metres; the length scale
    /// `L` of [`crate::solver::scaling`] for a mesh in its dimensionless variables).
    pub fn describe_in(&self, b: usize, c: &[f64; 6], length: f64) -> String {
        let body = self.bodies[b].in_units(length);
        describe(self.dim, &body, c)
    }

    /// The first body with a free rigid motion that has moved by more than its size under
    /// the displacement `u` (DOF order), with the motion it moved along
    /// ([`RigidMotions::fitted_motion`]); `None` if no body has. `length` is the unit of
    /// the coordinates in units of the displacements (1 when both are in metres; `L/U` in
    /// the dimensionless variables of [`crate::solver::scaling`]). Small-strain
    /// displacements never approach the size of the body: such a body has left the contact
    /// that was to carry its free motions (or slid off the friction meant to hold it).
    /// Over the nodes `share` counts, completed over the processes.
    pub fn runaway(&self, mesh: &Mesh, u: &[f64], length: f64, share: &Share) -> Option<Runaway> {
        let d = self.dim;
        // How far each body moved, over every process (0 for one without free motions).
        let mut moved: Vec<f64> = self
            .bodies
            .iter()
            .enumerate()
            .map(|(b, body)| {
                if self.free[b].is_empty() {
                    return 0.0;
                }
                let nodes = body.nodes.iter();
                nodes
                    .filter(|&&v| share.counts_node(v as usize))
                    .map(|&v| {
                        (0..d)
                            .map(|i| u[d * v as usize + i].powi(2))
                            .sum::<f64>()
                            .sqrt()
                    })
                    .fold(0.0, f64::max)
            })
            .collect();
        share.max(&mut moved);
        for (b, body) in self.bodies.iter().enumerate() {
            if self.free[b].is_empty() {
                continue;
            }
            let moved = moved[b];
            if moved > body.size * length || !moved.is_finite() {
                let motion = if moved.is_finite() {
                    self.fitted_motion(mesh, b, u, share)
                } else {
                    [0.0; 6]
                };
                return Some(Runaway {
                    body: b,
                    motion,
                    moved,
                });
            }
        }
        None
    }

    /// # Errors
    /// [`Error::ContactLost`] if a body with a free rigid motion has moved by more than
    /// its size under the displacement `u` ([`RigidMotions::runaway`]; `length` as there):
    /// the message names the motion it moved along and how far, in the units of `u` and of
    /// the mesh.
    pub fn check_runaway(&self, mesh: &Mesh, u: &[f64], length: f64) -> Result<()> {
        match self.runaway(mesh, u, length, &Share::WHOLE) {
            None => Ok(()),
            Some(r) => Err(self.contact_lost(&r, 1.0, length)),
        }
    }

    /// The [`Error::ContactLost`] of a runaway, described in the user's units: `length` (m)
    /// the unit of the mesh's coordinates, `displacement` (m) that of the displacements.
    pub fn contact_lost(&self, r: &Runaway, length: f64, displacement: f64) -> Error {
        let b = r.body;
        let which = match self.label(b) {
            l if l.is_empty() => l,
            l => format!("{l}: "),
        };
        let motion = if r.motion.iter().any(|&x| x != 0.0) {
            self.describe_in(b, &r.motion, length)
        } else {
            self.free[b]
                .iter()
                .map(|c| self.describe_in(b, c, length))
                .collect::<Vec<_>>()
                .join("; ")
        };
        Error::ContactLost {
            motions: format!(
                "{which}{motion} (the body moved by {} m, more than its size {} m)",
                crate::display::significant(r.moved * displacement),
                crate::display::significant(self.bodies[b].size * length)
            ),
        }
    }
}

/// A body that moved by more than its size ([`RigidMotions::runaway`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Runaway {
    /// The body.
    pub body: usize,
    /// The free rigid motion it moved along (coefficients; zero if the displacement is not
    /// finite).
    pub motion: [f64; 6],
    /// How far it moved: its largest nodal displacement (units of the displacements).
    pub moved: f64,
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
