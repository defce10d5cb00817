//! `hemicontact bench`: phase timings of a linear elastic solve on the paper's square.

use anyhow::Result;
use hemicontact::assembly::global::Want;
use hemicontact::assembly::{BulkAssembler, SystemPattern};
use hemicontact::linalg::{Cholesky, Layout, Ordering};
use hemicontact::scenario::builtin;
use std::time::Instant;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Runs the benchmark for each mesh size in `sizes`, repeating numeric phases `repeat` times.
pub fn run(ctx: &crate::RunContext, sizes: &[usize], repeat: usize, threads: usize) -> Result<()> {
    let c = &ctx.console;
    let repeat = repeat.max(1);
    crate::say!(
        c,
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
        let scenario = ctx.parse_scenario(&builtin::paper_elastic(n), "<bench>")?;
        let problem = scenario.into_problem()?;
        c.phase(format_args!(
            "n = {n}: timing the phases of a linear solve ({}), {repeat} repetitions",
            crate::solve::problem_size(&problem)
        ));
        let mesh = problem.mesh();
        let dofs = problem.dof_map();
        let t = Instant::now();
        let pattern = SystemPattern::new(mesh, &dofs)?;
        let t_pattern = t.elapsed().as_secs_f64();
        let bulk = BulkAssembler::new(mesh, &problem.materials()[0]);
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
        for (ordering, layout) in [
            (Ordering::NestedDissection, Layout::Auto),
            (Ordering::NestedDissection, Layout::Whole),
            (Ordering::Amd, Layout::Whole),
        ] {
            let t = Instant::now();
            let mut chol = Cholesky::analyze_with(
                mesh,
                dofs.equations(),
                &pattern,
                ordering,
                hemicontact::solver::parallelism(threads),
                layout,
            )?;
            let name = match (ordering, chol.is_substructured()) {
                (Ordering::NestedDissection, true) => "ND substructures",
                (Ordering::NestedDissection, false) => "ND whole",
                (Ordering::Amd, _) => "AMD whole",
            };
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
            crate::say!(
                c,
                "{:>5} {:>9} {:>18} {:>11} {:>8.3} {:>9.3} {:>9.3} {:>9.3} {:>9.3} {:>9.3}   (residual {:.1e})",
                n,
                dofs.n_dofs(),
                name,
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
    crate::say!(
        c,
        "times in seconds; numeric phases are medians of the repetitions"
    );
    Ok(())
}

/// Peak resident memory of this process so far (MiB), from /proc/self/status (Linux).
fn peak_memory_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

/// The nonlinear paper solve (C_κ = 10 000, or the scenario `file` refined to n) against one
/// linear elastic solve on the same mesh, measured in the same run: medians of `repeat`
/// end-to-end solves each.
pub fn run_paper(
    ctx: &crate::RunContext,
    sizes: &[usize],
    repeat: usize,
    file: Option<&std::path::Path>,
) -> Result<()> {
    let c = &ctx.console;
    let repeat = repeat.max(1);
    let scenario = match file {
        Some(f) => Some(hemicontact::scenario::Scenario::from_file(f)?.on(ctx.processes)),
        None => None,
    };
    if let Some(f) = file {
        crate::say!(c, "scenario {}", f.display());
    }
    crate::say!(
        c,
        "{:>5} {:>9} {:>10} {:>10} {:>7} {:>6} {:>7} {:>8} {:>6} {:>10} {:>10}",
        "n",
        "DOFs",
        "linear s",
        "paper s",
        "ratio",
        "outer",
        "Newton",
        "factor.",
        "PCG",
        "solve s",
        "peak MiB"
    );
    for &n in sizes {
        let case = match &scenario {
            Some(s) => s.with_resolution(n)?,
            None => ctx.parse_scenario(&builtin::paper(n, 1.0e4), "<bench>")?,
        };
        let (paper, settings) = (case.into_problem()?, case.settings()?);
        // The linear elastic reference: the same mesh, material, supports and loads, without
        // contact and locking.
        let linear = paper
            .to_builder()
            .without_contact()
            .material(hemicontact::material::Material::elastic(
                paper.materials()[0].elasticity,
            ))
            .build()?;
        let mut t_lin = Vec::new();
        let mut t_pap = Vec::new();
        let mut t_solve = Vec::new();
        let mut last = None;
        c.phase(format_args!(
            "n = {n}: {repeat} linear and {repeat} nonlinear solves ({})",
            crate::solve::problem_size(&paper)
        ));
        let progress = c.progress(&format!("n = {n}:"));
        let stop = std::sync::atomic::AtomicBool::new(false);
        for k in 0..repeat {
            progress.set_what(&format!("n = {n}, repetition {}/{repeat}, linear:", k + 1));
            let t = Instant::now();
            let s = hemicontact::solver::solve_observed(
                &linear,
                &settings,
                linear.initial_displacement(),
                &stop,
                &|p| progress.observe(p),
            )?;
            t_lin.push(t.elapsed().as_secs_f64());
            anyhow::ensure!(s.report.converged, "linear solve did not converge");
            progress.set_what(&format!(
                "n = {n}, repetition {}/{repeat}, nonlinear:",
                k + 1
            ));
            let t = Instant::now();
            let s = hemicontact::solver::solve_observed(
                &paper,
                &settings,
                paper.initial_displacement(),
                &stop,
                &|p| progress.observe(p),
            )?;
            t_pap.push(t.elapsed().as_secs_f64());
            anyhow::ensure!(
                s.report.converged,
                "paper solve did not converge: {}",
                s.report.message
            );
            let tm = &s.report.timings;
            t_solve.push(tm.total - tm.pattern - tm.symbolic);
            if repeat > 1 {
                progress.phase(format_args!(
                    "n = {n}, repetition {}/{repeat}: linear {} s, nonlinear {} s ({} outer / {} \
                     Newton)",
                    k + 1,
                    crate::console::significant_seconds(t_lin[k]),
                    crate::console::significant_seconds(t_pap[k]),
                    s.report.outer.len(),
                    s.report.newton.len()
                ));
            }
            last = Some(s);
        }
        progress.finish();
        let s = last.ok_or_else(|| anyhow::anyhow!("no run"))?;
        let (lin, pap) = (median(t_lin), median(t_pap));
        crate::say!(
            c,
            "{:>5} {:>9} {:>10.3} {:>10.3} {:>7.2} {:>6} {:>7} {:>8} {:>6} {:>10.3} {:>10.0}",
            n,
            s.report.n_dofs,
            lin,
            pap,
            pap / lin,
            s.report.outer.len(),
            s.report.newton.len(),
            s.report.timings.n_factorizations,
            s.report
                .newton
                .iter()
                .map(|step| step.pcg_iterations)
                .sum::<usize>(),
            median(t_solve),
            peak_memory_mib().unwrap_or(f64::NAN)
        );
    }
    crate::say!(
        c,
        "end-to-end seconds (setup included), medians of {repeat}; 'solve s' excludes the pattern \
         and symbolic analysis; PCG: conjugate-gradient iterations over all Newton steps; ratio \
         = paper / linear elastic on the same mesh; peak = process peak resident memory so far"
    );
    Ok(())
}
