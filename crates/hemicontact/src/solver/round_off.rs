//! The round-off floor of every residual: no tolerance below what floating point can
//! resolve there, and no residual excused by another part's round-off.
//!
//! An entry of the gradient `∇E` (a nodal force) is a sum of terms that cancel: where a
//! stiff part is moved as a whole by a displacement u, its cells' strains are sums of terms
//! `|∇φ| u` that cancel to a small strain, and the entry is polluted by round-off of about
//! the machine epsilon ε times the sum of the magnitudes of its terms, `|K| |u|` per row:
//! the stiff neighbour's stiffness times its displacement. No iteration can resolve an
//! entry below that (the displacement itself is only represented to `ε |u|`). Beside a part
//! 10¹² times softer, or a body moved 10⁵ times farther, that floor lies far above a
//! tolerance taken relative to the soft part's or the small body's own forces.
//!
//! The **floor** of entry k is `φ_k = c ε a_k`, with `a_k` the sum of the magnitudes of
//! the terms that entry sums ([`crate::assembly::magnitudes`]: the cells' element forces
//! with their strains taken term by term, the external force, the contact points' forces
//! with their kinematics and gaps) and c = [`ROUND_OFF_FACTOR`]. An entry no larger than
//! its floor is round-off and counts as zero ([`above_floor`]); an entry above it counts
//! whole. The floor is per entry: a soft region's nodes away from its stiff neighbour keep
//! the floors of their own forces.
//!
//! What the entries cannot resolve one by one, their sums along rigid motions may: a stiff
//! piece's cells do no work on its rigid motions, round-off included, so the resultant of
//! the residual over a region ([`super::regions`]: net force and moment) is known to the
//! round-off of the terms that do not cancel in it (the cells of other regions at its
//! nodes, cells with a prescribed DOF, loads, contacts) and of the cells' stresses as
//! computed. A soft bar stretched by a wrong amount beyond which a stiff bar is moved as a
//! whole leaves every node within its floor but a net force on the stiff bar. Each
//! region's resultants, beyond their own floors, join its body's residual.
//!
//! One computation ([`System::round_off_floors`]) and one measure ([`body_residuals`])
//! serve every test that compares a residual with a tolerance: Newton's stopping test
//! ([`super::convex::ConvexProblem`], where a body left with nothing but round-off is also
//! not moved further: it would move by round-off, and the energy and the line search with
//! it, while another body converges) and the certificate's equilibrium and contact laws
//! ([`super::certificate`]; a law residual against the floor of its node's force,
//! [`point_floor`]). On a problem without large cancellations `a_k` is of the size of the
//! forces balanced at the node and the floor about 10⁻¹⁴ of them: nothing changes.

use super::frozen::Frozen;
use super::local_scales::Bodies;
use super::regions::modes;
use super::System;
use crate::assembly::BulkAssembler;
use crate::contact::NormalResponse;
use crate::mesh::Mesh;
use crate::parallel::Share;
use crate::problem::Problem;

/// The factor c of the floor `c ε a_k` over the machine epsilon ε and the magnitudes `a_k`
/// of the terms an entry sums: 8. The magnitudes already add every term and product in
/// absolute value at every stage (strain, stress, element force, sum over the cells), an
/// upper bound of the round-off that each rounding adds at most ε of; every case of the
/// tests (contrasts of stiffness to 10¹², bodies moved 10⁵ times farther than their
/// neighbour, a compliance 10⁸ times stiffer) converges with c = 1, and 8 leaves a margin.
pub const ROUND_OFF_FACTOR: f64 = 8.0;

/// The round-off floors of a residual ([`System::round_off_floors`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Floors {
    /// The floor of every entry (DOF order, N).
    pub dof: Vec<f64>,
    /// The floor of every resultant of every region along each of its rigid modes (region
    /// r's from `r · modes(d)`, N; [`super::regions::Regions::resultants`]).
    pub region: Vec<f64>,
}

/// The entry `value` where it is above its round-off floor `floor`, else 0 (round-off).
#[inline]
pub fn above_floor(value: f64, floor: f64) -> f64 {
    if value.abs() <= floor {
        0.0
    } else {
        value
    }
}

/// The floor of the force at node `v` (dimension `d`) over its components not `fixed`, from
/// the floors `floor` of the entries (DOF order): their Euclidean norm.
pub fn point_floor(floor: &[f64], d: usize, v: usize, fixed: impl Fn(usize) -> bool) -> f64 {
    (0..d)
        .filter(|&k| !fixed(d * v + k))
        .map(|k| floor[d * v + k].powi(2))
        .sum::<f64>()
        .sqrt()
}

/// The residual of every body of `bodies` (into `out`), counting only what lies above the
/// round-off floors `floors`: the Euclidean norm of the entries `row(k)` above their floors
/// (0 for an entry left out) with the resultants of the body's regions along their rigid
/// modes of the entries `all(k)` (0 for a prescribed DOF) above theirs. Sums over what
/// `share` counts, then over the processes.
pub fn body_residuals(
    bodies: &Bodies,
    mesh: &Mesh,
    share: &Share,
    floors: &Floors,
    row: impl Fn(usize) -> f64,
    all: impl Fn(usize) -> f64,
    out: &mut Vec<f64>,
) {
    let d = mesh.dim();
    let n = d * mesh.n_nodes();
    bodies.norms(share, d, n, |k| above_floor(row(k), floors.dof[k]), out);
    let regions = &bodies.regions;
    let mut resultant = Vec::new();
    regions.resultants(mesh, share, all, &mut resultant);
    let nm = modes(d);
    for (r, &b) in regions.body.iter().enumerate() {
        let Some(s) = out.get_mut(b as usize) else {
            continue;
        };
        let extra: f64 = (0..nm)
            .map(|j| above_floor(resultant[r * nm + j], floors.region[r * nm + j]).powi(2))
            .sum();
        if extra > 0.0 {
            *s = s.hypot(extra.sqrt());
        }
    }
}

impl System {
    /// The round-off floors of the entries of the gradient and of the regions' resultants
    /// at `u` for the frozen quantities `frozen` and the responses `responses` of
    /// user-defined compliance laws at `u` (see the module documentation), into `out`: the
    /// entries' exact at the DOFs of the nodes this process owns, the resultants' summed
    /// over the processes.
    pub fn round_off_floors(
        &self,
        problem: &Problem,
        u: &[f64],
        frozen: &Frozen,
        responses: &[NormalResponse],
        out: &mut Floors,
    ) {
        let mesh = &problem.mesh;
        let d = mesh.dim();
        let (share, fixed) = (self.share(), |k: usize| self.dofs.is_fixed(k));
        // The terms that cancel in no sum: loads and contacts, at every DOF.
        let dof = &mut out.dof;
        dof.clear();
        dof.extend(self.f_ext.iter().map(|f| f.abs()));
        let mut ca = self.contact_assembler(problem);
        ca.responses = responses;
        ca.term_magnitudes(u, &frozen.contact(), dof);
        let regions = &self.bodies.regions;
        let nm = modes(d);
        let region = &mut out.region;
        region.clear();
        region.resize(regions.count * nm, 0.0);
        for (k, &a) in dof.iter().enumerate() {
            if !share.counts_dof(k) || fixed(k) {
                continue;
            }
            let (v, i) = (k / d, k % d);
            for &r in regions.of_node(v) {
                let r = r as usize;
                for j in 0..nm {
                    region[r * nm + j] += regions.mode(r, j, d, mesh.node(v), i).abs() * a;
                }
            }
        }
        let bulk = BulkAssembler {
            ideal: super::system::evaluate::ideal_locking(
                &self.continuation.penalties,
                problem,
                frozen,
            ),
            ..BulkAssembler::of(problem, mesh)
        };
        bulk.cell_magnitudes(u, |c, m| {
            let cell = mesh.cell(c);
            let own = regions.of_cell[c] as usize;
            // Along a rigid mode of the cell's own region, its terms cancel when all those
            // the mode moves are summed: none of them at a prescribed DOF.
            let mut whole = [true; 6];
            for p in 0..d * cell.len() {
                let v = cell[p / d] as usize;
                if fixed(d * v + p % d) {
                    for (j, w) in whole.iter_mut().enumerate().take(nm) {
                        *w &= regions.mode(own, j, d, mesh.node(v), p % d) == 0.0;
                    }
                }
            }
            for p in 0..d * cell.len() {
                let v = cell[p / d] as usize;
                let k = d * v + p % d;
                dof[k] += m.term[p];
                if fixed(k) {
                    continue;
                }
                let x = mesh.node(v);
                for &r in regions.of_node(v) {
                    let r = r as usize;
                    for j in 0..nm {
                        let mode = regions.mode(r, j, d, x, p % d).abs();
                        if r == own && whole[j] {
                            if share.counts_cell(c) {
                                region[r * nm + j] += mode * m.rigid[p];
                            }
                        } else if share.counts_dof(k) {
                            region[r * nm + j] += mode * m.term[p];
                        }
                    }
                }
            }
        });
        share.sum(region);
        let scale = ROUND_OFF_FACTOR * f64::EPSILON;
        dof.iter_mut().for_each(|a| *a *= scale);
        region.iter_mut().for_each(|a| *a *= scale);
    }
}

/// The round-off of the displacement `u` itself in the energy norm of every body (into
/// `out`): `c ε (Σ_T |T| W(e_T))^{1/2}` over the body's cells, `e_T` the magnitudes of the
/// terms of the cell's strain ([`crate::assembly::magnitudes::strain_magnitudes`]) and W
/// the cell's Hooke law `hooke(c)`. A change of u between outer iterations below it is no
/// change; over the cells `share` counts, then over the processes.
pub fn change_floors(
    bodies: &Bodies,
    share: &Share,
    mesh: &Mesh,
    hooke: &dyn Fn(usize) -> crate::material::Hooke,
    u: &[f64],
    out: &mut Vec<f64>,
) {
    use crate::material::StrainEnergy;
    out.clear();
    out.resize(bodies.count, 0.0);
    for c in 0..mesh.n_cells() {
        let b = bodies.of_node[mesh.cell(c)[0] as usize] as usize;
        if b >= out.len() || !share.counts_cell(c) {
            continue;
        }
        let (measure, e) = crate::assembly::magnitudes::strain_magnitudes(mesh, u, c);
        out[b] += measure * hooke(c).energy(&e);
    }
    share.sum(out);
    let scale = ROUND_OFF_FACTOR * f64::EPSILON;
    out.iter_mut().for_each(|s| *s = scale * s.max(0.0).sqrt());
}
