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
    "Inputs that are valid SI numbers but look like a unit mix-up: sizes that \
     look like millimetres (a body longer than 10 m, a section wider than 1 m, \
     a TCA coil diameter above 0.1 m, a routing offset or helix radius above \
     1 m, an anchor or a TCA length above 10 m), a Young's modulus outside \
     1 kPa-1 TPa, temperatures above 273 C (kelvin typed as Celsius), and a \
     density given without gravity (a weightless body)."
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

/// Registers part of the module's contents.
type Register = fn(&Bound<'_, PyModule>) -> PyResult<()>;

/// The module's parts: each is also the submodule `tcarod._core.<part>` (in
/// `sys.modules`), so that the stub package `tcarod/_core/` (one private stub
/// per part, re-exported by `__init__.pyi`) is checked part by part by
/// `mypy.stubtest`. Everything is re-exported at the top level, where Python
/// code imports it from; classes keep `__module__ == "tcarod._core"`.
const PARTS: [(&str, &[Register]); 8] = [
    ("_common", &[register_errors]),
    ("_tca", &[material::register, tca::register]),
    ("_rod", &[rod::register]),
    ("_solution", &[rod::register_solution]),
    ("_inverse", &[inverse::register, results::register]),
    ("_batch", &[batch::register, bench::register]),
    ("_stability", &[stability::register]),
    ("_fixtures", &[fixtures::register]),
];

fn register_errors(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("ConvergenceError", m.py().get_type::<ConvergenceError>())?;
    m.add("UnitsWarning", m.py().get_type::<UnitsWarning>())?;
    m.add(
        "UnstableEquilibriumError",
        m.py().get_type::<UnstableEquilibriumError>(),
    )
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    let modules = py.import("sys")?.getattr("modules")?;
    for (name, registers) in PARTS {
        let full = format!("tcarod._core.{name}");
        let part = PyModule::new(py, &full)?;
        for register in registers {
            register(&part)?;
        }
        for item in part.getattr("__all__")?.try_iter()? {
            let name: String = item?.extract()?;
            m.add(name.as_str(), part.getattr(name.as_str())?)?;
        }
        m.setattr(name, &part)?; // not in `__all__`: private
        modules.set_item(full, part)?;
    }
    Ok(())
}
