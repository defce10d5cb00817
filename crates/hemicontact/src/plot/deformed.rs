//! The deformed mesh with the interface tractions on Γ_C, for one case or several side by
//! side.
//!
//! Drawn, in world coordinates mapped to the panel (y up, equal scales, axes in m): an
//! optional colour field on the deformed cells ([`ColorField`], von Mises stress by default)
//! with its colour bar, the undeformed boundary (dashed grey), the deformed mesh (thin) and
//! boundary, the rigid foundations (thick black: the contact facets shifted by the gap along
//! their normals), the contact points coloured by state (grey separated, dark grey contact
//! without friction, blue stick, red slip) and the interface tractions R_i/w_i (Pa: the
//! force of the foundation on point i over its weight) as arrows to a stated scale.
//!
//! Displacements are magnified by [`super::scales::magnification`] (a 1, 2 or 5 × 10^k factor making the
//! largest displacement about a tenth of the body), and so are the gaps, so that the
//! foundations stay where the magnified body touches them; the legend says so. At most
//! [`Options::max_arrows`] arrows are drawn per contact part, evenly spaced along it. The
//! legend sits below the drawing, inside the panel. A 3D solution is drawn as a front view
//! (orthographic projection on the x–z plane).

use super::axes::{self, Axis};
use super::field::{color_of, colorbar, level, level_color, range, ColorField, LEVELS};
use super::interface::{along, traction_floor};
use super::layout::{fit_text, quantity, round_down_125};
use super::legend::{flow, Entry, Swatch};
use super::scales::{
    arrow_points, chains, contact_spacing, magnification, max_traction, mesh_drawn,
};
use super::{raster, Anchor, Figure, Prim, Rgb};
use crate::problem::Problem;
use crate::solver::{ContactResult, FrictionState, NormalState, Solution};

const GREY: Rgb = [150, 150, 150];
const MESH: Rgb = [110, 125, 155];
const DARK: Rgb = [30, 30, 30];
const ARROW: Rgb = [0, 110, 50];
const BLUE: Rgb = [20, 80, 220];
const RED: Rgb = [220, 30, 30];
const CONTACT: Rgb = [70, 70, 70];

/// What the deformed-mesh figure shows besides the mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Options {
    /// The colour field on the cells (2D only).
    pub field: ColorField,
    /// Largest number of traction arrows per contact part (evenly spaced along it, and at
    /// least 8 px apart on average).
    pub max_arrows: usize,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            field: ColorField::VonMises,
            max_arrows: 40,
        }
    }
}

/// Marker colour of a contact point: its friction state, and for frictionless points its
/// normal state.
fn status_color(c: &ContactResult) -> Rgb {
    match (c.friction_state, c.normal_state) {
        (FrictionState::Stick, _) => BLUE,
        (FrictionState::Slip, _) => RED,
        (FrictionState::None, NormalState::Contact) => CONTACT,
        (FrictionState::None, NormalState::Separated) => GREY,
    }
}

/// Whether a contact point touches its foundation (normal state; drawn as a large marker).
fn touching(c: &ContactResult) -> bool {
    c.normal_state == NormalState::Contact
}

/// What a panel's legend needs to know.
struct Key {
    magnification: f64,
    max_t: f64,
    /// Pixels per Pa of the arrows.
    arrow_scale: f64,
    arrows: usize,
    touching_points: usize,
    field: ColorField,
    gaps: bool,
    /// Whether the problem has a contact boundary.
    contact: bool,
    /// Whether a contact boundary faces a rigid foundation or obstacle (not another body).
    foundation: bool,
    /// Whether the mesh edges are drawn (else only the deformed boundary: too fine).
    mesh_drawn: bool,
    cells: usize,
    /// Whether interfaces between materials are drawn (2D, several materials).
    interfaces: bool,
}

/// The legend entries of a panel.
fn entries(solution: &Solution, key: &Key) -> Vec<Entry> {
    let m = key.magnification;
    let scale = if m > 1.0 {
        format!("displacements × {}", super::layout::number(m))
    } else {
        "displacements at true scale (× 1)".to_string()
    };
    let mut e = vec![
        if key.mesh_drawn {
            Entry::new(
                Swatch::Line {
                    color: MESH,
                    width: 1.0,
                    dashed: false,
                },
                format!("deformed mesh, {scale}"),
            )
        } else {
            Entry::new(
                Swatch::Line {
                    color: DARK,
                    width: 1.2,
                    dashed: false,
                },
                format!(
                    "deformed boundary, {scale} (the {} cells are too small to draw)",
                    key.cells
                ),
            )
        },
        Entry::new(
            Swatch::Line {
                color: GREY,
                width: 1.0,
                dashed: true,
            },
            "undeformed boundary",
        ),
    ];
    if key.interfaces {
        e.push(Entry::new(
            Swatch::Line {
                color: DARK,
                width: 1.2,
                dashed: false,
            },
            "boundaries and interfaces between materials",
        ));
    }
    if !key.contact {
        e.push(Entry::new(Swatch::None, "no contact boundary"));
        push_field(&mut e, key.field);
        return e;
    }
    if key.foundation {
        e.push(Entry::new(
            Swatch::Line {
                color: DARK,
                width: 4.0,
                dashed: false,
            },
            if key.gaps && m > 1.0 {
                format!("rigid foundation (gap × {})", super::layout::number(m))
            } else {
                "rigid foundation".to_string()
            },
        ));
    }
    let count =
        |f: &dyn Fn(&ContactResult) -> bool| solution.contact.iter().filter(|c| f(c)).count();
    let states: [(Rgb, &str, usize); 4] = [
        (
            GREY,
            "separated",
            count(&|c| !touching(c) && c.friction_state == FrictionState::None),
        ),
        (
            CONTACT,
            "contact, no friction",
            count(&|c| touching(c) && c.friction_state == FrictionState::None),
        ),
        (
            BLUE,
            "stick",
            count(&|c| c.friction_state == FrictionState::Stick),
        ),
        (
            RED,
            "slip",
            count(&|c| c.friction_state == FrictionState::Slip),
        ),
    ];
    for (color, label, n) in states {
        if n > 0 || label == "stick" || label == "slip" {
            e.push(Entry::new(
                Swatch::Dot { color, radius: 4.0 },
                format!("{label} ({n})"),
            ));
        }
    }
    if key.max_t > 0.0 {
        let reference = round_down_125(key.max_t);
        e.push(Entry::new(
            Swatch::Arrow {
                color: ARROW,
                length: (key.arrow_scale * reference).max(8.0),
            },
            format!(
                "interface traction R/w (max {}): this arrow = {}",
                quantity(key.max_t, "Pa"),
                quantity(reference, "Pa")
            ),
        ));
        if key.arrows < key.touching_points {
            e.push(Entry::new(
                Swatch::None,
                format!(
                    "arrows at {} of {} points in contact",
                    key.arrows, key.touching_points
                ),
            ));
        }
    } else {
        e.push(Entry::new(
            Swatch::None,
            "interface traction 0 (no point in contact)",
        ));
    }
    push_field(&mut e, key.field);
    e
}

/// The legend entry naming the colour field, if any.
fn push_field(e: &mut Vec<Entry>, field: ColorField) {
    if field != ColorField::None {
        e.push(Entry::new(
            Swatch::Patch {
                color: color_of(0.7, [0.0, 1.0]),
            },
            format!("colours: {}", field.label()),
        ));
    }
}

/// The title lines of a panel fitted to its width; returns the primitives and the height
/// they take.
fn title(text: &str, x0: f64, y0: f64, w: f64) -> (Vec<Prim>, f64) {
    let (lines, size) = fit_text(text, w - 24.0, 16.0, 12.0);
    let prims = lines
        .iter()
        .enumerate()
        .map(|(k, l)| Prim::Text {
            pos: [x0 + w / 2.0, y0 + 8.0 + size + 1.3 * size * k as f64],
            text: l.clone(),
            size,
            anchor: Anchor::Middle,
            color: DARK,
        })
        .collect();
    (prims, 14.0 + 1.3 * size * lines.len() as f64)
}

/// Primitives of one panel at pixel rectangle `(x0, y0, w, h)` with a title, with the
/// default [`Options`].
pub fn panel(problem: &Problem, solution: &Solution, rect: [f64; 4], title: &str) -> Vec<Prim> {
    panel_with(problem, solution, rect, title, Options::default())
}

/// Primitives of one panel at pixel rectangle `(x0, y0, w, h)` with a title. The drawing
/// is as large as the width allows and at most the height less title, axes and legend; the
/// legend follows right below it.
pub fn panel_with(
    problem: &Problem,
    solution: &Solution,
    rect: [f64; 4],
    text: &str,
    options: Options,
) -> Vec<Prim> {
    panel_layout(problem, solution, rect, text, options).0
}

/// The panel and the y (px) of its lowest content.
fn panel_layout(
    problem: &Problem,
    solution: &Solution,
    rect: [f64; 4],
    text: &str,
    options: Options,
) -> (Vec<Prim>, f64) {
    let mesh = &problem.mesh;
    let d = mesh.dim();
    let [x0, y0, w, h] = rect;
    let (mut prims, title_h) = title(text, x0, y0, w);
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
    let pos = |n: usize, s: f64| {
        let x = mesh.node(n);
        [
            x[0] + s * m * solution.u[d * n],
            x[iy] + s * m * solution.u[d * n + iy],
        ]
    };
    // Which nodes and facets are drawn: all in 2D; in 3D those facing the viewer.
    let facing: Vec<usize> = (0..mesh.n_facets())
        .filter(|&f| d == 2 || mesh.facet_measure_normal(f).1[1] < -0.5)
        .collect();
    let mut visible = vec![d == 2; mesh.n_nodes()];
    for &f in &facing {
        for &v in mesh.facet(f) {
            visible[v as usize] = true;
        }
    }
    // Foundations: contact facets shifted by the magnified gap along their normals (in 3D
    // the facets seen edge-on). Against an obstacle each node moves by its own gap along its
    // own normal, which at true scale puts it on its closest point of the obstacle: drawn
    // are the edges of the part's facets in the plane of the drawing (in 3D, those on the
    // face nearest the viewer) whose points fall within the body's box widened by a fifth
    // of its size (far from the body the magnified gaps would distort the shape).
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
    let gaps = problem
        .contact
        .iter()
        .any(|cb| cb.gap != 0.0 || cb.obstacle.is_some());
    let spacing = contact_spacing(problem, solution);
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
    for (a, b) in &foundation {
        grow(*a);
        grow(*b);
    }
    // Arrows and the legend, whose height fixes the drawing area.
    let max_t = max_traction(solution);
    let field = if d == 2 {
        options.field
    } else {
        ColorField::None
    };
    let has_bar = field != ColorField::None;
    let right = if has_bar { 90.0 } else { 24.0 };
    let area_w = w - 70.0 - right;
    let shown = |k: usize| {
        let c = &solution.contact[k];
        visible[c.node as usize] && touching(c)
    };
    let touching_points = (0..solution.contact.len()).filter(|&k| shown(k)).count();
    // The legend is first set with the note on thinned arrows (the arrows are chosen once
    // the scale is known), so that the final legend is never taller.
    let arrows = 0;
    let mut key = Key {
        magnification: m,
        max_t,
        arrow_scale: 0.0,
        arrows,
        touching_points,
        field,
        gaps,
        contact: !problem.contact.is_empty(),
        foundation: problem.contact.iter().any(|c| c.against.is_none()),
        mesh_drawn: true,
        cells: if d == 2 { mesh.n_cells() } else { facing.len() },
        interfaces: d == 2 && problem.materials.len() > 1,
    };
    // The arrows' scale depends on the width only, and its legend entry on the scale.
    let arrow_px = 0.08 * area_w;
    key.arrow_scale = if max_t > 0.0 { arrow_px / max_t } else { 0.0 };
    // Whether the mesh is drawn is known only once the frame is: the legend is set both
    // ways (the text of the boundary entry differs) and the taller one is kept.
    let probe = [true, false]
        .map(|drawn| {
            let key = Key {
                mesh_drawn: drawn,
                ..key
            };
            flow(
                &entries(solution, &key),
                x0 + 16.0,
                x0 + w - 16.0,
                0.0,
                12.0,
            )
            .bottom
        })
        .into_iter()
        .fold(0.0, f64::max);
    let area = [
        x0 + 70.0,
        y0 + title_h + axes::ABOVE,
        area_w,
        h - title_h - axes::ABOVE - axes::BELOW - probe - 14.0,
    ];
    let frame = Frame::new(lo, hi, area);
    let px = |p: [f64; 2]| frame.px(p);
    key.mesh_drawn = mesh_drawn(mesh, frame.scale, d);
    let mesh_drawn = key.mesh_drawn;
    let chosen = arrow_points(
        problem,
        solution,
        &visible,
        options.max_arrows,
        8.0 / frame.scale,
    );
    key.arrows = (0..solution.contact.len())
        .filter(|&k| shown(k) && chosen[k])
        .count();
    // Colour field on the deformed cells.
    let mut bar = None;
    if let Some(values) = field.cell_values(problem, solution) {
        let r = range(&values);
        // One primitive per colour band of the bar: cells grouped by their band.
        let mut bands: Vec<Vec<Vec<[f64; 2]>>> = vec![Vec::new(); LEVELS];
        for (c, v) in values.iter().enumerate() {
            let ring = mesh
                .cell(c)
                .iter()
                .map(|&v| px(pos(v as usize, 1.0)))
                .collect();
            bands[level(*v, r)].push(ring);
        }
        let bands: Vec<_> = bands
            .into_iter()
            .enumerate()
            .filter(|(_, rings)| !rings.is_empty())
            .map(|(k, rings)| (level_color(k), rings))
            .collect();
        // Cells too small to draw their edges are too small to draw one by one: the field
        // is sampled at the resolution of the picture.
        match (!mesh_drawn).then(|| raster::rasterize(&bands)).flatten() {
            Some(image) => prims.push(Prim::Raster(image)),
            None => prims.extend(
                bands
                    .into_iter()
                    .map(|(fill, rings)| Prim::Polygons { rings, fill }),
            ),
        }
        bar = Some(r);
    }
    // Undeformed boundary, dashed along each chain of boundary edges (in 3D the undeformed
    // bounding box).
    if d == 2 {
        for chain in chains(mesh) {
            prims.push(Prim::Polyline {
                points: chain.iter().map(|&n| px(pos(n as usize, 0.0))).collect(),
                color: GREY,
                width: 1.0,
                dashed: true,
            });
        }
    } else {
        let c = [
            [blo[0], blo[2]],
            [bhi[0], blo[2]],
            [bhi[0], bhi[2]],
            [blo[0], bhi[2]],
        ];
        prims.push(Prim::Polyline {
            points: [c[0], c[1], c[2], c[3], c[0]]
                .iter()
                .map(|&p| px(p))
                .collect(),
            color: GREY,
            width: 1.0,
            dashed: true,
        });
    }
    // Deformed mesh edges: in 2D each cell edge once (a < b; shared edges appear in two
    // cells with opposite orientation), in 3D the edges of the facets facing the viewer.
    let mut edges = Vec::new();
    if d == 2 && mesh_drawn {
        for c in 0..mesh.n_cells() {
            let cell = mesh.cell(c);
            for k in 0..3 {
                let (a, b) = (cell[k] as usize, cell[(k + 1) % 3] as usize);
                if a < b {
                    edges.push((px(pos(a, 1.0)), px(pos(b, 1.0))));
                }
            }
        }
    } else if d == 3 {
        for &f in &facing {
            let v = mesh.facet(f);
            for k in 0..3 {
                let (a, b) = (v[k] as usize, v[(k + 1) % 3] as usize);
                edges.push((px(pos(a, 1.0)), px(pos(b, 1.0))));
            }
        }
    }
    if mesh_drawn {
        prims.push(Prim::Segments {
            segments: edges,
            color: MESH,
            width: 0.6,
        });
    }
    prims.push(Prim::Segments {
        segments: foundation.iter().map(|(a, b)| (px(*a), px(*b))).collect(),
        color: DARK,
        width: 4.0,
    });
    if d == 2 {
        let boundary = (0..mesh.n_facets())
            .map(|f| {
                let v = mesh.facet(f);
                (px(pos(v[0] as usize, 1.0)), px(pos(v[1] as usize, 1.0)))
            })
            .collect();
        prims.push(Prim::Segments {
            segments: boundary,
            color: DARK,
            width: 1.2,
        });
        if key.interfaces {
            let segments = material_interfaces(problem)
                .into_iter()
                .map(|(a, b)| (px(pos(a as usize, 1.0)), px(pos(b as usize, 1.0))))
                .collect();
            prims.push(Prim::Segments {
                segments,
                color: DARK,
                width: 1.2,
            });
        }
    }
    if field == ColorField::ContactPressure {
        bar = Some(pressure_edges(problem, solution, &mut prims, &|n| {
            px(pos(n, 1.0))
        }));
    }
    // Interface tractions and contact points; markers shrink where points are closer than
    // about 8 px.
    let marker = (0.35 * frame.scale * spacing).clamp(1.6, 3.0);
    for (k, c) in solution.contact.iter().enumerate() {
        if !visible[c.node as usize] {
            continue;
        }
        let p = px(pos(c.node as usize, 1.0));
        if touching(c) && max_t > 0.0 && chosen[k] {
            let t = [c.force[0] / c.weight, c.force[iy] / c.weight];
            let tip = [p[0] + key.arrow_scale * t[0], p[1] - key.arrow_scale * t[1]];
            if (tip[0] - p[0]).hypot(tip[1] - p[1]) > 1.0 {
                prims.push(Prim::Arrow {
                    from: p,
                    to: tip,
                    color: ARROW,
                    width: 1.5,
                });
            }
        }
        let r = if touching(c) { marker } else { 0.6 * marker };
        if marker >= 2.5 {
            prims.push(Prim::Circle {
                center: p,
                radius: r + 0.8,
                fill: [255, 255, 255],
            });
        }
        prims.push(Prim::Circle {
            center: p,
            radius: r,
            fill: status_color(c),
        });
    }
    // Axes in metres around the drawing box, the colour bar, and the legend below.
    let (bl, bh) = (frame.px(frame.lo), frame.px(frame.hi));
    let xa = Axis {
        lo: frame.lo[0],
        hi: frame.hi[0],
        px0: bl[0],
        px1: bh[0],
    };
    let ya = Axis {
        lo: frame.lo[1],
        hi: frame.hi[1],
        px0: bl[1],
        px1: bh[1],
    };
    prims.extend(axes::frame(&xa, &ya, [1.0, 1.0], ["x (m)", view_y], false));
    if d == 3 {
        prims.push(Prim::Text {
            pos: [bh[0], bh[1] - 8.0],
            text: "front view, looking along +y".into(),
            size: 12.0,
            anchor: Anchor::End,
            color: DARK,
        });
    }
    if let Some(r) = bar {
        prims.extend(colorbar(
            field,
            r,
            [bh[0] + 14.0, bh[1], 14.0, bl[1] - bh[1]],
        ));
    }
    let legend = flow(
        &entries(solution, &key),
        x0 + 16.0,
        x0 + w - 16.0,
        bl[1] + axes::BELOW,
        12.0,
    );
    prims.extend(legend.prims);
    (prims, legend.bottom)
}

/// The edges of a 2D mesh between two cells of different materials (node pairs).
fn material_interfaces(problem: &Problem) -> Vec<(u32, u32)> {
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

/// Colours the contact boundary edges by the mean contact pressure of their two end
/// points (Pa), drawn thick over the deformed boundary; returns the colour range.
fn pressure_edges(
    problem: &Problem,
    solution: &Solution,
    prims: &mut Vec<Prim>,
    px: &dyn Fn(usize) -> [f64; 2],
) -> [f64; 2] {
    let floor = traction_floor(solution);
    let mut edges = Vec::new();
    for b in 0..problem.contact.len() {
        let al = along(problem, solution, b);
        for w in al.rows.windows(2) {
            let (c0, c1) = (&solution.contact[w[0]], &solution.contact[w[1]]);
            let p = 0.5 * (c0.pressure + c1.pressure);
            edges.push((
                c0.node as usize,
                c1.node as usize,
                if p.abs() <= floor { 0.0 } else { p },
            ));
        }
    }
    let values: Vec<f64> = edges.iter().map(|e| e.2).collect();
    let r = range(&values);
    for (a, b, p) in edges {
        prims.push(Prim::Polyline {
            points: vec![px(a), px(b)],
            color: color_of(p, r),
            width: 5.0,
            dashed: false,
        });
    }
    r
}

/// The map from world coordinates (y up) to the pixels of a drawing area: equal scales,
/// the world box `lo..hi` grown by a 6 % margin, centred across the area and at its top.
struct Frame {
    lo: [f64; 2],
    hi: [f64; 2],
    scale: f64,
    origin: [f64; 2],
}

impl Frame {
    fn new(lo: [f64; 2], hi: [f64; 2], area: [f64; 4]) -> Self {
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

    fn px(&self, p: [f64; 2]) -> [f64; 2] {
        [
            self.origin[0] + self.scale * (p[0] - self.lo[0]),
            self.origin[1] + self.scale * (self.hi[1] - p[1]),
        ]
    }
}

/// One case, with the default [`Options`].
pub fn figure(problem: &Problem, solution: &Solution, title: &str) -> Figure {
    figure_with(problem, solution, title, Options::default())
}

/// One case.
pub fn figure_with(
    problem: &Problem,
    solution: &Solution,
    title: &str,
    options: Options,
) -> Figure {
    let (prims, bottom) = panel_layout(problem, solution, [0.0, 0.0, 820.0, 900.0], title, options);
    let mut fig = Figure::new(820, (bottom + 12.0).ceil().min(900.0) as u32);
    fig.prims = prims;
    fig
}

/// Several cases side by side, with the default [`Options`]; each panel keeps its title,
/// axes and legend inside its own column.
pub fn side_by_side(cases: &[(&Problem, &Solution, String)]) -> Figure {
    let pw = 640.0;
    let ph = 760.0;
    let mut fig = Figure::new((pw * cases.len() as f64) as u32, ph as u32);
    let mut bottom: f64 = 0.0;
    for (k, (p, s, title)) in cases.iter().enumerate() {
        let rect = [k as f64 * pw, 0.0, pw, ph];
        let (prims, b) = panel_layout(p, s, rect, title, Options::default());
        fig.prims.extend(prims);
        bottom = bottom.max(b);
    }
    fig.height = (bottom + 12.0).ceil().min(ph) as u32;
    fig
}
