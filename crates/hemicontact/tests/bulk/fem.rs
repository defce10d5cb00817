//! # Verification: P1 element exactness and consistent loads
//!
//! What is verified, and why it must hold:
//!
//! - **Gradients reproduce affine fields.** The P1 space contains every affine field, so for
//!   `u(x) = a + B x` the nodal interpolant *is* `u`, and the element strain `B_e u_e` must
//!   equal `sym(B)` exactly (up to round-off) on any non-degenerate triangle or tetrahedron.
//!   Checked on random cells of both orientations' worth of shapes; rigid motions
//!   (`B` skew) give zero strain.
//! - **Element gradient, Hessian and energy agree.** For a quadratic energy,
//!   `K_e u_e = |T| Bᵀσ(ε(u_e))` and `½ u_eᵀ K_e u_e = |T| W(ε(u_e))`.
//! - **Consistent loads integrate constant data exactly.** `∫_T φ_a = |T|/(d+1)` and
//!   `∫_F φ_a = |F|/d`, so the nodal loads of a constant body force sum to `f_0 |Ω|`, those
//!   of a constant traction on a side sum to `t |side|`, and — since `x = Σ_a x_a φ_a` for
//!   P1 — their first moments `Σ_a F_a x_a` equal `f_0 ∫_Ω x` and `t ∫_side x` exactly.
//!   Checked on generated rectangles and on a mesh with randomly perturbed interior nodes.

use crate::common::Rng;
use hemicontact::assembly::{element, loads};
use hemicontact::geometry::simplex;
use hemicontact::material::{Hooke, StrainEnergy};
use hemicontact::mesh::generate::{rectangle, CutPattern, Rectangle};
use hemicontact::mesh::Mesh;
use hemicontact::tensor::Sym;

/// A random positively oriented simplex in `dim` dimensions with vertices in [−2, 2]^d and
/// a measure bounded away from zero.
fn random_simplex(rng: &mut Rng, dim: usize) -> [[f64; 3]; 4] {
    loop {
        let mut x = [[0.0; 3]; 4];
        for p in x.iter_mut().take(dim + 1) {
            for c in p.iter_mut().take(dim) {
                *c = rng.uniform(-2.0, 2.0);
            }
        }
        let m = simplex::signed_measure(dim, &x);
        if m.abs() < 0.05 {
            continue;
        }
        if m < 0.0 {
            x.swap(1, 2);
        }
        return x;
    }
}

/// Area of a triangle by Heron's formula (independent of the determinant formula).
fn heron(x: &[[f64; 3]; 4]) -> f64 {
    let d = |a: usize, b: usize| ((x[a][0] - x[b][0]).powi(2) + (x[a][1] - x[b][1]).powi(2)).sqrt();
    let (a, b, c) = (d(0, 1), d(1, 2), d(2, 0));
    let s = 0.5 * (a + b + c);
    (s * (s - a) * (s - b) * (s - c)).max(0.0).sqrt()
}

/// Local displacement vector of the affine field `a + B x` at the vertices of `x`
/// (`LD = d(d+1)` local DOFs).
fn affine_local<const LD: usize>(x: &[[f64; 3]; 4], a: &[f64; 3], b: &[[f64; 3]; 3]) -> [f64; LD] {
    let dim = element::dim_of(LD);
    let mut ue = [0.0; LD];
    for v in 0..=dim {
        for i in 0..dim {
            ue[dim * v + i] = a[i] + (0..dim).map(|j| b[i][j] * x[v][j]).sum::<f64>();
        }
    }
    ue
}

fn random_matrix(rng: &mut Rng) -> [[f64; 3]; 3] {
    let mut b = [[0.0; 3]; 3];
    for row in b.iter_mut() {
        for v in row.iter_mut() {
            *v = rng.uniform(-1.0, 1.0);
        }
    }
    b
}

fn sym_part(b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut s = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            s[i][j] = 0.5 * (b[i][j] + b[j][i]);
        }
    }
    s
}

#[test]
fn geometry_of_random_simplices() {
    let mut rng = Rng::new(10);
    for dim in [2, 3] {
        for _ in 0..50 {
            let x = random_simplex(&mut rng, dim);
            let g = simplex::geometry(dim, &x);
            if dim == 2 {
                assert!((g.measure - heron(&x)).abs() <= 1e-10 * g.measure);
            }
            // Partition of unity: Σ_a ∇φ_a = 0. Linear precision: Σ_a x_a ⊗ ∇φ_a = I.
            for i in 0..dim {
                let s: f64 = (0..=dim).map(|a| g.grad[a][i]).sum();
                assert!(s.abs() < 1e-12, "Σ∇φ = {s}");
                for j in 0..dim {
                    let m: f64 = (0..=dim).map(|a| x[a][i] * g.grad[a][j]).sum();
                    let id = if i == j { 1.0 } else { 0.0 };
                    assert!((m - id).abs() < 1e-12, "Σ x⊗∇φ [{i}][{j}] = {m}");
                }
            }
            // ∇φ_a is zero along the opposite facet: ∇φ_a · (x_b − x_c) = 0 for b, c ≠ a.
            for a in 0..=dim {
                let others: Vec<usize> = (0..=dim).filter(|&b| b != a).collect();
                for w in others.windows(2) {
                    let t: f64 = (0..dim)
                        .map(|i| g.grad[a][i] * (x[w[1]][i] - x[w[0]][i]))
                        .sum();
                    assert!(t.abs() < 1e-12);
                }
            }
        }
    }
}

/// Affine fields and rigid motions on random cells with `LD = d(d+1)` local DOFs.
fn check_affine<const LD: usize>(rng: &mut Rng) {
    let dim = element::dim_of(LD);
    for _ in 0..50 {
        let x = random_simplex(rng, dim);
        let geo = simplex::geometry(dim, &x);
        let bm = element::b_matrix::<LD>(&geo);
        let a = [
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
        ];
        let b = random_matrix(rng);
        let eps = element::strain(&bm, &affine_local::<LD>(&x, &a, &b));
        let expected = Sym::from_matrix(dim, &sym_part(&b));
        assert_eq!(eps.dim, dim);
        for k in 0..6 {
            assert!(
                (eps.c[k] - expected.c[k]).abs() < 1e-11,
                "dim {dim}: ε[{k}] = {} expected {}",
                eps.c[k],
                expected.c[k]
            );
        }
        // Rigid motion: skew B gives zero strain.
        let mut skew = b;
        for i in 0..3 {
            for j in 0..3 {
                skew[i][j] = 0.5 * (b[i][j] - b[j][i]);
            }
        }
        let eps = element::strain(&bm, &affine_local::<LD>(&x, &a, &skew));
        assert!(eps.norm() < 1e-11, "rigid motion strains: {eps:?}");
    }
}

#[test]
fn p1_strain_reproduces_affine_fields_exactly() {
    let mut rng = Rng::new(11);
    check_affine::<6>(&mut rng);
    check_affine::<12>(&mut rng);
}

/// `K_e u_e = |T| Bᵀσ` and `½ u_eᵀ K_e u_e = |T| W` on random cells and displacements.
fn check_element_consistency<const LD: usize>(rng: &mut Rng, law: &Hooke) {
    let dim = element::dim_of(LD);
    for _ in 0..20 {
        let x = random_simplex(rng, dim);
        let geo = simplex::geometry(dim, &x);
        let bm = element::b_matrix::<LD>(&geo);
        let mut ue = [0.0; LD];
        for v in ue.iter_mut() {
            *v = rng.uniform(-1.0, 1.0);
        }
        let eps = element::strain(&bm, &ue);
        let g = element::gradient(&bm, &law.stress(&eps), geo.measure);
        let k = element::hessian(&bm, &law.tangent(&eps), geo.measure);
        let kfull = |p: usize, q: usize| if p <= q { k[p][q] } else { k[q][p] };
        let scale = g.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        let mut quad = 0.0;
        for p in 0..LD {
            let ku: f64 = (0..LD).map(|q| kfull(p, q) * ue[q]).sum();
            assert!(
                (ku - g[p]).abs() < 1e-12 * scale,
                "dim {dim}: K u = {ku:e} ≠ |T| Bᵀσ = {:e} at local DOF {p}",
                g[p]
            );
            quad += ue[p] * ku;
        }
        let w = geo.measure * law.energy(&eps);
        assert!((0.5 * quad - w).abs() < 1e-11 * w.abs().max(1.0));
    }
}

#[test]
fn element_gradient_hessian_and_energy_agree() {
    let mut rng = Rng::new(12);
    let law = Hooke {
        lambda: 1.7,
        mu: 0.9,
    };
    check_element_consistency::<6>(&mut rng, &law);
    check_element_consistency::<12>(&mut rng, &law);
}

/// The generated rectangle `[0.5, 3.5] × [−1, 1]`, and a copy with randomly perturbed
/// interior nodes (same cells and boundary), built through `Mesh::try_new`.
fn test_meshes() -> Vec<(Mesh, [f64; 2], [f64; 2])> {
    let origin = [0.5, -1.0];
    let size = [3.0, 2.0];
    let mut out = Vec::new();
    for (n, pattern) in [
        ([5, 4], CutPattern::Uniform),
        ([6, 4], CutPattern::Symmetric),
    ] {
        let mesh = rectangle(&Rectangle {
            origin,
            size,
            n,
            pattern,
            progression: [1.0; 2],
        })
        .unwrap();
        let mut rng = Rng::new(13);
        let mut coords = mesh.coords().to_vec();
        let h = [size[0] / n[0] as f64, size[1] / n[1] as f64];
        for (node, x) in coords.chunks_mut(2).enumerate() {
            let (i, j) = (node % (n[0] + 1), node / (n[0] + 1));
            if i > 0 && i < n[0] && j > 0 && j < n[1] {
                x[0] += 0.15 * h[0] * rng.uniform(-1.0, 1.0);
                x[1] += 0.15 * h[1] * rng.uniform(-1.0, 1.0);
            }
        }
        let facets: Vec<u32> = (0..mesh.n_facets())
            .flat_map(|f| mesh.facet(f).to_vec())
            .collect();
        let parts: Vec<u16> = (0..mesh.n_facets())
            .map(|f| mesh.facet_part(f) as u16)
            .collect();
        let perturbed = Mesh::try_new(
            2,
            coords,
            mesh.cells().to_vec(),
            facets,
            parts,
            mesh.part_names().to_vec(),
        )
        .expect("perturbed mesh is valid");
        out.push((mesh, origin, size));
        out.push((perturbed, origin, size));
    }
    out
}

#[test]
fn body_force_load_integrates_constants_exactly() {
    let f0 = [1.5, -2.5, 0.0];
    for (mesh, origin, size) in test_meshes() {
        let area = size[0] * size[1];
        let centroid = [origin[0] + 0.5 * size[0], origin[1] + 0.5 * size[1]];
        assert!((mesh.measure() - area).abs() < 1e-12 * area);
        let mut f = vec![0.0; 2 * mesh.n_nodes()];
        loads::add_body_force(&mesh, &f0, &mut f);
        for i in 0..2 {
            let total: f64 = f.iter().skip(i).step_by(2).sum();
            assert!(
                (total - f0[i] * area).abs() < 1e-12 * area,
                "Σ F_{i} = {total}, expected {}",
                f0[i] * area
            );
            for j in 0..2 {
                let moment: f64 = (0..mesh.n_nodes())
                    .map(|n| f[2 * n + i] * mesh.node(n)[j])
                    .sum();
                let expected = f0[i] * area * centroid[j];
                assert!(
                    (moment - expected).abs() < 1e-12 * area * 4.0,
                    "Σ F_{i} x_{j} = {moment}, expected {expected}"
                );
            }
        }
    }
}

#[test]
fn traction_load_integrates_constants_exactly() {
    let t = [0.7, -1.1, 0.0];
    for (mesh, origin, size) in test_meshes() {
        let (x0, y0, x1, y1) = (
            origin[0],
            origin[1],
            origin[0] + size[0],
            origin[1] + size[1],
        );
        // (part, length, midpoint, outward normal)
        let sides = [
            ("bottom", size[0], [0.5 * (x0 + x1), y0], [0.0, -1.0]),
            ("right", size[1], [x1, 0.5 * (y0 + y1)], [1.0, 0.0]),
            ("top", size[0], [0.5 * (x0 + x1), y1], [0.0, 1.0]),
            ("left", size[1], [x0, 0.5 * (y0 + y1)], [-1.0, 0.0]),
        ];
        for (name, length, mid, normal) in sides {
            let part = mesh.part_index(name).unwrap();
            let mut f = vec![0.0; 2 * mesh.n_nodes()];
            loads::add_traction(&mesh, part, &t, &mut f);
            for i in 0..2 {
                let total: f64 = f.iter().skip(i).step_by(2).sum();
                assert!(
                    (total - t[i] * length).abs() < 1e-12,
                    "{name}: Σ F_{i} = {total}, expected {}",
                    t[i] * length
                );
                for j in 0..2 {
                    let moment: f64 = (0..mesh.n_nodes())
                        .map(|n| f[2 * n + i] * mesh.node(n)[j])
                        .sum();
                    let expected = t[i] * length * mid[j];
                    assert!(
                        (moment - expected).abs() < 1e-12 * 10.0,
                        "{name}: Σ F_{i} x_{j} = {moment}, expected {expected}"
                    );
                }
            }
            // Loads only on the nodes of the part.
            let nodes = mesh.part_nodes(part);
            for n in 0..mesh.n_nodes() {
                if nodes.binary_search(&(n as u32)).is_err() {
                    assert_eq!(f[2 * n], 0.0);
                    assert_eq!(f[2 * n + 1], 0.0);
                }
            }
            // Facet measures sum to the side length; normals are the outward unit normal.
            let mut sum = 0.0;
            for facet in mesh.part_facets(part) {
                let (m, nrm) = mesh.facet_measure_normal(facet);
                sum += m;
                assert!((nrm[0] - normal[0]).abs() < 1e-14 && (nrm[1] - normal[1]).abs() < 1e-14);
            }
            assert!((sum - length).abs() < 1e-12);
        }
    }
}
