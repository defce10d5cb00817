//! How evenly the cell loop divides when the nodes are split into contiguous ranges, as
//! `mpirun -np N` splits them (`Processes::node_range`): for each scenario and number of
//! processes N, the most cells one process assembles (its owned cells and its ghost layer,
//! `parallel::Subdomain`) over the even share `cells / N`, and all ghost cells over the
//! cells (the assembly work repeated). 1 and 0 would be a perfect split.
//!
//! ```sh
//! cargo run --release -p hemicontact --example subdomain_load -- scenarios/hertz3d.toml
//! ```

use hemicontact::parallel::{share, Subdomain};
use hemicontact::scenario::Scenario;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let files: Vec<String> = std::env::args().skip(1).collect();
    if files.is_empty() {
        return Err("usage: subdomain_load SCENARIO.toml ...".into());
    }
    println!("| scenario | cells | processes | most cells on one process / even share | ghost cells / cells |");
    println!("|---|---|---|---|---|");
    for file in files {
        let problem = Scenario::from_file(std::path::Path::new(&file))?.into_problem()?;
        let mesh = problem.mesh();
        let (cells, nodes) = (mesh.n_cells(), mesh.n_nodes());
        for processes in [2usize, 4, 16, 64] {
            let mut most = 0usize;
            let mut ghosts = 0usize;
            for rank in 0..processes {
                let sub = Subdomain::new(mesh, share(nodes, rank, processes));
                most = most.max(sub.cells.len());
                ghosts += sub.cells.len() - sub.owned;
            }
            println!(
                "| {file} | {cells} | {processes} | {:.2} | {:.2} |",
                most as f64 * processes as f64 / cells as f64,
                ghosts as f64 / cells as f64
            );
        }
    }
    Ok(())
}
