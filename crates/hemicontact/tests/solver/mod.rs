//! The solver: the certificate, local scales and units, uniqueness, determinism, interruption and observation, load stepping, the linear solvers and the assembly's parity across threads and parts.

mod assembly_parity;
mod certificate;
mod determinism;
mod factor_reuse;
mod interrupt;
mod linear_solver;
mod loading;
mod local_scales;
mod multigrid;
mod observer;
mod scale_invariance;
mod substructures;
mod uniqueness;
