//! Input: scenarios and Gmsh files that must be read or refused with a clear error, and their fuzzing.

mod fuzz_gmsh;
mod fuzz_scenario;
mod gmsh;
mod scenario_input;
mod validation;
