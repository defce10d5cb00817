//! The cells of a `.msh` file: the elements of dimension d, checked one by one (a 2D mesh in
//! the plane z = 0, finite and non-degenerate measure), oriented positively entity by
//! entity, and checked for duplicates; with the cell region of each.

use super::sections::Block;
use super::source::{Names, Source, UNTAGGED};
use crate::error::{FileLocation, Result};
use crate::geometry::simplex;
use crate::mesh::validate::{diameter, DEGENERATE_TOL};

/// The cells read from a file, in file order.
pub(super) struct Cells {
    /// Vertices (indices into the file's nodes), `n_cells × (d + 1)`, positively oriented.
    pub(super) cells: Vec<u32>,
    /// Gmsh tag of each cell's element.
    pub(super) element_tags: Vec<u64>,
    /// Region of each cell: an index into `regions`.
    pub(super) region_of: Vec<u32>,
    /// The cell regions: the physical groups of dimension d, and [`UNTAGGED`] if some cell
    /// is in none.
    pub(super) regions: Names,
    /// Number of cells in several physical groups of dimension d.
    pub(super) multi_region: usize,
}

/// Reads the cells of dimension `d` from the element blocks `blocks`.
///
/// # Errors
/// A node of a 2D mesh off the plane z = 0, a cell of non-finite measure or degenerate (zero
/// measure up to round-off), an entity with cells of both orientations, no cells, too many
/// cells, two cells with the same nodes, a block of an entity `$Entities` does not define.
pub(super) fn read_cells(
    src: &Source,
    d: usize,
    blocks: &[Block],
    notes: &mut Vec<String>,
) -> Result<Cells> {
    let nodes = src.nodes;
    let nv = d + 1;
    let mut cells: Vec<u32> = Vec::new();
    let mut element_tags: Vec<u64> = Vec::new();
    let mut region_of: Vec<u32> = Vec::new();
    let mut regions = Names::default();
    let mut untagged_region = None;
    let mut multi_region = 0usize;
    // Orientation of each cell, and the cells of each element block.
    let mut negative: Vec<bool> = Vec::new();
    let mut cell_blocks: Vec<(i32, FileLocation, std::ops::Range<usize>)> = Vec::new();
    for b in blocks.iter().filter(|b| b.dim as usize == d) {
        let start = element_tags.len();
        let groups = src.physical(d, b)?;
        let region = match groups.first() {
            Some(&t) => regions.get(src.group_name(d, t), i64::from(t)),
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
                    return Err(src.err(
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
            let h = diameter(d, &x[..nv]);
            if !m.is_finite() || !h.is_finite() {
                return Err(src.err(
                    b.at,
                    format!(
                        "element {tag} (nodes {:?}) has a non-finite measure: coordinates too large",
                        src.tags_of(&c[..nv])
                    ),
                ));
            }
            if m.abs() <= DEGENERATE_TOL * h.powi(d as i32) {
                return Err(src.err(
                    b.at,
                    format!(
                        "element {tag} (nodes {:?}) is degenerate: its {} is {m:e}, zero up to \
                         round-off",
                        src.tags_of(&c[..nv]),
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
        return Err(src.whole("the file has no cells".into()));
    }
    reorient(d, &mut cells, &negative, &cell_blocks, &element_tags, notes)
        .map_err(|(at, message)| src.err(at, message))?;
    if n_cells > u32::MAX as usize / 8 {
        return Err(src.whole(format!("{n_cells} cells: more than supported")));
    }

    // Duplicate cells would hide the boundary (every facet shared twice).
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
        return Err(src.whole(format!(
            "elements {} and {} have the same nodes {:?} (duplicate cell)",
            element_tags[w[0].1 as usize],
            element_tags[w[1].1 as usize],
            src.tags_of(&w[0].0[..nv])
        )));
    }
    Ok(Cells {
        cells,
        element_tags,
        region_of,
        regions,
        multi_region,
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
        let names =
            crate::mesh::listing::list_cells(&odd, &|c| format!("element {}", element_tags[c]));
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
