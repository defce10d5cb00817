//! Validation in the library: a `Problem` exists only validated, settings validate
//! themselves, and the scenario layer reports the library's errors with the field paths of
//! the file.
//!
//! Each case is a datum outside its range given through the library's own types (as a
//! Rust or Python user builds a problem), checked for an [`Error::Invalid`] naming the
//! field; then the same datum through a scenario file, checked for an [`Error::Scenario`]
//! naming the field of the file.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::contact::{
    ContactBoundary, Friction, FrictionBound, FrictionCoefficient, FrictionPotential,
    NormTreatment, NormalCompliance, NormalLaw,
};
use hemicontact::material::{
    Elasticity, Hencky, Hooke, Locking, LockingPenalty, LockingSet, Material,
};
use hemicontact::mesh::generate::{rectangle, CutPattern, Rectangle};
use hemicontact::mesh::Mesh;
use hemicontact::problem::{Dirichlet, Problem, Traction};
use hemicontact::scenario::Scenario;
use hemicontact::solver::{solve, OuterSettings, SolverSettings};
use hemicontact::Error;

fn square() -> Mesh {
    rectangle(&Rectangle {
        origin: [0.0, 0.0],
        size: [1.0, 1.0],
        n: [2, 2],
        pattern: CutPattern::Uniform,
        progression: [1.0; 2],
    })
    .unwrap()
}

fn hooke() -> Material {
    Material::elastic(Elasticity::Hooke(Hooke {
        lambda: 1.0,
        mu: 1.0,
    }))
}

fn part(mesh: &Mesh, name: &str) -> usize {
    mesh.part_index(name).unwrap()
}

/// A clamped square pressed by a traction on top, with `contact` on its right side.
fn builder(material: Material, contact: Option<ContactBoundary>) -> Result<Problem, Error> {
    let mesh = square();
    let (bottom, top, right) = (
        part(&mesh, "bottom"),
        part(&mesh, "top"),
        part(&mesh, "right"),
    );
    let mut b = Problem::builder(mesh, material)
        .dirichlet(Dirichlet {
            part: bottom,
            components: [true, true, false],
            value: [0.0; 3],
        })
        .traction(Traction {
            part: top,
            value: [0.0, -1.0, 0.0],
        });
    if let Some(mut c) = contact {
        c.part = right;
        b = b.contact(c);
    }
    b.build()
}

fn friction(potential: FrictionPotential) -> ContactBoundary {
    ContactBoundary {
        against: None,
        part: 0,
        gap: 0.0,
        obstacle: None,
        normal: NormalLaw::Compliance(NormalCompliance { c_nu: 10.0 }),
        friction: Some(Friction {
            bound: FrictionBound::Coulomb,
            mu: FrictionCoefficient::Constant { mu: 0.3 },
            potential,
        }),
    }
}

#[track_caller]
fn invalid_field(r: Result<Problem, Error>) -> String {
    match r {
        Err(Error::Invalid { field, .. }) => field,
        Err(e) => panic!("expected an invalid field, got: {e}"),
        Ok(_) => panic!("invalid data accepted"),
    }
}

#[track_caller]
fn scenario_field(text: &str) -> String {
    let scenario = Scenario::from_str(text, "case.toml").unwrap();
    match scenario.into_problem() {
        Err(Error::Scenario { file, field, .. }) => {
            assert_eq!(file, "case.toml");
            field
        }
        Err(e) => panic!("expected a scenario error, got: {e}"),
        Ok(_) => panic!("invalid scenario accepted"),
    }
}

const BASE: &str = r#"
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [2, 2]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "bottom"
[[loads.traction]]
part = "top"
value = [0.0, -1.0]
"#;

/// The valid problem is accepted: the checks below fail on their datum alone.
#[test]
fn the_reference_problem_is_valid() {
    let norm = FrictionPotential::Norm {
        treatment: NormTreatment::default(),
    };
    builder(hooke(), Some(friction(norm))).unwrap();
    Scenario::from_str(BASE, "case.toml")
        .unwrap()
        .into_problem()
        .unwrap();
}

/// Friction laws check their parameters: the nonconvex potential needs 0 < a < 1, a
/// smoothed norm a regularization below 1 % of the displacement scale.
#[test]
fn friction_laws_validate_themselves() {
    let a = FrictionPotential::Nonconvex {
        a: 1.5,
        unit: 1.0,
        treatment: NormTreatment::Exact,
    };
    assert_eq!(
        invalid_field(builder(hooke(), Some(friction(a)))),
        "contact[0].friction.a"
    );
    let coarse = FrictionPotential::Norm {
        treatment: NormTreatment::Smoothed {
            regularization: 0.5,
        },
    };
    assert_eq!(
        invalid_field(builder(hooke(), Some(friction(coarse)))),
        "contact[0].friction.regularization"
    );
    let text = format!(
        "{BASE}[[contact]]\npart = \"right\"\nc_nu = 10.0\n[contact.friction]\nbound = \
         \"coulomb\"\npotential = {{ kind = \"nonconvex\", a = 1.5 }}\nmu = {{ law = \"constant\", mu = 0.3 }}\n"
    );
    assert_eq!(scenario_field(&text), "contact[0].friction.potential.a");
}

/// Materials check their constants: a Hencky transition strain of zero, an ideal-locking
/// set with a NaN threshold, a negative locking threshold.
#[test]
fn materials_validate_themselves() {
    let hencky = Material::elastic(Elasticity::Hencky(Hencky {
        bulk: 1.0,
        shear: 1.0,
        shear_inf: 2.0,
        s0: 0.0,
    }));
    assert_eq!(
        invalid_field(builder(hencky, None)),
        "material.elasticity.s0"
    );
    let ideal_nan = Material {
        locking: Locking::Ideal(LockingSet::Prager { kappa: f64::NAN }),
        ..hooke()
    };
    assert_eq!(
        invalid_field(builder(ideal_nan, None)),
        "material.locking.kappa"
    );
    let negative = Material {
        locking: Locking::Penalty(LockingPenalty {
            set: LockingSet::LimitedCompressibility { theta: -0.1 },
            c_kappa: 1.0,
        }),
        ..hooke()
    };
    assert_eq!(
        invalid_field(builder(negative, None)),
        "material.locking.theta"
    );
    let text = format!(
        "{BASE}[locking]\nset = \"limited-compressibility\"\ntheta = -0.1\nc_kappa = 1.0\n"
    );
    assert_eq!(scenario_field(&text), "locking.theta");
}

/// Loads must be finite and may not contradict the supports.
#[test]
fn loads_are_checked_against_the_supports() {
    let mesh = square();
    let top = part(&mesh, "top");
    let bottom = part(&mesh, "bottom");
    let nan = Problem::builder(mesh.clone(), hooke())
        .dirichlet(Dirichlet {
            part: bottom,
            components: [true, true, false],
            value: [0.0; 3],
        })
        .traction(Traction {
            part: top,
            value: [f64::NAN, 0.0, 0.0],
        })
        .build();
    assert_eq!(invalid_field(nan), "tractions[0].value");
    let on_support = Problem::builder(mesh, hooke())
        .dirichlet(Dirichlet {
            part: bottom,
            components: [true, true, false],
            value: [0.0; 3],
        })
        .traction(Traction {
            part: bottom,
            value: [0.0, -1.0, 0.0],
        })
        .build();
    assert_eq!(invalid_field(on_support), "tractions[0].value");
    let text = BASE.replace("part = \"top\"", "part = \"bottom\"");
    assert_eq!(scenario_field(&text), "loads.traction[0].value");
}

/// Solver settings validate themselves, so a library user cannot pass an Anderson depth
/// of `usize::MAX` (whose history length `depth + 1` overflows) or a NaN forcing term
/// (which `f64::clamp` rejects with a panic); the scenario reports the same under
/// `solver.`.
#[test]
fn solver_settings_validate_themselves() {
    let problem = builder(hooke(), None).unwrap();
    let deep = SolverSettings {
        outer: OuterSettings {
            depth: usize::MAX,
            ..OuterSettings::default()
        },
        ..SolverSettings::default()
    };
    match solve(&problem, &deep) {
        Err(Error::Invalid { field, .. }) => assert_eq!(field, "outer.depth"),
        other => panic!("expected an invalid depth, got {:?}", other.map(|_| ())),
    }
    let mut nan = SolverSettings::default();
    nan.newton.pcg_tolerance = f64::NAN;
    match solve(&problem, &nan) {
        Err(Error::Invalid { field, .. }) => assert_eq!(field, "newton.pcg_tolerance"),
        other => panic!("expected an invalid tolerance, got {:?}", other.map(|_| ())),
    }
    // Unbounded loop counts: a line search of usize::MAX halvings, a PCG reuse budget of
    // usize::MAX iterations.
    let mut backtracks = SolverSettings::default();
    backtracks.newton.max_backtracks = usize::MAX;
    match solve(&problem, &backtracks) {
        Err(Error::Invalid { field, .. }) => assert_eq!(field, "newton.max_backtracks"),
        other => panic!("expected invalid backtracks, got {:?}", other.map(|_| ())),
    }
    let mut reuse = SolverSettings::default();
    reuse.newton.pcg_iterations = 10_001;
    match solve(&problem, &reuse) {
        Err(Error::Invalid { field, .. }) => assert_eq!(field, "newton.pcg_iterations"),
        other => panic!(
            "expected invalid PCG iterations, got {:?}",
            other.map(|_| ())
        ),
    }
    let text = format!("{BASE}[solver.outer]\ndepth = 51\n");
    let scenario = Scenario::from_str(&text, "case.toml").unwrap();
    match scenario.settings() {
        Err(Error::Scenario { field, .. }) => assert_eq!(field, "solver.outer.depth"),
        other => panic!("expected a scenario error, got {:?}", other.map(|_| ())),
    }
}

/// A threshold of another locking set than the chosen one would be ignored: it is refused,
/// naming it (a `kappa` with `set = "ball"` is a typo for `radius`, not a default).
#[test]
fn threshold_of_another_locking_set_is_refused() {
    let text = format!(
        "{BASE}[locking]\nset = \"ball\"\nradius = 0.1\nkappa = 0.2\ntreatment = \"penalty\"\nc_kappa = 100.0\n"
    );
    assert_eq!(scenario_field(&text), "locking.kappa");
    let text = format!("{BASE}[locking]\nset = \"none\"\ntheta = 0.16\n");
    assert_eq!(scenario_field(&text), "locking.theta");
}
