//! The iterate of the outer loop: everything held fixed over one convex problem, the
//! friction data of the convexification ([`FrictionData`]) and the multipliers of the
//! exact constraints ([`Multipliers`]). [`Frozen::image`] is the map G of the outer
//! fixed point `z ↦ G(z)`; [`Frozen::flatten`] gives the vector the mixing
//! ([`super::mixing`]) works on.
//!
//! The quantities and their vector are here; the first ones, the image and the fixed-point
//! residual, computed on the system, in `image`.

mod image;

use super::multipliers::Multipliers;
use crate::assembly::contact::{ContactData, FrictionData};
use crate::parallel::share::Entries;
use crate::parallel::Share;

/// The quantities frozen for one convex problem.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frozen {
    /// Friction bound and linear term of the convexification, per contact point.
    pub friction: FrictionData,
    /// Multipliers of the exact constraints.
    pub multipliers: Multipliers,
}

impl Frozen {
    /// The per-point data the contact assembler reads.
    pub fn contact(&self) -> ContactData<'_> {
        ContactData {
            bound: &self.friction.bound,
            linear: &self.friction.linear,
            pressure: &self.multipliers.pressure,
            traction: &self.multipliers.traction,
        }
    }

    /// The fixed-point vector
    /// `z = [F (n), b (2n), λ_contact (n), τ (2n), λ_locking (cells or 0)]`.
    pub fn flatten(&self) -> Vec<f64> {
        let (f, m) = (&self.friction, &self.multipliers);
        let n = f.bound.len();
        let mut z = Vec::with_capacity(6 * n + m.locking.len());
        z.extend_from_slice(&f.bound);
        for b in &f.linear {
            z.extend_from_slice(b);
        }
        z.extend_from_slice(&m.pressure);
        for t in &m.traction {
            z.extend_from_slice(t);
        }
        z.extend_from_slice(&m.locking);
        z
    }

    /// The quantities of the whole problem from every process's of its own contact points
    /// and cells ([`Share::to_whole`]; the locking multipliers with `ideal` locking only);
    /// these themselves on one process.
    pub fn to_whole(self, share: &Share, ideal: bool) -> Frozen {
        if !share.is_split() {
            return self;
        }
        let points = |v: Vec<f64>, width| share.to_whole(v, width, Entries::Points);
        let pairs = |v: Vec<[f64; 2]>| -> Vec<[f64; 2]> {
            let flat = points(v.into_iter().flatten().collect(), 2);
            flat.chunks_exact(2).map(|p| [p[0], p[1]]).collect()
        };
        let (f, m) = (self.friction, self.multipliers);
        Frozen {
            friction: FrictionData {
                bound: points(f.bound, 1),
                linear: pairs(f.linear),
            },
            multipliers: Multipliers {
                pressure: points(m.pressure, 1),
                traction: pairs(m.traction),
                locking: match ideal {
                    true => share.to_whole(m.locking, 1, Entries::Cells),
                    false => Vec::new(),
                },
            },
        }
    }

    /// The entries of [`Frozen::flatten`]'s vector for `n` contact points and `n_cells`
    /// locking multipliers that `share` counts: those of its own contact points (not its
    /// ghost points) and of its owned cells (every entry on one process).
    pub fn counted(share: &Share, n: usize, n_cells: usize) -> Vec<bool> {
        // The layout of `flatten`: F (1 per point), b (2), λ (1), τ (2).
        let mut counts = Vec::with_capacity(6 * n + n_cells);
        for width in [1, 2, 1, 2] {
            for i in 0..n {
                counts.extend(std::iter::repeat_n(share.counts_point(i), width));
            }
        }
        counts.extend((0..n_cells).map(|c| share.counts_cell(c)));
        counts
    }

    /// Inverse of [`Frozen::flatten`] for `n` contact points and `n_cells` locking
    /// multipliers, projecting bounds and multipliers onto their admissible sets (`F ≥ 0`,
    /// `λ ≥ 0`): a mixed iterate then still defines convex subproblems.
    pub fn unflatten(z: &[f64], n: usize, n_cells: usize) -> Frozen {
        let pair = |o: usize, i: usize| [z[o + 2 * i], z[o + 2 * i + 1]];
        Frozen {
            friction: FrictionData {
                bound: z[..n].iter().map(|&x| x.max(0.0)).collect(),
                linear: (0..n).map(|i| pair(n, i)).collect(),
            },
            multipliers: Multipliers {
                pressure: z[3 * n..4 * n].iter().map(|&x| x.max(0.0)).collect(),
                traction: (0..n).map(|i| pair(4 * n, i)).collect(),
                locking: z[6 * n..6 * n + n_cells]
                    .iter()
                    .map(|&x| x.max(0.0))
                    .collect(),
            },
        }
    }
}
