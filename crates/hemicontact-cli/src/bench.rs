//! `hemicontact bench`: phase timings of a linear elastic solve on the paper's square.

use anyhow::Result;
use hemicontact::assembly::global::Want;
use hemicontact::assembly::{BulkAssembler, SystemPattern};
use hemicontact::linalg::{Cholesky, Ordering};
use hemicontact::scenario::{builtin, Scenario};
use std::time::Instant;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Runs the benchmark for each mesh size in `sizes`, repeating numeric phases `repeat` times.
pub fn run(sizes: &[usize], repeat: usize) -> Result<()> {
    let repeat = repeat.max(1);
    println!(
        "{:>5} {:>9} {:>18} {:>11} {:>8} {:>9} {:>9} {:>9} {:>9} {:>9}",
        "n",
        "DOFs",
        "ordering",
        "nnz(L)",
        "pattern",
        "assembly",
        "symbolic",
        "numeric",
        "solve",
        "asm+num+solve"
    );
    for &n in sizes {
        let scenario = Scenario::from_str(&builtin::paper_elastic(n), "<bench>")?;
        let problem = scenario.into_problem()?;
        let mesh = &problem.mesh;
        let dofs = problem.dof_map();
        let t = Instant::now();
        let pattern = SystemPattern::new(mesh, &dofs)?;
        let t_pattern = t.elapsed().as_secs_f64();
        let bulk = BulkAssembler {
            mesh,
            material: &problem.material,
        };
        let u = problem.prescribed_displacement();
        let mut grad = vec![0.0; u.len()];
        let mut hess = vec![0.0; pattern.nnz()];
        let t_asm = median(
            (0..repeat)
                .map(|_| {
                    let t = Instant::now();
                    bulk.assemble(&u, &mut grad, Want::Hessian, &pattern, Some(&mut hess));
                    t.elapsed().as_secs_f64()
                })
                .collect(),
        );
        let f = problem.external_forces();
        let mut rhs = vec![0.0; pattern.n()];
        for (dof, &eq) in dofs.equations().iter().enumerate() {
            if eq != u32::MAX {
                rhs[eq as usize] = f[dof];
            }
        }
        for ordering in [Ordering::NestedDissection, Ordering::Amd] {
            let t = Instant::now();
            let mut chol = Cholesky::analyze(
                mesh,
                dofs.equations(),
                &pattern,
                ordering,
                faer::Par::rayon(0),
            )?;
            let t_sym = t.elapsed().as_secs_f64();
            let mut t_num = Vec::new();
            let mut t_sol = Vec::new();
            let mut x = rhs.clone();
            for _ in 0..repeat {
                let t = Instant::now();
                chol.factorize(&pattern, &hess)?;
                t_num.push(t.elapsed().as_secs_f64());
                x.copy_from_slice(&rhs);
                let t = Instant::now();
                chol.solve_in_place(&mut x);
                t_sol.push(t.elapsed().as_secs_f64());
            }
            // Check the solve: relative residual of K x = f.
            let mut kx = vec![0.0; x.len()];
            pattern.sym_matvec(&hess, &x, &mut kx);
            let res = kx
                .iter()
                .zip(&rhs)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt()
                / rhs.iter().map(|b| b * b).sum::<f64>().sqrt();
            let (num, sol) = (median(t_num), median(t_sol));
            println!(
                "{:>5} {:>9} {:>18} {:>11} {:>8.3} {:>9.3} {:>9.3} {:>9.3} {:>9.3} {:>9.3}   (residual {:.1e})",
                n,
                dofs.n_dofs(),
                format!("{ordering:?}"),
                chol.nnz_factor(),
                t_pattern,
                t_asm,
                t_sym,
                num,
                sol,
                t_asm + num + sol,
                res
            );
        }
    }
    println!("times in seconds; numeric phases are medians of the repetitions");
    Ok(())
}
