//! What the rigid drop ([`super::rigid_drop`]) and the friction limit
//! ([`super::Sliding`]) share about the motions of a group of held bodies: the load of
//! the external forces along them, a motion in words, the round-off threshold and a norm
//! that neither overflows nor underflows.

use crate::mesh::Mesh;
use crate::rigid::{Group, Motion, RigidMotions};
use crate::solver::System;

/// Relative size below which a load, a direction component or a slack counts as round-off
/// in the rigid drop and the friction limit.
pub(super) const ROUND_OFF: f64 = 1e-12;

/// The motion `c` of body `b` in words in the user's coordinates, with the body
/// ([`RigidMotions::label`]) when the mesh has several.
pub(super) fn describe(rigid: &RigidMotions, b: usize, c: &[f64; 6], length: f64) -> String {
    let motion = rigid.describe_in(b, c, length);
    match rigid.label(b) {
        l if l.is_empty() => motion,
        l => format!("{l}: {motion}"),
    }
}

/// The load `F_l = f·ρ_l` of the external forces along each motion `ρ_l` of `basis` (its
/// coefficients on each body of `group`), over the free DOFs of the nodes this process
/// counts: this process's part, which a sum over the processes completes.
pub(super) fn load_along(
    system: &System,
    mesh: &Mesh,
    group: &Group,
    basis: &[Motion],
) -> Vec<f64> {
    let rigid = &system.rigid;
    let (d, f, share) = (rigid.dim, &system.f_ext, system.share());
    let mut load = vec![0.0; basis.len()];
    for (j, &b) in group.bodies.iter().enumerate() {
        let nodes = rigid.bodies[b].nodes.iter();
        for &v in nodes.filter(|&&v| share.counts_node(v as usize)) {
            let x = mesh.node(v as usize);
            for (l, c) in basis.iter().enumerate() {
                let r = rigid.displacement(b, &c[j], x);
                for i in 0..d {
                    let dof = d * v as usize + i;
                    if !system.dofs.is_fixed(dof) {
                        load[l] += r[i] * f[dof];
                    }
                }
            }
        }
    }
    load
}

/// The Euclidean norm of `x` by `hypot`, so that no square overflows or underflows (a drop
/// across a gap of 10^300 displacement units, a load of 10^-300 in them).
pub(super) fn norm(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |n, v| n.hypot(*v))
}
