//! pyo3 bindings: the `tcarod._core` extension module.
//!
//! Thin wrappers only: every function converts its arguments, calls the
//! pyo3-free core and converts back. Errors map to Python in `errors.rs`.

mod batch;
mod errors;
mod inverse;
mod rod;
mod stability;
mod tca;

use pyo3::prelude::*;

pub use errors::ConvergenceError;

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("ConvergenceError", m.py().get_type::<ConvergenceError>())?;
    tca::register(m)?;
    rod::register(m)?;
    inverse::register(m)?;
    batch::register(m)?;
    stability::register(m)?;
    Ok(())
}
