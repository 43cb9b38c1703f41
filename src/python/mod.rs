//! pyo3 bindings: the `tcarod._core` extension module.
//!
//! Thin wrappers only: every function converts its arguments, calls the
//! pyo3-free core and converts back. Errors map to Python in `errors.rs`.

mod args;
mod batch;
mod bench;
mod errors;
mod fixtures;
mod inverse;
mod material;
mod outcome;
mod results;
mod rod;
mod stability;
mod tca;
mod to_py;

use pyo3::prelude::*;

pub(crate) use args::{count_or, counts, reals, vec3_arg, Real, MAX_SEQUENCE};
pub use errors::{ConvergenceError, UnstableEquilibriumError};
pub(crate) use to_py::{pb, pf, ps, pv};

pyo3::create_exception!(
    tcarod._core,
    UnitsWarning,
    pyo3::exceptions::PyUserWarning,
    "Sizes that are valid SI numbers but look like millimetres (a body longer \
     than 10 m, a section wider than 1 m, a TCA coil diameter above 0.1 m)."
);

/// Warn with [`UnitsWarning`].
pub(crate) fn warn_units(py: Python<'_>, msg: String) -> PyResult<()> {
    PyErr::warn(
        py,
        &py.get_type::<UnitsWarning>(),
        &std::ffi::CString::new(msg)?,
        1,
    )
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("ConvergenceError", m.py().get_type::<ConvergenceError>())?;
    m.add("UnitsWarning", m.py().get_type::<UnitsWarning>())?;
    m.add(
        "UnstableEquilibriumError",
        m.py().get_type::<UnstableEquilibriumError>(),
    )?;
    material::register(m)?;
    tca::register(m)?;
    rod::register(m)?;
    inverse::register(m)?;
    results::register(m)?;
    batch::register(m)?;
    bench::register(m)?;
    stability::register(m)?;
    fixtures::register(m)?;
    Ok(())
}
