//! VTK XML UnstructuredGrid writer (`.vtu`): binary appended data, zlib-compressed in
//! blocks ([`super::zlib_blocks`], 64-bit block headers), every array in a block of its own
//! at an offset of its own, the blocks in the reverse order of their arrays (so that meshio
//! reads every array as VTK does: [`VtuWriter::to_bytes`]), readable by ParaView, VTK and
//! meshio; the same input always gives the same bytes.
//!
//! Point coordinates are written with 3 components (z = 0 in 2D); vectors with 3 components;
//! symmetric tensors as 9-component full matrices (row-major). Data about the whole file
//! (title, time or load factor, program version, units) go to its `FieldData`: numbers as
//! `Float64` arrays, text as `UInt8` arrays of its UTF-8 bytes followed by one NUL byte
//! (meshio cannot read VTK's `String` arrays). [`solution_vtu`] fills a file with the fields
//! of a solution (`solution.vtu`).

use super::zlib_blocks;
use crate::error::{Error, Result};
use crate::fields::cell_fields;
use crate::mesh::Mesh;
use crate::problem::Problem;
use crate::solver::Solution;
use std::fmt::Write as _;
use std::path::Path;

mod parallel;

enum Data {
    F64(Vec<f64>),
    I32(Vec<i32>),
    I64(Vec<i64>),
    U8(Vec<u8>),
}

impl Data {
    /// The VTK type name and the little-endian bytes.
    fn encode(&self) -> (&'static str, Vec<u8>) {
        let bytes = match self {
            Data::F64(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            Data::I32(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            Data::I64(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            Data::U8(v) => v.clone(),
        };
        (self.type_name(), bytes)
    }

    /// The VTK type name.
    fn type_name(&self) -> &'static str {
        match self {
            Data::F64(_) => "Float64",
            Data::I32(_) => "Int32",
            Data::I64(_) => "Int64",
            Data::U8(_) => "UInt8",
        }
    }

    /// The tuples `ids` of `components` values each, in that order.
    fn select(&self, components: usize, ids: &[u32]) -> Data {
        fn pick<T: Copy>(v: &[T], c: usize, ids: &[u32]) -> Vec<T> {
            ids.iter()
                .flat_map(|&i| &v[c * i as usize..c * (i as usize + 1)])
                .copied()
                .collect()
        }
        match self {
            Data::F64(v) => Data::F64(pick(v, components, ids)),
            Data::I32(v) => Data::I32(pick(v, components, ids)),
            Data::I64(v) => Data::I64(pick(v, components, ids)),
            Data::U8(v) => Data::U8(pick(v, components, ids)),
        }
    }

    fn len(&self) -> usize {
        match self {
            Data::F64(v) => v.len(),
            Data::I32(v) => v.len(),
            Data::I64(v) => v.len(),
            Data::U8(v) => v.len(),
        }
    }
}

struct Array {
    name: String,
    components: usize,
    data: Data,
}

/// A `.vtu` file under construction: a mesh plus named point, cell and field arrays.
pub struct VtuWriter<'a> {
    mesh: &'a Mesh,
    field: Vec<Array>,
    point: Vec<Array>,
    cell: Vec<Array>,
}

impl<'a> VtuWriter<'a> {
    /// Starts a file for `mesh`.
    pub fn new(mesh: &'a Mesh) -> Self {
        VtuWriter {
            mesh,
            field: Vec::new(),
            point: Vec::new(),
            cell: Vec::new(),
        }
    }

    /// Adds a `Float64` array of `FieldData` (data about the whole file, e.g. `TimeValue`).
    pub fn field_f64(&mut self, name: &str, values: Vec<f64>) -> &mut Self {
        self.field.push(Array {
            name: name.into(),
            components: 1,
            data: Data::F64(values),
        });
        self
    }

    /// Adds a text to `FieldData`: a `UInt8` array of the UTF-8 bytes of `text` followed by
    /// one NUL byte.
    pub fn field_text(&mut self, name: &str, text: &str) -> &mut Self {
        let mut bytes = text.as_bytes().to_vec();
        bytes.push(0);
        self.field.push(Array {
            name: name.into(),
            components: 1,
            data: Data::U8(bytes),
        });
        self
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

    /// Encodes the file: the XML header, then the appended data, every array compressed
    /// by [`zlib_blocks::compress`] into a block of its own.
    ///
    /// The blocks are laid out in the reverse order of their `<DataArray>` elements (the
    /// last array's block at offset 0, the first array's block last), every offset its own.
    /// VTK reads each array at its offset, whatever the order. meshio (5.3.5) converts raw
    /// appended data to base64 block by block, from the first byte on, finds the element of
    /// each block by the offset attribute (the first element in document order with that
    /// value) and renumbers that attribute to the block's base64 position as it goes; in
    /// document order, a block's raw offset could equal the new number of an element
    /// already renumbered, and meshio then gave the block to that element, swapping two
    /// arrays. In reverse order every element already renumbered comes after the one whose
    /// offset is looked up, so the lookup always finds the right one.
    pub fn to_bytes(&self) -> Vec<u8> {
        self.encode(None)
    }

    /// The file of the whole mesh (`piece` = `None`), or of the cells `piece` and the nodes
    /// they use, with their `node_id` and `cell_id` ([`VtuWriter::parallel_files`]).
    fn encode(&self, piece: Option<&[u32]>) -> Vec<u8> {
        let mesh = self.mesh;
        // The piece's cells and nodes (increasing), and each node's number in the piece.
        let all_cells: Vec<u32>;
        let cells: &[u32] = match piece {
            Some(c) => c,
            None => {
                all_cells = (0..mesh.n_cells() as u32).collect();
                &all_cells
            }
        };
        let (nodes, local) = piece_nodes(mesh, piece);
        let mut parts = vec![Part::Xml(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" \
             byte_order=\"LittleEndian\" header_type=\"UInt64\" \
             compressor=\"vtkZLibDataCompressor\">\n<UnstructuredGrid>\n"
                .to_string(),
        )];
        if !self.field.is_empty() {
            parts.push(Part::Xml("<FieldData>\n".into()));
            for a in &self.field {
                let (ty, bytes) = a.data.encode();
                let tag = format!(
                    "<DataArray type=\"{ty}\" Name=\"{}\" NumberOfTuples=\"{}\" \
                     format=\"appended\"",
                    a.name,
                    a.data.len()
                );
                parts.push(array(tag, &bytes));
            }
            parts.push(Part::Xml("</FieldData>\n".into()));
        }
        parts.push(Part::Xml(format!(
            "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
            nodes.len(),
            cells.len()
        )));
        self.data_parts(&mut parts, piece, &nodes, cells);
        geometry_parts(&mut parts, mesh, &nodes, cells, &local);
        parts.push(Part::Xml(
            "</Cells>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_".into(),
        ));
        assemble(&parts)
    }

    /// The `<PointData>` and `<CellData>` sections of the nodes and cells of the file,
    /// restricted to them (with their `node_id` and `cell_id`) for a `piece`.
    fn data_parts(
        &self,
        parts: &mut Vec<Part>,
        piece: Option<&[u32]>,
        nodes: &[u32],
        cells: &[u32],
    ) {
        for (section, arrays, ids, id) in [
            ("PointData", &self.point, nodes, "node_id"),
            ("CellData", &self.cell, cells, "cell_id"),
        ] {
            parts.push(Part::Xml(format!("<{section}>\n")));
            let restricted: Vec<Array> = match piece {
                Some(_) => arrays
                    .iter()
                    .map(|a| Array {
                        name: a.name.clone(),
                        components: a.components,
                        data: a.data.select(a.components, ids),
                    })
                    .chain(std::iter::once(Array {
                        name: id.into(),
                        components: 1,
                        data: Data::I64(ids.iter().map(|&x| i64::from(x)).collect()),
                    }))
                    .collect(),
                None => Vec::new(),
            };
            let arrays: Vec<&Array> = match piece {
                Some(_) => restricted.iter().collect(),
                None => arrays.iter().collect(),
            };
            for a in arrays {
                let (ty, bytes) = a.data.encode();
                let tag = format!(
                    "<DataArray type=\"{ty}\" Name=\"{}\" NumberOfComponents=\"{}\" \
                     format=\"appended\"",
                    a.name, a.components
                );
                parts.push(array(tag, &bytes));
            }
            parts.push(Part::Xml(format!("</{section}>\n")));
        }
    }

    /// Writes the file atomically.
    ///
    /// # Errors
    /// [`crate::Error::Io`] if it cannot be written.
    pub fn write(&self, path: &Path) -> Result<()> {
        crate::atomic_file::write(path, &self.to_bytes())
    }
}

/// A piece of a VTU file in document order: XML text, or an appended array (its
/// `<DataArray` tag up to its offset, and its encoded block).
enum Part {
    Xml(String),
    Array { tag: String, block: Vec<u8> },
}

/// The appended array of the `<DataArray` tag `tag` (up to its offset) with the data
/// `bytes`, compressed by [`zlib_blocks::compress`].
fn array(tag: String, bytes: &[u8]) -> Part {
    Part::Array {
        tag,
        block: zlib_blocks::compress(bytes),
    }
}

/// The nodes that the cells `piece` use (increasing; all the nodes for `None`) and each
/// node's number among them (`u32::MAX` for the others).
fn piece_nodes(mesh: &Mesh, piece: Option<&[u32]>) -> (Vec<u32>, Vec<u32>) {
    let mut local = vec![u32::MAX; mesh.n_nodes()];
    let nodes: Vec<u32> = match piece {
        Some(c) => {
            let mut used = vec![false; mesh.n_nodes()];
            for &cell in c {
                for &v in mesh.cell(cell as usize) {
                    used[v as usize] = true;
                }
            }
            (0..mesh.n_nodes() as u32)
                .filter(|&v| used[v as usize])
                .collect()
        }
        None => (0..mesh.n_nodes() as u32).collect(),
    };
    for (k, &v) in nodes.iter().enumerate() {
        local[v as usize] = k as u32;
    }
    (nodes, local)
}

/// The `<Points>` and `<Cells>` sections of the `nodes` and `cells` of the file, `local`
/// numbering the nodes among them.
fn geometry_parts(parts: &mut Vec<Part>, mesh: &Mesh, nodes: &[u32], cells: &[u32], local: &[u32]) {
    let d = mesh.dim();
    let nv = d + 1;
    let mut pts = Vec::with_capacity(24 * nodes.len());
    for &n in nodes {
        let x = mesh.node(n as usize);
        for i in 0..3 {
            pts.extend_from_slice(&(if i < d { x[i] } else { 0.0 }).to_le_bytes());
        }
    }
    parts.push(Part::Xml("<Points>\n".into()));
    parts.push(array(
        "<DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" \
         format=\"appended\""
            .into(),
        &pts,
    ));
    parts.push(Part::Xml("</Points>\n<Cells>\n".into()));
    let conn: Vec<u8> = cells
        .iter()
        .flat_map(|&c| mesh.cell(c as usize))
        .flat_map(|&v| i64::from(local[v as usize]).to_le_bytes())
        .collect();
    let offs: Vec<u8> = (1..=cells.len())
        .flat_map(|c| ((c * nv) as i64).to_le_bytes())
        .collect();
    let vtk_type: u8 = if d == 2 { 5 } else { 10 };
    let types = vec![vtk_type; cells.len()];
    for (ty, name, bytes) in [
        ("Int64", "connectivity", &conn),
        ("Int64", "offsets", &offs),
        ("UInt8", "types", &types),
    ] {
        let tag = format!("<DataArray type=\"{ty}\" Name=\"{name}\" format=\"appended\"");
        parts.push(array(tag, bytes));
    }
}

/// The file: the XML of the `parts` with each array's offset, then the appended data, the
/// blocks in reverse document order, one after the other.
fn assemble(parts: &[Part]) -> Vec<u8> {
    // Offsets: the blocks in reverse document order, one after the other.
    let mut offsets = vec![0usize; parts.len()];
    let mut at = 0;
    for (k, part) in parts.iter().enumerate().rev() {
        if let Part::Array { block, .. } = part {
            offsets[k] = at;
            at += block.len();
        }
    }
    let mut xml = String::new();
    for (part, offset) in parts.iter().zip(&offsets) {
        match part {
            Part::Xml(text) => xml.push_str(text),
            Part::Array { tag, .. } => {
                let _ = writeln!(xml, "{tag} offset=\"{offset}\"/>");
            }
        }
    }
    let mut out = xml.into_bytes();
    out.reserve(at + 32);
    for part in parts.iter().rev() {
        if let Part::Array { block, .. } = part {
            out.extend_from_slice(block);
        }
    }
    out.extend_from_slice(b"\n</AppendedData>\n</VTKFile>\n");
    out
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

/// The point and cell fields of `solution.vtu` with their units (2D forces are per unit
/// thickness), in the order written; the text of the `units` entry of its `FieldData`.
pub fn field_units(dim: usize) -> Vec<(&'static str, &'static str)> {
    let force = if dim == 2 { "N/m" } else { "N" };
    vec![
        ("displacement", "m"),
        ("reaction", force),
        ("contact_normal_state", "code"),
        ("contact_friction_state", "code"),
        ("contact_pressure", "Pa"),
        ("friction_traction", "Pa"),
        ("slip", "m"),
        ("interface_force", force),
        ("contact_normal", "1"),
        ("strain", "1"),
        ("stress", "Pa"),
        ("von_mises", "Pa"),
        ("trace_strain", "1"),
        ("locking_active", "code"),
        ("locking_q", "1 (strain; strain^2 for the Prager set)"),
        ("locking_multiplier", "Pa"),
    ]
}

/// The unit of the `material` cell field, written for a body of several materials.
pub const MATERIAL_UNIT: &str = "index (0, 1, …) of the material, in the order of the \
     scenario's [[material]] tables and of summary.json's materials";

/// The integer codes of the state fields of `solution.vtu`; the text of the `codes` entry
/// of its `FieldData`, one line per field.
pub const STATE_CODES: &str = "contact_normal_state: -1 not a contact node, 0 separated, \
     1 contact (positive pressure)\n\
     contact_friction_state: -1 not a contact node, 0 no friction force (frictionless, or \
     Coulomb bound at a separated point), 1 stick, 2 slip\n\
     locking_active: 0 free, 1 locking acts";

/// The `.vtu` content of a solution titled `title` at the load factor `load_factor` (1 for
/// a single solve): displacement, reactions and contact data at points; strain, stress,
/// von Mises stress, tr ε and locking activity per cell; and in `FieldData` the `TITLE`,
/// the load factor as `TimeValue` (ParaView's time), `hemicontact_version`, the `units` of
/// every field ([`field_units`], one `name: unit` line each) and the state `codes`
/// ([`STATE_CODES`]).
///
/// `stress` is the full 3×3 tensor ([`crate::material::Material::stress_3x3`]): in 2D plane
/// strain with `σ_zz = ∂W/∂ε_zz` (Hooke: `λ tr ε`) plus the zz part of the locking stress,
/// in plane stress with `σ_zz = 0`; `von_mises` is `√(3/2 s:s)` of its 3D deviator s
/// ([`crate::tensor::von_mises`]). `strain` is the strain of the model: in 2D its
/// out-of-plane components are written as 0 (exact in plane strain; in plane stress the
/// thickness strain ε_zz is not computed).
///
/// Contact point data (for nodes that are not contact nodes: states −1, zeros elsewhere):
/// `contact_normal_state` (0 separated, 1 contact), `contact_friction_state` (0 none,
/// 1 stick, 2 slip), `contact_pressure` p = −σ_ν (Pa; for Signorini the multiplier of
/// `u_ν ≤ g`), `slip` ‖u_τ‖, and, both as the action of the foundation on the body in
/// global coordinates, the `friction_traction` σ_τ = R_τ/w (Pa, opposing the slip) and the
/// nodal `interface_force` R (N, N/m in 2D; its normal part is about −w p ν), and the unit
/// `contact_normal` ν of the point (outward from the body; against a rigid obstacle the
/// opposite of the obstacle's normal at the node's closest point). Where a node
/// is several contact points (on two contact boundaries, or at a corner of one), the last
/// point's values are shown and the forces are summed. Between two bodies the master
/// side's nodes carry the reaction of the pairs, `−N_j R` for each pair whose master facet
/// holds the node (action = reaction: the `interface_force` of the two sides sums to zero).
/// Cell data: `locking_active` is 1 where the locking constraint acts (nearly locking:
/// `Q(ε) > 0`; ideal locking: multiplier > 0), `locking_q` is Q(ε), `locking_multiplier`
/// the magnitude λ_T of the locking stress `λ_T ∂Q` (ideal locking: the multiplier; nearly
/// locking: its penalty approximation `C_κ Q_+`). The stress includes the locking stress.
///
/// # Errors
/// [`Error::Invalid`] if `load_factor` is not finite; the errors of
/// [`Problem::contact_nodes`] (none for a problem that was solved).
pub fn solution_vtu<'a>(
    problem: &'a Problem,
    solution: &Solution,
    title: &str,
    load_factor: f64,
) -> Result<VtuWriter<'a>> {
    if !load_factor.is_finite() {
        return Err(Error::Invalid {
            field: "solution.vtu: load factor".into(),
            value: format!("{load_factor:?}"),
            allowed: "a finite number (1 for a single solve)".into(),
        });
    }
    let mesh = &problem.mesh;
    let d = mesh.dim();
    let cells = cell_fields(problem, solution);
    let n = mesh.n_nodes();
    let mut normal_state = vec![-1i32; n];
    let mut friction_state = vec![-1i32; n];
    let mut pressure = vec![0.0; n];
    let mut slip = vec![0.0; n];
    let mut force = vec![0.0; 3 * n];
    let mut traction = vec![0.0; 3 * n];
    let mut normal = vec![0.0; 3 * n];
    let points = problem.contact_nodes()?;
    for (c, nu) in solution.contact.iter().zip(&points.normal) {
        let v = c.node as usize;
        normal[3 * v..3 * v + 3].copy_from_slice(nu);
        normal_state[v] = c.normal_state.code();
        friction_state[v] = c.friction_state.code();
        pressure[v] = c.pressure;
        slip[v] = c.slip;
        for k in 0..3 {
            force[3 * v + k] += c.force[k];
            traction[3 * v + k] = c.friction_traction[k];
        }
    }
    // Between two bodies, the reaction of each pair on the master facet's nodes: −N_j R.
    for (i, c) in solution.contact.iter().enumerate() {
        let (len, nodes, coef) = points.stencil(d, i);
        for a in 1..len {
            let m = nodes[a] as usize;
            for k in 0..3 {
                force[3 * m + k] += coef[a] * c.force[k];
            }
        }
    }
    let mut units: String = field_units(d)
        .iter()
        .map(|(name, unit)| format!("{name}: {unit}\n"))
        .collect();
    let with_material = !problem.region_material.is_empty();
    if with_material {
        units.push_str(&format!("material: {MATERIAL_UNIT}\n"));
    }
    let mut w = VtuWriter::new(mesh);
    w.field_text("TITLE", title)
        .field_f64("TimeValue", vec![load_factor])
        .field_text("hemicontact_version", env!("CARGO_PKG_VERSION"))
        .field_text("units", units.trim_end())
        .field_text("codes", STATE_CODES)
        .point_f64("displacement", 3, pad_vector(d, &solution.u))
        .point_f64("reaction", 3, pad_vector(d, &solution.reactions))
        .point_i32("contact_normal_state", normal_state)
        .point_i32("contact_friction_state", friction_state)
        .point_f64("contact_pressure", 1, pressure)
        .point_f64("friction_traction", 3, traction)
        .point_f64("slip", 1, slip)
        .point_f64("interface_force", 3, force)
        .point_f64("contact_normal", 3, normal)
        .cell_f64("strain", 9, cells.strain)
        .cell_f64("stress", 9, cells.stress)
        .cell_f64("von_mises", 1, cells.von_mises)
        .cell_f64("trace_strain", 1, cells.trace_strain)
        .cell_i32("locking_active", cells.locking_active)
        .cell_f64("locking_q", 1, cells.locking_q)
        .cell_f64("locking_multiplier", 1, cells.locking_multiplier);
    if with_material {
        w.cell_i32("material", cells.material);
    }
    Ok(w)
}

/// The files of a solution's fields ([`solution_vtu`]): `solution.vtu`, or, for a solution
/// of several MPI processes ([`Solution::partition`]), ParaView's parallel format with one
/// piece per process that owns cells, `solution_<rank>.vtu` holding the cells that rank
/// owns ([`crate::parallel::Partition::owned_cells`]), and the index `solution.pvtu` last
/// ([`VtuWriter::parallel_files`]). Names are relative to the result folder.
///
/// # Errors
/// As [`solution_vtu`].
pub fn solution_files(
    problem: &Problem,
    solution: &Solution,
    title: &str,
    load_factor: f64,
) -> Result<Vec<(String, Vec<u8>)>> {
    let w = solution_vtu(problem, solution, title, load_factor)?;
    Ok(match &solution.partition {
        Some(p) if p.size() > 1 => w.parallel_files(&p.owned_cells(&problem.mesh), "solution"),
        _ => vec![("solution.vtu".to_string(), w.to_bytes())],
    })
}
