//! Helpers shared by the integration tests: a deterministic pseudo-random generator,
//! scenario construction, closed-form Lamé constants, a solve with a prescribed
//! displacement field on the Dirichlet DOFs, and the harness of the fuzz tests.
//!
//! The test binary declares this module once (`tests/main.rs`); each test module uses part of it.
#![allow(dead_code)]

pub mod fuzz;
mod rng;
pub mod vtu;

#[allow(unused_imports)] // Not every test file draws random numbers.
pub use rng::Rng;

use hemicontact::mesh::Mesh;
use hemicontact::problem::Problem;
use hemicontact::scenario::Scenario;
use hemicontact::solver::newton::NewtonRecord;
use hemicontact::solver::{convex, SolverSettings, System};
use hemicontact::tensor::{mandel_len, Sym};

/// Lamé constants `(λ, G)` from E and ν by the textbook formulas, written out
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
    let mesh = problem.mesh();
    let d = mesh.dim();
    assert!(
        problem.contact().is_empty(),
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
    let frozen = hemicontact::solver::Frozen::initial(&system, problem, &u).expect("friction data");
    let settings = &solver.newton;
    let mut eval = hemicontact::solver::Evaluation::new(&system);
    let mut energy =
        convex::ConvexProblem::new(&mut system, &mut eval, problem, &frozen, settings, &u);
    let outcome = convex::minimize(
        &mut energy,
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

/// Asserts that a solve converged (its certificate passed, every law residual within the
/// certificate tolerance of its point's own force scale), that its equilibrium residual is
/// below `tol`, and that its normal-law and friction-law residuals, computed from
/// equilibrium of the body, are below `tol` times the largest force of the solution (`w p`,
/// `w F` or a component of the interface force of any point, or a support reaction), at
/// least the force unit `S U L^{d−2}` of its scales (stress, displacement and length).
#[track_caller]
pub fn assert_certified(s: &hemicontact::solver::Solution, tol: f64) {
    let c = &s.report.certificate;
    assert!(s.report.converged, "not converged: {}", s.report.message);
    assert!(
        c.equilibrium < tol,
        "equilibrium residual {:e}",
        c.equilibrium
    );
    let scale = s
        .contact
        .iter()
        .flat_map(|c| {
            [
                c.weight * c.pressure,
                c.weight * c.bound,
                c.force[0],
                c.force[1],
                c.force[2],
            ]
        })
        .chain(s.reactions.iter().copied())
        .chain(
            s.report
                .scales
                .map(|sc| sc.stress * sc.displacement * sc.length.powi(sc.dim as i32 - 2)),
        )
        .fold(f64::MIN_POSITIVE, |m, f| m.max(f.abs()));
    let worst = |f: &dyn Fn(&hemicontact::solver::ContactResult) -> f64| {
        s.contact.iter().map(f).fold(0.0f64, f64::max) / scale
    };
    let normal = worst(&|c| c.normal_residual);
    let friction = worst(&|c| c.friction_residual);
    assert!(
        normal < tol,
        "normal-law residual {normal:e} of the largest force"
    );
    assert!(
        friction < tol,
        "friction-law residual {friction:e} of the largest force"
    );
}

/// Boundary facets as a sorted list of (part, sorted vertices): facet order carries no
/// meaning (the writer groups facets by part).
pub fn facet_set(m: &Mesh) -> Vec<(usize, Vec<u32>)> {
    let mut out: Vec<(usize, Vec<u32>)> = (0..m.n_facets())
        .map(|f| {
            let mut v = m.facet(f).to_vec();
            v.sort_unstable();
            (m.facet_part(f), v)
        })
        .collect();
    out.sort();
    out
}

/// A random strain of dimension `dim` whose Mandel components are uniform in
/// `[-scale, scale]`.
pub fn random_strain(rng: &mut Rng, dim: usize, scale: f64) -> Sym {
    let mut e = Sym::zero(dim);
    for k in 0..mandel_len(dim) {
        e.c[k] = scale * rng.uniform(-1.0, 1.0);
    }
    e
}

/// A fresh empty folder `hemicontact-<prefix>-<process id>-<nanoseconds>` under the system
/// temporary folder.
pub fn fresh_dir(prefix: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "hemicontact-{prefix}-{}-{}",
        std::process::id(),
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .unwrap()
            .as_nanos()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Two meshes as one (the nodes of `lower` first), their boundary parts prefixed
/// `{names[0]}_` and `{names[1]}_` and their cells in the regions `names[0]` and `names[1]`:
/// two bodies that share no node, for contact between them.
pub fn two_bodies(lower: &Mesh, upper: &Mesh, names: [&str; 2]) -> Mesh {
    several_bodies(&[lower, upper], &names)
}

/// Several meshes as one (the nodes of `meshes[0]` first, then those of `meshes[1]`, …),
/// the boundary parts of `meshes[k]` prefixed `{names[k]}_` and its cells in the region
/// `names[k]`: bodies that share no node, for contact between them.
pub fn several_bodies(meshes: &[&Mesh], names: &[&str]) -> Mesh {
    assert_eq!(meshes.len(), names.len());
    let d = meshes[0].dim();
    let (mut coords, mut cells, mut parts, mut region) = (vec![], vec![], vec![], vec![]);
    let mut offset = 0u32;
    for (k, (m, prefix)) in meshes.iter().zip(names).enumerate() {
        coords.extend_from_slice(m.coords());
        cells.extend(m.cells().iter().map(|&v| v + offset));
        for name in m.part_names() {
            let p = m.part_index(name).unwrap();
            let facets = m
                .part_facets(p)
                .flat_map(|f| m.facet(f).iter().map(move |&v| v + offset))
                .collect();
            parts.push((format!("{prefix}_{name}"), facets));
        }
        region.extend((0..m.n_cells()).map(|_| k as u16));
        offset += m.n_nodes() as u32;
    }
    Mesh::from_parts(d, coords, cells, &parts)
        .unwrap()
        .with_regions(region, names.iter().map(|n| n.to_string()).collect())
        .unwrap()
}

/// The name by which the test harness knows the test `test` of the module `module_path`
/// (`module_path!()` there): the module's path without the binary's own name, so that a
/// test can run another test of its binary in a child process with `--exact`.
pub fn test_path(module_path: &str, test: &str) -> String {
    match module_path.split_once("::") {
        Some((_, module)) => format!("{module}::{test}"),
        None => test.to_string(),
    }
}
