//! Colour fields of meshes too fine to draw cell by cell, sampled at the resolution of the
//! picture instead.
//!
//! Half a million triangles drawn into a panel of 700 × 500 pixels put several cells into
//! each pixel: drawn one by one as vector polygons they make SVG files of tens of megabytes
//! and cost seconds to render, for no detail a reader can see. Such a field is drawn as an
//! image ([`Raster`]) of [`SAMPLES`] image pixels per figure pixel. Each image pixel is
//! divided into `SUB × SUB` samples; a sample takes the colour of the cell that contains its
//! centre (none: transparent), and the pixel is the average of its samples, so edges are
//! anti-aliased and adjacent cells show no seams. The SVG embeds the image as a PNG; the
//! PNG figure draws it averaged down to one pixel per figure pixel.
//!
//! The sampling is exact arithmetic on the cells' corners in figure pixels: the same
//! cells always give the same image.

use super::color::Rgb;

/// Image pixels per figure pixel along each axis (the SVG's embedded image is sharp at 2×
/// zoom).
pub const SAMPLES: u32 = 2;

/// Samples per image pixel along each axis.
const SUB: usize = 2;

/// Largest image drawn (pixels); a larger field is left to the vector path.
const MAX_PIXELS: usize = 1 << 26;

/// An image placed in a figure: premultiplied RGBA, `samples` image pixels per figure pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct Raster {
    /// Left edge in figure pixels.
    pub x: i32,
    /// Top edge in figure pixels.
    pub y: i32,
    /// Width in figure pixels.
    pub width: u32,
    /// Height in figure pixels.
    pub height: u32,
    /// Image pixels per figure pixel along each axis.
    pub samples: u32,
    /// Premultiplied RGBA bytes, `(width · samples) × (height · samples)` pixels, row by row.
    pub rgba: Vec<u8>,
}

impl Raster {
    /// Width of the image in its own pixels.
    pub fn image_width(&self) -> u32 {
        self.width * self.samples
    }

    /// Height of the image in its own pixels.
    pub fn image_height(&self) -> u32 {
        self.height * self.samples
    }

    /// The image averaged down to one pixel per figure pixel (premultiplied RGBA, `width ×
    /// height` pixels): each pixel is the mean of its `samples × samples` image pixels.
    pub fn figure_pixels(&self) -> Vec<u8> {
        let s = self.samples as usize;
        let (w, h) = (self.width as usize, self.height as usize);
        let iw = w * s;
        let mut out = vec![0u8; 4 * w * h];
        let n = (s * s) as u32;
        for row in 0..h {
            for col in 0..w {
                let mut sum = [0u32; 4];
                for dy in 0..s {
                    let base = 4 * ((row * s + dy) * iw + col * s);
                    for dx in 0..s {
                        for (c, v) in sum.iter_mut().enumerate() {
                            *v += u32::from(self.rgba[base + 4 * dx + c]);
                        }
                    }
                }
                let o = 4 * (row * w + col);
                for c in 0..4 {
                    out[o + c] = ((sum[c] + n / 2) / n) as u8;
                }
            }
        }
        out
    }
}

/// Samples the polygons `bands` (each a fill colour and its rings, corners in figure pixels;
/// convex rings, drawn as fans of triangles) into a [`Raster`] covering their bounding box.
/// Where polygons overlap, the one drawn last wins, as when they are painted in order.
/// `None` if there is nothing to draw, more than 254 colours, or the image would exceed
/// 2²⁶ pixels.
pub fn rasterize(bands: &[(Rgb, Vec<Vec<[f64; 2]>>)]) -> Option<Raster> {
    if bands.len() > 254 {
        return None;
    }
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in bands.iter().flat_map(|(_, rings)| rings.iter().flatten()) {
        if p[0].is_finite() && p[1].is_finite() {
            for i in 0..2 {
                lo[i] = lo[i].min(p[i]);
                hi[i] = hi[i].max(p[i]);
            }
        }
    }
    if !(lo[0] <= hi[0] && lo[1] <= hi[1]) {
        return None;
    }
    let (x0, y0) = (lo[0].floor(), lo[1].floor());
    let width = ((hi[0].ceil() - x0) as u32).max(1);
    let height = ((hi[1].ceil() - y0) as u32).max(1);
    let s = SAMPLES as usize;
    let (iw, ih) = (width as usize * s, height as usize * s);
    if iw.checked_mul(ih)? > MAX_PIXELS {
        return None;
    }
    // Sample grid: SUB × SUB samples per image pixel; sample (i, j) has its centre at
    // (i + ½, j + ½) in sample units from the corner (x0, y0).
    let (nx, ny) = (iw * SUB, ih * SUB);
    let per_px = (s * SUB) as f64;
    let mut owner = vec![u8::MAX; nx * ny];
    for (k, (_, rings)) in bands.iter().enumerate() {
        for ring in rings.iter().filter(|r| r.len() >= 3) {
            let q = |p: [f64; 2]| [(p[0] - x0) * per_px, (p[1] - y0) * per_px];
            let a = q(ring[0]);
            for pair in ring[1..].windows(2) {
                fill_triangle(&mut owner, nx, ny, a, q(pair[0]), q(pair[1]), k as u8);
            }
        }
    }
    // Resolve: each image pixel is the mean of its samples (premultiplied: an empty sample
    // adds nothing).
    let n = (SUB * SUB) as u32;
    let mut rgba = vec![0u8; 4 * iw * ih];
    for row in 0..ih {
        for col in 0..iw {
            let mut sum = [0u32; 4];
            for dy in 0..SUB {
                for dx in 0..SUB {
                    let band = owner[(row * SUB + dy) * nx + col * SUB + dx];
                    if let Some((c, _)) = bands.get(band as usize) {
                        sum[0] += u32::from(c[0]);
                        sum[1] += u32::from(c[1]);
                        sum[2] += u32::from(c[2]);
                        sum[3] += 255;
                    }
                }
            }
            let o = 4 * (row * iw + col);
            for c in 0..4 {
                rgba[o + c] = ((sum[c] + n / 2) / n) as u8;
            }
        }
    }
    Some(Raster {
        x: x0 as i32,
        y: y0 as i32,
        width,
        height,
        samples: SAMPLES,
        rgba,
    })
}

/// Marks with `band` every sample of the `nx × ny` grid whose centre lies in the triangle
/// `a b c` (sample units), edges included, so that triangles sharing an edge leave no gap.
fn fill_triangle(
    owner: &mut [u8],
    nx: usize,
    ny: usize,
    a: [f64; 2],
    b: [f64; 2],
    c: [f64; 2],
    band: u8,
) {
    let cross = |o: [f64; 2], p: [f64; 2], q: [f64; 2]| {
        (p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0])
    };
    let area = cross(a, b, c);
    if !area.is_finite() || area == 0.0 {
        return;
    }
    let (b, c) = if area > 0.0 { (b, c) } else { (c, b) };
    let lo_x = a[0].min(b[0]).min(c[0]);
    let hi_x = a[0].max(b[0]).max(c[0]);
    let lo_y = a[1].min(b[1]).min(c[1]);
    let hi_y = a[1].max(b[1]).max(c[1]);
    // Sample centres i + ½ within [lo, hi].
    let first = |lo: f64| (lo - 0.5).ceil().max(0.0) as usize;
    let last = |hi: f64, n: usize| ((hi - 0.5).floor()).min(n as f64 - 1.0);
    let (i0, j0) = (first(lo_x), first(lo_y));
    let (i1, j1) = (last(hi_x, nx), last(hi_y, ny));
    if i1 < 0.0 || j1 < 0.0 {
        return;
    }
    for j in j0..=j1 as usize {
        let y = j as f64 + 0.5;
        for i in i0..=i1 as usize {
            let p = [i as f64 + 0.5, y];
            if cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0 {
                owner[j * nx + i] = band;
            }
        }
    }
}

/// `bytes` in base64 (RFC 4648, with padding), for an image embedded in an SVG.
pub fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let word = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ALPHABET[((word >> (18 - 6 * k)) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn base64_of_the_rfc_4648_test_vectors() {
        for (plain, coded) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(plain.as_bytes()), coded, "{plain:?}");
        }
    }

    /// A square of `n × n` cells (two triangles each) of side `side` px at (10.25, 20.5),
    /// each triangle in its own colour band of two alternating colours.
    fn checkerboard(n: usize, side: f64) -> Vec<(Rgb, Vec<Vec<[f64; 2]>>)> {
        let h = side / n as f64;
        let mut bands = vec![([200, 0, 0], Vec::new()), ([0, 0, 200], Vec::new())];
        for i in 0..n {
            for j in 0..n {
                let p =
                    |a: usize, b: usize| [10.25 + (i + a) as f64 * h, 20.5 + (j + b) as f64 * h];
                bands[0].1.push(vec![p(0, 0), p(1, 0), p(1, 1)]);
                bands[1].1.push(vec![p(0, 0), p(1, 1), p(0, 1)]);
            }
        }
        bands
    }

    #[test]
    fn a_tiled_square_is_covered_without_seams_and_its_colour_is_the_mean_of_its_cells() {
        // 173 × 173 cells in 50 × 50 px: about 12 cells per pixel. Inside the square every
        // pixel is opaque and each of its samples is red or blue (no seam lets the
        // background through: red + blue = 200 up to rounding); the two colours cover half
        // the area each, so their mean over the square is 100.
        let r = rasterize(&checkerboard(173, 50.0)).unwrap();
        assert_eq!((r.x, r.y, r.width, r.height), (10, 20, 51, 51));
        let px = r.figure_pixels();
        let (mut red, mut count) = (0.0, 0.0);
        for row in 1..50 {
            for col in 1..50 {
                let o = 4 * (row * 51 + col);
                assert_eq!(px[o + 3], 255, "pixel ({col}, {row})");
                let sum = u32::from(px[o]) + u32::from(px[o + 2]);
                assert!(
                    sum.abs_diff(200) <= 1,
                    "red + blue = {sum} at ({col}, {row})"
                );
                red += f64::from(px[o]);
                count += 1.0;
            }
        }
        assert!(
            (red / count - 100.0).abs() < 3.0,
            "mean red {}",
            red / count
        );
        // The first column (x in [10, 11)) is covered from x = 10.25 on: 3 of its 4
        // sample columns (3/4 of 255, rounded twice).
        let o = 4 * (10 * 51);
        assert!(px[o + 3].abs_diff(191) <= 1, "alpha {}", px[o + 3]);
        // The last column (x in [60, 61)) is covered up to x = 60.25: 1 of 4.
        let o = 4 * (10 * 51 + 50);
        assert!(px[o + 3].abs_diff(64) <= 1, "alpha {}", px[o + 3]);
    }

    #[test]
    fn coarse_cells_keep_their_own_colour_and_the_last_drawn_wins_an_overlap() {
        let r = rasterize(&checkerboard(2, 40.0)).unwrap();
        let px = r.figure_pixels();
        // Pixel (35, 25) in figure px: cell (1, 0), below its diagonal: band 0 (red).
        let at = |x: i32, y: i32| {
            let o = 4 * (((y - r.y) as usize) * r.width as usize + (x - r.x) as usize);
            [px[o], px[o + 1], px[o + 2], px[o + 3]]
        };
        assert_eq!(at(40, 22), [200, 0, 0, 255]);
        assert_eq!(at(32, 38), [0, 0, 200, 255]);
        // Two colours over the same triangle: the later band is drawn on top.
        let tri = vec![[0.0, 0.0], [30.0, 0.0], [0.0, 30.0]];
        let r = rasterize(&[([1, 2, 3], vec![tri.clone()]), ([9, 8, 7], vec![tri])]).unwrap();
        assert_eq!(&r.figure_pixels()[..4], &[9, 8, 7, 255]);
    }

    #[test]
    fn nothing_to_draw_gives_none_and_an_inverted_triangle_is_drawn_too() {
        assert!(rasterize(&[]).is_none());
        assert!(rasterize(&[([0, 0, 0], vec![vec![[f64::NAN, 0.0]; 3]])]).is_none());
        let cw = vec![[0.0, 0.0], [0.0, 10.0], [10.0, 0.0]];
        let r = rasterize(&[([50, 60, 70], vec![cw])]).unwrap();
        assert_eq!(&r.figure_pixels()[..4], &[50, 60, 70, 255]);
    }

    /// A smooth colour field on 150 × 150 cells (two triangles each) of 2/3 px over the
    /// square [20, 120]² px, banded by the x of each cell's centre like a stress field.
    fn smooth_field() -> Vec<(Rgb, Vec<Vec<[f64; 2]>>)> {
        use super::super::field::{level_color, LEVELS};
        let (n, side) = (150, 100.0);
        let h = side / n as f64;
        let mut bands: Vec<(Rgb, Vec<Vec<[f64; 2]>>)> =
            (0..LEVELS).map(|k| (level_color(k), Vec::new())).collect();
        for i in 0..n {
            for j in 0..n {
                let p = |a: usize, b: usize| [20.0 + (i + a) as f64 * h, 20.0 + (j + b) as f64 * h];
                let band = ((i as f64 + 0.5) / n as f64 * LEVELS as f64) as usize;
                bands[band].1.push(vec![p(0, 0), p(1, 0), p(1, 1)]);
                bands[band].1.push(vec![p(0, 0), p(1, 1), p(0, 1)]);
            }
        }
        bands
    }

    #[test]
    fn each_pixel_of_a_fine_field_mixes_only_the_colours_of_the_cells_it_covers() {
        use super::super::field::{level_color, LEVELS};
        use super::super::{Figure, Prim};
        let bands = smooth_field();
        let mut image = Figure::new(140, 140);
        image.prims.push(Prim::Raster(rasterize(&bands).unwrap()));
        let png = tiny_skia::Pixmap::decode_png(&image.to_png().unwrap()).unwrap();
        // Inside the square, pixel column [x, x + 1) covers the cell columns i with
        // [20 + i h, 20 + (i + 1) h) meeting it; each channel must lie between the least
        // and the largest of their band colours (up to rounding).
        let (n, h) = (150usize, 100.0 / 150.0);
        for x in 20..120u32 {
            let colours: Vec<Rgb> = (0..n)
                .filter(|&i| {
                    let (a, b) = (20.0 + i as f64 * h, 20.0 + (i + 1) as f64 * h);
                    a < f64::from(x + 1) && b > f64::from(x)
                })
                .map(|i| level_color(((i as f64 + 0.5) / n as f64 * LEVELS as f64) as usize))
                .collect();
            for y in 20..120u32 {
                let p = png.pixel(x, y).unwrap();
                assert_eq!(p.alpha(), 255, "({x}, {y})");
                for (c, v) in [p.red(), p.green(), p.blue()].into_iter().enumerate() {
                    let lo = colours.iter().map(|k| k[c]).min().unwrap();
                    let hi = colours.iter().map(|k| k[c]).max().unwrap();
                    assert!(
                        v.saturating_add(1) >= lo && v <= hi.saturating_add(1),
                        "({x}, {y}) channel {c}: {v} outside [{lo}, {hi}]"
                    );
                }
            }
        }
        // Outside the square, nothing is drawn.
        for (x, y) in [(10, 10), (125, 60), (60, 125)] {
            assert_eq!(png.pixel(x, y).unwrap().red(), 255, "({x}, {y})");
            assert_eq!(png.pixel(x, y).unwrap().blue(), 255, "({x}, {y})");
        }
        // The SVG embeds the image as a PNG and is much smaller than the polygons.
        let mut vector = Figure::new(140, 140);
        for (fill, rings) in &bands {
            vector.prims.push(Prim::Polygons {
                rings: rings.clone(),
                fill: *fill,
            });
        }
        let (sv, si) = (vector.to_svg().len(), image.to_svg().len());
        assert!(10 * si < sv, "SVG bytes: polygons {sv}, image {si}");
        assert!(image
            .to_svg()
            .contains("xlink:href=\"data:image/png;base64,iVBOR"));
    }
}
