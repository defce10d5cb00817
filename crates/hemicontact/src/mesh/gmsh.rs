//! Gmsh `.msh` files, format 4.1: a reader (ASCII and binary) and a writer.
//!
//! # What is read
//!
//! | section | use |
//! |---------|-----|
//! | `$MeshFormat` | must come first and say `4.1`; file type 0 (ASCII) or 1 (binary: little-endian, 8-byte `size_t`, checked by the endianness int `1`) |
//! | `$PhysicalNames` | names of the physical groups (optional) |
//! | `$Entities` | the physical groups of each geometric entity, which the element blocks refer to (optional: without it no element belongs to a physical group) |
//! | `$Nodes` | node tags (arbitrary, sparse) and coordinates; must precede `$Elements` |
//! | `$Elements` | element blocks, one per entity and element type |
//! | `$PartitionedEntities` | an error: partitioned meshes are not supported |
//! | anything else (`$Periodic`, `$NodeData`, …) | skipped |
//!
//! The dimension d of the mesh is the highest dimension of its elements (points ignored).
//! Cells are the triangles (Gmsh type 2, d = 2) or tetrahedra (type 4, d = 3); boundary
//! facets are the lines (type 1, d = 2) or triangles (type 2, d = 3). Any other element type
//! of dimension d or d − 1 (quadrangles, second-order elements, hexahedra, prisms, …) is an
//! error: only P1 simplices are supported. Elements of lower dimension are ignored. A 2D
//! mesh must lie in the plane z = 0 (Gmsh always writes three coordinates).
//!
//! # How a file becomes a [`Mesh`]
//!
//! - **Nodes** not used by any cell are dropped (Gmsh writes the nodes of geometry points
//!   and other lower-dimensional entities); the others keep their order in the file, so a
//!   file whose node tags are `1..=N` in order and all used gives mesh node `i` = tag `i + 1`.
//!   [`GmshMesh::node_tags`] maps back.
//! - **Cells** keep their order in the file. Gmsh orients the cells of a geometric entity
//!   (a surface in 2D, a volume in 3D) alike, but the orientation depends on the geometry:
//!   an entity whose cells are *all* negatively oriented (clockwise triangles, left-handed
//!   tetrahedra) is reoriented by swapping the last two vertices of each cell, with a note.
//!   An entity with cells of both orientations is tangled (a node moved past its
//!   neighbours): an error naming the elements of the minority orientation. Degenerate cells
//!   (zero measure up to round-off) are an error naming the element, and so are cells that
//!   overlap although each is oriented like its neighbours (the cell measures do not sum to
//!   the measure enclosed by the boundary; see [`crate::mesh`]).
//! - **Boundary parts** are the physical groups of dimension d − 1, named by
//!   `$PhysicalNames` (a group without a name is named by its tag, e.g. `"3"`; groups with
//!   equal names form one part), in the order of their physical tags. Facets keep their order
//!   in the file. A boundary facet in two physical groups with different names is an error:
//!   a facet belongs to one boundary part. Facets of a physical group that lie inside the
//!   domain (interfaces) are ignored, with a note.
//! - **Untagged boundary facets**: every boundary facet of a [`Mesh`] carries a part, so the
//!   boundary facets that belong to no physical group form the part [`UNTAGGED`]. A scenario
//!   that does not name it leaves it traction-free.
//! - **Cell regions**: the physical groups of dimension d are read into
//!   [`GmshMesh::cell_region`] and [`GmshMesh::region_names`] (cells in no group are in
//!   the region [`UNTAGGED`]). They are informational: one material applies to the whole
//!   mesh.
//!
//! Facts worth telling the user (reoriented entities, untagged facets, dropped nodes, ignored
//! interior facets, several cell regions) are returned in [`GmshMesh::notes`].
//!
//! # Errors
//!
//! Every problem is an [`Error::MeshFile`] naming the file and, where it applies, the line
//! (ASCII) or byte offset (binary), and saying what was expected: not a 4.1 file, truncated
//! file, malformed number, a count that does not match the data or that the rest of the file
//! cannot hold (checked before anything is allocated, so a small file claiming 10¹⁸ nodes
//! fails at once), duplicate or undefined node tags, non-finite coordinates, unsupported
//! element types, missing sections, degenerate or duplicate cells, cells of both orientations
//! in one entity, overlapping cells, non-manifold facets.
//!
//! # Example
//!
//! ```
//! use hemicontact::mesh::generate::{rectangle, CutPattern, Rectangle};
//! use hemicontact::mesh::gmsh::{parse_msh, write_msh, MshEncoding};
//!
//! let mesh = rectangle(&Rectangle {
//!     origin: [0.0, 0.0],
//!     size: [2.0, 1.0],
//!     n: [4, 2],
//!     pattern: CutPattern::Uniform,
//! })
//! .unwrap();
//! let bytes = write_msh(&mesh, MshEncoding::Ascii);
//! let read = parse_msh(&bytes, "rectangle.msh").unwrap();
//! assert_eq!(read.mesh.coords(), mesh.coords());
//! assert_eq!(read.mesh.cells(), mesh.cells());
//! assert_eq!(read.mesh.part_names(), ["bottom", "right", "top", "left"]);
//! ```

mod element_types;

use crate::error::{Error, FileLocation, Result};
use crate::fem::simplex;
use crate::mesh::{Mesh, DEGENERATE_TOL};
use element_types::element_type;
use std::collections::HashMap;
use std::path::Path;

/// Name of the boundary part holding the boundary facets that belong to no physical group
/// (and of the cell region of cells in no physical group).
pub const UNTAGGED: &str = "untagged";

/// A mesh read from a Gmsh file, with the Gmsh numbering and what the reader noticed.
#[derive(Clone, Debug)]
pub struct GmshMesh {
    /// The validated mesh.
    pub mesh: Mesh,
    /// Gmsh tag of each mesh node (length `n_nodes`).
    pub node_tags: Vec<u64>,
    /// Gmsh tag of each cell's element (length `n_cells`).
    pub element_tags: Vec<u64>,
    /// Region of each cell (length `n_cells`): an index into [`GmshMesh::region_names`].
    pub cell_region: Vec<u16>,
    /// Names of the cell regions: the physical groups of dimension d, in the order of their
    /// tags, then [`UNTAGGED`] if some cell is in no group.
    pub region_names: Vec<String>,
    /// Facts worth telling the user (reoriented entities, untagged boundary facets, dropped
    /// nodes, ignored interior facets, several cell regions), one sentence each.
    pub notes: Vec<String>,
}

/// Reads a Gmsh 4.1 `.msh` file (ASCII or binary); see the module documentation.
///
/// # Errors
/// [`Error::Io`] if the file cannot be read or is not a regular file (a folder, a device
/// such as `/dev/zero`, a pipe: reading it could take without end); [`Error::MeshFile`] if
/// its content is not a supported mesh (see [`parse_msh`]).
pub fn read_msh(path: &Path) -> Result<GmshMesh> {
    let meta = std::fs::metadata(path).map_err(|e| Error::io(path, e))?;
    if !meta.is_file() {
        return Err(Error::io(
            path,
            std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a regular file"),
        ));
    }
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    parse_msh(&bytes, &path.display().to_string())
}

/// Parses the content of a Gmsh 4.1 `.msh` file (ASCII or binary); `source` names it in
/// error messages. See the module documentation for what is read and how.
///
/// # Errors
/// [`Error::MeshFile`] naming `source` and the line (ASCII) or byte offset (binary) of the
/// problem: the file is not in format 4.1, is truncated or malformed, its counts do not
/// match its data, a node tag is duplicated or undefined, a coordinate is not finite, an
/// element type other than P1 simplices is used in the cell or facet dimension, a section is
/// missing, a cell is degenerate or duplicated, an entity has cells of both orientations,
/// cells overlap, or a facet is in two boundary parts.
pub fn parse_msh(bytes: &[u8], source: &str) -> Result<GmshMesh> {
    let sections = Reader::new(bytes, source).read()?;
    assemble(sections, source)
}

// ---------------------------------------------------------------------------------------
// Reading the sections.
// ---------------------------------------------------------------------------------------

/// Gmsh element types used as cells or facets.
const LINE: i32 = 1;
const TRIANGLE: i32 = 2;
const TETRAHEDRON: i32 = 4;
const POINT: i32 = 15;

/// Longest section name accepted (Gmsh's are at most 20 characters); bounds the search for
/// the end of a skipped section.
const MAX_SECTION_NAME: usize = 64;

/// Most nodes a [`Mesh`] can index.
const MAX_NODES: u64 = u32::MAX as u64 / 2;

/// `$Nodes`: tags and coordinates in file order, and the index of each tag.
struct Nodes {
    tags: Vec<u64>,
    coords: Vec<[f64; 3]>,
    index: HashMap<u64, u32>,
}

/// An element block of a type the reader uses (line, triangle, tetrahedron).
struct Block {
    /// Dimension of the entity (and of the elements).
    dim: u8,
    /// Entity tag.
    entity: i32,
    /// Where the block header is.
    at: FileLocation,
    /// Element tags.
    tags: Vec<u64>,
    /// Node indices (into `Nodes`), `tags.len() × nodes per element`.
    conn: Vec<u32>,
}

/// A non-empty element block of a type the reader does not use.
struct Skipped {
    dim: u8,
    entity: i32,
    etype: i32,
    name: &'static str,
    at: FileLocation,
}

/// Everything read from the file, before it is turned into a mesh.
#[derive(Default)]
struct Sections {
    /// `(dimension, tag)` → name.
    names: HashMap<(i32, i32), String>,
    /// `(dimension, entity tag)` → physical tags; `None` without `$Entities`.
    entities: Option<HashMap<(i32, i32), Vec<i32>>>,
    nodes: Option<Nodes>,
    blocks: Vec<Block>,
    skipped: Vec<Skipped>,
    seen: Vec<String>,
}

/// A cursor over the file's bytes that reads tokens (ASCII) or raw little-endian numbers
/// (binary sections), tracking the line number and the location of the last item read.
struct Reader<'a> {
    bytes: &'a [u8],
    pos: usize,
    /// Line of `pos` (1-based; meaningful in ASCII files only).
    line: u64,
    /// The file is binary: locations are byte offsets.
    binary_file: bool,
    /// Numbers are currently read in binary (the body of a binary section).
    binary: bool,
    /// Location of the item read last (for error messages).
    at: FileLocation,
    file: &'a str,
}

/// A token for an error message: lossy UTF-8, at most 40 characters.
fn show(token: &[u8]) -> String {
    let s = String::from_utf8_lossy(token);
    let mut out: String = s.chars().take(40).collect();
    if s.chars().count() > 40 {
        out.push('…');
    }
    out
}

impl<'a> Reader<'a> {
    fn new(bytes: &'a [u8], file: &'a str) -> Self {
        Reader {
            bytes,
            pos: 0,
            line: 1,
            binary_file: false,
            binary: false,
            at: FileLocation::Line(1),
            file,
        }
    }

    fn err(&self, message: impl Into<String>) -> Error {
        Error::MeshFile {
            file: self.file.to_string(),
            location: self.at,
            message: message.into(),
        }
    }

    fn remaining(&self) -> usize {
        self.bytes.len().saturating_sub(self.pos)
    }

    /// Records the current position as the location of the next item.
    fn mark(&mut self) {
        self.at = if self.binary_file {
            FileLocation::Byte(self.pos as u64)
        } else {
            FileLocation::Line(self.line)
        };
    }

    fn skip_ws(&mut self) {
        while let Some(&b) = self.bytes.get(self.pos) {
            if !b.is_ascii_whitespace() {
                break;
            }
            if b == b'\n' {
                self.line += 1;
            }
            self.pos += 1;
        }
    }

    /// The next whitespace-delimited token.
    fn token(&mut self, what: &str) -> Result<&'a [u8]> {
        self.skip_ws();
        self.mark();
        let start = self.pos;
        while self
            .bytes
            .get(self.pos)
            .is_some_and(|b| !b.is_ascii_whitespace())
        {
            self.pos += 1;
        }
        match self.bytes.get(start..self.pos) {
            Some(t) if !t.is_empty() => Ok(t),
            _ => Err(self.err(format!(
                "unexpected end of file while reading {what} (truncated file?)"
            ))),
        }
    }

    fn text_u64(&mut self, what: &str) -> Result<u64> {
        let t = self.token(what)?;
        std::str::from_utf8(t)
            .ok()
            .filter(|s| !s.starts_with('+'))
            .and_then(|s| s.parse::<u64>().ok())
            .ok_or_else(|| {
                self.err(format!(
                    "expected {what} (a non-negative integer), found `{}`",
                    show(t)
                ))
            })
    }

    fn text_i32(&mut self, what: &str) -> Result<i32> {
        let t = self.token(what)?;
        std::str::from_utf8(t)
            .ok()
            .and_then(|s| s.parse::<i32>().ok())
            .ok_or_else(|| {
                self.err(format!(
                    "expected {what} (a 32-bit integer), found `{}`",
                    show(t)
                ))
            })
    }

    fn text_f64(&mut self, what: &str) -> Result<f64> {
        let t = self.token(what)?;
        std::str::from_utf8(t)
            .ok()
            .and_then(|s| s.parse::<f64>().ok())
            .ok_or_else(|| self.err(format!("expected {what} (a number), found `{}`", show(t))))
    }

    /// `N` raw bytes of a binary section.
    fn raw<const N: usize>(&mut self, what: &str) -> Result<[u8; N]> {
        self.mark();
        let mut out = [0u8; N];
        match self.bytes.get(self.pos..self.pos.saturating_add(N)) {
            Some(s) if s.len() == N => {
                out.copy_from_slice(s);
                self.pos += N;
                Ok(out)
            }
            _ => Err(self.err(format!(
                "unexpected end of file while reading {what} (truncated file?)"
            ))),
        }
    }

    /// A `size_t` field.
    fn size(&mut self, what: &str) -> Result<u64> {
        if self.binary {
            Ok(u64::from_le_bytes(self.raw::<8>(what)?))
        } else {
            self.text_u64(what)
        }
    }

    /// An `int` field.
    fn int(&mut self, what: &str) -> Result<i32> {
        if self.binary {
            Ok(i32::from_le_bytes(self.raw::<4>(what)?))
        } else {
            self.text_i32(what)
        }
    }

    /// A `double` field.
    fn float(&mut self, what: &str) -> Result<f64> {
        if self.binary {
            Ok(f64::from_le_bytes(self.raw::<8>(what)?))
        } else {
            self.text_f64(what)
        }
    }

    /// Minimum bytes of an item of `numbers` fields (at least a digit and a separator each
    /// in ASCII) or `bytes` bytes (binary).
    fn item(&self, numbers: u64, bytes: u64) -> u64 {
        if self.binary {
            bytes
        } else {
            2 * numbers
        }
    }

    /// Checks that the rest of the file can hold `count` items of at least `item_bytes`
    /// bytes each, before anything is allocated for them; returns the count as `usize`.
    fn guard(&self, count: u64, item_bytes: u64, what: &str) -> Result<usize> {
        let remaining = self.remaining() as u64;
        match count.checked_mul(item_bytes) {
            Some(need) if need <= remaining => Ok(count as usize),
            _ => Err(self.err(format!(
                "the file claims {count} {what}, but the {remaining} bytes left cannot hold them \
                 (truncated or corrupt file)"
            ))),
        }
    }

    /// Consumes the rest of the current line (blanks only) and its line break: binary data
    /// start on the next byte.
    fn end_of_line(&mut self, after: &str) -> Result<()> {
        loop {
            match self.bytes.get(self.pos) {
                Some(b' ' | b'\t' | b'\r') => self.pos += 1,
                Some(b'\n') => {
                    self.pos += 1;
                    self.line += 1;
                    return Ok(());
                }
                _ => {
                    self.mark();
                    return Err(self.err(format!("expected the end of the line after {after}")));
                }
            }
        }
    }

    /// Starts the body of section `name`: in a binary file, numbers are read in binary from
    /// the line after the header.
    fn begin(&mut self, name: &str) -> Result<()> {
        if self.binary_file {
            self.end_of_line(&format!("`${name}`"))?;
            self.binary = true;
        }
        Ok(())
    }

    /// Reads `$End<name>`.
    fn end(&mut self, name: &str) -> Result<()> {
        self.binary = false;
        let expected = format!("$End{name}");
        let t = self.token(&format!("`{expected}`"))?;
        if t != expected.as_bytes() {
            return Err(self.err(format!(
                "expected `{expected}`, found `{}`: the data of ${name} do not match its counts",
                show(t)
            )));
        }
        Ok(())
    }

    fn read(mut self) -> Result<Sections> {
        self.header()?;
        let mut s = Sections {
            seen: vec!["MeshFormat".into()],
            ..Sections::default()
        };
        let mut elements = false;
        loop {
            self.skip_ws();
            if self.pos >= self.bytes.len() {
                break;
            }
            let t = self.token("a section header")?;
            let name = match t.strip_prefix(b"$") {
                Some(n)
                    if !n.is_empty()
                        && n.len() <= MAX_SECTION_NAME
                        && n.iter().all(|b| b.is_ascii_alphanumeric() || *b == b'_') =>
                {
                    String::from_utf8_lossy(n).into_owned()
                }
                _ => {
                    return Err(self.err(format!(
                        "expected a section header such as `$Nodes`, found `{}`",
                        show(t)
                    )))
                }
            };
            if name.starts_with("End") {
                return Err(self.err(format!("`${name}` closes a section that was not opened")));
            }
            if s.seen.contains(&name) {
                return Err(self.err(format!("section `${name}` appears twice")));
            }
            match name.as_str() {
                "PhysicalNames" => self.physical_names(&mut s)?,
                "Entities" => s.entities = Some(self.entities()?),
                "PartitionedEntities" => {
                    return Err(self.err(
                        "partitioned meshes are not supported: save the mesh without partitions",
                    ))
                }
                "Nodes" => s.nodes = Some(self.nodes()?),
                "Elements" => {
                    let Some(nodes) = s.nodes.as_ref() else {
                        return Err(self.err(
                            "`$Elements` comes before `$Nodes`: the nodes must be defined first \
                             (as Gmsh writes them)",
                        ));
                    };
                    let (blocks, skipped) = self.elements(nodes)?;
                    s.blocks = blocks;
                    s.skipped = skipped;
                    elements = true;
                }
                _ => self.skip_section(&name)?,
            }
            s.seen.push(name);
        }
        self.at = FileLocation::Whole;
        if s.nodes.is_none() {
            return Err(self.err("missing `$Nodes` section"));
        }
        if !elements {
            return Err(self.err("missing `$Elements` section"));
        }
        Ok(s)
    }

    fn header(&mut self) -> Result<()> {
        self.skip_ws();
        if self.pos >= self.bytes.len() {
            return Err(self.err("empty file: not a Gmsh mesh"));
        }
        let t = self.token("`$MeshFormat`")?;
        if t == b"$NOD" || t == b"$NOE" {
            return Err(self.err(
                "format 1.0 is not supported; export as 4.1 (gmsh -format msh41, or \
                 Mesh.MshFileVersion = 4.1)",
            ));
        }
        if t != b"$MeshFormat" {
            return Err(self.err(format!(
                "not a Gmsh mesh file: it must begin with `$MeshFormat`, found `{}`",
                show(t)
            )));
        }
        let v = self.token("the format version")?;
        if v != b"4.1" {
            let text = show(v);
            return Err(if text.parse::<f64>().is_ok_and(f64::is_finite) {
                self.err(format!(
                    "format {text} is not supported; export as 4.1 (gmsh -format msh41, or \
                     Mesh.MshFileVersion = 4.1)"
                ))
            } else {
                self.err(format!("expected the format version 4.1, found `{text}`"))
            });
        }
        let file_type = self.text_u64("the file type")?;
        let data_size = self.text_u64("the data size")?;
        match file_type {
            0 => {}
            1 => {
                if data_size != 8 {
                    return Err(self.err(format!(
                        "data size {data_size}: only binary files with 8-byte size_t (as written \
                         by 64-bit Gmsh) are supported"
                    )));
                }
                // The rest of the line, then the binary int 1.
                self.end_of_line("`4.1 1 8`")?;
                self.binary_file = true;
                match self.raw::<4>("the endianness check (the binary int 1)")? {
                    [1, 0, 0, 0] => {}
                    [0, 0, 0, 1] => {
                        return Err(self.err(
                            "big-endian binary files are not supported: write the mesh on a \
                             little-endian machine, or as ASCII (Mesh.Binary = 0)",
                        ))
                    }
                    other => {
                        return Err(self.err(format!(
                            "the endianness check reads the bytes {other:?} instead of the int 1 \
                             written as [1, 0, 0, 0]: not a little-endian binary file with 4-byte \
                             ints"
                        )))
                    }
                }
            }
            other => {
                return Err(self.err(format!(
                    "file type {other}: expected 0 (ASCII) or 1 (binary)"
                )))
            }
        }
        self.end("MeshFormat")
    }

    /// `$PhysicalNames` (always text, also in binary files).
    fn physical_names(&mut self, s: &mut Sections) -> Result<()> {
        let n = self.text_u64("the number of physical names")?;
        // `1 1 ""` and a line break.
        let n = self.guard(n, 7, "physical names")?;
        for _ in 0..n {
            let dim = self.text_i32("the dimension of a physical group")?;
            if !(0..=3).contains(&dim) {
                return Err(self.err(format!(
                    "physical group dimension {dim}: expected 0, 1, 2 or 3"
                )));
            }
            let tag = self.text_i32("the tag of a physical group")?;
            let name = self.quoted("the name of a physical group")?;
            if s.names.insert((dim, tag), name).is_some() {
                return Err(self.err(format!(
                    "physical group {tag} of dimension {dim} is named twice"
                )));
            }
        }
        self.end("PhysicalNames")
    }

    /// A name in double quotes, on one line.
    fn quoted(&mut self, what: &str) -> Result<String> {
        self.skip_ws();
        self.mark();
        if self.bytes.get(self.pos) != Some(&b'"') {
            return Err(self.err(format!("expected {what} in double quotes")));
        }
        let start = self.pos + 1;
        let rest = self.bytes.get(start..).unwrap_or_default();
        match rest.iter().position(|&b| b == b'"' || b == b'\n') {
            Some(i) if rest[i] == b'"' => {
                let name = String::from_utf8_lossy(&rest[..i]).into_owned();
                self.pos = start + i + 1;
                Ok(name)
            }
            _ => Err(self.err(format!("{what} has no closing double quote on its line"))),
        }
    }

    fn entities(&mut self) -> Result<HashMap<(i32, i32), Vec<i32>>> {
        self.begin("Entities")?;
        let mut counts = [0u64; 4];
        for (dim, c) in counts.iter_mut().enumerate() {
            *c = self.size(
                [
                    "the number of points",
                    "the number of curves",
                    "the number of surfaces",
                    "the number of volumes",
                ][dim],
            )?;
        }
        let mut total = 0usize;
        for (dim, &c) in counts.iter().enumerate() {
            // Point: tag, 3 coordinates, a count; others: tag, 6 bounds, two counts.
            let item = if dim == 0 {
                self.item(5, 36)
            } else {
                self.item(10, 68)
            };
            total = total.saturating_add(self.guard(c, item, "entities")?);
        }
        let mut map = HashMap::with_capacity(total);
        for (dim, &count) in counts.iter().enumerate() {
            for _ in 0..count {
                let tag = self.int("an entity tag")?;
                for _ in 0..if dim == 0 { 3 } else { 6 } {
                    self.float("an entity's bounding box")?;
                }
                let np = self.size("the number of physical groups of an entity")?;
                let np = self.guard(np, self.item(1, 4), "physical groups of an entity")?;
                let mut phys = Vec::with_capacity(np);
                for _ in 0..np {
                    phys.push(self.int("a physical group tag")?);
                }
                if dim > 0 {
                    let nb = self.size("the number of bounding entities")?;
                    let nb = self.guard(nb, self.item(1, 4), "bounding entities")?;
                    for _ in 0..nb {
                        self.int("a bounding entity tag")?;
                    }
                }
                if map.insert((dim as i32, tag), phys).is_some() {
                    return Err(
                        self.err(format!("entity {tag} of dimension {dim} is defined twice"))
                    );
                }
            }
        }
        self.end("Entities")?;
        Ok(map)
    }

    fn nodes(&mut self) -> Result<Nodes> {
        self.begin("Nodes")?;
        let n_blocks = self.size("the number of node blocks")?;
        let n_nodes = self.size("the number of nodes")?;
        self.size("the smallest node tag")?;
        self.size("the largest node tag")?;
        // Block header: 3 ints and a count; node: a tag and 3 coordinates.
        let n = self.guard(n_nodes, self.item(4, 32), "nodes")?;
        let n_blocks = self.guard(n_blocks, self.item(4, 20), "node blocks")?;
        if n_nodes > MAX_NODES {
            return Err(self.err(format!(
                "{n_nodes} nodes: more than the {MAX_NODES} supported"
            )));
        }
        let mut nodes = Nodes {
            tags: Vec::with_capacity(n),
            coords: Vec::with_capacity(n),
            index: HashMap::with_capacity(n),
        };
        for _ in 0..n_blocks {
            let dim = self.int("the entity dimension of a node block")?;
            if !(0..=3).contains(&dim) {
                return Err(self.err(format!(
                    "entity dimension {dim} of a node block: expected 0, 1, 2 or 3"
                )));
            }
            self.int("the entity tag of a node block")?;
            let parametric = self.int("the parametric flag of a node block")?;
            if parametric != 0 && parametric != 1 {
                return Err(self.err(format!(
                    "parametric flag {parametric} of a node block: expected 0 or 1"
                )));
            }
            let count = self.size("the number of nodes of a block")?;
            // Parametric nodes carry `dim` more coordinates.
            let extra = if parametric == 1 { dim as u64 } else { 0 };
            let count = self.guard(
                count,
                self.item(4 + extra, 32 + 8 * extra),
                "nodes in a block",
            )?;
            if nodes.tags.len() + count > n {
                return Err(self.err(format!(
                    "the node blocks hold more nodes than the {n} announced by the `$Nodes` header"
                )));
            }
            let first = nodes.tags.len();
            for _ in 0..count {
                let tag = self.size("a node tag")?;
                let index = nodes.tags.len() as u32;
                if nodes.index.insert(tag, index).is_some() {
                    return Err(self.err(format!("node tag {tag} is defined twice")));
                }
                nodes.tags.push(tag);
            }
            for k in 0..count {
                let mut x = [0.0; 3];
                for xi in x.iter_mut() {
                    *xi = self.float("a node coordinate")?;
                    if !xi.is_finite() {
                        return Err(self.err(format!(
                            "node tag {} has a non-finite coordinate ({xi})",
                            nodes.tags[first + k]
                        )));
                    }
                }
                for _ in 0..extra {
                    self.float("a parametric node coordinate")?;
                }
                nodes.coords.push(x);
            }
        }
        if nodes.tags.len() != n {
            return Err(self.err(format!(
                "the `$Nodes` header announces {n} nodes, its blocks hold {}",
                nodes.tags.len()
            )));
        }
        self.end("Nodes")?;
        Ok(nodes)
    }

    fn elements(&mut self, nodes: &Nodes) -> Result<(Vec<Block>, Vec<Skipped>)> {
        self.begin("Elements")?;
        let n_blocks = self.size("the number of element blocks")?;
        let n_elements = self.size("the number of elements")?;
        self.size("the smallest element tag")?;
        self.size("the largest element tag")?;
        // An element is at least a tag and one node.
        self.guard(n_elements, self.item(2, 16), "elements")?;
        let n_blocks = self.guard(n_blocks, self.item(4, 20), "element blocks")?;
        let mut blocks = Vec::new();
        let mut skipped = Vec::new();
        let mut total: u64 = 0;
        for _ in 0..n_blocks {
            let dim = self.int("the entity dimension of an element block")?;
            let at = self.at;
            if !(0..=3).contains(&dim) {
                return Err(self.err(format!(
                    "entity dimension {dim} of an element block: expected 0, 1, 2 or 3"
                )));
            }
            let entity = self.int("the entity tag of an element block")?;
            let etype = self.int("the element type of an element block")?;
            let Some((tdim, nn, name)) = element_type(etype) else {
                return Err(self.err(format!(
                    "unknown element type {etype}: only P1 simplices (Gmsh types 1, 2, 4) are \
                     supported"
                )));
            };
            if nn == 0 {
                return Err(self.err(format!(
                    "element type {etype} ({name}) has a variable number of nodes: only P1 \
                     simplices are supported"
                )));
            }
            if i32::from(tdim) != dim {
                return Err(self.err(format!(
                    "element type {etype} ({name}) has dimension {tdim}, but its block belongs to \
                     an entity of dimension {dim}"
                )));
            }
            let count = self.size("the number of elements of a block")?;
            let width = 1 + nn as u64;
            let count = self.guard(count, self.item(width, 8 * width), "elements in a block")?;
            total = total.saturating_add(count as u64);
            if total > n_elements {
                return Err(self.err(format!(
                    "the element blocks hold more elements than the {n_elements} announced by \
                     the `$Elements` header"
                )));
            }
            if matches!(etype, LINE | TRIANGLE | TETRAHEDRON) {
                let mut block = Block {
                    dim: tdim,
                    entity,
                    at,
                    tags: Vec::with_capacity(count),
                    conn: Vec::with_capacity(count * nn),
                };
                for _ in 0..count {
                    let tag = self.size("an element tag")?;
                    block.tags.push(tag);
                    for _ in 0..nn {
                        let node = self.size("a node tag of an element")?;
                        match nodes.index.get(&node) {
                            Some(&i) => block.conn.push(i),
                            None => {
                                return Err(self.err(format!(
                                    "element {tag} refers to node tag {node}, which `$Nodes` \
                                     does not define"
                                )))
                            }
                        }
                    }
                }
                blocks.push(block);
            } else {
                for _ in 0..count as u64 * width {
                    self.size("element data")?;
                }
                if etype != POINT && count > 0 {
                    skipped.push(Skipped {
                        dim: tdim,
                        entity,
                        etype,
                        name,
                        at,
                    });
                }
            }
        }
        if total != n_elements {
            return Err(self.err(format!(
                "the `$Elements` header announces {n_elements} elements, its blocks hold {total}"
            )));
        }
        self.end("Elements")?;
        Ok((blocks, skipped))
    }

    /// Steps over a section the reader does not use, up to its `$End<name>` line.
    fn skip_section(&mut self, name: &str) -> Result<()> {
        let end = format!("$End{name}");
        let end = end.as_bytes();
        let rest = self.bytes.get(self.pos..).unwrap_or_default();
        let mut found = None;
        for (i, _) in rest.iter().enumerate().filter(|(_, &b)| b == b'$') {
            let starts_line = i == 0 || rest[i - 1].is_ascii_whitespace();
            let after = rest.get(i + end.len());
            if starts_line
                && rest.get(i..i + end.len()) == Some(end)
                && after.is_none_or(|b| b.is_ascii_whitespace())
            {
                found = Some(i);
                break;
            }
        }
        let Some(i) = found else {
            return Err(self.err(format!(
                "section `${name}` has no `$End{name}` (truncated file?)"
            )));
        };
        if !self.binary_file {
            self.line += rest[..i].iter().filter(|&&b| b == b'\n').count() as u64;
        }
        self.pos += i + end.len();
        Ok(())
    }
}

// ---------------------------------------------------------------------------------------
// From sections to a mesh.
// ---------------------------------------------------------------------------------------

/// Interns physical-group names: index of each distinct name, with the smallest physical
/// tag carrying it (parts and regions are ordered by it).
#[derive(Default)]
struct Names {
    names: Vec<String>,
    min_tag: Vec<i64>,
    index: HashMap<String, u32>,
}

impl Names {
    fn get(&mut self, name: String, tag: i64) -> u32 {
        if let Some(&i) = self.index.get(&name) {
            let m = &mut self.min_tag[i as usize];
            *m = (*m).min(tag);
            return i;
        }
        let i = self.names.len() as u32;
        self.index.insert(name.clone(), i);
        self.names.push(name);
        self.min_tag.push(tag);
        i
    }

    /// The order of the names by smallest tag: `rank[i]` is the position of name `i`.
    fn ranks(&self) -> (Vec<String>, Vec<usize>) {
        let mut order: Vec<usize> = (0..self.names.len()).collect();
        order.sort_by_key(|&i| (self.min_tag[i], i));
        let mut rank = vec![0; order.len()];
        for (r, &i) in order.iter().enumerate() {
            rank[i] = r;
        }
        (order.iter().map(|&i| self.names[i].clone()).collect(), rank)
    }
}

/// Facet key: the sorted vertex indices, padded with `u32::MAX`.
fn facet_key(v: &[u32]) -> [u32; 3] {
    let mut k = [u32::MAX; 3];
    k[..v.len()].copy_from_slice(v);
    k[..v.len()].sort_unstable();
    k
}

fn assemble(s: Sections, file: &str) -> Result<GmshMesh> {
    let err = |at: FileLocation, message: String| Error::MeshFile {
        file: file.to_string(),
        location: at,
        message,
    };
    let whole = |message: String| err(FileLocation::Whole, message);
    let Some(nodes) = s.nodes else {
        return Err(whole("missing `$Nodes` section".into()));
    };
    let mut notes = Vec::new();

    // Dimension: the highest dimension of a non-empty element block (points excluded).
    let d = s
        .blocks
        .iter()
        .filter(|b| !b.tags.is_empty())
        .map(|b| b.dim)
        .chain(s.skipped.iter().map(|k| k.dim))
        .max()
        .unwrap_or(0) as usize;
    if d < 2 {
        return Err(whole(
            "the file has no triangles or tetrahedra: nothing to compute on. When physical groups \
             are defined, Gmsh saves only their elements: add a physical surface (2D) or volume \
             (3D) holding the domain, or set Mesh.SaveAll = 1"
                .into(),
        ));
    }
    if let Some(k) = s.skipped.iter().find(|k| k.dim as usize + 1 >= d) {
        let (cells, facets) = if d == 2 {
            ("triangles (type 2)", "lines (type 1)")
        } else {
            ("tetrahedra (type 4)", "triangles (type 2)")
        };
        return Err(err(
            k.at,
            format!(
                "element type {} ({}) in entity {} of dimension {}: only P1 simplices are \
                 supported ({cells} as cells, {facets} as boundary facets); re-mesh with \
                 Mesh.ElementOrder = 1 and Mesh.RecombineAll = 0",
                k.etype, k.name, k.entity, k.dim
            ),
        ));
    }
    let physical = |dim: usize, b: &Block| -> Result<&[i32]> {
        match &s.entities {
            None => Ok(&[]),
            Some(map) => map
                .get(&(dim as i32, b.entity))
                .map(Vec::as_slice)
                .ok_or_else(|| {
                    err(
                        b.at,
                        format!(
                            "the element block belongs to entity {} of dimension {dim}, which \
                             `$Entities` does not define",
                            b.entity
                        ),
                    )
                }),
        }
    };
    let group_name = |dim: usize, tag: i32| -> String {
        s.names
            .get(&(dim as i32, tag))
            .filter(|n| !n.trim().is_empty())
            .cloned()
            .unwrap_or_else(|| tag.to_string())
    };
    if s.entities.is_none() {
        notes.push(
            "the file has no `$Entities` section: physical groups are unknown, every boundary \
             facet is in the part `untagged`"
                .into(),
        );
    }

    // Cells, their orientations and regions.
    let nv = d + 1;
    let mut cells: Vec<u32> = Vec::new();
    let mut element_tags: Vec<u64> = Vec::new();
    let mut region_of: Vec<u32> = Vec::new();
    let mut regions = Names::default();
    let mut untagged_region = None;
    let mut multi_region = 0usize;
    let tags_of = |v: &[u32]| -> Vec<u64> { v.iter().map(|&i| nodes.tags[i as usize]).collect() };
    // Orientation of each cell, and the cells of each element block.
    let mut negative: Vec<bool> = Vec::new();
    let mut cell_blocks: Vec<(i32, FileLocation, std::ops::Range<usize>)> = Vec::new();
    for b in s.blocks.iter().filter(|b| b.dim as usize == d) {
        let start = element_tags.len();
        let groups = physical(d, b)?;
        let region = match groups.first() {
            Some(&t) => regions.get(group_name(d, t), i64::from(t)),
            None => {
                *untagged_region.get_or_insert_with(|| regions.get(UNTAGGED.to_string(), i64::MAX))
            }
        };
        if groups.len() > 1 {
            multi_region += b.tags.len();
        }
        for (k, &tag) in b.tags.iter().enumerate() {
            let mut c = [0u32; 4];
            c[..nv].copy_from_slice(&b.conn[k * nv..(k + 1) * nv]);
            let mut x = [[0.0; 3]; 4];
            for a in 0..nv {
                x[a] = nodes.coords[c[a] as usize];
            }
            if d == 2 {
                if let Some(a) = (0..nv).find(|&a| x[a][2] != 0.0) {
                    return Err(err(
                        b.at,
                        format!(
                            "node tag {} of triangle {tag} has z = {}: a 2D mesh (triangles only) \
                             must lie in the plane z = 0",
                            nodes.tags[c[a] as usize], x[a][2]
                        ),
                    ));
                }
            }
            let m = simplex::signed_measure(d, &x);
            let mut h: f64 = 0.0;
            for a in 0..nv {
                for q in 0..a {
                    let e: f64 = (0..d).map(|i| (x[a][i] - x[q][i]).powi(2)).sum();
                    h = h.max(e.sqrt());
                }
            }
            if !m.is_finite() || !h.is_finite() {
                return Err(err(
                    b.at,
                    format!(
                        "element {tag} (nodes {:?}) has a non-finite measure: coordinates too large",
                        tags_of(&c[..nv])
                    ),
                ));
            }
            if m.abs() <= DEGENERATE_TOL * h.powi(d as i32) {
                return Err(err(
                    b.at,
                    format!(
                        "element {tag} (nodes {:?}) is degenerate: its {} is {m:e}, zero up to \
                         round-off",
                        tags_of(&c[..nv]),
                        if d == 2 { "area" } else { "volume" }
                    ),
                ));
            }
            cells.extend_from_slice(&c[..nv]);
            element_tags.push(tag);
            region_of.push(region);
            negative.push(m < 0.0);
        }
        cell_blocks.push((b.entity, b.at, start..element_tags.len()));
    }
    let n_cells = element_tags.len();
    if n_cells == 0 {
        return Err(whole("the file has no cells".into()));
    }
    reorient(
        d,
        &mut cells,
        &negative,
        &cell_blocks,
        &element_tags,
        &mut notes,
    )
    .map_err(|(at, message)| err(at, message))?;
    if n_cells > u32::MAX as usize / 8 {
        return Err(whole(format!("{n_cells} cells: more than supported")));
    }

    // Duplicate cells would hide the boundary (every facet shared twice).
    {
        let mut keys: Vec<([u32; 4], u32)> = (0..n_cells)
            .map(|c| {
                let mut k = [u32::MAX; 4];
                k[..nv].copy_from_slice(&cells[c * nv..(c + 1) * nv]);
                k[..nv].sort_unstable();
                (k, c as u32)
            })
            .collect();
        keys.sort_unstable();
        if let Some(w) = keys.windows(2).find(|w| w[0].0 == w[1].0) {
            return Err(whole(format!(
                "elements {} and {} have the same nodes {:?} (duplicate cell)",
                element_tags[w[0].1 as usize],
                element_tags[w[1].1 as usize],
                tags_of(&w[0].0[..nv])
            )));
        }
    }

    // Boundary facets: the facets of exactly one cell.
    let mut all: Vec<([u32; 3], u32)> = Vec::with_capacity(n_cells * nv);
    for c in 0..n_cells {
        let cell = &cells[c * nv..(c + 1) * nv];
        for skip in 0..nv {
            let mut v = [0u32; 3];
            let mut j = 0;
            for (a, &n) in cell.iter().enumerate() {
                if a != skip {
                    v[j] = n;
                    j += 1;
                }
            }
            all.push((facet_key(&v[..d]), c as u32));
        }
    }
    all.sort_unstable();
    let mut boundary: Vec<[u32; 3]> = Vec::new();
    let mut i = 0;
    while i < all.len() {
        let mut j = i + 1;
        while j < all.len() && all[j].0 == all[i].0 {
            j += 1;
        }
        match j - i {
            1 => boundary.push(all[i].0),
            2 => {}
            k => {
                return Err(whole(format!(
                    "the facet with nodes {:?} is shared by {k} cells (non-manifold mesh)",
                    tags_of(&all[i].0[..d])
                )))
            }
        }
        i = j;
    }
    drop(all);

    // Tagged facets: the boundary part of each boundary facet, from the physical groups.
    let mut parts = Names::default();
    let mut assigned: Vec<Option<(u32, u64)>> = vec![None; boundary.len()];
    let mut tagged: Vec<(usize, [u32; 3])> = Vec::new();
    let mut interior: HashMap<String, usize> = HashMap::new();
    for b in s.blocks.iter().filter(|b| b.dim as usize + 1 == d) {
        // The distinct group names of the block's entity (with their smallest tags), once
        // per block: an entity may be in very many groups.
        let mut names: Vec<(String, i32)> = Vec::new();
        let mut seen: HashMap<String, usize> = HashMap::new();
        for &g in physical(d - 1, b)? {
            let name = group_name(d - 1, g);
            match seen.get(&name) {
                Some(&k) => names[k].1 = names[k].1.min(g),
                None => {
                    seen.insert(name.clone(), names.len());
                    names.push((name, g));
                }
            }
        }
        let mut part: Option<u32> = None;
        let mut n_interior = 0usize;
        for (k, &tag) in b.tags.iter().enumerate() {
            let v = &b.conn[k * d..(k + 1) * d];
            let Ok(pos) = boundary.binary_search(&facet_key(v)) else {
                n_interior += 1;
                continue;
            };
            let two = |first: &str, second: &str, elements: String| {
                err(
                    b.at,
                    format!(
                        "boundary facet with nodes {:?} ({elements}) is in physical groups `{first}` \
                         and `{second}`; a facet may belong to one boundary part",
                        tags_of(v)
                    ),
                )
            };
            let p = match names.as_slice() {
                [] => continue,
                [(name, g)] => *part.get_or_insert_with(|| parts.get(name.clone(), i64::from(*g))),
                [(first, _), (second, _), ..] => {
                    return Err(two(first, second, format!("element {tag}")))
                }
            };
            match assigned[pos] {
                None => {
                    assigned[pos] = Some((p, tag));
                    let mut f = [u32::MAX; 3];
                    f[..d].copy_from_slice(v);
                    tagged.push((pos, f));
                }
                Some((q, other)) if q != p => {
                    return Err(two(
                        &parts.names[q as usize],
                        &parts.names[p as usize],
                        format!("elements {other} and {tag}"),
                    ))
                }
                Some(_) => {}
            }
        }
        if n_interior > 0 {
            for (name, _) in names {
                *interior.entry(name).or_default() += n_interior;
            }
        }
    }
    let mut interior: Vec<(String, usize)> = interior.into_iter().collect();
    interior.sort();
    for (name, n) in interior {
        notes.push(format!(
            "physical group `{name}`: {n} facets lie inside the domain, not on its boundary; \
             they are ignored"
        ));
    }
    let n_untagged = assigned.iter().filter(|a| a.is_none()).count();
    let untagged_part = if n_untagged > 0 {
        notes.push(format!(
            "{n_untagged} boundary facets belong to no physical group of dimension {}: they form \
             the boundary part `{UNTAGGED}` (traction-free unless the scenario names it)",
            d - 1
        ));
        Some(parts.get(UNTAGGED.to_string(), i64::MAX))
    } else {
        None
    };
    let (part_names, part_rank) = parts.ranks();
    if part_names.len() > u16::MAX as usize {
        return Err(whole(format!(
            "{} boundary parts: more than the {} supported",
            part_names.len(),
            u16::MAX
        )));
    }

    // Nodes used by cells, in file order.
    let mut new_index = vec![u32::MAX; nodes.tags.len()];
    for &v in &cells {
        new_index[v as usize] = 0;
    }
    let mut coords = Vec::new();
    let mut node_tags = Vec::new();
    let mut next = 0u32;
    for (i, slot) in new_index.iter_mut().enumerate() {
        if *slot == 0 {
            *slot = next;
            next += 1;
            coords.extend_from_slice(&nodes.coords[i][..d]);
            node_tags.push(nodes.tags[i]);
        }
    }
    // Two used nodes at the same point: an unmerged geometry (the mesh would have a crack
    // there, its two faces becoming boundary facets).
    {
        let n_used = node_tags.len();
        let mut order: Vec<u32> = (0..n_used as u32).collect();
        let key = |i: u32| &coords[i as usize * d..(i as usize + 1) * d];
        order.sort_unstable_by(|&a, &b| {
            key(a)
                .iter()
                .zip(key(b))
                .map(|(x, y)| x.total_cmp(y))
                .find(|o| o.is_ne())
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        if let Some(w) = order.windows(2).find(|w| key(w[0]) == key(w[1])) {
            return Err(whole(format!(
                "nodes {} and {} are at the same point {:?} (duplicate nodes: the geometry is \
                 not merged, which would cut the body; merge duplicates in Gmsh, e.g. with \
                 Geometry.Tolerance / `Coherence;`)",
                node_tags[w[0] as usize],
                node_tags[w[1] as usize],
                key(w[0])
            )));
        }
    }
    let dropped = nodes.tags.len() - node_tags.len();
    if dropped > 0 {
        notes.push(format!("{dropped} nodes not used by any cell were dropped"));
    }
    let renumber = |v: u32| new_index[v as usize];
    let cells: Vec<u32> = cells.into_iter().map(renumber).collect();
    let mut facets = Vec::with_capacity(boundary.len() * d);
    let mut facet_part = Vec::with_capacity(boundary.len());
    for (pos, f) in &tagged {
        if let Some((p, _)) = assigned[*pos] {
            facets.extend(f[..d].iter().map(|&v| renumber(v)));
            facet_part.push(part_rank[p as usize] as u16);
        }
    }
    if let Some(p) = untagged_part {
        for (key, a) in boundary.iter().zip(&assigned) {
            if a.is_none() {
                facets.extend(key[..d].iter().map(|&v| renumber(v)));
                facet_part.push(part_rank[p as usize] as u16);
            }
        }
    }

    // Regions.
    let (region_names, region_rank) = regions.ranks();
    if region_names.len() > u16::MAX as usize {
        return Err(whole(format!(
            "{} cell regions: more than the {} supported",
            region_names.len(),
            u16::MAX
        )));
    }
    let cell_region = region_of
        .iter()
        .map(|&r| region_rank[r as usize] as u16)
        .collect();
    if region_names.len() > 1 {
        notes.push(format!(
            "{} cell regions ({}): one material applies to all of them",
            region_names.len(),
            region_names
                .iter()
                .map(|n| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    if multi_region > 0 {
        notes.push(format!(
            "{multi_region} cells are in several physical groups of dimension {d}; their region \
             is the first one"
        ));
    }

    let element = |c: usize| format!("element {}", element_tags[c]);
    let mesh = Mesh::try_new_named(d, coords, cells, facets, facet_part, part_names, &element)
        .map_err(|e| match e {
            Error::Mesh(m) => whole(format!("invalid mesh: {m}")),
            other => other,
        })?;
    Ok(GmshMesh {
        mesh,
        node_tags,
        element_tags,
        cell_region,
        region_names,
        notes,
    })
}

/// Orients the cells positively, entity by entity: an entity whose cells are all negatively
/// oriented (a surface meshed clockwise) is reoriented by swapping the last two vertices of
/// each cell, with a note; an entity with cells of both orientations is an error naming the
/// cells of the minority orientation (those whose orientation differs from the rest).
/// `blocks` lists (entity, location, cell range) per element block.
fn reorient(
    d: usize,
    cells: &mut [u32],
    negative: &[bool],
    blocks: &[(i32, FileLocation, std::ops::Range<usize>)],
    element_tags: &[u64],
    notes: &mut Vec<String>,
) -> std::result::Result<(), (FileLocation, String)> {
    let nv = d + 1;
    let (kind, entity_kind, neg, pos) = if d == 2 {
        ("triangles", "surface", "clockwise", "counterclockwise")
    } else {
        ("tetrahedra", "volume", "left-handed", "right-handed")
    };
    let mut entities: Vec<i32> = blocks.iter().map(|b| b.0).collect();
    entities.sort_unstable();
    entities.dedup();
    let mut flipped: Vec<(i32, usize)> = Vec::new();
    for &e in &entities {
        let ranges = || blocks.iter().filter(move |b| b.0 == e).map(|b| b.2.clone());
        let n_neg = ranges().flatten().filter(|&c| negative[c]).count();
        let n_all: usize = ranges().map(|r| r.len()).sum();
        if n_neg == 0 {
            continue;
        }
        if n_neg == n_all {
            for c in ranges().flatten() {
                cells.swap(c * nv + d - 1, c * nv + d);
            }
            flipped.push((e, n_all));
            continue;
        }
        // Mixed: the minority orientation is the inverted one.
        let odd_is_negative = 2 * n_neg <= n_all;
        let odd: Vec<usize> = ranges()
            .flatten()
            .filter(|&c| negative[c] == odd_is_negative)
            .collect();
        let (odd_word, rest_word) = if odd_is_negative {
            (neg, pos)
        } else {
            (pos, neg)
        };
        let at = blocks
            .iter()
            .find(|b| b.0 == e && b.2.contains(&odd[0]))
            .map_or(FileLocation::Whole, |b| b.1);
        let names = crate::mesh::list_cells(&odd, &|c| format!("element {}", element_tags[c]));
        return Err((
            at,
            format!(
                "{} of the {n_all} {kind} of {entity_kind} {e} {} inverted: {names} {} ordered \
                 {odd_word}, the others {rest_word} (a tangled mesh, e.g. a node moved past its \
                 neighbours). The cells of one {entity_kind} must all have the same \
                 orientation: {pos} is used as is, {neg} throughout is reoriented",
                odd.len(),
                if odd.len() == 1 { "is" } else { "are" },
                if odd.len() == 1 { "is" } else { "are" },
            ),
        ));
    }
    if !flipped.is_empty() {
        let list: Vec<String> = flipped
            .iter()
            .map(|(e, n)| format!("{entity_kind} {e} ({n} {kind})"))
            .collect();
        notes.push(format!(
            "the {kind} of {} are all ordered {neg}: they were reoriented ({pos}) by swapping \
             their last two vertices",
            list.join(", ")
        ));
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------
// Writing.
// ---------------------------------------------------------------------------------------

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

/// Writes `mesh` as a Gmsh 4.1 file (ASCII or binary) that [`parse_msh`] and Gmsh read back.
///
/// Layout: one geometric entity of dimension d (tag 1) holding all nodes and cells, in the
/// physical group `domain` (tag P + 1); one entity of dimension d − 1 per boundary part
/// (tag k + 1 for part k) in a physical group named after the part (tag k + 1). Node tags are
/// `1..=n_nodes` in mesh order and element tags number the part facets, then the cells, from
/// 1; so reading the file back gives the same node, cell and facet arrays and parts (parts
/// without facets are not read back). Double quotes and line feeds in part names, which
/// `$PhysicalNames` cannot hold, are written as `'` and spaces.
pub fn write_msh(mesh: &Mesh, encoding: MshEncoding) -> Vec<u8> {
    let d = mesh.dim();
    let binary = encoding == MshEncoding::Binary;
    let mut o = Out {
        buf: Vec::new(),
        binary,
    };
    o.begin("MeshFormat");
    if binary {
        o.text("4.1 1 8\n");
        o.buf.extend_from_slice(&1i32.to_le_bytes());
        o.buf.push(b'\n');
    } else {
        o.text("4.1 0 8\n");
    }
    o.text("$EndMeshFormat\n");

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

    let bbox = |nodes: &mut dyn Iterator<Item = usize>| -> [f64; 6] {
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
    };
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
    o.buf
}

/// Writes `mesh` to the file `path` with [`write_msh`] (atomically: a temporary file
/// renamed over `path`).
///
/// # Errors
/// [`Error::Io`] if the file cannot be written.
pub fn write_msh_file(mesh: &Mesh, path: &Path, encoding: MshEncoding) -> Result<()> {
    crate::io::atomic::write(path, &write_msh(mesh, encoding))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn locations_display_as_line_or_byte() {
        let e = Error::MeshFile {
            file: "a.msh".into(),
            location: FileLocation::Line(12),
            message: "bad".into(),
        };
        assert_eq!(e.to_string(), "a.msh:12: bad");
        let e = Error::MeshFile {
            file: "a.msh".into(),
            location: FileLocation::Byte(7),
            message: "bad".into(),
        };
        assert_eq!(e.to_string(), "a.msh (byte 7): bad");
    }

    #[test]
    fn tokens_track_lines_and_reject_bad_numbers() {
        let mut r = Reader::new(b"1\n\n  -2 x", "t");
        assert_eq!(r.text_u64("a").unwrap(), 1);
        assert_eq!(r.text_i32("b").unwrap(), -2);
        assert_eq!(r.at, FileLocation::Line(3));
        let e = r.text_u64("c").unwrap_err().to_string();
        assert!(
            e.starts_with("t:3: expected c (a non-negative integer), found `x`"),
            "{e}"
        );
        let e = r.text_u64("d").unwrap_err().to_string();
        assert!(e.contains("unexpected end of file"), "{e}");
    }

    #[test]
    fn guard_refuses_counts_the_file_cannot_hold() {
        let r = Reader::new(b"0123456789", "t");
        assert_eq!(r.guard(5, 2, "x").unwrap(), 5);
        assert!(r.guard(6, 2, "x").is_err());
        assert!(r.guard(u64::MAX, 2, "x").is_err());
    }
}
