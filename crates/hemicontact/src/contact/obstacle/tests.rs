//! Unit tests of the obstacles' closest points.
use super::meridian_root;

/// Newton's method for the closest point on a paraboloid converges in a handful of
/// steps over twenty decades of distances and heights, to a root of the cubic.
#[test]
fn meridian_newton_converges_in_few_steps() {
    // SplitMix64, uniform in [0, 1).
    let mut state = 11_u64;
    let mut unit = move || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1_u64 << 53) as f64
    };
    let mut log_uniform = move || 10f64.powf(-12.0 + 20.0 * unit());
    let mut most = 0;
    for k in 0..200_000 {
        let r = log_uniform();
        let z = if k % 2 == 0 { 1.0 } else { -1.0 } * log_uniform();
        let (s, steps) = meridian_root(r, z).unwrap();
        most = most.max(steps);
        assert!(s > 0.0);
        // φ(ŝ) = 0 to the rounding of its terms.
        let b = 1.0 - z;
        let phi = (0.5 * s * s + b) * s - r;
        let terms = 0.5 * s * s * s + (b * s).abs() + r;
        assert!(
            phi.abs() <= 8.0 * f64::EPSILON * terms,
            "r̂ = {r}, ẑ = {z}: φ = {phi}"
        );
    }
    assert!(most <= 7, "{most} Newton steps");
}
