//! Gmsh `.msh` files, format 4.1: the reader (ASCII and binary). The writer is
//! [`crate::io::msh`].
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
//! # How a file becomes a [`Mesh`](crate::mesh::Mesh)
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
//! - **Untagged boundary facets**: every boundary facet of a [`Mesh`](crate::mesh::Mesh) carries a part, so the
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
//! # Layout
//!
//! | file | job |
//! |------|-----|
//! | `lexer.rs` | tokens: ASCII numbers, quoted names, section markers, raw little-endian numbers of binary sections; locations for error messages; counts checked against the bytes left |
//! | `sections.rs` | the sections, each checked as it is read, into an unvalidated record of the file |
//! | `element_types.rs` | the table of Gmsh element types (dimension, nodes, name) |
//! | `source.rs` | what the later steps share: the file's physical groups and nodes, the interned group names, the name [`UNTAGGED`] |
//! | `build.rs` | from the sections to a [`GmshMesh`] (defined there): dimension, used nodes, regions, the validated [`Mesh`](crate::mesh::Mesh) |
//! | `cells.rs` | the cells: checks, orientation per entity, duplicates, regions |
//! | `parts.rs` | the boundary parts: physical groups of the boundary facets (found as for any [`Mesh`](crate::mesh::Mesh)) |
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
//! let bytes = write_msh(&mesh, MshEncoding::Ascii);
//! let read = parse_msh(&bytes, "rectangle.msh").unwrap();
//! assert_eq!(read.mesh.coords(), mesh.coords());
//! assert_eq!(read.mesh.cells(), mesh.cells());
//! assert_eq!(read.mesh.part_names(), ["bottom", "right", "top", "left"]);
//! ```

mod build;
mod cells;
pub(crate) mod element_types;
mod lexer;
mod parts;
mod sections;
mod source;

pub use build::GmshMesh;
pub use source::UNTAGGED;

use crate::error::{Error, Result};
use std::path::Path;

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
    let sections = lexer::Reader::new(bytes, source).read()?;
    build::assemble(sections, source)
}
