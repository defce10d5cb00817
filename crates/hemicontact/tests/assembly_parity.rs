//! Serial/parallel assembly parity: the chunked parallel assembly (per-chunk buffers summed
//! in chunk order) equals the serial cell loop up to the order of floating-point additions,
//! and is bitwise reproducible run to run for a given number of chunks.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::assembly::global::{Want, Workspace};
use hemicontact::assembly::{BulkAssembler, SystemPattern};
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
