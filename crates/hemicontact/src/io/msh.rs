//! Gmsh `.msh` writer, format 4.1, ASCII or binary: a [`Mesh`] with its boundary parts as
//! physical groups, as [`crate::mesh::gmsh::parse_msh`] and Gmsh read it back.
//!
//! # Example
//!
//! ```
//! use hemicontact::io::msh::{write_msh, MshEncoding};
//! use hemicontact::mesh::generate::{rectangle, CutPattern, Rectangle};
//! use hemicontact::mesh::gmsh::parse_msh;
//!
//! let mesh = rectangle(&Rectangle {
//!     origin: [0.0, 0.0],
//!     size: [2.0, 1.0],
//!     n: [4, 2],
//!     pattern: CutPattern::Uniform,
//!     progression: [1.0; 2],
//! })
//! .unwrap();
//! let bytes = write_msh(&mesh, MshEncoding::Binary);
//! let read = parse_msh(&bytes, "rectangle.msh").unwrap();
//! assert_eq!(read.mesh.coords(), mesh.coords());
//! assert_eq!(read.mesh.cells(), mesh.cells());
//! ```

use crate::mesh::gmsh::element_types::{LINE, TETRAHEDRON, TRIANGLE};
use crate::mesh::Mesh;

/// Encoding of a written `.msh` file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MshEncoding {
    /// Text (`4.1 0 8`).
    Ascii,
    /// Little-endian binary with 8-byte `size_t` (`4.1 1 8`), as 64-bit Gmsh writes it.
    Binary,
}

/// Output buffer writing fields as text (separated by spaces, one record per line) or as
/// little-endian binary.
struct Out {
    buf: Vec<u8>,
    binary: bool,
}

impl Out {
    fn text(&mut self, s: &str) {
        self.buf.extend_from_slice(s.as_bytes());
    }

    fn size(&mut self, v: u64) {
        if self.binary {
            self.buf.extend_from_slice(&v.to_le_bytes());
        } else {
            self.text(&format!("{v} "));
        }
    }

    fn int(&mut self, v: i32) {
        if self.binary {
            self.buf.extend_from_slice(&v.to_le_bytes());
        } else {
            self.text(&format!("{v} "));
        }
    }

    fn float(&mut self, v: f64) {
        if self.binary {
            self.buf.extend_from_slice(&v.to_le_bytes());
        } else {
            // `{:?}` is the shortest text that reads back to the same f64.
            self.text(&format!("{v:?} "));
        }
    }

    /// Ends a record (a line in ASCII; nothing in binary).
    fn eol(&mut self) {
        if !self.binary {
            if self.buf.last() == Some(&b' ') {
                self.buf.pop();
            }
            self.buf.push(b'\n');
        }
    }

    fn begin(&mut self, name: &str) {
        self.text(&format!("${name}\n"));
    }

    fn end(&mut self, name: &str) {
        if self.binary {
            self.buf.push(b'\n');
        }
        self.text(&format!("$End{name}\n"));
    }
}

/// Writes `mesh` as a Gmsh 4.1 file (ASCII or binary) that
/// [`parse_msh`](crate::mesh::gmsh::parse_msh) and Gmsh read back.
///
/// Layout: one geometric entity of dimension d (tag 1) holding all nodes and cells, in the
/// physical group `domain` (tag P + 1); one entity of dimension d − 1 per boundary part
/// (tag k + 1 for part k) in a physical group named after the part (tag k + 1). Node tags are
/// `1..=n_nodes` in mesh order and element tags number the part facets, then the cells, from
/// 1; so reading the file back gives the same node, cell and facet arrays and parts (parts
/// without facets are not read back). Double quotes and line feeds in part names, which
/// `$PhysicalNames` cannot hold, are written as `'` and spaces.
pub fn write_msh(mesh: &Mesh, encoding: MshEncoding) -> Vec<u8> {
    let binary = encoding == MshEncoding::Binary;
    let mut o = Out {
        buf: Vec::new(),
        binary,
    };
    mesh_format(&mut o);
    physical_names(&mut o, mesh);
    entities(&mut o, mesh);
    nodes(&mut o, mesh);
    elements(&mut o, mesh);
    o.buf
}

/// The `$MeshFormat` section: version 4.1, the encoding and, in binary, the one that
/// tells the byte order.
fn mesh_format(o: &mut Out) {
    let binary = o.binary;
    o.begin("MeshFormat");
    if binary {
        o.text("4.1 1 8\n");
        o.buf.extend_from_slice(&1i32.to_le_bytes());
        o.buf.push(b'\n');
    } else {
        o.text("4.1 0 8\n");
    }
    o.text("$EndMeshFormat\n");
}

/// The `$PhysicalNames` section: one group per boundary part (tag k + 1), then `domain`
/// (tag P + 1).
fn physical_names(o: &mut Out, mesh: &Mesh) {
    let d = mesh.dim();
    let names = mesh.part_names();
    let n_parts = names.len();
    let domain_tag = n_parts as i32 + 1;
    o.begin("PhysicalNames");
    o.text(&format!("{}\n", n_parts + 1));
    for (k, name) in names.iter().enumerate() {
        let clean: String = name
            .chars()
            .map(|c| match c {
                '"' => '\'',
                '\n' => ' ',
                c => c,
            })
            .collect();
        o.text(&format!("{} {} \"{clean}\"\n", d - 1, k + 1));
    }
    o.text(&format!("{d} {domain_tag} \"domain\"\n"));
    o.text("$EndPhysicalNames\n");
}

/// The bounding box `[min x, min y, min z, max x, max y, max z]` (m) of the `nodes` of
/// `mesh` (z = 0 in 2D; all 0 without nodes).
fn bounding_box(mesh: &Mesh, nodes: &mut dyn Iterator<Item = usize>) -> [f64; 6] {
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        0.0,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
        0.0,
    ];
    let mut any = false;
    for n in nodes {
        any = true;
        for (i, &x) in mesh.node(n).iter().enumerate() {
            b[i] = b[i].min(x);
            b[3 + i] = b[3 + i].max(x);
        }
    }
    if any {
        b
    } else {
        [0.0; 6]
    }
}

/// The `$Entities` section: one entity of dimension d − 1 per boundary part (tag k + 1),
/// one of dimension d (tag 1) for the domain.
fn entities(o: &mut Out, mesh: &Mesh) {
    let d = mesh.dim();
    let names = mesh.part_names();
    let n_parts = names.len();
    let domain_tag = n_parts as i32 + 1;
    let bbox = |nodes: &mut dyn Iterator<Item = usize>| bounding_box(mesh, nodes);
    o.begin("Entities");
    let mut counts = [0u64; 4];
    counts[d - 1] = n_parts as u64;
    counts[d] = 1;
    for c in counts {
        o.size(c);
    }
    o.eol();
    for (k, _) in names.iter().enumerate() {
        o.int(k as i32 + 1);
        let nodes = mesh.part_nodes(k);
        for x in bbox(&mut nodes.iter().map(|&n| n as usize)) {
            o.float(x);
        }
        o.size(1);
        o.int(k as i32 + 1);
        o.size(0);
        o.eol();
    }
    o.int(1);
    for x in bbox(&mut (0..mesh.n_nodes())) {
        o.float(x);
    }
    o.size(1);
    o.int(domain_tag);
    o.size(0);
    o.eol();
    o.end("Entities");
}

/// The `$Nodes` section: every node in one block of the domain entity, tags `1..=n_nodes`.
fn nodes(o: &mut Out, mesh: &Mesh) {
    let d = mesh.dim();
    let n = mesh.n_nodes() as u64;
    o.begin("Nodes");
    for v in [1, n, 1, n] {
        o.size(v);
    }
    o.eol();
    o.int(d as i32);
    o.int(1);
    o.int(0);
    o.size(n);
    o.eol();
    for t in 1..=n {
        o.size(t);
        o.eol();
    }
    for i in 0..mesh.n_nodes() {
        let x = mesh.node(i);
        for k in 0..3 {
            o.float(x.get(k).copied().unwrap_or(0.0));
        }
        o.eol();
    }
    o.end("Nodes");
}

/// The `$Elements` section: the facets of each boundary part with facets (one block per
/// part), then the cells, tagged from 1 in that order.
fn elements(o: &mut Out, mesh: &Mesh) {
    let d = mesh.dim();
    let n_parts = mesh.part_names().len();
    let (facet_type, cell_type) = if d == 2 {
        (LINE, TRIANGLE)
    } else {
        (TRIANGLE, TETRAHEDRON)
    };
    let part_facets: Vec<Vec<usize>> = (0..n_parts)
        .map(|k| mesh.part_facets(k).collect())
        .collect();
    let n_blocks = 1 + part_facets.iter().filter(|f| !f.is_empty()).count() as u64;
    let n_elements = (mesh.n_facets() + mesh.n_cells()) as u64;
    o.begin("Elements");
    for v in [n_blocks, n_elements, 1, n_elements] {
        o.size(v);
    }
    o.eol();
    let mut tag = 1u64;
    for (k, fs) in part_facets
        .iter()
        .enumerate()
        .filter(|(_, f)| !f.is_empty())
    {
        o.int(d as i32 - 1);
        o.int(k as i32 + 1);
        o.int(facet_type);
        o.size(fs.len() as u64);
        o.eol();
        for &f in fs {
            o.size(tag);
            tag += 1;
            for &v in mesh.facet(f) {
                o.size(u64::from(v) + 1);
            }
            o.eol();
        }
    }
    o.int(d as i32);
    o.int(1);
    o.int(cell_type);
    o.size(mesh.n_cells() as u64);
    o.eol();
    for c in 0..mesh.n_cells() {
        o.size(tag);
        tag += 1;
        for &v in mesh.cell(c) {
            o.size(u64::from(v) + 1);
        }
        o.eol();
    }
    o.end("Elements");
}
