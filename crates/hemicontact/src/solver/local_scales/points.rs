//! The local scales of the contact points ([`System::point_scales`]): each point's force
//! and the floor of its force scale, from its node's cells and its body (see
//! [`super`]).

use super::super::frozen::Frozen;
use super::super::system::evaluate::ideal_locking;
use super::super::System;
use super::{BODY_FLOOR, FLOW_FLOOR};
use crate::assembly::BulkAssembler;
use crate::contact::NormalResponse;
use crate::problem::Problem;
impl System {
    /// The local scales of every contact point counted here ([`crate::contact::ContactNodes::owned`]) at `u`
    /// for the frozen quantities `frozen`
    /// (see [`crate::solver::local_scales`]): its force `w_i max(F_i, p_i)` (N; the frozen bound, the
    /// pressure at `u`, with the responses `responses` of user-defined compliance laws at
    /// `u`) into `force`, and the floor of its force scale `max(η L_i, η_b F_b)` (N; F_b the
    /// force scale of its body, from `body_scale`) into `floor`.
    pub fn point_scales(
        &self,
        problem: &Problem,
        u: &[f64],
        frozen: &Frozen,
        responses: &[NormalResponse],
        body_scale: &[f64],
        force: &mut Vec<f64>,
        floor: &mut Vec<f64>,
    ) {
        let n = self.contact.owned();
        let bulk = BulkAssembler {
            ideal: ideal_locking(&self.continuation.penalties, problem, frozen),
            ..BulkAssembler::of(problem, &problem.mesh)
        };
        let mut ca = self.contact_assembler(problem);
        ca.responses = responses;
        let data = frozen.contact();
        force.clear();
        floor.clear();
        let (offsets, cells) = &self.point_cells;
        for i in 0..n {
            let p = ca.state(u, i, &data).pressure;
            force.push(self.contact.weight[i] * data.bound[i].max(p));
            let around = &cells[offsets[i]..offsets[i + 1]];
            let v = self.contact.node[i];
            let body = body_scale
                .get(self.bodies.of_node[v as usize] as usize)
                .copied()
                .unwrap_or(0.0);
            floor.push((FLOW_FLOOR * bulk.nodal_force_sum(u, v, around)).max(BODY_FLOOR * body));
        }
    }
}
