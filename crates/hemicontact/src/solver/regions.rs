//! The regions of a body over which residuals are summed: the connected pieces of one
//! material, and their rigid-mode resultants.
//!
//! Round-off that no single entry of a residual can resolve may still cancel in a sum of
//! entries. Where a stiff piece is moved as a whole (a stiff bar beyond a soft one, a stiff
//! block pressed into a soft one), each of its nodal forces is known only to the machine
//! epsilon times its stiffness times its displacement ([`super::round_off`]), far above the
//! forces the soft neighbour passes to it. But every cell's forces on its nodes do no work
//! on a rigid motion, round-off included: summed over the piece's nodes along a rigid
//! motion, the stiff cells' terms cancel, and what remains is the force the neighbours,
//! the loads and the contacts exert on the piece, known as accurately as those are. A soft
//! part stretched by a wrong amount shows there, as a net force on the stiff piece beyond
//! it; no single node sees it.
//!
//! A **region** is a connected set of cells of one material in one body (cells that share
//! a node belong to the same region); a body of one material is one region. Its **rigid
//! modes** are the d translations and the d(d−1)/2 rotations about the centre of its
//! bounding box, a rotation's displacement divided by the box's half-diagonal ρ (so that
//! every mode moves no node by more than 1). The **resultant** of a residual r over a region
//! along a mode m is `Σ_k m_k r_k` over the region's free DOFs: its net force, and its net
//! moment over ρ, both forces.

use crate::mesh::Mesh;
use crate::parallel::Share;

/// The regions of a mesh; see the module documentation.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Regions {
    /// The region of each cell of the mesh held (on a process, of its part's cells).
    pub of_cell: Vec<u32>,
    /// Number of regions of the whole problem.
    pub count: usize,
    /// The body of each region ([`super::local_scales::Bodies::of_node`]).
    pub body: Vec<u32>,
    /// The centre of each region's bounding box (m).
    pub center: Vec<[f64; 3]>,
    /// The half-diagonal ρ of each region's bounding box (m; at least the smallest positive
    /// number).
    pub radius: Vec<f64>,
    /// The regions of each node in compressed rows: those of node v are
    /// `node_regions.1[node_regions.0[v]..node_regions.0[v + 1]]`.
    pub node_regions: (Vec<usize>, Vec<u32>),
}

/// The number of rigid modes in dimension `d`: 3 in 2D, 6 in 3D.
pub fn modes(d: usize) -> usize {
    d + d * (d - 1) / 2
}

impl Regions {
    /// The regions of `mesh` whose cell `c` has the material `material(c)`, its nodes in
    /// the bodies `body_of_node` (`u32::MAX`: in no cell).
    pub fn new(mesh: &Mesh, material: impl Fn(usize) -> usize, body_of_node: &[u32]) -> Self {
        let n_cells = mesh.n_cells();
        // Union-find over the cells: two cells of one material sharing a node are joined.
        let mut parent: Vec<u32> = (0..n_cells as u32).collect();
        fn root(parent: &mut [u32], mut c: u32) -> u32 {
            while parent[c as usize] != c {
                let up = parent[parent[c as usize] as usize];
                parent[c as usize] = up;
                c = up;
            }
            c
        }
        let mut anchor: std::collections::HashMap<(u32, usize), u32> = Default::default();
        for c in 0..n_cells {
            let m = material(c);
            for &v in mesh.cell(c) {
                let a = *anchor.entry((v, m)).or_insert(c as u32);
                let (ra, rc) = (root(&mut parent, a), root(&mut parent, c as u32));
                if ra != rc {
                    parent[ra.max(rc) as usize] = ra.min(rc);
                }
            }
        }
        // Regions numbered in the order of their first cell.
        let mut number = vec![u32::MAX; n_cells];
        let mut of_cell = Vec::with_capacity(n_cells);
        let mut body = Vec::new();
        for c in 0..n_cells {
            let r = root(&mut parent, c as u32) as usize;
            if number[r] == u32::MAX {
                number[r] = body.len() as u32;
                body.push(body_of_node[mesh.cell(c)[0] as usize]);
            }
            of_cell.push(number[r]);
        }
        let count = body.len();
        let mut lo = vec![[f64::INFINITY; 3]; count];
        let mut hi = vec![[f64::NEG_INFINITY; 3]; count];
        let d = mesh.dim();
        for (c, &r) in of_cell.iter().enumerate() {
            for &v in mesh.cell(c) {
                let x = mesh.node(v as usize);
                for i in 0..d {
                    lo[r as usize][i] = lo[r as usize][i].min(x[i]);
                    hi[r as usize][i] = hi[r as usize][i].max(x[i]);
                }
            }
        }
        let mut center = vec![[0.0; 3]; count];
        let mut radius = vec![0.0; count];
        for r in 0..count {
            let mut diag = 0.0;
            for i in 0..d {
                center[r][i] = 0.5 * (lo[r][i] + hi[r][i]);
                diag += (hi[r][i] - lo[r][i]).powi(2);
            }
            radius[r] = (0.5 * diag.sqrt()).max(f64::MIN_POSITIVE);
        }
        let node_regions = node_regions(mesh, &of_cell);
        Regions {
            of_cell,
            count,
            body,
            center,
            radius,
            node_regions,
        }
    }

    /// These regions on a process's part `mesh`, whose cell p is the whole mesh's
    /// `cells[p]`.
    pub fn restricted(&self, mesh: &Mesh, cells: &[u32]) -> Regions {
        let of_cell: Vec<u32> = cells.iter().map(|&c| self.of_cell[c as usize]).collect();
        let node_regions = node_regions(mesh, &of_cell);
        Regions {
            of_cell,
            node_regions,
            ..self.clone()
        }
    }

    /// The regions of node `v`.
    pub fn of_node(&self, v: usize) -> &[u32] {
        let (offsets, ids) = &self.node_regions;
        &ids[offsets[v]..offsets[v + 1]]
    }

    /// Along rigid mode `j` of region `r`, the displacement of DOF `i` of the node at `x`
    /// (dimension `d`): 1 or 0 for a translation, `(e_a × (x − c))_i / ρ` for the rotation
    /// about axis a (2D: the one about z).
    #[inline]
    pub fn mode(&self, r: usize, j: usize, d: usize, x: &[f64], i: usize) -> f64 {
        if j < d {
            return f64::from(u8::from(i == j));
        }
        let c = &self.center[r];
        let y = [
            x[0] - c[0],
            x[1] - c[1],
            if d == 3 { x[2] - c[2] } else { 0.0 },
        ];
        // Rotation about axis a: e_a × y.
        let a = if d == 2 { 2 } else { j - d };
        let cross = match (a, i) {
            (0, 1) => -y[2],
            (0, 2) => y[1],
            (1, 0) => y[2],
            (1, 2) => -y[0],
            (2, 0) => -y[1],
            (2, 1) => y[0],
            _ => 0.0,
        };
        cross / self.radius[r]
    }

    /// The resultants along every rigid mode of every region of the residual whose entry
    /// at DOF k is `value(k)` (0 for a DOF left out), into `out` (region r's
    /// [`modes`] values from `r · modes(d)`), over the DOFs `share` counts, then over the
    /// processes.
    pub fn resultants(
        &self,
        mesh: &Mesh,
        share: &Share,
        value: impl Fn(usize) -> f64,
        out: &mut Vec<f64>,
    ) {
        let d = mesh.dim();
        let nm = modes(d);
        out.clear();
        out.resize(self.count * nm, 0.0);
        for v in 0..mesh.n_nodes() {
            let x = mesh.node(v);
            for i in 0..d {
                let k = d * v + i;
                if !share.counts_dof(k) {
                    continue;
                }
                let g = value(k);
                if g == 0.0 {
                    continue;
                }
                for &r in self.of_node(v) {
                    let r = r as usize;
                    for j in 0..nm {
                        out[r * nm + j] += self.mode(r, j, d, x, i) * g;
                    }
                }
            }
        }
        share.sum(out);
    }
}

/// The regions of every node of `mesh` from the regions `of_cell` of its cells, in
/// compressed rows ([`Regions::node_regions`]).
fn node_regions(mesh: &Mesh, of_cell: &[u32]) -> (Vec<usize>, Vec<u32>) {
    let mut pairs: Vec<(u32, u32)> = Vec::with_capacity(of_cell.len() * (mesh.dim() + 1));
    for (c, &r) in of_cell.iter().enumerate() {
        pairs.extend(mesh.cell(c).iter().map(|&v| (v, r)));
    }
    pairs.sort_unstable();
    pairs.dedup();
    let mut offsets = vec![0usize; mesh.n_nodes() + 1];
    for &(v, _) in &pairs {
        offsets[v as usize + 1] += 1;
    }
    for v in 0..mesh.n_nodes() {
        offsets[v + 1] += offsets[v];
    }
    (offsets, pairs.into_iter().map(|(_, r)| r).collect())
}
