//! Linear axes: the map from values to pixels, and a frame with round ticks, tick labels
//! and axis titles with units.

use super::layout::{number, ticks};
use super::{Anchor, Prim, Rgb};

const DARK: Rgb = [30, 30, 30];
const GRID: Rgb = [225, 225, 225];

/// One linear axis: values `lo..hi` onto pixels `px0..px1` (`px1 < px0` for a y axis
/// pointing up).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Axis {
    /// Value at `px0`.
    pub lo: f64,
    /// Value at `px1`.
    pub hi: f64,
    /// Pixel of `lo`.
    pub px0: f64,
    /// Pixel of `hi`.
    pub px1: f64,
}

impl Axis {
    /// The pixel of value `v`.
    pub fn px(&self, v: f64) -> f64 {
        self.px0 + (v - self.lo) / (self.hi - self.lo) * (self.px1 - self.px0)
    }
}

/// The frame of the axes `x` (bottom) and `y` (left): a box, light grid lines and ticks at
/// round values, tick labels (the values divided by `factors[i]`, e.g. 10⁶ to print MPa)
/// and the axis titles `labels` (x centred below, y above the left edge).
pub fn frame(x: &Axis, y: &Axis, factors: [f64; 2], labels: [&str; 2], grid: bool) -> Vec<Prim> {
    let mut prims = Vec::new();
    let (l, r) = (x.px0.min(x.px1), x.px0.max(x.px1));
    let (t, b) = (y.px0.min(y.px1), y.px0.max(y.px1));
    let xt = ticks(x.lo.min(x.hi), x.lo.max(x.hi), 6);
    let yt = ticks(y.lo.min(y.hi), y.lo.max(y.hi), 5);
    if grid {
        let mut lines = Vec::new();
        for &v in &xt {
            lines.push(([x.px(v), t], [x.px(v), b]));
        }
        for &v in &yt {
            lines.push(([l, y.px(v)], [r, y.px(v)]));
        }
        prims.push(Prim::Segments {
            segments: lines,
            color: GRID,
            width: 1.0,
        });
    }
    let mut marks = Vec::new();
    for &v in &xt {
        let p = x.px(v);
        marks.push(([p, b], [p, b + 5.0]));
        prims.push(Prim::Text {
            pos: [p, b + 18.0],
            text: number(v / factors[0]),
            size: 11.0,
            anchor: Anchor::Middle,
            color: DARK,
        });
    }
    for &v in &yt {
        let p = y.px(v);
        marks.push(([l - 5.0, p], [l, p]));
        prims.push(Prim::Text {
            pos: [l - 8.0, p + 4.0],
            text: number(v / factors[1]),
            size: 11.0,
            anchor: Anchor::End,
            color: DARK,
        });
    }
    prims.push(Prim::Segments {
        segments: marks,
        color: DARK,
        width: 1.0,
    });
    prims.push(Prim::Polyline {
        points: vec![[l, t], [r, t], [r, b], [l, b], [l, t]],
        color: DARK,
        width: 1.0,
        dashed: false,
    });
    let titles = [
        ([0.5 * (l + r), b + 36.0], Anchor::Middle),
        ([l, t - 8.0], Anchor::Start),
    ];
    for (k, (pos, anchor)) in titles.into_iter().enumerate() {
        if !labels[k].is_empty() {
            prims.push(Prim::Text {
                pos,
                text: labels[k].to_string(),
                size: 12.0,
                anchor,
                color: DARK,
            });
        }
    }
    prims
}

/// Height (px) the frame needs below its box for tick labels and the x title.
pub const BELOW: f64 = 44.0;
/// Height (px) the frame needs above its box for the y title.
pub const ABOVE: f64 = 22.0;
