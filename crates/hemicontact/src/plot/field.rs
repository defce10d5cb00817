//! Colour fields on the deformed mesh and their colour bar.

use super::layout::{number, si_prefix, ticks};
use super::{Anchor, Prim, Rgb};
use crate::problem::Problem;
use crate::solver::Solution;

const DARK: Rgb = [30, 30, 30];

/// A scalar field drawn as colours on the deformed mesh (2D), with a colour bar.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ColorField {
    /// No colours: the mesh edges only.
    None,
    /// Von Mises stress `√(3/2 s:s)` of each cell (Pa), s the deviator of σ (locking
    /// stress included), as in `solution.vtu`.
    #[default]
    VonMises,
    /// Volumetric strain `tr ε` of each cell (dimensionless).
    TraceStrain,
    /// Locking multiplier λ_T of each cell (Pa): the multiplier of ideal locking, `C_κ Q₊`
    /// for the penalty form, 0 without locking.
    LockingMultiplier,
    /// Contact pressure `p = −σ_ν` (Pa) on the contact boundary edges (the mean of the two
    /// end points' pressures), the cells left blank.
    ContactPressure,
}

impl ColorField {
    /// The colour bar's label (name and symbol).
    pub fn label(self) -> &'static str {
        match self {
            ColorField::None => "",
            ColorField::VonMises => "von Mises stress σ_vM",
            ColorField::TraceStrain => "volumetric strain tr ε",
            ColorField::LockingMultiplier => "locking multiplier λ_T",
            ColorField::ContactPressure => "contact pressure p",
        }
    }

    /// The field's SI unit (empty: dimensionless).
    pub fn unit(self) -> &'static str {
        match self {
            ColorField::TraceStrain | ColorField::None => "",
            _ => "Pa",
        }
    }

    /// The values of the field on the cells (`None` for [`ColorField::None`] and
    /// [`ColorField::ContactPressure`], which is not a cell field).
    pub fn cell_values(self, problem: &Problem, solution: &Solution) -> Option<Vec<f64>> {
        let cells = || crate::fields::cell_fields(problem, solution);
        match self {
            ColorField::VonMises => Some(cells().von_mises),
            ColorField::TraceStrain => Some(cells().trace_strain),
            ColorField::LockingMultiplier => Some(cells().locking_multiplier),
            ColorField::None | ColorField::ContactPressure => None,
        }
    }
}

/// The colour range of `values`: `[min(0, min), max]` for fields that are never negative
/// (the range starts at 0), `[min, max]` otherwise; a constant field gets a unit range
/// above its value so that it maps to the low end.
pub fn range(values: &[f64]) -> [f64; 2] {
    let finite = values.iter().copied().filter(|v| v.is_finite());
    let (lo, hi) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    if lo > hi {
        return [0.0, 1.0];
    }
    let lo = lo.min(0.0);
    if hi - lo <= 1e-12 * hi.abs().max(lo.abs()) || hi <= lo {
        [lo, lo + if lo == 0.0 { 1.0 } else { lo.abs() }]
    } else {
        [lo, hi]
    }
}

/// The colour of `t ∈ [0, 1]` on a light sequential map (pale yellow, orange, brown), light
/// enough that mesh lines, arrows and markers stay visible on it.
pub fn colormap(t: f64) -> Rgb {
    const STOPS: [Rgb; 5] = [
        [255, 252, 212],
        [254, 227, 145],
        [254, 180, 80],
        [236, 120, 40],
        [190, 70, 20],
    ];
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let x = t * (STOPS.len() - 1) as f64;
    let k = (x.floor() as usize).min(STOPS.len() - 2);
    let f = x - k as f64;
    let mut c = [0u8; 3];
    for i in 0..3 {
        let (a, b) = (f64::from(STOPS[k][i]), f64::from(STOPS[k + 1][i]));
        c[i] = (a + f * (b - a)).round() as u8;
    }
    c
}

/// The number of colour bands of a field and its bar (64: the eye sees a continuous ramp).
pub const LEVELS: usize = 64;

/// The band (0 … [`LEVELS`] − 1) of value `v` in the range `[lo, hi]`.
pub fn level(v: f64, [lo, hi]: [f64; 2]) -> usize {
    let t = (v - lo) / (hi - lo);
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    ((t * LEVELS as f64) as usize).min(LEVELS - 1)
}

/// The colour of band `k`: the map at the band's middle.
pub fn level_color(k: usize) -> Rgb {
    colormap((k as f64 + 0.5) / LEVELS as f64)
}

/// The colour of value `v` in the range `[lo, hi]`.
pub fn color_of(v: f64, [lo, hi]: [f64; 2]) -> Rgb {
    colormap((v - lo) / (hi - lo))
}

/// A vertical colour bar in the box `(x, y, w, h)` (px) for the range `[lo, hi]`: the
/// colour ramp, ticks at round values with labels to its right in the unit with an SI
/// prefix, and the unit above it (the field's name goes into the figure's legend).
pub fn colorbar(field: ColorField, [lo, hi]: [f64; 2], rect: [f64; 4]) -> Vec<Prim> {
    let [x, y, w, h] = rect;
    let mut prims = Vec::new();
    for k in 0..LEVELS {
        let (a, b) = (k as f64 / LEVELS as f64, (k + 1) as f64 / LEVELS as f64);
        let (ya, yb) = (y + h * (1.0 - a), y + h * (1.0 - b));
        prims.push(Prim::Polygon {
            points: vec![[x, ya], [x + w, ya], [x + w, yb], [x, yb]],
            fill: level_color(k),
        });
    }
    prims.push(Prim::Polyline {
        points: vec![[x, y], [x + w, y], [x + w, y + h], [x, y + h], [x, y]],
        color: DARK,
        width: 1.0,
        dashed: false,
    });
    let unit = field.unit();
    let (factor, prefixed) = if unit.is_empty() {
        (1.0, String::new())
    } else {
        si_prefix(hi.abs().max(lo.abs()), unit)
    };
    for t in ticks(lo, hi, 5) {
        let ty = y + h * (1.0 - (t - lo) / (hi - lo));
        prims.push(Prim::Segments {
            segments: vec![([x + w, ty], [x + w + 4.0, ty])],
            color: DARK,
            width: 1.0,
        });
        prims.push(Prim::Text {
            pos: [x + w + 7.0, ty + 4.0],
            text: number(t / factor),
            size: 11.0,
            anchor: Anchor::Start,
            color: DARK,
        });
    }
    let unit_label = if prefixed.is_empty() {
        "(–)".to_string()
    } else {
        format!("({prefixed})")
    };
    prims.push(Prim::Text {
        pos: [x + w, y - 8.0],
        text: unit_label,
        size: 11.0,
        anchor: Anchor::End,
        color: DARK,
    });
    prims
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colormap_runs_from_light_to_dark() {
        let lum = |c: Rgb| 0.3 * f64::from(c[0]) + 0.59 * f64::from(c[1]) + 0.11 * f64::from(c[2]);
        let mut last = f64::INFINITY;
        for k in 0..=20 {
            let l = lum(colormap(k as f64 / 20.0));
            assert!(l < last, "luminance not decreasing at {k}");
            last = l;
        }
        assert_eq!(colormap(-1.0), colormap(0.0));
        assert_eq!(colormap(f64::NAN), colormap(0.0));
    }

    #[test]
    fn ranges_start_at_zero_for_positive_fields_and_never_collapse() {
        assert_eq!(range(&[2.0, 5.0, 3.0]), [0.0, 5.0]);
        assert_eq!(range(&[-1.0, 3.0]), [-1.0, 3.0]);
        assert_eq!(range(&[0.0, 0.0]), [0.0, 1.0]);
        assert_eq!(range(&[]), [0.0, 1.0]);
    }

    #[test]
    fn bands_split_the_range_evenly() {
        let r = [2.0, 10.0];
        assert_eq!(level(2.0, r), 0);
        assert_eq!(level(10.0, r), LEVELS - 1);
        assert_eq!(level(6.0, r), LEVELS / 2);
        assert_eq!(level(-5.0, r), 0);
        assert_eq!(level(f64::NAN, r), 0);
    }
}
