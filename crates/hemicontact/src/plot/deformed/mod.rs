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

mod draw;
mod geometry;
mod key;
mod palette;

use super::axes;
use super::field::ColorField;
use super::legend::flow;
use super::scales::{arrow_points, contact_spacing, max_traction, mesh_drawn};
use super::{Figure, Prim};
use crate::problem::Problem;
use crate::solver::Solution;
use draw::Canvas;
use geometry::{Frame, View};
use key::{entries, title, touching, Key};

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
    let view = View::new(problem, solution);
    let m = view.m;
    let facing = geometry::facing_facets(mesh);
    let visible = geometry::visible_nodes(mesh, &facing);
    let foundation = geometry::foundations(problem, &view);
    let gaps = problem
        .contact
        .iter()
        .any(|cb| cb.gap != 0.0 || cb.obstacle.is_some());
    let spacing = contact_spacing(problem, solution);
    let (lo, hi) = geometry::extent(&view, &visible, &foundation);
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
    let canvas = Canvas {
        problem,
        solution,
        view: &view,
        frame: &frame,
    };
    let mut bar = draw::field_cells(&canvas, field, mesh_drawn, &mut prims);
    draw::undeformed_boundary(&canvas, &mut prims);
    draw::mesh_edges(&canvas, &facing, mesh_drawn, &mut prims);
    draw::boundaries(&canvas, &foundation, key.interfaces, &mut prims);
    if field == ColorField::ContactPressure {
        bar = Some(draw::pressure_edges(problem, solution, &mut prims, &|n| {
            frame.px(view.pos(n, 1.0))
        }));
    }
    draw::contact_points(
        &canvas,
        &visible,
        &chosen,
        spacing,
        max_t,
        key.arrow_scale,
        &mut prims,
    );
    let bottom = draw::axes_and_legend(&canvas, field, bar, &key, [x0, w], &mut prims);
    (prims, bottom)
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
