//! What the steps of building a mesh from a file share: the file itself (its name for error
//! messages, its physical groups and their names, its nodes) and the interned names of the
//! physical groups that become boundary parts and cell regions, with the name of the part
//! and region of what is in no group ([`UNTAGGED`]).

use super::sections::{Block, Nodes};
use crate::error::{Error, FileLocation, Result};
use std::collections::HashMap;

/// Name of the boundary part holding the boundary facets that belong to no physical group
/// (and of the cell region of cells in no physical group).
pub const UNTAGGED: &str = "untagged";

/// What the steps of building need of the file besides its elements: its name (for error
/// messages), its physical groups and their names, and its nodes.
pub(super) struct Source<'a> {
    /// The file, as named in error messages.
    pub(super) file: &'a str,
    /// `(dimension, tag)` → name of a physical group.
    pub(super) names: &'a HashMap<(i32, i32), String>,
    /// `(dimension, entity tag)` → physical tags; `None` without `$Entities`.
    pub(super) entities: Option<&'a HashMap<(i32, i32), Vec<i32>>>,
    /// The nodes of the file.
    pub(super) nodes: &'a Nodes,
}

impl<'a> Source<'a> {
    /// An error at `at` in the file.
    pub(super) fn err(&self, at: FileLocation, message: String) -> Error {
        Error::MeshFile {
            file: self.file.to_string(),
            location: at,
            message,
        }
    }

    /// An error about the file as a whole.
    pub(super) fn whole(&self, message: String) -> Error {
        self.err(FileLocation::Whole, message)
    }

    /// The physical groups of the entity of dimension `dim` of block `b` (none without
    /// `$Entities`).
    pub(super) fn physical(&self, dim: usize, b: &Block) -> Result<&'a [i32]> {
        match self.entities {
            None => Ok(&[]),
            Some(map) => map
                .get(&(dim as i32, b.entity))
                .map(Vec::as_slice)
                .ok_or_else(|| {
                    self.err(
                        b.at,
                        format!(
                            "the element block belongs to entity {} of dimension {dim}, which \
                             `$Entities` does not define",
                            b.entity
                        ),
                    )
                }),
        }
    }

    /// The name of physical group `tag` of dimension `dim`: its `$PhysicalNames` name, or
    /// its tag if it has none (or a blank one).
    pub(super) fn group_name(&self, dim: usize, tag: i32) -> String {
        self.names
            .get(&(dim as i32, tag))
            .filter(|n| !n.trim().is_empty())
            .cloned()
            .unwrap_or_else(|| tag.to_string())
    }

    /// The Gmsh tags of the nodes `v` (indices into the file's nodes).
    pub(super) fn tags_of(&self, v: &[u32]) -> Vec<u64> {
        v.iter().map(|&i| self.nodes.tags[i as usize]).collect()
    }
}

/// Interns physical-group names: index of each distinct name, with the smallest physical
/// tag carrying it (parts and regions are ordered by it).
#[derive(Default)]
pub(super) struct Names {
    /// The distinct names, in the order first met.
    pub(super) names: Vec<String>,
    /// Smallest physical tag carrying each name.
    min_tag: Vec<i64>,
    /// Index of each name in `names`.
    index: HashMap<String, u32>,
}

impl Names {
    /// The index of `name`, carried by physical tag `tag`.
    pub(super) fn get(&mut self, name: String, tag: i64) -> u32 {
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
    pub(super) fn ranks(&self) -> (Vec<String>, Vec<usize>) {
        let mut order: Vec<usize> = (0..self.names.len()).collect();
        order.sort_by_key(|&i| (self.min_tag[i], i));
        let mut rank = vec![0; order.len()];
        for (r, &i) in order.iter().enumerate() {
            rank[i] = r;
        }
        (order.iter().map(|&i| self.names[i].clone()).collect(), rank)
    }
}
