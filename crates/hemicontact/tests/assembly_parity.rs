//! Serial/parallel assembly parity: the chunked parallel assembly (per-chunk buffers summed
//! in chunk order) equals the serial cell loop up to the order of floating-point additions,
//! and is bitwise reproducible run to run for a given number of chunks; the assembly of a
//! subdomain (what one of several processes assembles) gives its rows of the whole.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::assembly::global::{Want, Workspace};
use hemicontact::assembly::{BulkAssembler, SystemPattern};
use hemicontact::parallel::{Partition, Subdomain};
use hemicontact::scenario::{builtin, Scenario};

#[test]
fn parallel_assembly_matches_serial() {
    // n = 64: 8192 cells, enough for two chunks of at least 4096 cells.
    let problem = Scenario::from_str(&builtin::paper(64, 1.0e4), "test")
        .unwrap()
        .into_problem()
        .unwrap();
    let dofs = problem.dof_map();
    let pattern = SystemPattern::new(problem.mesh(), &dofs).unwrap();
    let bulk = BulkAssembler::new(problem.mesh(), problem.material());
    // A displacement that activates the locking penalty in part of the body.
    let u: Vec<f64> = (0..2 * problem.mesh().n_nodes())
        .map(|k| {
            let x = problem.mesh().node(k / 2);
            if k % 2 == 0 {
                0.05 * x[0] * x[1]
            } else {
                -0.12 * x[1] + 0.01 * x[0] * x[0]
            }
        })
        .collect();
    let n = u.len();
    let (mut g1, mut h1) = (vec![0.0; n], vec![0.0; pattern.nnz()]);
    let e1 = bulk.assemble(&u, &mut g1, Want::Hessian, &pattern, Some(&mut h1));
    for chunks in [2, 3] {
        let mut ws = Workspace::new(chunks);
        let (mut g2, mut h2) = (vec![0.0; n], vec![0.0; pattern.nnz()]);
        let e2 =
            bulk.assemble_parallel(&u, &mut g2, Want::Hessian, &pattern, Some(&mut h2), &mut ws);
        let gs = g1.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let hs = h1.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!((e1 - e2).abs() <= 1e-13 * e1.abs());
        assert!(g1.iter().zip(&g2).all(|(a, b)| (a - b).abs() <= 1e-14 * gs));
        assert!(h1.iter().zip(&h2).all(|(a, b)| (a - b).abs() <= 1e-14 * hs));
        // Bitwise reproducible for the same number of chunks.
        let (mut g3, mut h3) = (vec![0.0; n], vec![0.0; pattern.nnz()]);
        let e3 =
            bulk.assemble_parallel(&u, &mut g3, Want::Hessian, &pattern, Some(&mut h3), &mut ws);
        assert_eq!(e2.to_bits(), e3.to_bits());
        assert_eq!(g2, g3);
        assert_eq!(h2, h3);
    }
}

/// Assembly by subdomains, as on several processes: for the nodes of each of 3 contiguous
/// ranges, the cells around them (owned, then ghost), assembled on a pattern of those cells
/// alone (whose columns of the range's equations are the whole pattern's), give that
/// range's gradient entries and Hessian rows of the whole assembly (to the order of
/// additions), each cell's energy
/// is counted by exactly one range, and the ranges' energies add up to the whole; with two
/// chunks per range too. In 2D (the paper's mesh) and in 3D (its cube analogue).
#[test]
fn subdomains_give_their_rows_of_the_whole_assembly() {
    let paper3d = std::fs::read_to_string(format!(
        "{}/../../scenarios/paper3d.toml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
    .replace("n = [16, 16, 16]", "n = [12, 12, 12]");
    assert!(paper3d.contains("n = [12, 12, 12]"));
    for text in [builtin::paper(64, 1.0e4), paper3d] {
        let problem = Scenario::from_str(&text, "test")
            .unwrap()
            .into_problem()
            .unwrap();
        let mesh = problem.mesh();
        let d = mesh.dim();
        let dofs = problem.dof_map();
        let pattern = SystemPattern::new(mesh, &dofs).unwrap();
        let bulk = BulkAssembler::new(mesh, problem.material());
        let u: Vec<f64> = (0..d * mesh.n_nodes())
            .map(|k| {
                let x = mesh.node(k / d);
                0.03 * x[0] * x[1] - 0.11 * x[k % d] + 0.01 * x[0] * x[0]
            })
            .collect();
        let n = u.len();
        let (mut g, mut h) = (vec![0.0; n], vec![0.0; pattern.nnz()]);
        let e = bulk.assemble(&u, &mut g, Want::Hessian, &pattern, Some(&mut h));
        let gs = g.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let hs = h.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        // DOF of every equation, to find the rows of the upper-triangular slots.
        let mut dof_of = vec![0usize; pattern.n()];
        for (dof, &eq) in dofs.equations().iter().enumerate() {
            if eq != u32::MAX {
                dof_of[eq as usize] = dof;
            }
        }
        let parts = 3;
        let partition = Partition::ranges(mesh.n_nodes(), parts);
        let mut owner = vec![usize::MAX; mesh.n_cells()];
        let mut energy = 0.0;
        for part in 0..parts {
            let nodes = part * mesh.n_nodes() / parts..(part + 1) * mesh.n_nodes() / parts;
            let sub = Subdomain::new(mesh, partition.clone(), part);
            let rows = d * nodes.start..d * nodes.end;
            // The cells are exactly those with a node in the range, the owned ones those
            // whose lowest node is in it.
            let around: Vec<usize> = (0..mesh.n_cells())
                .filter(|&c| mesh.cell(c).iter().any(|&v| nodes.contains(&(v as usize))))
                .collect();
            let mut listed: Vec<usize> = sub.cells.iter().map(|&c| c as usize).collect();
            listed.sort_unstable();
            assert_eq!(listed, around);
            for &c in &sub.cells[..sub.owned] {
                assert_eq!(owner[c as usize], usize::MAX, "cell {c} owned twice");
                owner[c as usize] = part;
            }
            // The pattern of the subdomain's cells alone: the columns of its equations are
            // those of the whole pattern, and it is smaller.
            let local = SystemPattern::on_cells(mesh, &dofs, Some(&sub.cells)).unwrap();
            assert_eq!(local.n(), pattern.n());
            assert!(local.nnz() < pattern.nnz());
            let column = |p: &SystemPattern, j: usize| {
                p.row_idx()[p.col_ptr()[j]..p.col_ptr()[j + 1]].to_vec()
            };
            for j in 0..pattern.n() {
                if rows.contains(&dof_of[j]) {
                    assert_eq!(column(&local, j), column(&pattern, j), "column {j}");
                }
            }
            for chunks in [1, 2] {
                let mut ws = Workspace::new(chunks);
                ws.subdomain = Some(sub.clone());
                let (mut gp, mut hp) = (vec![0.0; n], vec![0.0; local.nnz()]);
                let ep = bulk.assemble_parallel(
                    &u,
                    &mut gp,
                    Want::Hessian,
                    &local,
                    Some(&mut hp),
                    &mut ws,
                );
                if chunks == 1 {
                    energy += ep;
                }
                for k in rows.clone() {
                    assert!((g[k] - gp[k]).abs() <= 1e-14 * gs, "gradient at DOF {k}");
                }
                // Every entry of a row of the subdomain, found by its (row, column) in the
                // whole pattern.
                let (cp, ri) = (local.col_ptr(), local.row_idx());
                let mut checked = 0;
                for j in 0..local.n() {
                    for s in cp[j]..cp[j + 1] {
                        if rows.contains(&dof_of[ri[s]]) || rows.contains(&dof_of[j]) {
                            let whole = pattern.find(ri[s], j).unwrap();
                            let diff = (h[whole] - hp[s]).abs();
                            assert!(diff <= 1e-14 * hs, "Hessian entry ({}, {j})", ri[s]);
                            checked += 1;
                        }
                    }
                }
                assert!(checked > pattern.nnz() / (2 * parts));
            }
        }
        assert!(owner.iter().all(|&p| p < parts), "a cell owned by no range");
        assert!(
            (energy - e).abs() <= 1e-13 * e.abs(),
            "{energy} against {e}"
        );
    }
}
