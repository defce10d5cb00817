//! The choice of the linear solver (`[solver] linear_solver = "auto"`): it is made with the
//! number of free equations (after the Dirichlet elimination), and the memory estimate
//! checked against the memory limit is the one of the solver that the system prepares —
//! also near the threshold, where the number of DOFs `d · n_nodes` is above it and the
//! number of free equations below.

use hemicontact::linalg::LinearSolver;
use hemicontact::parallel::Processes;
use hemicontact::resources::{estimate_box, estimate_box_iterative};
use hemicontact::scenario::Scenario;
use hemicontact::solver::{SolverSettings, System};

/// Cells per axis of the box: (21 · 21 · 23) nodes = 10 143, 30 429 DOFs, of which the
/// clamped bottom face (21 · 21 nodes) fixes 1 323, leaving 29 106 free equations.
const N: [u64; 3] = [20, 20, 22];

/// A box clamped at the bottom and loaded on top, `auto` linear solver.
fn text() -> String {
    format!(
        "[mesh]\nkind = \"box\"\nsize = [1.0, 1.0, 1.1]\nn = {N:?}\n\
         [material]\nyoung = 1000.0\npoisson = 0.3\n\
         [[dirichlet]]\npart = \"bottom\"\n\
         [[loads.traction]]\npart = \"top\"\nvalue = [0.0, 0.0, -30.0]\n"
    )
}

fn scenario(memory_limit: Option<u64>) -> Scenario {
    let mut s = Scenario::from_str(&text(), "near-threshold.toml").unwrap();
    s.memory_limit = memory_limit;
    s
}

#[test]
fn memory_estimate_and_prepared_solver_agree_near_the_threshold() {
    let threshold = LinearSolver::AUTO_ITERATIVE_EQUATIONS;
    let problem = scenario(None).into_problem().unwrap();
    let nodes = problem.mesh().n_nodes();
    let free = problem.dof_map().n_free();
    // The case: DOFs above the threshold, free equations below (counted by hand above).
    assert_eq!(nodes, 21 * 21 * 23);
    assert_eq!(free, 3 * nodes - 3 * 21 * 21);
    assert!(
        3 * nodes >= threshold && free < threshold,
        "{nodes} nodes, {free} free"
    );
    // The system prepares the direct solver: `auto` is direct below the threshold.
    let system = System::new(&problem, &SolverSettings::default()).unwrap();
    assert_eq!(system.linear_solver.kind(), LinearSolver::Direct);
    assert!(system.linear_solver.nnz_factor() > 0);
    drop(system);
    // The direct solver's estimate is the larger one here (it adds the Cholesky factor).
    let direct = estimate_box(N[0], N[1], N[2]);
    let iterative = estimate_box_iterative(N[0], N[1], N[2]);
    assert!(iterative < direct, "{iterative} vs {direct}");
    // A memory limit between the two refuses the problem: the direct solver would run.
    let between = (iterative + direct) / 2;
    let err = match scenario(Some(between)).into_problem() {
        Ok(_) => panic!("accepted, although the direct solver needs more than {between} bytes"),
        Err(e) => e.to_string(),
    };
    assert!(
        err.contains("mesh.n") && err.contains("--ignore-memory-limit"),
        "{err}"
    );
    // A limit that holds the direct solver's estimate and the parallel assembly's work
    // arrays accepts it; one byte less refuses it.
    let buffers = hemicontact::assembly::global::Workspace::buffer_bytes(
        rayon::current_num_threads(),
        problem.mesh().n_cells(),
    );
    assert!(scenario(Some(direct + buffers)).into_problem().is_ok());
    assert!(scenario(Some(direct + buffers - 1)).into_problem().is_err());
}

/// The setting's rule, with the number of free equations: `auto` is iterative exactly from
/// the threshold on in 3D, direct in 2D; explicit choices are kept.
#[test]
fn auto_resolves_by_free_equations() {
    let t = LinearSolver::AUTO_ITERATIVE_EQUATIONS;
    assert_eq!(
        LinearSolver::Auto.resolve(3, t, &Processes::alone()),
        LinearSolver::Iterative
    );
    assert_eq!(
        LinearSolver::Auto.resolve(3, t - 1, &Processes::alone()),
        LinearSolver::Direct
    );
    assert_eq!(
        LinearSolver::Auto.resolve(2, 10 * t, &Processes::alone()),
        LinearSolver::Direct
    );
    assert_eq!(
        LinearSolver::Iterative.resolve(3, 1, &Processes::alone()),
        LinearSolver::Iterative
    );
    // The memory estimate follows the same rule; the bound used before the free equations
    // are known is below the estimate for every count up to its maximum.
    let (nodes, cells) = (21 * 21 * 23, 6 * 20 * 20 * 22);
    let auto =
        |free| LinearSolver::Auto.memory_estimate(3, free, nodes, cells, &Processes::alone());
    let direct = LinearSolver::Direct.memory_estimate(3, 0, nodes, cells, &Processes::alone());
    let iterative =
        LinearSolver::Iterative.memory_estimate(3, 0, nodes, cells, &Processes::alone());
    assert_eq!(auto(t - 1), direct);
    assert_eq!(auto(t), iterative);
    assert_eq!(direct, estimate_box(20, 20, 22));
    assert_eq!(iterative, estimate_box_iterative(20, 20, 22));
    let bound = LinearSolver::Auto.memory_lower_bound(
        3,
        3 * nodes as usize,
        nodes,
        cells,
        &Processes::alone(),
    );
    assert!(bound <= auto(t - 1) && bound <= auto(t));
}

/// A small 3D scenario with the given `[solver]` lines.
fn with_solver(lines: &str) -> String {
    format!(
        "[mesh]\nkind = \"box\"\nsize = [1.0, 1.0, 1.0]\nn = [2, 2, 2]\n\
         [material]\nyoung = 1000.0\npoisson = 0.3\n\
         [[dirichlet]]\npart = \"bottom\"\n\
         [[loads.traction]]\npart = \"top\"\nvalue = [0.0, 0.0, -30.0]\n\
         [solver]\n{lines}\n"
    )
}

/// The first error of reading `text` and resolving its settings.
fn settings_error(text: &str) -> String {
    match Scenario::from_str(text, "petsc.toml").and_then(|s| s.settings()) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// Without the cargo feature `petsc`, `linear_solver = "petsc"` is refused naming the file,
/// the field and how to get the backend.
#[cfg(not(feature = "petsc"))]
#[test]
fn petsc_needs_its_feature() {
    let e = settings_error(&with_solver("linear_solver = \"petsc\""));
    assert!(
        e.contains("petsc.toml") && e.contains("linear_solver") && e.contains("--features petsc"),
        "{e}"
    );
}

/// `[solver.petsc] options` must read as PETSc's command line: `-option [value]` words.
#[test]
fn petsc_options_are_checked() {
    let ok = with_solver("[solver.petsc]\noptions = \"-pc_type hypre -ksp_monitor\"");
    assert!(Scenario::from_str(&ok, "petsc.toml")
        .unwrap()
        .settings()
        .is_ok());
    for bad in ["pc_type hypre", "-pc_type\\u0007hypre"] {
        let e = settings_error(&with_solver(&format!(
            "[solver.petsc]\noptions = \"{bad}\""
        )));
        assert!(e.contains("solver.petsc.options"), "{bad}: {e}");
    }
}
