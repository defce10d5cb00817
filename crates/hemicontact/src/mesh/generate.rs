//! Built-in mesh generators.
//!
//! [`rectangle`] cuts `[x0, x0+lx] × [y0, y0+ly]` into `nx × ny` rectangles and each into
//! two triangles. Nodes are numbered row by row, `n = j (nx+1) + i`. The four
//! sides are the boundary parts `bottom`, `right`, `top`, `left` (in this order).
//!
//! The cut pattern decides the diagonal of each square:
//!
//! ```text
//!   Uniform:   every square "/"          Symmetric: "/" left of the centre line,
//!   +--+--+--+--+                         "\" right of it (mirror-symmetric about
//!   | /| /| /| /|                         x = x0 + lx/2, nested under refinement)
//!   |/ |/ |/ |/ |                         +--+--+--+--+
//!   +--+--+--+--+                         | /| /|\ |\ |
//!                                         |/ |/ | \| \|
//!                                         +--+--+--+--+
//! ```
//!
//! Along each axis the cells are equal (progression 1) or graded by a geometric
//! progression `r` (as Gmsh's transfinite `Using Progression r`): the cell sizes are
//! `h_k = h_0 r^k`, `k = 0 … n−1`, summing to the side length `L`, so node `i` sits at
//!
//! ```text
//!   x_i = x0 + L (r^i − 1) / (r^n − 1)      (r ≠ 1),      x_i = x0 + L i / n      (r = 1).
//! ```
//!
//! `r > 1` refines towards the origin side (`x = x0`), `r < 1` towards the far side; see
//! [`axis_nodes`]. The symmetric cut pattern needs progression 1 along x: a graded x axis
//! has no mirror symmetry about its centre, so the pair is refused rather than silently
//! giving a pattern that only looks symmetric by index.

use super::Mesh;
use crate::error::{Error, Result};

/// Diagonal pattern of a generated rectangle mesh; see the module documentation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CutPattern {
    /// Every square cut along "/".
    Uniform,
    /// "/" left of the vertical centre line, "\" right of it (needs an even `nx`).
    Symmetric,
}

/// Geometry of a generated rectangle: origin, side lengths and subdivisions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rectangle {
    /// Lower-left corner (m).
    pub origin: [f64; 2],
    /// Side lengths `(lx, ly)` (m).
    pub size: [f64; 2],
    /// Squares per side `(nx, ny)`.
    pub n: [usize; 2],
    /// Diagonal pattern.
    pub pattern: CutPattern,
    /// Ratio of consecutive cell sizes along x and y, from the origin side to the far side
    /// (dimensionless; `1` for equal cells); see [`axis_nodes`].
    pub progression: [f64; 2],
}

/// Largest number of subdivisions per side accepted by the generator (a 4096 × 4096 mesh
/// has 33 million triangles; larger requests are almost certainly typos).
pub const MAX_SUBDIVISIONS: usize = 4096;

/// Smallest and largest progression ratio accepted by the generators (dimensionless).
pub const PROGRESSION_RANGE: [f64; 2] = [1e-3, 1e3];

/// Smallest cell of a graded axis accepted by the generators, as a fraction of the side.
pub const MIN_RELATIVE_CELL: f64 = 1e-9;

/// The smallest cell of `n` cells graded by the progression `r`, as a fraction of the
/// side: `(q − 1)/(q^n − 1)` with `q = max(r, 1/r)` (`1/n` for `r = 1`), computed as
/// `expm1(a)/expm1(n a)`, `a = |ln r|`, which stays accurate for `r` near 1 and gives 0
/// instead of overflowing for very large `q^n`.
pub fn smallest_relative_cell(r: f64, n: usize) -> f64 {
    if r == 1.0 {
        return 1.0 / n as f64;
    }
    let a = r.ln().abs();
    a.exp_m1() / (n as f64 * a).exp_m1()
}

/// Checks the progression `r` of an axis of `n` cells: `Ok` if it is finite, within
/// [`PROGRESSION_RANGE`] and its smallest cell is at least [`MIN_RELATIVE_CELL`] of the
/// side; otherwise `Err` with a description of what is allowed.
///
/// # Errors
/// The description of the allowed values (for the caller to name its field in).
pub fn check_progression(r: f64, n: usize) -> std::result::Result<(), String> {
    let [lo, hi] = PROGRESSION_RANGE;
    let allowed = format!(
        "a finite ratio from {lo:e} to {hi:e} whose smallest cell is at least \
         {MIN_RELATIVE_CELL:e} of the side"
    );
    if !(r.is_finite() && (lo..=hi).contains(&r)) {
        return Err(allowed);
    }
    let smallest = smallest_relative_cell(r, n.max(1));
    if smallest < MIN_RELATIVE_CELL {
        return Err(format!(
            "{allowed} (with {n} cells its smallest cell is {smallest:.1e} of the side)"
        ));
    }
    Ok(())
}

/// Node coordinates `x_0 … x_n` of an axis from `x0` of length `length` (m) cut into `n`
/// cells graded by the progression `r` (cell sizes `h_k = h_0 r^k`):
/// `x_i = x0 + L (r^i − 1)/(r^n − 1)`, evaluated as `x0 + L expm1(i ln r)/expm1(n ln r)`
/// (no cancellation for `r` near 1). For `r = 1` it is `x0 + L (i/n)`, the expression of
/// the uniform grid, bitwise. The ends are exact: `x_0 = x0`, `x_n = x0 + L`. The caller
/// checks `r` ([`check_progression`]) and `n ≥ 1`.
pub fn axis_nodes(x0: f64, length: f64, n: usize, r: f64) -> Vec<f64> {
    if r == 1.0 {
        // Exact at the ends: i == n gives x0 + L, not a rounded sum.
        return (0..=n)
            .map(|i| x0 + length * (i as f64 / n as f64))
            .collect();
    }
    let a = r.ln();
    let total = (n as f64 * a).exp_m1();
    (0..=n)
        .map(|i| match i {
            0 => x0,
            _ if i == n => x0 + length,
            _ => x0 + length * ((i as f64 * a).exp_m1() / total),
        })
        .collect()
}

/// Checks the progressions of a generated mesh: each with [`check_progression`], and
/// progression 1 along x with the symmetric pattern.
fn check_progressions(progression: &[f64], n: &[usize], pattern: CutPattern) -> Result<()> {
    for (axis, (&r, &cells)) in progression.iter().zip(n).enumerate() {
        if let Err(allowed) = check_progression(r, cells) {
            return Err(Error::Mesh(format!(
                "the progression along {} must be {allowed}, got {r}",
                ["x", "y", "z"][axis]
            )));
        }
    }
    if pattern == CutPattern::Symmetric && progression[0] != 1.0 {
        return Err(Error::Mesh(format!(
            "the symmetric cut pattern needs progression 1 along x (a graded x axis is not \
             mirror-symmetric about its centre), got {}; use the uniform pattern",
            progression[0]
        )));
    }
    Ok(())
}

/// Generates the rectangle mesh described by `r`; see the module documentation.
///
/// # Errors
/// [`Error::Mesh`] if a side length is not positive and finite, a subdivision count is zero
/// or above [`MAX_SUBDIVISIONS`], a progression fails [`check_progression`], or the
/// symmetric pattern is asked for an odd `nx` or a progression other than 1 along x.
pub fn rectangle(r: &Rectangle) -> Result<Mesh> {
    let [nx, ny] = r.n;
    let [lx, ly] = r.size;
    if !(lx.is_finite() && ly.is_finite() && lx > 0.0 && ly > 0.0) {
        return Err(Error::Mesh(format!(
            "rectangle sides must be positive, got {lx} × {ly}"
        )));
    }
    if !(r.origin[0].is_finite() && r.origin[1].is_finite()) {
        return Err(Error::Mesh("rectangle origin must be finite".into()));
    }
    if nx == 0 || ny == 0 || nx > MAX_SUBDIVISIONS || ny > MAX_SUBDIVISIONS {
        return Err(Error::Mesh(format!(
            "subdivisions must be between 1 and {MAX_SUBDIVISIONS}, got {nx} × {ny}"
        )));
    }
    if r.pattern == CutPattern::Symmetric && !nx.is_multiple_of(2) {
        return Err(Error::Mesh(format!(
            "the symmetric cut pattern needs an even number of squares along x, got {nx}"
        )));
    }
    check_progressions(&r.progression, &r.n, r.pattern)?;
    let id = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
    let xs = axis_nodes(r.origin[0], lx, nx, r.progression[0]);
    let ys = axis_nodes(r.origin[1], ly, ny, r.progression[1]);
    let mut coords = Vec::with_capacity(2 * (nx + 1) * (ny + 1));
    for &y in &ys {
        for &x in &xs {
            coords.push(x);
            coords.push(y);
        }
    }
    let mut cells = Vec::with_capacity(6 * nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            let (v00, v10, v01, v11) = (id(i, j), id(i + 1, j), id(i, j + 1), id(i + 1, j + 1));
            let slash = match r.pattern {
                CutPattern::Uniform => true,
                CutPattern::Symmetric => i < nx / 2,
            };
            if slash {
                cells.extend_from_slice(&[v00, v10, v11, v00, v11, v01]);
            } else {
                cells.extend_from_slice(&[v00, v10, v01, v10, v11, v01]);
            }
        }
    }
    let mut facets = Vec::with_capacity(4 * (nx + ny));
    let mut part = Vec::with_capacity(2 * (nx + ny));
    for i in 0..nx {
        facets.extend_from_slice(&[id(i, 0), id(i + 1, 0)]);
        part.push(0);
    }
    for j in 0..ny {
        facets.extend_from_slice(&[id(nx, j), id(nx, j + 1)]);
        part.push(1);
    }
    for i in (0..nx).rev() {
        facets.extend_from_slice(&[id(i + 1, ny), id(i, ny)]);
        part.push(2);
    }
    for j in (0..ny).rev() {
        facets.extend_from_slice(&[id(0, j + 1), id(0, j)]);
        part.push(3);
    }
    let names = ["bottom", "right", "top", "left"]
        .map(String::from)
        .to_vec();
    Mesh::try_new(2, coords, cells, facets, part, names)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rectangle_counts_and_area() {
        for pattern in [CutPattern::Uniform, CutPattern::Symmetric] {
            let r = Rectangle {
                origin: [0.0, 0.0],
                size: [4.0, 3.0],
                n: [6, 5],
                pattern,
                progression: [1.0; 2],
            };
            let m = rectangle(&r).unwrap();
            assert_eq!(m.n_nodes(), 7 * 6);
            assert_eq!(m.n_cells(), 60);
            assert_eq!(m.n_facets(), 22);
            assert!((m.measure() - 12.0).abs() < 1e-12);
            assert_eq!(m.part_nodes(m.part_index("left").unwrap()).len(), 6);
        }
    }

    #[test]
    fn symmetric_pattern_is_mirror_symmetric() {
        let r = Rectangle {
            origin: [0.0, 0.0],
            size: [4.0, 4.0],
            n: [8, 8],
            pattern: CutPattern::Symmetric,
            progression: [1.0; 2],
        };
        let m = rectangle(&r).unwrap();
        // Every cell's mirror image (x → 4 − x) is a cell of the mesh.
        let mirror = |n: u32| {
            let (i, j) = (n as usize % 9, n as usize / 9);
            (j * 9 + (8 - i)) as u32
        };
        let mut set: Vec<[u32; 3]> = (0..m.n_cells())
            .map(|c| {
                let mut k: [u32; 3] = m.cell(c).try_into().unwrap();
                k.sort();
                k
            })
            .collect();
        set.sort();
        for c in 0..m.n_cells() {
            let mut k: [u32; 3] = m.cell(c).iter().map(|&n| mirror(n)).collect::<Vec<_>>()[..]
                .try_into()
                .unwrap();
            k.sort();
            assert!(set.binary_search(&k).is_ok());
        }
    }

    #[test]
    fn odd_nx_with_symmetric_pattern_is_rejected() {
        let r = Rectangle {
            origin: [0.0, 0.0],
            size: [1.0, 1.0],
            n: [3, 2],
            pattern: CutPattern::Symmetric,
            progression: [1.0; 2],
        };
        assert!(matches!(rectangle(&r), Err(Error::Mesh(_))));
    }
}

/// Geometry of a generated box: origin, side lengths and subdivisions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoxSpec {
    /// Corner with the smallest coordinates (m).
    pub origin: [f64; 3],
    /// Side lengths `(lx, ly, lz)` (m).
    pub size: [f64; 3],
    /// Cubes per side `(nx, ny, nz)`.
    pub n: [usize; 3],
    /// Pattern: `Uniform` (every cube split the same way) or `Symmetric` (mirrored about
    /// the plane `x = x0 + lx/2`).
    pub pattern: CutPattern,
    /// Ratio of consecutive cell sizes along x, y and z, from the origin side to the far
    /// side (dimensionless; `1` for equal cells); see [`axis_nodes`].
    pub progression: [f64; 3],
}

/// Generates the box mesh described by `b`: `nx × ny × nz` cuboids, each cut into 6
/// tetrahedra along its main diagonal (Kuhn's triangulation: the tetrahedra
/// `[v₀, v₀ + e_a, v₀ + e_a + e_b, v₀ + e_x + e_y + e_z]` for the 6 orderings `(a, b, c)` of
/// the axes), which is conforming and nested under refinement by two. With the symmetric
/// pattern the cuboids right of the centre plane use the mirror image of the diagonal.
/// Nodes are numbered `n = (k (ny+1) + j) (nx+1) + i`. The six faces are the boundary parts
/// `left` (x = x0), `right`, `front` (y = y0), `back`, `bottom` (z = z0), `top`.
///
/// # Errors
/// [`Error::Mesh`] on non-positive sides, subdivisions out of `1 ..= MAX_SUBDIVISIONS`, a
/// progression failing [`check_progression`], or the symmetric pattern with an odd `nx` or
/// a progression other than 1 along x.
pub fn cuboid(b: &BoxSpec) -> Result<Mesh> {
    let [nx, ny, nz] = b.n;
    if b.size.iter().any(|&s| !(s.is_finite() && s > 0.0))
        || b.origin.iter().any(|x| !x.is_finite())
    {
        return Err(Error::Mesh(format!(
            "box sides must be positive and finite, got {:?}",
            b.size
        )));
    }
    if b.n.iter().any(|&k| k == 0 || k > MAX_SUBDIVISIONS) {
        return Err(Error::Mesh(format!(
            "subdivisions must be between 1 and {MAX_SUBDIVISIONS}, got {:?}",
            b.n
        )));
    }
    if b.pattern == CutPattern::Symmetric && !nx.is_multiple_of(2) {
        return Err(Error::Mesh(format!(
            "the symmetric cut pattern needs an even number of cubes along x, got {nx}"
        )));
    }
    check_progressions(&b.progression, &b.n, b.pattern)?;
    // Node indices are u32 and the 6 tetrahedra per cube must be addressable: refuse
    // sizes beyond that before allocating anything.
    let nodes = (nx as u64 + 1) * (ny as u64 + 1) * (nz as u64 + 1);
    let tets = 6 * nx as u64 * ny as u64 * nz as u64;
    if nodes > u32::MAX as u64 / 2 || tets > u32::MAX as u64 {
        return Err(Error::Mesh(format!(
            "{nx} × {ny} × {nz} cubes give {nodes} nodes and {tets} tetrahedra, more than supported"
        )));
    }
    let id = |i: usize, j: usize, k: usize| ((k * (ny + 1) + j) * (nx + 1) + i) as u32;
    let mut coords = Vec::new();
    let mut cells = Vec::new();
    if coords.try_reserve_exact(3 * nodes as usize).is_err()
        || cells.try_reserve_exact(4 * tets as usize).is_err()
    {
        return Err(Error::OutOfMemory(format!(
            "a box mesh of {nodes} nodes and {tets} tetrahedra"
        )));
    }
    let [xs, ys, zs] =
        [0, 1, 2].map(|a| axis_nodes(b.origin[a], b.size[a], b.n[a], b.progression[a]));
    for &z in &zs {
        for &y in &ys {
            for &x in &xs {
                coords.extend_from_slice(&[x, y, z]);
            }
        }
    }
    let orders = [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ];
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let mirrored = b.pattern == CutPattern::Symmetric && i >= nx / 2;
                // Local corner (a, b, c) ∈ {0,1}³ → global node; mirroring flips a.
                let corner = |p: [usize; 3]| {
                    let a = if mirrored { 1 - p[0] } else { p[0] };
                    id(i + a, j + p[1], k + p[2])
                };
                for ord in orders {
                    let mut p = [0usize; 3];
                    let mut tet = [corner(p); 4];
                    for (s, &axis) in ord.iter().enumerate() {
                        p[axis] = 1;
                        tet[s + 1] = corner(p);
                    }
                    // Mirroring (and half of the orderings) reverse the orientation.
                    let x: Vec<[f64; 3]> = tet
                        .iter()
                        .map(|&v| {
                            let o = 3 * v as usize;
                            [coords[o], coords[o + 1], coords[o + 2]]
                        })
                        .collect();
                    let vol =
                        crate::geometry::simplex::signed_measure(3, &[x[0], x[1], x[2], x[3]]);
                    if vol < 0.0 {
                        tet.swap(2, 3);
                    }
                    cells.extend_from_slice(&tet);
                }
            }
        }
    }
    // Boundary facets: the two triangles of every boundary square, from the cells' faces.
    let mut facets = Vec::new();
    let mut part = Vec::new();
    let on = |v: u32, axis: usize, side: usize| {
        let v = v as usize;
        let c = [
            v % (nx + 1),
            (v / (nx + 1)) % (ny + 1),
            v / ((nx + 1) * (ny + 1)),
        ];
        c[axis] == if side == 0 { 0 } else { b.n[axis] }
    };
    for c in cells.chunks(4) {
        for skip in 0..4 {
            let f: Vec<u32> = (0..4).filter(|&a| a != skip).map(|a| c[a]).collect();
            for axis in 0..3 {
                for side in 0..2 {
                    if f.iter().all(|&v| on(v, axis, side)) {
                        facets.extend_from_slice(&f);
                        // Part order: left, right, front, back, bottom, top.
                        part.push((2 * axis + side) as u16);
                    }
                }
            }
        }
    }
    let names = ["left", "right", "front", "back", "bottom", "top"]
        .map(String::from)
        .to_vec();
    Mesh::try_new(3, coords, cells, facets, part, names)
}

#[cfg(test)]
mod box_tests {
    use super::*;

    #[test]
    fn box_volume_counts_and_parts() {
        for pattern in [CutPattern::Uniform, CutPattern::Symmetric] {
            let b = BoxSpec {
                origin: [0.0; 3],
                size: [4.0, 2.0, 3.0],
                n: [4, 2, 3],
                pattern,
                progression: [1.0; 3],
            };
            let m = cuboid(&b).unwrap();
            assert_eq!(m.n_nodes(), 5 * 3 * 4);
            assert_eq!(m.n_cells(), 6 * 24);
            assert!((m.measure() - 24.0).abs() < 1e-12);
            // Two triangles per boundary square.
            assert_eq!(m.n_facets(), 2 * 2 * (4 * 2 + 4 * 3 + 2 * 3));
            let area: f64 = m
                .part_facets(m.part_index("bottom").unwrap())
                .map(|f| m.facet_measure_normal(f).0)
                .sum();
            assert!((area - 8.0).abs() < 1e-12);
        }
    }
}
