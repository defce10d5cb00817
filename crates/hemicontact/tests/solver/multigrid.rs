//! The geometric multigrid preconditioner (`linalg::multigrid`): the V-cycle is symmetric
//! and positive, multigrid-preconditioned CG agrees with the direct solve, its iteration
//! counts stay bounded under refinement, and a nonlinear 3D solve with the iterative linear
//! solver reproduces the direct one. Lagged set-ups (new fine operator, old coarse levels)
//! solve changed matrices to the requested residual, and give way to a full set-up when
//! they stop paying or stop converging.

use hemicontact::linalg::{Cholesky, Multigrid};
use hemicontact::parallel::Processes;
use hemicontact::problem::Problem;
use hemicontact::scenario::Scenario;
use hemicontact::solver::{SolverSettings, System};

/// The validated problem and `[solver]` settings of a scenario text.
fn setup(text: &str) -> (Problem, SolverSettings) {
    let scenario = Scenario::from_str(text, "test").unwrap();
    let problem = scenario.into_problem().unwrap();
    (problem, scenario.settings().unwrap())
}

use crate::common::problem;

/// A box `(0,2)×(0,1)×(0,1)` with `n` cells per unit length, clamped at the bottom.
fn box_problem(n: usize) -> Problem {
    problem(&box_problem_text(n))
}

/// The scenario text of [`box_problem`].
fn box_problem_text(n: usize) -> String {
    format!(
        "[mesh]\nkind = \"box\"\nsize = [2.0, 1.0, 1.0]\nn = [{}, {n}, {n}]\n\
         [material]\nyoung = 1000.0\npoisson = 0.3\n\
         [[dirichlet]]\npart = \"bottom\"\n\
         [[loads.traction]]\npart = \"top\"\nvalue = [10.0, 5.0, -30.0]\n",
        2 * n
    )
}

/// A rectangle `(0,3)×(0,1)` clamped at the left, loaded on the right.
fn rectangle_problem(n: usize) -> Problem {
    problem(&format!(
        "[mesh]\nkind = \"rectangle\"\nsize = [3.0, 1.0]\nn = [{}, {n}]\n\
         [material]\nyoung = 1000.0\npoisson = 0.3\n\
         [[dirichlet]]\npart = \"left\"\n\
         [[loads.traction]]\npart = \"right\"\nvalue = [0.0, -20.0]\n",
        3 * n
    ))
}

/// The stiffness matrix (upper values on the system pattern) and the reduced load vector.
fn linear_system(p: &Problem) -> (System, Vec<f64>, Vec<f64>) {
    let mut system = System::new(p, &SolverSettings::default()).unwrap();
    let u = vec![0.0; p.mesh().dim() * p.mesh().n_nodes()];
    let frozen = hemicontact::solver::Frozen::initial(&system, p, &u).expect("friction data");
    let mut eval = hemicontact::solver::Evaluation::new(&system);
    system.evaluate(p, &u, &frozen, &mut eval, true);
    let mut b = vec![0.0; system.pattern.n()];
    system.reduce(&eval.grad, &mut b);
    for v in b.iter_mut() {
        *v = -*v;
    }
    (system, eval.hess, b)
}

fn multigrid(p: &Problem, system: &System, hess: &[f64]) -> Multigrid {
    let mut mg = Multigrid::new(p.mesh(), system.dofs.equations(), &system.pattern);
    mg.update(hess).unwrap();
    mg
}

fn direct(p: &Problem, system: &System, hess: &[f64], b: &[f64]) -> Vec<f64> {
    let mut chol = Cholesky::analyze(
        p.mesh(),
        system.dofs.equations(),
        &system.pattern,
        Default::default(),
        faer::Par::Seq,
    )
    .unwrap();
    chol.factorize(&system.pattern, hess).unwrap();
    let mut x = b.to_vec();
    chol.solve_in_place(&mut x);
    x
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    let d: f64 = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum();
    (d / dot(b, b)).sqrt()
}

/// Deterministic pseudo-random vector.
fn vector(n: usize, seed: u64) -> Vec<f64> {
    let mut s = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (0..n)
        .map(|_| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect()
}

#[test]
fn v_cycle_is_symmetric_and_positive() {
    for p in [box_problem(8), rectangle_problem(24)] {
        let (system, hess, _) = linear_system(&p);
        let mut mg = multigrid(&p, &system, &hess);
        assert!(mg.level_sizes().len() >= 2, "{:?}", mg.level_sizes());
        let n = system.pattern.n();
        let (x, y) = (vector(n, 1), vector(n, 2));
        let (mut mx, mut my) = (vec![0.0; n], vec![0.0; n]);
        mg.apply(&x, &mut mx);
        mg.apply(&y, &mut my);
        let (a, b) = (dot(&y, &mx), dot(&x, &my));
        let scale = (dot(&x, &mx) * dot(&y, &my)).sqrt();
        assert!((a - b).abs() <= 1e-12 * scale, "yᵀMx = {a}, xᵀMy = {b}");
        for seed in 3..8 {
            let v = vector(n, seed);
            let mut mv = vec![0.0; n];
            mg.apply(&v, &mut mv);
            assert!(dot(&v, &mv) > 0.0);
        }
    }
}

#[test]
fn pcg_agrees_with_direct_solve() {
    for p in [box_problem(8), rectangle_problem(32)] {
        let (system, hess, b) = linear_system(&p);
        let mut mg = multigrid(&p, &system, &hess);
        let mut x = vec![0.0; b.len()];
        let out = mg.solve(&b, &mut x, 1e-11, 500).unwrap();
        assert!(out.converged, "{out:?}");
        let e = rel_diff(&x, &direct(&p, &system, &hess, &b));
        assert!(e < 1e-8, "relative difference {e:e} ({out:?})");
    }
}

#[test]
fn iterations_bounded_under_refinement() {
    let mut counts = Vec::new();
    for n in [6, 10, 14] {
        let p = box_problem(n);
        let (system, hess, b) = linear_system(&p);
        let mut mg = multigrid(&p, &system, &hess);
        let mut x = vec![0.0; b.len()];
        let out = mg.solve(&b, &mut x, 1e-8, 500).unwrap();
        assert!(out.converged, "{out:?}");
        counts.push((b.len(), mg.level_sizes(), out.iterations));
    }
    eprintln!("{counts:?}");
    let first = counts[0].2 as f64;
    assert!(counts[2].2 as f64 <= 1.5 * first, "{counts:?}");
}

/// The 3D analogue of the paper example (`scenarios/paper3d.toml`, contact with friction
/// and limited compressibility) at a small resolution: the iterative linear solver gives
/// the direct solver's solution, certified.
#[test]
fn paper3d_iterative_matches_direct() {
    use hemicontact::solver::{solve, LinearSolver};
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/paper3d.toml");
    let scenario = Scenario::from_file(&path)
        .unwrap()
        .with_resolution(8)
        .unwrap();
    let p = scenario.into_problem().unwrap();
    let mut settings = scenario.settings().unwrap();
    settings.linear_solver = LinearSolver::Direct;
    let direct = solve(&p, &settings).unwrap();
    settings.linear_solver = LinearSolver::Iterative;
    let iterative = solve(&p, &settings).unwrap();
    assert!(direct.report.converged, "{}", direct.report.message);
    assert!(iterative.report.converged, "{}", iterative.report.message);
    assert!(!iterative.report.multigrid_levels.is_empty());
    assert_eq!(iterative.report.nnz_factor, 0);
    assert!(iterative.report.newton.iter().any(|s| s.pcg_iterations > 0));
    let e = rel_diff(&iterative.u, &direct.u);
    assert!(e < 1e-7, "relative difference {e:e}");
    // Deterministic: a second iterative solve is bit-identical.
    let again = solve(&p, &settings).unwrap();
    assert_eq!(again.u, iterative.u);
}

/// `[solver] linear_solver` parses in kebab case, and `auto` picks the iterative solver
/// only for large 3D systems.
#[test]
fn linear_solver_setting() {
    use hemicontact::solver::LinearSolver;
    let mut text = box_problem_text(2);
    text.push_str("[solver]\nlinear_solver = \"iterative\"\n");
    let (p, settings) = setup(&text);
    assert_eq!(settings.linear_solver, LinearSolver::Iterative);
    let system = System::new(&p, &settings).unwrap();
    let solver = &system.linear_solver;
    assert_eq!(solver.kind(), LinearSolver::Iterative);
    assert!(solver.nnz_factor() == 0 && !solver.level_sizes().is_empty());
    let (p, settings) = setup(&box_problem_text(2));
    assert_eq!(settings.linear_solver, LinearSolver::Auto);
    let system = System::new(&p, &settings).unwrap();
    let solver = &system.linear_solver;
    assert_eq!(solver.kind(), LinearSolver::Direct);
    assert!(solver.nnz_factor() > 0 && solver.level_sizes().is_empty());
    let big = LinearSolver::AUTO_ITERATIVE_EQUATIONS;
    assert_eq!(
        LinearSolver::Auto.resolve(3, big, &Processes::alone()),
        LinearSolver::Iterative
    );
    assert_eq!(
        LinearSolver::Auto.resolve(3, big - 1, &Processes::alone()),
        LinearSolver::Direct
    );
    assert_eq!(
        LinearSolver::Auto.resolve(2, 10 * big, &Processes::alone()),
        LinearSolver::Direct
    );
    assert_eq!(
        LinearSolver::Direct.resolve(3, 10 * big, &Processes::alone()),
        LinearSolver::Direct
    );
    let bad = format!(
        "{}[solver]\nlinear_solver = \"multigrid\"\n",
        box_problem_text(2)
    );
    assert!(Scenario::from_str(&bad, "test").is_err());
}

/// `λ_max(D⁻¹A)` of the fine operator by dense eigenvalues of `D^{-1/2} A D^{-1/2}`, and
/// `D⁻¹`.
fn jacobi_spectrum_top(a: &hemicontact::linalg::multigrid::Csr) -> (f64, Vec<f64>) {
    let n = a.n_rows();
    let mut inv = vec![0.0f64; n];
    for (i, d) in inv.iter_mut().enumerate() {
        *d = 1.0 / a.row(i).find(|&(j, _)| j == i).unwrap().1;
    }
    let mut m = faer::Mat::<f64>::zeros(n, n);
    for i in 0..n {
        for (j, v) in a.row(i) {
            m[(i, j)] = v * (inv[i] * inv[j]).sqrt();
        }
    }
    let top = m
        .self_adjoint_eigenvalues(faer::Side::Lower)
        .unwrap()
        .into_iter()
        .fold(f64::NEG_INFINITY, f64::max);
    (top, inv)
}

#[test]
fn the_smoother_interval_covers_the_spectrum_on_a_graded_mesh() {
    use hemicontact::linalg::lanczos::{largest_eigenvalue, LanczosWork};
    use hemicontact::linalg::multigrid::{EIGENVALUE_SAFETY, LANCZOS_STEPS};
    // A box graded towards two faces (cells from 0.03 to 0.35 of the side), nearly
    // incompressible: 1 344 equations, small enough for dense eigenvalues.
    let p = problem(
        "[mesh]\nkind = \"box\"\nsize = [1.0, 1.0, 1.0]\nn = [7, 7, 7]\n\
         pattern = \"uniform\"\nprogression = [1.6, 1.0, 1.6]\n\
         [material]\nyoung = 1000.0\npoisson = 0.45\n\
         [[dirichlet]]\npart = \"bottom\"\n",
    );
    let (system, hess, _) = linear_system(&p);
    let mg = multigrid(&p, &system, &hess);
    let a = mg.operator();
    let (exact, inv_diag) = jacobi_spectrum_top(a);
    let estimate =
        largest_eigenvalue(a, &inv_diag, LANCZOS_STEPS, &mut LanczosWork::default()).unwrap();
    // A Ritz value lies below λ_max; with the safety factor the interval covers it.
    assert!(
        estimate <= exact * (1.0 + 1e-12),
        "{estimate} > λ_max = {exact}"
    );
    assert!(
        EIGENVALUE_SAFETY * estimate >= exact,
        "interval top {} below λ_max = {exact}",
        EIGENVALUE_SAFETY * estimate
    );
    // The power iteration it replaces (as many products, same start) falls short by more
    // than the safety factor on this mesh: the case is one where the estimate matters.
    let n = inv_diag.len();
    let mut x: Vec<f64> = (0..n)
        .map(|i| 1.0 + ((i * 7919) % 13) as f64 / 13.0)
        .collect();
    let (mut t, mut power) = (vec![0.0; n], 0.0);
    for _ in 0..LANCZOS_STEPS {
        let norm = x.iter().map(|v| v * v).sum::<f64>().sqrt();
        a.matvec(&x, &mut t);
        power = 0.0;
        for i in 0..n {
            x[i] = inv_diag[i] * t[i] / norm;
            power += x[i] * x[i];
        }
        power = power.sqrt();
    }
    assert!(
        EIGENVALUE_SAFETY * power < exact,
        "power {power}, λ_max {exact}"
    );
}

/// Solves `H x = b` with `solver` to `eta`, checks the residual independently, and returns
/// whether the multigrid operators were set up fully for it.
fn solve_checked(
    solver: &mut hemicontact::linalg::MultigridCg,
    system: &System,
    hess: &[f64],
    b: &[f64],
    eta: f64,
) -> (bool, usize) {
    use hemicontact::linalg::{SolveRequest, SpdSolver};
    let mut x = vec![0.0; b.len()];
    let request = SolveRequest {
        eta,
        reuse_iterations: 8,
    };
    let stats = solver
        .solve(&system.pattern, hess, b, &mut x, &request)
        .unwrap();
    let mut ax = vec![0.0; b.len()];
    system.pattern.sym_matvec(hess, &x, &mut ax);
    let r: Vec<f64> = ax.iter().zip(b).map(|(a, b)| b - a).collect();
    let res = (dot(&r, &r) / dot(b, b)).sqrt();
    assert!(res <= eta, "residual {res:e} > {eta:e}");
    (stats.refactorized, stats.iterations)
}

/// Adds `c` times the cell's own stiffness pattern, all ones (`c 𝟙𝟙ᵀ` on its DOFs), to
/// every `every`-th cell: a stiff term coupling all of a cell's DOFs, as a locking penalty
/// does.
fn stiffen_cells(p: &Problem, system: &System, hess: &mut [f64], every: usize, c: f64) {
    for cell in (0..p.mesh().n_cells()).step_by(every) {
        for &s in system.pattern.cell_slots(cell) {
            if s != u32::MAX {
                hess[s as usize] += c;
            }
        }
    }
}

#[test]
fn lagged_set_ups_solve_changed_matrices_with_fewer_full_set_ups() {
    // Newton matrices that change at some nodes from step to step (a contact stiffness
    // switching on and growing): the fine operator is refilled, the coarse levels kept.
    let p = box_problem(6);
    let (system, h0, b) = linear_system(&p);
    let mut solver =
        hemicontact::linalg::MultigridCg::new(p.mesh(), system.dofs.equations(), &system.pattern);
    let n = system.pattern.n();
    let (full, _) = solve_checked(&mut solver, &system, &h0, &b, 1e-8);
    assert!(full, "the first solve sets up");
    let mut full_set_ups = 0;
    for k in 1..=10 {
        let mut h = h0.clone();
        for eq in (k..n).step_by(41) {
            h[system.pattern.diagonal_slot(eq)] *= 1.0 + 0.3 * k as f64;
        }
        let (full, iterations) = solve_checked(&mut solver, &system, &h, &b, 1e-8);
        assert!(iterations > 0);
        full_set_ups += usize::from(full);
    }
    assert!(
        full_set_ups <= 3,
        "{full_set_ups} full set-ups in 10 changed solves"
    );
}

#[test]
fn a_lagged_v_cycle_far_from_the_matrix_gives_way_to_a_full_set_up() {
    // Stiff terms coupling all DOFs of many cells lift the top of the spectrum of D⁻¹A far
    // above the smoothing interval of the old set-up: the lagged V-cycle cannot converge,
    // and the solver must set up fully, within the same solve or by the next one, and
    // still meet the residual.
    let p = box_problem(6);
    let (system, h0, b) = linear_system(&p);
    let mut solver =
        hemicontact::linalg::MultigridCg::new(p.mesh(), system.dofs.equations(), &system.pattern);
    solve_checked(&mut solver, &system, &h0, &b, 1e-8);
    let scale = h0.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut h1 = h0.clone();
    stiffen_cells(&p, &system, &mut h1, 3, 10.0 * scale);
    let (first, _) = solve_checked(&mut solver, &system, &h1, &b, 1e-8);
    let mut h2 = h1.clone();
    stiffen_cells(&p, &system, &mut h2, 5, 10.0 * scale);
    let (second, _) = solve_checked(&mut solver, &system, &h2, &b, 1e-8);
    assert!(
        first || second,
        "no full set-up for matrices far from the set-up's"
    );
}

#[test]
fn lagged_solves_that_cost_more_iterations_than_a_set_up_end_in_one() {
    // A matrix drifting away from the set-up's (small stiff terms on more and more cells):
    // each lagged solve converges, within its cap, but with iterations beyond a fresh
    // set-up's; once their sum reaches the cost of a set-up, the solver sets up fully again
    // (without the cost count, every solve here would be lagged).
    let p = box_problem(6);
    let (system, h0, b) = linear_system(&p);
    let mut solver =
        hemicontact::linalg::MultigridCg::new(p.mesh(), system.dofs.equations(), &system.pattern);
    let (_, fresh) = solve_checked(&mut solver, &system, &h0, &b, 1e-8);
    let scale = h0.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut h = h0.clone();
    let mut log = Vec::new();
    for k in 1..=12 {
        stiffen_cells(&p, &system, &mut h, 7 + k, 0.005 * scale);
        log.push(solve_checked(&mut solver, &system, &h, &b, 1e-8));
    }
    let full = log.iter().filter(|(f, _)| *f).count();
    let lagged_extra: usize = log
        .iter()
        .filter(|(f, _)| !f)
        .map(|(_, k)| k.saturating_sub(fresh))
        .sum();
    assert!(full >= 1, "never set up again: {log:?} (fresh {fresh})");
    assert!(full < log.len(), "never lagged: {log:?}");
    assert!(
        lagged_extra > 0,
        "lagged solves cost nothing extra: {log:?}"
    );
}
