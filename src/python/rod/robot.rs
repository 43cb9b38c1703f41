//! Bindings of the robot and its forward solve.

use std::sync::Arc;

use pyo3::prelude::*;

use super::actuator::PyActuator;
use super::body::{body_repr, PyBody};
use super::solution::{checked_solution, PySolution};
use crate::error::{Error, Result};
use crate::python::args::solve_options;
use crate::python::to_py::{hash_by_text, positional_args, NewArgs};
use crate::python::{pv, reals, Real, MAX_SEQUENCE};
use crate::rod::{Actuator, Robot};
use crate::shooting::solve;

/// A body with its embedded actuators: `Robot(body, actuators=())`.
///
/// `body` is a `Body`; `actuators` a sequence of `Actuator` (inputs are given
/// in this order to `solve`: temperature [C] for TCAs, tension [N] for
/// tendons, pull [m] for linear tendons). Building checks the layout: anchors
/// inside the body, routings inside the section, TCAs no longer than their
/// span (ValueError naming `actuators[i]`). Value object: immutable, `==`
/// (two identically built robots are equal), picklable, so it travels to
/// process pools and Dask workers.
#[pyclass(name = "Robot", module = "tcarod._core", frozen, subclass, eq, hash)]
#[derive(Clone)]
pub struct PyRobot {
    pub(crate) inner: Arc<Robot>,
    pub(crate) body: PyBody,
    pub(crate) actuators: Vec<PyActuator>,
}

#[pymethods]
impl PyRobot {
    #[new]
    #[pyo3(signature = (body, actuators=None), text_signature = "(body, actuators=())")]
    fn new(body: PyBody, actuators: Option<Bound<'_, PyAny>>) -> PyResult<Self> {
        let actuators = match actuators {
            None => Vec::new(),
            Some(seq) => actuator_list(&seq)?,
        };
        let acts: Vec<Actuator> = actuators.iter().map(|a| a.inner.clone()).collect();
        let robot = Robot::new(body.inner.clone(), acts)?;
        Ok(PyRobot {
            inner: Arc::new(robot),
            body,
            actuators,
        })
    }
    /// The soft body (`Body`).
    #[getter]
    fn body(&self) -> PyBody {
        self.body.clone()
    }
    /// The actuators (list of `Actuator`), in input order.
    #[getter]
    fn actuators(&self) -> Vec<PyActuator> {
        self.actuators.clone()
    }
    /// Passive inputs: ambient temperature [C] for TCAs, zero tension [N] / pull [m] for tendons.
    #[getter]
    fn reference_inputs(&self) -> Vec<f64> {
        self.inner.reference_inputs()
    }

    /// Solve the forward kinetostatics for one input per actuator
    /// (temperature [C] for TCAs, tension [N] for tendons, pull [m] for linear
    /// tendons). `steps`: RK4 steps over the body (1 to 100,000); `tol`:
    /// Newton tolerance on the dimensionless residual; `max_iter`: Newton
    /// iterations (1 to 100,000); `warm_start`: a nearby `Solution` of this
    /// robot, or of a robot with the same actuators under other loads (load
    /// continuation); `require_stable`: check the equilibrium's stability
    /// (one tangent IVP more, cached in `Solution.stable`) and raise
    /// `UnstableEquilibriumError` (attributes `margin` [-] and `solution`) if it
    /// is unstable; a stable one is reached with
    /// `tcarod.stability.follow_branch(..., stable_only=True)` or another
    /// `warm_start`. Raises `ValueError` on bad input, `TypeError` on wrong types and
    /// `ConvergenceError` if Newton fails.
    #[pyo3(signature = (inputs, *, steps=None, tol=Real(1e-10), max_iter=None, warm_start=None, require_stable=false),
        text_signature = "($self, inputs, *, steps=100, tol=1e-10, max_iter=50, warm_start=None, require_stable=False)")]
    #[allow(clippy::too_many_arguments)]
    fn solve(
        slf: &Bound<'_, Self>,
        py: Python<'_>,
        inputs: Bound<'_, PyAny>,
        steps: Option<Bound<'_, PyAny>>,
        tol: Real,
        max_iter: Option<Bound<'_, PyAny>>,
        warm_start: Option<PyRef<'_, PySolution>>,
        require_stable: bool,
    ) -> PyResult<PySolution> {
        let this = slf.get();
        let opts = solve_options(steps.as_ref(), tol, max_iter.as_ref())?;
        let q = reals("inputs", &inputs, None)?;
        let robot = this.inner.clone();
        let warm = warm_start.map(|w| w.inner.clone());
        let sol = crate::python::errors::detach_interruptible(py, || {
            solve(&robot, &q, &opts, warm.as_ref()).and_then(checked_solution)
        })?;
        let sol = PySolution::new(sol, slf.clone().unbind());
        if require_stable {
            let (stable, margin) = sol.verdict(py)?;
            if !stable {
                let tip = sol.inner.tip_position();
                let err = crate::python::errors::UnstableEquilibriumError::new_err(format!(
                    "the equilibrium found (tip at {} m) is unstable: stability margin \
                     {margin:.3e} < 0; continue to a stable one with \
                     tcarod.stability.follow_branch(..., stable_only=True) or solve from \
                     another warm_start",
                    pv(tip.as_slice())
                ));
                let value = err.value(py);
                value.setattr("margin", margin)?;
                value.setattr("solution", Py::new(py, sol)?)?;
                return Err(err);
            }
        }
        Ok(sol)
    }

    /// Solve along rows of `inputs` (shape `(k, n_actuators)`, at most
    /// 10,000,000 rows), each warm-started from the previous one. Returns a
    /// list of `Solution`. Options as for `solve`.
    #[pyo3(signature = (inputs, *, steps=None, tol=Real(1e-10), max_iter=None),
        text_signature = "($self, inputs, *, steps=100, tol=1e-10, max_iter=50)")]
    fn sweep(
        slf: &Bound<'_, Self>,
        py: Python<'_>,
        inputs: Bound<'_, PyAny>,
        steps: Option<Bound<'_, PyAny>>,
        tol: Real,
        max_iter: Option<Bound<'_, PyAny>>,
    ) -> PyResult<Vec<PySolution>> {
        let opts = solve_options(steps.as_ref(), tol, max_iter.as_ref())?;
        let rows_iter = inputs.try_iter().map_err(|_| {
            pyo3::exceptions::PyTypeError::new_err("inputs: expected a sequence of rows")
        })?;
        let mut rows: Vec<Vec<f64>> = Vec::new();
        for (k, row) in rows_iter.enumerate() {
            if k >= crate::limits::MAX_BATCH_ROWS {
                return Err(Error::input(
                    "inputs",
                    format!("more than {} rows per call", crate::limits::MAX_BATCH_ROWS),
                )
                .into());
            }
            let row = reals(&format!("inputs[{k}]"), &row?, None)?;
            slf.get().inner.check_inputs(&row)?;
            rows.push(row);
        }
        let robot = slf.get().inner.clone();
        let sols = crate::python::errors::detach_interruptible(py, || {
            crate::shooting::sweep(&robot, &rows, &opts)?
                .into_iter()
                .map(checked_solution)
                .collect::<Result<Vec<_>>>()
        })?;
        Ok(sols
            .into_iter()
            .map(|s| PySolution::new(s, slf.clone().unbind()))
            .collect())
    }

    fn __repr__(&self) -> String {
        let acts: Vec<String> = self.actuators.iter().map(|a| a.__repr__()).collect();
        format!(
            "Robot(body={}, actuators=[{}])",
            body_repr(&self.body.inner),
            acts.join(", ")
        )
    }
    /// Constructor arguments, for pickle and copy.
    fn __getnewargs_ex__<'py>(&self, py: Python<'py>) -> NewArgs<'py> {
        positional_args((self.body.clone(), self.actuators.clone()), py)
    }
}

impl PartialEq for PyRobot {
    fn eq(&self, other: &Self) -> bool {
        self.same_as(other)
    }
}

hash_by_text!(PyRobot, |r| r.__repr__());

impl PyRobot {
    /// Built from equal bodies and equal actuators.
    pub(crate) fn same_as(&self, other: &PyRobot) -> bool {
        Arc::ptr_eq(&self.inner, &other.inner)
            || (self.body.inner == other.body.inner
                && self.actuators.len() == other.actuators.len()
                && self
                    .actuators
                    .iter()
                    .zip(&other.actuators)
                    .all(|(a, b)| a.identity() == b.identity()))
    }
}

/// `seq` as a list of actuators, at most [`MAX_SEQUENCE`] (never
/// trusting `__len__`): `TypeError` for anything else.
fn actuator_list(seq: &Bound<'_, PyAny>) -> PyResult<Vec<PyActuator>> {
    let iter = seq.try_iter().map_err(|_| {
        pyo3::exceptions::PyTypeError::new_err("actuators: expected a sequence of Actuator")
    })?;
    let mut out = Vec::new();
    for (k, item) in iter.enumerate() {
        if k >= MAX_SEQUENCE {
            return Err(
                Error::input("actuators", format!("more than {} actuators", MAX_SEQUENCE)).into(),
            );
        }
        let item = item?;
        let a = item.cast::<PyActuator>().map_err(|_| {
            pyo3::exceptions::PyTypeError::new_err(format!(
                "actuators[{k}]: expected an Actuator, not {}",
                item.get_type()
                    .name()
                    .map(|n| n.to_string())
                    .unwrap_or_default()
            ))
        })?;
        out.push(a.get().clone());
    }
    Ok(out)
}
