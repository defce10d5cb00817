//! Local scales: no part of a problem is decided by another part's scale.
//!
//! Every threshold that decides a contact point's law or label — the numerical
//! regularization of the smoothed friction norm, the stick threshold, the certificate's
//! tolerances — is relative to the point's own scales (its friction bound and pressure, its
//! elastic stiffness per unit area), and every convergence test is taken body by body.
//!
//! 1. Two bodies in one mesh, sharing one contact part: body A's answer (displacements to
//!    1e-8 relative, friction labels identical) does not depend on how far body B is pulled
//!    (0 … 10 % of its size, and 10 and 1000 times its size), with regularized and with
//!    exact friction.
//! 2. Within one body: a contact region whose slips are below 1e-5 of the largest
//!    displacement elsewhere (a flagpole's root, 2.8e-7 of its tip) matches the
//!    exact-friction answer to 1e-6.
//! 3. The certificate sees the class: an answer computed with the former global
//!    regularization (ρ = 1e-8 U_global) on the two-body problem, where the former global
//!    certificate passes, fails the new certificate.
//! 4. A small body beside one moved far: body A pressed by 10⁻² down to 10⁻⁸ m converges
//!    and matches its closed form to 1e-8 while body B is stretched by 1000 m (a strain of
//!    10³) or lifted by 1000 m, whose forces and energy are known only to their round-off.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use hemicontact::mesh::generate::{rectangle, CutPattern, Rectangle};
use hemicontact::mesh::Mesh;
use hemicontact::problem::{Dirichlet, Problem};
use hemicontact::solver::{solve, FrictionState, Solution, SolverSettings};

/// Two blocks `[0, 1] × [0, 0.5]` (body A) and `[2, 3] × [0, 0.5]` (body B), 16 × 8 squares
/// each, in one mesh. Parts: `bottom` (both bottoms: one contact part), `a_top`, `b_top`,
/// `sides` (the rest).
fn two_blocks() -> Mesh {
    let block = |x0: f64| {
        rectangle(&Rectangle {
            origin: [x0, 0.0],
            size: [1.0, 0.5],
            n: [16, 8],
            pattern: CutPattern::Uniform,
            progression: [1.0, 1.0],
        })
        .unwrap()
    };
    merge(&[(block(0.0), "a"), (block(2.0), "b")])
}

/// The meshes of `bodies` in one mesh: part `bottom` of each goes to `bottom`, `top` to
/// `<prefix>_top`, every other part to `sides`.
fn merge(bodies: &[(Mesh, &str)]) -> Mesh {
    let mut names: Vec<String> = vec!["bottom".into(), "sides".into()];
    let (mut coords, mut cells, mut facets, mut facet_part) = (vec![], vec![], vec![], vec![]);
    for (mesh, prefix) in bodies {
        let offset = (coords.len() / 2) as u32;
        coords.extend_from_slice(mesh.coords());
        cells.extend(mesh.cells().iter().map(|v| v + offset));
        let top = format!("{prefix}_top");
        names.push(top.clone());
        for f in 0..mesh.n_facets() {
            facets.extend(mesh.facet(f).iter().map(|v| v + offset));
            let name = &mesh.part_names()[mesh.facet_part(f)];
            let target = match name.as_str() {
                "bottom" => "bottom",
                "top" => top.as_str(),
                _ => "sides",
            };
            facet_part.push(names.iter().position(|n| n == target).unwrap() as u16);
        }
    }
    Mesh::try_new(2, coords, cells, facets, facet_part, names).unwrap()
}

/// The scenario whose material and contact law the two-block problems use: Signorini
/// contact and Coulomb friction μ, with the further friction keys `friction`.
fn laws(mu: f64, friction: &str) -> Problem {
    laws_of("law = \"signorini\"", mu, friction)
}

/// As [`laws`] with the normal law `normal` (its keys).
fn laws_of(normal: &str, mu: f64, friction: &str) -> Problem {
    common::problem(&format!(
        r#"
[mesh]
kind = "rectangle"
size = [1.0, 0.5]
n = [2, 2]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "top"
[[contact]]
part = "bottom"
{normal}
[contact.friction]
bound = "coulomb"
mu = {{ law = "constant", mu = {mu} }}
{friction}
"#
    ))
}

/// Body A's top pressed down by 0.01 and pushed sideways by 0.004 (part of its bottom
/// slips); body B's top pulled sideways by `pull` and pressed by 0.01.
fn two_block_problem(friction: &str, pull: f64) -> Problem {
    on_two_blocks(&laws(0.3, friction), pull)
}

/// The two blocks with the material and the contact law of `laws`, loaded as
/// [`two_block_problem`] says.
fn on_two_blocks(laws: &Problem, pull: f64) -> Problem {
    let mesh = two_blocks();
    let part = |name: &str| mesh.part_index(name).unwrap();
    let mut contact = laws.contact()[0].clone();
    contact.part = part("bottom");
    Problem::builder(mesh.clone(), laws.materials()[0].clone())
        .plane(laws.plane())
        .dirichlet(Dirichlet {
            part: part("a_top"),
            components: [true, true, false],
            value: [0.004, -0.01, 0.0],
        })
        .dirichlet(Dirichlet {
            part: part("b_top"),
            components: [true, true, false],
            value: [pull, -0.01, 0.0],
        })
        .contact(contact)
        .build()
        .unwrap()
}

/// The largest difference of the displacements of body A (nodes with x ≤ 1) of two
/// solutions, relative to A's largest displacement.
fn body_a_difference(mesh: &Mesh, a: &Solution, b: &Solution) -> f64 {
    let (mut diff, mut scale) = (0.0f64, 0.0f64);
    for v in 0..mesh.n_nodes() {
        if mesh.node(v)[0] > 1.0 + 1e-12 {
            continue;
        }
        for k in 0..2 {
            diff = diff.max((a.u[2 * v + k] - b.u[2 * v + k]).abs());
            scale = scale.max(a.u[2 * v + k].abs());
        }
    }
    diff / scale
}

/// The friction states of body A's contact points.
fn body_a_labels(mesh: &Mesh, s: &Solution) -> Vec<FrictionState> {
    s.contact
        .iter()
        .filter(|c| mesh.node(c.node as usize)[0] <= 1.0 + 1e-12)
        .map(|c| c.friction_state)
        .collect()
}

#[track_caller]
fn certified(s: &Solution) {
    assert!(s.report.converged, "{}", s.report.message);
}

fn two_bodies_do_not_see_each_other(friction: &str) {
    let settings = SolverSettings::default();
    let reference = solve(&two_block_problem(friction, 0.0), &settings).unwrap();
    certified(&reference);
    let mesh = two_blocks();
    let labels = body_a_labels(&mesh, &reference);
    let n_slip = labels.iter().filter(|&&l| l == FrictionState::Slip).count();
    let n_stick = labels
        .iter()
        .filter(|&&l| l == FrictionState::Stick)
        .count();
    println!("{friction}: body A alone: {n_stick} stick, {n_slip} slip");
    assert!(n_slip > 0 && n_stick > 0, "the test needs both states on A");
    for pull in [1e-3, 1e-2, 0.03, 0.1, 10.0, 1000.0] {
        let s = solve(&two_block_problem(friction, pull), &settings).unwrap();
        certified(&s);
        let diff = body_a_difference(&mesh, &s, &reference);
        println!("  B pulled by {pull}: A differs by {diff:.2e}");
        assert!(diff <= 1e-8, "B pulled by {pull}: A differs by {diff:e}");
        assert_eq!(body_a_labels(&mesh, &s), labels, "B pulled by {pull}");
    }
}

#[test]
fn regularized_friction_on_body_a_is_independent_of_body_b() {
    two_bodies_do_not_see_each_other("");
}

#[test]
fn exact_friction_on_body_a_is_independent_of_body_b() {
    two_bodies_do_not_see_each_other("exact = true");
}

/// A flagpole: a root block `[0, 1]²` (20 × 20 squares) and a thin arm `[1, 21] × [0.9, 1]`
/// (400 × 2 squares) in one body, the arm's nodes on `x = 1` merged with the block's.
/// Parts: `left` (the block's left side), `bottom` (the block's bottom), `tip` (the arm's
/// end `x = 21`), `free` (the rest).
fn flagpole() -> Mesh {
    let rect = |origin: [f64; 2], size: [f64; 2], n: [usize; 2]| {
        rectangle(&Rectangle {
            origin,
            size,
            n,
            pattern: CutPattern::Uniform,
            progression: [1.0, 1.0],
        })
        .unwrap()
    };
    let parts = [
        rect([0.0, 0.0], [1.0, 1.0], [20, 20]),
        rect([1.0, 0.9], [20.0, 0.1], [400, 2]),
    ];
    // Nodes merged by position (both meshes put the shared nodes at the same coordinates).
    let key = |x: &[f64]| ((x[0] * 1e6).round() as i64, (x[1] * 1e6).round() as i64);
    let mut index = std::collections::HashMap::new();
    let (mut coords, mut cells) = (Vec::new(), Vec::new());
    let mut edges: std::collections::HashMap<(u32, u32), (u32, u32, usize)> = Default::default();
    for mesh in &parts {
        let map: Vec<u32> = (0..mesh.n_nodes())
            .map(|v| {
                let x = mesh.node(v);
                *index.entry(key(x)).or_insert_with(|| {
                    coords.extend_from_slice(x);
                    (coords.len() / 2 - 1) as u32
                })
            })
            .collect();
        for c in 0..mesh.n_cells() {
            let cell: Vec<u32> = mesh.cell(c).iter().map(|&v| map[v as usize]).collect();
            cells.extend_from_slice(&cell);
            for k in 0..3 {
                let (a, b) = (cell[k], cell[(k + 1) % 3]);
                let e = edges.entry((a.min(b), a.max(b))).or_insert((a, b, 0));
                e.2 += 1;
            }
        }
    }
    // Boundary edges (in one cell), in the cell's orientation, tagged by position.
    let names = ["left", "bottom", "tip", "free"];
    let mut boundary: Vec<_> = edges.values().filter(|e| e.2 == 1).collect();
    boundary.sort_unstable_by_key(|e| (e.0, e.1));
    let (mut facets, mut facet_part) = (Vec::new(), Vec::new());
    for &&(a, b, _) in &boundary {
        let (xa, xb) = (&coords[2 * a as usize..], &coords[2 * b as usize..]);
        let on = |i: usize, v: f64| (xa[i] - v).abs() < 1e-9 && (xb[i] - v).abs() < 1e-9;
        let part = if on(0, 0.0) {
            0
        } else if on(1, 0.0) {
            1
        } else if on(0, 21.0) {
            2
        } else {
            3
        };
        facets.extend_from_slice(&[a, b]);
        facet_part.push(part as u16);
    }
    let names = names.iter().map(|s| s.to_string()).collect();
    Mesh::try_new(2, coords, cells, facets, facet_part, names).unwrap()
}

/// The flagpole clamped on `left`, its tip moved down by 1 (5 % of the arm): the block
/// turns and presses its bottom onto a foundation with Coulomb friction (μ = 1, Signorini
/// contact), where the slips are a few 10⁻⁷ of the tip's displacement.
fn flagpole_problem(friction: &str) -> Problem {
    let mesh = flagpole();
    let laws = laws(1.0, friction);
    let part = |name: &str| mesh.part_index(name).unwrap();
    let mut contact = laws.contact()[0].clone();
    contact.part = part("bottom");
    Problem::builder(mesh.clone(), laws.materials()[0].clone())
        .plane(laws.plane())
        .dirichlet(Dirichlet {
            part: part("left"),
            components: [true, true, false],
            value: [0.0; 3],
        })
        .dirichlet(Dirichlet {
            part: part("tip"),
            components: [false, true, false],
            value: [0.0, -1.0, 0.0],
        })
        .contact(contact)
        .build()
        .unwrap()
}

#[test]
fn a_region_of_small_slips_is_regularized_on_its_own_scale() {
    let settings = SolverSettings::default();
    let smoothed = solve(&flagpole_problem(""), &settings).unwrap();
    certified(&smoothed);
    let exact = solve(&flagpole_problem("exact = true"), &settings).unwrap();
    certified(&exact);
    let max_u = smoothed.u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let touching: Vec<usize> = (0..exact.contact.len())
        .filter(|&i| exact.contact[i].pressure > 0.0)
        .collect();
    let max_slip = touching
        .iter()
        .fold(0.0f64, |m, &i| m.max(exact.contact[i].slip));
    let max_force = touching.iter().fold(0.0f64, |m, &i| {
        m.max(exact.contact[i].force_tangential[0].abs())
    });
    let n_slip = touching
        .iter()
        .filter(|&&i| exact.contact[i].friction_state == FrictionState::Slip)
        .count();
    println!(
        "{} points in contact ({n_slip} slipping), largest slip {max_slip:.3e} = {:.1e} of max|u| = {max_u:.3e}",
        touching.len(),
        max_slip / max_u
    );
    assert!(max_slip <= 1e-4 * max_u && max_slip > 0.0);
    assert!(n_slip > 0 && n_slip < touching.len());
    let (mut du, mut df) = (0.0f64, 0.0f64);
    for &i in &touching {
        let (a, b) = (&smoothed.contact[i], &exact.contact[i]);
        du = du.max((a.u_tau[0] - b.u_tau[0]).abs());
        df = df.max((a.force_tangential[0] - b.force_tangential[0]).abs());
        assert_eq!(a.friction_state, b.friction_state, "node {}", a.node);
    }
    println!(
        "smoothed vs exact: slips differ by {:.2e} of the largest, friction forces by {:.2e}",
        du / max_slip,
        df / max_force
    );
    assert!(du <= 1e-6 * max_slip, "{}", du / max_slip);
    assert!(df <= 1e-6 * max_force, "{}", df / max_force);
}

/// The two blocks with normal compliance (c_ν = 10⁵ Pa/m) and Coulomb friction (μ = 0.3)
/// of potential `potential`, body B pulled by `pull`.
fn two_block_compliance(potential: &str, pull: f64) -> Problem {
    let laws = laws_of(
        "law = \"normal-compliance\"\nc_nu = 1.0e5",
        0.3,
        &format!("potential = {potential}"),
    );
    on_two_blocks(&laws, pull)
}

#[test]
fn the_certificate_fails_an_answer_of_the_former_global_thresholds() {
    let settings = SolverSettings::default();
    let tol = settings.certificate_tolerance;
    let mesh = two_blocks();
    let norm = "{ kind = \"norm\" }";
    // Body B pulled by 1000 m, 1000 times its size: the former displacement scale was U =
    // 1024 m (the power of two nearest to the largest prescribed displacement), its
    // friction regularization ρ = 10⁻⁸ U, its stick threshold tol · max|u| and its force
    // scale the largest force of the problem.
    let pull = 1000.0;
    let reference = solve(&two_block_compliance(norm, 0.0), &settings).unwrap();
    certified(&reference);
    let now = solve(&two_block_compliance(norm, pull), &settings).unwrap();
    certified(&now);
    let diff = body_a_difference(&mesh, &now, &reference);
    println!("local scales: A differs by {diff:.2e} with B pulled by {pull} m");
    assert!(diff <= 1e-8, "{diff:e}");
    assert_eq!(body_a_labels(&mesh, &now), body_a_labels(&mesh, &reference));
    // The former answer: the norm smoothed with the global ρ is the smooth law (19) with
    // that ρ, solved and certified as such.
    let rho = 1e-8 * 1024.0;
    let former = solve(
        &two_block_compliance(&format!("{{ kind = \"regularized\", rho = {rho} }}"), pull),
        &settings,
    )
    .unwrap();
    certified(&former);
    let diff = body_a_difference(&mesh, &former, &reference);
    println!("former global regularization: A differs by {diff:.2e}");
    assert!(diff > 1e-3, "the former answer is wrong on A: {diff:e}");
    // The former certificate, written out here: stick up to tol · max|u|, every residual
    // relative to one force scale, the largest contact force or bound, at least the force
    // unit of the prescribed displacements S max|u_D| (S = λ + 2G = E(1 − ν)/((1 + ν)(1 −
    // 2ν)) in plane strain); it passes.
    let max_u = former
        .u
        .chunks(2)
        .map(|c| c[0].hypot(c[1]))
        .fold(0.0, f64::max);
    let s = 1000.0 * 0.7 / (1.3 * 0.4);
    let force_scale = former.contact.iter().fold(s * pull, |m, c| {
        m.max(c.weight * c.pressure).max(c.weight * c.bound)
    });
    let (mut worst, mut a_stick) = (0.0f64, 0);
    for c in &former.contact {
        let stick = c.slip <= tol * max_u;
        let ft = c.force_tangential[0].abs();
        let residual = if stick {
            (ft - c.weight * c.bound).max(0.0)
        } else {
            (ft - c.weight * c.bound).abs()
        };
        worst = worst.max(residual / force_scale);
        if stick && mesh.node(c.node as usize)[0] <= 1.0 {
            a_stick += 1;
        }
    }
    println!(
        "former certificate: worst friction residual {worst:.2e}, {a_stick} of A's points stick"
    );
    assert!(worst <= tol, "{worst:e}");
    // The certificate of the norm law, on the points' own scales, fails it on body A.
    let (_, cert) =
        hemicontact::solver::certify(&two_block_compliance(norm, pull), &settings, &former.u)
            .unwrap();
    let failures = cert.failures();
    println!("local certificate: {failures:?}");
    let friction = failures
        .iter()
        .find(|f| f.law == "friction law")
        .expect("the friction law fails");
    let at = friction.at.unwrap();
    assert!(mesh.node(at.node as usize)[0] <= 1.0, "at node {}", at.node);
    assert!(friction.residual > 1e3 * tol, "{}", friction.residual);
    // The same certificate passes the answer of the local scales.
    let (_, cert) =
        hemicontact::solver::certify(&two_block_compliance(norm, pull), &settings, &now.u).unwrap();
    assert!(cert.passes(), "{:?}", cert.failures());
}

/// Body A, `[0, 1] × [0, 0.5]` (16 × 8 squares, E = 1000 Pa, ν = 0), its top moved down
/// by `delta` onto a rigid foundation with Signorini contact and Coulomb friction μ = 0.3
/// (with the friction keys `friction`); beside it body B, `[2, 3] × [0, 0.5]`, either
/// stretched by 1000 m (`lifted` false: held on its left side, its right side moved along
/// x) or lifted by 1000 m as a whole (its top moved up, its bottom a contact part too).
fn beside_a_far_body(delta: f64, lifted: bool, friction: &str) -> Problem {
    let block = |x0: f64| {
        rectangle(&Rectangle {
            origin: [x0, 0.0],
            size: [1.0, 0.5],
            n: [16, 8],
            pattern: CutPattern::Uniform,
            progression: [1.0, 1.0],
        })
        .unwrap()
    };
    let mesh = common::two_bodies(&block(0.0), &block(2.0), ["a", "b"]);
    let part = |name: &str| mesh.part_index(name).unwrap();
    let laws = common::problem(&format!(
        r#"
[mesh]
kind = "rectangle"
size = [1.0, 0.5]
n = [2, 2]
[material]
young = 1000.0
poisson = 0.0
[[dirichlet]]
part = "top"
[[contact]]
part = "bottom"
law = "signorini"
[contact.friction]
bound = "coulomb"
mu = 0.3
{friction}
"#
    ));
    let held = |name: &str, components: [bool; 3], value: [f64; 3]| Dirichlet {
        part: part(name),
        components,
        value,
    };
    let mut contact = laws.contact()[0].clone();
    contact.part = part("a_bottom");
    let mut builder = Problem::builder(mesh.clone(), laws.materials()[0].clone())
        .plane(laws.plane())
        .dirichlet(held("a_top", [true, true, false], [0.0, -delta, 0.0]))
        .contact(contact.clone());
    builder = if lifted {
        contact.part = part("b_bottom");
        builder
            .dirichlet(held("b_top", [true, true, false], [0.0, 1000.0, 0.0]))
            .contact(contact)
    } else {
        builder
            .dirichlet(held("b_left", [true, true, false], [0.0; 3]))
            .dirichlet(held("b_right", [true, false, false], [1000.0, 0.0, 0.0]))
    };
    builder.build().unwrap()
}

/// A small body beside one moved far: body A of [`beside_a_far_body`], pressed by δ from
/// 10⁻² down to 10⁻⁸ m, converges and matches its closed form (ν = 0: uniaxial compression
/// `u_y = −δ y/H`, `u_x = 0`, nothing slips) to 1e-8 of δ, while body B is stretched by
/// 1000 m (a strain of 10³) or lifted by 1000 m. B's nodal forces are then known only to
/// the round-off of terms `E · 1000 m`, and the energy to the round-off of B's: A's
/// convergence and line search are decided on A's own forces and its own energy's change.
#[test]
fn a_small_body_converges_beside_one_moved_far() {
    let settings = SolverSettings::default();
    let mut failed = Vec::new();
    for friction in ["", "exact = true"] {
        for lifted in [false, true] {
            for delta in [1e-2, 1e-5, 1e-8] {
                let problem = beside_a_far_body(delta, lifted, friction);
                let s = solve(&problem, &settings).unwrap();
                let case = format!(
                    "{friction} δ = {delta:e}, B {}",
                    if lifted { "lifted" } else { "stretched" }
                );
                if !s.report.converged {
                    failed.push(format!("{case}: {}", s.report.message));
                    continue;
                }
                let mesh = problem.mesh();
                let error = (0..mesh.n_nodes())
                    .filter(|&v| mesh.node(v)[0] <= 1.0)
                    .map(|v| {
                        let exact = -delta * mesh.node(v)[1] / 0.5;
                        (s.u[2 * v + 1] - exact).abs().max(s.u[2 * v].abs())
                    })
                    .fold(0.0f64, f64::max);
                println!(
                    "{case}: {} outer iterations, {} Newton steps, A's error {:.1e} δ",
                    s.report.outer.len(),
                    s.report.newton.len(),
                    error / delta
                );
                if error > 1e-8 * delta {
                    failed.push(format!("{case}: A's error {:e} δ", error / delta));
                }
            }
        }
    }
    assert!(failed.is_empty(), "{failed:#?}");
}
