//! How evenly the cell loop divides among N processes: for each scenario and N, the most
//! cells one process assembles (its owned cells and its ghost layer,
//! `parallel::Subdomain`) over the even share `cells / N`, and all ghost cells over the
//! cells (the assembly work repeated), for the nodes split into contiguous ranges of node
//! numbers and, built with the feature `petsc`, into Scotch's parts of the node graph (what
//! `mpirun -np N` uses). 1 and 0 would be a perfect split.
//!
//! ```sh
//! cargo run --release -p hemicontact --features petsc --example subdomain_load -- scenarios/hertz3d.toml
//! ```

use hemicontact::mesh::Mesh;
use hemicontact::parallel::{Partition, Subdomain};
use hemicontact::scenario::Scenario;

/// The most cells on one process over an even share, and the ghost cells over the cells.
fn load(mesh: &Mesh, partition: &Partition, processes: usize) -> (f64, f64) {
    let mut most = 0usize;
    let mut ghosts = 0usize;
    for rank in 0..processes {
        let sub = Subdomain::new(mesh, partition.clone(), rank);
        most = most.max(sub.cells.len());
        ghosts += sub.cells.len() - sub.owned;
    }
    let cells = mesh.n_cells() as f64;
    (
        most as f64 * processes as f64 / cells,
        ghosts as f64 / cells,
    )
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let files: Vec<String> = std::env::args().skip(1).collect();
    if files.is_empty() {
        return Err("usage: subdomain_load SCENARIO.toml ...".into());
    }
    println!("| scenario | cells | processes | ranges: most / share | ranges: ghosts / cells | Scotch: most / share | Scotch: ghosts / cells |");
    println!("|---|---|---|---|---|---|---|");
    for file in files {
        let problem = Scenario::from_file(std::path::Path::new(&file))?.into_problem()?;
        let mesh = problem.mesh();
        for processes in [2usize, 4, 16, 64] {
            let (most, ghosts) = load(
                mesh,
                &Partition::ranges(mesh.n_nodes(), processes),
                processes,
            );
            #[cfg(feature = "petsc")]
            let scotch = {
                let (ptr, adj) = mesh.node_adjacency();
                let adj: Vec<usize> = adj.iter().map(|&w| w as usize).collect();
                let parts = hemicontact_petsc::partition(&ptr, &adj, processes)?;
                let partition =
                    Partition::from_ranks(parts.iter().map(|&p| p as u32).collect(), processes);
                let (m, g) = load(mesh, &partition, processes);
                format!("{m:.2} | {g:.2}")
            };
            #[cfg(not(feature = "petsc"))]
            let scotch = "(feature petsc) | ".to_string();
            println!(
                "| {file} | {} | {processes} | {most:.2} | {ghosts:.2} | {scotch} |",
                mesh.n_cells()
            );
        }
    }
    Ok(())
}
