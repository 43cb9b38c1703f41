//! The one place where core errors become Python exceptions.
//!
//! * `Error::InvalidParameter`, `Error::InvalidInput`, `Error::NoSolution`
//!   -> `ValueError` (the message names the field, its value and the allowed
//!   range);
//! * `Error::NotConverged`, `Error::Integration` -> `tcarod.ConvergenceError`
//!   (a `RuntimeError`) with attributes `residual` and `iterations`.

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

use crate::error::Error;

pyo3::create_exception!(
    _core,
    ConvergenceError,
    PyRuntimeError,
    "A solve stopped without meeting its tolerance. Attributes: `residual` \
     (final residual norm, dimensionless) and `iterations`."
);

impl From<Error> for PyErr {
    fn from(e: Error) -> PyErr {
        let msg = e.to_string();
        match e {
            Error::NotConverged {
                iterations,
                residual,
                ..
            } => convergence_error(msg, residual, iterations),
            Error::Integration { .. } => convergence_error(msg, f64::INFINITY, 0),
            _ => PyValueError::new_err(msg),
        }
    }
}

fn convergence_error(msg: String, residual: f64, iterations: usize) -> PyErr {
    Python::attach(|py| {
        let err = ConvergenceError::new_err(msg);
        let value = err.value(py);
        // Setting attributes on a fresh exception instance cannot fail in
        // practice; if it does, the exception is still raised without them.
        let _ = value.setattr("residual", residual);
        let _ = value.setattr("iterations", iterations);
        err
    })
}
