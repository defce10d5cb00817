//! ParaView's parallel format (`.pvtu`) of a [`VtuWriter`]'s data: one `.vtu` piece per
//! process that owns cells, and the index naming them.

use super::{Array, VtuWriter};
use std::fmt::Write as _;

impl VtuWriter<'_> {
    /// The files of the same data split into pieces, as ParaView's parallel format: piece
    /// `r` (`{stem}_{r}.vtu`) holds the cells `pieces[r]` and the nodes they use (in
    /// increasing order), every array restricted to them, plus the point array `node_id`
    /// and the cell array `cell_id` (their numbers in the whole mesh, from 0); last the
    /// index `{stem}.pvtu` naming the pieces. Every piece repeats the `FieldData`. A node on
    /// the border of two pieces is in both, with the same values. An empty `pieces[r]` (a
    /// rank that owns no cell of a mesh smaller than the launch) gives no file and is not
    /// named in the index: a piece of no points is not read by every reader (meshio refuses
    /// it), and a piece with nothing in it adds nothing.
    ///
    /// # Panics
    /// If a cell number is out of range.
    pub fn parallel_files(&self, pieces: &[Vec<u32>], stem: &str) -> Vec<(String, Vec<u8>)> {
        let mut files: Vec<(String, Vec<u8>)> = pieces
            .iter()
            .enumerate()
            .filter(|(_, cells)| !cells.is_empty())
            .map(|(r, cells)| (format!("{stem}_{r}.vtu"), self.encode(Some(cells))))
            .collect();
        let mut xml = String::from(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" \
             byte_order=\"LittleEndian\" header_type=\"UInt64\">\n\
             <PUnstructuredGrid GhostLevel=\"0\">\n",
        );
        // A section's declarations: the arrays of every piece, then the piece's own ids.
        let declare = |section: &str, arrays: &[Array], id: &str| {
            let mut x = format!("<P{section}>\n");
            for a in arrays {
                let _ = writeln!(
                    x,
                    "<PDataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\"/>",
                    a.data.type_name(),
                    a.name,
                    a.components
                );
            }
            let _ = writeln!(
                x,
                "<PDataArray type=\"Int64\" Name=\"{id}\" NumberOfComponents=\"1\"/>"
            );
            let _ = writeln!(x, "</P{section}>");
            x
        };
        xml.push_str(&declare("PointData", &self.point, "node_id"));
        xml.push_str(&declare("CellData", &self.cell, "cell_id"));
        xml.push_str(
            "<PPoints>\n<PDataArray type=\"Float64\" Name=\"Points\" \
             NumberOfComponents=\"3\"/>\n</PPoints>\n",
        );
        for (name, _) in &files {
            let _ = writeln!(xml, "<Piece Source=\"{name}\"/>");
        }
        xml.push_str("</PUnstructuredGrid>\n</VTKFile>\n");
        files.push((format!("{stem}.pvtu"), xml.into_bytes()));
        files
    }
}
