//! Friction laws: slip-dependent coefficient μ(r), friction bound F, and the
//! friction potential j with its difference-of-convex split `j = j_cvx − h`.
//!
//! The friction condition is `−σ_τ ∈ F ∂j(u_τ)` (Clarke subdifferential), with
//! `F = μ(‖u_τ‖)` (Tresca type) or `F = μ(‖u_τ‖) p(u_ν)` (Coulomb type).
//!
//! | potential | j(ξ), r = ‖ξ‖ | j_cvx | h |
//! |-----------|---------------|-------|---|
//! | norm | `r` | `r` | 0 |
//! | nonconvex (17), 0 < a < 1 | `r + (a−1)/(2a) r²` (r ≤ a), `a r + a(1−a)/2` (r > a) | `r` | `(1−a)/(2a) r²` (r ≤ a), `(1−a) r − a(1−a)/2` (r > a) |
//!
//! The paper states (17) with the slip r in metres; the law is `ℓ j₁₇(r/ℓ)` with the slip
//! unit ℓ = 1 m ([`FrictionPotential::Nonconvex::unit`]), which keeps its form when the
//! variables are made dimensionless (ℓ becomes ℓ/U for a displacement scale U).
//! | regularized (19) | `√(r² + ρ²) − ρ` | j | 0 |
//!
//! The norm is nonsmooth at 0. For the potentials whose convex part is the norm (`norm`,
//! `nonconvex`) the law says how the term `F ‖·‖` is treated ([`NormTreatment`]): exactly,
//! or with a small elastic slip; both through the friction multiplier τ. The regularized
//! law (19) is smooth already and carries no treatment, so exact stick/slip of a smooth law
//! cannot be expressed.
//!
//! ## The smoothed norm: an elastic slip on the point's own scale
//!
//! The smoothed norm of contact point i is exact friction in series with an elastic slip
//! of compliance `c_i = ε / k_i` (m/Pa): ε the law's `regularization`, `k_i = S / h_i` the
//! point's elastic stiffness per unit area (S the P-wave modulus, `h_i` the local mesh size;
//! [`crate::solver::constraints::contact_stiffness`]). Its friction traction is
//! `τ = proj_{B_F}(ξ / c_i)`: a sticking point slips elastically by `c_i ‖τ‖ ≤ ε F_i / k_i`,
//! a slipping point carries exactly the bound. `F_i / k_i` is the slip over which the
//! friction bound deforms the body around the point, so the regularization is relative to
//! the point's own scales, whatever the loads or displacements elsewhere. The law is the
//! Moreau–Yosida regularization of `F‖·‖`, and it is solved like exact friction: the
//! augmented Lagrangian of the series law is the Moreau envelope with the compliances
//! added, `1/r' = 1/r + c_i`, so the Newton matrix never sees a stiffness above the penalty
//! r, however small ε.
//!
//! ## The tangential term of one contact point
//!
//! With the frozen bound `F ≥ 0`, linear term `b` (the linearized concave part), the
//! tangential energy at slip ξ is ([`Friction::tangential_term`])
//!
//! - law (19): `F φ_ρ(ξ) − b·ξ`, `φ_ρ(ξ) = √(‖ξ‖² + ρ²) − ρ`;
//! - the norm, multiplier τ (the friction traction), penalty r and compliance c (0 when
//!   exact): the augmented Lagrangian `H_F(z)/r' − ‖τ‖²/(2r) − b·ξ` with
//!   `z = r'ξ + (r'/r)τ`, `r' = r/(1 + rc)` (`z = τ + rξ` when exact), the Huber function
//!   `H_F(z) = ‖z‖²/2` (‖z‖ ≤ F), `F‖z‖ − F²/2` (‖z‖ > F), whose gradient is the projection
//!   `proj_{B_F}(z)` onto the ball of radius F; the multiplier update is
//!   `τ ← proj_{B_F}(z)` ([`Friction::updated_traction`]), whose fixed point is the law.

mod coefficient;
mod law;
mod tangential;

pub use coefficient::FrictionCoefficient;
pub use law::{Friction, FrictionBound, FrictionPotential, NormTreatment, DEFAULT_REGULARIZATION};
pub use tangential::{project_ball, regularized_norm, TangentialData, TangentialTerm};
