//! Bindings of the batch solver (`tcarod.batch`).

use numpy::{
    PyArray1, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods,
};
use pyo3::prelude::*;

use super::rod::{solve_options, PyRobot};
use super::{count_or, Real};
use crate::batch::{
    solve_batch as core_solve_batch, solve_batch_shapes, thread_count, BatchOptions,
};
use crate::error::Error;

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(solve_batch, m)?)?;
    m.add_function(wrap_pyfunction!(default_threads, m)?)?;
    Ok(())
}

type BatchArrays<'py> = (
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray3<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray1<i64>>,
    Bound<'py, PyArray1<i64>>,
    Bound<'py, PyArray1<bool>>,
    Option<Bound<'py, PyArray1<bool>>>,
    Option<Bound<'py, PyArray1<f64>>>,
    Option<ShapeArrays<'py>>,
);

/// Arc length `(nodes,)` [m] and positions `(n, nodes, 3)` [m] of a batch's shapes.
type ShapeArrays<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray3<f64>>);

/// The `stability` argument of `solve_batch`: a verdict per row or none.
fn batch_stability(policy: &str) -> PyResult<bool> {
    match policy {
        "report" => Ok(true),
        "off" => Ok(false),
        _ => Err(Error::input(
            "stability",
            format!("{policy:?}: must be 'report' or 'off' for a batch"),
        )
        .into()),
    }
}

/// Solve the forward problem for every row of ``inputs``, in the core.
///
/// The binding behind ``tcarod.batch.solve_batch`` (which returns a
/// ``BatchResult``); the GIL is released. Rows are cut into chunks of
/// ``chunk_size``, each solved in order with warm starts.
///
/// Parameters
/// ----------
/// robot : Robot
///     The robot.
/// inputs : numpy.ndarray
///     Shape ``(n, n_actuators)``: temperatures [C] for TCAs; at most
///     10,000,000 rows per call.
/// wrenches : numpy.ndarray, optional
///     Shape ``(n, 6)``: tip force [N] and moment [N m], world frame.
/// steps, tol, max_iter : optional
///     As for ``Robot.solve`` (``steps`` and ``max_iter`` 1 to 100,000).
/// chunk_size : int, optional
///     Rows per warm-started chunk, 1 to 10,000,000 (default 256).
/// threads : int, optional
///     Worker threads, 0 (default: all cores) to 1024.
/// warm : bool, optional
///     Warm-start each row from the previous row of its chunk (default).
/// stability : {"report", "off"}, optional
///     ``"report"``: one tangent integration per converged row for its
///     verdict; ``"off"``: none.
/// shapes : bool, optional
///     Also return every row's centre line (recorded by the solve: no extra IVP).
///
/// Returns
/// -------
/// tuple
///     ``(tip_positions (n, 3) [m], tip_rotations (n, 3, 3) [-], tensions
///     (n, n_actuators) [N], iterations (n,), evaluations (n,), converged
///     (n,), stable (n,), margin (n,) [-], shapes)``: NaN pose and tensions
///     and ``converged = False`` where a row does not converge; ``stable``
///     and ``margin`` ``None`` with ``stability="off"`` (NaN margin where
///     there is no verdict); ``shapes`` is ``(arc_length (nodes,) [m],
///     positions (n, nodes, 3) [m])`` with ``shapes=True``, else ``None``.
///
/// Raises
/// ------
/// ValueError
///     An argument outside its range, or a row of ``inputs`` (named).
///
/// Examples
/// --------
/// >>> from tcarod import _core
/// >>> from tcarod.batch import fig6_square_robot
/// >>> out = _core.solve_batch(fig6_square_robot(), np.array([[25.0, 25.0], [60.0, 60.0]]), steps=20)
/// >>> out[0].shape, out[5].tolist()           # tip positions (n, 3) [m], converged
/// ((2, 3), [True, True])
#[pyfunction]
#[pyo3(signature = (robot, inputs, wrenches=None, *, steps=None, tol=Real(1e-10), max_iter=None, chunk_size=None, threads=None, warm=true, stability="report", shapes=false),
    text_signature = "(robot, inputs, wrenches=None, *, steps=100, tol=1e-10, max_iter=50, chunk_size=256, threads=0, warm=True, stability='report', shapes=False)")]
#[allow(clippy::too_many_arguments)]
fn solve_batch<'py>(
    py: Python<'py>,
    robot: &Bound<'py, PyRobot>,
    inputs: PyReadonlyArray2<'py, f64>,
    wrenches: Option<PyReadonlyArray2<'py, f64>>,
    steps: Option<Bound<'py, PyAny>>,
    tol: Real,
    max_iter: Option<Bound<'py, PyAny>>,
    chunk_size: Option<Bound<'py, PyAny>>,
    threads: Option<Bound<'py, PyAny>>,
    warm: bool,
    stability: &str,
    shapes: bool,
) -> PyResult<BatchArrays<'py>> {
    use crate::limits::{MAX_CHUNK, MAX_THREADS};
    let solve = solve_options(steps.as_ref(), tol, max_iter.as_ref())?;
    let chunk_size = count_or("chunk_size", chunk_size.as_ref(), 256, 1, MAX_CHUNK)?;
    let threads = count_or("threads", threads.as_ref(), 0, 0, MAX_THREADS)?;
    let with_verdict = batch_stability(stability)?;
    let r = robot.get().inner.clone();
    let na = r.actuators.len();
    let shape = inputs.shape();
    if shape[1] != na {
        return Err(Error::input(
            "inputs",
            format!("expected shape (n, {na}), got ({}, {})", shape[0], shape[1]),
        )
        .into());
    }
    let n = shape[0];
    let q: Vec<f64> = inputs.as_array().iter().copied().collect(); // row-major
    let w: Option<Vec<f64>> = match wrenches {
        Some(w) => {
            let s = w.shape();
            if s[0] != n || s[1] != 6 {
                return Err(Error::input(
                    "wrenches",
                    format!("expected shape ({n}, 6), got ({}, {})", s[0], s[1]),
                )
                .into());
            }
            Some(w.as_array().iter().copied().collect())
        }
        None => None,
    };
    let opts = BatchOptions {
        solve,
        chunk_size,
        threads,
        warm,
        stability: with_verdict,
    };
    let out = super::errors::detach_interruptible(py, || {
        if shapes {
            solve_batch_shapes(&r, &q, w.as_deref(), &opts)
        } else {
            core_solve_batch(&r, &q, w.as_deref(), &opts)
        }
    })?;
    let shape_arrays = if shapes {
        Some(shape_arrays(py, &out.shapes)?)
    } else {
        None
    };
    let pos =
        PyArray1::from_iter(py, out.tip_positions.iter().flatten().copied()).reshape([n, 3])?;
    let rot =
        PyArray1::from_iter(py, out.tip_rotations.iter().flatten().copied()).reshape([n, 3, 3])?;
    let tens = PyArray1::from_slice(py, &out.tensions).reshape([n, na])?;
    let it = PyArray1::from_iter(py, out.iterations.iter().map(|&k| k as i64));
    let ev = PyArray1::from_iter(py, out.evaluations.iter().map(|&k| k as i64));
    let ok = PyArray1::from_iter(py, out.converged.iter().copied());
    let stable = with_verdict.then(|| PyArray1::from_slice(py, &out.stable));
    let margin = with_verdict.then(|| PyArray1::from_slice(py, &out.margin));
    Ok((pos, rot, tens, it, ev, ok, stable, margin, shape_arrays))
}

/// Arc length `(nodes,)` [m] and positions `(n, nodes, 3)` [m] of the rows'
/// shapes, NaN for a row without one. Every shape of one robot and `steps`
/// lies on the same nodes; no converged row gives zero nodes.
fn shape_arrays<'py>(py: Python<'py>, shapes: &[Vec<[f64; 4]>]) -> PyResult<ShapeArrays<'py>> {
    let first = shapes.iter().find(|s| !s.is_empty());
    let nodes = first.map_or(0, Vec::len);
    let s: Vec<f64> = first.map_or_else(Vec::new, |f| f.iter().map(|p| p[0]).collect());
    let mut flat = Vec::with_capacity(shapes.len() * nodes * 3);
    for row in shapes {
        if row.is_empty() {
            flat.extend(std::iter::repeat(f64::NAN).take(nodes * 3));
        } else if row.len() != nodes || row.iter().zip(&s).any(|(p, s)| p[0] != *s) {
            return Err(Error::input("shapes", "rows on different nodes").into());
        } else {
            flat.extend(row.iter().flat_map(|p| [p[1], p[2], p[3]]));
        }
    }
    let pos = PyArray1::from_vec(py, flat).reshape([shapes.len(), nodes, 3])?;
    Ok((PyArray1::from_vec(py, s), pos))
}

/// Worker threads ``solve_batch`` uses for ``threads=0``.
///
/// Returns
/// -------
/// int
///     The available cores [-].
///
/// Examples
/// --------
/// >>> from tcarod import _core
/// >>> _core.default_threads() >= 1
/// True
#[pyfunction]
fn default_threads() -> usize {
    thread_count(0)
}
