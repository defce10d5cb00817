//! Serial/parallel assembly parity: the parallel assembly (tasks that each own a range of
//! nodes, with their gradient entries and Hessian columns) gives bitwise the serial cell
//! loop's energy, gradient and Hessian for any number of tasks, on meshes numbered well
//! and badly, with ideal locking active; the assembly of a subdomain (what one of several
//! processes assembles) gives its rows of the whole.

use hemicontact::assembly::global::{IdealLocking, Want, Workspace};
use hemicontact::assembly::{BulkAssembler, SystemPattern};
use hemicontact::fem::dofs::DofMap;
use hemicontact::material::LockingSet;
use hemicontact::mesh::Mesh;
use hemicontact::parallel::{Partition, Subdomain};
use hemicontact::scenario::{builtin, Scenario};

/// A displacement of `mesh` that strains its cells unevenly (and, in the paper's square,
/// locks part of the body).
fn displacement(mesh: &Mesh) -> Vec<f64> {
    let d = mesh.dim();
    (0..d * mesh.n_nodes())
        .map(|k| {
            let x = mesh.node(k / d);
            0.05 * x[0] * x[1] - 0.12 * x[k % d] + 0.01 * x[0] * x[0]
        })
        .collect()
}

/// Serial and parallel passes of `bulk` on `pattern`, bitwise equal for 2 to 13 tasks and
/// for a task count above the mesh's nodes' worth of work (tasks with empty node ranges).
fn assert_bitwise_parity<M>(bulk: &BulkAssembler<'_, M>, pattern: &SystemPattern, u: &[f64])
where
    M: hemicontact::material::StrainEnergy + Sync,
{
    let n = u.len();
    let (mut g1, mut h1) = (vec![0.0; n], vec![0.0; pattern.nnz()]);
    let e1 = bulk.assemble(u, &mut g1, Want::Hessian, pattern, Some(&mut h1));
    assert!(e1 > 0.0 && g1.iter().any(|&g| g != 0.0));
    for tasks in [2, 3, 5, 8, 13, 1000] {
        let mut ws = Workspace::new(tasks);
        ws.cells_per_chunk = 1;
        for want in [Want::Hessian, Want::Gradient, Want::Hessian] {
            // Filled with garbage: every entry must be overwritten.
            let (mut g2, mut h2) = (vec![f64::NAN; n], vec![f64::NAN; pattern.nnz()]);
            let e2 = bulk.assemble_parallel(u, &mut g2, want, pattern, Some(&mut h2), &mut ws);
            assert_eq!(e1.to_bits(), e2.to_bits(), "energy, {tasks} tasks");
            let same =
                |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
            assert!(same(&g1, &g2), "gradient, {tasks} tasks");
            if want == Want::Hessian {
                assert!(same(&h1, &h2), "Hessian, {tasks} tasks");
            }
        }
    }
}

#[test]
fn parallel_assembly_is_bitwise_the_serial_one() {
    let problem = Scenario::from_str(&builtin::paper(32, 1.0e4), "test")
        .unwrap()
        .into_problem()
        .unwrap();
    let mesh = problem.mesh();
    let dofs = problem.dof_map();
    let pattern = SystemPattern::new(mesh, &dofs).unwrap();
    let u = displacement(mesh);
    let bulk = BulkAssembler::new(mesh, &problem.materials()[0]);
    assert_bitwise_parity(&bulk, &pattern, &u);
    // Ideal locking: two energy terms per cell, the multiplier of every other cell active.
    let multipliers: Vec<f64> = (0..mesh.n_cells()).map(|c| (c % 2) as f64 * 0.3).collect();
    let ideal = BulkAssembler {
        ideal: Some(IdealLocking {
            sets: &[Some(LockingSet::LimitedCompressibility { theta: 0.01 })],
            r: &[50.0],
            multipliers: &multipliers,
        }),
        ..bulk
    };
    assert_bitwise_parity(&ideal, &pattern, &u);

    // The same mesh with its nodes numbered at random: most cells then span several
    // tasks' node ranges, and some DOFs are prescribed.
    let nn = mesh.n_nodes();
    let mut perm: Vec<u32> = (0..nn as u32).collect();
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    for i in (1..nn).rev() {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        perm.swap(i, (state % (i as u64 + 1)) as usize);
    }
    let mut coords = vec![0.0; 2 * nn];
    for v in 0..nn {
        let w = perm[v] as usize;
        coords[2 * w..2 * w + 2].copy_from_slice(&mesh.node(v)[..2]);
    }
    let cells: Vec<u32> = mesh.cells().iter().map(|&v| perm[v as usize]).collect();
    let scrambled = Mesh::from_parts(2, coords, cells, &[]).unwrap();
    let fixed: Vec<bool> = (0..2 * nn).map(|k| k % 7 == 0).collect();
    let dofs = DofMap::new(2, nn, &fixed);
    let pattern = SystemPattern::new(&scrambled, &dofs).unwrap();
    let u = displacement(&scrambled);
    let bulk = BulkAssembler::new(&scrambled, &problem.materials()[0]);
    assert_bitwise_parity(&bulk, &pattern, &u);
}

/// Assembly by subdomains, as on several processes: for the nodes of each of 3 contiguous
/// ranges, the cells around them (owned, then ghost) make the range's part of the mesh, its
/// own nodes first, then the other nodes of its cells. Assembled on that part alone (its
/// own pattern, its DOFs prescribed as in the whole problem), it gives the range's gradient
/// entries and both triangles of its Hessian rows of the whole assembly (to the order of
/// additions), each row with as many entries as in the whole pattern; each cell's energy
/// is counted by exactly one range, and the ranges' energies add up to the whole; with 2
/// and 5 parallel tasks per range, bitwise the one-task pass. In 2D (the paper's mesh) and
/// in 3D (its cube analogue).
/// `scenarios/paper3d.toml` on an `n × n × n` mesh.
fn paper3d(n: usize) -> String {
    let text = std::fs::read_to_string(format!(
        "{}/../../scenarios/paper3d.toml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    assert!(text.contains("n = [16, 16, 16]"));
    text.replace("n = [16, 16, 16]", &format!("n = [{n}, {n}, {n}]"))
}

/// The problem of the scenario `text`.
fn problem(text: &str) -> hemicontact::problem::Problem {
    Scenario::from_str(text, "test")
        .unwrap()
        .into_problem()
        .unwrap()
}

#[test]
fn subdomains_give_their_rows_of_the_whole_assembly() {
    for text in [builtin::paper(64, 1.0e4), paper3d(12)] {
        let problem = problem(&text);
        let mesh = problem.mesh();
        let d = mesh.dim();
        let dofs = problem.dof_map();
        let pattern = SystemPattern::new(mesh, &dofs).unwrap();
        let bulk = BulkAssembler::new(mesh, &problem.materials()[0]);
        let displacement = |m: &hemicontact::mesh::Mesh| -> Vec<f64> {
            (0..d * m.n_nodes())
                .map(|k| {
                    let x = m.node(k / d);
                    0.03 * x[0] * x[1] - 0.11 * x[k % d] + 0.01 * x[0] * x[0]
                })
                .collect()
        };
        let u = displacement(mesh);
        let n = u.len();
        let (mut g, mut h) = (vec![0.0; n], vec![0.0; pattern.nnz()]);
        let e = bulk.assemble(&u, &mut g, Want::Hessian, &pattern, Some(&mut h));
        let gs = g.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let hs = h.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        // Entries of every equation's row in both triangles of a pattern.
        let row_lengths = |p: &SystemPattern| {
            let mut len = vec![0usize; p.n()];
            for j in 0..p.n() {
                for &i in &p.row_idx()[p.col_ptr()[j]..p.col_ptr()[j + 1]] {
                    len[j] += 1;
                    if i != j {
                        len[i] += 1;
                    }
                }
            }
            len
        };
        let whole_rows = row_lengths(&pattern);
        let parts = 3;
        let partition = Partition::ranges(mesh.n_nodes(), parts);
        let mut owner = vec![usize::MAX; mesh.n_cells()];
        let mut energy = 0.0;
        for part in 0..parts {
            let nodes = part * mesh.n_nodes() / parts..(part + 1) * mesh.n_nodes() / parts;
            let sub = Subdomain::new(mesh, partition.clone(), part);
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
            // The part of the mesh: own nodes first, in order, then the ghosts; each cell
            // the whole mesh's cell with its vertices renumbered, at the same coordinates.
            let (local_mesh, local_nodes) = sub.local_mesh(mesh).unwrap();
            let own = nodes.len();
            assert_eq!(
                local_nodes[..own],
                nodes.clone().map(|v| v as u32).collect::<Vec<_>>()[..]
            );
            assert!(local_nodes[own..]
                .iter()
                .all(|&v| !nodes.contains(&(v as usize))));
            assert_eq!(local_mesh.n_cells(), sub.cells.len());
            for (p, &c) in sub.cells.iter().enumerate() {
                let back: Vec<u32> = local_mesh
                    .cell(p)
                    .iter()
                    .map(|&l| local_nodes[l as usize])
                    .collect();
                assert_eq!(back, mesh.cell(c as usize));
            }
            for (l, &v) in local_nodes.iter().enumerate() {
                assert_eq!(local_mesh.node(l), mesh.node(v as usize));
            }
            let local_dofs = dofs.restricted(&local_nodes);
            for (l, &v) in local_nodes.iter().enumerate() {
                for k in 0..d {
                    let dof = d * v as usize + k;
                    assert_eq!(local_dofs.is_fixed(d * l + k), dofs.is_fixed(dof));
                }
            }
            let local = SystemPattern::new(&local_mesh, &local_dofs).unwrap();
            assert!(local.nnz() < pattern.nnz());
            // The whole equation of every local one.
            let mut whole_eq = vec![0usize; local.n()];
            for (dof, &eq) in local_dofs.equations().iter().enumerate() {
                if eq != u32::MAX {
                    let v = local_nodes[dof / d] as usize;
                    whole_eq[eq as usize] = dofs.equation(d * v + dof % d) as usize;
                }
            }
            // Own equations come first.
            let own_eqs = local_dofs.equations()[..d * own]
                .iter()
                .filter(|&&eq| eq != u32::MAX)
                .count();
            let local_rows = row_lengths(&local);
            for j in 0..own_eqs {
                assert_eq!(
                    local_rows[j], whole_rows[whole_eq[j]],
                    "row of equation {j}"
                );
            }
            let u_local = displacement(&local_mesh);
            let mut first: Option<(f64, Vec<f64>, Vec<f64>)> = None;
            for chunks in [1, 2, 5] {
                let mut ws = Workspace::new(chunks);
                ws.cells_per_chunk = 1;
                ws.owned_cells = Some(sub.owned);
                let mut gp = vec![0.0; u_local.len()];
                let mut hp = vec![0.0; local.nnz()];
                let part_bulk = BulkAssembler::new(&local_mesh, &problem.materials()[0]);
                let ep = part_bulk.assemble_parallel(
                    &u_local,
                    &mut gp,
                    Want::Hessian,
                    &local,
                    Some(&mut hp),
                    &mut ws,
                );
                // Any number of tasks gives the one-task pass bitwise.
                match &first {
                    None => {
                        energy += ep;
                        first = Some((ep, gp.clone(), hp.clone()));
                    }
                    Some((e1, g1, h1)) => {
                        assert_eq!(e1.to_bits(), ep.to_bits());
                        assert_eq!(g1, &gp);
                        assert_eq!(h1, &hp);
                    }
                }
                for l in 0..own {
                    for k in 0..d {
                        let whole = g[d * local_nodes[l] as usize + k];
                        let diff = (whole - gp[d * l + k]).abs();
                        assert!(diff <= 1e-14 * gs, "gradient at node {}", local_nodes[l]);
                    }
                }
                // Every entry of an own row, found by its (row, column) in the whole
                // pattern.
                let (cp, ri) = (local.col_ptr(), local.row_idx());
                let mut checked = 0;
                for j in 0..local.n() {
                    for s in cp[j]..cp[j + 1] {
                        if ri[s] < own_eqs || j < own_eqs {
                            let at = pattern.find(whole_eq[ri[s]], whole_eq[j]).unwrap();
                            let diff = (h[at] - hp[s]).abs();
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

/// The reductions of the outer loop, Newton and the certificate are split among the
/// processes by what each counts (`Share`) of its part of the mesh: every node, DOF,
/// equation and cell of the whole problem is counted by exactly one of 3
/// processes, for a partition in contiguous ranges and for a scattered one; the processes'
/// shares of a body's norm, energy norm and a dot product, each on its part, add up to the
/// whole one; and the part's entries of a whole array (`Share::of_part`) go back to their
/// places in the whole (`Share::to_whole`, here on one process: its own entries, the rest
/// NaN).
#[test]
fn each_entry_is_counted_by_one_process() {
    use hemicontact::fem::dofs::FIXED;
    use hemicontact::parallel::share::Entries;
    use hemicontact::parallel::{Processes, Share};
    use hemicontact::solver::local_scales::Bodies;
    for text in [builtin::paper(32, 1.0e4), paper3d(8)] {
        let problem = problem(&text);
        let mesh = problem.mesh();
        let d = mesh.dim();
        let dofs = problem.dof_map();
        let contact = problem.contact_nodes().unwrap();
        assert!(contact.len() > 10);
        let bodies = Bodies::new(&problem, &problem.rigid_motions().unwrap());
        let hooke = problem.materials()[0].elasticity.small_strain_hooke(d);
        let v: Vec<f64> = (0..d * mesh.n_nodes())
            .map(|k| {
                let x = mesh.node(k / d);
                0.03 * x[0] * x[1] - 0.11 * x[k % d] + 0.01 * x[0] * x[0]
            })
            .collect();
        let x: Vec<f64> = (0..dofs.n_free()).map(|e| (e as f64).sin()).collect();
        let whole = Share::whole();
        let (mut norm, mut energy) = (Vec::new(), Vec::new());
        bodies.norms(&whole, d, v.len(), |k| v[k], &mut norm);
        bodies.energy_norms(&whole, mesh, &|_| hooke, &v, &mut energy);
        let mut resultant = Vec::new();
        bodies
            .regions
            .resultants(mesh, &whole, |k| v[k], &mut resultant);
        let dot = whole.dot_equations(&x, &x);
        let sizes = [mesh.n_nodes(), contact.len(), mesh.n_cells()];
        let parts = 3;
        let scattered: Vec<u32> = (0..mesh.n_nodes()).map(|v| (v * 7 % 3) as u32).collect();
        for partition in [
            Partition::ranges(mesh.n_nodes(), parts),
            Partition::from_ranks(scattered, parts),
        ] {
            let mut nodes = vec![0; mesh.n_nodes()];
            let mut equations = vec![0; dofs.n_free()];
            let mut cells = vec![0; mesh.n_cells()];
            let mut back = vec![f64::NAN; v.len()];
            let (mut norm2, mut energy2, mut dots) =
                (vec![0.0; bodies.count], vec![0.0; bodies.count], 0.0);
            let mut resultant2 = vec![0.0; resultant.len()];
            for rank in 0..parts {
                let sub = Subdomain::new(mesh, partition.clone(), rank);
                let (part, ids) = sub.local_mesh(mesh).unwrap();
                let part_dofs = dofs.restricted(&ids);
                let own: Vec<u32> = (0..contact.len() as u32)
                    .filter(|&i| {
                        partition.rank_of[contact.node[i as usize] as usize] as usize == rank
                    })
                    .collect();
                let share = Share::of(
                    d,
                    &sub,
                    ids.clone(),
                    &part_dofs,
                    own.clone(),
                    own.len(),
                    sizes,
                    Processes::alone(),
                );
                assert!(share.is_split());
                for (l, &w) in ids.iter().enumerate() {
                    nodes[w as usize] += usize::from(share.counts_node(l));
                    assert_eq!(share.whole_node(l as u32), w);
                    for k in 0..d {
                        assert_eq!(share.counts_dof(d * l + k), share.counts_node(l));
                        let eq = part_dofs.equations()[d * l + k];
                        if eq != FIXED {
                            assert_eq!(share.counts_equation(eq as usize), share.counts_node(l));
                            let whole_eq = dofs.equations()[d * w as usize + k];
                            assert_ne!(whole_eq, FIXED);
                            equations[whole_eq as usize] +=
                                usize::from(share.counts_equation(eq as usize));
                        }
                    }
                }
                for (c, &w) in sub.cells.iter().enumerate() {
                    cells[w as usize] += usize::from(share.counts_cell(c));
                }
                let v_part = share.of_part(v.clone(), d, Entries::Nodes);
                for (k, b) in share
                    .to_whole(v_part.clone(), d, Entries::Nodes)
                    .iter()
                    .enumerate()
                {
                    if !b.is_nan() {
                        assert_eq!(partition.rank_of[k / d] as usize, rank);
                        back[k] = *b;
                    }
                }
                let mut x_part = vec![0.0; part_dofs.n_free()];
                for (k, &eq) in part_dofs.equations().iter().enumerate() {
                    if eq != FIXED {
                        x_part[eq as usize] =
                            x[dofs.equations()[d * ids[k / d] as usize + k % d] as usize];
                    }
                }
                let part_bodies = bodies.restricted(&ids, &part, &sub.cells);
                let mut part_resultant = Vec::new();
                let regions = &part_bodies.regions;
                regions.resultants(&part, &share, |k| v_part[k], &mut part_resultant);
                for (r, p) in resultant2.iter_mut().zip(&part_resultant) {
                    *r += p;
                }
                let (mut part_norm, mut part_energy) = (Vec::new(), Vec::new());
                part_bodies.norms(&share, d, v_part.len(), |k| v_part[k], &mut part_norm);
                part_bodies.energy_norms(&share, &part, &|_| hooke, &v_part, &mut part_energy);
                for b in 0..bodies.count {
                    norm2[b] += part_norm[b].powi(2);
                    energy2[b] += part_energy[b].powi(2);
                }
                dots += share.dot_equations(&x_part, &x_part);
            }
            assert!(nodes.iter().all(|&n| n == 1));
            assert!(equations.iter().all(|&n| n == 1));
            assert!(cells.iter().all(|&n| n == 1));
            assert_eq!(
                back, v,
                "the parts' own entries, put back, are the whole array"
            );
            for b in 0..bodies.count {
                assert!(
                    (norm2[b].sqrt() - norm[b]).abs() <= 1e-13 * norm[b],
                    "body {b}"
                );
                assert!(
                    (energy2[b].sqrt() - energy[b]).abs() <= 1e-13 * energy[b],
                    "body {b}"
                );
            }
            assert!((dots - dot).abs() <= 1e-13 * dot);
            // The regions' resultants along their rigid modes, summed over the parts.
            let scale = resultant.iter().fold(0.0f64, |m, r| m.max(r.abs()));
            assert!(scale > 0.0);
            for (a, b) in resultant.iter().zip(&resultant2) {
                assert!(
                    (a - b).abs() <= 1e-13 * scale,
                    "{resultant:?} {resultant2:?}"
                );
            }
        }
    }
}

/// Contact between two bodies on a part of the mesh: a process holds the pairs of its own
/// slave nodes and, as *ghost points*, the pairs whose slave node is another's but whose
/// master facet has a node of its own; their other nodes are ghost nodes of its part,
/// brought in by the pairs' couplings. Then the part's contact assembly gives its own
/// nodes' gradient and its own rows of the Hessian of the whole, and the energies of the
/// points each counts add up to the whole energy. Checked on the punch on a block (exact
/// Coulomb friction between non-matching meshes) for two partitions that cut the pairs
/// (scattered nodes, and the slave nodes apart from all others; 3 parts each), at a
/// displacement that presses some points and separates others.
#[test]
fn a_part_assembles_its_rows_of_the_contact_pairs() {
    use hemicontact::assembly::contact::{contact_slots, ContactAssembler, ContactData};
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let problem = Scenario::from_file(&root.join("scenarios/punch-on-block.toml"))
        .unwrap()
        .into_problem()
        .unwrap();
    let mesh = problem.mesh();
    let d = mesh.dim();
    // The points as paired in the reference configuration, without the translation that
    // the punch's support carries it by (the displacement below is the whole one).
    let contact = hemicontact::contact::ContactNodes::new(
        mesh,
        problem.contact(),
        &problem.fully_prescribed(),
        None,
    )
    .unwrap();
    assert!(contact.has_pairs() && contact.len() > 20);
    let n = contact.len();
    // The point data, different at every point: bounds, linear terms, multipliers.
    let wave = |i: usize, a: f64| 1.0 + 0.5 * (a * i as f64).sin();
    let bound: Vec<f64> = (0..n).map(|i| 1e3 * wave(i, 1.3)).collect();
    let linear: Vec<[f64; 2]> = (0..n).map(|i| [30.0 * wave(i, 0.7), 0.0]).collect();
    let pressure: Vec<f64> = (0..n).map(|i| 2e3 * wave(i, 2.1)).collect();
    let traction: Vec<[f64; 2]> = (0..n).map(|i| [1e2 * wave(i, 0.4), 0.0]).collect();
    let stiffness: Vec<f64> = (0..n).map(|i| 1e7 * wave(i, 0.9)).collect();
    let penalty: Vec<f64> = (0..n).map(|i| 1e8 * wave(i, 1.7)).collect();
    // The punch pushed into the block and sheared, unevenly.
    let u: Vec<f64> = (0..d * mesh.n_nodes())
        .map(|k| {
            let x = mesh.node(k / d);
            let v = (k / d) as u32;
            let punch = if x[1] > 0.5 + 1e-9 || contact.node.contains(&v) {
                1.0
            } else {
                0.0
            };
            1e-4 * (0.3 * (7.0 * x[0]).sin() + punch * [0.5, (23.0 * x[0]).sin()][k % d])
        })
        .collect();
    let coupled = mesh.clone().with_couplings(contact.couplings(d));
    let dofs = problem.dof_map();
    let pattern = SystemPattern::new(&coupled, &dofs).unwrap();
    let slots = contact_slots(&contact, d, dofs.equations(), &pattern);
    let data = ContactData {
        bound: &bound,
        linear: &linear,
        pressure: &pressure,
        traction: &traction,
    };
    let (mut g, mut h) = (vec![0.0; u.len()], vec![0.0; pattern.nnz()]);
    let whole = ContactAssembler {
        dim: d,
        nodes: &contact,
        boundaries: problem.contact(),
        stiffness: &stiffness,
        penalty: &penalty,
        responses: &[],
    };
    let e = whole.assemble(&u, &data, &mut g, Some((&mut h, &slots)));
    let (gs, hs) = (
        g.iter().fold(0.0f64, |m, x| m.max(x.abs())),
        h.iter().fold(0.0f64, |m, x| m.max(x.abs())),
    );
    assert!(e > 0.0 && gs > 0.0 && hs > 0.0);
    let pressed = (0..n)
        .filter(|&i| whole.state(&u, i, &data).pressure > 0.0)
        .count();
    assert!(
        pressed > 0 && pressed < n,
        "{pressed} of {n} points pressed"
    );
    let parts = 3;
    let scattered: Vec<u32> = (0..mesh.n_nodes()).map(|v| (v * 7 % 3) as u32).collect();
    // The punch's contact nodes on one process, the rest shared by the other two: every
    // pair is cut.
    let apart: Vec<u32> = (0..mesh.n_nodes() as u32)
        .map(|v| match contact.node.contains(&v) {
            true => 0,
            false => 1 + v % 2,
        })
        .collect();
    for partition in [
        Partition::from_ranks(scattered, parts),
        Partition::from_ranks(apart, parts),
    ] {
        let (mut energy, mut ghosts, mut counted) = (0.0, 0, vec![0; n]);
        for rank in 0..parts {
            let sub = Subdomain::new(&coupled, partition.clone(), rank);
            let (part, ids) = sub.local_mesh(&coupled).unwrap();
            let own = sub.nodes().len();
            let mut local_of = vec![u32::MAX; mesh.n_nodes()];
            for (l, &v) in ids.iter().enumerate() {
                local_of[v as usize] = l as u32;
            }
            let (points, n_own) = sub.contact_points(&contact, d);
            ghosts += points.len() - n_own;
            for &i in &points[..n_own] {
                counted[i as usize] += 1;
            }
            // Every node of every held point's stencil is in the part.
            let held = contact.restricted(&points, points.len() - n_own, |v| {
                assert_ne!(
                    local_of[v as usize],
                    u32::MAX,
                    "node {v} not in part {rank}"
                );
                local_of[v as usize]
            });
            assert_eq!(held.owned(), n_own);
            let part = part.with_couplings(held.couplings(d));
            let part_dofs = dofs.restricted(&ids);
            let part_pattern = SystemPattern::new(&part, &part_dofs).unwrap();
            let part_slots = contact_slots(&held, d, part_dofs.equations(), &part_pattern);
            let pick =
                |all: &[f64]| -> Vec<f64> { points.iter().map(|&i| all[i as usize]).collect() };
            let pick2 = |all: &[[f64; 2]]| -> Vec<[f64; 2]> {
                points.iter().map(|&i| all[i as usize]).collect()
            };
            let (b, l, p, t) = (
                pick(&bound),
                pick2(&linear),
                pick(&pressure),
                pick2(&traction),
            );
            let (k, r) = (pick(&stiffness), pick(&penalty));
            let part_data = ContactData {
                bound: &b,
                linear: &l,
                pressure: &p,
                traction: &t,
            };
            let u_part: Vec<f64> = (0..d * ids.len())
                .map(|k| u[d * ids[k / d] as usize + k % d])
                .collect();
            let (mut gp, mut hp) = (vec![0.0; u_part.len()], vec![0.0; part_pattern.nnz()]);
            energy += ContactAssembler {
                nodes: &held,
                stiffness: &k,
                penalty: &r,
                ..whole
            }
            .assemble(&u_part, &part_data, &mut gp, Some((&mut hp, &part_slots)));
            for lv in 0..own {
                for c in 0..d {
                    let diff = (g[d * ids[lv] as usize + c] - gp[d * lv + c]).abs();
                    assert!(diff <= 1e-13 * gs, "gradient at node {}: {diff:e}", ids[lv]);
                }
            }
            // Every entry of an own row, found by its (row, column) in the whole pattern.
            let mut whole_eq = vec![0usize; part_pattern.n()];
            for (dof, &eq) in part_dofs.equations().iter().enumerate() {
                if eq != u32::MAX {
                    whole_eq[eq as usize] =
                        dofs.equation(d * ids[dof / d] as usize + dof % d) as usize;
                }
            }
            let own_eqs = part_dofs.equations()[..d * own]
                .iter()
                .filter(|&&eq| eq != u32::MAX)
                .count();
            let (cp, ri) = (part_pattern.col_ptr(), part_pattern.row_idx());
            for j in 0..part_pattern.n() {
                for s in cp[j]..cp[j + 1] {
                    if ri[s] < own_eqs || j < own_eqs {
                        let (a, b) = (whole_eq[ri[s]], whole_eq[j]);
                        let at = pattern.find(a.min(b), a.max(b)).unwrap();
                        let diff = (h[at] - hp[s]).abs();
                        assert!(diff <= 1e-13 * hs, "Hessian entry ({a}, {b}): {diff:e}");
                    }
                }
            }
        }
        assert!(counted.iter().all(|&c| c == 1), "each point counted once");
        assert!(ghosts > 0, "the partition cuts no pair");
        assert!(
            (energy - e).abs() <= 1e-13 * e.abs(),
            "{energy} against {e}"
        );
    }
}
