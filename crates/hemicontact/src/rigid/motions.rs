//! The rigid motions of every body that the Dirichlet conditions leave free
//! ([`RigidMotions`]; see [`super`]): found, restricted to a process's part, queried on
//! the groups' contact points, fitted to a displacement, and a body that ran away.

use super::body::{bodies, mode_row, n_modes, Body};
use super::dense::{solve_small, solve_symmetric, Normal};
use super::groups::{self, sides, Group, Motion, Side};
use crate::contact::ContactNodes;
use crate::mesh::Mesh;
use crate::parallel::Share;

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

impl RigidMotions {
    /// The sides of contact point `i` on the bodies of group `g` ([`sides`]), each with its
    /// body's place in [`Group::bodies`]: none if the point touches no body of the group.
    pub fn group_sides(
        &self,
        contact: &ContactNodes,
        mesh: &Mesh,
        i: usize,
        g: usize,
    ) -> Vec<(usize, Side)> {
        let members = &self.groups[g].bodies;
        sides(contact, mesh, i, &self.body_of)
            .into_iter()
            .flatten()
            .filter_map(|s| Some((members.binary_search(&s.body).ok()?, s)))
            .collect()
    }

    /// The change of the relative displacement of a contact point with the sides `on` (of
    /// group `g`, [`RigidMotions::group_sides`]) under the group motion `motion`:
    /// `Σ sign · r_b(x)` over its sides (m, first d entries).
    pub fn relative_motion(&self, g: usize, motion: &Motion, on: &[(usize, Side)]) -> [f64; 3] {
        let mut rho = [0.0; 3];
        for (j, side) in on {
            let r = self.displacement(self.groups[g].bodies[*j], &motion[*j], &side.x[..self.dim]);
            for k in 0..self.dim {
                rho[k] += side.sign * r[k];
            }
        }
        rho
    }

    /// The share of the rigid motion `c` of body `b` that is sliding: `‖P c‖ / ‖c‖` in the
    /// coefficients, P the orthogonal projection onto the span of body b's part of its
    /// group's sliding motions ([`Group::sliding`]); 0 for `c = 0` or a body without free
    /// motions.
    pub fn sliding_share(&self, b: usize, c: &[f64; 6]) -> f64 {
        let norm = c.iter().map(|x| x * x).sum::<f64>().sqrt();
        let g = self.group_of[b];
        if norm == 0.0 || g == u32::MAX {
            return 0.0;
        }
        let group = &self.groups[g as usize];
        let Ok(j) = group.bodies.binary_search(&b) else {
            return 0.0;
        };
        let dot = |a: &[f64; 6], b: &[f64; 6]| (0..6).map(|i| a[i] * b[i]).sum::<f64>();
        if group.bodies.len() == 1 {
            // An orthonormal basis: the projection's norm is that of the coefficients.
            let projected = group
                .sliding
                .iter()
                .map(|s| dot(&s[0], c).powi(2))
                .sum::<f64>()
                .sqrt();
            return projected / norm;
        }
        // Body b's parts of the group's motions are not orthonormal: least squares.
        let parts: Vec<&[f64; 6]> = group.sliding.iter().map(|s| &s[j]).collect();
        let k = parts.len();
        let gram: Vec<f64> = (0..k * k)
            .map(|e| dot(parts[e / k], parts[e % k]))
            .collect();
        let rhs: Vec<f64> = parts.iter().map(|p| dot(p, c)).collect();
        let y = solve_symmetric(&gram, &rhs);
        let mut projected = [0.0; 6];
        for (yl, p) in y.iter().zip(&parts) {
            for i in 0..6 {
                projected[i] += yl * p[i];
            }
        }
        dot(&projected, &projected).sqrt() / norm
    }
}
