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

pub use errors::{ConvergenceError, UnstableEquilibriumError};

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
    tca::register(m)?;
    rod::register(m)?;
    inverse::register(m)?;
    batch::register(m)?;
    stability::register(m)?;
    Ok(())
}

/// A float in Python syntax that round-trips (`repr(float)` and Rust's `{:?}`
/// both print the shortest round-trip digits); `inf`/`nan` as Python spells
/// them inside `float(...)`.
pub(crate) fn pf(x: f64) -> String {
    if x.is_finite() {
        format!("{x:?}")
    } else {
        format!("float('{x}')")
    }
}

/// A string literal in Python syntax (single quotes, as `repr(str)`).
pub(crate) fn ps(s: &str) -> String {
    let mut out = String::from("'");
    for c in s.chars() {
        match c {
            '\'' => out.push_str("\\'"),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            c => out.push(c),
        }
    }
    out.push('\'');
    out
}

/// A vector `(x, y, z)` in Python syntax.
pub(crate) fn pv(v: &[f64]) -> String {
    let items: Vec<String> = v.iter().map(|x| pf(*x)).collect();
    format!("[{}]", items.join(", "))
}

/// A bool in Python syntax.
pub(crate) fn pb(b: bool) -> &'static str {
    if b {
        "True"
    } else {
        "False"
    }
}

/// Hash of a text (for `__hash__` of immutable value objects, consistent
/// with `__eq__` because the text holds every field).
pub(crate) fn hash_text(s: &str) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    s.hash(&mut h);
    h.finish()
}

/// A real-number argument with the strict contract of issue 12: `float`,
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
        Ok(Real(obj.extract::<errors::Real>()?.0))
    }
}

/// `TypeError` unless `obj` may be read as a real number.
fn reject_non_real(obj: &Bound<'_, PyAny>) -> PyResult<()> {
    use pyo3::exceptions::PyTypeError;
    use pyo3::types::{PyByteArray, PyBytes, PyComplex, PyString};
    let bad = obj.is_none()
        || obj.is_instance_of::<PyString>()
        || obj.is_instance_of::<PyBytes>()
        || obj.is_instance_of::<PyByteArray>()
        || obj.is_instance_of::<PyComplex>()
        || is_numpy_complex(obj);
    if bad {
        return Err(PyTypeError::new_err(format!(
            "expected a real number, not {}",
            obj.get_type().name()?
        )));
    }
    Ok(())
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
/// other than `expect` (if given) or beyond [`MAX_SEQUENCE`]. A scalar is
/// read as a list of one when `expect` allows it. Never trusts `__len__`
/// for allocation.
pub(crate) fn reals(
    name: &str,
    obj: &Bound<'_, PyAny>,
    expect: Option<usize>,
) -> PyResult<Vec<f64>> {
    use pyo3::exceptions::{PyTypeError, PyValueError};
    use pyo3::types::{PyByteArray, PyBytes, PyString};
    if obj.is_instance_of::<PyString>()
        || obj.is_instance_of::<PyBytes>()
        || obj.is_instance_of::<PyByteArray>()
    {
        return Err(PyTypeError::new_err(format!(
            "{name}: expected a sequence of real numbers, not {}",
            obj.get_type().name()?
        )));
    }
    // a scalar (a number, or a 0-d array): one value
    let is_scalar = obj.hasattr("__float__")? && !obj.hasattr("__len__")?
        || obj
            .getattr("ndim")
            .map(|n| n.eq(0).unwrap_or(false))
            .unwrap_or(false);
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
                "{name}: more than {} values (the cap per call)",
                limit.max(MAX_SEQUENCE)
            )));
        }
        let item = item?;
        let x = item
            .extract::<Real>()
            .map_err(|e| PyTypeError::new_err(format!("{name}[{k}]: {}", e.value(obj.py()))))?;
        out.push(x.0);
    }
    check_len(name, out, expect)
}

fn check_len(name: &str, v: Vec<f64>, expect: Option<usize>) -> PyResult<Vec<f64>> {
    match expect {
        Some(n) if v.len() != n => Err(pyo3::exceptions::PyValueError::new_err(format!(
            "{name}: expected {n} values, got {}",
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
    use pyo3::exceptions::{PyTypeError, PyValueError};
    use pyo3::types::PyBool;
    if obj.is_instance_of::<PyBool>() {
        return Err(PyTypeError::new_err(format!(
            "{name}: expected an integer, not bool"
        )));
    }
    let v: i128 = match obj.extract::<i64>() {
        Ok(v) => v as i128,
        Err(e) if e.is_instance_of::<pyo3::exceptions::PyOverflowError>(obj.py()) => {
            if obj.gt(0)? {
                i128::MAX
            } else {
                i128::MIN
            }
        }
        Err(_) => {
            return Err(PyTypeError::new_err(format!(
                "{name}: expected an integer, not {}",
                obj.get_type().name()?
            )))
        }
    };
    if v < lo as i128 || v > hi as i128 {
        let shown = if v == i128::MAX || v == i128::MIN {
            obj.str()?.to_string()
        } else {
            v.to_string()
        };
        let shown = if shown.len() > 40 {
            format!("{}...", &shown[..40])
        } else {
            shown
        };
        return Err(PyValueError::new_err(format!(
            "invalid {name} = {shown}: allowed {lo} <= {name} <= {hi}"
        )));
    }
    Ok(v as usize)
}

/// Integer list argument (e.g. `groups`), each in `[0, hi]`, at most [`MAX_SEQUENCE`] long.
pub(crate) fn counts(name: &str, obj: &Bound<'_, PyAny>, hi: usize) -> PyResult<Vec<usize>> {
    use pyo3::exceptions::{PyTypeError, PyValueError};
    use pyo3::types::{PyByteArray, PyBytes, PyString};
    if obj.is_instance_of::<PyString>()
        || obj.is_instance_of::<PyBytes>()
        || obj.is_instance_of::<PyByteArray>()
    {
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
                "{name}: more than {MAX_SEQUENCE} values (the cap per call)"
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
