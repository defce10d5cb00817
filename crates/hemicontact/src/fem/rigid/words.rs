//! Rigid motions in words: the free motions of a body described for the user (a
//! translation along an axis, a rotation about an axis through a point) with what would
//! block each.

use super::Body;

const AXES: [&str; 3] = ["x", "y", "z"];

pub(super) fn point(x: &[f64]) -> String {
    point_at_scale(x, 0.0)
}

/// `(x, y[, z])` with 6 significant digits, coordinates below `10⁻⁹ scale` shown as 0 (the
/// round-off of a point computed on a body of that size).
fn point_at_scale(x: &[f64], scale: f64) -> String {
    let parts: Vec<String> = x
        .iter()
        .map(|&v| {
            format!(
                "{}",
                if v.abs() <= 1e-9 * scale {
                    0.0
                } else {
                    round(v)
                }
            )
        })
        .collect();
    format!("({})", parts.join(", "))
}

/// Rounds to 6 significant digits for display (and −0 to 0).
fn round(v: f64) -> f64 {
    if v == 0.0 || !v.is_finite() {
        return 0.0;
    }
    let e = 10f64.powi(5 - v.abs().log10().floor() as i32);
    (v * e).round() / e + 0.0
}

/// A direction in words: "x" for a coordinate axis, else "(a, b[, c])" normalized.
fn direction(d: usize, a: &[f64]) -> String {
    let n = a[..d].iter().map(|x| x * x).sum::<f64>().sqrt();
    for (i, name) in AXES.iter().enumerate().take(d) {
        if (a[i].abs() - n).abs() <= 1e-9 * n {
            return (*name).to_string();
        }
    }
    let unit: Vec<f64> = a[..d].iter().map(|x| x / n).collect();
    point(&unit)
}

/// Splits coefficients `c` of `body` into translation `a` (m/unit), physical angular
/// velocity `ω` (rad/unit) and, for a rotation, a point on its axis `p` (m) and the
/// translation along the axis.
fn kinematics(d: usize, body: &Body, c: &[f64; 6]) -> ([f64; 3], [f64; 3], [f64; 3], f64) {
    let mut a = [0.0; 3];
    a[..d].copy_from_slice(&c[..d]);
    let mut w = [0.0; 3];
    if d == 2 {
        w[2] = c[2] / body.size;
    } else {
        for k in 0..3 {
            w[k] = c[3 + k] / body.size;
        }
    }
    let w2: f64 = w.iter().map(|x| x * x).sum();
    let mut p = body.centroid;
    let mut along = 0.0;
    if w2 > 0.0 {
        // a = a_par + a_perp; the axis passes through p = x̄ + ω × a_perp / |ω|².
        let wn = w2.sqrt();
        along = (0..3).map(|i| a[i] * w[i]).sum::<f64>() / wn;
        let mut perp = a;
        for i in 0..3 {
            perp[i] -= along * w[i] / wn;
        }
        let q = crate::fem::simplex::cross(&w, &perp);
        for i in 0..3 {
            p[i] += q[i] / w2;
        }
    }
    (a, w, p, along)
}

/// The rigid motion with coefficients `c` of `body` in a mechanician's words: "translation
/// along x", "translation along (0.6, 0.8)", "rotation about z through (1, 2)", "rotation
/// about the axis (0, 0.6, 0.8) through (…)" and, for a helical motion, "… combined with a
/// translation along that axis".
pub fn describe(d: usize, body: &Body, c: &[f64; 6]) -> String {
    let (a, w, p, along) = kinematics(d, body, c);
    let wn = w.iter().map(|x| x * x).sum::<f64>().sqrt();
    if wn == 0.0 {
        return format!("translation along {}", direction(d, &a));
    }
    let axis = if d == 2 {
        "z".to_string()
    } else {
        let dir = direction(3, &w);
        if dir.len() == 1 {
            dir
        } else {
            format!("the axis {dir}")
        }
    };
    let reach = body.size + body.centroid.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let mut s = format!(
        "rotation about {axis} through {}",
        point_at_scale(&p[..d], reach)
    );
    let scale = a
        .iter()
        .map(|x| x * x)
        .sum::<f64>()
        .sqrt()
        .max(wn * body.size);
    if along.abs() > 1e-9 * scale {
        s.push_str(" combined with a translation along that axis");
    }
    s
}

/// What would block the motion `c` of `body`, in words.
pub(super) fn remedy(d: usize, body: &Body, c: &[f64; 6]) -> String {
    let (a, w, _, _) = kinematics(d, body, c);
    let wn = w.iter().map(|x| x * x).sum::<f64>().sqrt();
    if wn == 0.0 {
        let dir = direction(d, &a);
        if dir.len() == 1 {
            format!(
                "prescribe u_{dir} on some part of this body ([[dirichlet]]), or add a \
                 [[contact]] part whose normal has a nonzero {dir} component"
            )
        } else {
            format!(
                "prescribe the displacement component along {dir} on some part of this body \
                 ([[dirichlet]]), or add a [[contact]] part whose normal has a component along \
                 it"
            )
        }
    } else {
        "prescribe displacements ([[dirichlet]]) on a part away from the rotation axis, or \
         on two parts apart, or add a [[contact]] part whose normal does not point through \
         the axis"
            .to_string()
    }
}
