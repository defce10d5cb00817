//! Sparse Cholesky by two substructures and a dense Schur complement on their separator
//! (`linalg::substructures`): it solves the same systems as the whole factorization to
//! round-off, in 2D and 3D, with contact and locking terms in the matrix; its result does
//! not depend on the number of threads; it refuses a matrix that is not positive definite
//! even when only the Schur complement shows it; and the automatic layout takes it where
//! the separator is small next to the factorization (2D) and two threads can run it, and
//! not where the separator is large (a cube) or the pool has one thread.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::linalg::{Cholesky, Layout, Ordering};
use hemicontact::problem::Problem;
use hemicontact::solver::{SolverSettings, System};

mod common;

use common::problem;

/// The Newton matrix of `p` at the displacement `u` (upper values on the system pattern).
fn newton_matrix(p: &Problem, u: &[f64]) -> (System, Vec<f64>) {
    let mut system = System::new(p, &SolverSettings::default()).unwrap();
    let frozen = hemicontact::solver::Frozen::initial(&system, p, u).expect("friction data");
    let mut eval = hemicontact::solver::Evaluation::new(&system);
    system.evaluate(p, u, &frozen, &mut eval, true);
    (system, eval.hess)
}

fn factor(p: &Problem, system: &System, layout: Layout, par: faer::Par) -> Cholesky {
    Cholesky::analyze_with(
        p.mesh(),
        system.dofs.equations(),
        &system.pattern,
        Ordering::NestedDissection,
        par,
        layout,
    )
    .unwrap()
}

fn solve(chol: &mut Cholesky, system: &System, values: &[f64], b: &[f64]) -> Vec<f64> {
    chol.factorize(&system.pattern, values).unwrap();
    let mut x = b.to_vec();
    chol.solve_in_place(&mut x);
    x
}

fn norm(a: &[f64]) -> f64 {
    a.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
    norm(&d) / norm(b)
}

/// `‖b − A x‖ / ‖b‖`.
fn residual(system: &System, values: &[f64], x: &[f64], b: &[f64]) -> f64 {
    let mut ax = vec![0.0; x.len()];
    system.pattern.sym_matvec(values, x, &mut ax);
    let r: Vec<f64> = ax.iter().zip(b).map(|(a, b)| b - a).collect();
    norm(&r) / norm(b)
}

/// Reproducible pseudo-random numbers in (−1, 1).
fn vector(n: usize, seed: u64) -> Vec<f64> {
    let mut rng = common::Rng::new(seed);
    (0..n).map(|_| rng.uniform(-1.0, 1.0)).collect()
}

/// The paper's square (nearly locking, normal compliance, slip-dependent friction) on an
/// `n × n` mesh.
fn paper(n: usize) -> Problem {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenarios/paper.toml"
    ))
    .unwrap()
    .replace("n = [128, 128]", &format!("n = [{n}, {n}]"));
    assert!(
        text.contains(&format!("n = [{n}, {n}]")),
        "mesh size not set"
    );
    problem(&text)
}

/// A box `(0,2)×(0,1)×(0,1)` with `n` cells per unit length, clamped at the bottom.
fn box_problem(n: usize) -> Problem {
    problem(&format!(
        "[mesh]\nkind = \"box\"\nsize = [2.0, 1.0, 1.0]\nn = [{}, {n}, {n}]\n\
         [material]\nyoung = 1000.0\npoisson = 0.3\n\
         [[dirichlet]]\npart = \"bottom\"\n\
         [[loads.traction]]\npart = \"top\"\nvalue = [10.0, 5.0, -30.0]\n",
        2 * n
    ))
}

/// A displacement that presses the paper square's sides into contact and locks cells, so
/// that the Newton matrix holds contact, friction and locking terms.
fn pressed(p: &Problem) -> Vec<f64> {
    let mesh = p.mesh();
    let mut u = vec![0.0; 2 * mesh.n_nodes()];
    for v in 0..mesh.n_nodes() {
        let (x, y) = (mesh.coords()[2 * v], mesh.coords()[2 * v + 1]);
        u[2 * v] = 0.3 * (x - 2.0) * y / 4.0;
        u[2 * v + 1] = -0.25 * y;
    }
    u
}

#[test]
fn substructures_solve_the_paper_newton_system_as_the_whole_factorization_does() {
    let p = paper(48);
    let (system, values) = newton_matrix(&p, &pressed(&p));
    let b = vector(system.pattern.n(), 7);
    let mut whole = factor(&p, &system, Layout::Whole, faer::Par::Seq);
    let mut split = factor(&p, &system, Layout::Substructures, faer::Par::Seq);
    assert!(!whole.is_substructured());
    assert!(split.is_substructured());
    let x_whole = solve(&mut whole, &system, &values, &b);
    let x_split = solve(&mut split, &system, &values, &b);
    let (r_whole, r_split) = (
        residual(&system, &values, &x_whole, &b),
        residual(&system, &values, &x_split, &b),
    );
    let diff = rel_diff(&x_split, &x_whole);
    assert!(r_split < 1e-12, "residual {r_split:e} (whole: {r_whole:e})");
    assert!(
        diff < 1e-11,
        "substructures differ from the whole solve by {diff:e}"
    );
    // A second factorization on the same pattern with other values (refactorization).
    let scaled: Vec<f64> = values.iter().map(|v| 2.0 * v).collect();
    let x2 = solve(&mut split, &system, &scaled, &b);
    let half: Vec<f64> = x_whole.iter().map(|x| 0.5 * x).collect();
    let diff2 = rel_diff(&x2, &half);
    assert!(diff2 < 1e-11, "refactorized: {diff2:e}");
}

#[test]
fn substructures_solve_a_3d_system_as_the_whole_factorization_does() {
    let p = box_problem(4);
    let u = vec![0.0; 3 * p.mesh().n_nodes()];
    let (system, values) = newton_matrix(&p, &u);
    let b = vector(system.pattern.n(), 11);
    let mut whole = factor(&p, &system, Layout::Whole, faer::Par::Seq);
    let mut split = factor(&p, &system, Layout::Substructures, faer::Par::Seq);
    assert!(split.is_substructured());
    let x_whole = solve(&mut whole, &system, &values, &b);
    let x_split = solve(&mut split, &system, &values, &b);
    let r = residual(&system, &values, &x_split, &b);
    let diff = rel_diff(&x_split, &x_whole);
    assert!(r < 1e-12, "residual {r:e}");
    assert!(diff < 1e-11, "{diff:e}");
}

#[test]
fn the_substructured_solution_is_the_same_bit_for_bit_on_one_thread_or_two() {
    let p = paper(40);
    let (system, values) = newton_matrix(&p, &pressed(&p));
    let b = vector(system.pattern.n(), 3);
    // The substructures run side by side on rayon's pool; the dense blocks use `par`.
    let (mesh, equations, pattern) = (p.mesh(), system.dofs.equations(), &system.pattern);
    let run = |pool_threads: usize, par: faer::Par| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(pool_threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut chol = Cholesky::analyze_with(
                mesh,
                equations,
                pattern,
                Ordering::NestedDissection,
                par,
                Layout::Substructures,
            )
            .unwrap();
            chol.factorize(pattern, &values).unwrap();
            let mut x = b.clone();
            chol.solve_in_place(&mut x);
            x
        })
    };
    let x1 = run(1, faer::Par::Seq);
    for x2 in [run(2, faer::Par::Seq), run(2, faer::Par::rayon(2))] {
        assert!(x1.iter().zip(&x2).all(|(a, b)| a.to_bits() == b.to_bits()));
    }
}

#[test]
fn a_matrix_that_is_not_positive_definite_is_refused_even_when_only_the_separator_shows_it() {
    let p = paper(32);
    let (system, values) = newton_matrix(&p, &pressed(&p));
    // A separator equation: the middle node of the first bisection's cut lies on the
    // vertical line x = 2 of the square; take the equation of the node nearest (2, 2).
    let mesh = p.mesh();
    let node = (0..mesh.n_nodes())
        .min_by(|&a, &b| {
            let d = |v: usize| {
                (mesh.coords()[2 * v] - 2.0).powi(2) + (mesh.coords()[2 * v + 1] - 2.0).powi(2)
            };
            d(a).total_cmp(&d(b))
        })
        .unwrap();
    let eq = system.dofs.equations()[2 * node] as usize;
    let slot = system.pattern.diagonal_slot(eq);
    // The smallest shift of that diagonal entry at which the whole matrix is no longer
    // positive definite, by bisection on whether the whole factorization succeeds.
    let mut whole = factor(&p, &system, Layout::Whole, faer::Par::Seq);
    let shifted = |sigma: f64| {
        let mut v = values.clone();
        v[slot] -= sigma;
        v
    };
    let (mut lo, mut hi) = (0.0, values[slot]);
    assert!(whole.factorize(&system.pattern, &shifted(hi)).is_err());
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if whole.factorize(&system.pattern, &shifted(mid)).is_ok() {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    // Just past it, each substructure is still positive definite (its Schur complement
    // subtracts one interior's coupling, not both), so only the Schur complement on the
    // separator reveals it.
    let sigma = hi * (1.0 + 1e-6);
    let mut split = factor(&p, &system, Layout::Substructures, faer::Par::Seq);
    let err = split
        .factorize(&system.pattern, &shifted(sigma))
        .unwrap_err();
    assert!(
        err.to_string().contains("Schur complement"),
        "refused, but not by the Schur complement: {err}"
    );
    // Just before it, the substructures factorize and solve.
    let ok = shifted(lo * (1.0 - 1e-6));
    assert!(split.factorize(&system.pattern, &ok).is_ok());
    // A negative interior pivot is refused by its substructure.
    let mut bad = values.clone();
    bad[system.pattern.diagonal_slot(0)] = -1.0;
    assert!(split.factorize(&system.pattern, &bad).is_err());
}

/// Whether the automatic layout of `p`'s Newton matrix is substructured when rayon's pool
/// has `threads` threads.
fn auto_is_substructured(p: &Problem, threads: usize) -> bool {
    let u = vec![0.0; p.mesh().dim() * p.mesh().n_nodes()];
    let (system, _) = newton_matrix(p, &u);
    let (mesh, equations, pattern) = (p.mesh(), system.dofs.equations(), &system.pattern);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        Cholesky::analyze_with(
            mesh,
            equations,
            pattern,
            Ordering::NestedDissection,
            faer::Par::Seq,
            Layout::Auto,
        )
        .unwrap()
        .is_substructured()
    })
}

#[test]
fn the_automatic_layout_takes_substructures_in_2d_on_two_threads_and_the_whole_matrix_otherwise() {
    // 2D: a separator of 2 (n + 1) equations, s³ ≈ 10⁶, against ≈ 10⁸ flops of the halves;
    // on a pool of one thread the substructures would only add work.
    let p = paper(64);
    assert!(auto_is_substructured(&p, 2));
    assert!(!auto_is_substructured(&p, 1));
    // 3D: a cube's separator is a whole face, 3 (n + 1)² equations; its dense Schur
    // complement would cost about as much as the factorization.
    let p = problem(
        "[mesh]\nkind = \"box\"\nsize = [1.0, 1.0, 1.0]\nn = [12, 12, 12]\n\
         [material]\nyoung = 1000.0\npoisson = 0.3\n\
         [[dirichlet]]\npart = \"bottom\"\n",
    );
    assert!(!auto_is_substructured(&p, 2));
    // The AMD ordering has no bisection: always the whole matrix.
    let p = paper(64);
    let (system, _) = newton_matrix(&p, &vec![0.0; 2 * p.mesh().n_nodes()]);
    let amd = Cholesky::analyze_with(
        p.mesh(),
        system.dofs.equations(),
        &system.pattern,
        Ordering::Amd,
        faer::Par::Seq,
        Layout::Auto,
    )
    .unwrap();
    assert!(!amd.is_substructured());
}
