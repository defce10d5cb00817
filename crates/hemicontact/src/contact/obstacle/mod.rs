//! Rigid obstacles of given shape: the gap and the contact normal of a point of the body by
//! closest-point projection onto the obstacle's surface.
//!
//! An obstacle is a rigid solid `𝒪` with a smooth boundary `∂𝒪`; the body lies outside it.
//! For a point `x` (m) of the body, the projection `P(x)` is the closest point of `∂𝒪`, the
//! **gap** is the signed distance
//!
//! ```text
//! g(x) = +‖x − P(x)‖  if x ∉ 𝒪 (apart),     g(x) = −‖x − P(x)‖  if x ∈ 𝒪 (penetrating),
//! ```
//!
//! and the **normal** `ν(x)` is the unit normal of `∂𝒪` at `P(x)` pointing out of the
//! obstacle, towards `x` when `x` is outside: `x = P(x) + g(x) ν(x)`. Where the projection
//! is unique, `g` is differentiable with `∇g = ν`. Friction acts in the tangent plane of
//! `∂𝒪` at `P(x)`, the plane orthogonal to `ν(x)`.
//!
//! Under small deformation the projection is taken once, in the reference configuration:
//! each contact point `X_i` gets the fixed data `g_i = g(X_i)` and `ν_i = ν(X_i)`, and the
//! contact kinematics are those of a flat foundation at that point: `u_ν = u·ν_i`,
//! penetration `u_ν − g_i` (the usual small-displacement linearization of the contact
//! condition).
//!
//! # Shapes ([`Obstacle`])
//!
//! Lengths in m; a direction (`normal`, `axis`) need not be of unit length (it is
//! normalized, written `n̂`, `â` below) but must be nonzero.
//!
//! - `plane` (2D, 3D) through `point` p with `normal` n pointing from the obstacle into the
//!   body; the obstacle is the half-space `(x − p)·n̂ < 0`:
//!   `g = (x − p)·n̂`, `ν = n̂`, `P = x − g n̂`.
//! - `circle` (2D) and `sphere` (3D), the solid disc or ball of `center` c and `radius` R:
//!   `g = ‖x − c‖ − R`, `ν = (x − c)/‖x − c‖`, `P = c + R ν`.
//! - `cylinder` (3D), the solid circular cylinder of `radius` R about the line through
//!   `point` p along `axis` a: with `ρ = (x − p) − ((x − p)·â) â` the part of `x − p`
//!   orthogonal to the axis, `g = ‖ρ‖ − R`, `ν = ρ/‖ρ‖`, `P = x − g ν`.
//! - `paraboloid` (2D: a parabola; 3D: a paraboloid of revolution), the Hertz indenter: in
//!   local coordinates about the `apex` q, the height `z = (x − q)·â` along `axis` a and the
//!   distance `r = ‖ρ‖` from the axis (`ρ = (x − q) − z â`), the surface is
//!   `z = r²/(2R)` with `radius` R its radius of curvature at the apex. The obstacle is the
//!   convex solid `z > r²/(2R)`, on the side the axis points to: **the axis points from the
//!   apex into the indenter, away from the body**. A body below an indenter whose tip is at
//!   height h above it has `axis = [0, 1]` (2D) or `[0, 0, 1]` (3D), and near the apex
//!   `g ≈ h + r²/(2R)` (the gap of Hertz's theory).
//!
//! # The closest point on a paraboloid
//!
//! The closest point lies in the meridian plane of `x`, at radial coordinate `s ≥ 0` along
//! `e = ρ/r` and height `s²/(2R)`. In dimensionless variables `ŝ = s/R`, `r̂ = r/R`,
//! `ẑ = z/R` the orthogonality condition `(x − P)·(e + ŝ â) = 0` is the cubic
//!
//! ```text
//! φ(ŝ) = ŝ³/2 + (1 − ẑ) ŝ − r̂ = 0.
//! ```
//!
//! For `r̂ > 0` it has exactly one positive root: `φ(0) = −r̂ < 0` and `φ` is convex on
//! `ŝ > 0`; that root is the closest point (a negative root is the farther branch). Newton's
//! method starts from an upper bound `ŝ₀` of the root within a factor 2 of it (with
//! `b = 1 − ẑ`: `min(r̂/b, ∛(2r̂))` if `b > 0`, else `max(∛(4r̂), 2√(−b))`), and, `φ` being
//! convex and increasing to the right of the root, decreases monotonically to it. It stops
//! when `φ(ŝ) ≤ 0` (the root is reached to rounding) or when the Newton step is below
//! `4ε ŝ` (ε the machine epsilon). The quadratic convergence makes that a handful of steps:
//! at most 7 over 200 000 points with `r̂` and `|ẑ|` log-uniform in `[10⁻¹², 10⁸]` (the
//! module's unit test).
//! The root is then known to a few units of rounding, and the gap, computed as
//! `(x − P)·ν`, is insensitive to an error in `ŝ` to first order (orthogonality): it is
//! accurate to a few units of rounding of `‖x − q‖ + R`. On the axis (`r = 0`) the closest
//! point is the apex if `z ≤ R`; above the centre of curvature (`z > R`, inside the
//! indenter) it is not unique.
//!
//! # Rigid displacement ([`ObstacleSpec`])
//!
//! A prescribed rigid translation `t` (m) of the obstacle moves every point of it by `t`.
//! The gap and normal of `x` are those of the projection onto the translated shape, which is
//! the projection of `x − t` onto the shape as given, moved back by `t`:
//! `g_t(x) = g(x − t)`, `ν_t(x) = ν(x − t)`, `P_t(x) = P(x − t) + t`. To first order in
//! `‖t‖`, `g_t(x) = g(x) − t·ν(x)`.

use crate::error::{require, Error};
use crate::Result;
use serde::{Deserialize, Serialize};

/// Relative distance to the centre of a circle or sphere, or to the axis of a cylinder or
/// (inside the indenter, beyond its centre of curvature) of a paraboloid, below which the
/// closest point is refused as not unique: closer than `AMBIGUITY · R` (R the radius), the
/// direction of the normal is set by rounding errors of the coordinates.
pub const AMBIGUITY: f64 = 1e-12;

/// Most Newton steps of the closest point on a paraboloid; convergence takes a handful
/// from the starting bound (see the module documentation), so reaching this is a breakdown.
const MAX_NEWTON_STEPS: usize = 64;

/// The shape and position of a rigid obstacle (lengths in m); see the module documentation
/// for the gap and normal of each. Vectors have one coordinate per space dimension.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Obstacle {
    /// The half-space `(x − p)·n̂ < 0` (2D, 3D).
    Plane {
        /// A point p of the plane (m).
        point: Vec<f64>,
        /// The normal n, pointing from the obstacle into the body (any nonzero length).
        normal: Vec<f64>,
    },
    /// The solid disc `‖x − c‖ < R` (2D).
    Circle {
        /// The centre c (m).
        center: Vec<f64>,
        /// The radius R > 0 (m).
        radius: f64,
    },
    /// The solid ball `‖x − c‖ < R` (3D).
    Sphere {
        /// The centre c (m).
        center: Vec<f64>,
        /// The radius R > 0 (m).
        radius: f64,
    },
    /// The solid circular cylinder of radius R about the line through p along a (3D).
    Cylinder {
        /// A point p of the axis (m).
        point: Vec<f64>,
        /// The direction a of the axis (any nonzero length).
        axis: Vec<f64>,
        /// The radius R > 0 (m).
        radius: f64,
    },
    /// The convex solid `z > r²/(2R)` about the apex q, with `z = (x − q)·â` and r the
    /// distance from the axis (2D, 3D): the Hertz indenter.
    Paraboloid {
        /// The apex q (m).
        apex: Vec<f64>,
        /// The axis a, pointing from the apex into the obstacle, away from the body (any
        /// nonzero length).
        axis: Vec<f64>,
        /// The radius of curvature R > 0 at the apex (m).
        radius: f64,
    },
}

/// A rigid obstacle as a scenario gives it: its shape, and an optional prescribed rigid
/// translation. In a file, `displacement` is a key of the obstacle's table beside `kind`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ObstacleSpec {
    /// The shape, in its position before the displacement.
    #[serde(flatten)]
    pub shape: Obstacle,
    /// The rigid translation t of the obstacle (m, one coordinate per space dimension);
    /// none if absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub displacement: Option<Vec<f64>>,
}

/// The closest-point projection of a point `x` onto an obstacle's surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projection {
    /// Signed distance g from the surface (m): > 0 apart, < 0 penetrating.
    pub gap: f64,
    /// Unit normal ν of the surface at the closest point, pointing out of the obstacle
    /// (into the body); `x = point + gap·normal`. Unused coordinates are 0.
    pub normal: [f64; 3],
    /// The closest point P of the surface (m). Unused coordinates are 0.
    pub point: [f64; 3],
}

/// A validated shape: vectors padded to 3 coordinates, directions of unit length.
#[derive(Clone, Copy, Debug)]
enum Shape {
    Plane {
        point: [f64; 3],
        normal: [f64; 3],
    },
    Ball {
        center: [f64; 3],
        radius: f64,
    },
    Cylinder {
        point: [f64; 3],
        axis: [f64; 3],
        radius: f64,
    },
    Paraboloid {
        apex: [f64; 3],
        axis: [f64; 3],
        radius: f64,
    },
}

impl Obstacle {
    /// The smallest radius of curvature of the obstacle's surface (m): R of a circle,
    /// sphere or cylinder, the radius of curvature R at the apex of a paraboloid (elsewhere
    /// it is larger); `None` for a plane (flat).
    pub fn curvature_radius(&self) -> Option<f64> {
        match self {
            Obstacle::Plane { .. } => None,
            Obstacle::Circle { radius, .. }
            | Obstacle::Sphere { radius, .. }
            | Obstacle::Cylinder { radius, .. }
            | Obstacle::Paraboloid { radius, .. } => Some(*radius),
        }
    }

    /// The name of the shape as a scenario writes it (`kind`).
    pub fn kind(&self) -> &'static str {
        match self {
            Obstacle::Plane { .. } => "plane",
            Obstacle::Circle { .. } => "circle",
            Obstacle::Sphere { .. } => "sphere",
            Obstacle::Cylinder { .. } => "cylinder",
            Obstacle::Paraboloid { .. } => "paraboloid",
        }
    }

    /// Checks the obstacle for a body of dimension `dim`.
    ///
    /// # Errors
    /// [`Error::Invalid`] naming the field: `dimension` not 2 or 3; `kind` not available in
    /// `dim` (circle in 2D only; sphere and cylinder in 3D only); a point, normal or axis
    /// without exactly `dim` finite coordinates; a zero `normal` or `axis`; a `radius` that is
    /// not finite and > 0.
    pub fn validate(&self, dim: usize) -> Result<()> {
        self.shape(dim).map(|_| ())
    }

    /// The projection of the point `x` (m; in 2D its third coordinate is ignored) onto the
    /// obstacle's surface: the signed distance, the normal and the closest point (see the
    /// module documentation).
    ///
    /// # Errors
    /// The errors of [`Obstacle::validate`]; [`Error::Invalid`] for `position` if `x` is not
    /// finite or its closest point is not unique (at the centre of a circle or sphere, on
    /// the axis of a cylinder, or on the axis of a paraboloid beyond its centre of
    /// curvature, within [`AMBIGUITY`] times the radius); [`Error::Breakdown`] if Newton's
    /// method for a paraboloid does not converge (not expected, see the module
    /// documentation).
    pub fn project(&self, x: [f64; 3], dim: usize) -> Result<Projection> {
        let shape = self.shape(dim)?;
        let y = position(x, dim)?;
        shape.project(y)?.ok_or_else(|| self.ambiguous(x, dim))
    }

    /// The error of a point whose closest point is not unique.
    fn ambiguous(&self, x: [f64; 3], dim: usize) -> Error {
        let allowed = match self {
            Obstacle::Plane { .. } => "a point with a unique closest point on the plane",
            Obstacle::Circle { .. } | Obstacle::Sphere { .. } => {
                "a point away from the centre: every point of the surface is closest to the \
                 centre, so the contact normal is undefined"
            }
            Obstacle::Cylinder { .. } => {
                "a point away from the axis: every point of the surface around it is equally \
                 close, so the contact normal is undefined"
            }
            Obstacle::Paraboloid { .. } => {
                "a point away from the axis of the paraboloid beyond its centre of curvature \
                 (more than R from the apex inside the indenter), where the closest point is \
                 not unique"
            }
        };
        Error::invalid("position", coordinates_text(&x[..dim]), allowed)
    }

    /// The validated shape for dimension `dim`.
    fn shape(&self, dim: usize) -> Result<Shape> {
        require(
            dim == 2 || dim == 3,
            "dimension",
            dim,
            "2 or 3 (the dimension of the body)",
        )?;
        let (available, allowed) = match self {
            Obstacle::Plane { .. } | Obstacle::Paraboloid { .. } => (true, ""),
            Obstacle::Circle { .. } => (
                dim == 2,
                "an obstacle of a 3D body: plane, sphere, cylinder or paraboloid (a circle is \
                 for 2D bodies)",
            ),
            Obstacle::Sphere { .. } | Obstacle::Cylinder { .. } => (
                dim == 3,
                "an obstacle of a 2D body: plane, circle or paraboloid (spheres and cylinders \
                 are for 3D bodies)",
            ),
        };
        require(available, "kind", self.kind(), allowed)?;
        Ok(match self {
            Obstacle::Plane { point, normal } => Shape::Plane {
                point: coordinates("point", point, dim)?,
                normal: direction("normal", normal, dim)?,
            },
            Obstacle::Circle { center, radius } | Obstacle::Sphere { center, radius } => {
                Shape::Ball {
                    center: coordinates("center", center, dim)?,
                    radius: positive_radius(*radius)?,
                }
            }
            Obstacle::Cylinder {
                point,
                axis,
                radius,
            } => Shape::Cylinder {
                point: coordinates("point", point, dim)?,
                axis: direction("axis", axis, dim)?,
                radius: positive_radius(*radius)?,
            },
            Obstacle::Paraboloid { apex, axis, radius } => Shape::Paraboloid {
                apex: coordinates("apex", apex, dim)?,
                axis: direction("axis", axis, dim)?,
                radius: positive_radius(*radius)?,
            },
        })
    }
}

impl ObstacleSpec {
    /// The rigid translation t (m, padded to 3 coordinates; zero if absent).
    ///
    /// # Errors
    /// [`Error::Invalid`] for `displacement` without exactly `dim` finite coordinates.
    pub fn translation(&self, dim: usize) -> Result<[f64; 3]> {
        match &self.displacement {
            Some(t) => coordinates("displacement", t, dim),
            None => Ok([0.0; 3]),
        }
    }

    /// Checks the shape ([`Obstacle::validate`]) and the displacement
    /// ([`ObstacleSpec::translation`]) for a body of dimension `dim`.
    ///
    /// # Errors
    /// Those of [`Obstacle::validate`] and [`ObstacleSpec::translation`].
    pub fn validate(&self, dim: usize) -> Result<()> {
        self.shape.validate(dim)?;
        self.translation(dim).map(|_| ())
    }

    /// The implicit function φ of the obstacle translated by t at the point `x` (m): a
    /// polynomial of degree at most 2 in `x`, negative exactly inside the obstacle, zero on
    /// its surface, positive outside. With `y = x − t` and the notation of the module
    /// documentation: plane `φ = −(y − p)·n̂` (m), ball `φ = ‖y − c‖² − R²`, cylinder
    /// `φ = ‖ρ‖² − R²`, paraboloid `φ = ‖ρ‖² − 2R z` (m²). Unlike the gap it is not a
    /// distance, but its restriction to a segment or triangle is a convex quadratic, whose
    /// minimum tells whether the obstacle reaches into it.
    ///
    /// # Errors
    /// Those of [`ObstacleSpec::validate`]; [`Error::Invalid`] for `position` if `x` is not
    /// finite.
    pub fn implicit(&self, x: [f64; 3], dim: usize) -> Result<f64> {
        let shape = self.shape.shape(dim)?;
        let t = self.translation(dim)?;
        let y = position(x, dim)?;
        let y = sub(y, t);
        Ok(match shape {
            Shape::Plane { point, normal } => -dot(sub(y, point), normal),
            Shape::Ball { center, radius } => {
                let w = sub(y, center);
                dot(w, w) - radius * radius
            }
            Shape::Cylinder {
                point,
                axis,
                radius,
            } => {
                let w = sub(y, point);
                let rho = orthogonal_part(w, dot(w, axis), axis);
                dot(rho, rho) - radius * radius
            }
            Shape::Paraboloid { apex, axis, radius } => {
                let w = sub(y, apex);
                let along = dot(w, axis);
                let rho = orthogonal_part(w, along, axis);
                dot(rho, rho) - 2.0 * radius * along
            }
        })
    }

    /// The projection of `x` (m) onto the obstacle translated by its displacement t:
    /// that of `x − t` onto the shape, with the closest point moved back by t (the gap and
    /// the normal are those of `x − t`).
    ///
    /// # Errors
    /// Those of [`ObstacleSpec::validate`] and [`Obstacle::project`] (a point whose closest
    /// point is not unique is named by `x` itself).
    pub fn project(&self, x: [f64; 3], dim: usize) -> Result<Projection> {
        self.project_translated(x, dim, self.translation(dim)?)
    }

    /// [`ObstacleSpec::project`] with the obstacle translated by `t` (m) instead of its own
    /// translation.
    ///
    /// # Errors
    /// Those of [`ObstacleSpec::project`].
    pub fn project_translated(&self, x: [f64; 3], dim: usize, t: [f64; 3]) -> Result<Projection> {
        let shape = self.shape.shape(dim)?;
        let y = position(x, dim)?;
        let shifted = [y[0] - t[0], y[1] - t[1], y[2] - t[2]];
        let mut p = shape
            .project(shifted)?
            .ok_or_else(|| self.shape.ambiguous(x, dim))?;
        for k in 0..3 {
            p.point[k] += t[k];
        }
        Ok(p)
    }
}

/// The rigid obstacle of a contact boundary as the solver evaluates it: an
/// [`ObstacleSpec`] (in metres) with the units of the positions it is given and of the gaps
/// it returns. Both units are 1 m in the user's problem; the solver's dimensionless problem
/// ([`crate::solver::scaling`]) gives positions in units of its length scale and takes gaps
/// in units of its displacement scale: `ĝ(x̂) = g(x̂ · length_unit) / gap_unit`.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactObstacle {
    /// The obstacle, lengths in m.
    pub spec: ObstacleSpec,
    /// Unit of the positions given to [`ContactObstacle::project`] (m).
    pub length_unit: f64,
    /// Unit of the gaps it returns (m).
    pub gap_unit: f64,
}

impl ContactObstacle {
    /// The obstacle `spec` in the user's units (both units 1 m).
    pub fn new(spec: ObstacleSpec) -> Self {
        ContactObstacle {
            spec,
            length_unit: 1.0,
            gap_unit: 1.0,
        }
    }

    /// The same obstacle for positions in units of `length` (m) and gaps in units of
    /// `displacement` (m).
    pub fn nondimensional(&self, length: f64, displacement: f64) -> Self {
        ContactObstacle {
            spec: self.spec.clone(),
            length_unit: self.length_unit * length,
            gap_unit: self.gap_unit * displacement,
        }
    }

    /// The rigid translation t of the obstacle in units of `gap_unit` (the displacement
    /// unit; padded to 3 coordinates, zero if absent).
    ///
    /// # Errors
    /// Those of [`ObstacleSpec::translation`].
    pub fn translation(&self, dim: usize) -> Result<[f64; 3]> {
        Ok(self.spec.translation(dim)?.map(|c| c / self.gap_unit))
    }

    /// The obstacle with its translation multiplied by the load factor `lambda`.
    pub fn with_load_factor(&self, lambda: f64) -> Self {
        let mut out = self.clone();
        if let Some(t) = out.spec.displacement.as_mut() {
            t.iter_mut().for_each(|x| *x *= lambda);
        }
        out
    }

    /// The projection of `x` (in units of `length_unit`) onto the obstacle
    /// ([`ObstacleSpec::project`]): the gap in units of `gap_unit`, the unit normal, and the
    /// closest point in units of `length_unit`.
    ///
    /// # Errors
    /// Those of [`ObstacleSpec::project`], the point named in metres.
    pub fn project(&self, x: [f64; 3], dim: usize) -> Result<Projection> {
        Ok(self.project_carried(x, dim, [0.0; 3])?.0)
    }

    /// The projection of the point `x` (in units of `length_unit`) of a body carried by the
    /// translation `c` (in units of `gap_unit`; [`crate::rigid::carry`]): that of `x` onto the
    /// obstacle translated by `t − c` (t its own translation), the obstacle as the carried
    /// body meets it. Returns the projection as [`ContactObstacle::project`] does, and the
    /// translation `t − c` in units of `gap_unit`. With `c = 0` it is
    /// [`ContactObstacle::project`] and [`ContactObstacle::translation`], bit for bit; the
    /// relative translation `t − c` is formed once, so that moving the obstacle by t and
    /// every support by −t give the same bits.
    ///
    /// # Errors
    /// Those of [`ObstacleSpec::project`].
    pub fn project_carried(
        &self,
        x: [f64; 3],
        dim: usize,
        c: [f64; 3],
    ) -> Result<(Projection, [f64; 3])> {
        let t = self.spec.translation(dim)?;
        let relative = [0, 1, 2].map(|k| t[k] - c[k] * self.gap_unit);
        let mut p = self
            .spec
            .project_translated(x.map(|c| c * self.length_unit), dim, relative)?;
        p.gap /= self.gap_unit;
        p.point = p.point.map(|c| c / self.length_unit);
        Ok((p, relative.map(|v| v / self.gap_unit)))
    }
}

impl Shape {
    /// The projection of `y` (third coordinate 0 in 2D), or `None` if the closest point is
    /// not unique.
    fn project(&self, y: [f64; 3]) -> Result<Option<Projection>> {
        Ok(match *self {
            Shape::Plane { point, normal } => {
                let gap = dot(sub(y, point), normal);
                Some(Projection {
                    gap,
                    normal,
                    point: axpy(-gap, normal, y),
                })
            }
            Shape::Ball { center, radius } => round_projection(sub(y, center), center, radius),
            Shape::Cylinder {
                point,
                axis,
                radius,
            } => {
                let w = sub(y, point);
                let along = dot(w, axis);
                round_projection(
                    orthogonal_part(w, along, axis),
                    axpy(along, axis, point),
                    radius,
                )
            }
            Shape::Paraboloid { apex, axis, radius } => {
                paraboloid_projection(sub(y, apex), apex, axis, radius)?
            }
        })
    }
}

/// The projection onto a circle of radius R about `base` in the plane of the offset
/// `w = y − base` (a ball, or a cross-section of a cylinder, `base` on its axis).
fn round_projection(w: [f64; 3], base: [f64; 3], radius: f64) -> Option<Projection> {
    let d = norm(w);
    if d <= AMBIGUITY * radius {
        return None;
    }
    let normal = w.map(|c| c / d);
    Some(Projection {
        gap: d - radius,
        normal,
        point: axpy(radius, normal, base),
    })
}

/// The projection onto the paraboloid `z = r²/(2R)` about `apex` along the unit `axis`, of
/// the point at offset `w` from the apex (see the module documentation).
fn paraboloid_projection(
    w: [f64; 3],
    apex: [f64; 3],
    axis: [f64; 3],
    radius: f64,
) -> Result<Option<Projection>> {
    let along = dot(w, axis);
    let z = along / radius;
    let rho = orthogonal_part(w, along, axis);
    let distance = norm(rho);
    let r = distance / radius;
    let (s, radial) = if r == 0.0 || (r <= AMBIGUITY && z > 1.0) {
        if z > 1.0 {
            return Ok(None);
        }
        // On the axis below the centre of curvature: the apex.
        (0.0, [0.0; 3])
    } else {
        (meridian_root(r, z)?.0, rho.map(|c| c / distance))
    };
    let scale = (1.0 + s * s).sqrt();
    let normal = [0, 1, 2].map(|k| (s * radial[k] - axis[k]) / scale);
    let height = 0.5 * s * s;
    let point = [0, 1, 2].map(|k| apex[k] + radius * (s * radial[k] + height * axis[k]));
    let gap = radius * ((r - s) * s - (z - height)) / scale;
    Ok(Some(Projection { gap, normal, point }))
}

/// The positive root ŝ of `φ(ŝ) = ŝ³/2 + (1 − ẑ) ŝ − r̂` for `r̂ > 0`, by Newton's method
/// from an upper bound (see the module documentation), with the number of steps taken.
fn meridian_root(r: f64, z: f64) -> Result<(f64, usize)> {
    let b = 1.0 - z;
    let mut s = if b > 0.0 {
        (r / b).min((2.0 * r).cbrt())
    } else {
        (4.0 * r).cbrt().max(2.0 * (-b).sqrt())
    };
    for k in 0..MAX_NEWTON_STEPS {
        let phi = (0.5 * s * s + b) * s - r;
        if phi <= 0.0 {
            return Ok((s, k));
        }
        let step = phi / (1.5 * s * s + b);
        s -= step;
        if step <= 4.0 * f64::EPSILON * s {
            return Ok((s, k + 1));
        }
    }
    Err(Error::Breakdown(format!(
        "the closest point on a paraboloid (radial distance {r} and height {z} in units of \
         its radius) did not converge in {MAX_NEWTON_STEPS} Newton steps"
    )))
}

/// The part of `w` orthogonal to the unit `axis`, given `along = w·axis`: `w − along axis`,
/// orthogonalized a second time so that its direction is orthogonal to the axis to rounding
/// even close to the axis.
fn orthogonal_part(w: [f64; 3], along: f64, axis: [f64; 3]) -> [f64; 3] {
    let once = axpy(-along, axis, w);
    axpy(-dot(once, axis), axis, once)
}

/// The point `x` with its unused coordinate zeroed, refused if not finite.
fn position(x: [f64; 3], dim: usize) -> Result<[f64; 3]> {
    require(
        x[..dim].iter().all(|c| c.is_finite()),
        "position",
        coordinates_text(&x[..dim]),
        "finite coordinates (m)",
    )?;
    let mut y = [0.0; 3];
    y[..dim].copy_from_slice(&x[..dim]);
    Ok(y)
}

/// The vector `field` = `v` padded to 3 coordinates, refused unless it has `dim` finite
/// coordinates.
fn coordinates(field: &str, v: &[f64], dim: usize) -> Result<[f64; 3]> {
    require(
        v.len() == dim,
        field,
        coordinates_text(v),
        &format!("{dim} coordinates (m), one per dimension of the {dim}D body"),
    )?;
    require(
        v.iter().all(|c| c.is_finite()),
        field,
        coordinates_text(v),
        "finite coordinates (m)",
    )?;
    let mut a = [0.0; 3];
    a[..dim].copy_from_slice(v);
    Ok(a)
}

/// The direction `field` = `v` normalized, refused unless it has `dim` finite coordinates,
/// not all zero.
fn direction(field: &str, v: &[f64], dim: usize) -> Result<[f64; 3]> {
    let a = coordinates(field, v, dim)?;
    let largest = a.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
    require(
        largest > 0.0,
        field,
        coordinates_text(v),
        "a nonzero direction vector (any length; it is normalized)",
    )?;
    let scaled = a.map(|c| c / largest);
    let length = norm(scaled);
    Ok(scaled.map(|c| c / length))
}

/// The radius, refused unless finite and > 0.
fn positive_radius(radius: f64) -> Result<f64> {
    require(
        radius.is_finite() && radius > 0.0,
        "radius",
        radius,
        "a finite radius R > 0 (m)",
    )?;
    Ok(radius)
}

/// `[a, b, c]` with each coordinate as Rust displays it.
fn coordinates_text(v: &[f64]) -> String {
    let items: Vec<String> = v.iter().map(|c| c.to_string()).collect();
    format!("[{}]", items.join(", "))
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `α a + b`.
fn axpy(alpha: f64, a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        alpha * a[0] + b[0],
        alpha * a[1] + b[1],
        alpha * a[2] + b[2],
    ]
}

#[cfg(test)]
mod tests;
