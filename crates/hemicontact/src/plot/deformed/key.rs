//! The legend and the title of a deformed-mesh panel: what the legend needs to know
//! ([`Key`]), its entries, and the colours and sizes of the contact markers.

use super::palette::{ARROW, BLUE, CONTACT, DARK, GREY, MESH, RED};
use crate::plot::field::{color_of, ColorField};
use crate::plot::layout::{fit_text, quantity, round_down_125};
use crate::plot::legend::{Entry, Swatch};
use crate::plot::{Anchor, Prim, Rgb};
use crate::solver::{ContactResult, FrictionState, NormalState, Solution};

/// Marker colour of a contact point: its friction state, and for frictionless points its
/// normal state.
pub(super) fn status_color(c: &ContactResult) -> Rgb {
    match (c.friction_state, c.normal_state) {
        (FrictionState::Stick, _) => BLUE,
        (FrictionState::Slip, _) => RED,
        (FrictionState::None, NormalState::Contact) => CONTACT,
        (FrictionState::None, NormalState::Separated) => GREY,
    }
}

/// Whether a contact point touches its foundation (normal state; drawn as a large marker).
pub(super) fn touching(c: &ContactResult) -> bool {
    c.normal_state == NormalState::Contact
}

/// What a panel's legend needs to know.
pub(super) struct Key {
    pub(super) magnification: f64,
    pub(super) max_t: f64,
    /// Pixels per Pa of the arrows.
    pub(super) arrow_scale: f64,
    pub(super) arrows: usize,
    pub(super) touching_points: usize,
    pub(super) field: ColorField,
    pub(super) gaps: bool,
    /// Whether the problem has a contact boundary.
    pub(super) contact: bool,
    /// Whether a contact boundary faces a rigid foundation or obstacle (not another body).
    pub(super) foundation: bool,
    /// Whether the mesh edges are drawn (else only the deformed boundary: too fine).
    pub(super) mesh_drawn: bool,
    pub(super) cells: usize,
    /// Whether interfaces between materials are drawn (2D, several materials).
    pub(super) interfaces: bool,
}

/// The legend entries of a panel.
pub(super) fn entries(solution: &Solution, key: &Key) -> Vec<Entry> {
    let m = key.magnification;
    let scale = if m > 1.0 {
        format!("displacements × {}", crate::plot::layout::number(m))
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
                format!(
                    "rigid foundation (gap × {})",
                    crate::plot::layout::number(m)
                )
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
pub(super) fn title(text: &str, x0: f64, y0: f64, w: f64) -> (Vec<Prim>, f64) {
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
