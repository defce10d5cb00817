//! Meshes exchanged with Python as byte buffers: node coordinates (float64), cells and
//! boundary facets (int64), little-endian, row-major.

use crate::errors::to_py;
use hemicontact::mesh::Mesh;
use hemicontact::Error;
use pyo3::prelude::*;
use pyo3::types::PyBytes;

/// The float64 values of a little-endian buffer.
pub fn f64s(bytes: &[u8], what: &str) -> PyResult<Vec<f64>> {
    if !bytes.len().is_multiple_of(8) {
        return Err(to_py(Error::Mesh(format!(
            "{what}: {} bytes, not a whole number of float64 values",
            bytes.len()
        ))));
    }
    Ok(bytes
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
        .collect())
}

/// The node indices of a little-endian int64 buffer, each from 0 to `u32::MAX − 1`.
fn indices(bytes: &[u8], what: &str) -> PyResult<Vec<u32>> {
    if !bytes.len().is_multiple_of(8) {
        return Err(to_py(Error::Mesh(format!(
            "{what}: {} bytes, not a whole number of int64 values",
            bytes.len()
        ))));
    }
    bytes
        .chunks_exact(8)
        .enumerate()
        .map(|(i, c)| {
            let v = i64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]);
            u32::try_from(v)
                .ok()
                .filter(|&v| v != u32::MAX)
                .ok_or_else(|| {
                    to_py(Error::Mesh(format!(
                        "{what}: entry {i} = {v} is not a node index (0 ≤ index < 2³² − 1)"
                    )))
                })
        })
        .collect()
}

/// Little-endian bytes of float64 values.
pub fn f64_bytes<'py>(py: Python<'py>, v: &[f64]) -> Bound<'py, PyBytes> {
    let bytes: Vec<u8> = v.iter().flat_map(|x| x.to_le_bytes()).collect();
    PyBytes::new(py, &bytes)
}

/// Little-endian bytes of int64 values.
pub fn i64_bytes<'py>(py: Python<'py>, v: impl Iterator<Item = i64>) -> Bound<'py, PyBytes> {
    let bytes: Vec<u8> = v.flat_map(|x| x.to_le_bytes()).collect();
    PyBytes::new(py, &bytes)
}

/// A validated mesh of the library.
#[pyclass(module = "hemicontact._core", name = "Mesh", frozen)]
pub struct NativeMesh {
    /// The library's mesh.
    pub mesh: Mesh,
}

#[pymethods]
impl NativeMesh {
    /// The mesh of dimension `dim` from the node coordinates `points` (float64, m), the
    /// cells `cells` (int64, `dim + 1` node indices each, positively oriented), the
    /// boundary parts `parts` (name, int64 facets of `dim` node indices; boundary facets in
    /// no part form the part `untagged`) and the cell regions `regions` (name, int64 cell
    /// indices; every cell in exactly one, or no regions at all).
    #[staticmethod]
    #[pyo3(signature = (dim, points, cells, parts, regions=Vec::new()))]
    fn from_buffers(
        py: Python<'_>,
        dim: usize,
        points: &[u8],
        cells: &[u8],
        parts: Vec<(String, Vec<u8>)>,
        regions: Vec<(String, Vec<u8>)>,
    ) -> PyResult<Self> {
        let coords = f64s(points, "points")?;
        let cells = indices(cells, "cells")?;
        let parts = parts
            .into_iter()
            .map(|(name, facets)| {
                let list = indices(&facets, &format!("facets of part {name:?}"))?;
                Ok((name, list))
            })
            .collect::<PyResult<Vec<_>>>()?;
        let n_cells = cells.len() / (dim + 1).max(1);
        let mut mesh = py
            .detach(|| Mesh::from_parts(dim, coords, cells, &parts))
            .map_err(to_py)?;
        if !regions.is_empty() {
            let mut region = vec![u16::MAX; n_cells];
            let mut names = Vec::with_capacity(regions.len());
            for (k, (name, list)) in regions.into_iter().enumerate() {
                for c in indices(&list, &format!("cells of region {name:?}"))? {
                    match region.get_mut(c as usize) {
                        Some(r) if *r == u16::MAX => *r = k as u16,
                        Some(r) => {
                            let other: &String = &names[*r as usize];
                            return Err(to_py(Error::Mesh(format!(
                                "cell {c} is in the regions {other:?} and {name:?}: each \
                                 cell belongs to one region"
                            ))));
                        }
                        None => {
                            return Err(to_py(Error::Mesh(format!(
                                "region {name:?}: cell {c} is out of range (there are \
                                 {n_cells} cells)"
                            ))))
                        }
                    }
                }
                names.push(name);
            }
            if let Some(c) = region.iter().position(|&r| r == u16::MAX) {
                return Err(to_py(Error::Mesh(format!(
                    "cell {c} is in no region: with regions, every cell belongs to one"
                ))));
            }
            mesh = mesh.with_regions(region, names).map_err(to_py)?;
        }
        Ok(NativeMesh { mesh })
    }

    /// The cell regions: (name, int64 bytes of its cell indices); empty for a mesh without
    /// regions.
    fn regions<'py>(&self, py: Python<'py>) -> Vec<(String, Bound<'py, PyBytes>)> {
        let m = &self.mesh;
        m.region_names()
            .iter()
            .enumerate()
            .map(|(r, name)| {
                let cells = (0..m.n_cells()).filter(|&c| m.cell_region(c) == r);
                (name.clone(), i64_bytes(py, cells.map(|c| c as i64)))
            })
            .collect()
    }

    /// Spatial dimension (2 or 3).
    #[getter]
    fn dim(&self) -> usize {
        self.mesh.dim()
    }

    /// Number of nodes.
    #[getter]
    fn n_nodes(&self) -> usize {
        self.mesh.n_nodes()
    }

    /// Number of cells.
    #[getter]
    fn n_cells(&self) -> usize {
        self.mesh.n_cells()
    }

    /// Node coordinates (float64 bytes, `n_nodes × dim`, m).
    fn points<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        f64_bytes(py, self.mesh.coords())
    }

    /// Cells (int64 bytes, `n_cells × (dim + 1)`).
    fn cells<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        i64_bytes(py, self.mesh.cells().iter().map(|&v| i64::from(v)))
    }

    /// The boundary parts: (name, int64 bytes of its facets, `k × dim`).
    fn parts<'py>(&self, py: Python<'py>) -> Vec<(String, Bound<'py, PyBytes>)> {
        let m = &self.mesh;
        m.part_names()
            .iter()
            .enumerate()
            .map(|(p, name)| {
                let nodes = m
                    .part_facets(p)
                    .flat_map(|f| m.facet(f).iter().map(|&v| i64::from(v)))
                    .collect::<Vec<_>>();
                (name.clone(), i64_bytes(py, nodes.into_iter()))
            })
            .collect()
    }
}
