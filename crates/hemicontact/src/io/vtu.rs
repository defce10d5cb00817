//! VTK XML UnstructuredGrid writer (`.vtu`), binary appended data (raw, little-endian,
//! 64-bit block headers), readable by ParaView, VTK and meshio.
//!
//! Point coordinates are written with 3 components (z = 0 in 2D); vectors with 3 components;
//! symmetric tensors as 9-component full matrices (row-major).

use crate::error::Result;
use crate::mesh::Mesh;
use std::fmt::Write as _;
use std::path::Path;

enum Data {
    F64(Vec<f64>),
    I32(Vec<i32>),
}

struct Array {
    name: String,
    components: usize,
    data: Data,
}

/// A `.vtu` file under construction: a mesh plus named point and cell arrays.
pub struct VtuWriter<'a> {
    mesh: &'a Mesh,
    point: Vec<Array>,
    cell: Vec<Array>,
}

impl<'a> VtuWriter<'a> {
    /// Starts a file for `mesh`.
    pub fn new(mesh: &'a Mesh) -> Self {
        VtuWriter {
            mesh,
            point: Vec::new(),
            cell: Vec::new(),
        }
    }

    /// Adds a point array with `components` values per node (node-major, length
    /// `components · n_nodes`).
    ///
    /// # Panics
    /// If the length does not match.
    #[track_caller]
    pub fn point_f64(&mut self, name: &str, components: usize, data: Vec<f64>) -> &mut Self {
        assert_eq!(data.len(), components * self.mesh.n_nodes());
        self.point.push(Array {
            name: name.into(),
            components,
            data: Data::F64(data),
        });
        self
    }

    /// Adds an integer point array (one value per node).
    ///
    /// # Panics
    /// If the length does not match.
    #[track_caller]
    pub fn point_i32(&mut self, name: &str, data: Vec<i32>) -> &mut Self {
        assert_eq!(data.len(), self.mesh.n_nodes());
        self.point.push(Array {
            name: name.into(),
            components: 1,
            data: Data::I32(data),
        });
        self
    }

    /// Adds a cell array with `components` values per cell (cell-major).
    ///
    /// # Panics
    /// If the length does not match.
    #[track_caller]
    pub fn cell_f64(&mut self, name: &str, components: usize, data: Vec<f64>) -> &mut Self {
        assert_eq!(data.len(), components * self.mesh.n_cells());
        self.cell.push(Array {
            name: name.into(),
            components,
            data: Data::F64(data),
        });
        self
    }

    /// Adds an integer cell array (one value per cell).
    ///
    /// # Panics
    /// If the length does not match.
    #[track_caller]
    pub fn cell_i32(&mut self, name: &str, data: Vec<i32>) -> &mut Self {
        assert_eq!(data.len(), self.mesh.n_cells());
        self.cell.push(Array {
            name: name.into(),
            components: 1,
            data: Data::I32(data),
        });
        self
    }

    /// Encodes the file.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mesh = self.mesh;
        let d = mesh.dim();
        let mut blocks: Vec<Vec<u8>> = Vec::new();
        let mut xml = String::new();
        let mut offset = 0usize;
        let mut push_block = |bytes: Vec<u8>, blocks: &mut Vec<Vec<u8>>| -> usize {
            let at = offset;
            offset += 8 + bytes.len();
            blocks.push(bytes);
            at
        };
        let _ = write!(
            xml,
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" \
             byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<UnstructuredGrid>\n\
             <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
            mesh.n_nodes(),
            mesh.n_cells()
        );
        for (tag, arrays) in [("PointData", &self.point), ("CellData", &self.cell)] {
            let _ = writeln!(xml, "<{tag}>");
            for a in arrays.iter() {
                let (ty, bytes) = match &a.data {
                    Data::F64(v) => ("Float64", v.iter().flat_map(|x| x.to_le_bytes()).collect()),
                    Data::I32(v) => ("Int32", v.iter().flat_map(|x| x.to_le_bytes()).collect()),
                };
                let at = push_block(bytes, &mut blocks);
                let _ = writeln!(
                    xml,
                    "<DataArray type=\"{ty}\" Name=\"{}\" NumberOfComponents=\"{}\" \
                     format=\"appended\" offset=\"{at}\"/>",
                    a.name, a.components
                );
            }
            let _ = writeln!(xml, "</{tag}>");
        }
        let mut pts = Vec::with_capacity(24 * mesh.n_nodes());
        for n in 0..mesh.n_nodes() {
            let x = mesh.node(n);
            for i in 0..3 {
                pts.extend_from_slice(&(if i < d { x[i] } else { 0.0 }).to_le_bytes());
            }
        }
        let at = push_block(pts, &mut blocks);
        let _ = writeln!(
            xml,
            "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" \
             offset=\"{at}\"/>\n</Points>"
        );
        let conn: Vec<u8> = mesh
            .cells()
            .iter()
            .flat_map(|&v| (v as i64).to_le_bytes())
            .collect();
        let nv = d + 1;
        let offs: Vec<u8> = (1..=mesh.n_cells())
            .flat_map(|c| ((c * nv) as i64).to_le_bytes())
            .collect();
        let vtk_type: u8 = if d == 2 { 5 } else { 10 };
        let types = vec![vtk_type; mesh.n_cells()];
        let a1 = push_block(conn, &mut blocks);
        let a2 = push_block(offs, &mut blocks);
        let a3 = push_block(types, &mut blocks);
        let _ = write!(
            xml,
            "<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"appended\" offset=\"{a1}\"/>\n\
             <DataArray type=\"Int64\" Name=\"offsets\" format=\"appended\" offset=\"{a2}\"/>\n\
             <DataArray type=\"UInt8\" Name=\"types\" format=\"appended\" offset=\"{a3}\"/>\n\
             </Cells>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_"
        );
        let mut out = xml.into_bytes();
        for b in blocks {
            out.extend_from_slice(&(b.len() as u64).to_le_bytes());
            out.extend_from_slice(&b);
        }
        out.extend_from_slice(b"\n</AppendedData>\n</VTKFile>\n");
        out
    }

    /// Writes the file atomically.
    ///
    /// # Errors
    /// [`crate::Error::Io`] if it cannot be written.
    pub fn write(&self, path: &Path) -> Result<()> {
        super::atomic::write(path, &self.to_bytes())
    }
}

/// Pads a DOF-order vector field (d components per node) to 3 components per node.
pub fn pad_vector(dim: usize, v: &[f64]) -> Vec<f64> {
    let n = v.len() / dim;
    let mut out = vec![0.0; 3 * n];
    for k in 0..n {
        out[3 * k..3 * k + dim].copy_from_slice(&v[dim * k..dim * k + dim]);
    }
    out
}
