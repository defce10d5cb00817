//! The direct solver's reuse of an old factorization (`linalg::direct`): on a sequence of
//! Newton matrices it solves every system to the requested residual, and it refactorizes
//! only when that pays. Two sequences make the cost model observable:
//!
//! - matrices that change at every solve by a rank-one term (a contact node's stiffness
//!   going back and forth): a factor of the last matrix would need the same one PCG
//!   iteration as the old one, so the old factor is kept for good;
//! - one changed matrix solved again and again (the active sets settled): a fresh factor
//!   would solve it directly, so the solver refactorizes once the PCG iterations have cost
//!   about a factorization, and solves directly from then on.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use hemicontact::linalg::{DirectSolver, Ordering, SolveRequest, SpdSolver};
use hemicontact::solver::{SolverSettings, System};

mod common;

use common::problem;

/// The elastic Newton matrix of a clamped square of `n × n` squares: its system and values.
fn square(n: usize) -> (hemicontact::problem::Problem, System, Vec<f64>) {
    let p = problem(&format!(
        "[mesh]\nkind = \"rectangle\"\nsize = [1.0, 1.0]\nn = [{n}, {n}]\n\
         [material]\nyoung = 1000.0\npoisson = 0.3\nplane = \"strain\"\n\
         [[dirichlet]]\npart = \"bottom\"\n\
         [[loads.traction]]\npart = \"top\"\nvalue = [10.0, -30.0]\n"
    ));
    let mut system = System::new(&p, &SolverSettings::default()).unwrap();
    let u = vec![0.0; system.dofs.n_dofs()];
    let frozen = hemicontact::solver::Frozen::initial(&system, &p, &u).expect("frozen data");
    let mut eval = hemicontact::solver::Evaluation::new(&system);
    system.evaluate(&p, &u, &frozen, &mut eval, true);
    (p, system, eval.hess)
}

fn residual(system: &System, values: &[f64], x: &[f64], b: &[f64]) -> f64 {
    let mut ax = vec![0.0; x.len()];
    system.pattern.sym_matvec(values, x, &mut ax);
    let r: f64 = ax.iter().zip(b).map(|(a, b)| (b - a).powi(2)).sum();
    let nb: f64 = b.iter().map(|v| v * v).sum();
    (r / nb).sqrt()
}

struct Run {
    solver: DirectSolver,
    factorizations: usize,
    iterations: Vec<usize>,
}

impl Run {
    fn new(p: &hemicontact::problem::Problem, system: &System) -> Run {
        let solver = DirectSolver::new(
            p.mesh(),
            system.dofs.equations(),
            &system.pattern,
            Ordering::NestedDissection,
            faer::Par::Seq,
        )
        .unwrap();
        Run {
            solver,
            factorizations: 0,
            iterations: Vec::new(),
        }
    }

    /// Solves `H x = b` to `eta` and checks the residual independently.
    fn solve(&mut self, system: &System, values: &[f64], b: &[f64], eta: f64) {
        let mut x = vec![0.0; b.len()];
        let request = SolveRequest {
            eta,
            reuse_iterations: 8,
        };
        let stats = self
            .solver
            .solve(&system.pattern, values, b, &mut x, &request)
            .unwrap();
        self.factorizations += usize::from(stats.refactorized);
        self.iterations.push(stats.iterations);
        let r = residual(system, values, &x, b);
        let bound = if stats.iterations == 0 { 1e-10 } else { eta };
        assert!(
            r <= bound,
            "solve {}: residual {r:e} > {bound:e}",
            self.iterations.len()
        );
    }
}

fn right_hand_side(n: usize) -> Vec<f64> {
    let mut rng = common::Rng::new(7);
    (0..n).map(|_| rng.uniform(-1.0, 1.0)).collect()
}

/// A factorization costs `nnz(L) / (12 n)` triangular solves in the solver's model; the
/// test needs a mesh where that allows PCG iterations at all.
fn factor_cost(solver: &DirectSolver, n: usize) -> f64 {
    (solver.nnz_factor() as f64 / (12.0 * n as f64)).max(1.0)
}

#[test]
fn matrices_that_change_at_every_solve_by_a_rank_one_term_keep_the_old_factor() {
    let (p, system, h0) = square(64);
    let n = system.pattern.n();
    let b = right_hand_side(n);
    let slot = system.pattern.diagonal_slot(n / 2);
    let mut run = Run::new(&p, &system);
    assert!(
        factor_cost(&run.solver, n) >= 3.0,
        "mesh too small for PCG reuse"
    );
    run.solve(&system, &h0, &b, 1e-8);
    // A contact node's stiffness going back and forth: each matrix differs from the last.
    for k in 0..40 {
        let mut h = h0.clone();
        h[slot] *= if k % 2 == 0 { 3.0 } else { 2.0 };
        run.solve(&system, &h, &b, 1e-8);
    }
    assert_eq!(run.factorizations, 1, "iterations {:?}", run.iterations);
    assert!(
        run.iterations[1..].iter().all(|&k| k == 1),
        "a rank-one change takes one PCG iteration: {:?}",
        run.iterations
    );
}

#[test]
fn one_changed_matrix_solved_again_and_again_is_refactorized_once_it_pays() {
    let (p, system, h0) = square(64);
    let n = system.pattern.n();
    let b = right_hand_side(n);
    let slot = system.pattern.diagonal_slot(n / 3);
    let mut run = Run::new(&p, &system);
    let cost = factor_cost(&run.solver, n);
    assert!(cost >= 3.0, "mesh too small for PCG reuse");
    run.solve(&system, &h0, &b, 1e-8);
    let mut h1 = h0.clone();
    h1[slot] *= 3.0;
    let solves = 30;
    for _ in 0..solves {
        run.solve(&system, &h1, &b, 1e-8);
    }
    assert_eq!(run.factorizations, 2, "iterations {:?}", run.iterations);
    // The first solve of h1 is the change (one iteration, no rent); each next one costs one
    // iteration of 1.1 solves until their sum reaches the factorization's cost.
    let refactor_at = run.iterations[1..]
        .iter()
        .position(|&k| k == 0)
        .expect("a direct solve after the refactorization");
    let bound = 2 + (cost / 1.1).ceil() as usize;
    assert!(
        refactor_at <= bound,
        "refactorized at solve {refactor_at} of h1, cost model allows {bound}: {:?}",
        run.iterations
    );
    assert!(
        run.iterations[1 + refactor_at..].iter().all(|&k| k == 0),
        "direct solves after the refactorization: {:?}",
        run.iterations
    );
}
