//! What a process sends of the contact results and the certificate of its own points, and
//! how the whole problem's are put together from every process's ([`Share::to_whole`],
//! [`Share::gather`]); on one process every function here returns its input.

use super::certificate::ContactResult;
use super::certificate::FrictionState;
use super::certificate::NormalState;
use super::certificate::Worst;
use crate::parallel::share::Entries;
use crate::parallel::Share;

impl ContactResult {
    /// The numbers of a [`ContactResult`] as a row ([`ContactResult::to_row`]).
    pub const ROW: usize = 25;

    /// These results as [`ContactResult::ROW`] numbers (the states as their codes): what
    /// a process sends of its points.
    pub fn to_row(&self) -> [f64; Self::ROW] {
        let mut row = [0.0; Self::ROW];
        let scalars = [
            f64::from(self.node),
            self.boundary as f64,
            self.weight,
            self.u_nu,
            self.gap,
            self.slip,
            self.pressure,
            self.bound,
            self.force_normal,
            f64::from(self.normal_state.code()),
            f64::from(self.friction_state.code()),
            self.normal_residual,
            self.friction_residual,
            self.force_scale,
            self.slip_scale,
        ];
        row[..15].copy_from_slice(&scalars);
        row[15..17].copy_from_slice(&self.u_tau);
        row[17..19].copy_from_slice(&self.force_tangential);
        row[19..22].copy_from_slice(&self.force);
        row[22..25].copy_from_slice(&self.friction_traction);
        row
    }

    /// The results a row of [`ContactResult::to_row`] holds.
    pub fn from_row(row: &[f64]) -> ContactResult {
        let pair = |k: usize| [row[k], row[k + 1]];
        let triple = |k: usize| [row[k], row[k + 1], row[k + 2]];
        ContactResult {
            // Node and boundary numbers below 2^32 are exact in floating point.
            node: row[0] as u32,
            boundary: row[1] as usize,
            weight: row[2],
            u_nu: row[3],
            gap: row[4],
            slip: row[5],
            pressure: row[6],
            bound: row[7],
            force_normal: row[8],
            normal_state: if row[9] == 1.0 {
                NormalState::Contact
            } else {
                NormalState::Separated
            },
            friction_state: match row[10] as i32 {
                1 => FrictionState::Stick,
                2 => FrictionState::Slip,
                _ => FrictionState::None,
            },
            normal_residual: row[11],
            friction_residual: row[12],
            force_scale: row[13],
            slip_scale: row[14],
            u_tau: pair(15),
            force_tangential: pair(17),
            force: triple(19),
            friction_traction: triple(22),
        }
    }
}

/// The contact results of the whole problem from every process's `results` of its own
/// points ([`Share::to_whole`]), with the whole mesh's node numbers; on one process
/// `results` themselves (each read back bit for bit from its row).
pub fn whole_results(share: &Share, results: Vec<ContactResult>) -> Vec<ContactResult> {
    let rows: Vec<f64> = results
        .into_iter()
        .flat_map(|mut r| {
            r.node = share.whole_node(r.node);
            r.to_row()
        })
        .collect();
    let rows = share.to_whole(rows, ContactResult::ROW, Entries::Points);
    rows.chunks_exact(ContactResult::ROW)
        .map(ContactResult::from_row)
        .collect()
}

/// The worst point of every process (`worst`, with its relative residual `value`), picked
/// as one pass over the points would, in rank order: the largest residual, a NaN before
/// any number, the first of equals.
pub(super) fn worst_of_all(
    share: &Share,
    worst: Option<Worst>,
    value: f64,
) -> (Option<Worst>, f64) {
    let mine = match worst {
        Some(w) => [value, 1.0, f64::from(w.node), w.boundary as f64],
        None => [value, 0.0, 0.0, 0.0],
    };
    let all = share.gather(&mine);
    let (mut worst, mut value) = (None, 0.0f64);
    for p in all.chunks_exact(4) {
        let rel = p[0];
        let better = rel > value || (rel.is_nan() && !value.is_nan());
        if p[1] > 0.0 && (better || worst.is_none()) {
            value = rel;
            // Node and boundary numbers below 2^32 are exact in floating point.
            worst = Some(Worst {
                node: p[2] as u32,
                boundary: p[3] as usize,
                residual: rel,
            });
        }
    }
    (worst, value)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What a process sends of a contact point's results is read back bit for bit, states
    /// included.
    #[test]
    fn a_contact_result_travels_as_a_row() {
        let mut k = 0.0f64;
        let mut next = || {
            k += 1.0;
            k.sqrt() * if (k as i32) % 2 == 0 { -1.0 } else { 1.0 }
        };
        for (normal_state, friction_state) in [
            (NormalState::Separated, FrictionState::None),
            (NormalState::Contact, FrictionState::Stick),
            (NormalState::Contact, FrictionState::Slip),
        ] {
            let r = ContactResult {
                node: 4_000_000_007,
                boundary: 3,
                weight: next(),
                u_nu: next(),
                gap: next(),
                u_tau: [next(), next()],
                slip: next(),
                pressure: next(),
                bound: next(),
                force_normal: next(),
                force_tangential: [next(), next()],
                force: [next(), next(), next()],
                friction_traction: [next(), next(), next()],
                normal_state,
                friction_state,
                normal_residual: next(),
                friction_residual: next(),
                force_scale: next(),
                slip_scale: next(),
            };
            assert_eq!(ContactResult::from_row(&r.to_row()), r);
        }
    }
}
