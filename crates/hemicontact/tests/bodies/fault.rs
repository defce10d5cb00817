//! # Verification: a fault with slip weakening between two deformable bodies
//!
//! The paper's slip-dependent friction between two bodies: an upper block sheared over a
//! lower one along the interface (the fault), the friction bound weakening exponentially
//! with the slip r = ‖u_τ‖ (the jump of the tangential displacement across the fault),
//! `μ(r) = (a − b) e^{−βr} + b`, of Tresca type (μ is a shear stress, the fault's strength
//! under a normal stress set elsewhere), Signorini across the fault.
//!
//! 1. **Closed form.** Two blocks `[0, 1] × [0, H/2]` and `[0, 1] × [H/2, H]` (ν = 0, shear
//!    modulus G), the bottom held, the top moved by (s, −δ), the sides loaded by the shear
//!    traction τ of the uniform state: the shear strain is τ/G in both blocks and the fault
//!    slips by r, so `s = r + τ H/G` with `τ = μ(r)` where it slips (r > 0), and it sticks
//!    (r = 0) if `G s/H ≤ μ(0)`. The slip is the root of the scalar equation
//!    `G (s − r)/H = μ(r)`, found here by bisection, independently of the solver. Exact
//!    friction reproduces it at every point to round-off.
//! 2. **Exact and regularized.** The smoothed norm (ε) converges to the exact law, the slip
//!    error proportional to ε (measured order printed).
//! 3. **Uniqueness.** The paper's condition `(μ₀ α_j + c_j L_μ) ‖γ‖² < m_A` with
//!    `L_μ = (a − b) β` holds for a gentle weakening and fails for a steep one; the scalar
//!    equation shows why: when `(a − b) β > G/H` the uniformly sheared fault has three
//!    states at one s (stick, and two slipping ones), the solver finds one of them and
//!    certifies it.
//! 4. **The scenario** `scenarios/fault.toml` (free sides, non-matching meshes): exact and
//!    regularized agree, the uniqueness condition holds as the scenario's comment says, and
//!    the fault slips in its middle and sticks at its ends.
//!
//! `cargo test --test fault -- --nocapture` prints the tables of docs/benchmarks.md.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use hemicontact::contact::{
    ContactBoundary, Friction, FrictionBound, FrictionCoefficient, FrictionPotential, MasterPart,
    NormTreatment, NormalLaw,
};
use hemicontact::material::{Elasticity, Hooke, Material, Plane};
use hemicontact::mesh::generate::{rectangle, CutPattern, Rectangle};
use hemicontact::mesh::Mesh;
use hemicontact::problem::{Dirichlet, Problem, Traction};
use hemicontact::solver::certificate::FrictionState;
use hemicontact::solver::{solve, uniqueness, Solution, SolverSettings};

/// Young's modulus (Pa), with ν = 0: G = E/2.
const E: f64 = 1000.0;
const G: f64 = E / 2.0;
/// The blocks' total height (m).
const H: f64 = 1.0;
/// The normal displacement of the top (m): the fault is pressed by E δ/H = 10 Pa.
const DELTA: f64 = 0.01;
/// Static strength μ(0) = a and residual strength μ(∞) = b of the fault (Pa).
const A: f64 = 6.0;
const B: f64 = 3.0;

fn strength(beta: f64, r: f64) -> f64 {
    (A - B) * (-beta * r).exp() + B
}

fn friction(beta: f64, treatment: NormTreatment) -> Friction {
    Friction {
        bound: FrictionBound::Tresca,
        mu: FrictionCoefficient::Exponential { a: A, b: B, beta },
        potential: FrictionPotential::Norm { treatment },
    }
}

/// The uniform states of the sheared blocks at the top displacement `s`: every `(r, τ)`
/// with `r = 0, τ = G s/H ≤ μ(0)` (stick) or `r > 0, G (s − r)/H = μ(r) = τ` (slip). The
/// slipping roots are bracketed on a fine grid of [0, s] and refined by bisection.
fn uniform_states(s: f64, beta: f64) -> Vec<(f64, f64)> {
    let h = |r: f64| G * (s - r) / H - strength(beta, r);
    let mut states = Vec::new();
    if G * s / H <= A {
        states.push((0.0, G * s / H));
    }
    let n = 100_000;
    for k in 0..n {
        let (mut lo, mut hi) = (s * k as f64 / n as f64, s * (k + 1) as f64 / n as f64);
        if k == 0 {
            lo = f64::MIN_POSITIVE;
        }
        if h(lo) * h(hi) > 0.0 || h(hi) == 0.0 {
            continue;
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if h(lo) * h(mid) <= 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        let r = 0.5 * (lo + hi);
        states.push((r, strength(beta, r)));
    }
    states
}

/// The two blocks in one mesh, `nx` × `ny` squares each, matching along the fault; parts
/// `lower_*` and `upper_*`.
fn blocks(nx: usize, ny: usize) -> Mesh {
    let block = |y0: f64| {
        rectangle(&Rectangle {
            origin: [0.0, y0],
            size: [1.0, H / 2.0],
            n: [nx, ny],
            pattern: CutPattern::Uniform,
            progression: [1.0, 1.0],
        })
        .unwrap()
    };
    common::two_bodies(&block(0.0), &block(H / 2.0), ["lower", "upper"])
}

/// The blocks sheared by `s` with the sides loaded by the uniform state's shear `tau`, the
/// fault's friction `friction`.
fn sheared(s: f64, tau: f64, friction: Friction) -> Problem {
    let mesh = blocks(4, 2);
    let part = |n: &str| mesh.part_index(n).unwrap();
    let mut builder = Problem::builder(
        mesh.clone(),
        Material::elastic(Elasticity::Hooke(Hooke { lambda: 0.0, mu: G })),
    )
    .plane(Plane::Strain)
    .dirichlet(Dirichlet {
        part: part("lower_bottom"),
        components: [true; 3],
        value: [0.0; 3],
    })
    .dirichlet(Dirichlet {
        part: part("upper_top"),
        components: [true; 3],
        value: [s, -DELTA, 0.0],
    })
    .contact(ContactBoundary {
        part: part("upper_bottom"),
        gap: 0.0,
        obstacle: None,
        against: Some(MasterPart::new(part("lower_top"))),
        normal: NormalLaw::Signorini,
        friction: Some(friction),
    });
    // σ_xy = τ on the sides: the traction (0, −τ) on x = 0 and (0, τ) on x = 1.
    for (side, sign) in [("left", -1.0), ("right", 1.0)] {
        for body in ["lower", "upper"] {
            builder = builder.traction(Traction {
                part: part(&format!("{body}_{side}")),
                value: [0.0, sign * tau, 0.0],
            });
        }
    }
    builder.build().unwrap()
}

fn certified(problem: &Problem) -> Solution {
    let s = solve(problem, &SolverSettings::default()).unwrap();
    assert!(s.report.converged, "{}", s.report.message);
    assert!(s.report.certificate.passes(), "{:?}", s.report.certificate);
    s
}

/// The largest error of the slip against `r` (relative to `scale`) and of the friction
/// traction against `tau` (relative to τ), over the fault's points.
fn errors(s: &Solution, r: f64, tau: f64, scale: f64) -> (f64, f64) {
    let mut slip = 0.0f64;
    let mut traction = 0.0f64;
    for c in &s.contact {
        slip = slip.max((c.slip - r).abs() / scale);
        let t = c.friction_traction[0].hypot(c.friction_traction[1]);
        traction = traction.max((t - tau).abs() / tau);
    }
    (slip, traction)
}

#[test]
fn a_uniformly_sheared_fault_slips_by_the_closed_form_of_slip_weakening() {
    let beta = 25.0;
    println!(
        "β = {beta} 1/m, G/H = {} Pa/m, (a − b) β = {} Pa/m",
        G / H,
        (A - B) * beta
    );
    println!(
        "s (m)   state  r exact (m)       r FE error   τ exact (Pa)   τ FE error   top shear error"
    );
    for s in [0.01, 0.015, 0.02, 0.03] {
        let states = uniform_states(s, beta);
        // Gentle weakening: one state.
        assert_eq!(states.len(), 1, "{states:?}");
        let (r, tau) = states[0];
        let problem = sheared(s, tau, friction(beta, NormTreatment::Exact));
        let sol = certified(&problem);
        let (e_slip, e_tau) = errors(&sol, r, tau, s);
        let m = problem.mesh();
        let shear: f64 = m
            .part_nodes(m.part_index("upper_top").unwrap())
            .iter()
            .map(|&v| sol.reactions[2 * v as usize])
            .sum();
        let e_shear = (shear.abs() - tau).abs() / tau;
        let state = if r == 0.0 { "stick" } else { "slip" };
        println!(
            "{s:<7} {state:<6} {r:.12e}  {e_slip:.1e}      {tau:.10}   {e_tau:.1e}      {e_shear:.1e}"
        );
        for c in &sol.contact {
            let expected = if r == 0.0 {
                FrictionState::Stick
            } else {
                FrictionState::Slip
            };
            assert_eq!(c.friction_state, expected, "node {}", c.node);
        }
        assert!(e_slip < 1e-9, "slip error {e_slip:e} of s");
        assert!(e_tau < 1e-9, "traction error {e_tau:e}");
        assert!(e_shear < 1e-9, "shear force error {e_shear:e}");
    }
}

/// The order of `errors` between consecutive parameters `params`.
fn orders(params: &[f64], errors: &[f64]) -> Vec<f64> {
    params
        .windows(2)
        .zip(errors.windows(2))
        .map(|(p, e)| (e[0] / e[1]).ln() / (p[0] / p[1]).ln())
        .collect()
}

#[test]
fn the_regularized_laws_converge_to_the_exact_one() {
    let beta = 25.0;
    // The smoothed norm (the default, ε relative to each point's slip scale) and the
    // paper's regularized potential √(r² + ρ²) − ρ (ρ in m), at a sticking state
    // (s = 0.01) and a slipping one (s = 0.02).
    let smoothed = |e: f64| FrictionPotential::Norm {
        treatment: NormTreatment::Smoothed { regularization: e },
    };
    let regularized = |rho: f64| FrictionPotential::Regularized { rho };
    let eps = [1e-3, 1e-4, 1e-5, 1e-6];
    let rhos = [1e-4, 1e-5, 1e-6, 1e-7];
    let mut measured = Vec::new();
    for (name, s, params, potential) in [
        (
            "smoothed norm, stick",
            0.01,
            eps,
            &smoothed as &dyn Fn(f64) -> FrictionPotential,
        ),
        ("smoothed norm, slip", 0.02, eps, &smoothed),
        ("regularized (19), stick", 0.01, rhos, &regularized),
        ("regularized (19), slip", 0.02, rhos, &regularized),
    ] {
        let (r, tau) = uniform_states(s, beta)[0];
        let mut slips = Vec::new();
        let mut tractions = Vec::new();
        for &p in &params {
            let fr = Friction {
                potential: potential(p),
                ..friction(beta, NormTreatment::Exact)
            };
            // The certificate checks the exact law, which a regularized solution misses by
            // its regularization: only its equilibrium is required here.
            let settings = SolverSettings {
                certificate_tolerance: 0.5,
                ..SolverSettings::default()
            };
            let sol = solve(&sheared(s, tau, fr), &settings).unwrap();
            assert!(sol.report.converged, "{}", sol.report.message);
            let equilibrium = sol.report.certificate.equilibrium;
            assert!(equilibrium < 1e-9, "{name}: equilibrium {equilibrium:e}");
            // The slip's error relative to s (the exact slip is 0 at a sticking state).
            let (e_slip, e_tau) = errors(&sol, r, tau, s);
            slips.push(e_slip);
            tractions.push(e_tau);
        }
        println!(
            "{name} (s = {s} m, r = {r:.6e} m, τ = {tau:.6} Pa): errors of the slip (of s), of τ"
        );
        let o_slip = orders(&params, &slips);
        let o_tau = orders(&params, &tractions);
        for (k, p) in params.iter().enumerate() {
            let o = |v: &[f64]| {
                if k == 0 {
                    "    ".to_string()
                } else {
                    format!("{:.2}", v[k - 1])
                }
            };
            println!(
                "  {p:.0e}   slip {:.2e} (order {})   traction {:.2e} (order {})",
                slips[k],
                o(&o_slip),
                tractions[k],
                o(&o_tau)
            );
        }
        measured.push((name, params, slips, tractions, o_slip, o_tau));
    }
    let first_order = |o: &f64| (0.95..1.05).contains(o);
    for (name, params, slips, tractions, o_slip, o_tau) in measured {
        match name {
            // A sticking point slips elastically by ε F/k: first order in ε, and below ε.
            "smoothed norm, stick" => {
                assert!(o_slip.iter().chain(&o_tau).all(first_order), "{name}");
                for k in 0..params.len() {
                    assert!(slips[k] <= params[k] && tractions[k] <= params[k], "{name}");
                }
            }
            // A slipping point carries the bound exactly: the smoothed norm changes nothing.
            "smoothed norm, slip" => {
                assert!(slips.iter().chain(&tractions).all(|e| *e < 1e-9), "{name}");
            }
            // √(r² + ρ²) − ρ: stiffness ~ 1/ρ at stick (first order) …
            "regularized (19), stick" => {
                assert!(o_slip.iter().chain(&o_tau).all(first_order), "{name}");
            }
            // … and the traction μ r/√(r² + ρ²) ≈ μ (1 − ρ²/(2r²)) when slipping.
            _ => {
                let r = uniform_states(0.02, beta)[0].0;
                assert!(
                    o_slip.iter().chain(&o_tau).all(|o| (1.9..2.1).contains(o)),
                    "{name}"
                );
                for k in 0..params.len() {
                    let bound = (params[k] / r).powi(2);
                    assert!(slips[k] <= bound && tractions[k] <= bound, "{name}");
                }
            }
        }
    }
}

#[test]
fn a_steep_weakening_fails_the_uniqueness_condition_and_has_several_states() {
    // Gentle: (a − b) β = 75 Pa/m below G/H = 500 Pa/m, one state at every s. Steep:
    // 3000 Pa/m, and at s = 0.011 m the fault may stick (τ = 5.5 Pa < μ(0)) or slip at
    // either of two slips.
    let gentle = uniform_states(0.011, 25.0);
    let steep = uniform_states(0.011, 1000.0);
    println!("s = 0.011 m: states (r m, τ Pa) with β = 25: {gentle:?}");
    println!("                              with β = 1000: {steep:?}");
    assert_eq!(gentle.len(), 1);
    assert_eq!(steep.len(), 3);
    assert_eq!(steep[0].0, 0.0);
    let settings = SolverSettings::default();
    for (beta, holds) in [(25.0, true), (1000.0, false)] {
        let (_, tau) = uniform_states(0.011, beta)[0];
        let problem = sheared(0.011, tau, friction(beta, NormTreatment::Exact));
        let u = uniqueness::evaluate(&problem, &settings);
        println!(
            "β = {beta}: L_μ = {} Pa/m, ‖γ‖ = {:.6}, (μ₀ α_j + c_j L_μ) ‖γ‖² = {:.1} Pa against m_A = {} Pa: {}",
            u.l_mu,
            u.trace_constant.unwrap(),
            u.lhs,
            u.m_a,
            if u.holds { "holds" } else { "fails" }
        );
        assert!(u.applies, "{:?}", u.note);
        assert_eq!(u.l_mu, (A - B) * beta);
        assert_eq!(u.holds, holds, "{u:?}");
    }
    // Two solutions of one problem. Loaded by the stick state's side traction, the fault
    // with a constant strength μ(0) sticks (unique: no weakening); that state is also a
    // solution with the steep weakening, since μ = μ(0) at zero slip. The solver, given the
    // weakening, finds another, slipping, state, also certified.
    let (_, tau) = steep[0];
    let constant = Friction {
        mu: FrictionCoefficient::Constant { mu: A },
        ..friction(1000.0, NormTreatment::Exact)
    };
    let stuck = certified(&sheared(0.011, tau, constant));
    let weakened = certified(&sheared(0.011, tau, friction(1000.0, NormTreatment::Exact)));
    let range = |s: &Solution| {
        s.contact.iter().fold((f64::MAX, f64::MIN), |(a, b), c| {
            (a.min(c.slip), b.max(c.slip))
        })
    };
    let (stuck_lo, stuck_hi) = range(&stuck);
    let (lo, hi) = range(&weakened);
    println!("stick data (τ = {tau} Pa): constant strength slips in [{stuck_lo:.1e}, {stuck_hi:.1e}] m (the stick state);");
    println!(
        "  with the steep weakening the solver finds slips in [{lo:.6e}, {hi:.6e}] m, certified"
    );
    assert!(stuck_hi < 1e-12 * 0.011, "{stuck_hi}");
    assert!(lo > 1e-3, "the solver found the stick state too: {lo}");
    // Loaded by the stable slipping state's traction, the solver finds that state.
    let (r, tau) = steep[2];
    let slipping = certified(&sheared(0.011, tau, friction(1000.0, NormTreatment::Exact)));
    let (e_slip, e_tau) = errors(&slipping, r, tau, 0.011);
    println!(
        "slipping state r = {r:.9e} m, τ = {tau:.9} Pa: errors {e_slip:.1e} (of s), {e_tau:.1e}"
    );
    assert!(e_slip < 1e-9 && e_tau < 1e-9, "{e_slip:e} {e_tau:e}");
}

#[test]
fn the_fault_scenario_slips_in_its_middle_exact_and_regularized_alike() {
    let text = std::fs::read_to_string(format!(
        "{}/../../scenarios/fault.toml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
    // Paths relative to the scenario's folder.
    .replace(
        "meshes/fault.msh",
        &format!(
            "{}/../../scenarios/meshes/fault.msh",
            env!("CARGO_MANIFEST_DIR")
        ),
    );
    let (problem, settings) = common::setup(&text);
    let exact = solve(&problem, &settings).unwrap();
    assert!(exact.report.converged, "{}", exact.report.message);
    assert!(exact.report.certificate.passes());
    let (regularized_problem, _) = common::setup(&text.replace("exact = true", ""));
    let regularized = solve(&regularized_problem, &settings).unwrap();
    assert!(
        regularized.report.converged,
        "{}",
        regularized.report.message
    );
    assert!(regularized.report.certificate.passes());
    let mesh = problem.mesh();
    let max_slip = exact.contact.iter().map(|c| c.slip).fold(0.0, f64::max);
    let mut difference = 0.0f64;
    let mut stick = Vec::new();
    for (e, r) in exact.contact.iter().zip(&regularized.contact) {
        assert_eq!(e.node, r.node);
        difference = difference.max((e.slip - r.slip).abs() / max_slip);
        if e.friction_state == FrictionState::Stick {
            stick.push(mesh.node(e.node as usize)[0]);
        }
    }
    let u = uniqueness::evaluate(&problem, &settings);
    println!(
        "fault.toml: {} points, {} sticking at x = {stick:.3?} m, largest slip {max_slip:.6e} m;",
        exact.contact.len(),
        stick.len()
    );
    println!("  exact and regularized (ε = 1e-8) slips differ by {difference:.1e} of the largest");
    println!(
        "  uniqueness: L_μ = {} Pa/m, ‖γ‖ = {:.6}, lhs {:.1} Pa against m_A = {} Pa: {}",
        u.l_mu,
        u.trace_constant.unwrap(),
        u.lhs,
        u.m_a,
        if u.holds { "holds" } else { "fails" }
    );
    assert!(difference < 1e-6, "{difference:e}");
    // The fault's ends stick (the shear stress vanishes at the free sides), its middle
    // slips.
    assert!(!stick.is_empty());
    assert!(
        stick.iter().all(|&x| !(0.5..=3.5).contains(&x)),
        "{stick:?}"
    );
    assert!(u.applies && u.holds, "{u:?}");
    // A weakening ten times steeper fails the condition.
    let (steep, _) = common::setup(&text.replace("beta = 25.0", "beta = 250.0"));
    let u = uniqueness::evaluate(&steep, &settings);
    println!(
        "  β = 250 1/m: lhs {:.1} Pa against m_A = {} Pa: fails",
        u.lhs, u.m_a
    );
    assert!(u.applies && !u.holds, "{u:?}");
}
