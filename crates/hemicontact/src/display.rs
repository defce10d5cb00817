//! Numbers in words: how the laws' `Display` implementations (and the command-line
//! program) write a parameter, rounded to six significant digits in its shortest form.

/// `x` rounded to six significant digits, in the shortest form that reads back as the
/// rounded value: plain between 10⁻⁴ and 10⁶ (`30.000000000000004` → `30`, `0.4` → `0.4`,
/// `10000` → `10000`), in scientific notation outside (`1e-8`, `2.5e7`). Non-finite values
/// and zero are written as they are.
pub fn significant(x: f64) -> String {
    if !x.is_finite() || x == 0.0 {
        return format!("{x}");
    }
    // Six significant digits: one before the point and five after it in scientific form.
    let rounded: f64 = format!("{x:.5e}").parse().unwrap_or(x);
    let magnitude = rounded.abs();
    if (1e-4..1e6).contains(&magnitude) {
        format!("{rounded}")
    } else {
        format!("{rounded:e}")
    }
}

#[cfg(test)]
mod tests {
    use super::significant;

    #[test]
    fn six_significant_digits_in_the_shortest_form() {
        assert_eq!(significant(30.000000000000004), "30");
        assert_eq!(significant(0.1 + 0.2), "0.3");
        assert_eq!(significant(0.4), "0.4");
        assert_eq!(significant(10000.0), "10000");
        assert_eq!(significant(1e-8), "1e-8");
        assert_eq!(significant(2.5e7), "2.5e7");
        assert_eq!(significant(1.23456789), "1.23457");
        assert_eq!(significant(-0.000123456789), "-0.000123457");
        assert_eq!(significant(0.0), "0");
        assert_eq!(significant(f64::INFINITY), "inf");
    }
}
