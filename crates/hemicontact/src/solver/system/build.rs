//! The set-up of a [`System`] ([`System::new`], [`System::for_solve`]): what is computed
//! once on the whole problem (contact points, their stiffnesses and penalties, external
//! forces, free rigid motions, bodies), this process's part of it on several processes,
//! the sparsity pattern with the cells around each contact point, the prepared linear
//! solver and the distribution of the sums ([`Share`]).

use super::super::constraints::contact_stiffness;
use super::super::continuation::Continuation;
use super::super::local_scales::Bodies;
use super::super::settings::{parallelism, SolverSettings};
use super::{System, WholeCounts};
use crate::assembly::contact::contact_slots;
use crate::assembly::global::Workspace;
use crate::assembly::SystemPattern;
use crate::contact::ContactNodes;
use crate::error::Result;
use crate::fem::dofs::{DofMap, FIXED};
use crate::linalg::{LinearSolver, PrepareOptions, SpdSolver};
use crate::mesh::Mesh;
use crate::parallel::Share;
use crate::parallel::{Partition, Placement, Processes, Subdomain};
use crate::problem::Problem;
use crate::rigid::RigidMotions;
use std::time::Instant;

/// What the set-up computes once on the whole problem, or its restriction to this
/// process's part ([`SetUp::restricted`]).
struct SetUp {
    /// DOF map (Dirichlet DOFs eliminated).
    dofs: DofMap,
    /// Contact points.
    contact: ContactNodes,
    /// Elastic stiffness per unit area of every contact point (Pa/m).
    contact_stiffness: Vec<f64>,
    /// The continuation stage of the outer loop.
    continuation: Continuation,
    /// External force vector (N), DOF order.
    f_ext: Vec<f64>,
    /// Rigid motions left free by the Dirichlet conditions.
    rigid: RigidMotions,
    /// The bodies of the mesh with the force units of their prescribed motions.
    bodies: Bodies,
}

/// This process's part of a distributed system: its subdomain, the part's mesh (in its own
/// numbering), the whole numbers of its nodes, and its contact points (by their numbers in
/// the whole problem: its own, then its ghost points).
struct Part {
    /// The subdomain of this process.
    sub: Subdomain,
    /// The part's mesh.
    mesh: Mesh,
    /// The whole numbers of the part's nodes.
    nodes: Vec<u32>,
    /// The contact points of the part, by their whole numbers.
    points: Vec<u32>,
}

impl SetUp {
    /// The set-up of the whole `problem` with the DOF map `dofs`, and the sizes of the
    /// whole problem.
    fn of_whole(
        problem: &Problem,
        settings: &SolverSettings,
        dofs: DofMap,
    ) -> Result<(SetUp, WholeCounts)> {
        let contact = problem.contact_nodes()?;
        let continuation = Continuation::new(problem, &settings.constraints, &contact);
        let contact_stiffness = contact_stiffness(problem, &contact);
        let f_ext = problem.external_forces();
        let rigid = problem.rigid_motions()?;
        let bodies = Bodies::new(problem, &rigid);
        let whole_counts = WholeCounts {
            dofs: dofs.n_dofs(),
            equations: dofs.n_free(),
            contact_points: contact.len(),
        };
        let whole = SetUp {
            dofs,
            contact,
            contact_stiffness,
            continuation,
            f_ext,
            rigid,
            bodies,
        };
        Ok((whole, whole_counts))
    }

    /// This process's part of the whole set-up: its subdomain, the part's mesh and the
    /// whole numbers of its nodes, and its contact points: its own (those of its own
    /// nodes), then its ghost points (pairs whose slave node is another's but whose master
    /// facet has a node of its own, assembled again so that that node's rows are
    /// complete). The pairs' couplings join the node graph that is split, which keeps most
    /// pairs inside one part, and bring their other nodes into the part as ghosts.
    fn restricted(self, problem: &Problem, processes: &Processes) -> Result<(SetUp, Part)> {
        let d = problem.mesh.dim();
        let SetUp {
            dofs,
            contact,
            contact_stiffness,
            continuation,
            f_ext,
            rigid,
            bodies,
        } = self;
        let coupled;
        let whole_mesh = if contact.has_pairs() {
            coupled = problem.mesh.clone().with_couplings(contact.couplings(d));
            &coupled
        } else {
            &problem.mesh
        };
        let partition = Partition::of(whole_mesh, processes)?;
        let sub = Subdomain::new(whole_mesh, partition, processes.rank());
        let (mesh, nodes) = sub.local_mesh(whole_mesh)?;
        let mut local_of = vec![u32::MAX; problem.mesh.n_nodes()];
        for (l, &v) in nodes.iter().enumerate() {
            local_of[v as usize] = l as u32;
        }
        let (points, own_points) = sub.contact_points(&contact, d);
        let pick = |all: &[f64]| points.iter().map(|&i| all[i as usize]).collect();
        let restricted = SetUp {
            dofs: dofs.restricted(&nodes),
            contact: contact
                .restricted(&points, points.len() - own_points, |v| local_of[v as usize]),
            contact_stiffness: pick(&contact_stiffness),
            continuation: continuation.restricted(&points),
            f_ext: nodes
                .iter()
                .flat_map(|&v| f_ext[d * v as usize..d * v as usize + d].iter().copied())
                .collect(),
            rigid: rigid.restricted(&nodes),
            bodies: bodies.restricted(&nodes, &mesh, &sub.cells),
        };
        let part = Part {
            sub,
            mesh,
            nodes,
            points,
        };
        Ok((restricted, part))
    }
}

impl System {
    /// [`System::with_linear_solver`], or with `split` [`System::for_solve`].
    pub(super) fn build(
        problem: &Problem,
        settings: &SolverSettings,
        kind: LinearSolver,
        split: bool,
    ) -> Result<(Self, Option<Problem>)> {
        let t0 = Instant::now();
        let dofs = problem.dof_map();
        let d = problem.mesh.dim();
        // Several processes with the distributed solver: the nodes split among them
        // (PETSc's rows and the cells each assembles follow the split), each holding the
        // cells around its own nodes (only that solver can take partial matrices), their
        // nodes, its contact points and every array of the solve on that part alone.
        // Otherwise every process holds the whole system.
        let processes = settings.processes;
        let distributed = split
            && kind
                .resolve(d, dofs.n_free(), &processes)
                .splits_the_problem(&processes);
        let (whole, whole_counts) = SetUp::of_whole(problem, settings, dofs)?;
        // On several processes, this process's part of all that ([`SetUp::restricted`]).
        let (set_up, part) = if distributed {
            let (restricted, part) = whole.restricted(problem, &processes)?;
            (restricted, Some(part))
        } else {
            (whole, None)
        };
        let SetUp {
            dofs,
            contact,
            contact_stiffness,
            continuation,
            f_ext,
            rigid,
            bodies,
        } = set_up;
        let mesh = part.as_ref().map_or(&problem.mesh, |p| &p.mesh);
        // The contact pairs couple each slave node with its master facet's nodes: the
        // matrix's graph (its pattern and fill-reducing ordering) has those couplings too.
        let coupled;
        let mesh = if contact.has_pairs() {
            coupled = mesh.clone().with_couplings(contact.couplings(d));
            &coupled
        } else {
            mesh
        };
        // This process's rows: the DOFs of its own nodes (all of them on one process).
        let own_dofs = part
            .as_ref()
            .map_or(dofs.n_dofs(), |p| d * p.sub.nodes().len());
        let pattern = SystemPattern::new(mesh, &dofs)?;
        let nnz = match &part {
            None => pattern.nnz(),
            Some(_) => whole_nnz(
                &pattern,
                &dofs,
                own_dofs,
                whole_counts.equations,
                &processes,
            )?,
        };
        let point_cells = point_cells(mesh, &contact, part.as_ref());
        let t1 = Instant::now();
        let linear_solver =
            prepare_linear_solver(problem, settings, kind, mesh, &dofs, &pattern, &part)?;
        let t2 = Instant::now();
        let contact_slots = contact_slots(&contact, d, dofs.equations(), &pattern);
        let rigid_slots = rigid_slots(&rigid, &dofs, &pattern, own_dofs);
        let mut workspace = Workspace::new(match settings.threads {
            0 => rayon::current_num_threads(),
            t => t,
        });
        // The translation the supports carry each body by: the solve is for the
        // displacement beyond it (the contact points already meet the obstacles there).
        let placement = problem.carried_displacement().map(|c| match &part {
            None => c,
            Some(Part { nodes, .. }) => nodes
                .iter()
                .flat_map(|&v| c[d * v as usize..d * v as usize + d].iter().copied())
                .collect(),
        });
        let (subdomain, share, processes, part_problem) = match part {
            None => (None, Share::whole(), Processes::alone(), None),
            Some(Part {
                sub,
                mesh,
                nodes,
                points,
            }) => {
                workspace.owned_cells = Some(sub.owned);
                let whole = [
                    problem.mesh.n_nodes(),
                    whole_counts.contact_points,
                    problem.mesh.n_cells(),
                ];
                let own_points = contact.owned();
                let share = Share::of(d, &sub, nodes, &dofs, points, own_points, whole, processes);
                let part_problem = part_problem(problem, mesh);
                (Some(sub), share, processes, Some(part_problem))
            }
        };
        let system = System {
            dofs,
            pattern,
            nnz,
            whole: whole_counts,
            linear_solver,
            contact,
            contact_slots,
            contact_stiffness,
            point_cells,
            continuation,
            f_ext,
            bodies,
            setup_time: ((t1 - t0).as_secs_f64(), (t2 - t1).as_secs_f64()),
            workspace,
            rigid,
            rigid_slots,
            subdomain,
            share,
            processes,
            scales: None,
            placement,
        };
        Ok((system, part_problem))
    }
}

/// The cells around each contact point of `contact` on `mesh` ([`System::point_cells`]); on
/// a process's part, in the whole mesh's order, as on one process.
fn point_cells(mesh: &Mesh, contact: &ContactNodes, part: Option<&Part>) -> (Vec<usize>, Vec<u32>) {
    let mut point_cells = cells_around(mesh, &contact.node);
    if let Some(Part { sub, .. }) = part {
        // The cells around each point in the whole mesh's order, as on one process.
        for i in 0..contact.len() {
            let (a, b) = (point_cells.0[i], point_cells.0[i + 1]);
            point_cells.1[a..b].sort_unstable_by_key(|&c| sub.cells[c as usize]);
        }
    }
    point_cells
}

/// The linear solver `kind` prepared on `pattern` (of `mesh`, DOF map `dofs`): the
/// symbolic analysis, the multigrid grids, or the distributed matrix's layout over the
/// partition of `part` (one range on one process).
///
/// # Errors
/// Those of [`LinearSolver::prepare`].
fn prepare_linear_solver(
    problem: &Problem,
    settings: &SolverSettings,
    kind: LinearSolver,
    mesh: &Mesh,
    dofs: &DofMap,
    pattern: &SystemPattern,
    part: &Option<Part>,
) -> Result<Box<dyn SpdSolver>> {
    let one;
    let partition = match part {
        Some(p) => &p.sub.partition,
        None => {
            one = Partition::ranges(problem.mesh.n_nodes(), 1);
            &one
        }
    };
    let options = PrepareOptions {
        ordering: settings.ordering,
        par: parallelism(settings.factorization_threads),
        petsc_options: &settings.petsc.options,
        placement: Placement {
            partition,
            nodes: part.as_ref().map(|p| p.nodes.as_slice()),
        },
        processes: settings.processes,
    };
    kind.prepare(mesh, dofs.equations(), pattern, &options)
}

/// The problem of a process's part: `problem`'s conditions on the part's mesh `mesh`.
fn part_problem(problem: &Problem, mesh: Mesh) -> Problem {
    Problem {
        mesh,
        materials: problem.materials.clone(),
        region_material: problem.region_material.clone(),
        plane: problem.plane,
        dirichlet: problem.dirichlet.clone(),
        tractions: problem.tractions.clone(),
        body_force: problem.body_force,
        contact: problem.contact.clone(),
    }
}

/// The diagonal slots in `pattern` of the free DOFs (of `dofs`, below `rows`) on which
/// `rigid` shifts the Newton matrix: this process's rows of them.
fn rigid_slots(
    rigid: &RigidMotions,
    dofs: &DofMap,
    pattern: &SystemPattern,
    rows: usize,
) -> Vec<usize> {
    rigid
        .shifted_dofs()
        .into_iter()
        .filter(|&k| k < rows && !dofs.is_fixed(k))
        .map(|k| pattern.diagonal_slot(dofs.equation(k) as usize))
        .collect()
}

/// The entries of the upper triangle of the whole reduced system, from this process's
/// `pattern` (its part's, DOF map `dofs`, its own DOFs the first `own_dofs`): every free
/// own row's entries in both triangles, summed over the processes, give twice the upper
/// triangle less the diagonal (`n_free` equations in all).
///
/// # Errors
/// MPI's.
fn whole_nnz(
    pattern: &SystemPattern,
    dofs: &DofMap,
    own_dofs: usize,
    n_free: usize,
    processes: &Processes,
) -> Result<usize> {
    let own_eqs = dofs.equations()[..own_dofs]
        .iter()
        .filter(|&&eq| eq != FIXED)
        .count();
    let (col_ptr, row_idx) = (pattern.col_ptr(), pattern.row_idx());
    // Own equations are the first ones of the part's numbering.
    let mut full = 0usize;
    for j in 0..pattern.n() {
        for &i in &row_idx[col_ptr[j]..col_ptr[j + 1]] {
            full += usize::from(j < own_eqs);
            full += usize::from(i != j && i < own_eqs);
        }
    }
    // Counts below 2^53 add exactly in floating point.
    let mut total = [full as f64];
    processes.sum(&mut total)?;
    Ok((total[0] as usize + n_free) / 2)
}

/// The cells around each of the nodes `nodes`, in compressed rows (see
/// [`System::point_cells`]).
fn cells_around(mesh: &Mesh, nodes: &[u32]) -> (Vec<usize>, Vec<u32>) {
    let mut wanted = vec![u32::MAX; mesh.n_nodes()];
    let mut lists: Vec<Vec<u32>> = vec![Vec::new(); nodes.len()];
    let mut first_point = Vec::with_capacity(nodes.len());
    for (i, &v) in nodes.iter().enumerate() {
        if wanted[v as usize] == u32::MAX {
            wanted[v as usize] = i as u32;
        }
        first_point.push(wanted[v as usize] as usize);
    }
    for c in 0..mesh.n_cells() {
        for &v in mesh.cell(c) {
            let i = wanted[v as usize];
            if i != u32::MAX {
                lists[i as usize].push(c as u32);
            }
        }
    }
    let mut offsets = vec![0];
    let mut cells = Vec::new();
    for &j in &first_point {
        cells.extend_from_slice(&lists[j]);
        offsets.push(cells.len());
    }
    (offsets, cells)
}
