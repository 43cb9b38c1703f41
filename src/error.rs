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
    ///
    /// Displayed as `invalid NAME = VALUE UNIT: allowed RANGE`: the unit is
    /// read from the trailing `[unit]` of `name` and printed after the value,
    /// which is written as a person would ([`human`]: `0.004`, `170`, `1e-300`).
    #[error("{}", param_message(name, *value, allowed))]
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
    /// The IVPs a solve spent before it failed ([`Error::NotConverged`]'s
    /// `evaluations`); 0 for an error that reports no work.
    pub fn evaluations(&self) -> usize {
        match self {
            Error::NotConverged { evaluations, .. } => *evaluations,
            _ => 0,
        }
    }

    /// The best residual of a failed solve ([`Error::NotConverged`]);
    /// infinite for any other error.
    pub fn best_residual(&self) -> f64 {
        match self {
            Error::NotConverged { residual, .. } => *residual,
            _ => f64::INFINITY,
        }
    }

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

/// `invalid NAME = VALUE UNIT: allowed RANGE`, the unit taken from the last
/// `[unit]` of `name` (an index such as `inputs[0]` is not a unit; `[-]`,
/// dimensionless, prints no unit).
fn param_message(name: &str, value: f64, allowed: &str) -> String {
    let (bare, unit) = split_unit(name);
    let unit = match unit {
        Some(u) if u != "-" => format!(" {u}"),
        _ => String::new(),
    };
    format!("invalid {bare} = {}{unit}: allowed {allowed}", human(value))
}

/// `name` without its unit and the unit: `"temperature [C]"` gives
/// `("temperature", Some("C"))`, `"inputs[0] (temperature [C])"` gives
/// `("inputs[0] (temperature)", Some("C"))`; a bracket holding only digits
/// (an index) is part of the name.
pub fn split_unit(name: &str) -> (String, Option<&str>) {
    let mut search = name.len();
    while let Some(open) = name[..search].rfind('[') {
        if let Some(len) = name[open..].find(']') {
            let inner = &name[open + 1..open + len];
            if !inner.is_empty() && !inner.chars().all(|c| c.is_ascii_digit()) {
                let head = name[..open].trim_end();
                let tail = &name[open + len + 1..];
                return (format!("{head}{tail}"), Some(inner));
            }
        }
        search = open;
    }
    (name.to_string(), None)
}

/// `x` as a person writes it: at most 10 significant digits, trailing zeros
/// dropped (`4`, `0.004`, `170`, `0.3` for `0.1 + 0.2`), an exponent only
/// far from 1 (`1e-300`, `2.5e+20`), `inf`, `-inf`, `NaN` as such. For an
/// input echoed back: every digit the user typed survives.
pub fn human(x: f64) -> String {
    to_digits(x, 10)
}

/// A computed quantity for a message: [`human`] to 6 significant digits
/// (`31.9074`, `0.142278`), the precision of a reported result, not of an
/// echoed input.
pub fn significant(x: f64) -> String {
    to_digits(x, 6)
}

/// `x` to at most `digits` significant digits (see [`human`]).
fn to_digits(x: f64, digits: i32) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    if x == 0.0 {
        return "0".to_string();
    }
    let ax = x.abs();
    if (1e-4..1e15).contains(&ax) {
        let magnitude = ax.log10().floor() as i32;
        let decimals = (digits - 1 - magnitude).max(0) as usize;
        let mut s = format!("{x:.decimals$}");
        if s.contains('.') {
            s = s.trim_end_matches('0').trim_end_matches('.').to_string();
        }
        // rounding can carry into the next decade (9.99999999995e-5): still fine
        s
    } else {
        let mantissa_digits = (digits - 1) as usize;
        let s = format!("{x:.mantissa_digits$e}");
        let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
        let mantissa = if mantissa.contains('.') {
            mantissa.trim_end_matches('0').trim_end_matches('.')
        } else {
            mantissa
        };
        let exponent = exponent.parse::<i32>().unwrap_or(0);
        format!(
            "{mantissa}e{}{}",
            if exponent < 0 { "-" } else { "+" },
            exponent.abs()
        )
    }
}

/// A length \[m\] for a message: in millimetres below 1 m (`6.85 mm`), in
/// metres from 1 m (`4 m`).
pub fn length_text(x: f64) -> String {
    if x.is_finite() && x.abs() < 1.0 {
        format!("{} mm", human(x * 1e3))
    } else {
        format!("{} m", human(x))
    }
}

/// Lengths \[m\] above this, for a part of a soft robot (an offset, a coil
/// radius, a section size), look like millimetres given as metres.
pub const MM_LOOKING_M: f64 = 1.0;

/// Beyond this length \[m\] (10,000 mm) a value is no millimetre typo.
pub const MM_LOOKING_MAX_M: f64 = 1e4;

/// The hint added to a length error or warning whose `value` \[m\] looks
/// like millimetres (above [`MM_LOOKING_M`], up to [`MM_LOOKING_MAX_M`]):
/// `" (millimetres? lengths are in metres: 4 mm is 0.004 m)"`; empty otherwise.
pub fn mm_hint(value: f64) -> String {
    if value.is_finite() && value.abs() > MM_LOOKING_M && value.abs() <= MM_LOOKING_MAX_M {
        mm_question(value)
    } else {
        String::new()
    }
}

/// `" (millimetres? lengths are in metres: 4 mm is 0.004 m)"` for `value`
/// \[m\], whatever its size (for checks with their own threshold).
pub fn mm_question(value: f64) -> String {
    format!(
        " (millimetres? lengths are in metres: {} mm is {} m)",
        human(value),
        human(value * 1e-3)
    )
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_written_as_a_person_would() {
        assert_eq!(human(4.0), "4");
        assert_eq!(human(0.004), "0.004");
        assert_eq!(human(170.0), "170");
        assert_eq!(human(0.1 + 0.2), "0.3");
        assert_eq!(human(-2.5), "-2.5");
        assert_eq!(human(1e-300), "1e-300");
        assert_eq!(human(2.5e20), "2.5e+20");
        assert_eq!(human(f64::INFINITY), "inf");
        assert_eq!(human(f64::NAN), "NaN");
        assert_eq!(human(160.0000001), "160.0000001");
    }

    #[test]
    fn the_unit_follows_the_value() {
        let e = Error::param("temperature [C]", 170.0, "25 <= T <= 160 C");
        assert_eq!(
            e.to_string(),
            "invalid temperature = 170 C: allowed 25 <= T <= 160 C"
        );
        let e = Error::param("inputs[1] (temperature [C])", 170.0, "x");
        assert_eq!(
            e.to_string(),
            "invalid inputs[1] (temperature) = 170 C: allowed x"
        );
        let e = Error::param("length_ratio [-]", 0.0, "> 0");
        assert_eq!(e.to_string(), "invalid length_ratio = 0: allowed > 0");
        let e = Error::param("steps", 0.0, ">= 1");
        assert_eq!(e.to_string(), "invalid steps = 0: allowed >= 1");
        let e = Error::param("x [m]", 4.0, "finite");
        assert!(!e.to_string().contains("e0"));
    }

    #[test]
    fn millimetres_are_suspected_above_a_metre() {
        assert_eq!(
            mm_hint(4.0),
            " (millimetres? lengths are in metres: 4 mm is 0.004 m)"
        );
        assert_eq!(mm_hint(0.004), "");
        assert_eq!(mm_hint(1e300), "");
        assert_eq!(length_text(6.85e-3), "6.85 mm");
        assert_eq!(length_text(4.0), "4 m");
    }
}
