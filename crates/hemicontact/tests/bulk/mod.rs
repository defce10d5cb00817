//! The elastic body: P1 elements, patch tests, manufactured solutions with measured orders, material and locking laws, several materials, meshes, stresses and the small-deformation check.

mod convergence;
mod convergence_3d;
mod fem;
mod grading;
mod laws;
mod locking_sets;
mod material_laws;
mod materials;
mod mesh;
mod patch;
mod small_deformation;
mod stress_output;
mod tangled;
mod three_d;
