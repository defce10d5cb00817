//! The deformed mesh with the interface forces on Γ_C (the paper's Fig. 2), and several
//! cases side by side (its Fig. 3).
//!
//! Drawn, in world coordinates mapped to the panel (y up, equal scales, displacements at
//! true scale): the undeformed boundary (dashed grey), the deformed mesh (thin), the
//! deformed boundary, the rigid foundations (thick black: the contact facets shifted by the
//! gap along their normals), the contact nodes coloured by status (grey separated, blue
//! stick, red slip) and the interface forces (green arrows, the force of the foundation on
//! the body divided by the node's weight, i.e. the traction, scaled so the largest arrow is
//! 12 % of the panel; the scale is printed). A 3D solution is drawn as a front view
//! (orthographic projection on the x–z plane).

use super::{Anchor, Figure, Prim, Rgb};
use crate::problem::Problem;
use crate::solver::{ContactResult, FrictionState, NormalState, Solution};

const GREY: Rgb = [150, 150, 150];
const MESH: Rgb = [120, 140, 175];
const DARK: Rgb = [30, 30, 30];
const GREEN: Rgb = [0, 140, 60];
const BLUE: Rgb = [20, 80, 220];
const RED: Rgb = [220, 30, 30];

/// Marker colour of a contact point: its friction state (grey: no friction force).
fn status_color(c: &ContactResult) -> Rgb {
    match c.friction_state {
        FrictionState::None => GREY,
        FrictionState::Stick => BLUE,
        FrictionState::Slip => RED,
    }
}

/// Whether a contact point touches its foundation (normal state; drawn as a large marker).
fn touching(c: &ContactResult) -> bool {
    c.normal_state == NormalState::Contact
}

/// Primitives of one panel at pixel rectangle `(x0, y0, w, h)` with a title.
pub fn panel(problem: &Problem, solution: &Solution, rect: [f64; 4], title: &str) -> Vec<Prim> {
    let mesh = &problem.mesh;
    let d = mesh.dim();
    let mut prims = Vec::new();
    let [x0, y0, w, h] = rect;
    prims.push(Prim::Text {
        pos: [x0 + w / 2.0, y0 + 20.0],
        text: title.to_string(),
        size: 16.0,
        anchor: Anchor::Middle,
        color: DARK,
    });
    if d != 2 {
        prims.extend(front_view(problem, solution, rect));
        return prims;
    }
    let pos = |n: usize, deformed: bool| {
        let x = mesh.node(n);
        let s = if deformed { 1.0 } else { 0.0 };
        [
            x[0] + s * solution.u[2 * n],
            x[1] + s * solution.u[2 * n + 1],
        ]
    };
    // Foundation segments: contact facets shifted by the gap along their normals.
    let mut foundation = Vec::new();
    for cb in &problem.contact {
        for f in mesh.part_facets(cb.part) {
            let (_, nrm) = mesh.facet_measure_normal(f);
            let v = mesh.facet(f);
            let a = pos(v[0] as usize, false);
            let b = pos(v[1] as usize, false);
            let sh = [cb.gap * nrm[0], cb.gap * nrm[1]];
            foundation.push(([a[0] + sh[0], a[1] + sh[1]], [b[0] + sh[0], b[1] + sh[1]]));
        }
    }
    // World bounding box: deformed and undeformed nodes, foundations.
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    let mut grow = |p: [f64; 2]| {
        for i in 0..2 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    };
    for n in 0..mesh.n_nodes() {
        grow(pos(n, false));
        grow(pos(n, true));
    }
    for (a, b) in &foundation {
        grow(*a);
        grow(*b);
    }
    let frame = Frame::new(lo, hi, rect);
    let px = |p: [f64; 2]| frame.px(p);
    // Undeformed boundary, dashed.
    let mut undeformed = Vec::new();
    let mut boundary = Vec::new();
    for f in 0..mesh.n_facets() {
        let v = mesh.facet(f);
        undeformed.push((px(pos(v[0] as usize, false)), px(pos(v[1] as usize, false))));
        boundary.push((px(pos(v[0] as usize, true)), px(pos(v[1] as usize, true))));
    }
    for (a, b) in undeformed {
        prims.push(Prim::Polyline {
            points: vec![a, b],
            color: GREY,
            width: 1.0,
            dashed: true,
        });
    }
    // Deformed mesh edges (each interior edge once: a < b within the cell).
    let mut edges = Vec::with_capacity(3 * mesh.n_cells() / 2 + mesh.n_facets());
    for c in 0..mesh.n_cells() {
        let cell = mesh.cell(c);
        for k in 0..3 {
            let (a, b) = (cell[k] as usize, cell[(k + 1) % 3] as usize);
            // Shared edges appear in two cells with opposite orientation: draw one.
            if a < b {
                edges.push((px(pos(a, true)), px(pos(b, true))));
            }
        }
    }
    let mesh_width = if mesh.n_cells() > 20_000 { 0.3 } else { 0.6 };
    prims.push(Prim::Segments {
        segments: edges,
        color: MESH,
        width: mesh_width,
    });
    prims.push(Prim::Segments {
        segments: boundary,
        color: DARK,
        width: 1.5,
    });
    let fnd: Vec<_> = foundation.iter().map(|(a, b)| (px(*a), px(*b))).collect();
    prims.push(Prim::Segments {
        segments: fnd,
        color: DARK,
        width: 4.0,
    });
    // Interface forces as tractions (force / weight).
    let max_t = solution
        .contact
        .iter()
        .map(|c| (c.force[0].hypot(c.force[1])) / c.weight)
        .fold(0.0, f64::max);
    let arrow_px = 0.12 * w.min(h);
    for c in &solution.contact {
        let p = px(pos(c.node as usize, true));
        if touching(c) && max_t > 0.0 {
            let t = [c.force[0] / c.weight, c.force[1] / c.weight];
            let k = arrow_px / max_t;
            let tip = [p[0] + k * t[0], p[1] - k * t[1]];
            if (tip[0] - p[0]).hypot(tip[1] - p[1]) > 1.0 {
                prims.push(Prim::Arrow {
                    from: p,
                    to: tip,
                    color: GREEN,
                    width: 1.5,
                });
            }
        }
        let r = if touching(c) { 3.0 } else { 1.5 };
        prims.push(Prim::Circle {
            center: p,
            radius: r,
            fill: status_color(c),
        });
    }
    legend(&mut prims, solution, max_t, rect);
    prims
}

/// Space above (title) and below (legend) the drawing in a panel (px).
const TOP: f64 = 34.0;
const BOTTOM: f64 = 40.0;

/// The map from world coordinates (y up) to the pixels of a panel: equal scales, the world
/// box `lo..hi` grown by an 8 % margin and centred between title and legend.
struct Frame {
    lo: [f64; 2],
    hi: [f64; 2],
    scale: f64,
    origin: [f64; 2],
}

impl Frame {
    fn new(lo: [f64; 2], hi: [f64; 2], rect: [f64; 4]) -> Self {
        let [x0, y0, w, h] = rect;
        let margin = 0.08 * (hi[0] - lo[0]).max(hi[1] - lo[1]);
        let lo = [lo[0] - margin, lo[1] - margin];
        let hi = [hi[0] + margin, hi[1] + margin];
        let scale = (w / (hi[0] - lo[0])).min((h - TOP - BOTTOM) / (hi[1] - lo[1]));
        let origin = [
            x0 + 0.5 * (w - scale * (hi[0] - lo[0])),
            y0 + TOP + 0.5 * (h - TOP - BOTTOM - scale * (hi[1] - lo[1])),
        ];
        Frame {
            lo,
            hi,
            scale,
            origin,
        }
    }

    fn px(&self, p: [f64; 2]) -> [f64; 2] {
        [
            self.origin[0] + self.scale * (p[0] - self.lo[0]),
            self.origin[1] + self.scale * (self.hi[1] - p[1]),
        ]
    }
}

/// The legend (slip and stick counts, largest traction) at the bottom of the panel `rect`.
fn legend(prims: &mut Vec<Prim>, solution: &Solution, max_t: f64, rect: [f64; 4]) {
    let [x0, y0, _, h] = rect;
    let ly = y0 + h - 14.0;
    let cert = &solution.report.certificate;
    let (n_contact, n_stick, n_slip) = (cert.n_contact, cert.n_stick, cert.n_slip);
    let mut lx = x0 + 10.0;
    for (label, color) in [
        (format!("contact {n_contact}"), DARK),
        (format!("slip {n_slip}"), RED),
        (format!("stick {n_stick}"), BLUE),
        (format!("|t| max {max_t:.2e}"), GREEN),
    ] {
        prims.push(Prim::Circle {
            center: [lx + 4.0, ly - 4.0],
            radius: 4.0,
            fill: color,
        });
        prims.push(Prim::Text {
            pos: [lx + 12.0, ly],
            text: label.clone(),
            size: 12.0,
            anchor: Anchor::Start,
            color: DARK,
        });
        lx += 12.0 + super::text_width(&label, 12.0) + 20.0;
    }
}

/// A 3D solution seen from the front (looking along +y, x to the right, z up), in
/// orthographic projection: the deformed boundary facets that face the viewer (thin), the
/// rigid foundations of the contact boundaries seen edge-on (thick: their facets shifted by
/// the gap), the undeformed bounding box (dashed), the visible contact nodes coloured by
/// status, and their interface tractions (arrows, projected).
fn front_view(problem: &Problem, solution: &Solution, rect: [f64; 4]) -> Vec<Prim> {
    let mesh = &problem.mesh;
    let [x0, y0, w, h] = rect;
    let mut prims = Vec::new();
    let pos = |n: usize, s: f64| {
        let x = mesh.node(n);
        [
            x[0] + s * solution.u[3 * n],
            x[2] + s * solution.u[3 * n + 2],
        ]
    };
    let facing: Vec<usize> = (0..mesh.n_facets())
        .filter(|&f| mesh.facet_measure_normal(f).1[1] < -0.5)
        .collect();
    let mut visible = vec![false; mesh.n_nodes()];
    for &f in &facing {
        for &v in mesh.facet(f) {
            visible[v as usize] = true;
        }
    }
    let mut foundation = Vec::new();
    for cb in &problem.contact {
        for f in mesh.part_facets(cb.part) {
            let (_, nrm) = mesh.facet_measure_normal(f);
            if nrm[1].abs() > 0.5 {
                continue;
            }
            let v = mesh.facet(f);
            for k in 0..3 {
                let (a, b) = (pos(v[k] as usize, 0.0), pos(v[(k + 1) % 3] as usize, 0.0));
                let sh = [cb.gap * nrm[0], cb.gap * nrm[2]];
                foundation.push(([a[0] + sh[0], a[1] + sh[1]], [b[0] + sh[0], b[1] + sh[1]]));
            }
        }
    }
    let (blo, bhi) = mesh.bounding_box();
    let mut lo = [blo[0], blo[2]];
    let mut hi = [bhi[0], bhi[2]];
    let mut grow = |p: [f64; 2]| {
        for i in 0..2 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    };
    for n in (0..mesh.n_nodes()).filter(|&n| visible[n]) {
        grow(pos(n, 1.0));
    }
    for (a, b) in &foundation {
        grow(*a);
        grow(*b);
    }
    let frame = Frame::new(lo, hi, rect);
    let px = |p: [f64; 2]| frame.px(p);
    let corners = [
        [blo[0], blo[2]],
        [bhi[0], blo[2]],
        [bhi[0], bhi[2]],
        [blo[0], bhi[2]],
        [blo[0], blo[2]],
    ];
    prims.push(Prim::Polyline {
        points: corners.iter().map(|&c| px(c)).collect(),
        color: GREY,
        width: 1.0,
        dashed: true,
    });
    let mut edges = Vec::with_capacity(3 * facing.len());
    for &f in &facing {
        let v = mesh.facet(f);
        for k in 0..3 {
            let (a, b) = (v[k] as usize, v[(k + 1) % 3] as usize);
            edges.push((px(pos(a, 1.0)), px(pos(b, 1.0))));
        }
    }
    prims.push(Prim::Segments {
        segments: edges,
        color: MESH,
        width: if facing.len() > 20_000 { 0.3 } else { 0.6 },
    });
    prims.push(Prim::Segments {
        segments: foundation.iter().map(|(a, b)| (px(*a), px(*b))).collect(),
        color: DARK,
        width: 4.0,
    });
    let norm3 = |f: &[f64; 3]| (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
    let max_t = solution
        .contact
        .iter()
        .map(|c| norm3(&c.force) / c.weight)
        .fold(0.0, f64::max);
    let arrow_px = 0.12 * w.min(h);
    for c in solution.contact.iter().filter(|c| visible[c.node as usize]) {
        let p = px(pos(c.node as usize, 1.0));
        if touching(c) && max_t > 0.0 {
            let k = arrow_px / max_t;
            let tip = [
                p[0] + k * c.force[0] / c.weight,
                p[1] - k * c.force[2] / c.weight,
            ];
            if (tip[0] - p[0]).hypot(tip[1] - p[1]) > 1.0 {
                prims.push(Prim::Arrow {
                    from: p,
                    to: tip,
                    color: GREEN,
                    width: 1.5,
                });
            }
        }
        prims.push(Prim::Circle {
            center: p,
            radius: if touching(c) { 3.0 } else { 1.5 },
            fill: status_color(c),
        });
    }
    prims.push(Prim::Text {
        pos: [x0 + w / 2.0, y0 + TOP + 8.0],
        text: "front view: x right, z up".into(),
        size: 12.0,
        anchor: Anchor::Middle,
        color: DARK,
    });
    legend(&mut prims, solution, max_t, rect);
    prims
}

/// The paper's Fig. 2: one case.
pub fn figure(problem: &Problem, solution: &Solution, title: &str) -> Figure {
    let mut fig = Figure::new(820, 820);
    fig.prims = panel(problem, solution, [0.0, 0.0, 820.0, 820.0], title);
    fig
}

/// The paper's Fig. 3: several cases side by side.
pub fn side_by_side(cases: &[(&Problem, &Solution, String)]) -> Figure {
    let pw = 620.0;
    let mut fig = Figure::new((pw * cases.len() as f64) as u32, 660);
    for (k, (p, s, title)) in cases.iter().enumerate() {
        fig.prims
            .extend(panel(p, s, [k as f64 * pw, 0.0, pw, 660.0], title));
    }
    fig
}
