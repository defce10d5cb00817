//! Helpers shared by the integration tests: a deterministic pseudo-random generator,
//! scenario construction, closed-form Lamé constants, and a solve with a prescribed
//! displacement field on the Dirichlet DOFs.
//!
//! Every test file includes this module with `mod common;` and uses only part of it.
#![allow(dead_code)]

use hemicontact::problem::Problem;
use hemicontact::scenario::Scenario;
use hemicontact::solver::newton::NewtonRecord;
use hemicontact::solver::{convex, SolverSettings, System};

/// A small deterministic generator (SplitMix64), so failures are reproducible without a
/// dependency.
pub struct Rng(u64);

impl Rng {
    /// A generator with the given seed.
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }

    /// Next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [lo, hi).
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

/// Lamé constants `(λ, G)` from E and ν by the textbook formulas (SPEC §2), written out
/// here independently of the library: plane strain / 3D
/// `λ = Eν/((1+ν)(1−2ν))`, plane stress `λ = Eν/(1−ν²)`; `G = E/(2(1+ν))` in both.
pub fn lame(young: f64, poisson: f64, plane_stress: bool) -> (f64, f64) {
    let g = young / (2.0 * (1.0 + poisson));
    let lambda = if plane_stress {
        young * poisson / (1.0 - poisson * poisson)
    } else {
        young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson))
    };
    (lambda, g)
}

/// Parses a scenario text and resolves it into a validated problem.
#[track_caller]
pub fn problem(text: &str) -> Problem {
    let scenario = Scenario::from_str(text, "<test>").expect("scenario parses");
    scenario.into_problem().expect("scenario is valid")
}

/// Parses a scenario text into its validated problem and its `[solver]` settings.
#[track_caller]
pub fn setup(text: &str) -> (Problem, SolverSettings) {
    let scenario = Scenario::from_str(text, "<test>").expect("scenario parses");
    let problem = scenario.into_problem().expect("scenario is valid");
    (problem, scenario.settings().expect("settings are valid"))
}

/// Solves a scenario text with its own `[solver]` settings.
#[track_caller]
pub fn solve_text(text: &str) -> hemicontact::Result<hemicontact::solver::Solution> {
    let (problem, settings) = setup(text);
    hemicontact::solver::solve(&problem, &settings)
}

/// Relative distance `|a − b| / max(|b|, floor)`.
pub fn rel(a: f64, b: f64, floor: f64) -> f64 {
    (a - b).abs() / b.abs().max(floor)
}

/// Minimizes the energy of `problem` with the Dirichlet DOFs set to the values of `field`
/// at the nodes (instead of the constant per-part values of the scenario). Free DOFs start
/// from zero, so the solver has to do the work. Returns the displacement (DOF order) and
/// the number of Newton steps taken, asserting convergence.
///
/// This drives the solver's lower-level API (`System`, `convex::minimize`) directly: a
/// problem without contact is a single convex minimization.
#[track_caller]
pub fn solve_with_prescribed_field<V: AsRef<[f64]>>(
    problem: &Problem,
    field: impl Fn(&[f64]) -> V,
) -> (Vec<f64>, usize) {
    let mesh = &problem.mesh;
    let d = mesh.dim();
    assert!(
        problem.contact.is_empty(),
        "helper is for problems without contact"
    );
    let solver = SolverSettings::default();
    let mut system = System::new(problem, &solver).expect("system");
    let mut u = vec![0.0; d * mesh.n_nodes()];
    for n in 0..mesh.n_nodes() {
        let v = field(mesh.node(n));
        let v = v.as_ref();
        for i in 0..d {
            if system.dofs.is_fixed(d * n + i) {
                u[d * n + i] = v[i];
            }
        }
    }
    let frozen = system.initial_frozen(problem, &u);
    let settings = &solver.newton;
    let outcome = convex::minimize(
        &mut system,
        problem,
        &frozen,
        settings,
        settings.residual_tolerance,
        &mut u,
        &mut NewtonRecord::default(),
    )
    .expect("Newton runs");
    assert!(
        outcome.converged,
        "not converged: residual {:e} after {} steps",
        outcome.residual, outcome.steps
    );
    (u, outcome.steps)
}

/// Asserts that a solve converged and that its certificate (equilibrium, normal-law and
/// friction-law residuals, computed from equilibrium of the body) is below `tol`.
#[track_caller]
pub fn assert_certified(s: &hemicontact::solver::Solution, tol: f64) {
    let c = &s.report.certificate;
    assert!(s.report.converged, "not converged: {}", s.report.message);
    assert!(
        c.equilibrium < tol,
        "equilibrium residual {:e}",
        c.equilibrium
    );
    assert!(c.normal_law < tol, "normal-law residual {:e}", c.normal_law);
    assert!(
        c.friction_law < tol,
        "friction-law residual {:e}",
        c.friction_law
    );
}
