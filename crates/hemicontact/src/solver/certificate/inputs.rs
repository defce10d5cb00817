//! What the certificate reads besides the contact assembler.

use super::super::local_scales::Bodies;
use super::super::round_off::Floors;
use crate::assembly::contact::ContactData;
use crate::mesh::Mesh;
use crate::parallel::Share;

/// The data [`super::evaluate`] needs besides the contact assembler.
pub struct Inputs<'a> {
    /// Displacement (DOF order).
    pub u: &'a [f64],
    /// The friction coefficient μ_i at `u` of every contact point, evaluated once for all
    /// points ([`crate::assembly::contact::ContactAssembler::friction_coefficients`]).
    pub mu: &'a [f64],
    /// `∇W(u) − f` (DOF order): the interface force at free DOFs of contact nodes.
    pub grad_bulk: &'a [f64],
    /// External forces (DOF order).
    pub f_ext: &'a [f64],
    /// Whether a DOF is prescribed.
    pub fixed: &'a dyn Fn(usize) -> bool,
    /// The bodies of the mesh, the unit of the equilibrium check
    /// ([`crate::solver::local_scales`]).
    pub bodies: &'a Bodies,
    /// The floor `η L_i` of the force scale of every contact point at `u` (N;
    /// [`crate::solver::System::point_scales`]).
    pub floor: &'a [f64],
    /// The round-off floors of the residual's entries and of its regions' resultants
    /// ([`crate::solver::System::round_off_floors`]): an entry or a law residual within its floor is
    /// round-off and counts as zero ([`crate::solver::round_off`]).
    pub round_off: &'a Floors,
    /// The mesh (of this process's part), whose regions' resultants equilibrium checks.
    pub mesh: &'a Mesh,
    /// The contact data of the last convex problem.
    pub frozen: ContactData<'a>,
    /// Certificate tolerance.
    pub tolerance: f64,
    /// What this process counts of the equilibrium check's sums.
    pub share: &'a Share,
}
