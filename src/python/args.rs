//! Reading Python arguments strictly (real numbers, integer counts,
//! sequences): a wrong Python type is a `TypeError`, a value out of range a
//! `ValueError` naming the argument and its range, never a silent
//! conversion. One reader per kind, shared by every class.

use pyo3::exceptions::{PyOverflowError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyByteArray, PyBytes, PyString};

use crate::error::Error;
use crate::limits::{CountLimit, EVALUATIONS, ITERATIONS, STEPS, TIME_LIMIT_ALLOWED};
use crate::shooting::SolveOptions;

/// A real-number argument, read strictly: `float`,
/// `int` (beyond the double range: `+-inf`, rejected downstream with a
/// `ValueError` naming the argument), NumPy reals, anything with
/// `__float__` that is not complex. `str`, `bytes`, `None` and complex
/// numbers (Python or NumPy, whose `__float__` would drop the imaginary part)
/// raise `TypeError`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Real(pub f64);

impl<'py> FromPyObject<'_, 'py> for Real {
    type Error = PyErr;

    fn extract(obj: Borrowed<'_, 'py, PyAny>) -> PyResult<Self> {
        use pyo3::types::{PyFloat, PyInt};
        if !(obj.is_exact_instance_of::<PyFloat>() || obj.is_exact_instance_of::<PyInt>()) {
            reject_non_real(&obj)?;
        }
        saturating_f64(&obj).map(Real)
    }
}

/// `obj` as `f64`, except that an `int` beyond the double range saturates to
/// `+-inf` (rejected downstream with a `ValueError` naming the argument)
/// instead of raising `OverflowError`.
fn saturating_f64(obj: &Bound<'_, PyAny>) -> PyResult<f64> {
    match obj.extract::<f64>() {
        Ok(v) => Ok(v),
        Err(e) if e.is_instance_of::<PyOverflowError>(obj.py()) => Ok(if obj.gt(0)? {
            f64::INFINITY
        } else {
            f64::NEG_INFINITY
        }),
        Err(e) => Err(e),
    }
}

/// `TypeError` unless `obj` may be read as a real number.
fn reject_non_real(obj: &Bound<'_, PyAny>) -> PyResult<()> {
    let bad = obj.is_none()
        || is_text(obj)
        || obj.is_instance_of::<pyo3::types::PyComplex>()
        || is_numpy_complex(obj);
    if bad {
        return Err(PyTypeError::new_err(format!(
            "expected a real number, not {}",
            obj.get_type().name()?
        )));
    }
    Ok(())
}

/// `str`, `bytes` or `bytearray`: iterable, but never a sequence of numbers.
fn is_text(obj: &Bound<'_, PyAny>) -> bool {
    obj.is_instance_of::<PyString>()
        || obj.is_instance_of::<PyBytes>()
        || obj.is_instance_of::<PyByteArray>()
}

fn is_numpy_complex(obj: &Bound<'_, PyAny>) -> bool {
    // NumPy complex scalars and complex 0-d arrays: their dtype kind is 'c'
    obj.getattr("dtype")
        .and_then(|d| d.getattr("kind"))
        .and_then(|k| k.extract::<String>())
        .map(|k| k == "c")
        .unwrap_or(false)
}

/// Largest sequence accepted from Python where a sequence of numbers is due
/// (inputs of one solve, variables, groups): far above any robot, far below
/// anything that could exhaust memory.
pub(crate) const MAX_SEQUENCE: usize = 10_000;

/// `obj` as a list of reals, named `name` in errors: `TypeError` for
/// `str`/`bytes`/non-sequences or non-real items, `ValueError` for a length
/// other than `expect` (if given) or beyond [`MAX_SEQUENCE`], and for an
/// array or nested sequence of more than one dimension (naming its shape).
/// A scalar is read as a list of one when `expect` allows it. Never trusts
/// `__len__` for allocation.
pub(crate) fn reals(
    name: &str,
    obj: &Bound<'_, PyAny>,
    expect: Option<usize>,
) -> PyResult<Vec<f64>> {
    let what = match expect {
        Some(n) => format!("({n},)"),
        None => "(n,)".to_string(),
    };
    reals_shaped(name, obj, expect, &what)
}

/// [`reals`] for one input per actuator of a robot with `n` actuators: a
/// wrong shape is `invalid inputs: expected shape (n,) (one input per
/// actuator), got (2, 1)`; the length itself is checked by the robot.
pub(crate) fn one_per_actuator(name: &str, obj: &Bound<'_, PyAny>, n: usize) -> PyResult<Vec<f64>> {
    reals_shaped(name, obj, None, &format!("({n},) (one input per actuator)"))
}

/// [`reals`], a shape error stating `expected shape {what}`.
fn reals_shaped(
    name: &str,
    obj: &Bound<'_, PyAny>,
    expect: Option<usize>,
    what: &str,
) -> PyResult<Vec<f64>> {
    if is_text(obj) {
        return Err(PyTypeError::new_err(format!(
            "{name}: expected a sequence of real numbers, not {}",
            obj.get_type().name()?
        )));
    }
    let ndim = obj
        .getattr("ndim")
        .ok()
        .and_then(|n| n.extract::<i64>().ok());
    if ndim.is_some_and(|n| n >= 2) {
        return Err(shape_error(name, obj, what));
    }
    // a scalar (a number, or a 0-d array): one value
    let is_scalar = obj.hasattr("__float__")? && !obj.hasattr("__len__")? || ndim == Some(0);
    if is_scalar {
        let x = obj
            .extract::<Real>()
            .map_err(|e| PyTypeError::new_err(format!("{name}: {}", e.value(obj.py()))))?;
        return check_len(name, vec![x.0], expect);
    }
    let iter = obj.try_iter().map_err(|_| {
        PyTypeError::new_err(format!(
            "{name}: expected a sequence of real numbers, not {}",
            obj.get_type()
                .name()
                .map(|n| n.to_string())
                .unwrap_or_default()
        ))
    })?;
    let limit = expect.unwrap_or(MAX_SEQUENCE);
    let mut out = Vec::new();
    for (k, item) in iter.enumerate() {
        if k >= limit.max(MAX_SEQUENCE) {
            return Err(PyValueError::new_err(format!(
                "invalid {name}: more than {} values (the cap per call)",
                limit.max(MAX_SEQUENCE)
            )));
        }
        let item = item?;
        // an item that is itself a sequence or an array: a 2-D input
        let nested = !is_text(&item)
            && (item.hasattr("__len__")? && !item.hasattr("__float__")?
                || item
                    .getattr("ndim")
                    .ok()
                    .and_then(|n| n.extract::<i64>().ok())
                    .is_some_and(|n| n >= 1));
        if nested {
            return Err(shape_error(name, obj, what));
        }
        let x = item
            .extract::<Real>()
            .map_err(|e| PyTypeError::new_err(format!("{name}[{k}]: {}", e.value(obj.py()))))?;
        out.push(x.0);
    }
    check_len(name, out, expect)
}

/// `invalid NAME: expected shape WHAT, got SHAPE`, the shape as NumPy
/// reads it (`numpy.shape`; "a nested sequence" if NumPy cannot).
fn shape_error(name: &str, obj: &Bound<'_, PyAny>, what: &str) -> PyErr {
    let py = obj.py();
    let shape = py
        .import("numpy")
        .and_then(|np| np.call_method1("shape", (obj,)))
        .and_then(|s| s.extract::<Vec<usize>>())
        .map(|s| match s.as_slice() {
            [n] => format!("({n},)"),
            dims => format!(
                "({})",
                dims.iter()
                    .map(|d| d.to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        })
        .unwrap_or_else(|_| "a nested sequence".to_string());
    PyValueError::new_err(format!(
        "invalid {name}: expected shape {what}, got {shape}"
    ))
}

fn check_len(name: &str, v: Vec<f64>, expect: Option<usize>) -> PyResult<Vec<f64>> {
    match expect {
        Some(n) if v.len() != n => Err(PyValueError::new_err(format!(
            "invalid {name}: expected {n} values, got {}",
            v.len()
        ))),
        _ => Ok(v),
    }
}

/// `obj` (optional) as a 3-vector of finite reals named `name`.
pub(crate) fn vec3_arg(
    name: &str,
    obj: Option<&Bound<'_, PyAny>>,
    default: [f64; 3],
) -> PyResult<[f64; 3]> {
    match obj {
        None => Ok(default),
        Some(o) if o.is_none() => Ok(default),
        Some(o) => {
            let v = reals(name, o, Some(3))?;
            for (k, x) in v.iter().enumerate() {
                crate::error::finite(&format!("{name}[{k}]"), *x)?;
            }
            Ok([v[0], v[1], v[2]])
        }
    }
}

/// A non-negative integer argument within `[lo, hi]`, named `name`:
/// `TypeError` for non-integers (floats, str, bytes, None), `ValueError`
/// naming the range for negative or huge values (never `OverflowError`).
pub(crate) fn count(name: &str, obj: &Bound<'_, PyAny>, lo: usize, hi: usize) -> PyResult<usize> {
    let v = integer(name, obj)?;
    if v < lo as i128 || v > hi as i128 {
        return Err(out_of_range(
            name,
            obj,
            v,
            &format!("{lo} <= {name} <= {hi}"),
        ));
    }
    Ok(v as usize)
}

/// An integer option checked by the core against `limit` (see
/// [`crate::limits`]): `TypeError` for non-integers, `ValueError` naming the
/// range for values no `usize` holds; the core checks the range itself.
fn count_for(
    limit: &CountLimit,
    obj: Option<&Bound<'_, PyAny>>,
    default: usize,
) -> PyResult<usize> {
    let Some(o) = obj.filter(|o| !o.is_none()) else {
        return Ok(default);
    };
    let v = integer(limit.name, o)?;
    usize::try_from(v).map_err(|_| out_of_range(limit.name, o, v, &limit.allowed()))
}

/// `obj` as an integer named `name` (`TypeError` for bool and non-integers);
/// ints beyond `i64` saturate to `i128::MAX` / `MIN`.
fn integer(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<i128> {
    use pyo3::types::PyBool;
    if obj.is_instance_of::<PyBool>() {
        return Err(PyTypeError::new_err(format!(
            "{name}: expected an integer, not bool"
        )));
    }
    match obj.extract::<i64>() {
        Ok(v) => Ok(v as i128),
        Err(e) if e.is_instance_of::<PyOverflowError>(obj.py()) => {
            Ok(if obj.gt(0)? { i128::MAX } else { i128::MIN })
        }
        Err(_) => Err(PyTypeError::new_err(format!(
            "{name}: expected an integer, not {}",
            obj.get_type().name()?
        ))),
    }
}

/// The `ValueError` of an integer `v` (read from `obj`) outside `allowed`:
/// the core's wording, a saturated value shown as Python wrote it (at most 40 digits).
fn out_of_range(name: &str, obj: &Bound<'_, PyAny>, v: i128, allowed: &str) -> PyErr {
    let shown = if v == i128::MAX || v == i128::MIN {
        obj.str().map(|s| s.to_string()).unwrap_or_default()
    } else {
        v.to_string()
    };
    let shown = if shown.len() > 40 {
        format!("{}...", &shown[..40])
    } else {
        shown
    };
    PyValueError::new_err(format!("invalid {name} = {shown}: allowed {allowed}"))
}

/// Integer list argument (e.g. `groups`), each in `[0, hi]`, at most [`MAX_SEQUENCE`] long.
pub(crate) fn counts(name: &str, obj: &Bound<'_, PyAny>, hi: usize) -> PyResult<Vec<usize>> {
    if is_text(obj) {
        return Err(PyTypeError::new_err(format!(
            "{name}: expected a sequence of integers, not {}",
            obj.get_type().name()?
        )));
    }
    let iter = obj
        .try_iter()
        .map_err(|_| PyTypeError::new_err(format!("{name}: expected a sequence of integers")))?;
    let mut out = Vec::new();
    for (k, item) in iter.enumerate() {
        if k >= MAX_SEQUENCE {
            return Err(PyValueError::new_err(format!(
                "invalid {name}: more than {MAX_SEQUENCE} values (the cap per call)"
            )));
        }
        out.push(count(&format!("{name}[{k}]"), &item?, 0, hi)?);
    }
    Ok(out)
}

/// [`count`] of an optional argument, `default` when absent or `None`.
pub(crate) fn count_or(
    name: &str,
    obj: Option<&Bound<'_, PyAny>>,
    default: usize,
    lo: usize,
    hi: usize,
) -> PyResult<usize> {
    match obj {
        Some(o) if !o.is_none() => count(name, o, lo, hi),
        _ => Ok(default),
    }
}

/// Solver options from Python arguments, checked by the core
/// ([`SolveOptions::check_limits`], [`SolveOptions::validate`]): `steps` in
/// `1..=MAX_STEPS`, `max_iter` in `1..=MAX_ITER` (ValueError naming the
/// argument and range beyond; TypeError for non-integers), `tol` finite and > 0.
pub(crate) fn solve_options(
    steps: Option<&Bound<'_, PyAny>>,
    tol: Real,
    max_iter: Option<&Bound<'_, PyAny>>,
) -> PyResult<SolveOptions> {
    let defaults = SolveOptions::default();
    let steps = count_for(&STEPS, steps, defaults.steps)?;
    let max_iter = count_for(&ITERATIONS, max_iter, defaults.max_iter)?;
    options(steps, tol.0, max_iter)
}

/// The per-solve budget from Python arguments, checked by the core
/// ([`SolveOptions::check_limits`]): `max_evaluations` in `1..=1e8` IVPs
/// (default [`crate::shooting::DEFAULT_MAX_EVALUATIONS`]), `time_limit` in
/// `(0, 1e9]` s (default none).
pub(crate) fn budget_options(
    opts: &mut SolveOptions,
    max_evaluations: Option<&Bound<'_, PyAny>>,
    time_limit: Option<Real>,
) -> PyResult<()> {
    opts.max_evaluations = count_for(&EVALUATIONS, max_evaluations, opts.max_evaluations)?;
    if let Some(Real(t)) = time_limit {
        // NaN, negative and unrepresentable seconds are no duration at all
        let d = std::time::Duration::try_from_secs_f64(t)
            .map_err(|_| Error::param("time_limit [s]", t, TIME_LIMIT_ALLOWED))?;
        opts.time_limit = Some(d);
    }
    Ok(opts.check_limits()?)
}

pub(crate) fn options(steps: usize, tol: f64, max_iter: usize) -> PyResult<SolveOptions> {
    let o = SolveOptions {
        steps,
        tol,
        max_iter,
        ..Default::default()
    };
    o.check_limits()?;
    o.validate()?;
    Ok(o)
}
