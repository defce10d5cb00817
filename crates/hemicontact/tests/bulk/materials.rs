//! # Verification: bodies of several materials
//!
//! A body made of parts of different materials (`[[material]]` tables, one per cell region
//! of the mesh) is assembled cell by cell with each cell's own law. P1 elements on a mesh
//! whose cells do not cross the interfaces contain every displacement that is affine in each
//! part and continuous across the interfaces, so such exact solutions are reproduced to
//! round-off:
//!
//! 1. **Bimaterial bar in tension** (2D, ν = 0, plane strain): two halves of moduli E₁ and
//!    E₂ in series, pulled by a traction σ: uniform stress σ, and the end moves by
//!    `σ (L₁/E₁ + L₂/E₂)`. The summary's per-material strain energies are `σ² A_i / (2E_i)`.
//! 2. **Layered block under pressure** (3D, confined compression): two layers of P-wave
//!    moduli `M_i = λ_i + 2G_i` stacked along z, on rollers, pressed by p on top:
//!    `σ_zz = −p` in every cell, `σ_xx = σ_yy = λ_i ε_zz,i` with `ε_zz,i = −p/M_i`, and the
//!    top settles by `p (h₁/M₁ + h₂/M₂)`.
//! 3. **Interface patch test** (2D and 3D): the piecewise-affine field whose strain jumps by
//!    `sym(a ⊗ n)` across a plane interface of normal n, with `a` chosen so that the
//!    traction `σ n` is continuous, is in equilibrium: the assembled internal forces vanish
//!    at every node not on the outer boundary, interface nodes included. The same field with
//!    the wrong jump (a = 0) leaves forces at the interface nodes, so the test can fail.
//! 4. **A layered block on a rigid foundation** (Signorini, frictionless): the contact
//!    pressure under the soft layer is the applied pressure at every point, so the contact
//!    points take their stiffness from their own material.
//! 5. **What the solve takes from all materials:** the stress scale is the stiffest
//!    material's P-wave modulus, the uniqueness constant m_A the smallest of the materials'.
//! 6. **Ideal locking of two different sets** (2D, ν = 0, stretched by a prescribed end
//!    displacement, layers stacked across the load): the lower layer with
//!    `|tr ε| ≤ θ`, the upper with Prager's `½‖ε^D‖² ≤ κ²`, both active. With the axial
//!    strain a fixed and the lateral strain b free, the lower layer has `b = θ − a`,
//!    `λ_T = E₁ (a − θ)`, the upper `b = a − 2κ`, `λ_T = E₂ (a − 2κ)/κ`: multipliers of
//!    different units (the set functions scale like a strain and like its square).
//! 7. **Refusals:** a region without a material, a material naming no region, a `[locking]`
//!    table beside `[[material]]` tables, boxes that leave a cell out.
//! 8. **Contrasts of stiffness up to 10¹²:** the bar (tension and compression, the soft half
//!    held or loaded) and the layered block (the soft layer below or above) match their
//!    closed forms to 1e-8, where the stiff part moved as a whole by the soft one has nodal
//!    forces known only to the round-off of `E_stiff u`; a soft half stretched by 10⁻⁵ too
//!    much (the stiff half moved along, every node within its round-off floor) still fails
//!    the certificate at contrast 10¹² as at contrast 1.

use hemicontact::assembly::global::Want;
use hemicontact::assembly::{BulkAssembler, SystemPattern};
use hemicontact::fields::cell_fields;
use hemicontact::material::{Hooke, Material, Plane};
use hemicontact::mesh::generate::{cuboid, rectangle, BoxSpec, CutPattern, Rectangle};
use hemicontact::mesh::Mesh;
use hemicontact::problem::Problem;
use hemicontact::scenario::Scenario;
use hemicontact::solver::{solve, SolverSettings};

fn problem_of(toml: &str) -> Problem {
    Scenario::from_str(toml, "materials.toml")
        .unwrap()
        .into_problem()
        .unwrap()
}

fn refusal(toml: &str) -> String {
    match Scenario::from_str(toml, "materials.toml").and_then(|s| s.into_problem()) {
        Ok(_) => panic!("accepted:\n{toml}"),
        Err(e) => e.to_string(),
    }
}

const BAR: &str = r#"
[mesh]
kind = "rectangle"
size = [2.0, 0.5]
n = [8, 2]
[[mesh.region]]
name = "soft"
min = [0.0, 0.0]
max = [1.0, 0.5]
[[mesh.region]]
name = "stiff"
min = [1.0, 0.0]
max = [2.0, 0.5]
[[material]]
part = "soft"
young = 1000.0
poisson = 0.0
[[material]]
part = "stiff"
young = 7000.0
poisson = 0.0
[[dirichlet]]
part = "left"
components = ["x"]
[[dirichlet]]
part = "bottom"
components = ["y"]
[[loads.traction]]
part = "right"
value = [35.0, 0.0]
"#;

#[test]
fn a_bimaterial_bar_stretches_by_the_sum_of_its_halves() {
    let problem = problem_of(BAR);
    assert_eq!(problem.materials().len(), 2);
    let s = solve(&problem, &SolverSettings::default()).unwrap();
    assert!(s.report.converged);
    let sigma = 35.0;
    let end = sigma * (1.0 / 1000.0 + 1.0 / 7000.0);
    let mesh = problem.mesh();
    for v in 0..mesh.n_nodes() {
        let x = mesh.node(v)[0];
        let exact = if x <= 1.0 {
            sigma * x / 1000.0
        } else {
            sigma / 1000.0 + sigma * (x - 1.0) / 7000.0
        };
        assert!(
            (s.u[2 * v] - exact).abs() <= 1e-10 * end,
            "node {v} at x = {x}: u_x = {:e}, exact {exact:e}",
            s.u[2 * v]
        );
        assert!(s.u[2 * v + 1].abs() <= 1e-10 * end, "u_y at node {v}");
    }
    let cells = cell_fields(&problem, &s);
    for c in 0..mesh.n_cells() {
        let sxx = cells.stress[9 * c];
        assert!(
            (sxx - sigma).abs() <= 1e-9 * sigma,
            "cell {c}: σ_xx = {sxx}"
        );
        let x0 = mesh.cell_coords(c)[..3].iter().map(|p| p[0]).sum::<f64>() / 3.0;
        assert_eq!(
            cells.material[c],
            i32::from(x0 > 1.0),
            "material of cell {c}"
        );
    }
    // Per material: the strain energy σ² A / (2E) of a unit-thickness half of area 0.5.
    let summary = hemicontact::io::summary::Summary::new(
        &problem,
        &SolverSettings::default(),
        &s,
        None,
        "bar",
    );
    assert!(summary.lame.is_none());
    let m = &summary.materials;
    assert_eq!(m.len(), 2);
    for (k, e) in [(0, 1000.0), (1, 7000.0)] {
        assert_eq!(m[k].cells, 16);
        assert!((m[k].volume - 0.5).abs() < 1e-14);
        let exact = sigma * sigma * 0.5 / (2.0 * e);
        assert!(
            (m[k].strain_energy - exact).abs() <= 1e-9 * exact,
            "material {k}: {} against {exact}",
            m[k].strain_energy
        );
    }
    assert_eq!(m[1].parts, ["stiff"]);
}

/// The layered block: two layers of different laws along z, on rollers, pressed by p.
fn layered_block(contact: bool) -> String {
    layered_block_of(contact, [10.0, 2000.0])
}

/// [`layered_block`] with the Young's moduli `young` of the lower (ν = 0.45) and the upper
/// (ν = 0.3) layer.
fn layered_block_of(contact: bool, young: [f64; 2]) -> String {
    let bottom = if contact {
        "[[contact]]\npart = \"bottom\"\nlaw = \"signorini\"\n"
    } else {
        "[[dirichlet]]\npart = \"bottom\"\ncomponents = [\"z\"]\n"
    };
    format!(
        r#"
[mesh]
kind = "box"
size = [1.0, 1.0, 1.0]
n = [2, 2, 4]
[[mesh.region]]
name = "rubber"
min = [0.0, 0.0, 0.0]
max = [1.0, 1.0, 0.5]
[[mesh.region]]
name = "steel"
min = [0.0, 0.0, 0.5]
max = [1.0, 1.0, 1.0]
[[material]]
part = "rubber"
young = {:e}
poisson = 0.45
[[material]]
part = "steel"
young = {:e}
poisson = 0.3
[[dirichlet]]
part = "left"
components = ["x"]
[[dirichlet]]
part = "right"
components = ["x"]
[[dirichlet]]
part = "front"
components = ["y"]
[[dirichlet]]
part = "back"
components = ["y"]
{bottom}
[[loads.traction]]
part = "top"
value = [0.0, 0.0, -0.25]
"#,
        young[0], young[1]
    )
}

fn lame_3d(e: f64, nu: f64) -> Hooke {
    Hooke::from_young_poisson(e, nu, 3, Plane::Strain)
}

#[test]
fn a_layered_block_under_pressure_settles_by_the_sum_of_its_layers() {
    let problem = problem_of(&layered_block(false));
    let s = solve(&problem, &SolverSettings::default()).unwrap();
    assert!(s.report.converged);
    let p = 0.25;
    let layers = [lame_3d(10.0, 0.45), lame_3d(2000.0, 0.3)];
    let m = layers.map(|h| h.lambda + 2.0 * h.mu);
    let settlement = p * (0.5 / m[0] + 0.5 / m[1]);
    let mesh = problem.mesh();
    for v in 0..mesh.n_nodes() {
        let z = mesh.node(v)[2];
        let exact = -p * (z.min(0.5) / m[0] + (z - 0.5).max(0.0) / m[1]);
        assert!(
            (s.u[3 * v + 2] - exact).abs() <= 1e-10 * settlement,
            "node {v} at z = {z}: u_z = {:e}, exact {exact:e}",
            s.u[3 * v + 2]
        );
    }
    let cells = cell_fields(&problem, &s);
    for c in 0..mesh.n_cells() {
        let k = cells.material[c] as usize;
        let eps_zz = -p / m[k];
        let st = &cells.stress[9 * c..9 * c + 9];
        assert!((st[8] + p).abs() <= 1e-9 * p, "cell {c}: σ_zz = {}", st[8]);
        let lateral = layers[k].lambda * eps_zz;
        assert!(
            (st[0] - lateral).abs() <= 1e-9 * p && (st[4] - lateral).abs() <= 1e-9 * p,
            "cell {c} (material {k}): σ_xx = {}, σ_yy = {}, exact {lateral}",
            st[0],
            st[4]
        );
    }
}

#[test]
fn a_layered_block_on_a_rigid_foundation_is_pressed_by_the_load_at_every_point() {
    let problem = problem_of(&layered_block(true));
    let s = solve(&problem, &SolverSettings::default()).unwrap();
    assert!(s.report.converged, "{:?}", s.report.certificate);
    assert!(!s.contact.is_empty());
    for c in &s.contact {
        assert!(
            (c.pressure - 0.25).abs() <= 1e-7 * 0.25,
            "node {}: pressure {}",
            c.node,
            c.pressure
        );
    }
}

/// A mesh of `n` cells per side of the unit square or cube, with the regions `lower`
/// (centroid below the plane x_{d−1} = 1/2) and `upper`.
fn two_layer_mesh(d: usize, n: usize) -> Mesh {
    let mesh = if d == 2 {
        rectangle(&Rectangle {
            origin: [0.0, 0.0],
            size: [1.0, 1.0],
            n: [n, n],
            pattern: CutPattern::Symmetric,
            progression: [1.0, 1.0],
        })
    } else {
        cuboid(&BoxSpec {
            origin: [0.0; 3],
            size: [1.0; 3],
            n: [n; 3],
            pattern: CutPattern::Symmetric,
            progression: [1.0; 3],
        })
    }
    .unwrap();
    let mut hi = [1.0; 3];
    hi[d - 1] = 0.5;
    let lower = mesh.cells_in_box([0.0; 3], hi);
    let mut region = vec![1u16; mesh.n_cells()];
    for c in lower {
        region[c] = 0;
    }
    mesh.with_regions(region, vec!["lower".into(), "upper".into()])
        .unwrap()
}

/// The stress `C ε` of Hooke's law as a d × d matrix.
fn hooke_stress(h: &Hooke, e: &[[f64; 3]; 3], d: usize) -> [[f64; 3]; 3] {
    let tr: f64 = (0..d).map(|i| e[i][i]).sum();
    let mut s = [[0.0; 3]; 3];
    for i in 0..d {
        for j in 0..d {
            s[i][j] = 2.0 * h.mu * e[i][j] + if i == j { h.lambda * tr } else { 0.0 };
        }
    }
    s
}

/// The jump `a` of the displacement gradient across the plane x_{d−1} = const for which
/// `C₂ (ε₁ + sym(a ⊗ n)) n = C₁ ε₁ n`, n = e_{d−1}: a d × d linear system, solved by
/// Gaussian elimination.
fn traction_continuous_jump(h: [&Hooke; 2], e1: &[[f64; 3]; 3], d: usize) -> [f64; 3] {
    let n = d - 1;
    let strain_of = |a: &[f64; 3]| {
        let mut e = *e1;
        for i in 0..d {
            e[i][n] += 0.5 * a[i];
            e[n][i] += 0.5 * a[i];
        }
        e
    };
    let target = hooke_stress(h[0], e1, d);
    let residual = |a: &[f64; 3]| {
        let s = hooke_stress(h[1], &strain_of(a), d);
        let mut r = [0.0; 3];
        for i in 0..d {
            r[i] = s[i][n] - target[i][n];
        }
        r
    };
    // The residual is affine in a: its matrix column by column.
    let r0 = residual(&[0.0; 3]);
    let mut m = [[0.0; 4]; 3];
    for j in 0..d {
        let mut a = [0.0; 3];
        a[j] = 1.0;
        let r = residual(&a);
        for i in 0..d {
            m[i][j] = r[i] - r0[i];
        }
    }
    for i in 0..d {
        m[i][3] = -r0[i];
    }
    for k in 0..d {
        let p = (k..d)
            .max_by(|&a, &b| m[a][k].abs().total_cmp(&m[b][k].abs()))
            .unwrap();
        m.swap(k, p);
        for i in 0..d {
            if i != k {
                let f = m[i][k] / m[k][k];
                for j in 0..4 {
                    m[i][j] -= f * m[k][j];
                }
            }
        }
    }
    let mut a = [0.0; 3];
    for i in 0..d {
        a[i] = m[i][3] / m[i][i];
    }
    a
}

/// The internal forces of the piecewise-affine field `u = ε₁ x` below the interface and
/// `u = ε₁ x + a (x_n − 1/2)` above, largest at a node off the outer boundary, relative to
/// the largest force at a boundary node.
fn interface_forces(d: usize, jump: bool) -> f64 {
    let mesh = two_layer_mesh(d, 4);
    let h = [
        Hooke::from_young_poisson(3.0, 0.2, d, Plane::Strain),
        Hooke::from_young_poisson(40.0, 0.35, d, Plane::Strain),
    ];
    let materials = [
        Material::elastic(hemicontact::material::Elasticity::Hooke(h[0])),
        Material::elastic(hemicontact::material::Elasticity::Hooke(h[1])),
    ];
    let e1 = [
        [0.01, 0.003, -0.002],
        [0.003, -0.004, 0.005],
        [-0.002, 0.005, 0.007],
    ];
    let a = if jump {
        traction_continuous_jump([&h[0], &h[1]], &e1, d)
    } else {
        [0.0; 3]
    };
    let mut u = vec![0.0; d * mesh.n_nodes()];
    for v in 0..mesh.n_nodes() {
        let x = mesh.node(v);
        let above = (x[d - 1] - 0.5).max(0.0);
        for i in 0..d {
            u[d * v + i] = (0..d).map(|j| e1[i][j] * x[j]).sum::<f64>() + a[i] * above;
        }
    }
    // Held on its whole boundary (the assembled forces are those at all DOFs anyway).
    let mut builder = Problem::builder(mesh.clone(), materials[0].clone())
        .materials(materials.to_vec(), vec![0, 1]);
    for part in 0..mesh.part_names().len() {
        builder = builder.dirichlet(hemicontact::problem::Dirichlet {
            part,
            components: [true; 3],
            value: [0.0; 3],
        });
    }
    let problem = builder.build().unwrap();
    let bulk = BulkAssembler::of(&problem, &mesh);
    let dofs = problem.dof_map();
    let pattern = SystemPattern::new(&mesh, &dofs).unwrap();
    let mut grad = vec![0.0; u.len()];
    bulk.assemble(&u, &mut grad, Want::Gradient, &pattern, None);
    let on_boundary = |x: &[f64]| {
        x.iter()
            .any(|&c| c.abs() < 1e-12 || (c - 1.0).abs() < 1e-12)
    };
    let (mut inner, mut outer) = (0.0f64, 0.0f64);
    for v in 0..mesh.n_nodes() {
        let f = grad[d * v..d * v + d]
            .iter()
            .map(|x| x * x)
            .sum::<f64>()
            .sqrt();
        if on_boundary(mesh.node(v)) {
            outer = outer.max(f);
        } else {
            inner = inner.max(f);
        }
    }
    inner / outer
}

#[test]
fn the_interface_patch_test_holds_in_2d_and_3d() {
    for d in [2, 3] {
        let balanced = interface_forces(d, true);
        let wrong = interface_forces(d, false);
        assert!(
            balanced < 1e-13,
            "{d}D: interior forces {balanced:e} of the boundary's"
        );
        assert!(wrong > 1e-2, "{d}D: the wrong jump leaves only {wrong:e}");
    }
}

#[test]
fn the_scales_take_the_stiffest_material_and_uniqueness_the_smallest_m_a() {
    let problem = problem_of(&layered_block(false));
    let steel = lame_3d(2000.0, 0.3);
    let stiffest = steel.lambda + 2.0 * steel.mu;
    assert_eq!(problem.stiffness(), stiffest);
    let scales = hemicontact::solver::scaling::Scales::of(&problem).unwrap();
    assert_eq!(scales.stress, stiffest.log2().round().exp2());
    let rubber = lame_3d(10.0, 0.45);
    let u = hemicontact::solver::uniqueness::evaluate(&problem, &SolverSettings::default());
    assert_eq!(u.m_a, rubber.monotonicity(3));
    assert!(u.m_a < steel.monotonicity(3));
}

#[test]
fn one_material_table_and_one_material_per_region_give_the_same_answer() {
    // The bar with both halves of one material, given as [[material]] per region and as
    // one [material] table: the same numbers, bit for bit.
    let per_region = BAR.replace("young = 7000.0", "young = 1000.0");
    let one = BAR.split("[[material]]").next().unwrap().to_string()
        + "[material]\nyoung = 1000.0\npoisson = 0.0\n"
        + &BAR[BAR.find("[[dirichlet]]").unwrap()..];
    let a = solve(&problem_of(&per_region), &SolverSettings::default()).unwrap();
    let b = solve(&problem_of(&one), &SolverSettings::default()).unwrap();
    assert_eq!(a.u, b.u);
}

#[test]
fn inconsistent_materials_are_refused_with_the_field_named() {
    let missing = BAR.replace(
        "[[material]]\npart = \"stiff\"\nyoung = 7000.0\npoisson = 0.0\n",
        "",
    );
    let e = refusal(&missing);
    assert!(
        e.contains("no [[material]] table for the cell region \"stiff\""),
        "{e}"
    );
    let unknown = BAR.replace("part = \"stiff\"", "part = \"steel\"");
    let e = refusal(&unknown);
    assert!(
        e.contains("material[1].part") && e.contains("\"soft\", \"stiff\""),
        "{e}"
    );
    let twice = BAR.replace("part = \"stiff\"", "part = \"soft\"");
    assert!(refusal(&twice).contains("material[0] has it"));
    let locking = format!("{BAR}\n[locking]\nset = \"ball\"\nradius = 0.1\nc_kappa = 1.0\n");
    assert!(refusal(&locking).contains("its own `locking` table"));
    let bad_young = BAR.replace("young = 7000.0", "young = -7000.0");
    assert!(refusal(&bad_young).contains("material[1].young"));
    let gap = BAR.replace("max = [1.0, 0.5]", "max = [0.5, 0.5]");
    assert!(refusal(&gap).contains("is in no box"));
    let no_regions = BAR
        .replace(
            "[[mesh.region]]\nname = \"soft\"\nmin = [0.0, 0.0]\nmax = [1.0, 0.5]\n",
            "",
        )
        .replace(
            "[[mesh.region]]\nname = \"stiff\"\nmin = [1.0, 0.0]\nmax = [2.0, 0.5]\n",
            "",
        );
    assert!(refusal(&no_regions).contains("the mesh has no cell regions"));
}

#[test]
fn a_penalty_locking_part_locks_and_the_other_does_not() {
    // The bar pulled far: the soft half with a ball of radius 0.01 and a stiff penalty,
    // the stiff half without locking. The locking acts in the soft half only.
    let toml = BAR
        .replace(
            "young = 1000.0\npoisson = 0.0\n",
            "young = 1000.0\npoisson = 0.0\n[material.locking]\nset = \"ball\"\nradius = 0.01\nc_kappa = 1e5\n",
        );
    let problem = problem_of(&toml);
    let s = solve(&problem, &SolverSettings::default()).unwrap();
    assert!(s.report.converged);
    let cells = cell_fields(&problem, &s);
    for c in 0..problem.mesh().n_cells() {
        assert_eq!(
            cells.locking_active[c],
            i32::from(cells.material[c] == 0),
            "cell {c} (material {})",
            cells.material[c]
        );
    }
}

#[test]
fn two_materials_lock_ideally_each_with_its_own_set() {
    let toml = r#"
[mesh]
kind = "rectangle"
size = [2.0, 0.5]
n = [8, 4]
[[mesh.region]]
name = "lower"
min = [0.0, 0.0]
max = [2.0, 0.25]
[[mesh.region]]
name = "upper"
min = [0.0, 0.25]
max = [2.0, 0.5]
[[material]]
part = "lower"
young = 1000.0
poisson = 0.0
[material.locking]
set = "limited-compressibility"
theta = 0.004
treatment = "exact"
[[material]]
part = "upper"
young = 7000.0
poisson = 0.0
[material.locking]
set = "prager"
kappa = 0.002
treatment = "exact"
[[dirichlet]]
part = "left"
components = ["x"]
[[dirichlet]]
part = "bottom"
components = ["y"]
[[dirichlet]]
part = "right"
components = ["x"]
value = [0.02, 0.0]
"#;
    let problem = problem_of(toml);
    let s = solve(&problem, &SolverSettings::default()).unwrap();
    assert!(s.report.converged, "{:?}", s.report.certificate);
    let (a, theta, kappa) = (0.01, 0.004, 0.002);
    let b = [theta - a, a - 2.0 * kappa];
    let lambda = [1000.0 * (a - theta), 7000.0 * (a - 2.0 * kappa) / kappa];
    let mesh = problem.mesh();
    for v in 0..mesh.n_nodes() {
        let x = mesh.node(v);
        let uy = b[0] * x[1].min(0.25) + b[1] * (x[1] - 0.25).max(0.0);
        assert!(
            (s.u[2 * v] - a * x[0]).abs() <= 1e-8 * 0.02,
            "u_x at node {v}"
        );
        assert!(
            (s.u[2 * v + 1] - uy).abs() <= 1e-8 * 0.02,
            "u_y at node {v}: {} vs {uy}",
            s.u[2 * v + 1]
        );
    }
    let cells = cell_fields(&problem, &s);
    for c in 0..mesh.n_cells() {
        let k = cells.material[c] as usize;
        let l = s.locking_multiplier[c];
        assert!(
            (l - lambda[k]).abs() <= 1e-6 * lambda[k],
            "cell {c} (material {k}): λ_T = {l}, exact {}",
            lambda[k]
        );
        assert_eq!(cells.locking_active[c], 1);
        // The stress across the layers (σ_yy) vanishes: the locking stress balances it.
        assert!(cells.stress[9 * c + 4].abs() <= 1e-6 * lambda[1] * kappa);
    }
}

/// [`BAR`] with the moduli `young` of its left half `[0, 1]` (held at x = 0) and its right
/// half `[1, 2]`, loaded by the traction σ on its right end.
fn bar_of(young: [f64; 2], sigma: f64) -> Problem {
    let text = BAR
        .replacen("young = 1000.0", &format!("young = {:e}", young[0]), 1)
        .replacen("young = 7000.0", &format!("young = {:e}", young[1]), 1)
        .replacen(
            "value = [35.0, 0.0]",
            &format!("value = [{sigma:e}, 0.0]"),
            1,
        );
    problem_of(&text)
}

/// The displacement `u_x` of the bar of [`bar_of`] at x: `σ x / E_0` on the left half,
/// `σ / E_0 + σ (x − 1) / E_1` on the right one.
fn bar_displacement(young: [f64; 2], sigma: f64, x: f64) -> f64 {
    if x <= 1.0 {
        sigma * x / young[0]
    } else {
        sigma / young[0] + sigma * (x - 1.0) / young[1]
    }
}

/// A bonded bar of two materials of any stiffness contrast up to 10¹², in tension and in
/// compression, the soft half held or loaded: the closed form to 1e-8 of the end's
/// displacement, converged and certified. With the soft half held, the stiff half is moved
/// as a whole by the soft half's stretch: its nodal forces are sums of terms `E_stiff u`
/// that cancel to σ, 10¹² times smaller, so their round-off lies far above the forces; the
/// solve then resolves what the stiff half can resolve, its net force.
#[test]
fn a_bar_of_two_materials_of_any_contrast_stretches_by_the_sum_of_its_halves() {
    let settings = SolverSettings::default();
    let mut failed = Vec::new();
    for contrast in [1.0, 1e3, 1e6, 1e9, 1e12] {
        for young in [[1000.0, 1000.0 * contrast], [1000.0 * contrast, 1000.0]] {
            for sigma in [35.0, -35.0] {
                let problem = bar_of(young, sigma);
                let s = solve(&problem, &settings).unwrap();
                let case = format!("E = {:e}, {:e}, σ = {sigma}", young[0], young[1]);
                if !s.report.converged {
                    failed.push(format!("{case}: {}", s.report.message));
                    continue;
                }
                let end = bar_displacement(young, sigma, 2.0).abs();
                let mesh = problem.mesh();
                let error = (0..mesh.n_nodes())
                    .map(|v| {
                        let exact = bar_displacement(young, sigma, mesh.node(v)[0]);
                        (s.u[2 * v] - exact).abs().max(s.u[2 * v + 1].abs())
                    })
                    .fold(0.0f64, f64::max);
                println!(
                    "{case}: {} Newton steps, error {:.1e} of the end's displacement",
                    s.report.newton.len(),
                    error / end
                );
                if error > 1e-8 * end {
                    failed.push(format!("{case}: error {:e}", error / end));
                }
            }
        }
    }
    assert!(failed.is_empty(), "{failed:#?}");
}

/// The floor of the round-off does not blind the certificate. At a contrast of 10¹², the
/// soft half's stretch changed by 10⁻⁵ (the stiff half moved along with it as a whole, so
/// that no node beyond the soft half sees a change of strain, and every node's force stays
/// within its round-off floor) fails equilibrium as it does at a contrast of 1: the stiff
/// half is no longer balanced, a net force that no single node resolves but their sum along
/// its translation does. (A change of 10⁻⁶ leaves a residual of 0.7 · 10⁻⁶ of the bar's
/// forces, within the tolerance 10⁻⁶ at any contrast.) The answer itself passes.
#[test]
fn the_certificate_fails_a_soft_half_stretched_too_much_at_any_contrast() {
    let settings = SolverSettings::default();
    let mut residual = Vec::new();
    for contrast in [1.0, 1e12] {
        let (young, sigma) = ([1000.0, 1000.0 * contrast], 35.0);
        let problem = bar_of(young, sigma);
        let s = solve(&problem, &settings).unwrap();
        assert!(s.report.converged, "{}", s.report.message);
        let (_, cert) = hemicontact::solver::certify(&problem, &settings, &s.u).unwrap();
        assert!(cert.passes(), "{:?}", cert.failures());
        let mesh = problem.mesh();
        let mut wrong = s.u.clone();
        for v in 0..mesh.n_nodes() {
            let x = mesh.node(v)[0];
            wrong[2 * v] += 1e-5 * sigma * x.min(1.0) / young[0];
        }
        let (_, cert) = hemicontact::solver::certify(&problem, &settings, &wrong).unwrap();
        println!("contrast {contrast:e}: {:?}", cert.failures());
        assert!(
            cert.failures().iter().any(|f| f.law == "equilibrium"),
            "contrast {contrast:e}: {cert:?}"
        );
        residual.push(cert.equilibrium);
    }
    assert!(residual[1] > 0.5 * residual[0], "{residual:?}");
}

/// The layered block of [`layered_block`] with stiffness contrasts up to 10¹², the soft
/// layer below (the stiff one moved as a whole by its compression) or above: the settlement
/// `p (h₁/M₁ + h₂/M₂)` and the displacement of every node to 1e-8 of it.
#[test]
fn a_layered_block_of_any_contrast_settles_by_the_sum_of_its_layers() {
    let settings = SolverSettings::default();
    let p = 0.25;
    let mut failed = Vec::new();
    for contrast in [1.0, 1e3, 1e6, 1e9, 1e12] {
        for young in [[10.0, 10.0 * contrast], [10.0 * contrast, 10.0]] {
            let problem = problem_of(&layered_block_of(false, young));
            let s = solve(&problem, &settings).unwrap();
            let case = format!("E = {:e}, {:e}", young[0], young[1]);
            if !s.report.converged {
                failed.push(format!("{case}: {}", s.report.message));
                continue;
            }
            let m =
                [lame_3d(young[0], 0.45), lame_3d(young[1], 0.3)].map(|h| h.lambda + 2.0 * h.mu);
            let settlement = p * (0.5 / m[0] + 0.5 / m[1]);
            let mesh = problem.mesh();
            let error = (0..mesh.n_nodes())
                .map(|v| {
                    let z = mesh.node(v)[2];
                    let exact = -p * (z.min(0.5) / m[0] + (z - 0.5).max(0.0) / m[1]);
                    (s.u[3 * v + 2] - exact).abs()
                })
                .fold(0.0f64, f64::max);
            println!(
                "{case}: {} Newton steps, error {:.1e} of the settlement",
                s.report.newton.len(),
                error / settlement
            );
            if error > 1e-8 * settlement {
                failed.push(format!("{case}: error {:e}", error / settlement));
            }
        }
    }
    assert!(failed.is_empty(), "{failed:#?}");
}
