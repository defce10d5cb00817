//! Built-in mesh generators.
//!
//! [`rectangle`] cuts `[x0, x0+lx] × [y0, y0+ly]` into `nx × ny` equal squares (rectangles)
//! and each into two triangles. Nodes are numbered row by row, `n = j (nx+1) + i`. The four
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
}

/// Largest number of subdivisions per side accepted by the generator (a 4096 × 4096 mesh
/// has 33 million triangles; larger requests are almost certainly typos).
pub const MAX_SUBDIVISIONS: usize = 4096;

/// Generates the rectangle mesh described by `r`; see the module documentation.
///
/// # Errors
/// [`Error::Mesh`] if a side length is not positive and finite, a subdivision count is zero
/// or above [`MAX_SUBDIVISIONS`], or the symmetric pattern is asked for an odd `nx`.
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
    let id = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
    let mut coords = Vec::with_capacity(2 * (nx + 1) * (ny + 1));
    for j in 0..=ny {
        for i in 0..=nx {
            // Exact at the ends: i == nx gives x0 + lx, not a rounded sum.
            coords.push(r.origin[0] + lx * (i as f64 / nx as f64));
            coords.push(r.origin[1] + ly * (j as f64 / ny as f64));
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
/// [`Error::Mesh`] on non-positive sides, subdivisions out of `1 ..= MAX_SUBDIVISIONS`, or
/// the symmetric pattern with an odd `nx`.
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
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                coords.push(b.origin[0] + b.size[0] * (i as f64 / nx as f64));
                coords.push(b.origin[1] + b.size[1] * (j as f64 / ny as f64));
                coords.push(b.origin[2] + b.size[2] * (k as f64 / nz as f64));
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
                    let vol = crate::fem::simplex::signed_measure(3, &[x[0], x[1], x[2], x[3]]);
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
