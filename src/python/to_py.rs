//! Values handed back to Python: Python-syntax text for `repr`, NumPy
//! arrays, and the pickle / `==` / `hash` support shared by the value objects.

use nalgebra::{DMatrix, Matrix3, Vector3};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

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

/// A 3-vector as a NumPy array of shape `(3,)`.
pub(crate) fn vec3<'py>(py: Python<'py>, v: &Vector3<f64>) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, v.as_slice())
}

/// A 3x3 matrix as a NumPy array of shape `(3, 3)` (row-major, as NumPy).
pub(crate) fn mat3<'py>(py: Python<'py>, m: &Matrix3<f64>) -> Bound<'py, PyArray2<f64>> {
    let rows: Vec<Vec<f64>> = (0..3)
        .map(|i| (0..3).map(|j| m[(i, j)]).collect())
        .collect();
    PyArray2::from_vec2(py, &rows).expect("3x3")
}

/// `n` 3-vectors as a NumPy array of shape `(n, 3)`.
pub(crate) fn stack3<'py>(py: Python<'py>, v: &[Vector3<f64>]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = v.iter().flat_map(|x| [x.x, x.y, x.z]).collect();
    PyArray1::from_vec(py, flat)
        .reshape([v.len(), 3])
        .expect("n x 3")
}

/// A matrix as a NumPy array of shape `(rows, cols)` (row-major, as NumPy).
pub(crate) fn dmat<'py>(py: Python<'py>, m: &DMatrix<f64>) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = (0..m.nrows())
        .flat_map(|i| (0..m.ncols()).map(move |j| m[(i, j)]))
        .collect();
    PyArray1::from_vec(py, flat)
        .reshape([m.nrows(), m.ncols()])
        .expect("shape")
}

/// What `__reduce__` returns: a rebuilding callable and its arguments.
pub(crate) type Reduce<'py, A> = PyResult<(Bound<'py, PyAny>, A)>;

/// What `__getnewargs_ex__` returns: positional and keyword constructor arguments.
pub(crate) type NewArgs<'py> = PyResult<(Bound<'py, PyTuple>, Bound<'py, PyDict>)>;

/// `__reduce__` of an object rebuilt by the private `tcarod._core` function
/// `restore` (e.g. `"_restore_section"`) called with `args`.
pub(crate) fn reduce_with<'py, A>(py: Python<'py>, restore: &str, args: A) -> Reduce<'py, A> {
    Ok((py.import("tcarod._core")?.getattr(restore)?, args))
}

/// `__getnewargs_ex__` of an object rebuilt by its constructor from keywords only.
pub(crate) fn keyword_args<'py>(kwargs: Bound<'py, PyDict>) -> NewArgs<'py> {
    Ok((PyTuple::empty(kwargs.py()), kwargs))
}

/// `__getnewargs_ex__` of an object rebuilt by its constructor from positional arguments only.
pub(crate) fn positional_args<'py, A>(args: A, py: Python<'py>) -> NewArgs<'py>
where
    A: IntoPyObject<'py, Target = PyTuple, Output = Bound<'py, PyTuple>>,
    PyErr: From<A::Error>,
{
    Ok((args.into_pyobject(py)?, PyDict::new(py)))
}

/// `impl Hash` for a value object from a text that holds every field (its
/// `repr` or its identity), so that `#[pyclass(eq, hash)]` gives a `__hash__`
/// consistent with `==`.
macro_rules! hash_by_text {
    ($ty:ty, |$s:ident| $text:expr) => {
        impl std::hash::Hash for $ty {
            fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
                let $s = self;
                std::hash::Hash::hash(&$text, state);
            }
        }
    };
}
pub(crate) use hash_by_text;

/// A constructor call in Python syntax: `callee(k1=v1, k2=v2)` (round-trips with `eval`).
pub(crate) fn call_repr(callee: &str, fields: &[(&str, f64)]) -> String {
    let args: Vec<String> = fields
        .iter()
        .map(|(k, v)| format!("{k}={}", pf(*v)))
        .collect();
    format!("{callee}({})", args.join(", "))
}

/// Named values as a Python `dict` (e.g. constructor keywords).
pub(crate) fn fields_dict<'py>(
    py: Python<'py>,
    fields: &[(&str, f64)],
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (k, v) in fields {
        d.set_item(k, v)?;
    }
    Ok(d)
}

/// Getters `name -> NumPy array (3,)` of the 3-vector fields `self.inner.name`,
/// each with its docstring.
macro_rules! vec3_getters {
    ($ty:ty { $($name:ident => $doc:literal),* $(,)? }) => {
        #[pymethods]
        impl $ty {
            $(
                #[doc = $doc]
                #[getter]
                fn $name<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
                    $crate::python::to_py::vec3(py, &self.inner.$name)
                }
            )*
        }
    };
}
pub(crate) use vec3_getters;
