//! Totals of a solution over each contact part (the `contact_totals` of `summary.json`):
//! the resultant interface force on the body, the counts of points in contact, sticking
//! and slipping, the contact length (2D) or area (3D), and the peak pressure with where it
//! is reached.
//!
//! Every total is a sum over the part's contact points of the point results of
//! [`ContactResult`] (the rows of `contact.csv`), so it inherits their conventions: the
//! interface force `R_i` is the force the foundation exerts on the body at point i,
//! recovered from equilibrium, with the outward normal `ν_i` (so `R_i·ν_i ≤ 0` when
//! pressed).

use crate::problem::Problem;
use crate::solver::{ContactResult, FrictionState, NormalState};
use serde::Serialize;

/// Totals over the contact points of one contact boundary (one `[[contact]]` entry).
///
/// Forces are in N in 3D and N/m (per unit thickness) in 2D; vectors have one component
/// per spatial dimension, in global coordinates.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ContactTotals {
    /// Name of the mesh part of the contact boundary.
    pub part: String,
    /// Number of contact points of the boundary.
    pub points: usize,
    /// Number of points in contact (normal state `contact`: positive pressure).
    pub n_contact: usize,
    /// Number of sticking points (friction state `stick`).
    pub n_stick: usize,
    /// Number of slipping points (friction state `slip`).
    pub n_slip: usize,
    /// Resultant interface force on the body, `Σ_i R_i` (N; N/m in 2D).
    pub force: Vec<f64>,
    /// Sum of the normal parts of the interface forces, `Σ_i R_i·ν_i` (N; N/m in 2D):
    /// negative when the body is pressed onto the foundation. On a flat part it is the
    /// component of `force` along the normal; on a curved part the normals differ and it
    /// is the sum of the scalar normal forces.
    pub force_normal: f64,
    /// Resultant of the tangential parts of the interface forces,
    /// `Σ_i (R_i − (R_i·ν_i) ν_i)` (N; N/m in 2D), in global coordinates: the friction
    /// force on the body.
    pub force_tangential: Vec<f64>,
    /// Contact measure: the length (2D, m) or area (3D, m²) in contact, `Σ w_i` over the
    /// points in contact, with `w_i` the lumped (nodal) weights. Being nodal, it is
    /// accurate to about one element size at the edge of the contact zone (up to half an
    /// element on each side of it).
    pub contact_measure: f64,
    /// Peak contact pressure `max_i p_i` over the points in contact (Pa); 0 when no
    /// point is in contact.
    pub max_pressure: f64,
    /// Mesh node (0-based) of the point of peak pressure (the first such point in the
    /// order of the contact results), or `None` when no point is in contact.
    pub max_pressure_node: Option<u32>,
    /// Reference coordinates (m) of the point of peak pressure, one per spatial
    /// dimension, or `None` when no point is in contact.
    pub max_pressure_at: Option<Vec<f64>>,
}

/// The totals of `contact` (the point results of a solution of `problem`), one entry per
/// contact boundary of `problem`, in the order of `problem.contact()`.
///
/// With `R_i` the interface force, `ν_i` the outward normal, `w_i` the lumped weight and
/// `p_i` the pressure of point i of a boundary:
/// `force = Σ R_i`, `force_normal = Σ R_i·ν_i`, `force_tangential = Σ w_i σ_τ,i` (the
/// friction traction `σ_τ,i = R_τ,i / w_i` times the weight), `contact_measure = Σ w_i`
/// over the points in contact, `max_pressure = max p_i` over them. Points whose boundary
/// index is not one of `problem`'s are ignored.
pub fn contact_totals(problem: &Problem, contact: &[ContactResult]) -> Vec<ContactTotals> {
    let mesh = &problem.mesh;
    let d = mesh.dim();
    let mut totals: Vec<ContactTotals> = problem
        .contact
        .iter()
        .map(|b| ContactTotals {
            part: mesh.part_names()[b.part].clone(),
            points: 0,
            n_contact: 0,
            n_stick: 0,
            n_slip: 0,
            force: vec![0.0; d],
            force_normal: 0.0,
            force_tangential: vec![0.0; d],
            contact_measure: 0.0,
            max_pressure: 0.0,
            max_pressure_node: None,
            max_pressure_at: None,
        })
        .collect();
    for c in contact {
        let Some(t) = totals.get_mut(c.boundary) else {
            continue;
        };
        t.points += 1;
        for k in 0..d {
            t.force[k] += c.force[k];
            t.force_tangential[k] += c.weight * c.friction_traction[k];
        }
        t.force_normal += c.force_normal;
        match c.friction_state {
            FrictionState::Stick => t.n_stick += 1,
            FrictionState::Slip => t.n_slip += 1,
            FrictionState::None => {}
        }
        if c.normal_state == NormalState::Contact {
            t.n_contact += 1;
            t.contact_measure += c.weight;
            if t.max_pressure_node.is_none() || c.pressure > t.max_pressure {
                t.max_pressure = c.pressure;
                t.max_pressure_node = Some(c.node);
            }
        }
    }
    for t in &mut totals {
        t.max_pressure_at = t.max_pressure_node.map(|n| mesh.node(n as usize).to_vec());
    }
    totals
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;
    use crate::scenario::Scenario;

    /// A 2 × 1 rectangle on a 2 × 1 grid (nodes 0, 1, 2 along the bottom at x = 0, 1, 2;
    /// 3, 4, 5 along the top), contact on `bottom` then on `top`.
    fn problem() -> Problem {
        let text = r#"
[mesh]
kind = "rectangle"
size = [2.0, 1.0]
n = [2, 1]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "left"
[[contact]]
part = "bottom"
gap = 0.0
c_nu = 1.0
[[contact]]
part = "top"
gap = 0.0
c_nu = 1.0
"#;
        Scenario::from_str(text, "<totals>")
            .unwrap()
            .into_problem()
            .unwrap()
    }

    /// A hand-made point result of boundary `boundary` at `node`.
    #[allow(clippy::too_many_arguments)]
    fn point(
        node: u32,
        boundary: usize,
        weight: f64,
        pressure: f64,
        force: [f64; 2],
        normal: [f64; 2],
        normal_state: NormalState,
        friction_state: FrictionState,
    ) -> ContactResult {
        let fn_ = force[0] * normal[0] + force[1] * normal[1];
        let ft = [force[0] - fn_ * normal[0], force[1] - fn_ * normal[1]];
        ContactResult {
            node,
            boundary,
            weight,
            u_nu: 0.0,
            gap: 0.0,
            u_tau: [0.0; 2],
            slip: 0.0,
            pressure,
            bound: 0.0,
            force_normal: fn_,
            force_tangential: [ft[0] * normal[1] - ft[1] * normal[0], 0.0],
            force: [force[0], force[1], 0.0],
            friction_traction: [ft[0] / weight, ft[1] / weight, 0.0],
            normal_state,
            friction_state,
            normal_residual: 0.0,
            friction_residual: 0.0,
            force_scale: 1.0,
            slip_scale: 1.0,
        }
    }

    fn node_of(problem: &Problem, x: [f64; 2]) -> u32 {
        (0..problem.mesh.n_nodes())
            .find(|&n| problem.mesh.node(n) == x)
            .unwrap() as u32
    }

    /// Sums, counts, measure and peak by hand on three bottom points and one top point.
    #[test]
    fn totals_are_the_sums_by_hand() {
        let pr = problem();
        let (n0, n1, n2) = (
            node_of(&pr, [0.0, 0.0]),
            node_of(&pr, [1.0, 0.0]),
            node_of(&pr, [2.0, 0.0]),
        );
        let n5 = node_of(&pr, [2.0, 1.0]);
        let down = [0.0, -1.0];
        let up = [0.0, 1.0];
        let results = [
            // Bottom: weights 0.5, 1, 0.5; the right end is separated.
            point(
                n0,
                0,
                0.5,
                4.0,
                [0.25, 2.0],
                down,
                NormalState::Contact,
                FrictionState::Stick,
            ),
            point(
                n1,
                0,
                1.0,
                6.0,
                [-1.0, 6.0],
                down,
                NormalState::Contact,
                FrictionState::Slip,
            ),
            point(
                n2,
                0,
                0.5,
                0.0,
                [0.0, 0.0],
                down,
                NormalState::Separated,
                FrictionState::None,
            ),
            // Top: one separated point.
            point(
                n5,
                1,
                0.5,
                0.0,
                [0.0, 0.0],
                up,
                NormalState::Separated,
                FrictionState::Stick,
            ),
        ];
        let t = contact_totals(&pr, &results);
        assert_eq!(t.len(), 2);
        let b = &t[0];
        assert_eq!(b.part, "bottom");
        assert_eq!((b.points, b.n_contact, b.n_stick, b.n_slip), (3, 2, 1, 1));
        assert_eq!(b.force, vec![-0.75, 8.0]);
        assert_eq!(b.force_normal, -8.0);
        assert_eq!(b.force_tangential, vec![-0.75, 0.0]);
        assert_eq!(b.contact_measure, 1.5);
        assert_eq!(b.max_pressure, 6.0);
        assert_eq!(b.max_pressure_node, Some(n1));
        assert_eq!(b.max_pressure_at, Some(vec![1.0, 0.0]));
        let top = &t[1];
        assert_eq!(top.part, "top");
        assert_eq!(
            (top.points, top.n_contact, top.n_stick, top.n_slip),
            (1, 0, 1, 0)
        );
        assert_eq!(top.force, vec![0.0, 0.0]);
        assert_eq!(top.contact_measure, 0.0);
        assert_eq!(top.max_pressure, 0.0);
        assert_eq!(top.max_pressure_node, None);
        assert_eq!(top.max_pressure_at, None);
    }

    /// A boundary without results has zero totals; the first of equal peaks is reported.
    #[test]
    fn empty_boundaries_are_zero_and_ties_keep_the_first_point() {
        let pr = problem();
        let (n3, n4) = (node_of(&pr, [0.0, 1.0]), node_of(&pr, [1.0, 1.0]));
        let up = [0.0, 1.0];
        let results = [
            point(
                n3,
                1,
                0.5,
                2.0,
                [0.0, -1.0],
                up,
                NormalState::Contact,
                FrictionState::None,
            ),
            point(
                n4,
                1,
                1.0,
                2.0,
                [0.0, -2.0],
                up,
                NormalState::Contact,
                FrictionState::None,
            ),
        ];
        let t = contact_totals(&pr, &results);
        assert_eq!(t[0].points, 0);
        assert_eq!(t[0].force, vec![0.0, 0.0]);
        assert_eq!(t[0].max_pressure_at, None);
        assert_eq!(t[1].force, vec![0.0, -3.0]);
        assert_eq!(t[1].force_normal, -3.0);
        assert_eq!(t[1].force_tangential, vec![0.0, 0.0]);
        assert_eq!(t[1].contact_measure, 1.5);
        assert_eq!(t[1].max_pressure_node, Some(n3));
        assert_eq!(t[1].max_pressure_at, Some(vec![0.0, 1.0]));
    }
}
