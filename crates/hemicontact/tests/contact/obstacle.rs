//! Rigid obstacles (`contact::obstacle`): gaps, normals and closest points against closed
//! forms and geometric facts derived here independently of the library:
//!
//! - plane, circle, sphere, cylinder: the distance formulas of elementary geometry at seeded
//!   random points, the closest point on the surface, `x = P + g ν`;
//! - every shape: ν is a unit vector equal to the gradient of the signed distance (central
//!   differences);
//! - paraboloid: the closest point is on the surface, `x − P` is along the surface normal
//!   (the gradient of the implicit function `(y − q)·â − r²/(2R)`), no sampled surface point
//!   is closer, the sign of the gap is the side of the surface, and near the apex
//!   `g = h + r²/(2R)` up to the third-order terms of the osculating circle;
//! - a displaced obstacle: the gap is that of `x − t`, and `g − t·ν` to first order;
//! - invalid shapes and points are refused naming the field; points with no unique closest
//!   point are refused; the serde form accepts the scenario syntax and refuses unknown keys.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use common::Rng;
use hemicontact::contact::obstacle::{Obstacle, ObstacleSpec, Projection};
use hemicontact::Error;

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// A random point in the cube `[−l, l]^dim` (unused coordinates 0).
fn point(rng: &mut Rng, dim: usize, l: f64) -> [f64; 3] {
    let mut p = [0.0; 3];
    for c in p.iter_mut().take(dim) {
        *c = rng.uniform(-l, l);
    }
    p
}

fn vec_of(p: [f64; 3], dim: usize) -> Vec<f64> {
    p[..dim].to_vec()
}

fn project(o: &Obstacle, x: [f64; 3], dim: usize) -> Projection {
    o.project(x, dim)
        .unwrap_or_else(|e| panic!("{o:?} at {x:?}: {e}"))
}

/// Checks `x = P + g ν` and `‖ν‖ = 1`, to `tol` (m).
fn check_decomposition(p: &Projection, x: [f64; 3], tol: f64) {
    assert!((norm(p.normal) - 1.0).abs() < 1e-14, "{p:?}");
    for k in 0..3 {
        let back = p.point[k] + p.gap * p.normal[k];
        assert!((back - x[k]).abs() <= tol, "x = {x:?}, {p:?}");
    }
}

/// The field and value of an [`Error::Invalid`].
fn invalid(e: Error) -> (String, String) {
    match e {
        Error::Invalid { field, value, .. } => (field, value),
        e => panic!("expected an Error::Invalid, got {e}"),
    }
}

#[test]
fn plane_gap_is_the_distance_along_the_normalized_normal() {
    let mut rng = Rng::new(1);
    for dim in [2, 3] {
        for _ in 0..200 {
            let p = point(&mut rng, dim, 5.0);
            let n = point(&mut rng, dim, 3.0);
            let x = point(&mut rng, dim, 10.0);
            let o = Obstacle::Plane {
                point: vec_of(p, dim),
                normal: vec_of(n, dim),
            };
            let pr = project(&o, x, dim);
            let expected = dot(sub(x, p), n) / norm(n);
            assert!((pr.gap - expected).abs() < 1e-12, "{pr:?} vs {expected}");
            for k in 0..3 {
                assert!((pr.normal[k] - n[k] / norm(n)).abs() < 1e-15);
            }
            // The closest point is on the plane.
            assert!(dot(sub(pr.point, p), n).abs() < 1e-12 * norm(n));
            check_decomposition(&pr, x, 1e-12);
        }
    }
}

#[test]
fn circle_and_sphere_gap_is_distance_to_centre_minus_radius() {
    let mut rng = Rng::new(2);
    for dim in [2, 3] {
        for _ in 0..200 {
            let c = point(&mut rng, dim, 5.0);
            let radius = rng.log_uniform(0.01, 10.0);
            let x = point(&mut rng, dim, 10.0);
            let o = if dim == 2 {
                Obstacle::Circle {
                    center: vec_of(c, dim),
                    radius,
                }
            } else {
                Obstacle::Sphere {
                    center: vec_of(c, dim),
                    radius,
                }
            };
            let pr = project(&o, x, dim);
            let d = norm(sub(x, c));
            assert!((pr.gap - (d - radius)).abs() < 1e-12, "{pr:?}");
            assert_eq!(pr.gap > 0.0, d > radius);
            assert!((norm(sub(pr.point, c)) - radius).abs() < 1e-12);
            check_decomposition(&pr, x, 1e-12);
        }
    }
}

#[test]
fn cylinder_gap_is_distance_to_axis_minus_radius() {
    let mut rng = Rng::new(3);
    for _ in 0..200 {
        let p = point(&mut rng, 3, 5.0);
        let a = point(&mut rng, 3, 2.0);
        let radius = rng.log_uniform(0.01, 10.0);
        let x = point(&mut rng, 3, 10.0);
        let o = Obstacle::Cylinder {
            point: vec_of(p, 3),
            axis: vec_of(a, 3),
            radius,
        };
        let pr = project(&o, x, 3);
        // Distance to the axis: ‖w × a‖ / ‖a‖ (cross product, independent of the
        // library's orthogonal decomposition).
        let w = sub(x, p);
        let cross = [
            w[1] * a[2] - w[2] * a[1],
            w[2] * a[0] - w[0] * a[2],
            w[0] * a[1] - w[1] * a[0],
        ];
        let d = norm(cross) / norm(a);
        assert!((pr.gap - (d - radius)).abs() < 1e-11, "{pr:?} vs {d}");
        // The normal is orthogonal to the axis, the closest point at distance R from it.
        assert!(dot(pr.normal, a).abs() < 1e-14 * norm(a));
        let wp = sub(pr.point, p);
        let cp = [
            wp[1] * a[2] - wp[2] * a[1],
            wp[2] * a[0] - wp[0] * a[2],
            wp[0] * a[1] - wp[1] * a[0],
        ];
        assert!((norm(cp) / norm(a) - radius).abs() < 1e-11);
        // Same position along the axis as x.
        assert!((dot(sub(pr.point, x), a) / norm(a)).abs() < 1e-11);
        check_decomposition(&pr, x, 1e-11);
    }
}

/// A random paraboloid: apex in a box, random axis, radius log-uniform.
fn random_paraboloid(rng: &mut Rng, dim: usize) -> ([f64; 3], [f64; 3], f64, Obstacle) {
    let q = point(rng, dim, 2.0);
    let mut a = point(rng, dim, 1.0);
    while norm(a) < 0.1 {
        a = point(rng, dim, 1.0);
    }
    let radius = rng.log_uniform(0.1, 10.0);
    let o = Obstacle::Paraboloid {
        apex: vec_of(q, dim),
        axis: vec_of(a, dim),
        radius,
    };
    let ahat = a.map(|c| c / norm(a));
    (q, ahat, radius, o)
}

/// Height along the axis and distance from the axis of `y` about the apex `q`.
fn local(y: [f64; 3], q: [f64; 3], ahat: [f64; 3]) -> (f64, f64) {
    let w = sub(y, q);
    let z = dot(w, ahat);
    let r = (dot(w, w) - z * z).max(0.0).sqrt();
    (z, r)
}

#[test]
fn normals_are_the_gradient_of_the_signed_distance() {
    let mut rng = Rng::new(4);
    let h = 1e-6;
    for dim in [2, 3] {
        let mut shapes: Vec<Obstacle> = vec![Obstacle::Plane {
            point: vec_of(point(&mut rng, dim, 1.0), dim),
            normal: vec_of(point(&mut rng, dim, 1.0), dim),
        }];
        let c = vec_of(point(&mut rng, dim, 1.0), dim);
        if dim == 2 {
            shapes.push(Obstacle::Circle {
                center: c,
                radius: 1.5,
            });
        } else {
            shapes.push(Obstacle::Sphere {
                center: c,
                radius: 1.5,
            });
            shapes.push(Obstacle::Cylinder {
                point: vec_of(point(&mut rng, 3, 1.0), 3),
                axis: vec_of(point(&mut rng, 3, 1.0), 3),
                radius: 1.5,
            });
        }
        shapes.push(random_paraboloid(&mut rng, dim).3);
        for o in &shapes {
            let mut tested = 0;
            while tested < 50 {
                let x = point(&mut rng, dim, 4.0);
                let pr = project(o, x, dim);
                // Keep away from the centre, the axis and the medial axis of the paraboloid,
                // where the distance is not differentiable: require the projection of the
                // nearby points to move little.
                let mut fd = [0.0; 3];
                let mut smooth = true;
                for k in 0..dim {
                    let mut xp = x;
                    let mut xm = x;
                    xp[k] += h;
                    xm[k] -= h;
                    let (pp, pm) = (project(o, xp, dim), project(o, xm, dim));
                    smooth &= norm(sub(pp.normal, pm.normal)) < 1e-3;
                    fd[k] = (pp.gap - pm.gap) / (2.0 * h);
                }
                if !smooth {
                    continue;
                }
                tested += 1;
                for k in 0..dim {
                    assert!(
                        (fd[k] - pr.normal[k]).abs() < 1e-6,
                        "{o:?} at {x:?}: ∇g = {fd:?}, ν = {:?}",
                        pr.normal
                    );
                }
            }
        }
    }
}

#[test]
fn paraboloid_closest_point_is_on_the_surface_and_orthogonal() {
    let mut rng = Rng::new(5);
    for dim in [2, 3] {
        for _ in 0..40 {
            let (q, ahat, radius, o) = random_paraboloid(&mut rng, dim);
            for _ in 0..25 {
                let x = point(&mut rng, dim, 20.0);
                let pr = project(&o, x, dim);
                let (zp, rp) = local(pr.point, q, ahat);
                let scale = norm(sub(x, q)) + radius;
                // On the surface z = r²/(2R).
                assert!(
                    (zp - rp * rp / (2.0 * radius)).abs() < 1e-12 * scale.max(zp.abs()),
                    "{pr:?}"
                );
                // The outward normal at P is −∇F/‖∇F‖ for F(y) = (y − q)·â − r²/(2R):
                // ∇F = â − ρ/R with ρ the part of y − q orthogonal to the axis.
                let w = sub(pr.point, q);
                let zw = dot(w, ahat);
                let grad = [0, 1, 2].map(|k| ahat[k] - (w[k] - zw * ahat[k]) / radius);
                let n = grad.map(|c| -c / norm(grad));
                for k in 0..3 {
                    assert!((pr.normal[k] - n[k]).abs() < 1e-10, "{pr:?} vs {n:?}");
                }
                check_decomposition(&pr, x, 1e-11 * scale);
                // The sign of the gap is the side of the surface.
                let (zx, rx) = local(x, q, ahat);
                let outside = zx < rx * rx / (2.0 * radius);
                if (zx - rx * rx / (2.0 * radius)).abs() > 1e-9 * scale {
                    assert_eq!(pr.gap > 0.0, outside, "x = {x:?}, {pr:?}");
                }
            }
        }
    }
}

/// The surface point of the paraboloid with local coordinates (u, v) (v unused in 2D).
fn surface_point(q: [f64; 3], ahat: [f64; 3], radius: f64, u: f64, v: f64, dim: usize) -> [f64; 3] {
    // An orthonormal basis (e1, e2) of the plane orthogonal to the axis.
    let e1 = if dim == 2 {
        [-ahat[1], ahat[0], 0.0]
    } else {
        let t = if ahat[0].abs() < 0.6 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let p = [0, 1, 2].map(|k| t[k] - dot(t, ahat) * ahat[k]);
        p.map(|c| c / norm(p))
    };
    let e2 = [
        ahat[1] * e1[2] - ahat[2] * e1[1],
        ahat[2] * e1[0] - ahat[0] * e1[2],
        ahat[0] * e1[1] - ahat[1] * e1[0],
    ];
    let v = if dim == 2 { 0.0 } else { v };
    let z = (u * u + v * v) / (2.0 * radius);
    [0, 1, 2].map(|k| q[k] + u * e1[k] + v * e2[k] + z * ahat[k])
}

#[test]
fn paraboloid_projection_is_the_global_minimum_of_the_distance() {
    let mut rng = Rng::new(6);
    for dim in [2, 3] {
        let (q, ahat, radius, o) = random_paraboloid(&mut rng, dim);
        // The closest point P has ‖P − x‖ ≤ ‖x − q‖, so ‖P − q‖ ≤ 2‖x − q‖ < 60: the grid
        // covers every candidate.
        let (n, half) = if dim == 2 {
            (200_000, 60.0)
        } else {
            (600, 60.0)
        };
        for _ in 0..10 {
            let x = point(&mut rng, dim, 15.0);
            assert!(2.0 * norm(sub(x, q)) < half);
            let pr = project(&o, x, dim);
            let distance = pr.gap.abs();
            // Brute force on a grid of the parametric plane; the grid step bounds how much
            // closer than the grid the true minimum can be.
            let step = 2.0 * half / n as f64;
            let mut best = f64::INFINITY;
            let m = if dim == 2 { 1 } else { n + 1 };
            for i in 0..=n {
                for j in 0..m {
                    let u = -half + step * i as f64;
                    let v = -half + step * j as f64;
                    let y = surface_point(q, ahat, radius, u, v, dim);
                    best = best.min(norm(sub(x, y)));
                }
            }
            assert!(distance <= best + 1e-12, "{x:?}: {distance} > grid {best}");
            // The grid's closest point is within one cell of the true one.
            let slope = 1.0 + half / radius;
            assert!(
                best - distance <= step * slope * 2.0,
                "{distance} vs {best}"
            );
        }
    }
}

#[test]
fn paraboloid_gap_near_the_apex_is_the_hertz_gap() {
    // For x at height h below the apex and distance r from the axis, the osculating circle
    // of radius R gives g = h + r²/(2(R + h)) + O(r⁴/R³), i.e.
    // g − (h + r²/(2R)) = −h r²/(2R²) + O(h²r²/R³ + r⁴/R³): bounded by |h| r²/R² + r⁴/R³.
    let mut rng = Rng::new(7);
    for dim in [2, 3] {
        let (q, ahat, radius, o) = random_paraboloid(&mut rng, dim);
        let mut dir = point(&mut rng, dim, 1.0);
        let along = dot(dir, ahat);
        dir = [0, 1, 2].map(|k| dir[k] - along * ahat[k]);
        let e = dir.map(|c| c / norm(dir));
        for &eps in &[1e-1, 1e-2, 1e-3, 1e-4] {
            for &(alpha, beta) in &[(1.0, 1.0), (-0.5, 1.0), (0.3, 2.0), (0.0, 1.0), (1.0, 0.0)] {
                let h = alpha * eps * radius;
                let r = beta * eps * radius;
                let x = [0, 1, 2].map(|k| q[k] - h * ahat[k] + r * e[k]);
                let pr = project(&o, x, dim);
                let hertz = h + r * r / (2.0 * radius);
                // Plus the rounding of the coordinates of x (about ε (‖q‖ + R)).
                let bound = h.abs() * r * r / radius.powi(2)
                    + r.powi(4) / radius.powi(3)
                    + 1e-14 * (norm(q) + radius);
                assert!(
                    (pr.gap - hertz).abs() <= bound,
                    "ε = {eps}, h = {h}, r = {r}: g = {}, Hertz {hertz}, bound {bound}",
                    pr.gap
                );
            }
        }
    }
}

#[test]
fn paraboloid_projection_holds_over_many_scales() {
    let mut rng = Rng::new(8);
    let o = Obstacle::Paraboloid {
        apex: vec![0.0, 0.0, 0.0],
        axis: vec![0.0, 0.0, 1.0],
        radius: 1.0,
    };
    for _ in 0..2000 {
        let r = rng.log_uniform(1e-9, 1e6);
        let z = rng.uniform(-1.0, 1.0) * rng.log_uniform(1e-9, 1e6);
        let x = [r, 0.0, z];
        let pr = project(&o, x, 3);
        let scale = norm(x) + 1.0;
        let (zp, rp) = (pr.point[2], pr.point[0]);
        assert!(
            (zp - rp * rp / 2.0).abs() <= 1e-13 * zp.abs().max(1.0),
            "{x:?}: {pr:?}"
        );
        assert!(rp >= 0.0 && pr.point[1] == 0.0);
        // Orthogonality: x − P along the normal (−r_P, 0, 1)/√(1 + r_P²) of the surface.
        let t = [1.0, 0.0, rp];
        let residual = dot(sub(x, pr.point), t) / norm(t);
        assert!(residual.abs() <= 1e-13 * scale, "{x:?}: {residual}");
        check_decomposition(&pr, x, 1e-12 * scale);
    }
}

#[test]
fn on_axis_points_project_to_the_apex_below_the_centre_of_curvature() {
    let o = Obstacle::Paraboloid {
        apex: vec![1.0, 2.0],
        axis: vec![0.0, 3.0],
        radius: 2.0,
    };
    // Below the apex, outside: the gap is the height.
    let pr = project(&o, [1.0, 1.25, 0.0], 2);
    assert_eq!(pr.gap, 0.75);
    assert_eq!(pr.normal, [0.0, -1.0, 0.0]);
    assert_eq!(pr.point, [1.0, 2.0, 0.0]);
    // Inside, below the centre of curvature (z = R = 2): still the apex.
    let pr = project(&o, [1.0, 3.5, 0.0], 2);
    assert_eq!(pr.gap, -1.5);
    assert_eq!(pr.point, [1.0, 2.0, 0.0]);
    // Beyond it the two branches are equally close.
    let (field, value) = invalid(o.project([1.0, 4.5, 0.0], 2).unwrap_err());
    assert_eq!((field.as_str(), value.as_str()), ("position", "[1, 4.5]"));
}

#[test]
fn displaced_obstacle_projects_the_shifted_point() {
    let mut rng = Rng::new(9);
    for _ in 0..200 {
        let c = point(&mut rng, 2, 5.0);
        let radius = rng.uniform(1.0, 3.0);
        let t = point(&mut rng, 2, 0.1);
        let x = point(&mut rng, 2, 10.0);
        let shape = Obstacle::Circle {
            center: vec_of(c, 2),
            radius,
        };
        let spec = ObstacleSpec {
            shape: shape.clone(),
            displacement: Some(vec_of(t, 2)),
        };
        let moved = Obstacle::Circle {
            center: vec_of([c[0] + t[0], c[1] + t[1], 0.0], 2),
            radius,
        };
        let d = norm(sub(x, c));
        if d < 1.0 {
            continue;
        }
        let pr = spec.project(x, 2).unwrap();
        let exact = project(&moved, x, 2);
        assert!((pr.gap - exact.gap).abs() < 1e-12);
        for k in 0..3 {
            assert!((pr.normal[k] - exact.normal[k]).abs() < 1e-12);
            assert!((pr.point[k] - exact.point[k]).abs() < 1e-12);
        }
        // First order in t: g_t = g − t·ν + e with 0 ≤ e ≤ ‖t‖²/‖x − c‖ (‖t‖ ≤ ‖x − c‖/2).
        let fixed = project(&shape, x, 2);
        let e = pr.gap - (fixed.gap - dot(t, fixed.normal));
        assert!(e >= -1e-12 && e <= dot(t, t) / d + 1e-12, "{e}");
    }
    // Hertz indentation: an indenter 0.01 above a point, pushed down by 0.03: −0.02.
    let spec: ObstacleSpec = toml::from_str(
        "kind = \"paraboloid\"\napex = [5.0, 10.01]\naxis = [0.0, 1.0]\nradius = 10.0\n\
         displacement = [0.0, -0.03]\n",
    )
    .unwrap();
    let pr = spec.project([5.0, 10.0, 0.0], 2).unwrap();
    assert!((pr.gap - (0.01 - 0.03)).abs() < 1e-14, "{pr:?}");
    assert!((pr.point[1] - (10.01 - 0.03)).abs() < 1e-14);
    assert_eq!(pr.normal, [0.0, -1.0, 0.0]);
}

#[test]
fn points_with_no_unique_closest_point_are_refused() {
    let cases: Vec<(Obstacle, usize, [f64; 3], &str)> = vec![
        (
            Obstacle::Circle {
                center: vec![1.0, -2.0],
                radius: 3.0,
            },
            2,
            [1.0, -2.0, 0.0],
            "[1, -2]",
        ),
        (
            Obstacle::Sphere {
                center: vec![0.0, 0.5, 0.0],
                radius: 1.0,
            },
            3,
            [0.0, 0.5, 0.0],
            "[0, 0.5, 0]",
        ),
        (
            Obstacle::Cylinder {
                point: vec![0.0, 0.0, 0.0],
                axis: vec![0.0, 0.0, 2.0],
                radius: 1.0,
            },
            3,
            [0.0, 0.0, 7.5],
            "[0, 0, 7.5]",
        ),
        (
            Obstacle::Paraboloid {
                apex: vec![0.0, 0.0, 0.0],
                axis: vec![0.0, 0.0, 1.0],
                radius: 1.0,
            },
            3,
            [0.0, 0.0, 3.0],
            "[0, 0, 3]",
        ),
    ];
    for (o, dim, x, text) in cases {
        let (field, value) = invalid(o.project(x, dim).unwrap_err());
        assert_eq!(field, "position", "{o:?}");
        assert_eq!(value, text);
        // The same through a displaced obstacle names the point as given.
        let t = vec![0.25; dim];
        let spec = ObstacleSpec {
            shape: o.clone(),
            displacement: Some(t),
        };
        let y = [0, 1, 2].map(|k| if k < dim { x[k] + 0.25 } else { 0.0 });
        let (field, _) = invalid(spec.project(y, dim).unwrap_err());
        assert_eq!(field, "position");
    }
}

#[test]
fn invalid_obstacles_are_refused_naming_the_field() {
    let circle = |center: Vec<f64>, radius: f64| Obstacle::Circle { center, radius };
    let cases: Vec<(Obstacle, usize, &str, &str)> = vec![
        (
            Obstacle::Plane {
                point: vec![0.0, 0.0],
                normal: vec![0.0, 0.0],
            },
            2,
            "normal",
            "[0, 0]",
        ),
        (
            Obstacle::Plane {
                point: vec![0.0, f64::NAN],
                normal: vec![0.0, 1.0],
            },
            2,
            "point",
            "[0, NaN]",
        ),
        (
            Obstacle::Plane {
                point: vec![0.0, 0.0],
                normal: vec![0.0, 1.0],
            },
            3,
            "point",
            "[0, 0]",
        ),
        (circle(vec![0.0, 0.0], 0.0), 2, "radius", "0"),
        (circle(vec![0.0, 0.0], -1.0), 2, "radius", "-1"),
        (circle(vec![0.0, 0.0], f64::NAN), 2, "radius", "NaN"),
        (circle(vec![0.0, 0.0], f64::INFINITY), 2, "radius", "inf"),
        (circle(vec![0.0, 0.0, 0.0], 1.0), 2, "center", "[0, 0, 0]"),
        (circle(vec![0.0, 0.0, 0.0], 1.0), 3, "kind", "circle"),
        (
            Obstacle::Sphere {
                center: vec![0.0, 0.0],
                radius: 1.0,
            },
            2,
            "kind",
            "sphere",
        ),
        (
            Obstacle::Cylinder {
                point: vec![0.0, 0.0],
                axis: vec![0.0, 1.0],
                radius: 1.0,
            },
            2,
            "kind",
            "cylinder",
        ),
        (
            Obstacle::Cylinder {
                point: vec![0.0, 0.0, 0.0],
                axis: vec![0.0, 0.0, 0.0],
                radius: 1.0,
            },
            3,
            "axis",
            "[0, 0, 0]",
        ),
        (
            Obstacle::Paraboloid {
                apex: vec![0.0, 0.0],
                axis: vec![0.0, 0.0],
                radius: 1.0,
            },
            2,
            "axis",
            "[0, 0]",
        ),
        (
            Obstacle::Paraboloid {
                apex: vec![0.0, 0.0],
                axis: vec![0.0, 1.0],
                radius: -2.0,
            },
            2,
            "radius",
            "-2",
        ),
        (
            Obstacle::Paraboloid {
                apex: vec![0.0, 0.0],
                axis: vec![0.0, 1.0],
                radius: 2.0,
            },
            4,
            "dimension",
            "4",
        ),
    ];
    for (o, dim, field, value) in cases {
        let e = o.validate(dim).unwrap_err();
        let message = e.to_string();
        let (f, v) = invalid(e);
        assert_eq!((f.as_str(), v.as_str()), (field, value), "{o:?} in {dim}D");
        assert!(message.contains(field), "{message}");
        // project refuses the same way.
        let (f, _) = invalid(o.project([0.0; 3], dim).unwrap_err());
        assert_eq!(f, field);
    }
    // A tiny but nonzero direction is normalized, not refused.
    let o = Obstacle::Plane {
        point: vec![0.0, 0.0],
        normal: vec![0.0, 1e-300],
    };
    assert_eq!(project(&o, [3.0, 2.0, 0.0], 2).gap, 2.0);
    // Non-finite points and displacements of the wrong dimension.
    let (f, v) = invalid(
        circle(vec![0.0, 0.0], 1.0)
            .project([f64::INFINITY, 0.0, 0.0], 2)
            .unwrap_err(),
    );
    assert_eq!((f.as_str(), v.as_str()), ("position", "[inf, 0]"));
    let spec = ObstacleSpec {
        shape: circle(vec![0.0, 0.0], 1.0),
        displacement: Some(vec![0.0, 0.1, 0.0]),
    };
    let (f, v) = invalid(spec.validate(2).unwrap_err());
    assert_eq!((f.as_str(), v.as_str()), ("displacement", "[0, 0.1, 0]"));
}

#[test]
fn the_scenario_syntax_parses_and_unknown_keys_are_refused() {
    #[derive(serde::Deserialize, Debug)]
    #[serde(deny_unknown_fields)]
    struct File {
        obstacle: ObstacleSpec,
    }
    let f: File =
        toml::from_str("obstacle = { kind = \"circle\", center = [5.0, 14.99], radius = 10 }")
            .unwrap();
    assert_eq!(
        f.obstacle,
        ObstacleSpec {
            shape: Obstacle::Circle {
                center: vec![5.0, 14.99],
                radius: 10.0
            },
            displacement: None,
        }
    );
    let f: File = toml::from_str(
        "[obstacle]\nkind = \"plane\"\npoint = [0.0, -0.1]\nnormal = [0.0, 1.0]\n\
         displacement = [0.0, -0.02]\n",
    )
    .unwrap();
    assert_eq!(f.obstacle.displacement, Some(vec![0.0, -0.02]));
    assert_eq!(f.obstacle.shape.kind(), "plane");
    for (text, word) in [
        (
            "obstacle = { kind = \"circle\", center = [0.0, 0.0], radius = 1.0, bogus = 1 }",
            "bogus",
        ),
        (
            "obstacle = { kind = \"circle\", center = [0.0, 0.0], radius = 1.0, axis = [0.0, 1.0] }",
            "axis",
        ),
        ("obstacle = { kind = \"ellipse\", center = [0.0, 0.0] }", "ellipse"),
        ("obstacle = { kind = \"circle\", center = [0.0, 0.0] }", "radius"),
        ("obstacle = { center = [0.0, 0.0], radius = 1.0 }", "kind"),
    ] {
        let e = toml::from_str::<File>(text).unwrap_err().to_string();
        assert!(e.contains(word), "{text}: {e}");
    }
    // The serialized form reads back the same.
    let spec = ObstacleSpec {
        shape: Obstacle::Paraboloid {
            apex: vec![0.0, 0.0, 1.0],
            axis: vec![0.0, 0.0, 1.0],
            radius: 2.5,
        },
        displacement: Some(vec![0.0, 0.0, -0.1]),
    };
    let text = toml::to_string(&spec).unwrap();
    assert_eq!(toml::from_str::<ObstacleSpec>(&text).unwrap(), spec);
}
