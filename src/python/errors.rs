//! The one place where core errors become Python exceptions.
//!
//! * `Error::InvalidParameter`, `Error::InvalidInput`, `Error::NoSolution`
//!   -> `ValueError` (the message names the field, its value and the allowed
//!   range: `invalid NAME = VALUE UNIT: allowed RANGE (reason)`, the value
//!   written by [`crate::error::human`] and the unit moved from the name's
//!   `[unit]` to after the value, as `tcarod._validate.real` writes it in
//!   Python);
//! * `Error::NotConverged`, `Error::Integration` -> `tcarod.ConvergenceError`
//!   (a `RuntimeError`) with attributes `residual` (best reached),
//!   `iterations`, `evaluations` (IVPs) and `reason` (`"iteration_limit"`,
//!   `"line_search"`, `"singular_jacobian"`, `"non_finite"`, `"other"`;
//!   `"integration"` for an IVP that could not be integrated), kept through
//!   pickling (they live in the instance `__dict__`);
//! * `Error::Interrupted` -> `KeyboardInterrupt` (see [`detach_interruptible`]).
//!
//! Arguments are read in `args.rs` ([`super::Real`]: a Python `int` too
//! large for a double becomes `+-inf`, which the core rejects with a
//! `ValueError` naming the argument, instead of an `OverflowError`; wrong
//! Python types stay `TypeError`). [`finite_output`] guards every value
//! handed back to Python: no binding returns NaN or inf.

use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError, PyValueError};
use pyo3::prelude::*;

use crate::error::{Error, Result};

/// Error unless `value` (a result about to be returned to Python) is finite.
/// Finite inputs that pass validation can still overflow or underflow inside
/// the law (e.g. a fibre diameter of 1e-300 m, whose fourth power is zero).
pub(crate) fn finite_output(name: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::input(
            name,
            format!(
                "the result is {value}: the inputs lie outside the range in which \
                 double precision can evaluate the TCA law"
            ),
        ))
    }
}

pyo3::create_exception!(
    tcarod._core,
    ConvergenceError,
    PyRuntimeError,
    "A solve stopped without meeting its tolerance.\n\n\
     Attributes\n\
     ----------\n\
     residual : float\n    \
     Best residual norm reached [-] (dimensionless).\n\
     iterations : int\n    \
     Iterations done [-].\n\
     evaluations : int\n    \
     IVPs integrated [-], failed attempts included.\n\
     reason : str\n    \
     Why it stopped: `\"iteration_limit\"`, `\"line_search\"`, \
     `\"singular_jacobian\"`, `\"non_finite\"`, `\"budget\"` (the IVP budget or \
     the time limit ran out), `\"other\"`, or `\"integration\"` (an IVP could \
     not be integrated)."
);

pyo3::create_exception!(
    tcarod._core,
    UnstableEquilibriumError,
    PyRuntimeError,
    "A solve required a stable equilibrium and converged to an unstable one.\n\n\
     Raised by `Robot.solve(..., stability=\"require\")` (or \
     `require_stable=True`).\n\n\
     Attributes\n\
     ----------\n\
     margin : float\n    \
     The equilibrium's stability margin [-], negative.\n\
     solution : Solution\n    \
     The unstable equilibrium (shape [m], tensions [N])."
);

impl From<Error> for PyErr {
    fn from(e: Error) -> PyErr {
        let msg = e.to_string();
        match e {
            Error::NotConverged {
                iterations,
                evaluations,
                residual,
                stop,
                ..
            } => convergence_error(msg, residual, iterations, evaluations, stop.name()),
            Error::Integration { .. } => convergence_error(msg, f64::INFINITY, 0, 1, "integration"),
            Error::Interrupted => PyKeyboardInterrupt::new_err(msg),
            _ => PyValueError::new_err(msg),
        }
    }
}

fn convergence_error(
    msg: String,
    residual: f64,
    iterations: usize,
    evaluations: usize,
    reason: &str,
) -> PyErr {
    Python::attach(|py| {
        let err = ConvergenceError::new_err(msg);
        let value = err.value(py);
        // Setting attributes on a fresh exception instance cannot fail in
        // practice; if it does, the exception is still raised without them.
        let _ = value.setattr("residual", residual);
        let _ = value.setattr("iterations", iterations);
        let _ = value.setattr("evaluations", evaluations);
        let _ = value.setattr("reason", reason);
        err
    })
}

/// Run `f` with the GIL released, answering Ctrl-C: the core's cancel check
/// ([`crate::solve::cancel`], polled every ~20 ms of work at most) briefly
/// reacquires the GIL and runs Python's signal handlers; a pending
/// `KeyboardInterrupt` stops the work with [`Error::Interrupted`], which
/// becomes `KeyboardInterrupt` again.
pub(crate) fn detach_interruptible<T: Send>(py: Python<'_>, f: impl FnOnce() -> T + Send) -> T {
    py.detach(|| {
        let check = || Python::attach(|py| py.check_signals().is_err());
        crate::solve::cancel::interruptible(&check, f)
    })
}
