//! Bindings of the batch solver and of the bench timings (`tcarod.batch`,
//! `tcarod bench`).

use numpy::{
    PyArray1, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods,
};
use pyo3::prelude::*;

use super::rod::{options, PyRobot};
use crate::batch::{solve_batch as core_solve_batch, thread_count, BatchOptions};
use crate::error::Error;

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(solve_batch, m)?)?;
    m.add_function(wrap_pyfunction!(default_threads, m)?)?;
    m.add_function(wrap_pyfunction!(bench_rows, m)?)?;
    m.add_function(wrap_pyfunction!(bench_time, m)?)?;
    Ok(())
}

type BatchArrays<'py> = (
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray3<f64>>,
    Bound<'py, PyArray1<i64>>,
    Bound<'py, PyArray1<i64>>,
    Bound<'py, PyArray1<bool>>,
);

/// Solve the forward problem for every row of `inputs` (shape
/// `(n, n_actuators)`, C for TCAs) and optional tip `wrenches` (shape `(n, 6)`:
/// force [N] and moment [N m], world frame), with the GIL released, on
/// `threads` threads (0: all cores). Rows are cut into chunks of `chunk_size`,
/// each solved in order with warm starts. Returns `(tip_positions (n, 3),
/// tip_rotations (n, 3, 3), iterations (n,), evaluations (n,), converged (n,))`;
/// a row that does not converge has NaN pose and `converged = False`.
#[pyfunction]
#[pyo3(signature = (robot, inputs, wrenches=None, *, steps=100, tol=1e-10, max_iter=50, chunk_size=256, threads=0, warm=true))]
#[allow(clippy::too_many_arguments)]
fn solve_batch<'py>(
    py: Python<'py>,
    robot: &Bound<'py, PyRobot>,
    inputs: PyReadonlyArray2<'py, f64>,
    wrenches: Option<PyReadonlyArray2<'py, f64>>,
    steps: usize,
    tol: f64,
    max_iter: usize,
    chunk_size: usize,
    threads: usize,
    warm: bool,
) -> PyResult<BatchArrays<'py>> {
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
        solve: options(steps, tol, max_iter)?,
        chunk_size,
        threads,
        warm,
    };
    let out = super::errors::detach_interruptible(py, || core_solve_batch(&r, &q, w.as_deref(), &opts))?;
    let pos =
        PyArray1::from_iter(py, out.tip_positions.iter().flatten().copied()).reshape([n, 3])?;
    let rot =
        PyArray1::from_iter(py, out.tip_rotations.iter().flatten().copied()).reshape([n, 3, 3])?;
    let it = PyArray1::from_iter(py, out.iterations.iter().map(|&k| k as i64));
    let ev = PyArray1::from_iter(py, out.evaluations.iter().map(|&k| k as i64));
    let ok = PyArray1::from_iter(py, out.converged.iter().copied());
    Ok((pos, rot, it, ev, ok))
}

/// Worker threads `solve_batch` uses for `threads=0` (the available cores).
#[pyfunction]
fn default_threads() -> usize {
    thread_count(0)
}

/// Rows of the performance table: `(name, description, target [s])`.
#[pyfunction]
fn bench_rows() -> Vec<(&'static str, &'static str, f64)> {
    crate::bench::ROWS
        .iter()
        .map(|r| (r.name, r.description, r.target))
        .collect()
}

/// Time row `name` in Rust: `repeats` runs, each a loop of at least
/// `min_time` [s]; returns seconds per operation of each run. The GIL is
/// released while timing.
#[pyfunction]
#[pyo3(signature = (name, repeats=7, min_time=0.05))]
fn bench_time(py: Python<'_>, name: &str, repeats: usize, min_time: f64) -> PyResult<Vec<f64>> {
    let name = name.to_owned();
    Ok(py.detach(move || crate::bench::time_row(&name, repeats.max(1), min_time))?)
}
