//! The boundary parts of a `.msh` file: the boundary facets of the cells (found by
//! [`crate::mesh::facets::boundary_facets`], as for any [`crate::mesh::Mesh`]) are given the
//! part of the physical group of dimension d − 1 their element is in; those in no group form
//! the part [`UNTAGGED`]. Elements of such groups inside the domain are ignored, with a note.

use super::sections::Block;
use super::source::{Names, Source, UNTAGGED};
use crate::error::Result;
use crate::mesh::facets::{boundary_facets, sorted_key};
use std::collections::HashMap;

/// The boundary facets of a file with their parts.
pub(super) struct BoundaryParts {
    /// Vertices (indices into the file's nodes), d per facet: first the facets of physical
    /// groups in file order (their vertices as in the file), then the untagged ones (vertices
    /// sorted).
    pub(super) facets: Vec<u32>,
    /// Part of each facet: an index into `part_names`.
    pub(super) facet_part: Vec<u16>,
    /// Part names, in the order of their smallest physical tags, [`UNTAGGED`] last.
    pub(super) part_names: Vec<String>,
}

/// Gives every boundary facet of the cells `cells` (indices into the file's nodes, d + 1
/// each) its part, from the element blocks of dimension d − 1 in `blocks`.
///
/// # Errors
/// A facet shared by more than two cells (non-manifold mesh), a boundary facet in two
/// physical groups with different names, more parts than a mesh can name, a block of an
/// entity `$Entities` does not define.
pub(super) fn boundary_parts(
    src: &Source,
    d: usize,
    cells: &[u32],
    blocks: &[Block],
    notes: &mut Vec<String>,
) -> Result<BoundaryParts> {
    let boundary = boundary_facets(d, cells).map_err(|shared| {
        src.whole(format!(
            "the facet with nodes {:?} is shared by {} cells (non-manifold mesh)",
            src.tags_of(&shared.facet[..d]),
            shared.cells
        ))
    })?;

    // Tagged facets: the boundary part of each boundary facet, from the physical groups.
    let mut parts = Names::default();
    let mut assigned: Vec<Option<(u32, u64)>> = vec![None; boundary.len()];
    let mut tagged: Vec<(usize, [u32; 3])> = Vec::new();
    let mut interior: HashMap<String, usize> = HashMap::new();
    for b in blocks.iter().filter(|b| b.dim as usize + 1 == d) {
        // The distinct group names of the block's entity (with their smallest tags), once
        // per block: an entity may be in very many groups.
        let mut names: Vec<(String, i32)> = Vec::new();
        let mut seen: HashMap<String, usize> = HashMap::new();
        for &g in src.physical(d - 1, b)? {
            let name = src.group_name(d - 1, g);
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
            let key = sorted_key(v);
            let Ok(pos) = boundary.binary_search_by(|(f, _)| f.cmp(&key)) else {
                n_interior += 1;
                continue;
            };
            let two = |first: &str, second: &str, elements: String| {
                src.err(
                    b.at,
                    format!(
                        "boundary facet with nodes {:?} ({elements}) is in physical groups `{first}` \
                         and `{second}`; a facet may belong to one boundary part",
                        src.tags_of(v)
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
        return Err(src.whole(format!(
            "{} boundary parts: more than the {} supported",
            part_names.len(),
            u16::MAX
        )));
    }

    let mut facets = Vec::with_capacity(boundary.len() * d);
    let mut facet_part = Vec::with_capacity(boundary.len());
    for (pos, f) in &tagged {
        if let Some((p, _)) = assigned[*pos] {
            facets.extend_from_slice(&f[..d]);
            facet_part.push(part_rank[p as usize] as u16);
        }
    }
    if let Some(p) = untagged_part {
        for ((key, _), a) in boundary.iter().zip(&assigned) {
            if a.is_none() {
                facets.extend_from_slice(&key[..d]);
                facet_part.push(part_rank[p as usize] as u16);
            }
        }
    }
    Ok(BoundaryParts {
        facets,
        facet_part,
        part_names,
    })
}
