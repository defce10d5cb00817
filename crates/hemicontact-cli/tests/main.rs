//! The command-line program's tests, in one binary: each module runs `hemicontact` as a
//! user would and checks what it prints, the files it writes and its exit codes.
//! `mpi_cli` (under `mpirun`, cargo feature `petsc`) is a binary of its own.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

mod certificate_cli;
mod cli;
mod console_cli;
mod gmsh_cli;
mod hardening;
mod loading_cli;
mod notes_cli;
mod paper_cli;
mod result_sets;
