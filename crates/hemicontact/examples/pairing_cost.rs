//! The cost of pairing the slave nodes of a contact pair with the master facets: two boxes
//! `[0, 1]² × [0, ½]` and `[0, 1]² × [½, 1]` (n × n × 2 cubes each, six tetrahedra per
//! cube, the upper one cut n + 1 across so that the interface meshes do not match), the
//! upper one's bottom paired with the lower one's top; prints the slave nodes, the master
//! facets and the wall time of `Problem::contact_nodes` (the pairing of every slave node,
//! which the solver, the certificate and the writers each ask for), the median of 5.
//!
//! ```sh
//! cargo build --release -p hemicontact --example pairing_cost
//! target/release/examples/pairing_cost 64
//! ```

use hemicontact::contact::{ContactBoundary, MasterPart, NormalLaw};
use hemicontact::material::{Elasticity, Hooke, Material, Plane};
use hemicontact::mesh::generate::{cuboid, BoxSpec, CutPattern};
use hemicontact::mesh::Mesh;
use hemicontact::problem::{Dirichlet, Problem};
use std::time::Instant;

fn block(z0: f64, n: usize) -> hemicontact::Result<Mesh> {
    cuboid(&BoxSpec {
        origin: [0.0, 0.0, z0],
        size: [1.0, 1.0, 0.5],
        n: [n, n, 2],
        pattern: CutPattern::Uniform,
        progression: [1.0; 3],
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
    let n: usize = match args.as_slice() {
        [_, n] => n.parse()?,
        _ => return Err("usage: pairing_cost N".into()),
    };
    let (b, a) = (block(0.0, n)?, block(0.5, n + 1)?);
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
    let mesh = Mesh::from_parts(3, coords, cells, &parts)?;
    let part = |name: &str| mesh.part_index(name).unwrap_or(usize::MAX);
    let (bottom, top, slave, master) = (
        part("b_bottom"),
        part("a_top"),
        part("a_bottom"),
        part("b_top"),
    );
    let n_master = mesh.part_facets(master).count();
    let material = Material::elastic(Elasticity::Hooke(Hooke::from_young_poisson(
        1000.0,
        0.3,
        3,
        Plane::Strain,
    )));
    let clamp = |part: usize| Dirichlet {
        part,
        components: [true; 3],
        value: [0.0; 3],
    };
    let problem = Problem::builder(mesh, material)
        .dirichlet(clamp(bottom))
        .dirichlet(clamp(top))
        .contact(ContactBoundary {
            part: slave,
            gap: 0.0,
            obstacle: None,
            against: Some(MasterPart::new(master)),
            normal: NormalLaw::Signorini,
            friction: None,
        })
        .build()?;
    let mut times = Vec::new();
    let mut points = 0;
    for _ in 0..5 {
        let start = Instant::now();
        points = problem.contact_nodes()?.len();
        times.push(start.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    println!(
        "n = {n}: {points} slave points against {n_master} master facets: contact_nodes {:.4} s \
         (median of 5)",
        times[2]
    );
    Ok(())
}
