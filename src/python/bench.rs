//! Bindings of `tcarod bench`: the performance table's rows (defined once in
//! `benches/rows/mod.rs`, shared with the criterion benches) timed in Rust, so
//! that the table measures the core without Python's call overhead (which
//! `tcarod bench` reports on its own line).

use std::time::Instant;

use pyo3::prelude::*;

use super::{count_or, Real};
use crate::error::{Error, Result};

// The rows are bench code, not library API: included from benches/ (the
// solver rows there are timed by criterion only).
#[allow(dead_code)]
#[path = "../../benches/rows/mod.rs"]
mod rows;

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(bench_rows, m)?)?;
    m.add_function(wrap_pyfunction!(bench_time, m)?)?;
    Ok(())
}

/// Rows of the performance table.
///
/// Returns
/// -------
/// list of tuple
///     ``(name, description, target [s])`` per row.
///
/// Examples
/// --------
/// >>> from tcarod import _core
/// >>> name, description, target = _core.bench_rows()[0]
/// >>> isinstance(name, str) and target > 0      # [s]
/// True
#[pyfunction]
fn bench_rows() -> Vec<(&'static str, &'static str, f64)> {
    rows::ROWS
        .iter()
        .map(|r| (r.name, r.description, r.target))
        .collect()
}

/// Time one row of the performance table in Rust.
///
/// The GIL is released while timing.
///
/// Parameters
/// ----------
/// name : str
///     A row of ``bench_rows()``.
/// repeats : int, optional
///     Runs, 1 to 1000 (default 7).
/// min_time : float, optional
///     Shortest loop of each run [s], 0 to 60 (default 0.05).
///
/// Returns
/// -------
/// list of float
///     Seconds per operation of each run [s].
///
/// Raises
/// ------
/// ValueError
///     An unknown ``name`` or an argument out of range.
///
/// Examples
/// --------
/// >>> from tcarod import _core
/// >>> times = _core.bench_time("ivp", repeats=2, min_time=0.0)     # [s] per IVP
/// >>> len(times), all(t > 0 for t in times)
/// (2, True)
#[pyfunction]
#[pyo3(signature = (name, repeats=None, min_time=Real(0.05)), text_signature = "(name, repeats=7, min_time=0.05)")]
fn bench_time(
    py: Python<'_>,
    name: &str,
    repeats: Option<Bound<'_, PyAny>>,
    min_time: Real,
) -> PyResult<Vec<f64>> {
    let repeats = count_or("repeats", repeats.as_ref(), 7, 1, 1000)?;
    let min_time = crate::error::non_negative("min_time [s]", min_time.0)?;
    if min_time > 60.0 {
        return Err(Error::param("min_time [s]", min_time, "0 <= min_time <= 60 s").into());
    }
    let name = name.to_owned();
    Ok(py.detach(move || time_row(&name, repeats, min_time))?)
}

/// Time `repeats` runs of row `name` (after one warm-up run), each run
/// repeated in a loop for at least `min_time` \[s\]; returns seconds per
/// operation of each run.
pub fn time_row(name: &str, repeats: usize, min_time: f64) -> Result<Vec<f64>> {
    let mut op = rows::operation(name)?;
    op()?;
    // inner loop length: enough calls for min_time
    let t0 = Instant::now();
    op()?;
    let one = t0.elapsed().as_secs_f64().max(1e-9);
    let inner = ((min_time / one).ceil() as usize).max(1);
    let mut out = Vec::with_capacity(repeats);
    for _ in 0..repeats {
        let t = Instant::now();
        for _ in 0..inner {
            op()?;
        }
        out.push(t.elapsed().as_secs_f64() / inner as f64);
    }
    Ok(out)
}
