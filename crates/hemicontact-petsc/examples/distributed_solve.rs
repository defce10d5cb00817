//! A check of the distributed linear algebra, run under `mpirun`: a symmetric positive
//! definite system with 3 DOFs per node on an `n × n × n` grid of nodes (a 7-point
//! Laplacian per component, coupled within each node), distributed by node ranges over the
//! processes, solved by CG + GAMG with the rigid-body modes of the grid, gathered on every
//! process, and compared with the known solution `x` of `b = A x`. Exit code 0 when every
//! process holds the same solution and it agrees with `x` to 1e-8 (relative, maximum
//! norm), and the values each process fetches of other processes' rows (the rows of their
//! first nodes, `KspSystem::ghost_values`) are bitwise those of the gathered solution; 1
//! otherwise.
//!
//! ```sh
//! mpirun -np 3 --oversubscribe target/release/examples/distributed_solve [--n 16] \
//!     [--options "-pc_type hypre"] [--fail-on-rank R]
//! ```
//!
//! `--fail-on-rank R` makes rank R fail alone before the solve: every process must then
//! end (through `World::abort`) instead of waiting for it in a collective operation.

use hemicontact_petsc::{KspSystem, World};

/// The known solution at DOF `k`.
fn exact(k: usize) -> f64 {
    let t = k as f64;
    (0.37 * t).sin() + 0.5 * (0.011 * t).cos()
}

/// The coupling of a node's 3 components (added to the diagonal block 6.5 I; its
/// eigenvalues ±0.14 keep the matrix positive definite).
const COUPLING: [[f64; 3]; 3] = [[0.0, 0.1, 0.0], [0.1, 0.0, 0.1], [0.0, 0.1, 0.0]];

fn main() {
    let world = match World::get() {
        Ok(w) => w,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    };
    let mut n = 16usize;
    let mut options = String::new();
    let mut fail_on = None;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match (arg.as_str(), args.next()) {
            ("--n", Some(v)) => n = v.parse().unwrap_or(n),
            ("--options", Some(v)) => options = v,
            ("--fail-on-rank", Some(v)) => fail_on = v.parse::<usize>().ok(),
            _ => {
                eprintln!("usage: distributed_solve [--n N] [--options OPTS] [--fail-on-rank R]");
                world.abort(2);
            }
        }
    }
    let nodes = n * n * n;
    let (rank, size) = (world.rank(), world.size());
    let (first_node, last_node) = (rank * nodes / size, (rank + 1) * nodes / size);
    if fail_on == Some(rank) {
        eprintln!("error: rank {rank} fails alone (--fail-on-rank)");
        world.abort(1);
    }
    // This process's rows: 3 per node, neighbours in global numbers, sorted.
    let mut row_ptr = vec![0usize];
    let (mut cols, mut values, mut b, mut coords) = (vec![], vec![], vec![], vec![]);
    for node in first_node..last_node {
        let (i, j, k) = (node % n, node / n % n, node / (n * n));
        let mut neighbours = vec![node];
        for (di, dj, dk) in [(1, 0, 0), (0, 1, 0), (0, 0, 1)] {
            let (ii, jj, kk) = (i + di, j + dj, k + dk);
            if ii < n && jj < n && kk < n {
                neighbours.push(ii + n * (jj + n * kk));
            }
            if i >= di && j >= dj && k >= dk {
                neighbours.push((i - di) + n * ((j - dj) + n * (k - dk)));
            }
        }
        neighbours.sort_unstable();
        for c in 0..3 {
            let mut rhs = 0.0;
            for &m in &neighbours {
                for d in 0..3 {
                    let v = if m == node {
                        if c == d {
                            6.5
                        } else {
                            COUPLING[c][d]
                        }
                    } else if c == d {
                        -1.0
                    } else {
                        continue;
                    };
                    cols.push(3 * m + d);
                    values.push(v);
                    rhs += v * exact(3 * m + d);
                }
            }
            row_ptr.push(cols.len());
            b.push(rhs);
            coords.push([i, j, k][c] as f64);
        }
    }
    let total = 3 * nodes;
    // Rows of other processes to fetch after the solve: the 3 rows of each one's first node.
    let ghost_rows: Vec<usize> = (0..size)
        .filter(|&r| r != rank)
        .flat_map(|r| (0..3).map(move |c| 3 * (r * nodes / size) + c))
        .collect();
    let mut ghosts = vec![0.0; ghost_rows.len()];
    let solved =
        KspSystem::new_distributed(total, 3 * first_node, &row_ptr, &cols, &coords, 3, &options)
            .and_then(|mut system| {
                system.set_values(&values)?;
                system.setup()?;
                let mut x = vec![0.0; b.len()];
                system.set_ghost_rows(&ghost_rows)?;
                let outcome = system.solve(&b, &mut x, 1e-12, 1000, true)?;
                system.ghost_values(&mut ghosts)?;
                Ok((outcome, x, system.describe()))
            });
    let (outcome, x, method) = match solved {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error on rank {rank}: {e}");
            world.abort(1);
        }
    };
    let x = match world.all_gather(&x, total) {
        Ok(x) => x,
        Err(e) => {
            eprintln!("error on rank {rank}: {e}");
            world.abort(1);
        }
    };
    let scale = (0..total).map(|k| exact(k).abs()).fold(0.0, f64::max);
    let error = (0..total)
        .map(|k| (x[k] - exact(k)).abs())
        .fold(0.0, f64::max)
        / scale;
    // The same gathered solution on every process: its checksum's spread is zero.
    let checksum: f64 = x
        .iter()
        .enumerate()
        .map(|(k, v)| v * (1.0 + k as f64))
        .sum();
    let mut spread = [checksum, -checksum];
    if let Err(e) = world.max(&mut spread) {
        eprintln!("error on rank {rank}: {e}");
        world.abort(1);
    }
    let same = spread[0] == -spread[1];
    // The fetched rows are the owners' values, bit for bit.
    let fetched = ghost_rows
        .iter()
        .zip(&ghosts)
        .all(|(&r, g)| g.to_bits() == x[r].to_bits());
    let mut all_fetched = [f64::from(u8::from(!fetched))];
    if let Err(e) = world.max(&mut all_fetched) {
        eprintln!("error on rank {rank}: {e}");
        world.abort(1);
    }
    let fetched = all_fetched[0] == 0.0;
    if rank == 0 {
        println!(
            "{size} ranks: {total} DOFs, {method}, {} iterations ({}), max relative error \
             {error:.1e}, the same solution on every rank: {same}, the rows fetched from \
             other ranks are theirs: {fetched}",
            outcome.iterations, outcome.reason_name
        );
    }
    if !(outcome.converged() && error <= 1e-8 && same && fetched) {
        std::process::exit(1);
    }
}
