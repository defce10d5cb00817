//! Output files: VTK UnstructuredGrid (`.vtu`), JSON summaries, Gmsh meshes (`.msh`), atomic
//! file writing, and result sets (the files of one run, put in place as a unit).

pub mod atomic;
pub mod msh;
pub mod result_set;
pub mod summary;
pub mod vtu;
