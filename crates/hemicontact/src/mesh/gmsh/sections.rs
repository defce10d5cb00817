//! Reading the sections of a `.msh` file ($MeshFormat, $PhysicalNames, $Entities, $Nodes,
//! $Elements; others are skipped) into [`Sections`], checking each number as it is read.
//! No mesh is built here: see [`super::build`].

use super::element_types::{element_type, LINE, POINT, TETRAHEDRON, TRIANGLE};
use super::lexer::{show, Reader};
use crate::error::{FileLocation, Result};
use std::collections::HashMap;

/// Longest section name accepted (Gmsh's are at most 20 characters); bounds the search for
/// the end of a skipped section.
const MAX_SECTION_NAME: usize = 64;

/// Most nodes a [`crate::mesh::Mesh`] can index.
const MAX_NODES: u64 = u32::MAX as u64 / 2;

/// `$Nodes`: tags and coordinates in file order, and the index of each tag.
pub(super) struct Nodes {
    /// Node tags in file order.
    pub(super) tags: Vec<u64>,
    /// Coordinates of each node (x, y, z).
    pub(super) coords: Vec<[f64; 3]>,
    /// Position in `tags` of each tag.
    pub(super) index: HashMap<u64, u32>,
}

/// An element block of a type the reader uses (line, triangle, tetrahedron).
pub(super) struct Block {
    /// Dimension of the entity (and of the elements).
    pub(super) dim: u8,
    /// Entity tag.
    pub(super) entity: i32,
    /// Where the block header is.
    pub(super) at: FileLocation,
    /// Element tags.
    pub(super) tags: Vec<u64>,
    /// Node indices (into `Nodes`), `tags.len() × nodes per element`.
    pub(super) conn: Vec<u32>,
}

/// A non-empty element block of a type the reader does not use.
pub(super) struct Skipped {
    /// Dimension of the entity (and of the elements).
    pub(super) dim: u8,
    /// Entity tag.
    pub(super) entity: i32,
    /// Gmsh element type.
    pub(super) etype: i32,
    /// Gmsh's name of the element type.
    pub(super) name: &'static str,
    /// Where the block header is.
    pub(super) at: FileLocation,
}

/// Everything read from the file, before it is turned into a mesh.
#[derive(Default)]
pub(super) struct Sections {
    /// `(dimension, tag)` → name.
    pub(super) names: HashMap<(i32, i32), String>,
    /// `(dimension, entity tag)` → physical tags; `None` without `$Entities`.
    pub(super) entities: Option<HashMap<(i32, i32), Vec<i32>>>,
    /// `$Nodes`, once read.
    pub(super) nodes: Option<Nodes>,
    /// The element blocks of the types the reader uses, in file order.
    pub(super) blocks: Vec<Block>,
    /// The non-empty element blocks of other types (points excepted).
    pub(super) skipped: Vec<Skipped>,
    /// The sections read so far, by name (a section may appear once).
    pub(super) seen: Vec<String>,
}

impl Reader<'_> {
    /// Reads the whole file into its sections: `$MeshFormat` first, then any order, with
    /// `$Nodes` before `$Elements`; both are required.
    pub(super) fn read(mut self) -> Result<Sections> {
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
}
