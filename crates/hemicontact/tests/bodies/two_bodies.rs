//! # Verification: contact between two deformable bodies
//!
//! Two blocks stacked along y, the upper one (slave side, its part `a_bottom`) pressed on
//! the lower one (master side, `b_top`) by a prescribed displacement −δ of its top, the
//! lower one held at its bottom. With ν = 0 the exact solution is uniaxial and uniform:
//! `u_y = −δ y/H` in both blocks, the stress `σ_yy = −E δ/H`, and the contact pressure
//! `p = E δ/H` at every point of the interface.
//!
//! 1. **Matching meshes** (the interface nodes of the two blocks coincide): the exact
//!    solution is in the discrete space and node-to-segment pairing transmits the nodal
//!    forces one to one, so the displacement, the pressure at every point and the force on
//!    the master side are reproduced to round-off, with Signorini's exact constraint and
//!    with normal compliance (whose penetration `p/c_ν` is then part of the solution), in 2D
//!    and 3D.
//! 2. **Non-matching meshes** (node-to-segment's known limit): the slave nodes' forces are
//!    spread onto the master facets with the shape functions at the projections, which is not
//!    the master side's consistent load of a uniform traction, so the patch test does not
//!    hold exactly. The measured error of the pressure and of the displacement is stated, and
//!    the total force is still exact (action = reaction).
//! 3. **Action = reaction**: the reactions of the two bodies' supports are equal and
//!    opposite, and every solve here is certified, the certificate checking each body's
//!    equilibrium with the pair forces spread onto the master nodes (without them the
//!    master body's residual is 0.7 of its force scale: checked by removing them).
//! 4. **Friction on the relative slip**: blocks sliding on each other carry the friction
//!    bound, and slip by the jump of the displacement across the interface.
//! 5. **Refusals**: a part against itself, two bodies whose free motions nothing carries
//!    but their contact with each other (named by their cell regions, with the motions in
//!    words), a gap with a master part.
//! 6. **A free body resting on a held one** through the pair, with or without an initial
//!    gap, carries the load exactly; a Gmsh file of two bodies with coincident interface
//!    nodes passes the patch test.
//! 7. **The trace constant of the jump** (uniqueness condition): with the master side
//!    clamped it equals the slave body's own (1.267894592052 both), and it grows when the
//!    master side is free (1.71).
//! 8. **Free bodies on free bodies**, their motions analysed together: a stack of two or
//!    three free blocks on a held foundation (2D, 3D, touching or across gaps, down to
//!    10⁻⁶ Pa) carries the load through every interface exactly; a block clamped by
//!    friction between a held block and a free one is held with the normal and friction
//!    forces its equilibrium gives, and refused above the friction limit.
//! 9. **Contrasts of stiffness up to 10¹²**, either block the slave side: on matching meshes
//!    the patch test of two materials (displacement, the force through the held block and
//!    the pressure to 1e-8, the pair's penalty the softer body's);
//!    on non-matching ones every solve converges, the force within node-to-segment's error.

use crate::common;
use hemicontact::contact::{
    ContactBoundary, Friction, FrictionBound, FrictionCoefficient, FrictionPotential, MasterPart,
    NormTreatment, NormalCompliance, NormalLaw,
};
use hemicontact::material::{Elasticity, Hooke, Material, Plane};
use hemicontact::mesh::generate::{cuboid, rectangle, BoxSpec, CutPattern, Rectangle};
use hemicontact::mesh::Mesh;
use hemicontact::problem::{Dirichlet, Problem, Traction};
use hemicontact::solver::certificate::FrictionState;
use hemicontact::solver::{solve, SolverSettings};

const E: f64 = 1000.0;
const DELTA: f64 = 0.01;
const H: f64 = 1.0;

/// Two rectangles `[0, 1] × [0, H/2]` (`b`, `nx_b` squares across) and `[0, 1] × [H/2, H]`
/// (`a`, `nx_a` squares across) in one mesh, without shared nodes; parts `a_*` and `b_*`.
fn stacked_2d(nx_a: usize, nx_b: usize, ny: usize) -> Mesh {
    stacked_2d_apart(nx_a, nx_b, ny, 0.0)
}

/// [`stacked_2d`] with the upper block raised by `gap`.
fn stacked_2d_apart(nx_a: usize, nx_b: usize, ny: usize, gap: f64) -> Mesh {
    let block = |y0: f64, nx: usize| layer([0.0, y0], 1.0, [nx, ny]);
    merged(&block(0.0, nx_b), &block(H / 2.0 + gap, nx_a))
}

/// The rectangle `[x0, x0 + width] × [y0, y0 + H/2]` (`origin` = (x0, y0)) of `n` squares
/// (or rectangles) across and up, its parts `bottom`, `top`, `left`, `right`.
fn layer(origin: [f64; 2], width: f64, n: [usize; 2]) -> Mesh {
    rectangle(&Rectangle {
        origin,
        size: [width, H / 2.0],
        n,
        pattern: CutPattern::Uniform,
        progression: [1.0, 1.0],
    })
    .unwrap()
}

/// Two boxes `[0, 1]² × [0, H/2]` (`b`, `n_b` cubes across) and `[0, 1]² × [H/2, H]` (`a`,
/// `n_a` across), as [`stacked_2d`] along z.
fn stacked_3d(n_a: usize, n_b: usize, nz: usize) -> Mesh {
    let block = |z0: f64, n: usize| {
        cuboid(&BoxSpec {
            origin: [0.0, 0.0, z0],
            size: [1.0, 1.0, H / 2.0],
            n: [n, n, nz],
            pattern: CutPattern::Uniform,
            progression: [1.0; 3],
        })
        .unwrap()
    };
    merged(&block(0.0, n_b), &block(H / 2.0, n_a))
}

/// The meshes `b` and `a` as one mesh (b's nodes first), their parts prefixed `b_` and `a_`.
fn merged(b: &Mesh, a: &Mesh) -> Mesh {
    common::two_bodies(b, a, ["b", "a"])
}

fn material() -> Material {
    // ν = 0: λ = 0, G = E/2.
    Material::elastic(Elasticity::Hooke(Hooke {
        lambda: 0.0,
        mu: E / 2.0,
    }))
}

/// The stacked blocks: `b_bottom` held, `a_top` moved by (0, −δ), `a_bottom` against
/// `b_top` with the normal law `normal`, frictionless.
fn pressed(mesh: Mesh, normal: NormalLaw) -> Problem {
    sheared(mesh, normal, None, 0.0)
}

/// The stacked blocks: `b_bottom` held, `a_top` moved by (s, −δ), `a_bottom` against `b_top`
/// with the normal law `normal` and the friction law `friction`.
fn sheared(mesh: Mesh, normal: NormalLaw, friction: Option<Friction>, s: f64) -> Problem {
    let names = ["b_bottom", "a_top", "a_bottom", "b_top"];
    sheared_named(mesh, normal, friction, s, names)
}

/// [`sheared`] with the parts named `[held, moved, slave, master]`.
fn sheared_named(
    mesh: Mesh,
    normal: NormalLaw,
    friction: Option<Friction>,
    s: f64,
    names: [&str; 4],
) -> Problem {
    let d = mesh.dim();
    let part = |n: &str| mesh.part_index(n).unwrap();
    let [bottom, top, slave, master] = names.map(part);
    Problem::builder(mesh, material())
        .plane(Plane::Strain)
        .dirichlet(Dirichlet {
            part: bottom,
            components: [true; 3],
            value: [0.0; 3],
        })
        .dirichlet(Dirichlet {
            part: top,
            components: [true; 3],
            value: if d == 2 {
                [s, -DELTA, 0.0]
            } else {
                [s, 0.0, -DELTA]
            },
        })
        .contact(ContactBoundary {
            part: slave,
            gap: 0.0,
            obstacle: None,
            against: Some(MasterPart::new(master)),
            normal,
            friction,
        })
        .build()
        .unwrap()
}

/// Largest error of the displacement against `u_y = −δ y/H − penetration above the
/// interface`, and of the contact pressures against `E δ/H`-based `p`, relative to δ and p.
fn errors(problem: &Problem, u: &[f64], pressures: &[f64], p: f64, penetration: f64) -> (f64, f64) {
    errors_raised(problem, u, pressures, p, penetration, 0.0)
}

/// [`errors`] with the upper block raised by `raised` in the mesh: it moves down by that
/// gap before it is compressed.
fn errors_raised(
    problem: &Problem,
    u: &[f64],
    pressures: &[f64],
    p: f64,
    penetration: f64,
    raised: f64,
) -> (f64, f64) {
    let mesh = problem.mesh();
    // The upper block's nodes come after the lower block's, whose top part is `b_top`.
    let first_upper = mesh
        .part_nodes(mesh.part_index("a_bottom").unwrap())
        .into_iter()
        .min()
        .unwrap() as usize;
    let d = mesh.dim();
    let mut eu = 0.0f64;
    for v in 0..mesh.n_nodes() {
        let y = mesh.node(v)[d - 1];
        // The strain ε = −p/E in both blocks; the upper one shifted down by the penetration.
        let upper = v >= first_upper;
        let exact = if upper {
            -p / E * (y - raised) - raised - penetration
        } else {
            -p / E * y
        };
        for k in 0..d - 1 {
            eu = eu.max(u[d * v + k].abs());
        }
        eu = eu.max((u[d * v + d - 1] - exact).abs());
    }
    let ep = pressures
        .iter()
        .map(|q| (q - p).abs())
        .fold(0.0f64, f64::max);
    (eu / DELTA, ep / p)
}

#[test]
fn matching_meshes_pass_the_contact_patch_test_to_round_off() {
    let settings = SolverSettings::default();
    for (d, mesh, points) in [(2, stacked_2d(4, 4, 2), 5), (3, stacked_3d(3, 3, 2), 16)] {
        // Signorini: no penetration, p = E δ / H.
        let problem = pressed(mesh.clone(), NormalLaw::Signorini);
        let s = solve(&problem, &settings).unwrap();
        assert!(s.report.converged, "{}", s.report.message);
        assert_eq!(s.contact.len(), points, "one point per slave node");
        let pressures: Vec<f64> = s.contact.iter().map(|c| c.pressure).collect();
        let (eu, ep) = errors(&problem, &s.u, &pressures, E * DELTA / H, 0.0);
        println!(
            "{d}D matching, Signorini: displacement error {eu:.1e} δ, pressure error {ep:.1e} p"
        );
        assert!(eu < 1e-10 && ep < 1e-10, "{eu:e} {ep:e}");
        assert!(s.report.certificate.passes(), "{:?}", s.report.certificate);
        // Normal compliance c_ν: p = E(δ − p/c_ν)/H, so p = E δ / (H + E/c_ν).
        let c_nu = 5.0e4;
        let problem = pressed(mesh, NormalLaw::Compliance(NormalCompliance { c_nu }));
        let s = solve(&problem, &settings).unwrap();
        assert!(s.report.converged, "{}", s.report.message);
        let p = E * DELTA / (H + E / c_nu);
        let pressures: Vec<f64> = s.contact.iter().map(|c| c.pressure).collect();
        let (eu, ep) = errors(&problem, &s.u, &pressures, p, p / c_nu);
        println!(
            "{d}D matching, compliance: displacement error {eu:.1e} δ, pressure error {ep:.1e} p"
        );
        assert!(eu < 1e-10 && ep < 1e-10, "{eu:e} {ep:e}");
        assert!(s.report.certificate.passes(), "{:?}", s.report.certificate);
    }
}

/// The stacked blocks with `nx_a` and `nx_b` squares across: the largest pressure and
/// displacement errors, relative to p and δ, and the total force on the slave and master
/// nodes along y.
fn non_matching(nx_a: usize, nx_b: usize, ny: usize) -> (f64, f64, f64, f64) {
    let problem = pressed(stacked_2d(nx_a, nx_b, ny), NormalLaw::Signorini);
    let s = solve(&problem, &SolverSettings::default()).unwrap();
    assert!(s.report.converged, "{}", s.report.message);
    assert!(s.report.certificate.passes(), "{:?}", s.report.certificate);
    let pressures: Vec<f64> = s.contact.iter().map(|c| c.pressure).collect();
    let (eu, ep) = errors(&problem, &s.u, &pressures, E * DELTA / H, 0.0);
    // Reactions at the held bottom and the moved top: equal and opposite.
    let mesh = problem.mesh();
    let total = |name: &str| -> f64 {
        mesh.part_nodes(mesh.part_index(name).unwrap())
            .iter()
            .map(|&v| s.reactions[2 * v as usize + 1])
            .sum()
    };
    (ep, eu, total("a_top"), total("b_bottom"))
}

#[test]
fn non_matching_meshes_transmit_the_force_exactly_and_the_pressure_within_the_stated_error() {
    // Refined at a fixed ratio of 5 slave segments to 4 master segments.
    let mut last_eu = f64::INFINITY;
    for (nx_a, nx_b, ny) in [(5, 4, 2), (10, 8, 4), (20, 16, 8)] {
        let (ep, eu, top, bottom) = non_matching(nx_a, nx_b, ny);
        println!(
            "slave {nx_a} / master {nx_b} across: pressure error {ep:.2e} p, displacement \
             error {eu:.2e} δ, force on the top {top:.6e}, on the bottom {bottom:.6e} N/m"
        );
        // Action = reaction: what the upper block receives, the lower one passes on.
        assert!(
            (top + bottom).abs() < 1e-12 * bottom.abs(),
            "{top} {bottom}"
        );
        // The force tends to E δ/H (per unit width); the displacement error converges,
        // at the measured orders 0.72 and 0.88 (the error is a boundary layer at the
        // interface, whose width is one element).
        assert!(
            (bottom - E * DELTA / H).abs() < 1e-3 * E * DELTA / H,
            "{bottom}"
        );
        let order = (last_eu / eu).log2();
        println!("  order {order:.2}");
        assert!(last_eu.is_infinite() || order > 0.6, "{eu} after {last_eu}");
        last_eu = eu;
        // Node-to-segment does not pass the patch test across non-matching meshes: the
        // local pressure error stays (7.7 % here) under refinement; the stated bound.
        assert!(ep > 1e-3 && ep < 0.08, "{ep}");
    }
    // The coarser side as the slave is worse: 10.6 % against 7.7 %.
    let (coarse_slave, ..) = non_matching(4, 5, 2);
    let (fine_slave, ..) = non_matching(5, 4, 2);
    println!("slave 4 / master 5: {coarse_slave:.2e} p, slave 5 / master 4: {fine_slave:.2e} p");
    assert!(coarse_slave > fine_slave, "{coarse_slave} {fine_slave}");
}

/// The figures of the 3D non-matching patch test ([`non_matching_3d`]), each relative to
/// the exact pressure `p = E δ/H`.
struct NonMatching3d {
    /// Largest error of the contact pressure.
    pressure: f64,
    /// Largest error of the contact pressure at the slave points inside the interface (off
    /// its edges).
    inside: f64,
    /// Largest error of a cell's σ_zz against −p.
    sigma_zz: f64,
    /// How far the force through the stack falls short of p over the unit area.
    force: f64,
}

/// The stacked boxes with `n_a` × `n_a` slave and `n_b` × `n_b` master cubes across, `nz`
/// layers each, Signorini: the errors against the uniform compression `σ_zz = −E δ/H`.
/// Every solve is certified, and the pair's action equals its reaction: the force on the
/// moved top and on the held bottom are equal and opposite.
fn non_matching_3d(n_a: usize, n_b: usize, nz: usize) -> NonMatching3d {
    let problem = pressed(stacked_3d(n_a, n_b, nz), NormalLaw::Signorini);
    let s = solve(&problem, &SolverSettings::default()).unwrap();
    assert!(s.report.converged, "{}", s.report.message);
    assert!(s.report.certificate.passes(), "{:?}", s.report.certificate);
    let p = E * DELTA / H;
    let mesh = problem.mesh();
    let off_edges = |v: u32| {
        let x = mesh.node(v as usize);
        (0..2).all(|k| x[k] > 1e-9 && x[k] < 1.0 - 1e-9)
    };
    let worst = |inside_only: bool| {
        s.contact
            .iter()
            .filter(|c| !inside_only || off_edges(c.node))
            .map(|c| (c.pressure - p).abs() / p)
            .fold(0.0f64, f64::max)
    };
    let sigma_zz = hemicontact::fields::cell_fields(&problem, &s)
        .stress
        .chunks_exact(9)
        .map(|sigma| (sigma[8] + p).abs() / p)
        .fold(0.0f64, f64::max);
    let total = |name: &str| -> f64 {
        mesh.part_nodes(mesh.part_index(name).unwrap())
            .iter()
            .map(|&v| s.reactions[3 * v as usize + 2])
            .sum()
    };
    let (top, bottom) = (total("a_top"), total("b_bottom"));
    assert!(
        (top + bottom).abs() < 1e-12 * bottom.abs(),
        "{top} {bottom}"
    );
    NonMatching3d {
        pressure: worst(false),
        inside: worst(true),
        sigma_zz,
        force: (p - bottom) / p,
    }
}

/// The 3D analogue of the 2D non-matching patch test: 4 × 4 slave squares over 3 × 3
/// master squares (two layers of cubes each), and the reverse. The force balance between
/// the bodies is exact; node-to-segment's local error is several times the 2D one, largest
/// on the edges of the interface, and inside it the finer slave side is again the better
/// choice. The measured figures (docs/benchmarks.md, docs/model.md) are asserted as bands,
/// so that a change of either sign shows.
#[test]
fn non_matching_3d_meshes_transmit_the_force_exactly_and_the_pressure_within_the_stated_error() {
    let mut measured = Vec::new();
    for (n_a, n_b) in [(4, 3), (3, 4)] {
        let m = non_matching_3d(n_a, n_b, 2);
        println!(
            "3D, slave {n_a}×{n_a} / master {n_b}×{n_b}: pressure error {:.4} p ({:.4} p off \
             the interface's edges), cell σ_zz error {:.4} p, force {:.4} below E δ/H",
            m.pressure, m.inside, m.sigma_zz, m.force
        );
        measured.push(m);
    }
    let (finer, coarser) = (&measured[0], &measured[1]);
    for (what, got, low, high) in [
        // Measured: 0.3116, 0.0724, 0.1668, 0.0036.
        ("finer slave, pressure", finer.pressure, 0.27, 0.35),
        (
            "finer slave, pressure off the edges",
            finer.inside,
            0.06,
            0.09,
        ),
        ("finer slave, σ_zz", finer.sigma_zz, 0.14, 0.19),
        ("finer slave, force", finer.force, 0.002, 0.005),
        // Measured: 0.3013, 0.2519, 0.2207, 0.0137.
        ("coarser slave, pressure", coarser.pressure, 0.26, 0.34),
        (
            "coarser slave, pressure off the edges",
            coarser.inside,
            0.22,
            0.29,
        ),
        ("coarser slave, σ_zz", coarser.sigma_zz, 0.19, 0.25),
        ("coarser slave, force", coarser.force, 0.011, 0.017),
    ] {
        assert!(
            got > low && got < high,
            "{what}: {got}, outside the measured band ({low}, {high})"
        );
    }
    assert!(finer.inside < coarser.inside && finer.sigma_zz < coarser.sigma_zz);
}

/// Friction acts on the slip of the slave node relative to the master body: the upper block
/// moved by (s, −δ) slides on the lower one, held at its bottom, the shear traction F
/// applied on the free sides. With a friction bound F below the stick force `G s/H`, every
/// point slips and carries τ = F: the shear stress is F in both blocks (`u_x = F y/G` below,
/// the same plus the slip above), and the slip `s − F H/G` is the jump of `u_x` across the
/// interface, not the displacement of the slave node (`s − F H/(2G)`).
#[test]
fn sliding_blocks_carry_the_friction_bound_and_slip_by_the_relative_displacement() {
    let g_shear = E / 2.0;
    let s = 0.02;
    let exact = |bound| Friction {
        bound,
        mu: FrictionCoefficient::Constant { mu: 0.4 },
        potential: FrictionPotential::Norm {
            treatment: NormTreatment::Exact,
        },
    };
    // Tresca with bound 4 Pa, and Coulomb with μ = 0.4 under p = E δ/H = 10 Pa: F = 4 Pa.
    for (name, fr) in [
        ("Tresca", exact(FrictionBound::Tresca)),
        ("Coulomb", exact(FrictionBound::Coulomb)),
    ] {
        let fr = match fr.bound {
            FrictionBound::Tresca => Friction {
                mu: FrictionCoefficient::Constant { mu: 4.0 },
                ..fr
            },
            _ => fr,
        };
        let mut problem = sheared(stacked_2d(4, 4, 2), NormalLaw::Signorini, Some(fr), s);
        // The shear stress τ = F on the free sides too: (0, ∓F) on the left and right.
        let mut builder = problem.to_builder();
        for (side, sign) in [("left", -1.0), ("right", 1.0)] {
            for body in ["a", "b"] {
                let part = problem
                    .mesh()
                    .part_index(&format!("{body}_{side}"))
                    .unwrap();
                builder = builder.traction(Traction {
                    part,
                    value: [0.0, sign * 4.0, 0.0],
                });
            }
        }
        problem = builder.build().unwrap();
        let sol = solve(&problem, &SolverSettings::default()).unwrap();
        assert!(sol.report.converged, "{}", sol.report.message);
        assert!(
            sol.report.certificate.passes(),
            "{:?}",
            sol.report.certificate
        );
        let bound = 4.0;
        let slip = s - bound * H / g_shear;
        let mut worst = 0.0f64;
        for c in &sol.contact {
            let traction = c.friction_traction[0].hypot(c.friction_traction[1]);
            worst = worst
                .max((c.slip - slip).abs() / slip)
                .max((traction - bound).abs() / bound)
                .max((c.pressure - E * DELTA / H).abs() / (E * DELTA / H));
        }
        let mesh = problem.mesh();
        let shear: f64 = mesh
            .part_nodes(mesh.part_index("a_top").unwrap())
            .iter()
            .map(|&v| sol.reactions[2 * v as usize])
            .sum();
        println!(
            "{name}: slip {:.6e} (exact {slip:.6e}), largest relative error {worst:.1e}, \
             shear force on the top {shear:.6e} N/m",
            sol.contact[2].slip
        );
        assert!(worst < 1e-9, "{worst:e}");
        assert!((shear.abs() - bound).abs() < 1e-9 * bound, "{shear}");
    }
}

/// What a pair cannot be, each refused naming `contact[0].against` and the reason.
#[test]
fn pairs_that_cannot_be_solved_are_refused_with_the_reason() {
    let mesh = stacked_2d(4, 4, 2);
    let part = |n: &str| mesh.part_index(n).unwrap();
    let pair = |against: usize| ContactBoundary {
        part: part("a_bottom"),
        gap: 0.0,
        obstacle: None,
        against: Some(MasterPart::new(against)),
        normal: NormalLaw::Signorini,
        friction: None,
    };
    let held = |b: hemicontact::problem::ProblemBuilder| {
        b.dirichlet(Dirichlet {
            part: part("b_bottom"),
            components: [true; 3],
            value: [0.0; 3],
        })
    };
    let refusal = |b: hemicontact::problem::ProblemBuilder| match b.build() {
        Ok(_) => panic!("accepted"),
        Err(e) => e.to_string(),
    };
    // Against itself.
    let e =
        refusal(held(Problem::builder(mesh.clone(), material())).contact(pair(part("a_bottom"))));
    assert!(
        e.contains("contact[0].against") && e.contains("other than the contact part"),
        "{e}"
    );
    // Two bodies each with free rigid motions (the lower one held along x only, the upper
    // one not at all).
    let e = refusal(
        Problem::builder(mesh.clone(), material())
            .dirichlet(Dirichlet {
                part: part("b_bottom"),
                components: [true, false, false],
                value: [0.0; 3],
            })
            .contact(pair(part("b_top"))),
    );
    // Their motions are analysed together: nothing holds them both up (nor their common
    // tilt, nor the upper one sideways).
    println!("{e}");
    for words in [
        "no contact part carries",
        "region `b`, mesh component 1 of 2",
        "region `a`, mesh component 2 of 2",
        "region `b` (mesh component 1 of 2) and region `a` (mesh component 2 of 2) together: \
         translation along y",
        "region `a` (mesh component 2 of 2): translation along x",
    ] {
        assert!(e.contains(words), "{words:?} not in {e}");
    }
    // A gap with a master part.
    let e = refusal(
        held(Problem::builder(mesh.clone(), material()))
            .dirichlet(Dirichlet {
                part: part("a_top"),
                components: [true; 3],
                value: [0.0; 3],
            })
            .contact(ContactBoundary {
                gap: 0.1,
                ..pair(part("b_top"))
            }),
    );
    assert!(e.contains("gap") && e.contains("against"), "{e}");
}

/// Two bodies meshed apart in Gmsh whose interface nodes coincide: the reader keeps the
/// coincident nodes of different bodies (it refuses them inside one body), and the pair
/// transmits the uniform pressure exactly.
/// The largest error of a 2D solution against uniform compression by `p` (ν = 0,
/// `u = (0, −p y/E)`, relative to δ) and of its contact pressures against p (relative).
fn compression_error(mesh: &Mesh, s: &hemicontact::solver::Solution, p: f64) -> f64 {
    let mut worst = s
        .contact
        .iter()
        .map(|c| (c.pressure - p).abs() / p)
        .fold(0.0f64, f64::max);
    for v in 0..mesh.n_nodes() {
        let exact = -p / E * mesh.node(v)[1];
        worst = worst
            .max((s.u[2 * v + 1] - exact).abs() / DELTA)
            .max(s.u[2 * v].abs() / DELTA);
    }
    worst
}

#[test]
fn a_gmsh_mesh_of_two_bodies_with_coincident_interface_nodes_passes_the_patch_test() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/gmsh/two-blocks.msh");
    let read = hemicontact::mesh::gmsh::read_msh(&path).unwrap();
    let mesh = read.mesh;
    let interface: Vec<u32> = mesh.part_nodes(mesh.part_index("upper_bottom").unwrap());
    // Each interface node has its twin on the other body, within round-off (Gmsh places
    // the nodes of the two lines from opposite ends: 3e-12 apart); the corners coincide exactly, which
    // the reader used to refuse as an unmerged geometry.
    let lower = mesh.part_nodes(mesh.part_index("lower_top").unwrap());
    let twin = |v: u32, tol: f64| {
        lower.iter().any(|&w| {
            let (a, b) = (mesh.node(w as usize), mesh.node(v as usize));
            w != v && (a[0] - b[0]).abs() <= tol && (a[1] - b[1]).abs() <= tol
        })
    };
    assert!(interface.iter().all(|&v| twin(v, 1e-11)));
    assert_eq!(interface.iter().filter(|&&v| twin(v, 0.0)).count(), 2);
    let names = ["lower_bottom", "upper_top", "upper_bottom", "lower_top"];
    let problem = sheared_named(mesh, NormalLaw::Signorini, None, 0.0, names);
    let s = solve(&problem, &SolverSettings::default()).unwrap();
    assert!(s.report.converged && s.report.certificate.passes());
    let p = E * DELTA / H;
    let mesh = problem.mesh();
    let worst = compression_error(mesh, &s, p);
    println!(
        "two-blocks.msh: {} points, largest relative error {worst:.1e}",
        s.contact.len()
    );
    assert_eq!(s.contact.len(), interface.len());
    assert!(worst < 1e-10, "{worst:e}");
}

/// A block resting on a held block: the upper block (the slave side) is pushed by a
/// pressure p on its top, held only along x there, so its vertical translation and its
/// rotation are free and carried by the pair, as by a foundation. With ν = 0 the exact
/// solution is the uniform compression `σ_yy = −p`, `u_y = −p y/E`, and the pressure p at
/// every point.
/// The free upper block either side of the pair: as its slave side (its bottom against the
/// held block's top) or as its master side (the held block's top against its bottom). Its
/// rows in the analysis of its free motions are then its master points', with the normal
/// reversed, and the rigid drop closes the gap from either side.
#[test]
fn a_block_resting_on_a_held_block_is_carried_by_the_pair() {
    // Matching and non-matching meshes, touching or apart by a gap the solve closes; the
    // free block as the slave side, then as the master side.
    let cases = [(4, 0.0), (5, 0.0), (4, 0.01), (5, 0.01)];
    for (free_slave, (nx_a, gap)) in [true, false]
        .into_iter()
        .flat_map(|s| cases.into_iter().map(move |c| (s, c)))
    {
        let mesh = stacked_2d_apart(nx_a, 4, 2, gap);
        let part = |n: &str| mesh.part_index(n).unwrap();
        let (slave, master) = match free_slave {
            true => ("a_bottom", "b_top"),
            false => ("b_top", "a_bottom"),
        };
        let p = 10.0;
        let problem = Problem::builder(mesh.clone(), material())
            .plane(Plane::Strain)
            .dirichlet(Dirichlet {
                part: part("b_bottom"),
                components: [true; 3],
                value: [0.0; 3],
            })
            .dirichlet(Dirichlet {
                part: part("a_top"),
                components: [true, false, false],
                value: [0.0; 3],
            })
            .traction(Traction {
                part: part("a_top"),
                value: [0.0, -p, 0.0],
            })
            .contact(ContactBoundary {
                part: part(slave),
                gap: 0.0,
                obstacle: None,
                against: Some(MasterPart::new(part(master))),
                normal: NormalLaw::Signorini,
                friction: None,
            })
            .build()
            .unwrap();
        let rigid = problem.rigid_motions().unwrap();
        let free: Vec<usize> = rigid.free.iter().map(Vec::len).collect();
        assert_eq!(
            free,
            vec![0, 2],
            "the upper block translates along y and rotates"
        );
        let s = solve(&problem, &SolverSettings::default()).unwrap();
        assert!(s.report.converged, "{}", s.report.message);
        assert!(s.report.certificate.passes(), "{:?}", s.report.certificate);
        let total: f64 = s.contact.iter().map(|c| c.pressure * c.weight).sum();
        let pressures: Vec<f64> = s.contact.iter().map(|c| c.pressure).collect();
        // The upper block moves down by the gap first.
        let (eu, ep) = errors_raised(&problem, &s.u, &pressures, p, 0.0, gap);
        println!(
            "resting block, {} side ({nx_a} : 4, gap {gap}): Σ w p = {total:.12} (exact {p}), \
             pressure error {ep:.2e} p, displacement error {eu:.2e} δ",
            if free_slave { "slave" } else { "master" }
        );
        assert!(
            rigid.groups.iter().all(|g| g.uncarried.is_empty()),
            "the pair carries every free motion"
        );
        // The load passes through the pair exactly; the pointwise error is node-to-segment's
        // (docs/model.md): 7.1 % of p with the finer side (5 cells) as the slave, 10.8 % with
        // the coarser (4 cells).
        assert!((total - p).abs() < 1e-10 * p, "{total}");
        if nx_a == 4 {
            assert!(ep < 1e-10 && eu < 1e-10, "{ep:e} {eu:e}");
        } else if free_slave {
            assert!(ep < 0.08, "{ep}");
        } else {
            assert!(ep < 0.11, "{ep}");
        }
    }
}

/// A block held by friction alone on a held block: pressed by p and pushed sideways by
/// τ < μ p on its top, with no support of its own (all three rigid motions free: the pair
/// carries the vertical one and the rotation, friction the sideways one). The first outer
/// iteration balances τ by uniform friction (the relief), and the block sticks. On matching
/// meshes each slave node pairs with the coincident master node, so the free block as the
/// slave side and as the master side is the same discrete problem: the two solves agree;
/// every point sticks, and the pair carries the block's load.
#[test]
fn a_block_held_by_friction_on_a_held_block_either_side_of_the_pair() {
    let mesh = stacked_2d(4, 4, 2);
    let part = |n: &str| mesh.part_index(n).unwrap();
    let (p, tau, mu) = (10.0, 2.0, 0.3);
    let solve_with = |slave: &str, master: &str| {
        let problem = Problem::builder(mesh.clone(), material())
            .plane(Plane::Strain)
            .dirichlet(Dirichlet {
                part: part("b_bottom"),
                components: [true; 3],
                value: [0.0; 3],
            })
            .traction(Traction {
                part: part("a_top"),
                value: [tau, -p, 0.0],
            })
            .contact(ContactBoundary {
                part: part(slave),
                gap: 0.0,
                obstacle: None,
                against: Some(MasterPart::new(part(master))),
                normal: NormalLaw::Signorini,
                friction: Some(Friction {
                    bound: FrictionBound::Coulomb,
                    mu: FrictionCoefficient::Constant { mu },
                    potential: FrictionPotential::Norm {
                        treatment: NormTreatment::Exact,
                    },
                }),
            })
            .build()
            .unwrap();
        let rigid = problem.rigid_motions().unwrap();
        assert_eq!(rigid.free.iter().map(Vec::len).collect::<Vec<_>>(), [0, 3]);
        assert_eq!(rigid.groups[0].bodies, [1]);
        assert_eq!(
            rigid.groups[0].sliding.len(),
            1,
            "the sideways motion: friction's"
        );
        let s = solve(&problem, &SolverSettings::default()).unwrap();
        assert!(s.report.converged, "{}", s.report.message);
        assert!(s.report.certificate.passes(), "{:?}", s.report.certificate);
        s
    };
    let (as_slave, as_master) = (
        solve_with("a_bottom", "b_top"),
        solve_with("b_top", "a_bottom"),
    );
    let scale = as_slave.u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let diff = as_slave
        .u
        .iter()
        .zip(&as_master.u)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    println!(
        "held by friction: u differs by {:.1e} of its largest {scale:.3e}",
        diff / scale
    );
    assert!(diff <= 1e-8 * scale, "{diff:e} of {scale:e}");
    // The block's equilibrium: the pair carries p and τ over its width (the moment of τ
    // makes the pressure vary along it), every point sticks.
    for s in [&as_slave, &as_master] {
        let width: f64 = s.contact.iter().map(|c| c.weight).sum();
        let normal: f64 = s.contact.iter().map(|c| c.pressure * c.weight).sum();
        let sideways: f64 = s
            .contact
            .iter()
            .map(|c| c.friction_traction[0] * c.weight)
            .sum();
        println!("  Σ w p = {normal:.12}, Σ w t_x = {sideways:.12}, width {width}");
        assert!((normal - p * width).abs() <= 1e-8 * p * width, "{normal}");
        assert!(
            (sideways.abs() - tau * width).abs() <= 1e-8 * tau * width,
            "{sideways}"
        );
        for c in &s.contact {
            assert_eq!(c.friction_state, FrictionState::Stick);
            assert!(c.slip <= 1e-10 * scale, "{}", c.slip);
        }
    }
}

/// The trace constant of the uniqueness condition takes, at a pair, the jump across the
/// interface. With the master side clamped the jump is the slave side's own trace, so the
/// constant equals that of the slave body alone against a foundation on the same part (the
/// two bodies' stiffnesses decouple); with the master side free it is larger (both sides
/// move the jump).
#[test]
fn the_trace_constant_of_a_pair_is_that_of_the_jump() {
    use hemicontact::solver::uniqueness::trace_constant;
    let settings = SolverSettings::default();
    let mesh = stacked_2d(5, 4, 2);
    let part = |n: &str| mesh.part_index(n).unwrap();
    let clamp = |p: usize| Dirichlet {
        part: p,
        components: [true; 3],
        value: [0.0; 3],
    };
    let pair = ContactBoundary {
        part: part("a_bottom"),
        gap: 0.0,
        obstacle: None,
        against: Some(MasterPart::new(part("b_top"))),
        normal: NormalLaw::Signorini,
        friction: None,
    };
    let both = |master_clamped: bool| {
        let mut b = Problem::builder(mesh.clone(), material())
            .plane(Plane::Strain)
            .dirichlet(clamp(part("b_bottom")))
            .dirichlet(clamp(part("a_top")))
            .contact(pair.clone());
        if master_clamped {
            b = b.dirichlet(clamp(part("b_top")));
        }
        b.build().unwrap()
    };
    let alone = {
        let m = rectangle(&Rectangle {
            origin: [0.0, H / 2.0],
            size: [1.0, H / 2.0],
            n: [5, 2],
            pattern: CutPattern::Uniform,
            progression: [1.0, 1.0],
        })
        .unwrap();
        let (top, bottom) = (
            m.part_index("top").unwrap(),
            m.part_index("bottom").unwrap(),
        );
        Problem::builder(m, material())
            .plane(Plane::Strain)
            .dirichlet(clamp(top))
            .contact(ContactBoundary {
                part: bottom,
                against: None,
                ..pair.clone()
            })
            .build()
            .unwrap()
    };
    let (clamped, _) = trace_constant(&both(true), &settings).unwrap();
    let (free, _) = trace_constant(&both(false), &settings).unwrap();
    let (one, _) = trace_constant(&alone, &settings).unwrap();
    println!("trace constants: master clamped {clamped:.12}, slave alone {one:.12}, master free {free:.12}");
    assert!((clamped - one).abs() <= 1e-8 * one, "{clamped} vs {one}");
    assert!(free > 1.01 * clamped, "{free} vs {clamped}");
}

/// The forces on each body (`summary.json`'s `bodies`): on non-matching meshes sheared
/// with exact Coulomb friction, each body's load, reactions and interface forces balance,
/// the pair's forces on the two bodies are equal and opposite, and the slave body's equals
/// the pair's resultant in `contact_totals`.
#[test]
fn each_body_balances_and_the_pair_acts_equal_and_opposite_on_the_two() {
    let fr = Friction {
        bound: FrictionBound::Coulomb,
        mu: FrictionCoefficient::Constant { mu: 0.3 },
        potential: FrictionPotential::Norm {
            treatment: NormTreatment::Exact,
        },
    };
    let problem = sheared(stacked_2d(5, 4, 2), NormalLaw::Signorini, Some(fr), 0.002);
    let s = solve(&problem, &SolverSettings::default()).unwrap();
    assert!(s.report.converged, "{}", s.report.message);
    let bodies = hemicontact::io::bodies::bodies(&problem, &s);
    let totals = hemicontact::io::contact_totals::contact_totals(&problem, &s.contact);
    assert_eq!(bodies.len(), 2);
    let (lower, upper) = (&bodies[0], &bodies[1]);
    println!("lower: {lower:?}\nupper: {upper:?}");
    assert_eq!(lower.regions, ["b"]);
    assert_eq!(upper.regions, ["a"]);
    assert!(upper.parts.contains(&"a_bottom".to_string()));
    let scale = upper.contact_force[1].abs();
    // Pressed (p = E δ/H on 1 m) and sheared: the friction force is below μ times it.
    assert!((scale - E * DELTA / H).abs() < 0.01 * scale, "{scale}");
    assert!(upper.contact_force[0].abs() > 0.1 * 0.3 * scale);
    for k in 0..2 {
        assert!((lower.contact_force[k] + upper.contact_force[k]).abs() < 1e-10 * scale);
        assert!((upper.contact_force[k] - totals[0].force[k]).abs() < 1e-12 * scale);
    }
    for b in &bodies {
        assert!(b.imbalance < 1e-9, "{b:?}");
    }
}

/// The interface figure's master side: on matching meshes the pressure spread onto the
/// master nodes is the slave side's to round-off, at every master node along the
/// interface; on non-matching ones it carries the same force, its nodal values off by the
/// node-to-segment error.
#[test]
fn the_master_side_carries_the_slave_pressure() {
    use hemicontact::plot::interface::{along, master_pressure};
    let p = E * DELTA / H;
    for (nx_a, nx_b) in [(4, 4), (5, 4)] {
        let problem = pressed(stacked_2d(nx_a, nx_b, 2), NormalLaw::Signorini);
        let s = solve(&problem, &SolverSettings::default()).unwrap();
        assert!(s.report.converged, "{}", s.report.message);
        let al = along(&problem, &s, 0);
        let master = master_pressure(&problem, &s, 0, &al);
        let worst = master
            .iter()
            .map(|m| (m.1 - p).abs() / p)
            .fold(0.0f64, f64::max);
        println!("{nx_a} slave against {nx_b} master segments: {} master nodes, pressure error {worst:.2e}", master.len());
        // Every master node of the interface is along the slave side (same width).
        assert_eq!(master.len(), nx_b + 1);
        if nx_a == nx_b {
            assert!(worst < 1e-12, "{worst:e}");
        } else {
            assert!(worst > 1e-3 && worst < 0.1, "{worst:e}");
        }
    }
}

/// A crack: two parts of one mesh (the crack's faces, their nodes coincident, its tips
/// shared) paired with each other. Pressed across the crack (ν = 0), the block is in
/// uniform compression as if uncut: the faces carry the pressure E δ/H at every point and
/// the displacement is exact, the tips (nodes of both faces) are no contact points. Without
/// the pair the faces are free and pass through each other.
#[test]
fn a_crack_closed_by_compression_transmits_the_pressure_exactly() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/gmsh/crack.msh");
    let read = hemicontact::mesh::gmsh::read_msh(&path).unwrap();
    println!("crack.msh notes: {:?}", read.notes);
    assert!(read
        .notes
        .iter()
        .any(|n| n.contains("`crack_lower` and `crack_upper`")));
    let mesh = read.mesh;
    let part = |name: &str| mesh.part_index(name).unwrap();
    let upper = mesh.part_nodes(part("crack_upper"));
    let lower = mesh.part_nodes(part("crack_lower"));
    let shared = upper.iter().filter(|v| lower.contains(v)).count();
    assert_eq!(shared, 2, "the two tips");
    let build = |pair: bool| {
        let mut b = Problem::builder(mesh.clone(), material())
            .plane(Plane::Strain)
            .dirichlet(Dirichlet {
                part: part("bottom"),
                components: [true; 3],
                value: [0.0; 3],
            })
            .dirichlet(Dirichlet {
                part: part("top"),
                components: [true; 3],
                value: [0.0, -DELTA, 0.0],
            });
        if pair {
            b = b.contact(ContactBoundary {
                part: part("crack_upper"),
                gap: 0.0,
                obstacle: None,
                against: Some(MasterPart::new(part("crack_lower"))),
                normal: NormalLaw::Signorini,
                friction: None,
            });
        }
        b.build().unwrap()
    };
    let problem = build(true);
    let s = solve(&problem, &SolverSettings::default()).unwrap();
    assert!(
        s.report.converged && s.report.certificate.passes(),
        "{}",
        s.report.message
    );
    let p = E * DELTA / H;
    let worst = compression_error(&mesh, &s, p);
    println!(
        "crack.msh: {} points ({} nodes on the upper face, 2 tips), largest relative error {worst:.1e}",
        s.contact.len(),
        upper.len()
    );
    assert_eq!(s.contact.len(), upper.len() - 2);
    assert!(worst < 1e-10, "{worst:e}");
    // Without the pair the faces pass through each other: the upper face's nodes move down
    // past their twins.
    let free = solve(&build(false), &SolverSettings::default()).unwrap();
    assert!(free.report.converged);
    let twin = |v: u32| {
        *lower
            .iter()
            .find(|&&w| w != v && mesh.node(w as usize) == mesh.node(v as usize))
            .unwrap()
    };
    let overlap = upper
        .iter()
        .filter(|v| !lower.contains(v))
        .map(|&v| free.u[2 * v as usize + 1] - free.u[2 * twin(v) as usize + 1])
        .fold(0.0f64, f64::min);
    println!("without the pair the faces overlap by {:.2e} m", -overlap);
    assert!(overlap < -1e-3 * DELTA, "{overlap}");
}

/// # The edge of the master surface
///
/// A slave node beyond the edge of the master surface is no contact point, even within the
/// 5 % by which a projection may fall outside a facet (that tolerance reaches across
/// interior edges and onto symmetry planes only) and even where its closest point is a
/// vertex shared by several master facets on the surface's outer edge (3D).
///
/// 2D: the upper block `[0.2, 1.04]` overhangs the lower one (`[0, 1]`, one facet across,
/// so 5 % of a facet is 0.05) by 0.04: its node at x = 1.04 was a contact point and carried
/// 2 % of the force; it is none now, every point is over the master, and the force on the
/// pair equals the reaction of the held bottom. A block standing wholly beside the master
/// (`x ∈ [1.002, 1.048]`) has no contact point: refused naming the two parts.
#[test]
fn slave_nodes_beyond_the_edge_of_the_master_surface_are_no_contact_points() {
    let rect = |x0: f64, y0: f64, w: f64, nx: usize| layer([x0, y0], w, [nx, 2]);
    let overhang = merged(&rect(0.0, 0.0, 1.0, 1), &rect(0.2, H / 2.0, 0.84, 4));
    let problem = pressed(overhang, NormalLaw::Signorini);
    let s = solve(&problem, &SolverSettings::default()).unwrap();
    assert!(s.report.converged, "{}", s.report.message);
    let mesh = problem.mesh();
    let beyond: Vec<f64> = s
        .contact
        .iter()
        .map(|c| mesh.node(c.node as usize)[0])
        .filter(|&x| x > 1.0)
        .collect();
    println!(
        "2D overhang by 0.04: {} points, beyond the edge at x = {beyond:?}",
        s.contact.len()
    );
    assert!(beyond.is_empty() && s.contact.len() == 4, "{beyond:?}");
    let pair: f64 = s.contact.iter().map(|c| c.force[1]).sum();
    let bottom: f64 = mesh
        .part_nodes(mesh.part_index("b_bottom").unwrap())
        .iter()
        .map(|&v| s.reactions[2 * v as usize + 1])
        .sum();
    assert!(
        (pair - bottom).abs() < 1e-10 * bottom.abs(),
        "{pair} {bottom}"
    );
    // Wholly beside the master: no contact point, refused.
    for nx_b in [1, 4] {
        let beside = merged(&rect(0.0, 0.0, 1.0, nx_b), &rect(1.002, H / 2.0, 0.046, 4));
        let part = |n: &str| beside.part_index(n).unwrap();
        let e = Problem::builder(beside.clone(), material())
            .contact(ContactBoundary {
                part: part("a_bottom"),
                gap: 0.0,
                obstacle: None,
                against: Some(MasterPart::new(part("b_top"))),
                normal: NormalLaw::Signorini,
                friction: None,
            })
            .dirichlet(Dirichlet {
                part: part("b_bottom"),
                components: [true; 3],
                value: [0.0; 3],
            })
            .build()
            .unwrap_err()
            .to_string();
        println!("beside ({nx_b} master facets): {e}");
        assert!(
            e.contains("contact[0].against")
                && e.contains("`a_bottom` against `b_top`")
                && e.contains("a pair with contact points"),
            "{e}"
        );
    }
}

/// 3D: the upper block (10 × 10 cubes across) overhangs the lower one (4 × 4) by two of its
/// elements along x. The nodes of the overhang are a full element or more beyond the master
/// surface's edge, where their closest points are vertices shared by two or three master
/// facets on that edge: no contact points (they were, as if above a convex corner, and
/// held the overhang up). Every point is over the master, and the pair's force balances
/// the held bottom.
#[test]
fn in_3d_an_overhang_beyond_the_master_surface_has_no_contact_points() {
    let cube = |origin: [f64; 3], n: usize| {
        cuboid(&BoxSpec {
            origin,
            size: [1.0, 1.0, H / 2.0],
            n: [n, n, 2],
            pattern: CutPattern::Uniform,
            progression: [1.0; 3],
        })
        .unwrap()
    };
    let mesh = merged(&cube([0.0; 3], 4), &cube([0.2, 0.0, H / 2.0], 10));
    let problem = pressed(mesh, NormalLaw::Signorini);
    let s = solve(&problem, &SolverSettings::default()).unwrap();
    assert!(s.report.converged, "{}", s.report.message);
    assert!(s.report.certificate.passes(), "{:?}", s.report.certificate);
    let mesh = problem.mesh();
    let beyond = s
        .contact
        .iter()
        .filter(|c| mesh.node(c.node as usize)[0] > 1.0 + 1e-12)
        .count();
    println!(
        "3D overhang: {} points, {beyond} beyond the master's edge",
        s.contact.len()
    );
    // The slave nodes over [0.2, 1] × [0, 1]: 9 columns of 11.
    assert_eq!((s.contact.len(), beyond), (99, 0));
    let pair: f64 = s.contact.iter().map(|c| c.force[2]).sum();
    let bottom: f64 = mesh
        .part_nodes(mesh.part_index("b_bottom").unwrap())
        .iter()
        .map(|&v| s.reactions[3 * v as usize + 2])
        .sum();
    assert!(
        (pair - bottom).abs() < 1e-10 * bottom.abs(),
        "{pair} {bottom}"
    );
}

/// # A slave part that turns a corner
///
/// The upper block's bottom and right side in one slave part: at the corner node the two
/// faces are paired apart, and the side, at a right angle to the pair's normal, is no
/// contact point, so the corner carries the bottom's weight only (0.125 of the 0.25-wide
/// elements, not 0.25). The solution is that of the bottom alone as the slave part, to
/// round-off, with Signorini and with normal compliance (where the doubled weight raised
/// the corner's force by 45 %), and the printed corner pressure is the same.
#[test]
fn a_slave_part_that_turns_a_corner_weighs_its_faces_apart() {
    let rect = |x0: f64, y0: f64, w: f64, nx: usize| layer([x0, y0], w, [nx, 2]);
    let mesh = merged(&rect(0.0, 0.0, 2.0, 8), &rect(0.5, H / 2.0, 1.0, 4));
    // The same mesh with the part `a_corner`: `a_bottom` and `a_right` together.
    let mut parts: Vec<(String, Vec<u32>)> = Vec::new();
    let mut corner = Vec::new();
    for name in mesh.part_names() {
        let p = mesh.part_index(name).unwrap();
        let facets: Vec<u32> = mesh
            .part_facets(p)
            .flat_map(|f| mesh.facet(f).to_vec())
            .collect();
        if name == "a_bottom" || name == "a_right" {
            corner.extend(facets);
        } else {
            parts.push((name.clone(), facets));
        }
    }
    parts.push(("a_corner".into(), corner));
    let turned = Mesh::from_parts(2, mesh.coords().to_vec(), mesh.cells().to_vec(), &parts)
        .unwrap()
        .with_regions(
            (0..mesh.n_cells())
                .map(|c| mesh.cell_region(c) as u16)
                .collect(),
            mesh.region_names().to_vec(),
        )
        .unwrap();
    for normal in [
        NormalLaw::Signorini,
        NormalLaw::Compliance(NormalCompliance { c_nu: 1e4 }),
    ] {
        let solve_with = |m: &Mesh, slave: &str| {
            let names = ["b_bottom", "a_top", slave, "b_top"];
            let problem = sheared_named(m.clone(), normal.clone(), None, 0.0, names);
            let s = solve(&problem, &SolverSettings::default()).unwrap();
            assert!(s.report.converged, "{}", s.report.message);
            s
        };
        let bottom = solve_with(&mesh, "a_bottom");
        let both = solve_with(&turned, "a_corner");
        let du = bottom
            .u
            .iter()
            .zip(&both.u)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f64, f64::max);
        let u_max = bottom.u.iter().map(|x| x.abs()).fold(0.0f64, f64::max);
        // The corner node (1.5, 0.5) of the upper block, where `a_corner` turns.
        let at_corner = |s: &hemicontact::solver::Solution, m: &Mesh| {
            s.contact
                .iter()
                .filter(|c| {
                    let x = m.node(c.node as usize);
                    (x[0] - 1.5).abs() < 1e-12 && (x[1] - 0.5).abs() < 1e-12
                })
                .map(|c| (c.weight, c.pressure, c.force[1]))
                .collect::<Vec<_>>()
        };
        let (one, two) = (at_corner(&bottom, &mesh), at_corner(&both, &turned));
        println!("{normal:?}: corner {two:?} (bottom alone {one:?}), max |Δu| {du:.1e}");
        assert_eq!(two.len(), 1, "one point at the corner");
        assert!((two[0].0 - 0.125).abs() < 1e-14, "weight {}", two[0].0);
        assert!(du <= 1e-12 * u_max, "{du:e}");
        assert!(
            (two[0].1 - one[0].1).abs() <= 1e-10 * one[0].1,
            "{two:?} {one:?}"
        );
    }
}

/// # A master part that does not face the slave part
///
/// Refused naming both parts: the slave part's own body's far face (`a_bottom` against
/// `a_top`, which took a contact force of 1002 N/m with no load at all), the other body's
/// far face (`a_bottom` against `b_bottom`: the two outward normals point the same way),
/// and the master's far face from the other side (`b_top` against `a_top`). Accepted: the
/// faces that touch, and two blocks meshed with an overlap of 0.01 (an interference fit,
/// negative gaps) and pressed by δ, which then carry the uniform pressure `E (δ + 0.01)/H`.
#[test]
fn a_master_part_that_does_not_face_the_slave_part_is_refused() {
    let mesh = stacked_2d(4, 4, 2);
    let part = |n: &str| mesh.part_index(n).unwrap();
    for (slave, master, says) in [
        ("a_bottom", "a_top", "lies inside the body of"),
        ("a_bottom", "b_bottom", "faces away"),
        ("b_top", "a_top", "faces away"),
    ] {
        let e = Problem::builder(mesh.clone(), material())
            .dirichlet(Dirichlet {
                part: part("b_bottom"),
                components: [true; 3],
                value: [0.0; 3],
            })
            .dirichlet(Dirichlet {
                part: part("a_top"),
                components: [true; 3],
                value: [0.0; 3],
            })
            .contact(ContactBoundary {
                part: part(slave),
                gap: 0.0,
                obstacle: None,
                against: Some(MasterPart::new(part(master))),
                normal: NormalLaw::Signorini,
                friction: None,
            })
            .build()
            .unwrap_err()
            .to_string();
        println!("{slave} against {master}: {e}");
        assert!(
            e.contains("contact[0].against")
                && e.contains(&format!("`{slave}` against `{master}`"))
                && e.contains(says),
            "{e}"
        );
    }
    // An interference fit: the upper block meshed 0.01 into the lower one and pressed by
    // δ: the two blocks, of natural heights H/2 each, are shortened by δ + 0.01 together.
    let overlap = 0.01;
    let problem = pressed(stacked_2d_apart(4, 4, 2, -overlap), NormalLaw::Signorini);
    let s = solve(&problem, &SolverSettings::default()).unwrap();
    assert!(s.report.converged, "{}", s.report.message);
    let p = E * (overlap + DELTA) / H;
    let worst = s
        .contact
        .iter()
        .map(|c| (c.pressure - p).abs() / p)
        .fold(0.0f64, f64::max);
    println!(
        "interference fit: pressure {:.6} (E (δ + overlap)/H = {p:.6}), error {worst:.1e}",
        s.contact[0].pressure
    );
    assert!(worst < 1e-10, "{worst:e}");
}

/// # Bodies that pass through each other
///
/// A block whose bottom (the slave part, one element 2 m across) is pressed by δ onto the
/// apex of a roof (the master part, the two upper facets of a triangle): its two nodes
/// stand 0.71 m from the roof's slopes, so no slave node touches, the block moves down
/// freely by δ, and the apex ends up δ inside it. Node-to-segment contact cannot see this
/// (it enforces the laws at the slave nodes): the solution is the model's, and its note says
/// that the apex (node 2) of `b_roof` lies δ = 0.3 m inside the body of `a_bottom`, in
/// `summary.json` among the notes. At δ = 0.1 (below a tenth of the 2 m facet) and with the
/// sides swapped (the roof's nodes as slaves, which keep the block out) there is no note.
#[test]
fn bodies_that_pass_through_each_other_get_a_note_with_the_depth() {
    // The roof (0, 0), (2, 0), (1, 1); the block [0, 2] × [1, 1.5] as two triangles.
    let coords = vec![
        0.0, 0.0, 2.0, 0.0, 1.0, 1.0, //
        0.0, 1.0, 2.0, 1.0, 2.0, 1.5, 0.0, 1.5,
    ];
    let cells = vec![0, 1, 2, 3, 4, 5, 3, 5, 6];
    let parts = vec![
        ("b_bottom".to_string(), vec![0, 1]),
        ("b_roof".to_string(), vec![1, 2, 2, 0]),
        ("a_bottom".to_string(), vec![3, 4]),
        ("a_top".to_string(), vec![5, 6]),
    ];
    let mesh = Mesh::from_parts(2, coords, cells, &parts).unwrap();
    for (delta, slave, master, noted) in [
        (0.3, "a_bottom", "b_roof", true),
        (0.1, "a_bottom", "b_roof", false),
        (0.3, "b_roof", "a_bottom", false),
    ] {
        let part = |n: &str| mesh.part_index(n).unwrap();
        let problem = Problem::builder(mesh.clone(), material())
            .plane(Plane::Strain)
            .dirichlet(Dirichlet {
                part: part("b_bottom"),
                components: [true; 3],
                value: [0.0; 3],
            })
            .dirichlet(Dirichlet {
                part: part("a_top"),
                components: [true; 3],
                value: [0.0, -delta, 0.0],
            })
            .contact(ContactBoundary {
                part: part(slave),
                gap: 0.0,
                obstacle: None,
                against: Some(MasterPart::new(part(master))),
                normal: NormalLaw::Signorini,
                friction: None,
            })
            .build()
            .unwrap();
        let settings = SolverSettings::default();
        let s = solve(&problem, &settings).unwrap();
        assert!(s.report.converged, "{}", s.report.message);
        let summary = hemicontact::io::summary::Summary::new(&problem, &settings, &s, None, "");
        let found = &summary.small_deformation.interpenetration;
        println!("δ = {delta}, {slave} against {master}: {found:?}");
        if noted {
            assert_eq!(found.len(), 1, "{found:?}");
            let i = &found[0];
            assert_eq!(
                (i.node, i.part.as_str(), i.through.as_str()),
                (2, "b_roof", "a_bottom")
            );
            assert!((i.depth - delta).abs() < 1e-12, "{}", i.depth);
            assert!(
                summary
                    .notes
                    .iter()
                    .any(|n| n.contains("pass through each other")
                        && n.contains("node 2 of `b_roof`")
                        && n.contains("0.3 m")),
                "{:?}",
                summary.notes
            );
        } else {
            assert!(found.is_empty(), "{found:?}");
        }
    }
}

/// Blocks of unit width and height H/2 stacked along the vertical (y in 2D, z in 3D): the
/// foundation `f` from 0, then the blocks `b1`, …, `b{n_free}`, each `gap` above the one
/// below (2D: 4 × 2 squares each; 3D: 2 × 2 × 1 cubes), one region and one prefix of parts
/// each.
fn stack_mesh(dim: usize, n_free: usize, gap: f64) -> Mesh {
    let names: Vec<String> = std::iter::once("f".to_string())
        .chain((1..=n_free).map(|k| format!("b{k}")))
        .collect();
    let blocks: Vec<Mesh> = (0..=n_free)
        .map(|k| {
            let z0 = k as f64 * (H / 2.0 + gap);
            if dim == 2 {
                rectangle(&Rectangle {
                    origin: [0.0, z0],
                    size: [1.0, H / 2.0],
                    n: [4, 2],
                    pattern: CutPattern::Uniform,
                    progression: [1.0, 1.0],
                })
            } else {
                cuboid(&BoxSpec {
                    origin: [0.0, 0.0, z0],
                    size: [1.0, 1.0, H / 2.0],
                    n: [2, 2, 1],
                    pattern: CutPattern::Uniform,
                    progression: [1.0; 3],
                })
            }
            .unwrap()
        })
        .collect();
    let refs: Vec<&Mesh> = blocks.iter().collect();
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    common::several_bodies(&refs, &names)
}

/// The stack of [`stack_mesh`] with `f_bottom` held, each free block held only sideways
/// (`u_x = 0` on its left side; in 3D `u_y = 0` on its front face too: free to move
/// vertically, nothing else), each block's bottom against the top of the one below
/// (Signorini, frictionless), and the vertical traction −p on the top of the highest.
fn stack(dim: usize, n_free: usize, gap: f64, p: f64) -> Problem {
    let mesh = stack_mesh(dim, n_free, gap);
    let part = |n: String| mesh.part_index(&n).unwrap();
    let mut load = [0.0; 3];
    load[dim - 1] = -p;
    let mut b = Problem::builder(mesh.clone(), material())
        .plane(Plane::Strain)
        .dirichlet(Dirichlet {
            part: part("f_bottom".into()),
            components: [true; 3],
            value: [0.0; 3],
        })
        .traction(Traction {
            part: part(format!("b{n_free}_top")),
            value: load,
        });
    for k in 1..=n_free {
        let below = if k == 1 {
            "f".to_string()
        } else {
            format!("b{}", k - 1)
        };
        b = b
            .dirichlet(Dirichlet {
                part: part(format!("b{k}_left")),
                components: [true, false, false],
                value: [0.0; 3],
            })
            .contact(ContactBoundary {
                part: part(format!("b{k}_bottom")),
                gap: 0.0,
                obstacle: None,
                against: Some(MasterPart::new(part(format!("{below}_top")))),
                normal: NormalLaw::Signorini,
                friction: None,
            });
        if dim == 3 {
            b = b.dirichlet(Dirichlet {
                part: part(format!("b{k}_front")),
                components: [false, true, false],
                value: [0.0; 3],
            });
        }
    }
    b.build().unwrap()
}

/// The exact displacement of the stack of [`stack`] (ν = 0): uniaxial compression
/// `u_v = −k g − p v′/E` at the height `v′ = v − k g` in the closed stack of a node of
/// block k (0 the foundation), nothing sideways.
fn stack_exact(mesh: &Mesh, v: usize, gap: f64, p: f64) -> Vec<f64> {
    let d = mesh.dim();
    let height = mesh.node(v)[d - 1];
    let k = (height / (H / 2.0 + gap) + 1e-9).floor();
    let mut u = vec![0.0; d];
    u[d - 1] = -k * gap - p * (height - k * gap) / E;
    u
}

/// A stack of free blocks on a held foundation, each block held only sideways, pressed by p
/// on the top of the highest: the blocks' vertical translations, free, are analysed
/// together (the pair between two free blocks has the row `y_k − y_{k−1}`), every
/// interface carries the uniform pressure p, and the displacement is uniaxial compression,
/// exact on matching meshes: two free blocks and a chain of three in 2D, two in 3D,
/// touching and each 0.01 m above the one below; and under 10⁻⁶ Pa, whose deformation
/// (10⁻⁹ m) is far below the gaps, dropped across them first (the rigid drop's linear
/// programme over the group's stacked coefficients), to 10⁻⁸ of the deformation. (Before
/// the joint analysis the pair between two free blocks was refused: "both bodies have free
/// rigid motions: the slave body (of node 30) 1, the master body (of node 26) 1".)
#[test]
fn a_stack_of_free_blocks_on_a_held_foundation_carries_the_load_through_every_interface() {
    for (dim, n_free, gap, p) in [
        (2, 2, 0.0, 10.0),
        (2, 2, 0.01, 10.0),
        (2, 3, 0.0, 10.0),
        (2, 3, 0.01, 10.0),
        (3, 2, 0.0, 10.0),
        (3, 2, 0.01, 10.0),
        (2, 3, 0.01, 1e-6),
        (3, 2, 0.01, 1e-6),
    ] {
        let case = format!("{dim}D, {n_free} free blocks, gap {gap}, p {p}");
        let problem = stack(dim, n_free, gap, p);
        let rigid = problem.rigid_motions().unwrap();
        let group: Vec<usize> = (1..=n_free).collect();
        assert_eq!(rigid.groups.len(), 1, "{case}");
        assert_eq!(rigid.groups[0].bodies, group, "{case}");
        assert!(rigid.groups[0].uncarried.is_empty(), "{case}");
        assert_eq!(
            rigid.groups[0].pressed.len(),
            n_free,
            "{case}: one vertical translation each"
        );
        let s =
            solve(&problem, &SolverSettings::default()).unwrap_or_else(|e| panic!("{case}: {e}"));
        assert!(s.report.converged, "{case}: {}", s.report.message);
        assert!(
            s.report.certificate.passes(),
            "{case}: {:?}",
            s.report.certificate
        );
        let mesh = problem.mesh();
        let d = mesh.dim();
        let mut eu = 0.0f64;
        for v in 0..mesh.n_nodes() {
            let exact = stack_exact(mesh, v, gap, p);
            for i in 0..d {
                eu = eu.max((s.u[d * v + i] - exact[i]).abs());
            }
        }
        let ep = s
            .contact
            .iter()
            .map(|c| (c.pressure - p).abs())
            .fold(0.0f64, f64::max);
        // Each interface carries p over its unit width (area).
        let mut per_interface = vec![0.0; n_free];
        for c in &s.contact {
            per_interface[c.boundary] += c.pressure * c.weight;
        }
        let deformation = p * (n_free as f64 + 1.0) * H / 2.0 / E;
        let rel = if p < 1.0 { 1e-8 } else { 1e-10 };
        // The rounding of a total of gaps: a few units in its last place.
        let tol_u = rel * deformation + 1e-14 * n_free as f64 * gap;
        println!(
            "{case}: Σ w p per interface {per_interface:?}, pressure error {:.1e} p, \
             displacement error {:.1e} of the deformation {deformation:.1e}; drop {:?}",
            ep / p,
            eu / deformation,
            s.report.rigid_drop
        );
        assert!(ep <= rel * p, "{case}: {ep:e}");
        assert!(eu <= tol_u, "{case}: {eu:e}");
        for total in per_interface {
            assert!((total - p).abs() <= rel * p, "{case}: {total}");
        }
        if gap > 100.0 * deformation {
            assert_eq!(
                s.report.rigid_drop.len(),
                n_free,
                "{case}: every block dropped"
            );
        }
    }
}

/// Three blocks side by side along x: `l` held at its left side, `m` free (no support at
/// all) and `r` held only vertically (`u_y = 0` on its bottom) and pushed against `m` by the
/// traction q on its right side; `m` pressed down by s on its top, held up by Coulomb
/// friction on both its sides. `m` and `r` both have free motions: their pair is analysed
/// jointly, and `m`'s vertical translation, which moves no contact point along its normal,
/// is a sliding motion of the group that friction alone carries.
fn clamped(s: f64, mu: f64) -> Problem {
    let blocks: Vec<Mesh> = (0..3)
        .map(|k| {
            rectangle(&Rectangle {
                origin: [k as f64, 0.0],
                size: [1.0, 1.0],
                n: [2, 4],
                pattern: CutPattern::Uniform,
                progression: [1.0, 1.0],
            })
            .unwrap()
        })
        .collect();
    let mesh = common::several_bodies(&[&blocks[0], &blocks[1], &blocks[2]], &["l", "m", "r"]);
    let part = |n: &str| mesh.part_index(n).unwrap();
    let friction = Some(Friction {
        bound: FrictionBound::Coulomb,
        mu: FrictionCoefficient::Constant { mu },
        potential: FrictionPotential::Norm {
            treatment: NormTreatment::Exact,
        },
    });
    let pair = |slave: &str, master: &str| ContactBoundary {
        part: part(slave),
        gap: 0.0,
        obstacle: None,
        against: Some(MasterPart::new(part(master))),
        normal: NormalLaw::Signorini,
        friction: friction.clone(),
    };
    Problem::builder(mesh.clone(), material())
        .plane(Plane::Strain)
        .dirichlet(Dirichlet {
            part: part("l_left"),
            components: [true; 3],
            value: [0.0; 3],
        })
        .dirichlet(Dirichlet {
            part: part("r_bottom"),
            components: [false, true, false],
            value: [0.0; 3],
        })
        .traction(Traction {
            part: part("r_right"),
            value: [-10.0, 0.0, 0.0],
        })
        .traction(Traction {
            part: part("m_top"),
            value: [0.0, -s, 0.0],
        })
        .contact(pair("m_left", "l_right"))
        .contact(pair("r_left", "m_right"))
        .build()
        .unwrap()
}

/// A block clamped by friction between two blocks, one of which is itself free (see
/// [`clamped`]): each side carries the push q × 1 m = 10 N/m as its normal force, the two
/// sides' friction carries the block's load s × 1 m, which friction holds up to
/// μ × (10 + 10) N/m, and above that limit the solve is refused naming the group's
/// sliding motion and the limit. (Before the joint analysis: refused, "`r_left` against
/// `m_right`: both bodies have free rigid motions: the slave body (of node 30) 1, the
/// master body (of node 17) 3".)
#[test]
fn a_block_clamped_by_friction_between_a_held_block_and_a_free_one_is_held() {
    let mu = 0.3;
    let s = 2.0;
    let problem = clamped(s, mu);
    let rigid = problem.rigid_motions().unwrap();
    assert_eq!(rigid.groups.len(), 1);
    assert_eq!(rigid.groups[0].bodies, [1, 2]);
    assert_eq!(rigid.groups[0].sliding.len(), 1, "m's vertical translation");
    let sol = solve(&problem, &SolverSettings::default()).unwrap();
    assert!(sol.report.converged, "{}", sol.report.message);
    assert!(
        sol.report.certificate.passes(),
        "{:?}",
        sol.report.certificate
    );
    let (mut normal, mut vertical) = ([0.0; 2], 0.0);
    for c in &sol.contact {
        normal[c.boundary] += c.pressure * c.weight;
        // The friction force on m: on its left side m is the slave, on its right the master.
        let on_m = if c.boundary == 0 { 1.0 } else { -1.0 };
        vertical += on_m * c.friction_traction[1] * c.weight;
    }
    println!("clamped block: normal forces {normal:?}, friction on m {vertical}");
    for n in normal {
        assert!((n - 10.0).abs() <= 1e-8 * 10.0, "{n}");
    }
    assert!((vertical - s).abs() <= 1e-8 * s, "{vertical}");
    // Above the limit 0.3 × 20 N/m = 6 N/m.
    match solve(&clamped(6.1, mu), &SolverSettings::default()) {
        Err(e) => {
            let msg = e.to_string();
            println!("{msg}");
            assert!(msg.contains("friction cannot hold the body"), "{msg}");
            assert!(
                msg.contains("region `m`") && msg.contains("translation along y"),
                "{msg}"
            );
            assert!(msg.contains("6.1 N/m") && msg.contains("6 N/m"), "{msg}");
        }
        Ok(s) => panic!("held above the limit: {}", s.report.message),
    }
}

/// Two free blocks in contact with each other, each held only sideways, and nothing holding
/// them vertically: their pair carries only their relative vertical motion, so their joint
/// vertical translation is free, and the problem is refused before any solve, naming the
/// two bodies by their cell regions and the motion in words. (Before: "both bodies have
/// free rigid motions: the slave body (of node 15) 1, the master body (of node 11) 1",
/// naming nodes, and no motion.)
#[test]
fn two_free_blocks_that_nothing_holds_together_are_refused_naming_them_and_the_motion() {
    let mesh = stacked_2d(4, 4, 2);
    let part = |n: &str| mesh.part_index(n).unwrap();
    let refused = Problem::builder(mesh.clone(), material())
        .plane(Plane::Strain)
        .dirichlet(Dirichlet {
            part: part("b_left"),
            components: [true, false, false],
            value: [0.0; 3],
        })
        .dirichlet(Dirichlet {
            part: part("a_left"),
            components: [true, false, false],
            value: [0.0; 3],
        })
        .traction(Traction {
            part: part("a_top"),
            value: [0.0, -10.0, 0.0],
        })
        .contact(ContactBoundary {
            part: part("a_bottom"),
            gap: 0.0,
            obstacle: None,
            against: Some(MasterPart::new(part("b_top"))),
            normal: NormalLaw::Signorini,
            friction: None,
        })
        .build();
    let msg = match refused {
        Err(e @ hemicontact::Error::RigidMotion { .. }) => e.to_string(),
        Err(e) => panic!("unexpected error: {e}"),
        Ok(_) => panic!("accepted"),
    };
    println!("{msg}");
    for words in [
        "region `b`, mesh component 1 of 2",
        "region `a`, mesh component 2 of 2",
        "region `b` (mesh component 1 of 2) and region `a` (mesh component 2 of 2) together: \
         translation along y",
    ] {
        assert!(msg.contains(words), "{words:?} not in {msg}");
    }
}

/// [`sheared_named`] without friction, the lower block `b` of Young's modulus `e_b` and the
/// upper block `a` of `e_a` (ν = 0 both, the cell regions of [`common::two_bodies`]),
/// the slave side `a_bottom` against `b_top` or, with `a_slave` false, `b_top` against
/// `a_bottom`.
fn pressed_two_materials(mesh: Mesh, e_b: f64, e_a: f64, a_slave: bool) -> Problem {
    let names = if a_slave {
        ["b_bottom", "a_top", "a_bottom", "b_top"]
    } else {
        ["b_bottom", "a_top", "b_top", "a_bottom"]
    };
    let of = |e: f64| {
        Material::elastic(Elasticity::Hooke(Hooke {
            lambda: 0.0,
            mu: e / 2.0,
        }))
    };
    sheared_named(mesh, NormalLaw::Signorini, None, 0.0, names)
        .to_builder()
        .materials(vec![of(e_b), of(e_a)], vec![0, 1])
        .build()
        .unwrap()
}

/// The stress `σ = δ / (h/E_b + h/E_a)` (h = H/2) of two blocks of moduli `e_b` and `e_a`
/// pressed on each other by δ, and the exact `u_y` at height y: `−σ y/E_b` in the lower
/// block, `−σ h/E_b − σ (y − h)/E_a` in the upper one (`upper`).
fn series(e_b: f64, e_a: f64, y: f64, upper: bool) -> (f64, f64) {
    let h = H / 2.0;
    let sigma = DELTA / (h / e_b + h / e_a);
    let u = if upper {
        -sigma * h / e_b - sigma * (y - h) / e_a
    } else {
        -sigma * y / e_b
    };
    (sigma, u)
}

/// Two blocks of stiffness contrast up to 10¹², pressed on each other, either block the
/// slave side, on matching meshes: the patch test of two materials (ν = 0, uniaxial: the
/// stress σ of [`series`] in both, the pressure σ at every point) to 1e-8 of δ for the
/// displacement, of σ for the force through the held block and for the pressure at every
/// point. The stiff upper block is moved by nearly δ as a whole when the lower one is soft:
/// its nodal forces are sums of terms `E_a δ` that cancel to σ, 10¹² times smaller. The
/// pair's penalty is the softer body's (`r = γ S/h` with S the smaller of the two sides'
/// moduli): with the stiff side's, the pressure `λ + r (u_ν − g)` of a stiff slave was
/// resolved only to `r ε δ`, 5.7e-3 σ at contrast 10¹².
#[test]
fn blocks_of_any_stiffness_contrast_pass_the_patch_test_from_either_side() {
    let settings = SolverSettings::default();
    let mut failed = Vec::new();
    for contrast in [1.0, 1e3, 1e6, 1e9, 1e12] {
        for (e_b, e_a) in [(E, E * contrast), (E * contrast, E)] {
            for a_slave in [true, false] {
                let problem = pressed_two_materials(stacked_2d(4, 4, 2), e_b, e_a, a_slave);
                let s = solve(&problem, &settings).unwrap();
                let case = format!(
                    "E_b = {e_b:e}, E_a = {e_a:e}, slave {}",
                    if a_slave { "a" } else { "b" }
                );
                if !s.report.converged {
                    failed.push(format!("{case}: {}", s.report.message));
                    continue;
                }
                let mesh = problem.mesh();
                let first_upper = mesh
                    .part_nodes(mesh.part_index("a_bottom").unwrap())
                    .into_iter()
                    .min()
                    .unwrap() as usize;
                let (sigma, _) = series(e_b, e_a, 0.0, false);
                let mut eu = 0.0f64;
                for v in 0..mesh.n_nodes() {
                    let (_, exact) = series(e_b, e_a, mesh.node(v)[1], v >= first_upper);
                    eu = eu.max((s.u[2 * v + 1] - exact).abs()).max(s.u[2 * v].abs());
                }
                let held: f64 = mesh
                    .part_nodes(mesh.part_index("b_bottom").unwrap())
                    .iter()
                    .map(|&v| s.reactions[2 * v as usize + 1])
                    .sum();
                let ef = (held - sigma).abs();
                let ep = s
                    .contact
                    .iter()
                    .map(|c| (c.pressure - sigma).abs())
                    .fold(0.0f64, f64::max);
                println!(
                    "{case}: {} Newton steps, displacement error {:.1e} δ, force through the \
                     held block {:.1e} σ, pressure {:.1e} σ",
                    s.report.newton.len(),
                    eu / DELTA,
                    ef / sigma,
                    ep / sigma
                );
                if eu > 1e-8 * DELTA || ef > 1e-8 * sigma || ep > 1e-8 * sigma {
                    failed.push(format!(
                        "{case}: errors {:e} δ, force {:e} σ, pressure {:e} σ",
                        eu / DELTA,
                        ef / sigma,
                        ep / sigma
                    ));
                }
            }
        }
    }
    assert!(failed.is_empty(), "{failed:#?}");
}

/// Blocks of stiffness contrast up to 10¹² on non-matching meshes (5 slave segments against
/// 4 master ones, and 4 against 5), either block the slave side: node-to-segment passes no
/// patch test here, but every solve converges with a passing certificate, and the force
/// through the held block is the stress σ of [`series`] within the error of node-to-segment
/// on these meshes for one material (1e-3).
#[test]
fn blocks_of_any_stiffness_contrast_on_non_matching_meshes_converge_from_either_side() {
    let settings = SolverSettings::default();
    let mut failed = Vec::new();
    for contrast in [1.0, 1e3, 1e6, 1e9, 1e12] {
        for (e_b, e_a) in [(E, E * contrast), (E * contrast, E)] {
            for a_slave in [true, false] {
                let (nx_a, nx_b) = if a_slave { (5, 4) } else { (4, 5) };
                let mesh = stacked_2d(nx_a, nx_b, 2);
                let problem = pressed_two_materials(mesh, e_b, e_a, a_slave);
                let s = solve(&problem, &settings).unwrap();
                let case = format!(
                    "E_b = {e_b:e}, E_a = {e_a:e}, slave {}",
                    if a_slave { "a" } else { "b" }
                );
                if !s.report.converged {
                    failed.push(format!("{case}: {}", s.report.message));
                    continue;
                }
                let mesh = problem.mesh();
                let (sigma, _) = series(e_b, e_a, 0.0, false);
                let held: f64 = mesh
                    .part_nodes(mesh.part_index("b_bottom").unwrap())
                    .iter()
                    .map(|&v| s.reactions[2 * v as usize + 1])
                    .sum();
                let ef = (held - sigma).abs() / sigma;
                println!(
                    "{case}: {} Newton steps, force through the held block off by {ef:.1e} σ",
                    s.report.newton.len()
                );
                if ef > 1e-3 {
                    failed.push(format!("{case}: force {ef:e} σ"));
                }
            }
        }
    }
    assert!(failed.is_empty(), "{failed:#?}");
}
