//! Groups of bodies whose free rigid motions contact pairs couple, and the joint analysis of
//! their motions: which are carried by contact, which only by friction (*sliding*), which by
//! normal contact (*pressed*).
//!
//! A contact point acts on up to two bodies, its *sides* ([`sides`]): its node's body, where
//! a rigid motion `r` changes the point's relative displacement by `+r(x_s)`, and, at a point
//! of a contact pair, its master facet's body, where it changes it by `−r(x_m)` at the master
//! point `x_m = Σ_j N_j x(m_j)`. When both bodies of a pair have free rigid motions (a block
//! resting on a block that rests on a held foundation), neither can be analysed alone: the
//! bodies linked through such pairs form a *group*, and its unknowns are the stacked
//! coefficients `y = (y_1, …, y_n)` of its bodies' free motions (`c_b = Z_b y_b`, `Z_b` the
//! orthonormal basis of body b's free motions, [`super::RigidMotions::free`]). The row of a
//! contact point along a direction `e` (its normal, or a tangent on a part with friction)
//! is
//!
//! ```text
//!     e · ( r_s(y_s)(x_s) − r_m(y_m)(x_m) ),
//! ```
//!
//! each term present when its body is in the group (a point between a body of the group and
//! a held body, a foundation or an obstacle has the one term). The analysis of one body
//! ([`super`]) then runs over the group's stacked coefficients: the null space of all rows
//! restricted to the free motions is the group's *uncarried* motions, that of the normal
//! rows alone its *sliding* motions, their complement its *pressed* motions. A body with
//! free motions in no such pair is a group of one, and the analysis is the single body's,
//! bit for bit. A stack of two blocks, each held sideways, on a held foundation: the group
//! of the two blocks has the rows `−y_1` (the lower block on the foundation) and `y_1 − y_2`
//! (the upper on the lower), and no uncarried motion; without the foundation the joint
//! translation `y_1 = y_2` is uncarried.
//!
//! Every group motion is written per body ([`Motion`]), and the basis vectors of a group
//! are orthonormal in the stacked coefficients.

use super::body::{mode_row, mode_row_norm2, n_modes, Body};
use super::dense::Normal;
use crate::contact::ContactNodes;
use crate::mesh::Mesh;

/// A rigid motion of a group of bodies: the coefficients (first m entries; see
/// [`super`]) of the motion of each of its bodies, in the order of [`Group::bodies`].
pub type Motion = Vec<[f64; 6]>;

/// Bodies with free rigid motions linked through contact pairs whose two sides both have
/// free rigid motions, with their joint analysis (see the module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    /// Its bodies (indices into [`super::RigidMotions::bodies`]), increasing.
    pub bodies: Vec<usize>,
    /// Orthonormal basis of the group's free motions that no contact point carries.
    pub uncarried: Vec<Motion>,
    /// Orthonormal basis of the group's free motions that move no contact point along its
    /// normal: carried by friction alone, if at all (contains `uncarried`).
    pub sliding: Vec<Motion>,
    /// Orthonormal basis of the orthogonal complement of `sliding` in the group's free
    /// motions: those that normal contact carries.
    pub pressed: Vec<Motion>,
}

/// Where a contact point acts on one body ([`sides`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Side {
    /// The body.
    pub body: usize,
    /// The point on it (m, first d entries): the slave node, or the master point
    /// `Σ_j N_j x(m_j)`.
    pub x: [f64; 3],
    /// How a rigid motion `r` of the body changes the point's relative displacement:
    /// `sign · r(x)`, +1 at the slave node, −1 at the master point.
    pub sign: f64,
    /// The point's stencil entries ([`ContactNodes::stencil`]) on the body: `0..1` for the
    /// slave node, `1..1 + d` for the master facet's nodes.
    pub stencil: std::ops::Range<usize>,
}

/// The sides of contact point `i` (`body_of` the body of each mesh node): its node's body
/// and, at a point of a contact pair, its master facet's body (the same body for a pair of
/// two parts of one body). The master point is computed as in
/// [`ContactNodes::on_body`].
pub fn sides(contact: &ContactNodes, mesh: &Mesh, i: usize, body_of: &[u32]) -> [Option<Side>; 2] {
    let d = mesh.dim();
    let node = contact.node[i] as usize;
    let mut x = [0.0; 3];
    x[..d].copy_from_slice(mesh.node(node));
    let slave = Side {
        body: body_of[node] as usize,
        x,
        sign: 1.0,
        stencil: 0..1,
    };
    let (n, nodes, coef) = contact.stencil(d, i);
    if n == 1 {
        return [Some(slave), None];
    }
    let mut x = [0.0; 3];
    for a in 1..n {
        let y = mesh.node(nodes[a] as usize);
        for k in 0..d {
            x[k] -= coef[a] * y[k];
        }
    }
    let master = Side {
        body: body_of[nodes[1] as usize] as usize,
        x,
        sign: -1.0,
        stencil: 1..n,
    };
    [Some(slave), Some(master)]
}

/// The groups of the bodies with free motions (`free[b]` non-empty), ordered by their
/// smallest body, and the group of each body (`u32::MAX` for a body without free motions):
/// bodies joined by a contact pair between two of them (see the module documentation).
fn form(
    contact: &ContactNodes,
    d: usize,
    body_of: &[u32],
    free: &[Vec<[f64; 6]>],
) -> Vec<Vec<usize>> {
    let n = free.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(parent: &mut [usize], mut b: usize) -> usize {
        while parent[b] != b {
            parent[b] = parent[parent[b]];
            b = parent[b];
        }
        b
    }
    for i in 0..contact.len() {
        let (k, nodes, _) = contact.stencil(d, i);
        if k == 1 {
            continue;
        }
        let (s, t) = (
            body_of[nodes[0] as usize] as usize,
            body_of[nodes[1] as usize] as usize,
        );
        if s != t && !free[s].is_empty() && !free[t].is_empty() {
            let (rs, rt) = (find(&mut parent, s), find(&mut parent, t));
            parent[rs.max(rt)] = rs.min(rt);
        }
    }
    let mut index_of_root = vec![usize::MAX; n];
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for b in (0..n).filter(|&b| !free[b].is_empty()) {
        let r = find(&mut parent, b);
        if index_of_root[r] == usize::MAX {
            index_of_root[r] = groups.len();
            groups.push(Vec::new());
        }
        groups[index_of_root[r]].push(b);
    }
    groups
}

/// The groups of the bodies `bodies` of `mesh` with free motions `free` (per body,
/// orthonormal coefficient vectors) and their joint analysis against the contact points
/// `contact` (`frictional[b]`: whether contact boundary b has friction); with the group of
/// each body (`u32::MAX` for a body without free motions).
pub(super) fn analyse(
    mesh: &Mesh,
    bodies: &[Body],
    body_of: &[u32],
    free: &[Vec<[f64; 6]>],
    contact: &ContactNodes,
    frictional: &[bool],
) -> (Vec<Group>, Vec<u32>) {
    let d = mesh.dim();
    let m = n_modes(d);
    let members = form(contact, d, body_of, free);
    let mut group_of = vec![u32::MAX; bodies.len()];
    let mut groups = Vec::with_capacity(members.len());
    for (g, members) in members.into_iter().enumerate() {
        for &b in &members {
            group_of[b] = g as u32;
        }
        // Offsets of the bodies' coefficients in the stacked unknowns.
        let mut offset = Vec::with_capacity(members.len() + 1);
        offset.push(0);
        for &b in &members {
            offset.push(offset[offset.len() - 1] + free[b].len());
        }
        let k = offset[members.len()];
        // Contact rows restricted to the free motions: all of them (`carried`), and the
        // normal rows alone (`pressing`).
        let mut carried = Normal::new(k);
        let mut pressing = Normal::new(k);
        for p in 0..contact.len() {
            let on: Vec<(usize, Side)> = sides(contact, mesh, p, body_of)
                .into_iter()
                .flatten()
                .filter_map(|s| Some((members.binary_search(&s.body).ok()?, s)))
                .collect();
            if on.is_empty() {
                continue;
            }
            let restricted = |dir: &[f64; 3]| {
                let mut r = vec![0.0; k];
                let mut n2 = 0.0;
                for (j, side) in &on {
                    let b = members[*j];
                    let row = mode_row(d, &bodies[b], &side.x[..d], dir);
                    for (l, zl) in free[b].iter().enumerate() {
                        let v: f64 = (0..m).map(|i| row[i] * zl[i]).sum();
                        // One side: the row as the single body's (its sign squares away).
                        r[offset[*j] + l] += if on.len() == 1 { v } else { side.sign * v };
                    }
                    n2 += mode_row_norm2(&row, m);
                }
                (r, n2)
            };
            let (r, n2) = restricted(&contact.normal[p]);
            carried.add_weighted(&r, n2);
            pressing.add_weighted(&r, n2);
            if frictional[contact.boundary[p] as usize] {
                for t in &contact.tangent[p][..d - 1] {
                    let (r, n2) = restricted(t);
                    carried.add_weighted(&r, n2);
                }
            }
        }
        // The group motions of the combinations `y` of the stacked free bases.
        let expand = |ys: Vec<Vec<f64>>| -> Vec<Motion> {
            ys.iter()
                .map(|y| {
                    members
                        .iter()
                        .enumerate()
                        .map(|(j, &b)| {
                            let mut c = [0.0; 6];
                            for (l, zl) in free[b].iter().enumerate() {
                                for i in 0..m {
                                    c[i] += y[offset[j] + l] * zl[i];
                                }
                            }
                            c
                        })
                        .collect()
                })
                .collect()
        };
        let uncarried = expand(carried.null_space());
        let (slide, press) = pressing.split();
        let (sliding, pressed) = (expand(slide), expand(press));
        groups.push(Group {
            bodies: members,
            uncarried,
            sliding,
            pressed,
        });
    }
    (groups, group_of)
}
