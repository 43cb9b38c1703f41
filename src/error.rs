//! Structured errors of the numerical core.
//!
//! Every fallible function of the crate returns [`Result`]. The Python
//! bindings map these variants to Python exceptions in exactly one place
//! (`src/python/errors.rs`): argument errors become `ValueError`, failed
//! solves become `tcarod.ConvergenceError`.

/// Errors raised by the tcarod core.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A scalar argument is non-finite or outside its allowed range.
    #[error("invalid {name} = {value}: allowed {allowed}")]
    InvalidParameter {
        /// Name of the argument, with its unit (e.g. `temperature \[C\]`).
        name: String,
        /// The offending value (SI units).
        value: f64,
        /// Human-readable allowed range, e.g. `25 <= T <= 160 C`.
        allowed: String,
    },
    /// A structured argument (array shape, actuator layout, ...) is invalid.
    #[error("invalid {name}: {reason}")]
    InvalidInput {
        /// Name of the argument.
        name: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A scalar equation has no solution inside the allowed interval
    /// (e.g. no temperature in the material's range produces a requested
    /// displacement).
    #[error("no solution: {reason}")]
    NoSolution {
        /// Why no solution exists, naming the interval searched.
        reason: String,
    },
    /// A Newton (or other iterative) solve stopped without meeting its tolerance.
    #[error(
        "{solver} did not converge: best residual {residual:.3e} after {iterations} iterations, {evaluations} evaluations ({reason})"
    )]
    NotConverged {
        /// Which solver.
        solver: &'static str,
        /// Iterations performed.
        iterations: usize,
        /// IVPs (function evaluations) spent, failed attempts included.
        evaluations: usize,
        /// Best residual norm reached (dimensionless unless the solver says otherwise).
        residual: f64,
        /// Why it stopped.
        stop: StopReason,
        /// Details.
        reason: String,
    },
    /// A cancel check (e.g. Ctrl-C in Python) stopped the work.
    #[error("interrupted")]
    Interrupted,
    /// The rod's initial value problem could not be integrated (singular
    /// stiffness system, an actuator stretched past its straight-fibre limit,
    /// non-finite state).
    #[error("integration failed at s = {s:.6e} m: {reason}")]
    Integration {
        /// Arc length \[m\] at which integration failed.
        s: f64,
        /// Why.
        reason: String,
    },
}

/// Why an iterative solve stopped without converging.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum StopReason {
    /// The iteration limit was reached.
    IterationLimit,
    /// The line search could not reduce the merit function.
    LineSearch,
    /// The Jacobian was singular.
    SingularJacobian,
    /// A non-finite state or residual.
    NonFinite,
    /// The solve's work budget (IVPs or wall time) ran out.
    Budget,
    /// Another reason given in the message.
    Other,
}

impl StopReason {
    /// Snake-case name (the Python attribute `ConvergenceError.reason`).
    pub fn name(&self) -> &'static str {
        match self {
            StopReason::IterationLimit => "iteration_limit",
            StopReason::LineSearch => "line_search",
            StopReason::SingularJacobian => "singular_jacobian",
            StopReason::NonFinite => "non_finite",
            StopReason::Budget => "budget",
            StopReason::Other => "other",
        }
    }
}

/// Result alias of the crate.
pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    /// Shorthand for [`Error::InvalidParameter`].
    pub fn param(name: &str, value: f64, allowed: impl Into<String>) -> Self {
        Error::InvalidParameter {
            name: name.to_string(),
            value,
            allowed: allowed.into(),
        }
    }

    /// The same error with the name of its offending argument rewritten by
    /// `rename` (to say which element of an array or which actuator it was);
    /// other variants are returned unchanged.
    pub fn renamed(self, rename: impl FnOnce(&str) -> String) -> Self {
        match self {
            Error::InvalidParameter {
                name,
                value,
                allowed,
            } => Error::InvalidParameter {
                name: rename(&name),
                value,
                allowed,
            },
            Error::InvalidInput { name, reason } => Error::InvalidInput {
                name: rename(&name),
                reason,
            },
            other => other,
        }
    }

    /// Shorthand for [`Error::InvalidInput`].
    pub fn input(name: &str, reason: impl Into<String>) -> Self {
        Error::InvalidInput {
            name: name.to_string(),
            reason: reason.into(),
        }
    }
}

/// Check that `value` is finite and strictly positive.
pub fn positive(name: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::param(name, value, "finite and > 0"))
    }
}

/// Check that `value` is finite and non-negative.
pub fn non_negative(name: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::param(name, value, "finite and >= 0"))
    }
}

/// Check that `value` is finite.
pub fn finite(name: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::param(name, value, "a finite number"))
    }
}
