//! The drawing steps of a deformed-mesh panel, in the order they are layered: the colour
//! field, the undeformed boundary, the deformed mesh, the boundaries and foundations, the
//! contact pressure along the contact boundary, the contact points with their traction
//! arrows, and the axes, colour bar and legend.

use super::geometry::{material_interfaces, Frame, Segment, View};
use super::key::{entries, status_color, touching, Key};
use super::palette::{ARROW, DARK, GREY, MESH};
use crate::plot::axes::{self, Axis};
use crate::plot::field::{color_of, colorbar, level, level_color, range, ColorField, LEVELS};
use crate::plot::interface::{along, traction_floor};
use crate::plot::legend::flow;
use crate::plot::scales::chains;
use crate::plot::{raster, Anchor, Prim};
use crate::problem::Problem;
use crate::solver::Solution;

/// What the drawing steps of a panel share: the case drawn, its view and the frame that
/// maps the view to pixels.
pub(super) struct Canvas<'a> {
    /// The problem drawn.
    pub(super) problem: &'a Problem,
    /// Its solution.
    pub(super) solution: &'a Solution,
    /// The deformed positions in the plane of the drawing.
    pub(super) view: &'a View<'a>,
    /// The map from the plane of the drawing to pixels.
    pub(super) frame: &'a Frame,
}

/// The colour field on the deformed cells; returns the range of its colour bar, if any.
pub(super) fn field_cells(
    canvas: &Canvas,
    field: ColorField,
    mesh_drawn: bool,
    prims: &mut Vec<Prim>,
) -> Option<[f64; 2]> {
    let (problem, solution, mesh) = (canvas.problem, canvas.solution, canvas.view.mesh);
    let px = |p: [f64; 2]| canvas.frame.px(p);
    let pos = |n: usize, s: f64| canvas.view.pos(n, s);
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
    bar
}

/// The undeformed boundary, dashed along each chain of boundary edges (in 3D the
/// undeformed bounding box).
pub(super) fn undeformed_boundary(canvas: &Canvas, prims: &mut Vec<Prim>) {
    let (mesh, d, blo, bhi) = (
        canvas.view.mesh,
        canvas.view.d,
        canvas.view.blo,
        canvas.view.bhi,
    );
    let px = |p: [f64; 2]| canvas.frame.px(p);
    let pos = |n: usize, s: f64| canvas.view.pos(n, s);
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
}

/// The deformed mesh edges: in 2D each cell edge once (a < b; shared edges appear in two
/// cells with opposite orientation), in 3D the edges of the facets `facing` the viewer;
/// none when the mesh is too fine to draw.
pub(super) fn mesh_edges(
    canvas: &Canvas,
    facing: &[usize],
    mesh_drawn: bool,
    prims: &mut Vec<Prim>,
) {
    let (mesh, d) = (canvas.view.mesh, canvas.view.d);
    let px = |p: [f64; 2]| canvas.frame.px(p);
    let pos = |n: usize, s: f64| canvas.view.pos(n, s);
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
        for &f in facing {
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
}

/// The rigid foundations (thick), and in 2D the deformed boundary and, if `interfaces`,
/// the interfaces between materials.
pub(super) fn boundaries(
    canvas: &Canvas,
    foundation: &[Segment],
    interfaces: bool,
    prims: &mut Vec<Prim>,
) {
    let (problem, mesh, d) = (canvas.problem, canvas.view.mesh, canvas.view.d);
    let px = |p: [f64; 2]| canvas.frame.px(p);
    let pos = |n: usize, s: f64| canvas.view.pos(n, s);
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
        if interfaces {
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
}

/// The interface tractions as arrows at the `chosen` points (`arrow_scale` px per Pa,
/// none if the largest traction `max_t` is 0) and the contact points coloured by state;
/// markers shrink where points are closer than about 8 px (`spacing`, m).
pub(super) fn contact_points(
    canvas: &Canvas,
    visible: &[bool],
    chosen: &[bool],
    spacing: f64,
    max_t: f64,
    arrow_scale: f64,
    prims: &mut Vec<Prim>,
) {
    let (solution, iy, frame) = (canvas.solution, canvas.view.iy, canvas.frame);
    let px = |p: [f64; 2]| canvas.frame.px(p);
    let pos = |n: usize, s: f64| canvas.view.pos(n, s);
    let marker = (0.35 * frame.scale * spacing).clamp(1.6, 3.0);
    for (k, c) in solution.contact.iter().enumerate() {
        if !visible[c.node as usize] {
            continue;
        }
        let p = px(pos(c.node as usize, 1.0));
        if touching(c) && max_t > 0.0 && chosen[k] {
            let t = [c.force[0] / c.weight, c.force[iy] / c.weight];
            let tip = [p[0] + arrow_scale * t[0], p[1] - arrow_scale * t[1]];
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
}

/// The axes in metres around the drawing box, the colour bar of `field` over `bar`, and
/// the legend below, across the panel's columns `x0..x0 + w` (px); returns the y (px) of
/// the legend's bottom.
pub(super) fn axes_and_legend(
    canvas: &Canvas,
    field: ColorField,
    bar: Option<[f64; 2]>,
    key: &Key,
    [x0, w]: [f64; 2],
    prims: &mut Vec<Prim>,
) -> f64 {
    let (solution, frame, d, view_y) = (
        canvas.solution,
        canvas.frame,
        canvas.view.d,
        canvas.view.view_y,
    );
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
        &entries(solution, key),
        x0 + 16.0,
        x0 + w - 16.0,
        bl[1] + axes::BELOW,
        12.0,
    );
    prims.extend(legend.prims);
    legend.bottom
}

/// Colours the contact boundary edges by the mean contact pressure of their two end
/// points (Pa), drawn thick over the deformed boundary; returns the colour range.
pub(super) fn pressure_edges(
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
