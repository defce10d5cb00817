//! The native part of the Python package `hemicontact`: scenarios, meshes and solves of
//! the Rust library, exchanged with Python as dictionaries, little-endian byte buffers (which
//! the Python part wraps as numpy arrays without a copy of the data per element) and JSON.
//! The user-facing API (`hemicontact.load`, `hemicontact.solve`, `Result`, …) is the Python
//! code in `python/hemicontact/`; this module is `hemicontact._core`.

mod convert;
mod errors;
mod interrupt;
mod laws;
mod mesh;
mod scenario;
mod solution;

use pyo3::prelude::*;

/// The module `hemicontact._core`.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("ScenarioError", m.py().get_type::<errors::ScenarioError>())?;
    m.add_class::<scenario::NativeScenario>()?;
    m.add_class::<mesh::NativeMesh>()?;
    m.add_class::<solution::NativeSolution>()?;
    m.add_function(wrap_pyfunction!(solution::solve, m)?)?;
    m.add_function(wrap_pyfunction!(solution::convergence, m)?)?;
    m.add_function(wrap_pyfunction!(solution::load_path, m)?)?;
    Ok(())
}
