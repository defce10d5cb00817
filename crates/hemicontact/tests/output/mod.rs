//! Output: result sets, `solution.vtu` and `.pvd` read back by every reader, and the documentation against the code.

mod docs;
mod result_set;
mod vtu_output;
mod vtu_readers;
