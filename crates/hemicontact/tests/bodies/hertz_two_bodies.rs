//! # Verification: Hertz and Cattaneo–Mindlin contact between two elastic bodies
//!
//! Two cylinders of radii R₁ (upper) and R₂ (lower) and different materials, pressed
//! together by a force F per unit length along their axes, touch over a strip of
//! half-width `a = √(4 F R*/(π E*))` with the elliptical pressure `p(x) = p₀ √(1 − x²/a²)`,
//! `p₀ = 2F/(π a)`, where `1/R* = 1/R₁ + 1/R₂` and `1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂`
//! (Johnson, *Contact Mechanics*, 1985, §4.2 and eq. 4.45). Hertz's theory holds for
//! bodies large against a (half-spaces near the contact).
//!
//! In 3D, two spheres: `a = (3 F R*/(4 E*))^{1/3}`, `p(r) = p₀ √(1 − r²/a²)`,
//! `p₀ = 3F/(2π a²)` (Johnson, §4.2, eq. 4.22–4.24), on a quarter of each body: the force,
//! the contact radius within one element and the peak pressure within 5 % are checked. Cattaneo–Mindlin (below) shears two
//! identical cylinders (2D) and two identical spheres (3D) with friction.
//!
//! Model: the half x ≥ 0 of each body (symmetry rollers on x = 0), each a block
//! `[0, 1] × [0, 1]` whose contact face follows the circle of its radius, graded toward the
//! contact point. The lower body (the master side) is held along y at its bottom; the upper
//! body (the slave side), pushed by the traction F/2 on its top, is free to move along y:
//! its vertical translation is carried by the pair. The force is thus exact by construction
//! (checked: the pair passes it whole); the half-width within one element and the peak
//! pressure within 5 % of Hertz are checked at the finest level, and the refinement table
//! is printed (`cargo test --release --test hertz_two_bodies -- --nocapture`).
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use hemicontact::contact::{
    ContactBoundary, Friction, FrictionBound, FrictionCoefficient, FrictionPotential, MasterPart,
    NormTreatment, NormalLaw,
};
use hemicontact::material::{Elasticity, Hooke, Material, Plane};
use hemicontact::mesh::generate::{cuboid, rectangle, BoxSpec, CutPattern, Rectangle};
use hemicontact::mesh::Mesh;
use hemicontact::problem::{Dirichlet, Problem, Traction};
use hemicontact::solver::certificate::FrictionState;
use hemicontact::solver::{solve, SolverSettings};
use std::f64::consts::PI;

const R1: f64 = 2.0;
const R2: f64 = 3.0;
const E1: f64 = 10.0;
const NU1: f64 = 0.3;
const E2: f64 = 20.0;
const NU2: f64 = 0.25;
/// The traction on the upper body's top (Pa): F = 2 q per unit length on the whole pair.
const Q: f64 = 0.025;

fn hooke(e: f64, nu: f64) -> Material {
    Material::elastic(Elasticity::Hooke(Hooke::from_young_poisson(
        e,
        nu,
        2,
        Plane::Strain,
    )))
}

/// The pair of the two bodies: the upper body's bottom (slave) against the lower body's top
/// (master), Signorini, with `friction`.
fn pair(mesh: &Mesh, friction: Option<Friction>) -> ContactBoundary {
    let part = |name: &str| mesh.part_index(name).unwrap();
    ContactBoundary {
        part: part("upper_bottom"),
        gap: 0.0,
        obstacle: None,
        against: Some(MasterPart::new(part("lower_top"))),
        normal: NormalLaw::Signorini,
        friction,
    }
}

/// The solution of `problem`, converged and certified.
fn certified(problem: &Problem) -> hemicontact::solver::Solution {
    let s = solve(problem, &SolverSettings::default()).unwrap();
    assert!(s.report.converged, "{}", s.report.message);
    assert!(s.report.certificate.passes(), "{:?}", s.report.certificate);
    s
}

/// The block `[0, 1] × [y0, y0 + 1]` (n × n cells, graded toward x = 0 and toward its
/// contact face at y = 0 by `r`), its face y = 0 moved onto the circle of radius `radius`
/// through the origin, curving away from the other body (`side` = +1 for the upper body,
/// −1 for the lower); the mapping fades linearly to the far face.
fn body(n: usize, r: f64, side: f64, radius: f64) -> Mesh {
    let y0 = if side > 0.0 { 0.0 } else { -1.0 };
    let m = rectangle(&Rectangle {
        origin: [0.0, y0],
        size: [1.0, 1.0],
        n: [n, n],
        pattern: CutPattern::Uniform,
        progression: [r, if side > 0.0 { r } else { 1.0 / r }],
    })
    .unwrap();
    let mut coords = m.coords().to_vec();
    for x in coords.chunks_exact_mut(2) {
        let lift = radius - (radius * radius - x[0] * x[0]).sqrt();
        let weight = 1.0 - x[1].abs();
        x[1] += side * lift * weight;
    }
    let parts: Vec<(String, Vec<u32>)> = m
        .part_names()
        .iter()
        .map(|name| {
            let p = m.part_index(name).unwrap();
            let facets = m.part_facets(p).flat_map(|f| m.facet(f).to_vec()).collect();
            (name.clone(), facets)
        })
        .collect();
    Mesh::from_parts(2, coords, m.cells().to_vec(), &parts).unwrap()
}

/// The two bodies in one mesh (lower first), parts prefixed `lower_` and `upper_`, cell
/// regions `lower` and `upper`.
fn cylinders(n: usize, r: f64) -> Mesh {
    common::two_bodies(
        &body(n, r, -1.0, R2),
        &body(n, r, 1.0, R1),
        ["lower", "upper"],
    )
}

/// From the points `(x, p)` along a line from the contact's centre: the spacing of the
/// points at the edge of the contact, the edge a_FE (the farthest point with a positive
/// pressure) and the pressure at x = 0.
fn profile(along: &[(f64, f64)]) -> (f64, f64, f64) {
    let a_fe = along
        .iter()
        .filter(|(_, p)| *p > 0.0)
        .map(|(x, _)| *x)
        .fold(0.0, f64::max);
    let peak = along.iter().find(|(x, _)| *x == 0.0).unwrap().1;
    let mut xs: Vec<f64> = along.iter().map(|(x, _)| *x).collect();
    xs.sort_by(f64::total_cmp);
    let h = xs
        .windows(2)
        .find(|w| w[1] >= a_fe)
        .map_or(xs[1] - xs[0], |w| w[1] - w[0]);
    (h, a_fe, peak)
}

/// One level: (h at the contact, a_FE, p_FE(0), total force of the pair, DOFs).
fn level(n: usize, r: f64) -> (f64, f64, f64, f64, usize) {
    let mesh = cylinders(n, r);
    let part = |name: &str| mesh.part_index(name).unwrap();
    let roller = |p: usize| Dirichlet {
        part: p,
        components: [true, false, false],
        value: [0.0; 3],
    };
    let problem = Problem::builder(mesh.clone(), hooke(E2, NU2))
        .materials(vec![hooke(E2, NU2), hooke(E1, NU1)], vec![0, 1])
        .plane(Plane::Strain)
        .dirichlet(roller(part("lower_left")))
        .dirichlet(roller(part("upper_left")))
        .dirichlet(Dirichlet {
            part: part("lower_bottom"),
            components: [false, true, false],
            value: [0.0; 3],
        })
        .traction(Traction {
            part: part("upper_top"),
            value: [0.0, -Q, 0.0],
        })
        .contact(pair(&mesh, None))
        .build()
        .unwrap();
    let s = certified(&problem);
    let along: Vec<(f64, f64)> = s
        .contact
        .iter()
        .map(|c| (mesh.node(c.node as usize)[0], c.pressure))
        .collect();
    let (h, a_fe, peak) = profile(&along);
    let force: f64 = s.contact.iter().map(|c| c.force[1]).sum();
    (h, a_fe, peak, force, s.report.n_dofs)
}

#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "66k DOFs at the finest level: run with --release (CI does)"
)]
fn two_cylinders_half_width_and_peak_pressure_against_hertz() {
    let e_star = 1.0 / ((1.0 - NU1 * NU1) / E1 + (1.0 - NU2 * NU2) / E2);
    let r_star = 1.0 / (1.0 / R1 + 1.0 / R2);
    let force = 2.0 * Q;
    let a = (4.0 * force * r_star / (PI * e_star)).sqrt();
    let p0 = 2.0 * force / (PI * a);
    println!(
        "Hertz: F = {force} N/m, R* = {r_star:.4}, E* = {e_star:.4}, a = {a:.5}, p0 = {p0:.5}"
    );
    println!("n     DOFs    h        a_FE     (a_FE−a)/h   p_FE(0)   p error");
    let mut last = None;
    for (n, r) in [(32, 1.017f64.powi(4)), (64, 1.017f64.powi(2)), (128, 1.017)] {
        let (h, a_fe, peak, f, dofs) = level(n, r);
        println!(
            "{n:<5} {dofs:<7} {h:.5}  {a_fe:.5}  {:+.2}        {peak:.5}   {:+.2} %",
            (a_fe - a) / h,
            100.0 * (peak / p0 - 1.0)
        );
        // The pair passes the whole load: F/2 on the half model.
        assert!((f.abs() - Q).abs() <= 1e-8 * Q, "force {f} vs {Q}");
        last = Some((h, a_fe, peak));
    }
    let (h, a_fe, peak) = last.unwrap();
    assert!(
        (a_fe - a).abs() <= h,
        "half-width {a_fe} vs Hertz {a} (h = {h})"
    );
    assert!((peak / p0 - 1.0).abs() <= 0.05, "peak {peak} vs Hertz {p0}");
}

/// Cattaneo's (Mindlin's in 3D) tangential traction at the distance r ≤ a from the centre:
/// `μp₀ √(1 − r²/a²)` in the slip zone c ≤ r ≤ a, less `(c/a) μp₀ √(1 − r²/c²)` in the stick
/// zone r < c (Johnson, §7.1), with `mu_p0` = μ p₀ (Pa).
fn cattaneo(r: f64, a: f64, c: f64, mu_p0: f64) -> f64 {
    let slip = mu_p0 * (1.0 - r * r / (a * a)).sqrt();
    if r < c {
        slip - (c / a) * mu_p0 * (1.0 - r * r / (c * c)).sqrt()
    } else {
        slip
    }
}

/// The full width `[−1, 1]` of a body from its half `[0, 1]` ([`body`]): the half mirrored
/// about x = 0 (cells reoriented), the nodes on x = 0 shared. Parts `bottom`, `top` (both
/// halves) and `sides` (x = ±1).
fn mirrored(half: &Mesh) -> Mesh {
    let n = half.n_nodes();
    let mut coords = half.coords().to_vec();
    let mut image = vec![0u32; n];
    for v in 0..n {
        let x = half.node(v);
        if x[0] == 0.0 {
            image[v] = v as u32;
        } else {
            image[v] = (coords.len() / 2) as u32;
            coords.extend_from_slice(&[-x[0], x[1]]);
        }
    }
    let mut cells = half.cells().to_vec();
    for c in half.cells().chunks_exact(3) {
        // Mirroring reverses the orientation: swap two vertices.
        cells.extend_from_slice(&[
            image[c[1] as usize],
            image[c[0] as usize],
            image[c[2] as usize],
        ]);
    }
    let facets = |name: &str| -> Vec<u32> {
        let p = half.part_index(name).unwrap();
        let mut out: Vec<u32> = half
            .part_facets(p)
            .flat_map(|f| half.facet(f).to_vec())
            .collect();
        let mirrored: Vec<u32> = half
            .part_facets(p)
            .flat_map(|f| {
                let v = half.facet(f);
                [image[v[1] as usize], image[v[0] as usize]]
            })
            .collect();
        out.extend(mirrored);
        out
    };
    let parts = vec![
        ("bottom".to_string(), facets("bottom")),
        ("top".to_string(), facets("top")),
        ("sides".to_string(), facets("right")),
    ];
    Mesh::from_parts(2, coords, cells, &parts).unwrap()
}

/// Cattaneo–Mindlin (2D): two identical cylinders (R = 20 m, E = 10 Pa, ν = 0.3), pressed
/// by P per unit length, then sheared: the upper one's top and sides moved along x by s
/// (which holds its rotation; its vertical translation stays free, carried by the pair),
/// the lower one's bottom clamped and its sides held along x, Coulomb friction μ = 0.3
/// between them, exact. The radius is large against a (a/R = 0.005): the pair's
/// small-deformation kinematics turns the approach of two curved faces into a spurious slip
/// of relative size (a/R)² (see `docs/model.md`), 9 % of μ p₀ in the traction at a/R = 0.05. With identical materials
/// the normal load makes no slip, so the static (total-slip) law and the incremental one
/// agree, and Cattaneo's solution holds: a central stick zone of half-width
/// `c = a √(1 − Q/(μP))` (Q the tangential force), the traction
/// `q(x) = μ p₀ √(1 − x²/a²)` in the slip zones c ≤ |x| ≤ a and
/// `q(x) = μ p₀ [√(1 − x²/a²) − (c/a) √(1 − x²/c²)]` in the stick zone (Johnson, §7.1).
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "33k DOFs with exact friction: run with --release (CI does)"
)]
fn cattaneo_mindlin_stick_zone_and_traction_of_two_cylinders() {
    let (e, nu, radius, mu) = (10.0, 0.3, 20.0, 0.3);
    let (n, r) = (64, 1.017f64.powi(2));
    let lower = mirrored(&body(n, r, -1.0, radius));
    let upper = mirrored(&body(n, r, 1.0, radius));
    let mesh = common::two_bodies(&lower, &upper, ["lower", "upper"]);
    let part = |name: &str| mesh.part_index(name).unwrap();
    // P = q · 2 m per unit length; Hertz with R* = R/2, E* = E/(2(1 − ν²)).
    let q = 0.0025;
    let force = 2.0 * q;
    let (r_star, e_star) = (radius / 2.0, e / (2.0 * (1.0 - nu * nu)));
    let a = (4.0 * force * r_star / (PI * e_star)).sqrt();
    let p0 = 2.0 * force / (PI * a);
    let shear = 4.0e-4;
    let problem = Problem::builder(mesh.clone(), hooke(e, nu))
        .plane(Plane::Strain)
        .dirichlet(Dirichlet {
            part: part("lower_bottom"),
            components: [true, true, false],
            value: [0.0; 3],
        })
        .dirichlet(Dirichlet {
            part: part("upper_top"),
            components: [true, false, false],
            value: [shear, 0.0, 0.0],
        })
        .dirichlet(Dirichlet {
            part: part("upper_sides"),
            components: [true, false, false],
            value: [shear, 0.0, 0.0],
        })
        .dirichlet(Dirichlet {
            part: part("lower_sides"),
            components: [true, false, false],
            value: [0.0; 3],
        })
        .traction(Traction {
            part: part("upper_top"),
            value: [0.0, -q, 0.0],
        })
        .contact(pair(
            &mesh,
            Some(Friction {
                bound: FrictionBound::Coulomb,
                mu: FrictionCoefficient::Constant { mu },
                potential: FrictionPotential::Norm {
                    treatment: NormTreatment::Exact,
                },
            }),
        ))
        .build()
        .unwrap();
    let s = certified(&problem);
    let x = |c: &hemicontact::solver::certificate::ContactResult| mesh.node(c.node as usize)[0];
    // The tangential force Q: the friction forces of the points (on the upper body).
    let tangential: f64 = s.contact.iter().map(|c| c.force[0]).sum();
    let normal: f64 = s.contact.iter().map(|c| c.force[1]).sum();
    let big_q = tangential.abs();
    // Q is what the upper body's supports apply (its top and sides, each node once).
    let mut held: Vec<u32> = mesh.part_nodes(part("upper_top"));
    held.extend(mesh.part_nodes(part("upper_sides")));
    held.sort_unstable();
    held.dedup();
    let applied: f64 = held.iter().map(|&v| s.reactions[2 * v as usize]).sum();
    assert!(
        (applied.abs() - big_q).abs() <= 1e-8 * big_q,
        "Q = {big_q} vs supports {applied}"
    );
    let ratio = big_q / (mu * force);
    let c = a * (1.0 - ratio).sqrt();
    let in_contact: Vec<_> = s.contact.iter().filter(|c| c.pressure > 0.0).collect();
    let a_fe = in_contact.iter().map(|c| x(c).abs()).fold(0.0, f64::max);
    let stick: Vec<f64> = in_contact
        .iter()
        .filter(|c| c.friction_state == FrictionState::Stick)
        .map(|c| x(c))
        .collect();
    let c_fe = stick.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let h = in_contact
        .iter()
        .map(|c| x(c))
        .filter(|&y| y > c_fe)
        .fold(f64::INFINITY, f64::min)
        - c_fe;
    // The traction profile against Cattaneo's, away from the stick–slip edges (one element).
    let mut worst: f64 = 0.0;
    for c_pt in &in_contact {
        let xi = x(c_pt);
        if (xi.abs() - c).abs() <= 1.5 * h || xi.abs() >= a {
            continue;
        }
        let exact = cattaneo(xi.abs(), a, c, mu * p0);
        let computed = c_pt.friction_traction[0].abs();
        worst = worst.max((computed - exact).abs() / (mu * p0));
    }
    println!(
        "Cattaneo–Mindlin: P = {force} N/m (contact {:.6}), Q = {big_q:.6e} = {ratio:.3} μP; \
         a = {a:.5} (FE {a_fe:.5}), c = {c:.5} (FE {c_fe:.5}, h = {h:.5}); traction error \
         {:.2} % of μ p0 away from the edges; {} points stick, {} slip",
        normal.abs(),
        100.0 * worst,
        stick.len(),
        in_contact.len() - stick.len()
    );
    assert!(
        (normal.abs() - force / 1.0).abs() <= 1e-8 * force,
        "{normal}"
    );
    assert!(
        ratio > 0.2 && ratio < 0.9,
        "Q/μP = {ratio}: choose the shear in between"
    );
    assert!(
        (c_fe - c).abs() <= h,
        "stick half-width {c_fe} vs {c} (h = {h})"
    );
    assert!(worst <= 0.05, "traction error {worst}");
}

/// The quarter box `[0, 1]² × [0, 1]` (`side` = +1, the upper body) or `[0, 1]² × [−1, 0]`
/// (−1, the lower body), n³ cubes graded toward x = y = 0 and toward its contact face
/// z = 0 by `r`, that face moved onto the sphere of radius `radius` through the origin,
/// curving away from the other body, the mapping fading linearly to the far face; parts
/// and regions as [`cylinders`].
///
/// Both bodies are cut alike: the box generator splits each cube into six tetrahedra
/// around its diagonal from its smallest to its largest corner, so a box generated above
/// z = 0 would put such a corner (shared by all six) at the apex, where the symmetry planes
/// meet, and a quarter model meshed so loads the nodes on those planes unevenly (the peak
/// pressure 12 % low, against 3 % high with the apex at a corner shared by two tetrahedra:
/// docs/benchmarks.md). The upper body is the mirror image of a box generated below z = 0.
fn ball(n: usize, r: f64, side: f64, radius: f64) -> Mesh {
    let below = cuboid(&BoxSpec {
        origin: [0.0, 0.0, -1.0],
        size: [1.0; 3],
        n: [n; 3],
        pattern: CutPattern::Uniform,
        progression: [r, r, 1.0 / r],
    })
    .unwrap();
    let m = if side > 0.0 { reflected(&below) } else { below };
    let mut coords = m.coords().to_vec();
    for x in coords.chunks_exact_mut(3) {
        let lift = radius - (radius * radius - x[0] * x[0] - x[1] * x[1]).sqrt();
        x[2] += side * lift * (1.0 - x[2].abs());
    }
    let parts: Vec<(String, Vec<u32>)> = m
        .part_names()
        .iter()
        .map(|name| {
            let p = m.part_index(name).unwrap();
            (
                name.clone(),
                m.part_facets(p).flat_map(|f| m.facet(f).to_vec()).collect(),
            )
        })
        .collect();
    Mesh::from_parts(3, coords, m.cells().to_vec(), &parts).unwrap()
}

/// One 3D level: (h at the contact, a_FE on the axis y = 0, p_FE(0), total force, DOFs).
fn level_3d(n: usize, r: f64, radii: [f64; 2], q: f64) -> (f64, f64, f64, f64, usize) {
    let (b, a) = (ball(n, r, -1.0, radii[1]), ball(n, r, 1.0, radii[0]));
    let mesh = common::two_bodies(&b, &a, ["lower", "upper"]);
    let part = |name: &str| mesh.part_index(name).unwrap();
    let roller = |p: usize, k: usize| {
        let mut components = [false; 3];
        components[k] = true;
        Dirichlet {
            part: p,
            components,
            value: [0.0; 3],
        }
    };
    let lame = |e: f64, nu: f64| {
        Material::elastic(Elasticity::Hooke(Hooke::from_young_poisson(
            e,
            nu,
            3,
            Plane::Strain,
        )))
    };
    let mut builder = Problem::builder(mesh.clone(), lame(E2, NU2))
        .materials(vec![lame(E2, NU2), lame(E1, NU1)], vec![0, 1]);
    for body in ["lower", "upper"] {
        builder = builder
            .dirichlet(roller(part(&format!("{body}_left")), 0))
            .dirichlet(roller(part(&format!("{body}_front")), 1));
    }
    let problem = builder
        .dirichlet(roller(part("lower_bottom"), 2))
        .traction(Traction {
            part: part("upper_top"),
            value: [0.0, 0.0, -q],
        })
        .contact(pair(&mesh, None))
        .build()
        .unwrap();
    let s = certified(&problem);
    // Along the symmetry line y = 0.
    let along: Vec<(f64, f64)> = s
        .contact
        .iter()
        .map(|c| mesh.node(c.node as usize))
        .zip(&s.contact)
        .filter(|(x, _)| x[1] == 0.0)
        .map(|(x, c)| (x[0], c.pressure))
        .collect();
    let (h, a_fe, peak) = profile(&along);
    let force: f64 = s.contact.iter().map(|c| c.force[2]).sum();
    (h, a_fe, peak, force, s.report.n_dofs)
}

/// Hertz between two elastic spheres (3D): radii 5 m (upper) and 10 m (lower), the
/// materials of the cylinders above, F = 4 q on the whole pair, the quarter of each body
/// graded toward the contact point (cells growing by a factor 20 across the body).
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "30k DOFs in 3D: run with --release (CI does)"
)]
fn two_spheres_contact_radius_and_peak_pressure_against_hertz() {
    let radii = [5.0, 10.0];
    let q = 0.000306;
    let e_star = 1.0 / ((1.0 - NU1 * NU1) / E1 + (1.0 - NU2 * NU2) / E2);
    let r_star = 1.0 / (1.0 / radii[0] + 1.0 / radii[1]);
    let force = 4.0 * q;
    let a = (3.0 * force * r_star / (4.0 * e_star)).cbrt();
    let p0 = 3.0 * force / (2.0 * PI * a * a);
    println!("Hertz (spheres): F = {force} N, R* = {r_star:.4}, E* = {e_star:.4}, a = {a:.5}, p0 = {p0:.5}");
    println!("n     DOFs    h        a_FE     (a_FE−a)/h   p_FE(0)   p error");
    let growth: f64 = 20.0;
    let mut last = None;
    for n in [8, 12, 16] {
        let r = growth.powf(1.0 / n as f64);
        let (h, a_fe, peak, f, dofs) = level_3d(n, r, radii, q);
        println!(
            "{n:<5} {dofs:<7} {h:.5}  {a_fe:.5}  {:+.2}        {peak:.5}   {:+.2} %",
            (a_fe - a) / h,
            100.0 * (peak / p0 - 1.0)
        );
        assert!((f.abs() - q).abs() <= 1e-8 * q, "force {f} vs {q}");
        last = Some((h, a_fe, peak));
    }
    // The contact radius within one element and the peak pressure within 5 % of Hertz's.
    let (h, a_fe, peak) = last.unwrap();
    assert!(
        (a_fe - a).abs() <= h,
        "radius {a_fe} vs Hertz {a} (h = {h})"
    );
    assert!((peak / p0 - 1.0).abs() <= 0.05, "peak {peak} vs Hertz {p0}");
}

/// `mesh` (3D) and its mirror image about the plane `x[axis] = 0`, the nodes on that plane
/// shared (cells of the image reoriented). Each part keeps its name and gains its image's
/// facets, except `inner` (the facets on the plane), which is dropped.
fn mirrored_3d(mesh: &Mesh, axis: usize, inner: &str) -> Mesh {
    let n = mesh.n_nodes();
    let mut coords = mesh.coords().to_vec();
    let mut image = vec![0u32; n];
    for (v, im) in image.iter_mut().enumerate() {
        let mut x: [f64; 3] = mesh.node(v).try_into().unwrap();
        if x[axis] == 0.0 {
            *im = v as u32;
        } else {
            *im = (coords.len() / 3) as u32;
            x[axis] = -x[axis];
            coords.extend_from_slice(&x);
        }
    }
    let mut cells = mesh.cells().to_vec();
    for c in mesh.cells().chunks_exact(4) {
        // Mirroring reverses the orientation: swap two vertices.
        cells.extend([c[1], c[0], c[2], c[3]].iter().map(|&v| image[v as usize]));
    }
    let parts: Vec<(String, Vec<u32>)> = mesh
        .part_names()
        .iter()
        .filter(|name| name.as_str() != inner)
        .map(|name| {
            let p = mesh.part_index(name).unwrap();
            let mut facets = Vec::new();
            for f in mesh.part_facets(p) {
                let v = mesh.facet(f);
                facets.extend_from_slice(v);
                facets.extend([v[1], v[0], v[2]].iter().map(|&w| image[w as usize]));
            }
            (name.clone(), facets)
        })
        .collect();
    Mesh::from_parts(3, coords, cells, &parts).unwrap()
}

/// The whole body `[−1, 1]² × [0, 1]` (or `[−1, 0]` along z) from its quarter ([`ball`]).
fn whole_ball(n: usize, r: f64, side: f64, radius: f64) -> Mesh {
    let half = mirrored_3d(&ball(n, r, side, radius), 0, "left");
    mirrored_3d(&half, 1, "front")
}

/// The mirror image of `mesh` about the plane of its last coordinate = 0 (y in 2D, z in
/// 3D), its parts `top` and `bottom` exchanged (cells reoriented).
fn reflected(mesh: &Mesh) -> Mesh {
    let d = mesh.dim();
    let mut coords = mesh.coords().to_vec();
    for x in coords.chunks_exact_mut(d) {
        x[d - 1] = -x[d - 1];
    }
    // Swapping the first two vertices of each cell and facet reverses its orientation.
    let swapped = |v: &[u32]| {
        let mut w = v.to_vec();
        w.swap(0, 1);
        w
    };
    let cells: Vec<u32> = mesh.cells().chunks_exact(d + 1).flat_map(swapped).collect();
    let parts: Vec<(String, Vec<u32>)> = mesh
        .part_names()
        .iter()
        .map(|name| {
            let p = mesh.part_index(name).unwrap();
            let facets = mesh
                .part_facets(p)
                .flat_map(|f| swapped(mesh.facet(f)))
                .collect();
            let renamed = match name.as_str() {
                "top" => "bottom",
                "bottom" => "top",
                other => other,
            };
            (renamed.to_string(), facets)
        })
        .collect();
    Mesh::from_parts(d, coords, cells, &parts).unwrap()
}

/// Cattaneo–Mindlin (3D): two identical spheres (R = 20 m, E = 10 Pa, ν = 0.3) pressed by
/// P, then sheared along x, Coulomb friction μ = 0.3 between them, exact; each body a box
/// `[−1, 1]² × [0, 1]` with its contact face on its sphere, graded towards the contact
/// point. The whole bodies, not halves: on a symmetry plane y = 0 held by rollers, the
/// master facets along it are tilted out of the plane (their centroids lie off it), so the
/// approach of the faces has a component along y that the rollers forbid to undo: those
/// points cannot stick, and their friction spends its bound along y (see
/// docs/model.md). The lower body's bottom is clamped and its sides held along x and y; the
/// upper one's top and sides are moved by (s, 0) along x and y (its vertical translation
/// stays free, carried by the pair), its top loaded by P. With identical materials the normal and
/// tangential problems decouple (Johnson, §7.1): the stick zone is the disc of radius
/// `c = a (1 − Q/(μP))^{1/3}`, the traction along x is `μ p₀ √(1 − r²/a²)` in the slip
/// annulus and `μ p₀ [√(1 − r²/a²) − (c/a) √(1 − r²/c²)]` in the stick disc (Mindlin's
/// approximation, the traction parallel to Q). Checked: Q equals the supports' force,
/// c within one element, the traction along y = 0 within 5 % of μ p₀ away from the
/// stick–slip edge.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "3D with exact friction: run with --release (CI does)"
)]
fn cattaneo_mindlin_stick_zone_and_traction_of_two_spheres() {
    let (e, nu, radius, mu) = (10.0, 0.3, 20.0, 0.3);
    // n = 16 (111k DOFs) in the test; `CM3D_N=12` for the coarser level of
    // docs/benchmarks.md.
    let n: usize = std::env::var("CM3D_N").map_or(16, |v| v.parse().unwrap());
    let r = 20.0f64.powf(1.0 / n as f64);
    // The lower body is the upper one's mirror image, so that the discrete bodies are as
    // identical as the spheres: two differently cut meshes would differ in their discrete
    // Poisson expansion under the normal load, a radial slip between them that the stick
    // zone locks in (an error of 20 % of μ p₀ at n = 8, odd in x).
    let upper = whole_ball(n, r, 1.0, radius);
    let lower = reflected(&upper);
    let mesh = common::two_bodies(&lower, &upper, ["lower", "upper"]);
    let part = |name: &str| mesh.part_index(name).unwrap();
    // a = 0.1 m: P = 4 E* a³/(3 R*), with R* = R/2, E* = E/(2(1 − ν²)), on a top of area
    // 4 m².
    let (r_star, e_star) = (radius / 2.0, e / (2.0 * (1.0 - nu * nu)));
    let force = 4.0 * e_star * 0.1f64.powi(3) / (3.0 * r_star);
    let q = force / 4.0;
    let a = (3.0 * force * r_star / (4.0 * e_star)).cbrt();
    let p0 = 3.0 * force / (2.0 * PI * a * a);
    let shear = 1.8e-4;
    let lame = Material::elastic(Elasticity::Hooke(Hooke::from_young_poisson(
        e,
        nu,
        3,
        Plane::Strain,
    )));
    let along_xy = |value: f64, p: usize| Dirichlet {
        part: p,
        components: [true, true, false],
        value: [value, 0.0, 0.0],
    };
    let problem = Problem::builder(mesh.clone(), lame)
        .dirichlet(Dirichlet {
            part: part("lower_bottom"),
            components: [true; 3],
            value: [0.0; 3],
        })
        .dirichlet(along_xy(0.0, part("lower_right")))
        .dirichlet(along_xy(0.0, part("lower_back")))
        .dirichlet(along_xy(shear, part("upper_top")))
        .dirichlet(along_xy(shear, part("upper_right")))
        .dirichlet(along_xy(shear, part("upper_back")))
        .traction(Traction {
            part: part("upper_top"),
            value: [0.0, 0.0, -q],
        })
        .contact(pair(
            &mesh,
            Some(Friction {
                bound: FrictionBound::Coulomb,
                mu: FrictionCoefficient::Constant { mu },
                potential: FrictionPotential::Norm {
                    treatment: NormTreatment::Exact,
                },
            }),
        ))
        .build()
        .unwrap();
    let start = std::time::Instant::now();
    let s = certified(&problem);
    let seconds = start.elapsed().as_secs_f64();
    let x = |c: &hemicontact::solver::certificate::ContactResult| mesh.node(c.node as usize);
    // Q and P: the points' forces (on the upper body).
    let big_q = s.contact.iter().map(|c| c.force[0]).sum::<f64>().abs();
    let normal = s.contact.iter().map(|c| c.force[2]).sum::<f64>().abs();
    // Q is what the upper body's supports along x apply (its top and sides, each node once).
    let mut held: Vec<u32> = mesh.part_nodes(part("upper_top"));
    held.extend(mesh.part_nodes(part("upper_right")));
    held.extend(mesh.part_nodes(part("upper_back")));
    held.sort_unstable();
    held.dedup();
    let applied: f64 = held
        .iter()
        .map(|&v| s.reactions[3 * v as usize])
        .sum::<f64>();
    assert!(
        (applied.abs() - big_q).abs() <= 1e-8 * big_q,
        "Q = {big_q} vs supports {applied}"
    );
    let ratio = big_q / (mu * force);
    let c = a * (1.0 - ratio).cbrt();
    let in_contact: Vec<_> = s.contact.iter().filter(|c| c.pressure > 0.0).collect();
    let radius_of = |c: &&hemicontact::solver::certificate::ContactResult| x(c)[0].hypot(x(c)[1]);
    let a_fe = in_contact.iter().map(radius_of).fold(0.0, f64::max);
    // Along the symmetry line y = 0.
    let line: Vec<_> = in_contact.iter().filter(|c| x(c)[1] == 0.0).collect();
    let stick: Vec<f64> = line
        .iter()
        .filter(|c| c.friction_state == FrictionState::Stick)
        .map(|c| x(c)[0])
        .collect();
    let c_fe = stick.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let h = line
        .iter()
        .map(|c| x(c)[0].abs())
        .filter(|&y| y > c_fe)
        .fold(f64::INFINITY, f64::min)
        - c_fe;
    // The traction along x against Mindlin's, at every point away from the stick–slip edge
    // (1.5 elements) and inside a.
    let mut worst: f64 = 0.0;
    let mut worst_at = 0.0;
    let mut compared = 0;
    for c_pt in &in_contact {
        let rho = radius_of(c_pt);
        if (rho - c).abs() <= 1.5 * h || rho >= a {
            continue;
        }
        let exact = cattaneo(rho, a, c, mu * p0);
        let computed = c_pt.friction_traction[0].abs();
        let err = (computed - exact).abs() / (mu * p0);
        compared += 1;
        if err > worst {
            worst = err;
            worst_at = rho;
        }
    }
    println!(
        "Cattaneo–Mindlin (spheres, n = {n}, {} DOFs, {seconds:.1} s): P = {force:.6e} N \
         (contact {normal:.6e}), Q = {big_q:.6e} = {ratio:.3} μP; a = {a:.5} (FE {a_fe:.5}), \
         c = {c:.5} (FE {c_fe:.5}, h = {h:.5}); traction error {:.2} % of μ p0 (at r = \
         {worst_at:.4}) at {compared} points away from the edges; {} points on y = 0 stick, \
         {} slip",
        s.report.n_dofs,
        100.0 * worst,
        stick.len(),
        line.len() - stick.len()
    );
    assert!(
        (normal - force).abs() <= 1e-8 * force,
        "{normal} vs {force}"
    );
    assert!(
        ratio > 0.2 && ratio < 0.9,
        "Q/μP = {ratio}: choose the shear in between"
    );
    assert!(
        (c_fe - c).abs() <= h,
        "stick radius {c_fe} vs {c} (h = {h})"
    );
    assert!(compared >= 8, "{compared} points compared");
    assert!(worst <= 0.05, "traction error {worst}");
}
