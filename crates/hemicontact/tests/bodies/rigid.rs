//! # Rigid motions that the Dirichlet conditions leave free
//!
//! 1. **Singular problems are refused before any solve**, with the direct and the iterative
//!    linear solver alike, naming the free motion: rollers on the two sides and a vertical
//!    load (translation along y free); a bottom roller only (translation along x free, no
//!    load along it); a second, unclamped body in the mesh; a 3D box on a bottom roller
//!    with `linear_solver = "iterative"`.
//! 2. **Contact carries them:** a block on a frictionless normal-compliance foundation
//!    (gap 0) pressed by a uniform traction `p`, rollers `u_x = 0` on both sides. Uniaxial
//!    strain: `σ_yy = −p`, `ε_xx = 0`, and the lumped foundation force `c_ν (u_ν − g)₊ w_i`
//!    balances the consistent traction load `p w_i` node by node, so (outward normal
//!    `ν = (0, −1)` at the bottom `y = 0`, `u_ν = −u_y`)
//!    `u_y(x, y) = −p/c_ν − p y/(λ + 2μ)`, `u_x = 0`, total contact force `p × width`.
//!    The same in 3D for a cube between four rollers.
//! 3. The same block **held sideways only by Coulomb friction** (no Dirichlet condition at
//!    all) under a load symmetric about the centre line, on a mirror-symmetric mesh: the
//!    contact force balances the load (vertical sum `= p × width`, horizontal sum 0), `u_x`
//!    is antisymmetric and `u_y` symmetric about the centre line, and the load along the
//!    free rigid motions is balanced to 1e-10 of the force scale.
//! 4. **The load pulls the body off its contact:** the block on rollers pulled upwards has no
//!    equilibrium: the solve fails with `Error::ContactLost`.

use crate::common;
use crate::common::{lame, problem};
use hemicontact::mesh::Mesh;
use hemicontact::problem::{Dirichlet, Problem};
use hemicontact::scenario::Scenario;
use hemicontact::solver::SolverSettings;
use hemicontact::Error;

const YOUNG: f64 = 1000.0;
const POISSON: f64 = 0.3;

fn block(n: usize, extra: &str) -> String {
    format!(
        r#"
[mesh]
kind = "rectangle"
size = [2.0, 1.0]
n = [{}, {n}]
pattern = "symmetric"
[material]
young = {YOUNG}
poisson = {POISSON}
{extra}
"#,
        2 * n
    )
}

/// The error of resolving the scenario `text` into a problem.
fn rejected(text: &str) -> String {
    let scenario = Scenario::from_str(text, "block.toml").unwrap();
    match scenario.into_problem() {
        Err(e @ Error::RigidMotion { .. }) => e.to_string(),
        Err(e) => panic!("unexpected error {e}"),
        Ok(_) => panic!("singular problem accepted"),
    }
}

#[test]
fn rollers_on_both_sides_with_a_vertical_load_leave_the_vertical_translation_free() {
    let msg = rejected(&block(
        4,
        r#"
[[dirichlet]]
part = "left"
components = ["x"]
[[dirichlet]]
part = "right"
components = ["x"]
[[loads.traction]]
part = "top"
value = [0.0, -10.0]
"#,
    ));
    assert!(msg.starts_with("block.toml: "), "{msg}");
    assert!(msg.contains("translation along y"), "{msg}");
    assert!(msg.contains("prescribe u_y"), "{msg}");
    // Rotation and horizontal translation are blocked by the two rollers.
    assert!(
        !msg.contains("rotation") && !msg.contains("along x"),
        "{msg}"
    );
}

#[test]
fn a_free_translation_without_load_along_it_is_refused() {
    let msg = rejected(&block(
        4,
        r#"
[[dirichlet]]
part = "bottom"
components = ["y"]
[[loads.traction]]
part = "top"
value = [0.0, -10.0]
"#,
    ));
    assert!(msg.contains("translation along x"), "{msg}");
    assert!(
        !msg.contains("along y") && !msg.contains("rotation"),
        "{msg}"
    );
}

/// A pin at a single corner node (both components prescribed) leaves free only the
/// rotation about z through that corner; a roller there (u_y only) also the translation
/// along x.
#[test]
fn a_pinned_corner_leaves_the_rotation_about_it_free() {
    let pr = problem(&block(
        2,
        r#"
[[dirichlet]]
part = "bottom"
"#,
    ));
    // Replace the clamp by a pin at node 0 = (0, 0): a Problem built in code.
    let mesh = pr.mesh().clone();
    let d = mesh.dim();
    let fixed = |k: usize| k < d;
    let motions = hemicontact::rigid::RigidMotions::new(
        &mesh,
        fixed,
        &hemicontact::contact::ContactNodes::default(),
        &[],
    );
    assert_eq!(motions.free[0].len(), 1);
    assert_eq!(
        motions.describe_free(0),
        vec!["rotation about z through (0, 0)".to_string()]
    );
    let roller = |k: usize| k == 1;
    let motions = hemicontact::rigid::RigidMotions::new(
        &mesh,
        roller,
        &hemicontact::contact::ContactNodes::default(),
        &[],
    );
    // Rotations about any point (0, y₀) keep u_y(0, 0) = 0; they differ by translations
    // along x, so the free span is described by that translation and the rotation whose
    // centre is level with the centroid (1, 0.5) of the 2 × 1 block: (0, 0.5).
    let mut free = motions.describe_free(0);
    free.sort();
    assert_eq!(
        free,
        vec![
            "rotation about z through (0, 0.5)".to_string(),
            "translation along x".to_string()
        ]
    );
}

/// Two unit squares, [0, 1]² and [2, 3] × [0, 1], two triangles each; the first has its
/// bottom edge on part `clamped`, every other boundary edge is on part `free`.
fn two_bodies() -> Mesh {
    let coords = vec![
        0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0, // body 1: nodes 0–3
        2.0, 0.0, 3.0, 0.0, 3.0, 1.0, 2.0, 1.0, // body 2: nodes 4–7
    ];
    let cells = vec![0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7];
    let facets = vec![0, 1, 1, 2, 2, 3, 3, 0, 4, 5, 5, 6, 6, 7, 7, 4];
    let facet_part = vec![0, 1, 1, 1, 1, 1, 1, 1];
    Mesh::try_new(
        2,
        coords,
        cells,
        facets,
        facet_part,
        vec!["clamped".into(), "free".into()],
    )
    .unwrap()
}

#[test]
fn a_floating_second_body_is_refused_naming_it() {
    let pr = problem(&block(
        2,
        r#"
[[dirichlet]]
part = "bottom"
"#,
    ));
    // A problem is built only validated: the builder refuses it (the solver could never
    // see it).
    let refused = Problem::builder(two_bodies(), pr.materials()[0].clone())
        .plane(pr.plane())
        .dirichlet(Dirichlet {
            part: 0,
            components: [true, true, false],
            value: [0.0; 3],
        })
        .build();
    assert!(matches!(refused, Err(Error::RigidMotion { .. })));
    let msg = refused.unwrap_err().to_string();
    assert!(
        msg.contains("mesh component 2 of 2 (4 nodes, from node 4, bounding box (2, 0) to (3, 1))"),
        "{msg}"
    );
    assert!(!msg.contains("component 1 of 2"), "{msg}");
    for motion in [
        "translation along x",
        "translation along y",
        "rotation about z through (2.5, 0.5)",
    ] {
        assert!(msg.contains(motion), "{motion} not in {msg}");
    }
}

#[test]
fn three_d_with_the_iterative_solver_is_refused() {
    let text = r#"
[mesh]
kind = "box"
size = [1.0, 1.0, 1.0]
n = [4, 4, 4]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "bottom"
components = ["z"]
[[loads.traction]]
part = "top"
value = [0.0, 0.0, -10.0]
[solver]
linear_solver = "iterative"
"#;
    let msg = rejected(text);
    for motion in [
        "translation along x",
        "translation along y",
        "rotation about z through (0.5, 0.5, 0.5)",
    ] {
        assert!(msg.contains(motion), "{motion} not in {msg}");
    }
    assert!(
        !msg.contains("along z") && !msg.contains("about x"),
        "{msg}"
    );
}

const P: f64 = 10.0;
const C_NU: f64 = 2000.0;

fn foundation(friction: &str) -> String {
    format!(
        r#"
[[contact]]
part = "bottom"
gap = 0.0
law = "normal-compliance"
c_nu = {C_NU}
{friction}
[[loads.traction]]
part = "top"
value = [0.0, -{P}]
"#
    )
}

#[test]
fn block_on_a_foundation_between_rollers_is_in_uniaxial_strain() {
    let rollers = r#"
[[dirichlet]]
part = "left"
components = ["x"]
[[dirichlet]]
part = "right"
components = ["x"]
"#;
    for linear_solver in ["direct", "iterative"] {
        let text = block(4, &(foundation("") + rollers))
            + &format!("[solver]\nlinear_solver = \"{linear_solver}\"\n");
        let (pr, settings) = common::setup(&text);
        let sol = hemicontact::solver::solve(&pr, &settings).unwrap();
        assert!(sol.report.converged, "{}", sol.report.message);
        assert_eq!(sol.report.free_rigid_motions, vec!["translation along y"]);
        assert!(sol.report.rigid_shift > 0.0);
        assert!(
            sol.report.rigid_residual <= 1e-10,
            "{}",
            sol.report.rigid_residual
        );
        let (lambda, mu) = lame(YOUNG, POISSON, false);
        let m = lambda + 2.0 * mu;
        let scale = P / C_NU + P / m;
        for v in 0..pr.mesh().n_nodes() {
            let x = pr.mesh().node(v);
            let exact = -P / C_NU - P * x[1] / m;
            assert!((sol.u[2 * v] - 0.0).abs() <= 1e-10 * scale, "u_x at {x:?}");
            assert!(
                (sol.u[2 * v + 1] - exact).abs() <= 1e-10 * scale,
                "u_y at {x:?}: {} vs {exact}",
                sol.u[2 * v + 1]
            );
        }
        // ε_yy = −p/(λ + 2μ) and ε_xx = 0 give σ_yy = (λ + 2μ) ε_yy = −p.
        let total: f64 = sol.contact.iter().map(|c| c.pressure * c.weight).sum();
        assert!((total - P * 2.0).abs() <= 1e-10 * P * 2.0, "{total}");
        let balance: f64 = sol.contact.iter().map(|c| c.force[1]).sum();
        assert!((balance - P * 2.0).abs() <= 1e-9 * P * 2.0, "{balance}");
    }
}

/// The 3D version: a cube between rollers on its four sides (u_x = 0 on left and right,
/// u_y = 0 on front and back) on a foundation at z = 0, pressed by `p` on top: the free
/// motion is the vertical translation and `u_z = −p/c_ν − p z/(λ + 2μ)`, with both linear
/// solvers.
#[test]
fn cube_on_a_foundation_between_rollers_is_in_uniaxial_strain() {
    let (lambda, mu) = lame(YOUNG, POISSON, false);
    let m = lambda + 2.0 * mu;
    let scale = P / C_NU + P / m;
    for linear_solver in ["direct", "iterative"] {
        let text = format!(
            r#"
[mesh]
kind = "box"
size = [1.0, 1.0, 1.0]
n = [4, 4, 4]
[material]
young = {YOUNG}
poisson = {POISSON}
[[dirichlet]]
part = "left"
components = ["x"]
[[dirichlet]]
part = "right"
components = ["x"]
[[dirichlet]]
part = "front"
components = ["y"]
[[dirichlet]]
part = "back"
components = ["y"]
[[contact]]
part = "bottom"
gap = 0.0
c_nu = {C_NU}
[[loads.traction]]
part = "top"
value = [0.0, 0.0, -{P}]
[solver]
linear_solver = "{linear_solver}"
"#
        );
        let (pr, settings) = common::setup(&text);
        let sol = hemicontact::solver::solve(&pr, &settings).unwrap();
        assert!(sol.report.converged, "{}", sol.report.message);
        assert_eq!(sol.report.free_rigid_motions, vec!["translation along z"]);
        assert!(
            sol.report.rigid_residual <= 1e-10,
            "{}",
            sol.report.rigid_residual
        );
        for v in 0..pr.mesh().n_nodes() {
            let x = pr.mesh().node(v);
            let exact = -P / C_NU - P * x[2] / m;
            for (i, e) in [0.0, 0.0, exact].iter().enumerate() {
                assert!(
                    (sol.u[3 * v + i] - e).abs() <= 1e-10 * scale,
                    "{linear_solver}: u_{i} at {x:?}: {} vs {e}",
                    sol.u[3 * v + i]
                );
            }
        }
        let total: f64 = sol.contact.iter().map(|c| c.pressure * c.weight).sum();
        assert!((total - P).abs() <= 1e-10 * P, "{total}");
    }
}

#[test]
fn block_held_only_by_coulomb_friction_is_in_equilibrium_and_symmetric() {
    let friction = r#"
[contact.friction]
bound = "coulomb"
potential = "norm"
mu = { law = "constant", mu = 0.3 }
"#;
    let n = 4;
    let pr = problem(&block(n, &foundation(friction)));
    assert!(pr.dirichlet().is_empty());
    let sol = hemicontact::solver::solve(&pr, &SolverSettings::default()).unwrap();
    assert!(sol.report.converged, "{}", sol.report.message);
    assert_eq!(sol.report.free_rigid_motions.len(), 3);
    assert!(
        sol.report.rigid_residual <= 1e-10,
        "{}",
        sol.report.rigid_residual
    );
    let (fx, fy): (f64, f64) = sol
        .contact
        .iter()
        .fold((0.0, 0.0), |(a, b), c| (a + c.force[0], b + c.force[1]));
    let load = P * 2.0;
    assert!((fy - load).abs() <= 1e-9 * load, "vertical {fy} vs {load}");
    assert!(fx.abs() <= 1e-9 * load, "horizontal {fx}");
    // Mirror symmetry about x = 1: node (i, j) ↔ (2n − i, j).
    let nx = 2 * n;
    let scale = sol.u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(scale > 0.0);
    for j in 0..=n {
        for i in 0..=nx {
            let a = j * (nx + 1) + i;
            let b = j * (nx + 1) + (nx - i);
            assert!(
                (sol.u[2 * a] + sol.u[2 * b]).abs() <= 1e-8 * scale,
                "u_x not antisymmetric at node {a}"
            );
            assert!(
                (sol.u[2 * a + 1] - sol.u[2 * b + 1]).abs() <= 1e-8 * scale,
                "u_y not symmetric at node {a}"
            );
        }
    }
}

#[test]
fn a_load_pulling_the_block_off_its_foundation_is_an_error() {
    let rollers = r#"
[[dirichlet]]
part = "left"
components = ["x"]
[[dirichlet]]
part = "right"
components = ["x"]
"#;
    let text = block(4, &(foundation("") + rollers)).replace(&format!("-{P}]"), &format!("{P}]"));
    let pr = problem(&text);
    match hemicontact::solver::solve(&pr, &SolverSettings::default()) {
        Err(e @ Error::ContactLost { .. }) => {
            assert!(e.to_string().contains("translation along y"), "{e}")
        }
        Err(e) => panic!("unexpected error {e}"),
        Ok(s) => panic!("solved: {}", s.report.message),
    }
}
