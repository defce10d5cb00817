//! Log–log convergence plot: relative energy-norm error against the element size h (the
//! element area, the paper's measure), one curve per case, with a reference slope.

use super::{text_width, Anchor, Figure, Prim, Rgb};
use crate::study::Study;

const COLORS: [Rgb; 4] = [[200, 30, 30], [20, 80, 220], [0, 140, 60], [150, 60, 170]];
const DARK: Rgb = [30, 30, 30];
const GREY: Rgb = [200, 200, 200];

/// The convergence figure of the studies.
pub fn figure(studies: &[Study], title: &str) -> Figure {
    let (w, h) = (760.0, 560.0);
    let (left, right, top, bottom) = (90.0, 30.0, 70.0, 70.0);
    let mut fig = Figure::new(w as u32, h as u32);
    let pts: Vec<(f64, f64)> = studies
        .iter()
        .flat_map(|s| s.levels.iter().map(|l| (l.h_area, l.error)))
        .filter(|(x, y)| *x > 0.0 && *y > 0.0)
        .collect();
    fig.prims.push(Prim::Text {
        pos: [w / 2.0, 28.0],
        text: title.into(),
        size: 16.0,
        anchor: Anchor::Middle,
        color: DARK,
    });
    if pts.is_empty() {
        return fig;
    }
    let lx = |v: f64| v.log10();
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &(x, y) in &pts {
        x0 = x0.min(lx(x));
        x1 = x1.max(lx(x));
        y0 = y0.min(lx(y));
        y1 = y1.max(lx(y));
    }
    let (x0, x1) = (x0.floor(), x1.ceil().max(x0.floor() + 1.0));
    let (y0, y1) = (y0.floor(), y1.ceil().max(y0.floor() + 1.0));
    let px = |x: f64| left + (lx(x) - x0) / (x1 - x0) * (w - left - right);
    let py = |y: f64| top + (y1 - lx(y)) / (y1 - y0) * (h - top - bottom);
    // Grid and decade labels.
    for k in (x0 as i32)..=(x1 as i32) {
        let x = px(10f64.powi(k));
        fig.prims.push(Prim::Polyline {
            points: vec![[x, top], [x, h - bottom]],
            color: GREY,
            width: 1.0,
            dashed: false,
        });
        fig.prims.push(Prim::Text {
            pos: [x, h - bottom + 20.0],
            text: format!("1e{k}"),
            size: 12.0,
            anchor: Anchor::Middle,
            color: DARK,
        });
    }
    for k in (y0 as i32)..=(y1 as i32) {
        let y = py(10f64.powi(k));
        fig.prims.push(Prim::Polyline {
            points: vec![[left, y], [w - right, y]],
            color: GREY,
            width: 1.0,
            dashed: false,
        });
        fig.prims.push(Prim::Text {
            pos: [left - 8.0, y + 4.0],
            text: format!("1e{k}"),
            size: 12.0,
            anchor: Anchor::End,
            color: DARK,
        });
    }
    fig.prims.push(Prim::Polyline {
        points: vec![[left, top], [left, h - bottom], [w - right, h - bottom]],
        color: DARK,
        width: 1.5,
        dashed: false,
    });
    fig.prims.push(Prim::Text {
        pos: [(left + w - right) / 2.0, h - 22.0],
        text: "h (element area)".into(),
        size: 14.0,
        anchor: Anchor::Middle,
        color: DARK,
    });
    fig.prims.push(Prim::Text {
        pos: [10.0, top - 16.0],
        text: "relative error in energy norm".into(),
        size: 12.0,
        anchor: Anchor::Start,
        color: DARK,
    });
    // Curves.
    let mut ly = top + 14.0;
    for (k, st) in studies.iter().enumerate() {
        let c = COLORS[k % COLORS.len()];
        let points: Vec<[f64; 2]> = st
            .levels
            .iter()
            .filter(|l| l.error > 0.0)
            .map(|l| [px(l.h_area), py(l.error)])
            .collect();
        for p in &points {
            fig.prims.push(Prim::Circle {
                center: *p,
                radius: 4.0,
                fill: c,
            });
        }
        fig.prims.push(Prim::Polyline {
            points,
            color: c,
            width: 2.0,
            dashed: false,
        });
        let last_order = st
            .levels
            .last()
            .and_then(|l| l.order_area)
            .map_or(String::new(), |o| format!(" (last order {o:.2})"));
        let label = format!("{}{last_order}", st.label);
        fig.prims.push(Prim::Circle {
            center: [w - right - text_width(&label, 12.0) - 24.0, ly - 4.0],
            radius: 4.0,
            fill: c,
        });
        fig.prims.push(Prim::Text {
            pos: [w - right - 10.0, ly],
            text: label,
            size: 12.0,
            anchor: Anchor::End,
            color: DARK,
        });
        ly += 18.0;
    }
    // Reference slopes 1/2 and 1 in h through the first point of the first study.
    if let Some(l) = studies.first().and_then(|s| s.levels.first()) {
        for slope in [0.5, 1.0] {
            // End where the line leaves the plot: at the left edge or the bottom.
            let x_end = 10f64
                .powf(x0)
                .max(l.h_area * (10f64.powf(y0) / l.error).powf(1.0 / slope));
            let y_end = l.error * (x_end / l.h_area).powf(slope);
            fig.prims.push(Prim::Polyline {
                points: vec![[px(l.h_area), py(l.error)], [px(x_end), py(y_end)]],
                color: DARK,
                width: 1.0,
                dashed: true,
            });
            fig.prims.push(Prim::Text {
                pos: [px(x_end) + 6.0, py(y_end) - 6.0],
                text: format!("{slope}"),
                size: 12.0,
                anchor: Anchor::Start,
                color: DARK,
            });
        }
        fig.prims.push(Prim::Text {
            pos: [w - right - 10.0, h - bottom - 10.0],
            text: "dashed: slopes 1/2 and 1 in h".into(),
            size: 12.0,
            anchor: Anchor::End,
            color: DARK,
        });
    }
    fig
}
