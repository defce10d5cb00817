//! Layout helpers shared by the figures: round numbers (1, 2, 5 × 10^k), axis ticks, number
//! labels with SI prefixes, titles fitted to a width, and label boxes that must not overlap.

use super::font::text_width;

/// An axis-aligned box in pixels: `[left, top, right, bottom]`.
pub type Rect = [f64; 4];

/// Whether two boxes overlap (touching edges do not count).
pub fn overlaps(a: Rect, b: Rect) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

/// Whether box `inner` lies inside box `outer`.
pub fn inside(inner: Rect, outer: Rect) -> bool {
    inner[0] >= outer[0] && inner[1] >= outer[1] && inner[2] <= outer[2] && inner[3] <= outer[3]
}

/// The box of a text of font size `size` whose baseline starts at `(x, y)` (left-aligned):
/// from 0.8 em above the baseline to 0.25 em below it (accents and descenders included).
pub fn text_box(text: &str, x: f64, y: f64, size: f64) -> Rect {
    [
        x,
        y - 0.8 * size,
        x + text_width(text, size),
        y + 0.25 * size,
    ]
}

/// The largest number `m · 10^k` with `m ∈ {1, 2, 5}` not above `x > 0` (`x` itself if it
/// is not finite and positive).
pub fn round_down_125(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return x;
    }
    let p = 10f64.powf(x.log10().floor());
    let m = x / p;
    // Tolerate round-off in m just below 2, 5 or 10.
    let m = if m >= 5.0 * (1.0 - 1e-12) {
        5.0
    } else if m >= 2.0 * (1.0 - 1e-12) {
        2.0
    } else {
        1.0
    };
    m * p
}

/// Tick positions covering `[lo, hi]` at a round step (1, 2 or 5 × 10^k) giving about
/// `target` ticks; returns the ticks inside the interval (with a round-off tolerance).
pub fn ticks(lo: f64, hi: f64, target: usize) -> Vec<f64> {
    if !(lo.is_finite() && hi.is_finite()) || hi <= lo {
        return vec![lo];
    }
    let raw = (hi - lo) / target.max(1) as f64;
    let mut step = round_down_125(raw);
    if (hi - lo) / step > 1.5 * target as f64 {
        step = round_down_125(2.5 * step);
    }
    let eps = 1e-9 * (hi - lo);
    let first = (lo / step - 1e-9).ceil();
    let mut out = Vec::new();
    let mut k = first;
    while k * step <= hi + eps && out.len() < 100 {
        let v = k * step;
        out.push(if v.abs() < eps { 0.0 } else { v });
        k += 1.0;
    }
    out
}

/// Superscript digits and minus for exponents (`-12` ↦ `⁻¹²`).
pub fn superscript(n: i32) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut s = String::new();
    if n < 0 {
        s.push('⁻');
    }
    for c in n.unsigned_abs().to_string().chars() {
        s.push(DIGITS[c.to_digit(10).unwrap_or(0) as usize]);
    }
    s
}

/// A power of ten as a label: `10⁻³`.
pub fn power_of_ten(k: i32) -> String {
    format!("10{}", superscript(k))
}

/// A number with up to three significant digits, trailing zeros dropped (`0.25`, `1200`,
/// `3.5×10⁻⁷` for magnitudes outside 10⁻³ … 10⁵); exact zero is `0`.
pub fn number(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return if v.is_finite() {
            "0".into()
        } else {
            format!("{v}")
        };
    }
    let a = v.abs();
    if (1e-3..1e5).contains(&a) {
        let digits = (2 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{v:.digits$}");
        let s = if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        };
        return s.replace('-', "−");
    }
    let k = a.log10().floor() as i32;
    let m = v / 10f64.powi(k);
    format!("{}×{}", number(m), power_of_ten(k))
}

/// A quantity with an SI prefix chosen for `scale` (the largest magnitude shown): returns
/// `(factor, prefixed unit)`, e.g. `(1e6, "MPa")` for a stress of 3·10⁶ Pa; values are
/// then printed as `v / factor`.
pub fn si_prefix(scale: f64, unit: &str) -> (f64, String) {
    const PREFIXES: [(f64, &str); 9] = [
        (1e12, "T"),
        (1e9, "G"),
        (1e6, "M"),
        (1e3, "k"),
        (1.0, ""),
        (1e-3, "m"),
        (1e-6, "μ"),
        (1e-9, "n"),
        (1e-12, "p"),
    ];
    let a = scale.abs();
    if !(a.is_finite() && a > 0.0) {
        return (1.0, unit.to_string());
    }
    for (f, p) in PREFIXES {
        if a >= f * (1.0 - 1e-12) {
            return (f, format!("{p}{unit}"));
        }
    }
    (1e-12, format!("p{unit}"))
}

/// A value with its unit and an SI prefix: `12.5 MPa`.
pub fn quantity(v: f64, unit: &str) -> String {
    let (f, u) = si_prefix(v, unit);
    format!("{} {u}", number(v / f))
}

/// Fits `text` into `width` px: the font size shrinks from `size` down to `min_size`, and
/// if the text is still too wide it is wrapped at spaces into lines. Returns the lines and
/// the font size; every line fits unless a single word is wider than `width`, in which case
/// that word is cut at the width and ends in `…`.
pub fn fit_text(text: &str, width: f64, size: f64, min_size: f64) -> (Vec<String>, f64) {
    let w = text_width(text, size);
    if w <= width {
        return (vec![text.to_string()], size);
    }
    let shrunk = (size * width / w).max(min_size);
    if text_width(text, shrunk) <= width {
        return (vec![text.to_string()], shrunk);
    }
    let size = min_size;
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in text.split(' ') {
        let candidate = if line.is_empty() {
            word.to_string()
        } else {
            format!("{line} {word}")
        };
        if text_width(&candidate, size) <= width || line.is_empty() {
            line = candidate;
        } else {
            lines.push(std::mem::take(&mut line));
            line = word.to_string();
        }
    }
    lines.push(line);
    for l in &mut lines {
        if text_width(l, size) > width {
            while !l.is_empty() && text_width(&format!("{l}…"), size) > width {
                l.pop();
            }
            l.push('…');
        }
    }
    (lines, size)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_down_125_gives_one_two_or_five_times_a_power_of_ten() {
        for (x, want) in [
            (1.0, 1.0),
            (1.9, 1.0),
            (2.0, 2.0),
            (4.99, 2.0),
            (5.0, 5.0),
            (9.9, 5.0),
            (37.0, 20.0),
            (0.07, 0.05),
            (123456.0, 100000.0),
        ] {
            let got = round_down_125(x);
            assert!((got - want).abs() <= 1e-12 * want, "{x}: {got} ≠ {want}");
        }
    }

    #[test]
    fn ticks_are_round_and_cover_the_range() {
        let t = ticks(0.0, 1.0, 5);
        assert_eq!(t.len(), 6, "{t:?}");
        for (k, v) in t.iter().enumerate() {
            assert!((v - 0.2 * k as f64).abs() < 1e-12, "{t:?}");
        }
        let t = ticks(-3.0e6, 7.0e6, 5);
        assert!(t.contains(&0.0) && t.len() >= 4 && t.len() <= 8, "{t:?}");
        for w in t.windows(2) {
            assert!((w[1] - w[0] - 2.0e6).abs() < 1.0, "{t:?}");
        }
    }

    #[test]
    fn numbers_print_compactly_with_unicode_signs() {
        assert_eq!(number(0.0), "0");
        assert_eq!(number(0.25), "0.25");
        assert_eq!(number(1200.0), "1200");
        assert_eq!(number(-2.5), "−2.5");
        assert_eq!(number(3.5e-7), "3.5×10⁻⁷");
        assert_eq!(power_of_ten(-12), "10⁻¹²");
        assert_eq!(quantity(2.5e6, "Pa"), "2.5 MPa");
        assert_eq!(quantity(40.0, "N/m"), "40 N/m");
    }

    #[test]
    fn fitted_titles_fit_their_width() {
        let long = "Paper example: locking material with nonmonotone slip-dependent friction, \
                    C_kappa = 10000, n = 128, compared with the case without locking";
        for width in [200.0, 400.0, 800.0] {
            let (lines, size) = fit_text(long, width, 16.0, 12.0);
            assert!((12.0..=16.0).contains(&size));
            for l in &lines {
                assert!(text_width(l, size) <= width, "{l:?} at {width}");
            }
            // Nothing is lost when every word fits: the lines rejoin to the text.
            assert_eq!(lines.join(" "), long);
        }
        let (lines, size) = fit_text("short", 400.0, 16.0, 12.0);
        assert_eq!((lines, size), (vec!["short".to_string()], 16.0));
    }

    #[test]
    fn boxes_overlap_only_when_they_share_area() {
        assert!(overlaps([0.0, 0.0, 2.0, 2.0], [1.0, 1.0, 3.0, 3.0]));
        assert!(!overlaps([0.0, 0.0, 2.0, 2.0], [2.0, 0.0, 3.0, 2.0]));
        assert!(inside([1.0, 1.0, 2.0, 2.0], [0.0, 0.0, 2.0, 2.0]));
        assert!(!inside([1.0, 1.0, 2.5, 2.0], [0.0, 0.0, 2.0, 2.0]));
    }
}
