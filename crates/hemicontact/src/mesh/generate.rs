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
    if r.pattern == CutPattern::Symmetric && nx % 2 != 0 {
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
