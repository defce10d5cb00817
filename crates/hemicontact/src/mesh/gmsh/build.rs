//! From the [`Sections`] of a file to a [`GmshMesh`]: the dimension, the cells
//! ([`super::cells`]), the boundary parts ([`super::parts`]), the nodes used by the cells
//! (renumbered in file order, duplicates refused), the cell regions, and last the validated
//! [`Mesh`]. Each step adds the facts worth telling the user to the notes.

use super::cells::read_cells;
use super::parts::boundary_parts;
use super::sections::Sections;
use super::source::{Source, UNTAGGED};
use crate::error::{Error, FileLocation, Result};
use crate::mesh::Mesh;
use std::collections::HashMap;

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

/// Builds the mesh of the file `file` from its sections; see the module documentation of
/// [`crate::mesh::gmsh`] for how.
pub(super) fn assemble(s: Sections, file: &str) -> Result<GmshMesh> {
    let Sections {
        names,
        entities,
        nodes,
        blocks,
        skipped,
        ..
    } = s;
    let Some(nodes) = nodes else {
        return Err(Error::MeshFile {
            file: file.to_string(),
            location: FileLocation::Whole,
            message: "missing `$Nodes` section".into(),
        });
    };
    let src = Source {
        file,
        names: &names,
        entities: entities.as_ref(),
        nodes: &nodes,
    };
    let mut notes = Vec::new();

    // Dimension: the highest dimension of a non-empty element block (points excluded).
    let d = blocks
        .iter()
        .filter(|b| !b.tags.is_empty())
        .map(|b| b.dim)
        .chain(skipped.iter().map(|k| k.dim))
        .max()
        .unwrap_or(0) as usize;
    if d < 2 {
        return Err(src.whole(
            "the file has no triangles or tetrahedra: nothing to compute on. When physical groups \
             are defined, Gmsh saves only their elements: add a physical surface (2D) or volume \
             (3D) holding the domain, or set Mesh.SaveAll = 1"
                .into(),
        ));
    }
    if let Some(k) = skipped.iter().find(|k| k.dim as usize + 1 >= d) {
        let (cells, facets) = if d == 2 {
            ("triangles (type 2)", "lines (type 1)")
        } else {
            ("tetrahedra (type 4)", "triangles (type 2)")
        };
        return Err(src.err(
            k.at,
            format!(
                "element type {} ({}) in entity {} of dimension {}: only P1 simplices are \
                 supported ({cells} as cells, {facets} as boundary facets); re-mesh with \
                 Mesh.ElementOrder = 1 and Mesh.RecombineAll = 0",
                k.etype, k.name, k.entity, k.dim
            ),
        ));
    }
    if entities.is_none() {
        notes.push(
            "the file has no `$Entities` section: physical groups are unknown, every boundary \
             facet is in the part `untagged`"
                .into(),
        );
    }

    let cells = read_cells(&src, d, &blocks, &mut notes)?;
    let parts = boundary_parts(&src, d, &cells.cells, &blocks, &mut notes)?;
    let (coords, node_tags, new_index) = used_nodes(&src, d, &cells.cells, &parts, &mut notes)?;
    let dropped = nodes.tags.len() - node_tags.len();
    if dropped > 0 {
        notes.push(format!("{dropped} nodes not used by any cell were dropped"));
    }
    let renumber = |v: &u32| new_index[*v as usize];
    let cell_nodes: Vec<u32> = cells.cells.iter().map(renumber).collect();
    let facets: Vec<u32> = parts.facets.iter().map(renumber).collect();

    // Regions.
    let (region_names, region_rank) = cells.regions.ranks();
    if region_names.len() > u16::MAX as usize {
        return Err(src.whole(format!(
            "{} cell regions: more than the {} supported",
            region_names.len(),
            u16::MAX
        )));
    }
    let cell_region: Vec<u16> = cells
        .region_of
        .iter()
        .map(|&r| region_rank[r as usize] as u16)
        .collect();
    if region_names.len() > 1 {
        notes.push(format!(
            "{} cell regions ({}): `[[material]]` tables naming them in `part` give each its \
             own material (a single `[material]` applies to all of them)",
            region_names.len(),
            region_names
                .iter()
                .map(|n| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    if cells.multi_region > 0 {
        notes.push(format!(
            "{} cells are in several physical groups of dimension {d}; their region is the \
             first one",
            cells.multi_region
        ));
    }

    let element_tags = cells.element_tags;
    let element = |c: usize| format!("element {}", element_tags[c]);
    let mesh = Mesh::try_new_named(
        d,
        coords,
        cell_nodes,
        facets,
        parts.facet_part,
        parts.part_names,
        &element,
    )
    .and_then(|m| m.with_regions(cell_region.clone(), region_names.clone()))
    .map_err(|e| match e {
        Error::Mesh(m) => src.whole(format!("invalid mesh: {m}")),
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

/// The body (connected component of the cells `cells`, `d + 1` file node indices each) of
/// each of the file's `n` nodes, as the index of a representative node; unused nodes are
/// their own.
fn bodies_of(d: usize, cells: &[u32], n: usize) -> Vec<u32> {
    let mut parent: Vec<u32> = (0..n as u32).collect();
    fn root(parent: &mut [u32], mut a: u32) -> u32 {
        while parent[a as usize] != a {
            let up = parent[parent[a as usize] as usize];
            parent[a as usize] = up;
            a = up;
        }
        a
    }
    for cell in cells.chunks_exact(d + 1) {
        let r0 = root(&mut parent, cell[0]);
        for &v in &cell[1..] {
            let r = root(&mut parent, v);
            if r != r0 {
                parent[r as usize] = r0;
            }
        }
    }
    (0..n as u32).map(|a| root(&mut parent, a)).collect()
}

/// The nodes used by the cells `cells` (indices into the file's nodes), in file order: their
/// coordinates (d each), their tags, and the new index of each node of the file (`u32::MAX`
/// for those dropped).
///
/// Nodes of different bodies may coincide (two bodies meshed apart that touch), and so may
/// two nodes of one body on coincident facets of two different named boundary parts (the
/// two faces of a crack, which a note counts).
///
/// # Errors
/// Two used nodes of one body at the same point that are not on coincident facets of two
/// different named boundary parts: an unmerged geometry (the mesh would have a crack there,
/// its two faces becoming boundary facets that no pair of physical groups names).
fn used_nodes(
    src: &Source,
    d: usize,
    cells: &[u32],
    parts: &super::parts::BoundaryParts,
    notes: &mut Vec<String>,
) -> Result<(Vec<f64>, Vec<u64>, Vec<u32>)> {
    let nodes = src.nodes;
    let mut new_index = vec![u32::MAX; nodes.tags.len()];
    for &v in cells {
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
    // Coincident nodes of two different bodies (meshed apart, touching along an interface
    // that a contact pair joins) are kept; inside one body they would cut it.
    let body = bodies_of(d, cells, nodes.tags.len());
    let file_index: Vec<usize> = new_index
        .iter()
        .enumerate()
        .filter(|(_, &k)| k != u32::MAX)
        .map(|(i, _)| i)
        .collect();
    let same_body = |a: u32, b: u32| body[file_index[a as usize]] == body[file_index[b as usize]];
    // The facets of named boundary parts (not `untagged`) at each file node.
    let mut named: HashMap<u32, Vec<usize>> = HashMap::new();
    for (f, &p) in parts.facet_part.iter().enumerate() {
        if parts.part_names[p as usize] != UNTAGGED {
            for &v in &parts.facets[f * d..(f + 1) * d] {
                named.entry(v).or_default().push(f);
            }
        }
    }
    // The points of facet f, sorted: two facets with the same points lie on each other.
    let points_of = |f: usize| {
        let mut x: Vec<Vec<u64>> = parts.facets[f * d..(f + 1) * d]
            .iter()
            .map(|&v| {
                nodes.coords[v as usize][..d]
                    .iter()
                    .map(|c| c.to_bits())
                    .collect()
            })
            .collect();
        x.sort_unstable();
        x
    };
    // Two faces of a crack: the two nodes on facets of two different named parts that lie
    // on each other (not merely two parts meeting at an unmerged corner).
    let crack = |a: u32, b: u32| -> Option<(u16, u16)> {
        let (fa, fb) = (
            named.get(&(file_index[a as usize] as u32))?,
            named.get(&(file_index[b as usize] as u32))?,
        );
        fa.iter().find_map(|&f| {
            let p = parts.facet_part[f];
            fb.iter()
                .filter(|&&g| parts.facet_part[g] != p)
                .find(|&&g| points_of(f) == points_of(g))
                .map(|&g| {
                    let q = parts.facet_part[g];
                    (p.min(q), p.max(q))
                })
        })
    };
    let mut cracks: Vec<((u16, u16), usize)> = Vec::new();
    let mut duplicate = None;
    for run in order
        .chunk_by(|&a, &b| key(a) == key(b))
        .filter(|run| run.len() > 1)
    {
        for (i, &a) in run.iter().enumerate() {
            for &b in run[i + 1..].iter().filter(|&&b| same_body(a, b)) {
                match crack(a, b) {
                    Some(faces) => match cracks.iter_mut().find(|c| c.0 == faces) {
                        Some(c) => c.1 += 1,
                        None => cracks.push((faces, 1)),
                    },
                    None => {
                        duplicate.get_or_insert([a.min(b), a.max(b)]);
                    }
                }
            }
        }
    }
    if let Some(w) = duplicate {
        return Err(src.whole(format!(
            "nodes {} and {} of one body are at the same point {:?} (duplicate nodes: the \
             geometry is not merged, which would cut the body; merge duplicates in Gmsh, e.g. \
             with Geometry.Tolerance / `Coherence;`; nodes of two different bodies may \
             coincide, and so may the nodes of a crack's two faces when each face is a \
             physical group of its own)",
            node_tags[w[0] as usize],
            node_tags[w[1] as usize],
            key(w[0])
        )));
    }
    for ((p, q), n) in cracks {
        notes.push(format!(
            "{n} pairs of coincident nodes of one body lie on the boundary parts `{}` and \
             `{}`: the body is cut there (a crack), its two faces free surfaces unless a \
             `[[contact]]` pair joins them (`against`)",
            parts.part_names[p as usize], parts.part_names[q as usize]
        ));
    }
    Ok((coords, node_tags, new_index))
}
