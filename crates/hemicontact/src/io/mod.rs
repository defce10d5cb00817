//! Output files: VTK UnstructuredGrid (`.vtu`), JSON summaries, atomic file writing.

pub mod atomic;
pub mod summary;
pub mod vtu;
