//! hemicontact's verification report: every integration test of the library, in one binary.
//!
//! One module per capability (`bulk`, `contact`, `bodies`, `solver`, `input`, `output`, `paper`),
//! one file per verified property; `common` holds the shared helpers (a deterministic
//! pseudo-random generator, scenario fixtures, closed-form Lamé constants, the VTU reader, the
//! fuzz harness). Run one capability with `cargo test -p hemicontact --test main contact::`.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

mod bodies;
mod bulk;
mod contact;
mod input;
mod output;
mod paper;
mod solver;
