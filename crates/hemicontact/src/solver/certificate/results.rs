//! The results of a certificate at each contact point ([`ContactResult`]): its kinematics,
//! its interface force from equilibrium, its states ([`NormalState`], [`FrictionState`]),
//! its law residuals and scales; and where a law residual is largest ([`Worst`]).

use serde::Serialize;

/// Normal contact state of a point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum NormalState {
    /// No pressure: not touching the foundation (or, with normal compliance, not
    /// penetrating the asperities).
    Separated,
    /// Positive contact pressure.
    Contact,
}

impl NormalState {
    /// Integer code for VTK/CSV output: 0 separated, 1 contact.
    pub fn code(self) -> i32 {
        match self {
            NormalState::Separated => 0,
            NormalState::Contact => 1,
        }
    }

    /// The state's name as written in CSV files.
    pub fn name(self) -> &'static str {
        match self {
            NormalState::Separated => "separated",
            NormalState::Contact => "contact",
        }
    }
}

/// Friction state of a point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum FrictionState {
    /// No friction force can act: frictionless contact, or a Coulomb-type bound at a
    /// separated point.
    None,
    /// Slip at most `tol` times the point's slip scale; the tangential force is within the
    /// bound.
    Stick,
    /// Slipping: the tangential force equals the bound and opposes the slip.
    Slip,
}

impl FrictionState {
    /// Integer code for VTK/CSV output: 0 none, 1 stick, 2 slip.
    pub fn code(self) -> i32 {
        match self {
            FrictionState::None => 0,
            FrictionState::Stick => 1,
            FrictionState::Slip => 2,
        }
    }

    /// The state's name as written in CSV files.
    pub fn name(self) -> &'static str {
        match self {
            FrictionState::None => "none",
            FrictionState::Stick => "stick",
            FrictionState::Slip => "slip",
        }
    }
}

/// Results at one contact point.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ContactResult {
    /// Mesh node.
    pub node: u32,
    /// Contact boundary index.
    pub boundary: usize,
    /// Lumped weight w_i.
    pub weight: f64,
    /// Normal displacement u_ν (m).
    pub u_nu: f64,
    /// Current gap `g − u_ν` (m; negative: penetration of the asperities).
    pub gap: f64,
    /// Tangential displacement coordinates (m).
    pub u_tau: [f64; 2],
    /// Slip ‖u_τ‖ (m).
    pub slip: f64,
    /// Contact pressure p (Pa, N/m in 2D) = −σ_ν.
    pub pressure: f64,
    /// Friction bound F(u).
    pub bound: f64,
    /// Interface force on the body from equilibrium, normal part `R·ν` (N).
    pub force_normal: f64,
    /// Interface force, tangential coordinates (N).
    pub force_tangential: [f64; 2],
    /// Interface force in global coordinates (N).
    pub force: [f64; 3],
    /// Friction traction `σ_τ = R_τ / w` in global coordinates (Pa): the tangential
    /// traction the foundation exerts on the body (opposing the slip), recovered from
    /// equilibrium, in the sign convention of the interface force `force`.
    pub friction_traction: [f64; 3],
    /// Normal contact state.
    pub normal_state: NormalState,
    /// Friction state.
    pub friction_state: FrictionState,
    /// Normal-law residual (N).
    pub normal_residual: f64,
    /// Friction-law residual (N).
    pub friction_residual: f64,
    /// The point's force scale (N), which its residuals are relative to: `w max(F, p)`, at
    /// least the force resolution of its body (see the module documentation).
    pub force_scale: f64,
    /// The point's slip scale `force_scale / (w k)` (m), k its elastic stiffness per unit
    /// area: the slip its force scale causes around it. It sticks up to `tol` times this.
    pub slip_scale: f64,
}

/// Where a law residual is largest: the point's node, contact boundary and residual.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Worst {
    /// Mesh node.
    pub node: u32,
    /// Contact boundary index (into the problem's list).
    pub boundary: usize,
    /// The residual relative to the point's force scale.
    pub residual: f64,
}
