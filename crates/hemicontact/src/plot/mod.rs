//! Figures as scenes of simple primitives, rendered to SVG (text) and PNG (tiny-skia, with
//! an embedded subset of DejaVu Sans, [`font`], so no system fonts are needed).
//!
//! A [`Figure`] is a list of [`Prim`]itives in pixel coordinates (origin top-left, y down).
//! [`deformed`] builds the deformed-mesh figures (one case, or several side by side),
//! [`interface`] the contact quantities along each contact part against the arc length,
//! [`convergence`] the log–log convergence plot. [`layout`] holds the shared layout rules
//! (round numbers, ticks, fitted titles, label boxes), [`field`] the colour fields and
//! their colour bar, [`legend`] the legends set below a panel, [`scales`] the scales of the
//! deformed drawing (magnification, arrows), [`raster`] the colour fields of meshes too fine
//! to draw cell by cell.

pub mod axes;
mod color;
pub mod convergence;
pub mod deformed;
pub mod field;
pub mod font;
pub mod interface;
pub mod layout;
pub mod legend;
pub mod raster;
pub mod scales;
#[cfg(test)]
mod tests;

use crate::error::{Error, Result};
use std::fmt::Write as _;
use std::path::Path;

pub use color::Rgb;

/// Text anchor.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Anchor {
    /// Left-aligned at the position.
    Start,
    /// Centred on the position.
    Middle,
    /// Right-aligned at the position.
    End,
}

/// A drawing primitive (pixel coordinates).
#[derive(Clone, Debug, PartialEq)]
pub enum Prim {
    /// Line segments `(a, b)` drawn with one stroke.
    Segments {
        /// The segments.
        segments: Vec<([f64; 2], [f64; 2])>,
        /// Colour.
        color: Rgb,
        /// Width (px).
        width: f64,
    },
    /// An open or closed polyline.
    Polyline {
        /// Vertices.
        points: Vec<[f64; 2]>,
        /// Colour.
        color: Rgb,
        /// Width (px).
        width: f64,
        /// Dashed.
        dashed: bool,
    },
    /// A filled polygon (outlined by a 0.5 px line of its colour, so that adjacent polygons
    /// show no seams).
    Polygon {
        /// Vertices.
        points: Vec<[f64; 2]>,
        /// Fill colour.
        fill: Rgb,
    },
    /// Several filled polygons of one colour (cells of a colour field), each outlined by a
    /// 0.5 px line of the colour like [`Prim::Polygon`].
    Polygons {
        /// The polygons' vertices.
        rings: Vec<Vec<[f64; 2]>>,
        /// Fill colour.
        fill: Rgb,
    },
    /// An arrow from `from` to `to` with a head of `head` px.
    Arrow {
        /// Tail.
        from: [f64; 2],
        /// Tip.
        to: [f64; 2],
        /// Colour.
        color: Rgb,
        /// Width (px).
        width: f64,
    },
    /// An image: a colour field sampled at the resolution of the picture
    /// ([`raster::rasterize`]), embedded in the SVG as a PNG.
    Raster(raster::Raster),
    /// A filled circle.
    Circle {
        /// Centre.
        center: [f64; 2],
        /// Radius (px).
        radius: f64,
        /// Fill colour.
        fill: Rgb,
    },
    /// A text label in DejaVu Sans.
    Text {
        /// Anchor position (baseline).
        pos: [f64; 2],
        /// The text (characters outside the embedded font are drawn as its empty box).
        text: String,
        /// Font size (px): the em square of the font.
        size: f64,
        /// Anchor.
        anchor: Anchor,
        /// Colour.
        color: Rgb,
    },
}

/// A figure: size in pixels and primitives.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Figure {
    /// Width (px).
    pub width: u32,
    /// Height (px).
    pub height: u32,
    /// Primitives, drawn in order.
    pub prims: Vec<Prim>,
}

fn hex(c: Rgb) -> String {
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

impl Figure {
    /// A blank figure.
    pub fn new(width: u32, height: u32) -> Self {
        Figure {
            width,
            height,
            prims: Vec::new(),
        }
    }

    /// The SVG document.
    pub fn to_svg(&self) -> String {
        let mut s = String::new();
        // Embedded images are linked the SVG 1.1 way (`xlink:href`), which every viewer reads.
        let xlink = if self.prims.iter().any(|p| matches!(p, Prim::Raster(_))) {
            " xmlns:xlink=\"http://www.w3.org/1999/xlink\""
        } else {
            ""
        };
        let _ = writeln!(
            s,
            "<svg xmlns=\"http://www.w3.org/2000/svg\"{xlink} width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\n\
             <rect width=\"{w}\" height=\"{h}\" fill=\"white\"/>",
            w = self.width,
            h = self.height
        );
        for p in &self.prims {
            svg_prim(&mut s, p);
        }
        s.push_str("</svg>\n");
        s
    }

    /// The PNG image.
    ///
    /// # Errors
    /// [`Error::Breakdown`] if the image cannot be allocated or encoded.
    pub fn to_png(&self) -> Result<Vec<u8>> {
        use tiny_skia::{
            Color, FillRule, Paint, PathBuilder, Pixmap, Stroke, StrokeDash, Transform,
        };
        let mut pm = Pixmap::new(self.width, self.height).ok_or_else(|| {
            Error::Breakdown(format!(
                "cannot allocate a {}×{} image",
                self.width, self.height
            ))
        })?;
        pm.fill(Color::WHITE);
        let paint_of = |c: Rgb| {
            let mut p = Paint::default();
            p.set_color_rgba8(c[0], c[1], c[2], 255);
            p.anti_alias = true;
            p
        };
        let id = Transform::identity();
        let f = |x: f64| x as f32;
        for p in &self.prims {
            match p {
                Prim::Segments {
                    segments,
                    color,
                    width,
                } => {
                    let mut pb = PathBuilder::new();
                    for (a, b) in segments {
                        pb.move_to(f(a[0]), f(a[1]));
                        pb.line_to(f(b[0]), f(b[1]));
                    }
                    if let Some(path) = pb.finish() {
                        let stroke = Stroke {
                            width: f(*width),
                            ..Stroke::default()
                        };
                        pm.stroke_path(&path, &paint_of(*color), &stroke, id, None);
                    }
                }
                Prim::Polyline {
                    points,
                    color,
                    width,
                    dashed,
                } => {
                    if let Some(path) = polygon_path(points, false) {
                        let mut stroke = Stroke {
                            width: f(*width),
                            ..Stroke::default()
                        };
                        if *dashed {
                            stroke.dash = StrokeDash::new(vec![6.0, 4.0], 0.0);
                        }
                        pm.stroke_path(&path, &paint_of(*color), &stroke, id, None);
                    }
                }
                Prim::Polygon { points, fill } => {
                    if let Some(path) = polygon_path(points, true) {
                        pm.fill_path(&path, &paint_of(*fill), FillRule::Winding, id, None);
                        // A hairline of the fill colour closes the anti-aliased seams
                        // between adjacent polygons (cells of a colour field).
                        let stroke = Stroke {
                            width: 0.5,
                            ..Stroke::default()
                        };
                        pm.stroke_path(&path, &paint_of(*fill), &stroke, id, None);
                    }
                }
                Prim::Polygons { rings, fill } => {
                    let mut pb = PathBuilder::new();
                    for ring in rings.iter().filter(|r| !r.is_empty()) {
                        pb.move_to(f(ring[0][0]), f(ring[0][1]));
                        for q in &ring[1..] {
                            pb.line_to(f(q[0]), f(q[1]));
                        }
                        pb.close();
                    }
                    if let Some(path) = pb.finish() {
                        pm.fill_path(&path, &paint_of(*fill), FillRule::Winding, id, None);
                        let stroke = Stroke {
                            width: 0.5,
                            ..Stroke::default()
                        };
                        pm.stroke_path(&path, &paint_of(*fill), &stroke, id, None);
                    }
                }
                Prim::Arrow {
                    from,
                    to,
                    color,
                    width,
                } => {
                    if let Some(path) = polygon_path(&[*from, *to], false) {
                        let stroke = Stroke {
                            width: f(*width),
                            ..Stroke::default()
                        };
                        pm.stroke_path(&path, &paint_of(*color), &stroke, id, None);
                    }
                    let h = arrow_head(*from, *to, 3.0 + 2.0 * width);
                    if let Some(path) = polygon_path(&h, true) {
                        pm.fill_path(&path, &paint_of(*color), FillRule::Winding, id, None);
                    }
                }
                Prim::Raster(r) => {
                    let size = tiny_skia::IntSize::from_wh(r.width, r.height);
                    if let Some(image) =
                        size.and_then(|size| tiny_skia::Pixmap::from_vec(r.figure_pixels(), size))
                    {
                        pm.draw_pixmap(
                            r.x,
                            r.y,
                            image.as_ref(),
                            &tiny_skia::PixmapPaint::default(),
                            id,
                            None,
                        );
                    }
                }
                Prim::Circle {
                    center,
                    radius,
                    fill,
                } => {
                    if let Some(path) =
                        PathBuilder::from_circle(f(center[0]), f(center[1]), f(*radius))
                    {
                        pm.fill_path(&path, &paint_of(*fill), FillRule::Winding, id, None);
                    }
                }
                Prim::Text {
                    pos,
                    text,
                    size,
                    anchor,
                    color,
                } => {
                    draw_text(&mut pm, *pos, text, *size, *anchor, *color);
                }
            }
        }
        pm.encode_png()
            .map_err(|e| Error::Breakdown(format!("PNG encoding: {e}")))
    }

    /// Writes `<stem>.svg` and `<stem>.png` into `dir` (atomically); returns the paths.
    ///
    /// # Errors
    /// [`Error::Io`] if a file cannot be written.
    pub fn write(&self, dir: &Path, stem: &str) -> Result<Vec<std::path::PathBuf>> {
        let svg = dir.join(format!("{stem}.svg"));
        let png = dir.join(format!("{stem}.png"));
        crate::atomic_file::write(&svg, self.to_svg().as_bytes())?;
        crate::atomic_file::write(&png, &self.to_png()?)?;
        Ok(vec![svg, png])
    }
}

/// The image of `r` at its full resolution as a PNG file (`None` if it cannot be encoded).
fn raster_png(r: &raster::Raster) -> Option<Vec<u8>> {
    let size = tiny_skia::IntSize::from_wh(r.image_width(), r.image_height())?;
    tiny_skia::Pixmap::from_vec(r.rgba.clone(), size)?
        .encode_png()
        .ok()
}

/// A tiny-skia path through `points`, closed if `close`.
fn polygon_path(points: &[[f64; 2]], close: bool) -> Option<tiny_skia::Path> {
    let mut pb = tiny_skia::PathBuilder::new();
    for (k, q) in points.iter().enumerate() {
        if k == 0 {
            pb.move_to(q[0] as f32, q[1] as f32);
        } else {
            pb.line_to(q[0] as f32, q[1] as f32);
        }
    }
    if close {
        pb.close();
    }
    pb.finish()
}

/// Width in pixels of `text` at font size `size` (px), from the embedded font's advance
/// widths ([`font::text_width`]).
pub fn text_width(text: &str, size: f64) -> f64 {
    font::text_width(text, size)
}

/// The three corners of an arrow head of length `len` at `to`.
fn arrow_head(from: [f64; 2], to: [f64; 2], len: f64) -> [[f64; 2]; 3] {
    let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
    let l = (dx * dx + dy * dy).sqrt().max(1e-9);
    let (ux, uy) = (dx / l, dy / l);
    let len = len.min(0.6 * l);
    let base = [to[0] - len * ux, to[1] - len * uy];
    let w = 0.5 * len;
    [
        to,
        [base[0] - w * uy, base[1] + w * ux],
        [base[0] + w * uy, base[1] - w * ux],
    ]
}

/// Draws `text` with the embedded font: glyph outlines filled with anti-aliasing.
fn draw_text(
    pm: &mut tiny_skia::Pixmap,
    pos: [f64; 2],
    text: &str,
    size: f64,
    anchor: Anchor,
    color: Rgb,
) {
    let width = text_width(text, size);
    let x0 = match anchor {
        Anchor::Start => pos[0],
        Anchor::Middle => pos[0] - width / 2.0,
        Anchor::End => pos[0] - width,
    };
    if let Some(path) = font::text_path(text, [x0, pos[1]], size) {
        let mut paint = tiny_skia::Paint::default();
        paint.set_color_rgba8(color[0], color[1], color[2], 255);
        paint.anti_alias = true;
        pm.fill_path(
            &path,
            &paint,
            tiny_skia::FillRule::Winding,
            tiny_skia::Transform::identity(),
            None,
        );
    }
}

/// Appends the SVG element of one primitive to `s` (coordinates rounded to 0.1 px).
fn svg_prim(s: &mut String, p: &Prim) {
    match p {
        Prim::Segments {
            segments,
            color,
            width,
        } => {
            let mut d = String::with_capacity(24 * segments.len());
            for (a, b) in segments {
                let _ = write!(d, "M{:.1} {:.1}L{:.1} {:.1}", a[0], a[1], b[0], b[1]);
            }
            let _ = writeln!(
                s,
                "<path d=\"{d}\" stroke=\"{}\" stroke-width=\"{width}\" fill=\"none\"/>",
                hex(*color)
            );
        }
        Prim::Polyline {
            points,
            color,
            width,
            dashed,
        } => {
            let pts: Vec<String> = points
                .iter()
                .map(|p| format!("{:.1},{:.1}", p[0], p[1]))
                .collect();
            let dash = if *dashed {
                " stroke-dasharray=\"6 4\""
            } else {
                ""
            };
            let _ = writeln!(
                s,
                "<polyline points=\"{}\" stroke=\"{}\" stroke-width=\"{width}\" fill=\"none\"{dash}/>",
                pts.join(" "),
                hex(*color)
            );
        }
        Prim::Polygon { points, fill } => {
            let pts: Vec<String> = points
                .iter()
                .map(|p| format!("{:.1},{:.1}", p[0], p[1]))
                .collect();
            let _ = writeln!(
                s,
                "<polygon points=\"{}\" fill=\"{c}\" stroke=\"{c}\" stroke-width=\"0.5\"/>",
                pts.join(" "),
                c = hex(*fill)
            );
        }
        Prim::Polygons { rings, fill } => {
            let mut d = String::with_capacity(32 * rings.len());
            for ring in rings {
                for (k, p) in ring.iter().enumerate() {
                    let c = if k == 0 { 'M' } else { 'L' };
                    let _ = write!(d, "{c}{:.1} {:.1}", p[0], p[1]);
                }
                d.push('Z');
            }
            let _ = writeln!(
                s,
                "<path d=\"{d}\" fill=\"{c}\" stroke=\"{c}\" stroke-width=\"0.5\"/>",
                c = hex(*fill)
            );
        }
        Prim::Arrow {
            from,
            to,
            color,
            width,
        } => {
            let head = arrow_head(*from, *to, 3.0 + 2.0 * width);
            let _ = writeln!(
                s,
                "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"{c}\" stroke-width=\"{width}\"/>\
                 <polygon points=\"{:.1},{:.1} {:.1},{:.1} {:.1},{:.1}\" fill=\"{c}\"/>",
                from[0],
                from[1],
                to[0],
                to[1],
                head[0][0],
                head[0][1],
                head[1][0],
                head[1][1],
                head[2][0],
                head[2][1],
                c = hex(*color)
            );
        }
        Prim::Raster(r) => {
            if let Some(png) = raster_png(r) {
                let _ = writeln!(
                    s,
                    "<image x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" \
                     preserveAspectRatio=\"none\" xlink:href=\"data:image/png;base64,{}\"/>",
                    r.x,
                    r.y,
                    r.width,
                    r.height,
                    raster::base64(&png)
                );
            }
        }
        Prim::Circle {
            center,
            radius,
            fill,
        } => {
            let _ = writeln!(
                s,
                "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"{radius}\" fill=\"{}\"/>",
                center[0],
                center[1],
                hex(*fill)
            );
        }
        Prim::Text {
            pos,
            text,
            size,
            anchor,
            color,
        } => {
            let a = match anchor {
                Anchor::Start => "start",
                Anchor::Middle => "middle",
                Anchor::End => "end",
            };
            let _ = writeln!(
                s,
                "<text x=\"{:.1}\" y=\"{:.1}\" font-family=\"{}\" font-size=\"{size:.1}\" \
                 text-anchor=\"{a}\" fill=\"{}\">{}</text>",
                pos[0],
                pos[1],
                font::SVG_FONT_FAMILY,
                hex(*color),
                xml_escape(text)
            );
        }
    }
}
