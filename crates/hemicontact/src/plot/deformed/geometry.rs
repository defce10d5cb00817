//! The geometry of a deformed-mesh panel in world coordinates (m): the magnified deformed
//! positions in the plane of the drawing ([`View`]), the facets and nodes facing the
//! viewer, the rigid foundations, the box that the drawing must hold, the interfaces
//! between materials, and the map to pixels ([`Frame`]).

use crate::mesh::Mesh;
use crate::plot::scales::magnification;
use crate::problem::Problem;
use crate::solver::Solution;

/// A segment in world coordinates (m), in the plane of the drawing.
pub(super) type Segment = ([f64; 2], [f64; 2]);

/// The plane of the drawing (x–y in 2D, x–z front view in 3D) and the magnified deformed
/// positions of the nodes in it.
pub(super) struct View<'a> {
    /// The mesh drawn.
    pub(super) mesh: &'a Mesh,
    /// The solution drawn (its displacements, m).
    solution: &'a Solution,
    /// The mesh's dimension.
    pub(super) d: usize,
    /// The coordinate drawn upwards: y in 2D, z in 3D.
    pub(super) iy: usize,
    /// The label of the vertical axis.
    pub(super) view_y: &'static str,
    /// The undeformed bounding box (m).
    pub(super) blo: [f64; 3],
    /// The undeformed bounding box (m).
    pub(super) bhi: [f64; 3],
    /// The body's size: the largest side of its bounding box (m).
    pub(super) size: f64,
    /// The displacement magnification.
    pub(super) m: f64,
}

impl<'a> View<'a> {
    /// The view of `solution` on `problem`'s mesh, magnified by
    /// [`magnification`] of the largest displacement.
    pub(super) fn new(problem: &'a Problem, solution: &'a Solution) -> Self {
        let mesh = &problem.mesh;
        let d = mesh.dim();
        // The plane of the drawing: x–y in 2D, x–z (front view) in 3D.
        let (iy, view_y) = if d == 2 { (1, "y (m)") } else { (2, "z (m)") };
        let (blo, bhi) = mesh.bounding_box();
        let size = (bhi[0] - blo[0]).max(bhi[1] - blo[1]).max(bhi[2] - blo[2]);
        let max_u = (0..mesh.n_nodes())
            .map(|n| {
                (0..d)
                    .map(|i| solution.u[d * n + i].powi(2))
                    .sum::<f64>()
                    .sqrt()
            })
            .fold(0.0, f64::max);
        let m = magnification(size, max_u);
        View {
            mesh,
            solution,
            d,
            iy,
            view_y,
            blo,
            bhi,
            size,
            m,
        }
    }

    /// Node `n` in the plane of the drawing, displaced by `s` times the magnified
    /// displacement (`s = 0`: undeformed, `s = 1`: deformed) (m).
    pub(super) fn pos(&self, n: usize, s: f64) -> [f64; 2] {
        let (mesh, solution, d, iy, m) = (self.mesh, self.solution, self.d, self.iy, self.m);
        let x = mesh.node(n);
        [
            x[0] + s * m * solution.u[d * n],
            x[iy] + s * m * solution.u[d * n + iy],
        ]
    }
}

/// The facets drawn: all in 2D; in 3D those facing the viewer.
pub(super) fn facing_facets(mesh: &Mesh) -> Vec<usize> {
    let d = mesh.dim();
    (0..mesh.n_facets())
        .filter(|&f| d == 2 || mesh.facet_measure_normal(f).1[1] < -0.5)
        .collect()
}

/// The nodes drawn: all in 2D; in 3D those of the facets facing the viewer.
pub(super) fn visible_nodes(mesh: &Mesh, facing: &[usize]) -> Vec<bool> {
    let d = mesh.dim();
    let mut visible = vec![d == 2; mesh.n_nodes()];
    for &f in facing {
        for &v in mesh.facet(f) {
            visible[v as usize] = true;
        }
    }
    visible
}

/// The rigid foundations as segments (m).
///
/// Foundations: contact facets shifted by the magnified gap along their normals (in 3D
/// the facets seen edge-on). Against an obstacle each node moves by its own gap along its
/// own normal, which at true scale puts it on its closest point of the obstacle: drawn
/// are the edges of the part's facets in the plane of the drawing (in 3D, those on the
/// face nearest the viewer) whose points fall within the body's box widened by a fifth
/// of its size (far from the body the magnified gaps would distort the shape).
pub(super) fn foundations(problem: &Problem, view: &View) -> Vec<Segment> {
    let mesh = &problem.mesh;
    let (d, iy, m, size, blo, bhi) = (view.d, view.iy, view.m, view.size, view.blo, view.bhi);
    let pos = |n: usize, s: f64| view.pos(n, s);
    let near = |p: [f64; 2]| {
        let margin = 0.2 * size;
        p[0] >= blo[0] - margin
            && p[0] <= bhi[0] + margin
            && p[1] >= blo[iy] - margin
            && p[1] <= bhi[iy] + margin
    };
    let points = problem.contact_nodes().unwrap_or_default();
    let mut shift = vec![[0.0; 2]; mesh.n_nodes()];
    let mut foundation = Vec::new();
    for (b, cb) in problem.contact.iter().enumerate() {
        if cb.against.is_some() {
            // Against another body: that body, drawn deformed, is the other side.
            continue;
        }
        if cb.obstacle.is_some() {
            for i in (0..points.len()).filter(|&i| points.boundary[i] as usize == b) {
                let (g, n) = (points.gap[i], points.normal[i]);
                shift[points.node[i] as usize] = [m * g * n[0], m * g * n[iy]];
            }
        }
        for f in mesh.part_facets(cb.part) {
            let (_, nrm) = mesh.facet_measure_normal(f);
            if d == 3 && nrm[1].abs() > 0.5 {
                continue;
            }
            let v = mesh.facet(f);
            let sh = |node: u32| match cb.obstacle {
                Some(_) => shift[node as usize],
                None => [m * cb.gap * nrm[0], m * cb.gap * nrm[iy]],
            };
            for k in 0..v.len() {
                if d == 2 && k == 1 {
                    break;
                }
                let (va, vb) = (v[k], v[(k + 1) % v.len()]);
                let (a, b) = (pos(va as usize, 0.0), pos(vb as usize, 0.0));
                let (sa, sb) = (sh(va), sh(vb));
                let segment = ([a[0] + sa[0], a[1] + sa[1]], [b[0] + sb[0], b[1] + sb[1]]);
                if cb.obstacle.is_some() {
                    let front = |v: u32| d == 2 || mesh.node(v as usize)[1] == blo[1];
                    if !(front(va) && front(vb) && near(segment.0) && near(segment.1)) {
                        continue;
                    }
                }
                foundation.push(segment);
            }
        }
    }
    foundation
}

/// The box (m) that the drawing must hold: the undeformed bounding box, the deformed
/// visible nodes and the foundations.
pub(super) fn extent(
    view: &View,
    visible: &[bool],
    foundation: &[Segment],
) -> ([f64; 2], [f64; 2]) {
    let (mesh, iy, blo, bhi) = (view.mesh, view.iy, view.blo, view.bhi);
    let pos = |n: usize, s: f64| view.pos(n, s);
    let mut lo = [blo[0], blo[iy]];
    let mut hi = [bhi[0], bhi[iy]];
    let mut grow = |p: [f64; 2]| {
        for i in 0..2 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    };
    for n in (0..mesh.n_nodes()).filter(|&n| visible[n]) {
        grow(pos(n, 1.0));
    }
    for (a, b) in foundation {
        grow(*a);
        grow(*b);
    }
    (lo, hi)
}

/// The edges of a 2D mesh between two cells of different materials (node pairs).
pub(super) fn material_interfaces(problem: &Problem) -> Vec<(u32, u32)> {
    let mesh = &problem.mesh;
    let mut first = std::collections::HashMap::new();
    let mut out = Vec::new();
    for c in 0..mesh.n_cells() {
        let v = mesh.cell(c);
        for k in 0..3 {
            let (a, b) = (v[k], v[(k + 1) % 3]);
            let edge = (a.min(b), a.max(b));
            match first.insert(edge, c) {
                Some(other) if problem.cell_material(other) != problem.cell_material(c) => {
                    out.push(edge);
                }
                _ => {}
            }
        }
    }
    out
}

/// The map from world coordinates (y up) to the pixels of a drawing area: equal scales,
/// the world box `lo..hi` grown by a 6 % margin, centred across the area and at its top.
pub(super) struct Frame {
    /// The world box drawn, margin included (m).
    pub(super) lo: [f64; 2],
    /// The world box drawn, margin included (m).
    pub(super) hi: [f64; 2],
    /// Pixels per metre.
    pub(super) scale: f64,
    /// The pixel position of the box's top-left corner.
    origin: [f64; 2],
}

impl Frame {
    /// The frame of the world box `lo..hi` (m) in the pixel rectangle `area`
    /// `(x0, y0, w, h)`.
    pub(super) fn new(lo: [f64; 2], hi: [f64; 2], area: [f64; 4]) -> Self {
        let [x0, y0, w, h] = area;
        let h = h.max(1.0);
        let margin = 0.06 * (hi[0] - lo[0]).max(hi[1] - lo[1]).max(f64::MIN_POSITIVE);
        let lo = [lo[0] - margin, lo[1] - margin];
        let hi = [hi[0] + margin, hi[1] + margin];
        let scale = (w / (hi[0] - lo[0])).min(h / (hi[1] - lo[1]));
        let origin = [x0 + 0.5 * (w - scale * (hi[0] - lo[0])), y0];
        Frame {
            lo,
            hi,
            scale,
            origin,
        }
    }

    /// The pixel position of the world point `p` (m).
    pub(super) fn px(&self, p: [f64; 2]) -> [f64; 2] {
        [
            self.origin[0] + self.scale * (p[0] - self.lo[0]),
            self.origin[1] + self.scale * (self.hi[1] - p[1]),
        ]
    }
}
