//! The cost of contact between two deformable bodies against a body on a rigid foundation
//! with the same number of DOFs: `two` stacks two blocks `[0, 1] × [0, ½]` and `[0, 1] ×
//! [½, 1]` (n × n/2 cells each, matching interface nodes), the upper one's bottom paired
//! with the lower one's top; `one` is the block `[0, 1]²` cut into n × (n + 1) cells (the
//! same (n + 1)(n + 2) nodes) on a flat rigid foundation. Both: plane strain, E = 1000 Pa,
//! ν = 0.3, Signorini with exact Coulomb friction μ = 0.3 (none with `frictionless`), the
//! top moved by (0.001, −0.01), the bottom (of the lower block) clamped. The two are not
//! the same mechanical problem (an elastic support against a rigid one): the comparison is
//! of the cost per solve at equal DOFs. Prints the DOFs, the solve's wall time, the outer
//! iterations and the Newton steps.
//!
//! ```sh
//! cargo build --release -p hemicontact --example two_body_cost
//! farm-bench -n 5 --vs 'target/release/examples/two_body_cost one 128' -- \
//!     target/release/examples/two_body_cost two 128
//! ```

use hemicontact::contact::{
    ContactBoundary, Friction, FrictionBound, FrictionCoefficient, FrictionPotential, MasterPart,
    NormTreatment, NormalLaw,
};
use hemicontact::material::{Hooke, Material, Plane};
use hemicontact::mesh::generate::{rectangle, CutPattern, Rectangle};
use hemicontact::mesh::Mesh;
use hemicontact::problem::{Dirichlet, Problem};
use hemicontact::solver::{solve, SolverSettings};
use std::time::Instant;

fn block(y0: f64, height: f64, nx: usize, ny: usize) -> hemicontact::Result<Mesh> {
    rectangle(&Rectangle {
        origin: [0.0, y0],
        size: [1.0, height],
        n: [nx, ny],
        pattern: CutPattern::Uniform,
        progression: [1.0, 1.0],
    })
}

/// The facets of part `name` of `m`, their nodes shifted by `offset`.
fn facets(m: &Mesh, name: &str, offset: u32) -> Vec<u32> {
    m.part_index(name)
        .map(|p| {
            m.part_facets(p)
                .flat_map(|f| m.facet(f).iter().map(move |&v| v + offset))
                .collect()
        })
        .unwrap_or_default()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let (case, n, frictional) = match args.as_slice() {
        [_, case, n] if case == "one" || case == "two" => (case.clone(), n.parse::<usize>()?, true),
        [_, case, n, f] if (case == "one" || case == "two") && f == "frictionless" => {
            (case.clone(), n.parse::<usize>()?, false)
        }
        _ => return Err("usage: two_body_cost one|two N [frictionless] (N even)".into()),
    };
    let friction = frictional.then_some(Friction {
        bound: FrictionBound::Coulomb,
        mu: FrictionCoefficient::Constant { mu: 0.3 },
        potential: FrictionPotential::Norm {
            treatment: NormTreatment::Exact,
        },
    });
    let material = Material::elastic(hemicontact::material::Elasticity::Hooke(
        Hooke::from_young_poisson(1000.0, 0.3, 2, Plane::Strain),
    ));
    let clamp = |part: usize, value: [f64; 3]| Dirichlet {
        part,
        components: [true; 3],
        value,
    };
    let moved = [0.001, -0.01, 0.0];
    let problem = if case == "two" {
        let (b, a) = (block(0.0, 0.5, n, n / 2)?, block(0.5, 0.5, n, n / 2)?);
        let offset = b.n_nodes() as u32;
        let mut coords = b.coords().to_vec();
        coords.extend_from_slice(a.coords());
        let mut cells = b.cells().to_vec();
        cells.extend(a.cells().iter().map(|&v| v + offset));
        let parts = vec![
            ("b_bottom".to_string(), facets(&b, "bottom", 0)),
            ("b_top".to_string(), facets(&b, "top", 0)),
            ("a_bottom".to_string(), facets(&a, "bottom", offset)),
            ("a_top".to_string(), facets(&a, "top", offset)),
        ];
        let mesh = Mesh::from_parts(2, coords, cells, &parts)?;
        let part = |name: &str| mesh.part_index(name).unwrap_or(usize::MAX);
        let (bottom, top, slave, master) = (
            part("b_bottom"),
            part("a_top"),
            part("a_bottom"),
            part("b_top"),
        );
        Problem::builder(mesh, material)
            .plane(Plane::Strain)
            .dirichlet(clamp(bottom, [0.0; 3]))
            .dirichlet(clamp(top, moved))
            .contact(ContactBoundary {
                part: slave,
                gap: 0.0,
                obstacle: None,
                against: Some(MasterPart::new(master)),
                normal: NormalLaw::Signorini,
                friction: friction.clone(),
            })
            .build()?
    } else {
        let mesh = block(0.0, 1.0, n, n + 1)?;
        let part = |name: &str| mesh.part_index(name).unwrap_or(usize::MAX);
        let (bottom, top) = (part("bottom"), part("top"));
        Problem::builder(mesh, material)
            .plane(Plane::Strain)
            .dirichlet(clamp(top, moved))
            .contact(ContactBoundary {
                part: bottom,
                gap: 0.0,
                obstacle: None,
                against: None,
                normal: NormalLaw::Signorini,
                friction: friction.clone(),
            })
            .build()?
    };
    let start = Instant::now();
    let s = solve(&problem, &SolverSettings::default())?;
    println!(
        "{case} n = {n}: {} DOFs, {} contact points, solve {:.3} s, {} outer iterations, {} \
         Newton steps, converged {}",
        s.report.n_dofs,
        s.contact.len(),
        start.elapsed().as_secs_f64(),
        s.report.outer.len(),
        s.report.newton.len(),
        s.report.converged
    );
    Ok(())
}
