//! Named regions of cells: the groups to which a scenario assigns materials.
//!
//! A region is a set of cells with a name: a Gmsh physical group of cells (surfaces in 2D,
//! volumes in 3D), a box of a generated mesh, or a tag per cell given by a script. Every
//! cell belongs to exactly one region. A mesh without regions has one unnamed region
//! (index 0), so a single material needs no region at all.

use super::Mesh;
use crate::error::{Error, Result};

/// The most regions a mesh may have (indices are stored as `u16`).
const MAX_REGIONS: usize = u16::MAX as usize;

impl Mesh {
    /// The same mesh with cell `c` in the region `names[region[c]]`.
    ///
    /// # Errors
    /// [`Error::Mesh`] if `region` does not have one entry per cell, an index is not below
    /// `names.len()`, a name is empty or repeated, a region holds no cell, or there are more
    /// than 65 535 regions.
    pub fn with_regions(mut self, region: Vec<u16>, names: Vec<String>) -> Result<Mesh> {
        if region.len() != self.n_cells() {
            return Err(Error::Mesh(format!(
                "{} cell region indices for {} cells: one per cell is required",
                region.len(),
                self.n_cells()
            )));
        }
        if names.is_empty() || names.len() > MAX_REGIONS {
            return Err(Error::Mesh(format!(
                "{} region names: between 1 and {MAX_REGIONS} are allowed",
                names.len()
            )));
        }
        for (i, name) in names.iter().enumerate() {
            if name.is_empty() || names[..i].contains(name) {
                return Err(Error::Mesh(format!(
                    "cell region {name:?}: region names must be non-empty and distinct"
                )));
            }
        }
        let mut cells_in = vec![0usize; names.len()];
        for (c, &r) in region.iter().enumerate() {
            match cells_in.get_mut(r as usize) {
                Some(n) => *n += 1,
                None => {
                    return Err(Error::Mesh(format!(
                        "cell {c}: region index {r} is out of range (there are {} regions)",
                        names.len()
                    )))
                }
            }
        }
        if let Some(r) = cells_in.iter().position(|&n| n == 0) {
            return Err(Error::Mesh(format!(
                "cell region {:?} holds no cell",
                names[r]
            )));
        }
        self.cell_region = region;
        self.region_names = names;
        Ok(self)
    }

    /// The names of the cell regions (empty for a mesh without regions).
    pub fn region_names(&self) -> &[String] {
        &self.region_names
    }

    /// The number of cell regions: at least 1 (a mesh without regions has one).
    pub fn n_regions(&self) -> usize {
        self.region_names.len().max(1)
    }

    /// The region of cell `c` (0 for a mesh without regions).
    #[inline]
    pub fn cell_region(&self, c: usize) -> usize {
        self.cell_region.get(c).map_or(0, |&r| r as usize)
    }

    /// Index of the cell region named `name`, if any.
    pub fn region_index(&self, name: &str) -> Option<usize> {
        self.region_names.iter().position(|r| r == name)
    }

    /// The cells whose centroid lies in the closed box `[lo, hi]` (m; the unused coordinates
    /// of a 2D mesh are ignored).
    pub fn cells_in_box(&self, lo: [f64; 3], hi: [f64; 3]) -> Vec<usize> {
        let d = self.dim();
        (0..self.n_cells())
            .filter(|&c| {
                let x = self.cell_coords(c);
                (0..d).all(|i| {
                    let centroid = x[..=d].iter().map(|p| p[i]).sum::<f64>() / (d + 1) as f64;
                    lo[i] <= centroid && centroid <= hi[i]
                })
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use crate::mesh::generate::{rectangle, CutPattern, Rectangle};

    fn square() -> crate::mesh::Mesh {
        rectangle(&Rectangle {
            origin: [0.0, 0.0],
            size: [2.0, 1.0],
            n: [4, 2],
            pattern: CutPattern::Uniform,
            progression: [1.0, 1.0],
        })
        .unwrap()
    }

    #[test]
    fn a_box_picks_the_cells_whose_centroid_it_holds() {
        let m = square();
        let left = m.cells_in_box([0.0, 0.0, 0.0], [1.0, 1.0, 0.0]);
        assert_eq!(left.len(), m.n_cells() / 2);
        let mut region = vec![1u16; m.n_cells()];
        for c in left {
            region[c] = 0;
        }
        let m = m
            .with_regions(region, vec!["soft".into(), "stiff".into()])
            .unwrap();
        assert_eq!(m.n_regions(), 2);
        assert_eq!(m.region_index("stiff"), Some(1));
        let x = m.cell_coords(0);
        assert_eq!(
            m.cell_region(0),
            usize::from(x[0][0] + x[1][0] + x[2][0] > 3.0)
        );
    }

    #[test]
    fn bad_regions_are_refused_with_the_reason() {
        let n = square().n_cells();
        let err = |r: Vec<u16>, names: Vec<&str>| {
            square()
                .with_regions(r, names.into_iter().map(String::from).collect())
                .unwrap_err()
                .to_string()
        };
        assert!(err(vec![0; n - 1], vec!["a"]).contains("one per cell"));
        assert!(err(vec![2; n], vec!["a", "b"]).contains("out of range"));
        assert!(err(vec![0; n], vec!["a", "a"]).contains("distinct"));
        assert!(err(vec![0; n], vec!["a", "b"]).contains("\"b\" holds no cell"));
        assert!(err(vec![0; n], vec![""]).contains("non-empty"));
    }
}
