//! # hemicontact
//!
//! P1 finite elements for static contact problems of elastic *locking* materials with
//! unilateral contact and nonmonotone, slip-dependent friction (variational–hemivariational
//! inequalities, Barboteu–Han–Migórski 2018).
//!
//! An elastic body `Ω ⊂ R^d` (P1 triangles or tetrahedra) is clamped on Γ_D, loaded on Γ_N and may touch
//! rigid foundations on Γ_C (normal compliance) with slip-dependent (nonmonotone) friction;
//! the material may *lock* (its strain is confined to a convex set B, here through the
//! nearly-locking penalty). The solver ([`solver::solve`]) is the convexification method:
//! each outer iteration freezes the friction bound `F = μ(‖u_τ‖) p(u_ν)` (and the
//! linearized concave part of a nonconvex potential) at the contact nodes and minimizes the
//! remaining convex energy
//! `E_k(u) = Σ_T |T| (W + Ψ)(ε_T(u)) + Σ_i w_i [P(u_ν,i) + F_i^k j_cvx(u_τ,i) − b_i^k·u_τ,i] − ⟨f, u⟩`
//! by a semismooth Newton method on a sparsity pattern whose symbolic Cholesky analysis is
//! done once. Every solve returns a certificate computed from the equilibrium of the body.
//!
//! Layout (dependency order): [`mesh`] → [`fem`] → [`material`], [`contact`] (pointwise
//! laws) → [`assembly`] → [`linalg`] → [`solver`] → [`scenario`] / [`io`] / `plot`
//! (figures; the cargo feature `plot`, on by default).
//!
//! ```
//! use hemicontact::scenario::Scenario;
//! let text = r#"
//! [mesh]
//! kind = "rectangle"
//! size = [1.0, 1.0]
//! n = [4, 4]
//! [material]
//! young = 1000.0
//! poisson = 0.3
//! [[dirichlet]]
//! part = "bottom"
//! [[loads.traction]]
//! part = "top"
//! value = [0.0, -300.0]
//! [[contact]]
//! part = "right"
//! gap = 0.01
//! c_nu = 1.0e4
//! [contact.friction]
//! bound = "coulomb"
//! mu = { law = "exponential", a = 0.4, b = 0.1, beta = 100.0 }
//! "#;
//! let scenario = Scenario::from_str(text, "<doc>").unwrap();
//! let (problem, settings) = (scenario.into_problem().unwrap(), scenario.settings().unwrap());
//! let solution = hemicontact::solver::solve(&problem, &settings).unwrap();
//! assert!(solution.report.converged);
//! // The block bulges into the wall on the right: some node is in contact.
//! assert!(solution.report.certificate.n_contact > 0);
//! assert!(solution.report.certificate.friction_law < 1e-8);
//! ```
//!
//! ## Outputs
//!
//! | file | content |
//! |------|---------|
//! | `solution.vtu` | VTK UnstructuredGrid: displacement, reactions, contact status, pressure, slip, interface force at points; strain, stress, von Mises, tr ε, locking activity per cell |
//! | `contact.csv` | one row per contact node: kinematics, forces, status, law residuals |
//! | `summary.json` | sizes, energy norm, max displacement, contact/slip/locked counts, iteration histories, timings, certificate, the small-deformation check, notes (of the scenario and of the solution) |
//! | `deformed.png/.svg` | the deformed mesh with interface forces (2D) |
//!
//! ## Current state / limitations
//!
//! - Meshes: generated rectangles (triangles) and boxes (tetrahedra), or Gmsh `.msh` 4.1
//!   files ([`mesh::gmsh`]; P1 simplices only, physical groups as boundary parts; cell
//!   regions are read but one material applies to the whole mesh; read meshes cannot be
//!   refined for convergence studies). Figures (cargo feature `plot`) are drawn in 2D and,
//!   for 3D problems, as a front view.
//! - The contact gap is one number per contact part, measured along the outward normal at
//!   each contact node: on a curved boundary the foundation is the boundary's offset by the
//!   gap, not a plane.
//! - Locking by the nearly-locking penalty or ideal (exact) locking; contact by normal
//!   compliance or the Signorini condition; friction with a smoothed or exact stick/slip.
//!   Exact constraints are imposed by augmented Lagrangians ([`solver::constraints`]).
//! - Every solve is carried out in dimensionless variables ([`solver::scaling`]), so units
//!   do not matter; the norm `‖·‖` of the friction potential is regularized numerically by
//!   an elastic slip of at most `10⁻⁸ F/k` at each point, F its friction bound and k its
//!   elastic stiffness per unit area (a parameter of the friction law, see
//!   [`contact::NormTreatment`]), or imposed exactly with `exact = true`. Every threshold
//!   that decides a contact point's law or label is relative to the point's own scales
//!   ([`solver::local_scales`]). A solve counts as converged only when its certificate
//!   passes ([`solver::certificate`]).
#![deny(missing_docs)]

pub mod assembly;
pub mod atomic_file;
pub mod contact;
pub mod display;
pub mod error;
pub mod fem;
pub mod fields;
pub mod geometry;
pub mod io;
pub mod linalg;
pub mod loading;
pub mod material;
pub mod mesh;
pub mod parallel;
#[cfg(feature = "plot")]
pub mod plot;
pub mod problem;
pub mod resources;
pub mod rigid;
pub mod scenario;
pub mod small_deformation;
pub mod solver;
pub mod study;
pub mod tensor;

pub use error::{Error, Result};
