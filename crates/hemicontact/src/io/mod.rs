//! Output files, one writer per format: VTK UnstructuredGrid (`.vtu`, its arrays
//! zlib-compressed in VTK's block layout), ParaView collections of datasets (`.pvd`), the
//! contact table (`.csv`), JSON summaries (with the totals over each contact part), the
//! tables of convergence studies, Gmsh meshes (`.msh`); the result files of a solution
//! written together (each file written atomically, [`crate::atomic_file`]), and result sets (the files of one run, put in
//! place as a unit).

pub mod bodies;
pub mod contact_totals;
pub mod csv;
pub mod msh;
pub mod pvd;
pub mod result_set;
pub mod results;
pub mod study_table;
pub mod summary;
pub mod vtu;
pub mod zlib_blocks;
