//! Time of the parallel bulk assembly (energy, gradient and Hessian) against the number of
//! tasks: for each scenario, the median over `REPEAT` passes (default 9) of
//! `BulkAssembler::assemble_parallel` on 1, 2, 4, … tasks up to the threads of rayon's pool
//! (`RAYON_NUM_THREADS`, else one per core), with no lower limit on the cells per task.
//!
//! ```sh
//! cargo run --release -p hemicontact --example assembly_threads -- scenarios/paper3d.toml
//! ```

use hemicontact::assembly::global::{Want, Workspace};
use hemicontact::assembly::{BulkAssembler, SystemPattern};
use hemicontact::scenario::Scenario;
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let files: Vec<String> = std::env::args().skip(1).collect();
    if files.is_empty() {
        return Err("usage: assembly_threads SCENARIO.toml ... (REPEAT=9)".into());
    }
    let repeat: usize = std::env::var("REPEAT")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(9);
    let threads = rayon::current_num_threads();
    println!("| scenario | cells | tasks | median s | speed-up |");
    println!("|---|---|---|---|---|");
    for file in files {
        let problem = Scenario::from_file(std::path::Path::new(&file))?.into_problem()?;
        let mesh = problem.mesh();
        let dofs = problem.dof_map();
        let pattern = SystemPattern::new(mesh, &dofs)?;
        let bulk = BulkAssembler::new(mesh, &problem.materials()[0]);
        let d = mesh.dim();
        // A displacement that strains every cell differently.
        let u: Vec<f64> = (0..d * mesh.n_nodes())
            .map(|k| {
                let x = mesh.node(k / d);
                1e-3 * (x[0] * x[1] - x[k % d] + 0.5 * x[0] * x[0])
            })
            .collect();
        let mut grad = vec![0.0; u.len()];
        let mut hess = vec![0.0; pattern.nnz()];
        let mut one = 0.0;
        let mut tasks = 1;
        while tasks <= threads {
            let mut workspace = Workspace::new(tasks);
            workspace.cells_per_chunk = 1;
            let mut times: Vec<f64> = (0..repeat + 1)
                .map(|_| {
                    let t = Instant::now();
                    bulk.assemble_parallel(
                        &u,
                        &mut grad,
                        Want::Hessian,
                        &pattern,
                        Some(&mut hess),
                        &mut workspace,
                    );
                    t.elapsed().as_secs_f64()
                })
                .skip(1) // the first pass builds the workspace
                .collect();
            times.sort_by(f64::total_cmp);
            let median = times[times.len() / 2];
            if tasks == 1 {
                one = median;
            }
            println!(
                "| {file} | {} | {tasks} | {median:.4} | {:.2} |",
                mesh.n_cells(),
                one / median
            );
            tasks *= 2;
        }
    }
    Ok(())
}
