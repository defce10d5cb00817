//! The embedded font of the figures: a subset of DejaVu Sans (`assets/fonts/`, made by
//! `scripts/subset-font.sh`), whose advance widths lay text out and whose glyph outlines
//! the PNG renderer fills (anti-aliased, nonzero winding). The SVG names the same family,
//! so both renderings have the same metrics where DejaVu Sans is installed.
//!
//! Sizes are font sizes in pixels (the em square): a glyph of advance `a` font units is
//! `a · size / units_per_em` px wide.

use std::sync::OnceLock;
use ttf_parser::{Face, GlyphId, OutlineBuilder};

/// The font file (DejaVu Sans, subset: ASCII, Greek, mathematical signs, super- and
/// subscripts; licence in `assets/fonts/LICENSE`).
pub const FONT_DATA: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans-subset.ttf");

/// The font family the SVG output names.
pub const SVG_FONT_FAMILY: &str = "DejaVu Sans, sans-serif";

/// The parsed font, or `None` if the embedded file cannot be parsed (text is then laid out
/// with an average advance of 0.6 em and not drawn in PNG).
fn face() -> Option<&'static Face<'static>> {
    static FACE: OnceLock<Option<Face<'static>>> = OnceLock::new();
    FACE.get_or_init(|| Face::parse(FONT_DATA, 0).ok()).as_ref()
}

/// The glyph of a character: its own, else the font's `.notdef` box (glyph 0).
fn glyph(face: &Face<'_>, ch: char) -> GlyphId {
    face.glyph_index(ch).unwrap_or(GlyphId(0))
}

/// Width (px) of `text` at font size `size` (px): the sum of the glyphs' advance widths.
pub fn text_width(text: &str, size: f64) -> f64 {
    match face() {
        Some(face) => {
            let units: f64 = text
                .chars()
                .map(|ch| f64::from(face.glyph_hor_advance(glyph(face, ch)).unwrap_or(0)))
                .sum();
            units * size / f64::from(face.units_per_em())
        }
        None => 0.6 * size * text.chars().count() as f64,
    }
}

/// Height (px) above the baseline of capitals at font size `size` (the font's cap height,
/// about 0.73 em).
pub fn cap_height(size: f64) -> f64 {
    match face() {
        Some(face) => {
            let cap = face.capital_height().unwrap_or(1493);
            f64::from(cap) * size / f64::from(face.units_per_em())
        }
        None => 0.73 * size,
    }
}

/// Collects glyph outlines into a tiny-skia path, mapping font units to pixels: `x ↦ ox +
/// k x`, `y ↦ oy − k y` (font y is up, pixel y is down).
struct PathSink {
    pb: tiny_skia::PathBuilder,
    origin: [f32; 2],
    k: f32,
}

impl PathSink {
    fn at(&self, x: f32, y: f32) -> (f32, f32) {
        (self.origin[0] + self.k * x, self.origin[1] - self.k * y)
    }
}

impl OutlineBuilder for PathSink {
    fn move_to(&mut self, x: f32, y: f32) {
        let (x, y) = self.at(x, y);
        self.pb.move_to(x, y);
    }
    fn line_to(&mut self, x: f32, y: f32) {
        let (x, y) = self.at(x, y);
        self.pb.line_to(x, y);
    }
    fn quad_to(&mut self, x1: f32, y1: f32, x: f32, y: f32) {
        let (x1, y1) = self.at(x1, y1);
        let (x, y) = self.at(x, y);
        self.pb.quad_to(x1, y1, x, y);
    }
    fn curve_to(&mut self, x1: f32, y1: f32, x2: f32, y2: f32, x: f32, y: f32) {
        let (x1, y1) = self.at(x1, y1);
        let (x2, y2) = self.at(x2, y2);
        let (x, y) = self.at(x, y);
        self.pb.cubic_to(x1, y1, x2, y2, x, y);
    }
    fn close(&mut self) {
        self.pb.close();
    }
}

/// The outline of `text` set at font size `size` (px) with its baseline starting at `pos`
/// (px), as one path of all its glyphs; `None` for text without visible glyphs.
pub fn text_path(text: &str, pos: [f64; 2], size: f64) -> Option<tiny_skia::Path> {
    let face = face()?;
    let k = size / f64::from(face.units_per_em());
    let mut sink = PathSink {
        pb: tiny_skia::PathBuilder::new(),
        origin: [pos[0] as f32, pos[1] as f32],
        k: k as f32,
    };
    for ch in text.chars() {
        let g = glyph(face, ch);
        let _ = face.outline_glyph(g, &mut sink);
        let advance = f64::from(face.glyph_hor_advance(g).unwrap_or(0)) * k;
        sink.origin[0] += advance as f32;
    }
    sink.pb.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_embedded_font_parses_and_has_the_figures_characters() {
        let face = face().expect("embedded font parses");
        for ch in "Aa0·×−±²³√≤≥∞μνκτλΓσ⁻⁰¹₁‖".chars() {
            assert!(face.glyph_index(ch).is_some(), "no glyph for {ch:?}");
        }
    }

    #[test]
    fn text_width_is_positive_and_grows_with_the_string() {
        let mut last = 0.0;
        let mut s = String::new();
        for ch in "displacements × 20".chars() {
            s.push(ch);
            let w = text_width(&s, 12.0);
            assert!(
                w > last || ch == ' ' && w >= last,
                "{s:?}: {w} after {last}"
            );
            last = w;
        }
        assert!(last > 0.0);
        // Proportional: an "i" is narrower than an "M", and width scales with the size.
        assert!(text_width("i", 12.0) < text_width("M", 12.0));
        let (a, b) = (text_width("Mesh", 12.0), text_width("Mesh", 24.0));
        assert!((b - 2.0 * a).abs() < 1e-9, "{a} {b}");
    }

    #[test]
    fn glyph_outlines_fill_the_text_box() {
        let p = text_path("Hx", [10.0, 50.0], 20.0).expect("a path");
        let b = p.bounds();
        // Glyphs sit on the baseline (y = 50), rise by about the cap height, and span about
        // the advance width.
        assert!(b.bottom() <= 50.5 && b.top() < 50.0 - 0.6 * 20.0, "{b:?}");
        assert!(b.left() >= 10.0 && b.right() <= 10.0 + text_width("Hx", 20.0) as f32);
    }
}
