//! The translation by which its supports carry a body.
//!
//! A body (a connected component of the cells, [`super::bodies`]) whose prescribed
//! displacement components all have one value `c_k` in component k — a block whose clamped
//! top is moved by (a, b), or a whole body moved by its supports — is *carried* by `c`:
//! its displacement is `u = c + w`, with `c` the rigid translation that the supports give
//! and `w` what the body does beyond it. Components not prescribed anywhere on the body, or
//! prescribed with different values (a bar stretched between its ends), carry nothing:
//! `c_k = 0`.
//!
//! The solver takes the carried translation exactly and solves for `w`
//! ([`crate::contact::ContactNodes::new`], [`crate::solver`]): a rigid obstacle is met
//! where the carried body is (the gap, normal and slip of a contact point are those of its
//! position `x + c` against the obstacle moved by its own translation t, that is of `x`
//! against the obstacle moved by `t − c`), and the displacement scale is set by what the
//! data ask beyond the carried translation. A translation of a body has no strain energy,
//! so nothing else changes: moving an obstacle by t and moving every support of the body by
//! −t are then the same discrete problem (Galilean invariance), whatever t.

use super::bodies;
use crate::mesh::Mesh;

/// The carried translation of every body of `mesh` as a displacement (m, DOF order: the
/// body's `c` at each of its nodes, 0 at nodes in no cell), from the prescribed
/// displacement `prescribed` (DOF order) at the DOFs where `is_fixed` holds; `None` when
/// no body is carried (every `c` zero). See the module documentation.
pub fn carried_translation(
    mesh: &Mesh,
    prescribed: &[f64],
    is_fixed: impl Fn(usize) -> bool,
) -> Option<Vec<f64>> {
    /// The prescribed values of one component of one body so far.
    #[derive(Clone, Copy, PartialEq)]
    enum Seen {
        Nothing,
        One(f64),
        Several,
    }
    let d = mesh.dim();
    let (body_of, list) = bodies(mesh);
    let mut seen = vec![[Seen::Nothing; 3]; list.len()];
    for (v, &b) in body_of.iter().enumerate() {
        if b == u32::MAX {
            continue;
        }
        for k in 0..d {
            let dof = d * v + k;
            if !is_fixed(dof) {
                continue;
            }
            let x = prescribed[dof];
            let s = &mut seen[b as usize][k];
            *s = match *s {
                Seen::Nothing => Seen::One(x),
                Seen::One(y) if y == x => Seen::One(y),
                _ => Seen::Several,
            };
        }
    }
    let carried: Vec<[f64; 3]> = seen
        .iter()
        .map(|s| {
            s.map(|c| match c {
                Seen::One(x) => x,
                _ => 0.0,
            })
        })
        .collect();
    if carried.iter().all(|c| c.iter().all(|&x| x == 0.0)) {
        return None;
    }
    let mut u = vec![0.0; d * mesh.n_nodes()];
    for (v, &b) in body_of.iter().enumerate() {
        if b != u32::MAX {
            u[d * v..d * v + d].copy_from_slice(&carried[b as usize][..d]);
        }
    }
    Some(u)
}
