//! Log–log convergence plot: the relative energy-norm error against the mesh size h, one
//! curve per case, the observed order written beside each segment, and dashed reference
//! slopes. h is the element edge length by default ([`HMeasure::Edge`]), or the element
//! area (volume in 3D) as in the paper ([`HMeasure::Area`]), where every order is half the
//! order in the edge length.
//!
//! The legend sits below the plot box; order labels are placed at the first of several
//! candidate spots beside their segment where their box stays inside the plot box and
//! overlaps no other label, marker or slope label.

use super::layout::{fit_text, inside, number, overlaps, power_of_ten, text_box, Rect};
use super::legend::{flow, Entry, Swatch};
use super::{Anchor, Figure, Prim, Rgb};
use crate::study::{Level, Study};

const COLORS: [Rgb; 4] = [[200, 30, 30], [20, 80, 220], [0, 140, 60], [150, 60, 170]];
const DARK: Rgb = [30, 30, 30];
const GREY: Rgb = [225, 225, 225];

/// The measure of the mesh size on the horizontal axis.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum HMeasure {
    /// The element edge length (m): the side of the squares along x.
    #[default]
    Edge,
    /// The element area (m²; volume, m³, in 3D): the paper's measure.
    Area,
}

impl HMeasure {
    fn h(self, l: &Level) -> f64 {
        match self {
            HMeasure::Edge => l.h_edge,
            HMeasure::Area => l.h_area,
        }
    }

    fn order(self, l: &Level) -> Option<f64> {
        match self {
            HMeasure::Edge => l.order_edge,
            HMeasure::Area => l.order_area,
        }
    }

    fn axis_label(self) -> &'static str {
        match self {
            HMeasure::Edge => "mesh size h = element edge length (m)",
            HMeasure::Area => "mesh size h = element area (m²; volume, m³, in 3D)",
        }
    }

    /// The reference slopes drawn: orders 1 and 2 in the edge length (½ and 1 in area).
    fn slopes(self) -> [f64; 2] {
        match self {
            HMeasure::Edge => [1.0, 2.0],
            HMeasure::Area => [0.5, 1.0],
        }
    }
}

/// One study as drawn: its colour, its levels with a positive error and mesh size, and
/// their points (px).
type Curve<'a> = (Rgb, Vec<&'a Level>, Vec<[f64; 2]>);

/// The convergence figure of the studies against the edge length.
pub fn figure(studies: &[Study], title: &str) -> Figure {
    figure_with(studies, title, HMeasure::Edge)
}

/// The convergence figure of the studies against the mesh size `measure`.
pub fn figure_with(studies: &[Study], title: &str, measure: HMeasure) -> Figure {
    layout(studies, title, measure).0
}

/// The figure and the boxes of its labels (order labels, slope labels, legend entries),
/// which must not overlap.
fn layout(studies: &[Study], title: &str, measure: HMeasure) -> (Figure, Vec<Rect>) {
    let (w, h) = (760.0, 600.0);
    let mut fig = Figure::new(w as u32, h as u32);
    let title_h = title_lines(&mut fig, title, w);
    let mut boxes: Vec<Rect> = Vec::new();
    let pts: Vec<(f64, f64)> = studies
        .iter()
        .flat_map(|s| s.levels.iter().map(|l| (measure.h(l), l.error)))
        .filter(|(x, y)| *x > 0.0 && *y > 0.0)
        .collect();
    if pts.is_empty() {
        return (fig, boxes);
    }
    // Legend below the plot box.
    let entries = legend_entries(studies, measure);
    let probe = flow(&entries, 20.0, w - 20.0, 0.0, 12.0);
    let (left, right, top) = (90.0, 30.0, title_h + 28.0);
    let bottom = h - probe.bottom - 16.0 - 44.0;
    let plot: Rect = [left, top, w - right, bottom];
    let axes = LogAxes::new(&pts, w, [left, right, top, bottom]);
    grid_and_axes(&mut fig, &axes, measure);
    let curves = curves(studies, measure, &axes);
    let slopes = reference_slopes(studies, measure, &axes);
    let taken = taken_space(&curves, &slopes);
    for (slope, a, b) in &slopes {
        fig.prims.push(Prim::Polyline {
            points: vec![*a, *b],
            color: DARK,
            width: 1.0,
            dashed: true,
        });
        let text = format!("slope {}", number(*slope));
        place(&mut fig, &mut boxes, &taken, plot, &text, *b, DARK);
    }
    for (c, levels, points) in curves {
        for p in &points {
            fig.prims.push(Prim::Circle {
                center: *p,
                radius: 4.0,
                fill: c,
            });
        }
        for (j, pair) in levels.windows(2).enumerate() {
            if let Some(order) = measure.order(pair[1]) {
                let (a, b) = (points[j], points[j + 1]);
                let mid = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
                let text = format!("{order:.2}");
                place(&mut fig, &mut boxes, &taken, plot, &text, mid, c);
            }
        }
        fig.prims.push(Prim::Polyline {
            points,
            color: c,
            width: 2.0,
            dashed: false,
        });
    }
    let legend = flow(&entries, 20.0, w - 20.0, bottom + 52.0, 12.0);
    fig.prims.extend(legend.prims);
    boxes.extend(legend.boxes);
    (fig, boxes)
}

/// The title lines fitted to the figure's width `w` (px); returns the height they take.
fn title_lines(fig: &mut Figure, title: &str, w: f64) -> f64 {
    let (lines, size) = fit_text(title, w - 24.0, 16.0, 12.0);
    for (k, l) in lines.iter().enumerate() {
        fig.prims.push(Prim::Text {
            pos: [w / 2.0, 8.0 + size + 1.3 * size * k as f64],
            text: l.clone(),
            size,
            anchor: Anchor::Middle,
            color: DARK,
        });
    }
    14.0 + 1.3 * size * lines.len() as f64
}

/// The legend entries: one per study (with its last order), the reference slopes and the
/// note on the order labels.
fn legend_entries(studies: &[Study], measure: HMeasure) -> Vec<Entry> {
    let (s0, s1) = (measure.slopes()[0], measure.slopes()[1]);
    let mut entries: Vec<Entry> = studies
        .iter()
        .enumerate()
        .map(|(k, st)| {
            let last = st
                .levels
                .last()
                .and_then(|l| measure.order(l))
                .map_or(String::new(), |o| format!(" (last order {o:.2})"));
            Entry::new(
                Swatch::Line {
                    color: COLORS[k % COLORS.len()],
                    width: 2.0,
                    dashed: false,
                },
                format!("{}{last}", st.label),
            )
        })
        .collect();
    entries.push(Entry::new(
        Swatch::Line {
            color: DARK,
            width: 1.0,
            dashed: true,
        },
        format!("reference slopes {} and {}", number(s0), number(s1)),
    ));
    entries.push(Entry::new(
        Swatch::None,
        "numbers beside the segments: observed orders",
    ));
    entries
}

/// The log–log axes of the plot box: whole decades around the points, mapped to pixels.
struct LogAxes {
    /// The figure's width (px).
    w: f64,
    /// The plot box's left margin (px).
    left: f64,
    /// The plot box's right margin (px).
    right: f64,
    /// The plot box's top (px).
    top: f64,
    /// The plot box's bottom (px).
    bottom: f64,
    /// The decades shown along h: log10 of the lowest and highest.
    x0: f64,
    /// The decades shown along h: log10 of the lowest and highest.
    x1: f64,
    /// The decades shown along the error: log10 of the lowest and highest.
    y0: f64,
    /// The decades shown along the error: log10 of the lowest and highest.
    y1: f64,
}

impl LogAxes {
    /// The axes holding the points `pts` (h, error), in a figure `w` px wide with the plot
    /// box's margins `[left, right, top, bottom]` (px).
    fn new(pts: &[(f64, f64)], w: f64, [left, right, top, bottom]: [f64; 4]) -> Self {
        let lx = |v: f64| v.log10();
        let (mut x0, mut x1, mut y0, mut y1) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for &(x, y) in pts {
            x0 = x0.min(lx(x));
            x1 = x1.max(lx(x));
            y0 = y0.min(lx(y));
            y1 = y1.max(lx(y));
        }
        let (x0, x1) = (x0.floor(), x1.ceil().max(x0.floor() + 1.0));
        let (y0, y1) = (y0.floor(), y1.ceil().max(y0.floor() + 1.0));
        LogAxes {
            w,
            left,
            right,
            top,
            bottom,
            x0,
            x1,
            y0,
            y1,
        }
    }

    /// The pixel column of the mesh size `x`.
    fn px(&self, x: f64) -> f64 {
        let (left, right, w, x0, x1) = (self.left, self.right, self.w, self.x0, self.x1);
        let lx = |v: f64| v.log10();
        left + (lx(x) - x0) / (x1 - x0) * (w - left - right)
    }

    /// The pixel row of the error `y`.
    fn py(&self, y: f64) -> f64 {
        let (top, bottom, y0, y1) = (self.top, self.bottom, self.y0, self.y1);
        let lx = |v: f64| v.log10();
        top + (y1 - lx(y)) / (y1 - y0) * (bottom - top)
    }
}

/// The grid, the decade ticks and their labels, the plot box and the axis labels.
fn grid_and_axes(fig: &mut Figure, axes: &LogAxes, measure: HMeasure) {
    let (w, left, right, top, bottom) = (axes.w, axes.left, axes.right, axes.top, axes.bottom);
    let (x0, x1, y0, y1) = (axes.x0, axes.x1, axes.y0, axes.y1);
    let px = |x: f64| axes.px(x);
    let py = |y: f64| axes.py(y);
    // Grid, decade ticks and labels.
    let mut grid = Vec::new();
    let mut marks = Vec::new();
    // Minor ticks at 2…9 × 10^k.
    for k in (x0 as i32)..(x1 as i32) {
        for m in 2..10 {
            let x = px(f64::from(m) * 10f64.powi(k));
            marks.push(([x, bottom], [x, bottom + 3.0]));
        }
    }
    for k in (y0 as i32)..(y1 as i32) {
        for m in 2..10 {
            let y = py(f64::from(m) * 10f64.powi(k));
            marks.push(([left - 3.0, y], [left, y]));
        }
    }
    for k in (x0 as i32)..=(x1 as i32) {
        let x = px(10f64.powi(k));
        grid.push(([x, top], [x, bottom]));
        marks.push(([x, bottom], [x, bottom + 5.0]));
        fig.prims.push(Prim::Text {
            pos: [x, bottom + 20.0],
            text: power_of_ten(k),
            size: 12.0,
            anchor: Anchor::Middle,
            color: DARK,
        });
    }
    for k in (y0 as i32)..=(y1 as i32) {
        let y = py(10f64.powi(k));
        grid.push(([left, y], [w - right, y]));
        marks.push(([left - 5.0, y], [left, y]));
        fig.prims.push(Prim::Text {
            pos: [left - 8.0, y + 5.0],
            text: power_of_ten(k),
            size: 12.0,
            anchor: Anchor::End,
            color: DARK,
        });
    }
    fig.prims.push(Prim::Segments {
        segments: grid,
        color: GREY,
        width: 1.0,
    });
    fig.prims.push(Prim::Segments {
        segments: marks,
        color: DARK,
        width: 1.0,
    });
    fig.prims.push(Prim::Polyline {
        points: vec![
            [left, top],
            [w - right, top],
            [w - right, bottom],
            [left, bottom],
            [left, top],
        ],
        color: DARK,
        width: 1.2,
        dashed: false,
    });
    fig.prims.push(Prim::Text {
        pos: [(left + w - right) / 2.0, bottom + 40.0],
        text: measure.axis_label().into(),
        size: 13.0,
        anchor: Anchor::Middle,
        color: DARK,
    });
    fig.prims.push(Prim::Text {
        pos: [left, top - 10.0],
        text: "relative error in the energy norm ‖u − u_ref‖_E / ‖u_ref‖_E".into(),
        size: 12.0,
        anchor: Anchor::Start,
        color: DARK,
    });
}

/// The studies' curves: their colours, levels with a positive error and mesh size, and
/// points (px).
fn curves<'a>(studies: &'a [Study], measure: HMeasure, axes: &LogAxes) -> Vec<Curve<'a>> {
    let px = |x: f64| axes.px(x);
    let py = |y: f64| axes.py(y);
    studies
        .iter()
        .enumerate()
        .map(|(k, st)| {
            let levels: Vec<&Level> = st
                .levels
                .iter()
                .filter(|l| l.error > 0.0 && measure.h(l) > 0.0)
                .collect();
            let points = levels
                .iter()
                .map(|l| [px(measure.h(l)), py(l.error)])
                .collect();
            (COLORS[k % COLORS.len()], levels, points)
        })
        .collect()
}

/// The reference slopes through the first point of the first study, each ending where it
/// leaves the plot (at the left edge or the bottom): the slope and its ends (px).
fn reference_slopes(
    studies: &[Study],
    measure: HMeasure,
    axes: &LogAxes,
) -> Vec<(f64, [f64; 2], [f64; 2])> {
    let (x0, y0) = (axes.x0, axes.y0);
    let px = |x: f64| axes.px(x);
    let py = |y: f64| axes.py(y);
    let mut slopes: Vec<(f64, [f64; 2], [f64; 2])> = Vec::new();
    if let Some(l) = studies.first().and_then(|s| s.levels.first()) {
        let (h0, e0) = (measure.h(l), l.error);
        if h0 > 0.0 && e0 > 0.0 {
            for slope in measure.slopes() {
                let x_end = 10f64
                    .powf(x0)
                    .max(h0 * (10f64.powf(y0) / e0).powf(1.0 / slope));
                let y_end = e0 * (x_end / h0).powf(slope);
                slopes.push((slope, [px(h0), py(e0)], [px(x_end), py(y_end)]));
            }
        }
    }
    slopes
}

/// The space that the markers and lines occupy, which labels avoid where they can.
fn taken_space(curves: &[Curve], slopes: &[(f64, [f64; 2], [f64; 2])]) -> Vec<Rect> {
    let mut taken: Vec<Rect> = Vec::new();
    for (_, _, points) in curves {
        for p in points {
            taken.push([p[0] - 5.0, p[1] - 5.0, p[0] + 5.0, p[1] + 5.0]);
        }
        for w in points.windows(2) {
            trace(&mut taken, w[0], w[1]);
        }
    }
    for (_, a, b) in slopes {
        trace(&mut taken, *a, *b);
    }
    taken
}

/// Small boxes every 3 px along the segment `a–b`: the space a line takes.
fn trace(taken: &mut Vec<Rect>, a: [f64; 2], b: [f64; 2]) {
    let n = ((b[0] - a[0]).hypot(b[1] - a[1]) / 3.0).ceil().max(1.0) as usize;
    for k in 0..=n {
        let t = k as f64 / n as f64;
        let (x, y) = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]));
        taken.push([x - 1.5, y - 1.5, x + 1.5, y + 1.5]);
    }
}

/// Writes `text` (size 11) near `at` at the first candidate spot (right-below, left-above,
/// right-above, left-below, then farther out) whose box lies inside `plot` and overlaps
/// neither another label's box in `boxes` nor a marker or line in `taken`; if there is
/// none, at the first spot that overlaps no other label; failing that, at the first
/// candidate. Records the chosen box in `boxes`.
fn place(
    fig: &mut Figure,
    boxes: &mut Vec<Rect>,
    taken: &[Rect],
    plot: Rect,
    text: &str,
    at: [f64; 2],
    color: Rgb,
) {
    let size = 11.0;
    let tw = super::text_width(text, size);
    let mut candidates = Vec::new();
    for d in [6.0, 12.0, 20.0, 30.0, 42.0, 56.0, 72.0] {
        candidates.push([at[0] + d * 0.5, at[1] + d + 0.5 * size]);
        candidates.push([at[0] - d * 0.5 - tw, at[1] - d]);
        candidates.push([at[0] + d * 0.5, at[1] - d]);
        candidates.push([at[0] - d * 0.5 - tw, at[1] + d + 0.5 * size]);
    }
    let fits = |p: &[f64; 2], avoid: &[Rect]| {
        let b = text_box(text, p[0], p[1], size);
        inside(b, plot) && !boxes.iter().chain(avoid).any(|o| overlaps(b, *o))
    };
    let p = candidates
        .iter()
        .copied()
        .find(|p| fits(p, taken))
        .or_else(|| candidates.iter().copied().find(|p| fits(p, &[])))
        .unwrap_or(candidates[0]);
    boxes.push(text_box(text, p[0], p[1], size));
    fig.prims.push(Prim::Text {
        pos: p,
        text: text.to_string(),
        size,
        anchor: Anchor::Start,
        color,
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A study whose error falls like `c · h_edge^order` over five halvings of the mesh.
    fn study(label: &str, c: f64, order: f64) -> Study {
        let mut levels: Vec<Level> = Vec::new();
        for k in 0..5 {
            let n = 4usize << k;
            let edge = 1.0 / n as f64;
            let error = c * edge.powf(order);
            let prev = levels.last();
            let order_edge = prev.map(|p| (p.error / error).ln() / (p.h_edge / edge).ln());
            levels.push(Level {
                n,
                h_area: 0.5 * edge * edge,
                h_edge: edge,
                dofs: 2 * (n + 1) * (n + 1),
                error,
                order_area: order_edge.map(|o| 0.5 * o),
                order_edge,
                outer: 1,
                newton: 1,
                converged: true,
                seconds: 0.0,
            });
        }
        Study {
            label: label.into(),
            reference_n: 128,
            reference_dofs: 0,
            reference_converged: true,
            reference_seconds: 0.0,
            reference_norm: 1.0,
            levels,
        }
    }

    #[test]
    fn labels_of_close_curves_do_not_collide() {
        // Two curves almost on top of each other: their order labels compete for space.
        let studies = [study("locking", 0.5, 1.0), study("no locking", 0.55, 1.02)];
        for measure in [HMeasure::Edge, HMeasure::Area] {
            let (fig, boxes) = layout(&studies, "convergence", measure);
            assert!(boxes.len() >= 2 * 4 + 2, "{} boxes", boxes.len());
            for (i, a) in boxes.iter().enumerate() {
                for b in &boxes[i + 1..] {
                    assert!(!overlaps(*a, *b), "{a:?} overlaps {b:?} ({measure:?})");
                }
                assert!(inside(
                    *a,
                    [0.0, 0.0, f64::from(fig.width), f64::from(fig.height)]
                ));
            }
        }
    }

    #[test]
    fn orders_are_those_of_the_chosen_measure() {
        let studies = [study("a", 1.0, 1.0)];
        let texts = |m| -> Vec<String> {
            layout(&studies, "t", m)
                .0
                .prims
                .iter()
                .filter_map(|p| match p {
                    Prim::Text { text, .. } => Some(text.clone()),
                    _ => None,
                })
                .collect()
        };
        // Error ∝ edge¹ = area^½: order 1.00 in the edge length, 0.50 in the area.
        assert!(texts(HMeasure::Edge).iter().any(|t| t == "1.00"));
        assert!(texts(HMeasure::Area).iter().any(|t| t == "0.50"));
    }
}
