//! Rigid motions in words: the free motions of a body described for the user (a
//! translation along an axis, a rotation about an axis through a point) with what would
//! block each; the bodies named by their cell regions; the motions of a group of bodies
//! ([`super::groups`]); the error for the motions nothing carries, and that of a body that
//! ran away ([`RigidMotions::contact_lost`]).

use super::body::{n_modes, Body};
use super::groups::Motion;
use super::motions::{RigidMotions, Runaway};
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::parallel::Share;

const AXES: [&str; 3] = ["x", "y", "z"];

fn point(x: &[f64]) -> String {
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
        let q = crate::geometry::simplex::cross(&w, &perp);
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
fn remedy(d: usize, body: &Body, c: &[f64; 6]) -> String {
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

/// A basis of the span of `basis` (motions of a group's bodies) in reduced row echelon form
/// with the rotation coefficients (of every body) first: so a span containing pure
/// translations shows them as such, and every other vector is a rotation (about a point or
/// axis found by [`describe`]).
pub(super) fn reduced(d: usize, basis: &[Motion]) -> Vec<Motion> {
    let m = n_modes(d);
    let n = basis.first().map_or(0, Vec::len);
    // Column order: every body's rotations, then every body's translations.
    let order: Vec<usize> = (0..n)
        .flat_map(|b| (d..m).map(move |i| 6 * b + i))
        .chain((0..n).flat_map(|b| (0..d).map(move |i| 6 * b + i)))
        .collect();
    let mut rows: Vec<Vec<f64>> = basis.iter().map(|c| c.concat()).collect();
    let mut lead = 0;
    for &col in &order {
        if lead == rows.len() {
            break;
        }
        let Some(p) =
            (lead..rows.len()).max_by(|&i, &j| rows[i][col].abs().total_cmp(&rows[j][col].abs()))
        else {
            break;
        };
        if rows[p][col].abs() <= 1e-8 {
            continue;
        }
        rows.swap(lead, p);
        let pivot = rows[lead][col];
        for x in rows[lead].iter_mut() {
            *x /= pivot;
        }
        for i in 0..rows.len() {
            if i != lead {
                let f = rows[i][col];
                let r = rows[lead].clone();
                for (x, y) in rows[i].iter_mut().zip(r) {
                    *x -= f * y;
                }
            }
        }
        lead += 1;
    }
    rows.iter()
        .map(|r| {
            r.chunks_exact(6)
                .map(|c| std::array::from_fn(|i| if c[i].abs() <= 1e-9 { 0.0 } else { c[i] }))
                .collect()
        })
        .collect()
}

/// `region `a`` or `regions `a`, `b``: the named cell regions of `body` (empty without).
fn regions(body: &Body) -> String {
    let names: Vec<String> = body.regions.iter().map(|r| format!("`{r}`")).collect();
    match names.len() {
        0 => String::new(),
        1 => format!("region {}", names[0]),
        _ => format!("regions {}", names.join(", ")),
    }
}

impl RigidMotions {
    /// The free motions of body `b` in words, one per basis vector (see [`describe`]).
    pub fn describe_free(&self, b: usize) -> Vec<String> {
        let one: Vec<Motion> = self.free[b].iter().map(|c| vec![*c]).collect();
        reduced(self.dim, &one)
            .iter()
            .map(|c| describe(self.dim, &self.bodies[b], &c[0]))
            .collect()
    }

    /// The free rigid motions of all bodies in words (empty if none), each prefixed with
    /// its mesh component when the mesh has several.
    pub fn describe_all(&self) -> Vec<String> {
        let several = self.bodies.len() > 1;
        (0..self.bodies.len())
            .flat_map(|b| {
                self.describe_free(b).into_iter().map(move |s| {
                    if several {
                        format!("mesh component {}: {s}", b + 1)
                    } else {
                        s
                    }
                })
            })
            .collect()
    }

    /// The rigid motion with coefficients `c` of body `b` in words, in coordinates whose
    /// unit is `length` times that of the mesh (1 for a mesh in metres; the length scale
    /// `L` of [`crate::solver::scaling`] for a mesh in its dimensionless variables).
    pub fn describe_in(&self, b: usize, c: &[f64; 6], length: f64) -> String {
        let body = self.bodies[b].in_units(length);
        describe(self.dim, &body, c)
    }

    /// # Errors
    /// [`Error::ContactLost`] if a body with a free rigid motion has moved by more than
    /// its size under the displacement `u` ([`RigidMotions::runaway`]; `length` as there):
    /// the message names the motion it moved along and how far, in the units of `u` and of
    /// the mesh.
    pub fn check_runaway(&self, mesh: &Mesh, u: &[f64], length: f64) -> Result<()> {
        match self.runaway(mesh, u, length, &Share::WHOLE) {
            None => Ok(()),
            Some(r) => Err(self.contact_lost(&r, 1.0, length)),
        }
    }

    /// The [`Error::ContactLost`] of a runaway, described in the user's units: `length` (m)
    /// the unit of the mesh's coordinates, `displacement` (m) that of the displacements.
    pub fn contact_lost(&self, r: &Runaway, length: f64, displacement: f64) -> Error {
        let b = r.body;
        let which = match self.label(b) {
            l if l.is_empty() => l,
            l => format!("{l}: "),
        };
        let motion = if r.motion.iter().any(|&x| x != 0.0) {
            self.describe_in(b, &r.motion, length)
        } else {
            self.free[b]
                .iter()
                .map(|c| self.describe_in(b, c, length))
                .collect::<Vec<_>>()
                .join("; ")
        };
        Error::ContactLost {
            motions: format!(
                "{which}{motion} (the body moved by {} m, more than its size {} m)",
                crate::display::significant(r.moved * displacement),
                crate::display::significant(self.bodies[b].size * length)
            ),
        }
    }

    /// Body `b` in a few words when the mesh has several: its cell regions, when the mesh
    /// names them, and its mesh component (`region `upper` (mesh component 3 of 3)`, `mesh
    /// component 3 of 3`); empty for the one body of a mesh.
    pub fn label(&self, b: usize) -> String {
        let names = regions(&self.bodies[b]);
        let n = self.bodies.len();
        match (n > 1, names.is_empty()) {
            (false, _) => String::new(),
            (true, true) => format!("mesh component {} of {n}", b + 1),
            (true, false) => format!("{names} (mesh component {} of {n})", b + 1),
        }
    }

    /// Body `b` at length, for an error: its cell regions, its mesh component, its node
    /// count, first node and bounding box.
    fn long_label(&self, b: usize) -> String {
        let body = &self.bodies[b];
        let (lo, hi) = body.bounding_box;
        let d = self.dim;
        let names = regions(body);
        format!(
            "{}mesh component {} of {} ({} nodes, from node {}, bounding box {} to {})",
            if names.is_empty() {
                names
            } else {
                format!("{names}, ")
            },
            b + 1,
            self.bodies.len(),
            body.nodes.len(),
            body.nodes[0],
            point(&lo[..d]),
            point(&hi[..d])
        )
    }

    /// The motion `motion` of group `g` in words, in coordinates whose unit is `length`
    /// times that of the mesh ([`RigidMotions::describe_in`]): for a group of one body its
    /// motion, prefixed with [`RigidMotions::label`] (`mesh component 2 of 3: translation
    /// along y`) when the mesh has several bodies or named regions; for several bodies, each
    /// moving body's, or the one motion they make together (`region `lower` (mesh
    /// component 2 of 3) and region `upper` (mesh component 3 of 3) together: translation
    /// along y`).
    pub fn describe_group_in(&self, g: usize, motion: &Motion, length: f64) -> String {
        let bodies = &self.groups[g].bodies;
        let words = |j: usize| self.describe_in(bodies[j], &motion[j], length);
        let with_label = |j: usize, w: String| match self.label(bodies[j]) {
            l if l.is_empty() => w,
            l => format!("{l}: {w}"),
        };
        if bodies.len() == 1 {
            return with_label(0, words(0));
        }
        let reach = motion.iter().map(norm6).fold(0.0f64, f64::max);
        let moving: Vec<usize> = (0..bodies.len())
            .filter(|&j| norm6(&motion[j]) > 1e-9 * reach)
            .collect();
        if moving.len() > 1
            && moving
                .iter()
                .all(|&j| self.same_motion(g, motion, moving[0], j))
        {
            let labels: Vec<String> = moving.iter().map(|&j| self.label(bodies[j])).collect();
            return format!("{} together: {}", labels.join(" and "), words(moving[0]));
        }
        moving
            .iter()
            .map(|&j| with_label(j, words(j)))
            .collect::<Vec<_>>()
            .join(", with ")
    }

    /// Whether bodies `i` and `j` of group `g` move by the same rigid motion of space under
    /// `motion` (the same angular velocity and the same displacement of the origin, to
    /// 10⁻⁹ of the motion's size).
    fn same_motion(&self, g: usize, motion: &Motion, i: usize, j: usize) -> bool {
        let d = self.dim;
        let global = |k: usize| {
            let body = &self.bodies[self.groups[g].bodies[k]];
            let c = &motion[k];
            let mut w = [0.0; 3];
            if d == 2 {
                w[2] = c[2] / body.size;
            } else {
                w.copy_from_slice(&c[3..6]);
                w = w.map(|x| x / body.size);
            }
            // The displacement of the origin: a − ω × x̄.
            let mut a = [0.0; 3];
            a[..d].copy_from_slice(&c[..d]);
            let wx = crate::geometry::simplex::cross(&w, &body.centroid);
            let o: [f64; 3] = std::array::from_fn(|k| a[k] - wx[k]);
            let reach = body.size + body.centroid.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            (o, w.map(|x| x * reach))
        };
        let ((oi, wi), (oj, wj)) = (global(i), global(j));
        let scale = [oi, wi, oj, wj]
            .iter()
            .map(|v| norm6(&[v[0], v[1], v[2], 0.0, 0.0, 0.0]))
            .fold(0.0f64, f64::max);
        (0..3)
            .all(|k| (oi[k] - oj[k]).abs() <= 1e-9 * scale && (wi[k] - wj[k]).abs() <= 1e-9 * scale)
    }

    /// # Errors
    /// [`Error::RigidMotion`] (with `source` as the file) if some group of bodies has a
    /// rigid motion that is neither prescribed nor carried by contact: the message names
    /// the bodies (by their cell regions, when the mesh names them, and their mesh
    /// components, when there are several), each such motion in words, and what would
    /// block it.
    pub fn check(&self, source: &str) -> Result<()> {
        let several = self.bodies.len() > 1;
        let mut parts = Vec::new();
        for (g, group) in self.groups.iter().enumerate() {
            if group.uncarried.is_empty() {
                continue;
            }
            let reduced = reduced(self.dim, &group.uncarried);
            if let [b] = group.bodies[..] {
                let body = &self.bodies[b];
                let motions: Vec<String> = reduced
                    .iter()
                    .map(|c| {
                        format!(
                            "{} ({})",
                            describe(self.dim, body, &c[0]),
                            remedy(self.dim, body, &c[0])
                        )
                    })
                    .collect();
                let which = if several {
                    format!("{}: ", self.long_label(b))
                } else {
                    String::new()
                };
                parts.push(format!("{which}{}", motions.join("; ")));
                continue;
            }
            let labels: Vec<String> = group.bodies.iter().map(|&b| self.long_label(b)).collect();
            let motions: Vec<String> = reduced
                .iter()
                .map(|c| self.describe_group_in(g, c, 1.0))
                .collect();
            parts.push(format!(
                "the bodies {}, in contact with one another, whose free motions contact \
                 carries only relative to one another: {} (hold one of these bodies along it \
                 by a Dirichlet condition ([[dirichlet]]), or let a [[contact]] part carry \
                 it against a foundation, an obstacle or a held body)",
                labels.join(" and "),
                motions.join("; ")
            ));
        }
        if parts.is_empty() {
            return Ok(());
        }
        Err(Error::RigidMotion {
            file: source.to_string(),
            motions: parts.join(" | "),
        })
    }
}

fn norm6(c: &[f64; 6]) -> f64 {
    c.iter().map(|x| x * x).sum::<f64>().sqrt()
}
