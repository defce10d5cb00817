//! Legends: entries (a swatch and a label) set in rows that wrap within a width, placed by
//! the figures outside their drawing areas.

use super::layout::{text_box, Rect};
use super::{Anchor, Prim, Rgb};

const DARK: Rgb = [30, 30, 30];

/// What an entry's swatch shows.
#[derive(Clone, Debug, PartialEq)]
pub enum Swatch {
    /// A line sample (24 px long).
    Line {
        /// Colour.
        color: Rgb,
        /// Width (px).
        width: f64,
        /// Dashed.
        dashed: bool,
    },
    /// A dot.
    Dot {
        /// Fill colour.
        color: Rgb,
        /// Radius (px).
        radius: f64,
    },
    /// A filled square.
    Patch {
        /// Fill colour.
        color: Rgb,
    },
    /// An arrow of a given length (px): the reference arrow of a force scale.
    Arrow {
        /// Colour.
        color: Rgb,
        /// Length (px).
        length: f64,
    },
    /// No swatch: a note.
    None,
}

/// A legend entry.
#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    /// The swatch.
    pub swatch: Swatch,
    /// The label.
    pub label: String,
}

impl Entry {
    /// An entry of a swatch and a label.
    pub fn new(swatch: Swatch, label: impl Into<String>) -> Self {
        Entry {
            swatch,
            label: label.into(),
        }
    }

    fn swatch_width(&self) -> f64 {
        match self.swatch {
            Swatch::Line { .. } => 24.0,
            Swatch::Dot { .. } | Swatch::Patch { .. } => 12.0,
            Swatch::Arrow { length, .. } => length,
            Swatch::None => 0.0,
        }
    }
}

/// A laid-out legend: its primitives, the box of each entry, and its bottom (px).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Placed {
    /// Primitives to draw.
    pub prims: Vec<Prim>,
    /// Box of each entry (swatch and label).
    pub boxes: Vec<Rect>,
    /// The y of the legend's lower edge (px).
    pub bottom: f64,
}

/// Sets `entries` at font size `size` in rows from `top` down, left-aligned within the
/// columns `x0..x1`; an entry that does not fit in the rest of a row starts the next.
pub fn flow(entries: &[Entry], x0: f64, x1: f64, top: f64, size: f64) -> Placed {
    let row = 1.55 * size;
    let gap = 1.4 * size;
    let mut out = Placed {
        bottom: top,
        ..Placed::default()
    };
    let (mut x, mut baseline) = (x0, top + 0.85 * size);
    for (k, e) in entries.iter().enumerate() {
        let sw = e.swatch_width();
        let pad = if sw > 0.0 { 6.0 } else { 0.0 };
        let width = sw + pad + super::text_width(&e.label, size);
        if k > 0 && x + width > x1 {
            x = x0;
            baseline += row;
        }
        let mid = baseline - 0.3 * size;
        match &e.swatch {
            Swatch::Line {
                color,
                width,
                dashed,
            } => out.prims.push(Prim::Polyline {
                points: vec![[x, mid], [x + sw, mid]],
                color: *color,
                width: *width,
                dashed: *dashed,
            }),
            Swatch::Dot { color, radius } => out.prims.push(Prim::Circle {
                center: [x + sw / 2.0, mid],
                radius: *radius,
                fill: *color,
            }),
            Swatch::Patch { color } => out.prims.push(Prim::Polygon {
                points: vec![
                    [x, mid - 5.0],
                    [x + sw, mid - 5.0],
                    [x + sw, mid + 5.0],
                    [x, mid + 5.0],
                ],
                fill: *color,
            }),
            Swatch::Arrow { color, length } => out.prims.push(Prim::Arrow {
                from: [x, mid],
                to: [x + length, mid],
                color: *color,
                width: 1.5,
            }),
            Swatch::None => {}
        }
        out.prims.push(Prim::Text {
            pos: [x + sw + pad, baseline],
            text: e.label.clone(),
            size,
            anchor: Anchor::Start,
            color: DARK,
        });
        let t = text_box(&e.label, x + sw + pad, baseline, size);
        out.boxes
            .push([x, t[1].min(mid - 6.0), t[2], t[3].max(mid + 6.0)]);
        x += width + gap;
        out.bottom = out.bottom.max(t[3].max(mid + 6.0));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::layout::{inside, overlaps};

    #[test]
    fn legend_rows_wrap_inside_their_columns_without_overlap() {
        let entries: Vec<Entry> = (0..9)
            .map(|k| {
                Entry::new(
                    Swatch::Dot {
                        color: [0, 0, 0],
                        radius: 4.0,
                    },
                    format!("entry number {k} with a long label"),
                )
            })
            .collect();
        let placed = flow(&entries, 20.0, 420.0, 100.0, 12.0);
        assert_eq!(placed.boxes.len(), entries.len());
        let area = [20.0, 100.0, 420.0, placed.bottom];
        for (i, a) in placed.boxes.iter().enumerate() {
            assert!(inside(*a, area), "{a:?} outside {area:?}");
            for b in &placed.boxes[i + 1..] {
                assert!(!overlaps(*a, *b), "{a:?} overlaps {b:?}");
            }
        }
        assert!(placed.bottom > 100.0 + 3.0 * 12.0, "wrapped into rows");
    }
}
