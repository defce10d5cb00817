//! # hemicontact
//!
//! P1 finite elements for static contact problems of elastic *locking* materials with
//! unilateral contact and nonmonotone, slip-dependent friction (variational–hemivariational
//! inequalities, Barboteu–Han–Migórski 2018).
//!
//! The displacement `u` of an elastic body `Ω ⊂ R^d` minimizes a (per outer iteration
//! convex) total energy
//! `Π(u) = Σ_T |T| W(ε_T(u)) − ⟨f, u⟩` over P1 fields with `u = u_D` on Γ_D. The Hessian is
//! assembled on a sparsity pattern built once, and factorized by a sparse Cholesky whose
//! symbolic analysis is done once.
//!
//! Layout (dependency order): [`mesh`] → [`fem`] → [`material`] → [`assembly`] →
//! [`linalg`] → [`solver`] → [`scenario`] / [`io`].
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
//! [[traction]]
//! part = "top"
//! value = [0.0, -10.0]
//! "#;
//! let problem = Scenario::from_str(text, "<doc>").unwrap().into_problem().unwrap();
//! let solution = hemicontact::solver::solve(&problem).unwrap();
//! assert!(solution.report.converged);
//! ```
//!
//! ## Outputs
//!
//! | file | content |
//! |------|---------|
//! | `solution.vtu` | VTK UnstructuredGrid: displacement and reactions at points; strain, stress, von Mises, tr ε per cell |
//! | `summary.json` | sizes, timings per phase, Newton history, energy, energy norm, max displacement |
//!
//! ## Current state / limitations
//!
//! - Linear elasticity (Hooke, plane strain/stress) in 2D on generated rectangles.
//! - Contact, friction and locking laws, 3D tetrahedra and Gmsh meshes are not yet
//!   implemented (see the project's issues).
#![deny(missing_docs)]

pub mod assembly;
pub mod contact;
pub mod error;
pub mod fem;
pub mod io;
pub mod linalg;
pub mod material;
pub mod mesh;
pub mod norms;
pub mod plot;
pub mod problem;
pub mod scenario;
pub mod solver;
pub mod tensor;

pub use error::{Error, Result};
