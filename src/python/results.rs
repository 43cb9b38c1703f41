//! Result objects of the inverse kinetostatics.
//!
//! They read like SciPy's `OptimizeResult`: `success`, `status`, `message`,
//! `nit`, `nfev`, besides the physical fields. They are value objects: `==`,
//! picklable (with their `Solution` and its robot).

use pyo3::prelude::*;

use super::outcome::{scipy_fields, tip_of_solution, Outcome};
use super::rod::PySolution;
use super::to_py::{reduce_with, Reduce};
use super::{pb, pf, ps, pv};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyInverseResult>()?;
    m.add_class::<PyBlockedResult>()?;
    m.add_function(wrap_pyfunction!(restore_inverse_result, m)?)?;
    m.add_function(wrap_pyfunction!(restore_blocked_result, m)?)?;
    Ok(())
}

/// Result of a tip-position inverse (SciPy ``OptimizeResult`` naming).
///
/// Returned by ``tcarod.tip_position``. ``success`` / ``reached``: the tip
/// is within ``tol`` [m] of the target. ``status``: 0 reached; 1
/// unreachable (no descent left and a variable rests on its bound: the
/// closest configuration within the temperature range); 2 out of budget
/// (``max_iter`` used up while the error still decreased: call again with
/// ``start=result.variables``); 3 stalled (the error stopped decreasing with
/// no variable on a bound: the target is off the set the tip can reach near
/// the closest point, e.g. off the plane of a planar robot, or a local
/// minimum). ``message`` says the same in words, with the closest tip point
/// found [m] and its distance from the target [m]; ``nit`` iterations,
/// ``nfev`` IVPs. ``variables``
/// (temperature [C] per group), ``error`` [m], ``at_bound``, ``solution``
/// (the final forward ``Solution``) and ``tip_position`` [m].
///
/// Examples
/// --------
/// >>> from tcarod.batch import fig6_square_robot
/// >>> robot = fig6_square_robot()
/// >>> target = robot.solve([80.0, 80.0], steps=20).tip_position     # [m]
/// >>> res = tcarod.tip_position(robot, target, groups=[0, 0], steps=20)
/// >>> res.success, round(res.variables[0], 3)                       # [C]
/// (True, 80.0)
#[pyclass(name = "InverseResult", module = "tcarod._core", frozen, eq)]
pub struct PyInverseResult {
    /// The forward solution at ``variables``.
    ///
    /// Returns
    /// -------
    /// Solution
    ///     The closest one found if the target was not reached.
    #[pyo3(get)]
    pub(crate) solution: Py<PySolution>,
    /// Final actuation variables.
    ///
    /// Returns
    /// -------
    /// list of float
    ///     Temperature [C] per group for TCAs.
    #[pyo3(get)]
    pub(crate) variables: Vec<f64>,
    /// Remaining tip error [m].
    ///
    /// Returns
    /// -------
    /// float
    ///     Distance to the target [m] (plus the weighted angle if an orientation
    ///     was asked).
    #[pyo3(get)]
    pub(crate) error: f64,
    /// Iterations (Jacobian evaluations) used (``nit``).
    ///
    /// Returns
    /// -------
    /// int
    ///     Iterations [-].
    #[pyo3(get)]
    pub(crate) iterations: usize,
    /// Whether the target was reached to ``tol``.
    ///
    /// Returns
    /// -------
    /// bool
    ///     Same as ``success``.
    #[pyo3(get)]
    pub(crate) reached: bool,
    /// Whether each variable rests on a bound of its range at the end.
    ///
    /// Returns
    /// -------
    /// list of bool
    ///     One per variable, in the order of `variables`.
    #[pyo3(get)]
    pub(crate) at_bound: Vec<bool>,
    /// IVPs integrated in total (``nfev``).
    ///
    /// Returns
    /// -------
    /// int
    ///     IVPs [-].
    #[pyo3(get)]
    pub(crate) evaluations: usize,
    /// The iteration budget the solve had.
    ///
    /// Returns
    /// -------
    /// int
    ///     The ``max_iter`` argument [-].
    #[pyo3(get)]
    pub(crate) max_iter: usize,
}

impl Outcome for PyInverseResult {
    fn status_code(&self) -> i64 {
        self.code()
    }
    fn status_message(&self) -> String {
        let tip = self.solution.get().inner.tip_position();
        self.core_status()
            .message(&tip, self.error, &self.at_bound, self.max_iter)
    }
    fn iteration_count(&self) -> usize {
        self.iterations
    }
    fn ivp_count(&self) -> usize {
        self.evaluations
    }
}

scipy_fields!(
    PyInverseResult,
    "Status code of the inverse (SciPy naming).\n\n\
     Returns\n\
     -------\n\
     int\n    \
     `0` target reached to `tol`; `1` target \
     unreachable (the closest configuration found has variables at their \
     bounds, `at_bound`); `2` iteration budget `max_iter` exhausted while the \
     error still decreased; `3` stalled (the error stopped decreasing with no \
     variable at a bound: the target is off the set the tip reaches near the \
     closest point, e.g. off the plane of a planar robot, or a local \
     minimum). `message` gives the closest tip point [m] and its distance [m]."
);
tip_of_solution!(PyInverseResult);

impl PyInverseResult {
    /// The core's status of this outcome (the same rule as the solve's).
    fn core_status(&self) -> crate::inverse::InverseStatus {
        let exhausted = self.iterations >= self.max_iter;
        crate::inverse::InverseStatus::of(self.reached, exhausted, &self.at_bound)
    }
    fn code(&self) -> i64 {
        self.core_status().code()
    }
}

#[pymethods]
impl PyInverseResult {
    fn __repr__(&self) -> String {
        format!(
            "<InverseResult success={} status={} message={} variables={} error={} nit={} nfev={} at_bound=[{}]>",
            pb(self.reached),
            self.code(),
            ps(&self.status_message()),
            pv(&self.variables),
            pf(self.error),
            self.iterations,
            self.evaluations,
            self.at_bound.iter().map(|b| pb(*b)).collect::<Vec<_>>().join(", ")
        )
    }
    /// Pickle support (the solution travels with its robot).
    fn __reduce__<'py>(&self, py: Python<'py>) -> Reduce<'py, InverseArgs> {
        let args = (
            self.solution.clone_ref(py),
            self.variables.clone(),
            self.error,
            self.iterations,
            self.reached,
            self.at_bound.clone(),
            self.evaluations,
            self.max_iter,
        );
        reduce_with(py, "_restore_inverse_result", args)
    }
}

impl PartialEq for PyInverseResult {
    fn eq(&self, o: &Self) -> bool {
        self.variables == o.variables
            && self.error.to_bits() == o.error.to_bits()
            && self.iterations == o.iterations
            && self.reached == o.reached
            && self.at_bound == o.at_bound
            && self.evaluations == o.evaluations
            && self.max_iter == o.max_iter
            && self.solution.get() == o.solution.get()
    }
}

/// `_restore_inverse_result` arguments (the fields in declaration order).
type InverseArgs = (
    Py<PySolution>,
    Vec<f64>,
    f64,
    usize,
    bool,
    Vec<bool>,
    usize,
    usize,
);

/// Rebuild an `InverseResult` (pickle support; not public API).
#[pyfunction]
#[pyo3(name = "_restore_inverse_result")]
#[allow(clippy::too_many_arguments)]
fn restore_inverse_result(
    solution: Py<PySolution>,
    variables: Vec<f64>,
    error: f64,
    iterations: usize,
    reached: bool,
    at_bound: Vec<bool>,
    evaluations: usize,
    max_iter: usize,
) -> PyInverseResult {
    PyInverseResult {
        solution,
        variables,
        error,
        iterations,
        reached,
        at_bound,
        evaluations,
        max_iter,
    }
}

/// A blocked-tip solution (SciPy naming).
///
/// Returned by ``tcarod.blocked_force`` and ``tcarod.blocked_temperature``:
/// the contact ``force`` [N] the tip presses with along the plane's normal,
/// the actuation ``variables`` (temperature [C] per group), the forward
/// ``solution`` with the contact force as tip load, ``tip_position`` [m].
/// ``success`` is always ``True`` and ``status`` 0 (a failed solve raises
/// ``ConvergenceError``); ``nit`` Newton iterations or eq-43 increments,
/// ``nfev`` IVPs integrated.
///
/// Examples
/// --------
/// >>> from tcarod.batch import fig6_square_robot
/// >>> robot = fig6_square_robot()
/// >>> tip = robot.solve([25.0, 25.0], steps=20).tip_position       # blocked where it rests [m]
/// >>> res = tcarod.blocked_force(robot, tip, [-1.0, 0.0, 0.0], [60.0], groups=[0, 0], steps=20)
/// >>> res.success, res.force > 0                                    # it presses toward -x [N]
/// (True, True)
#[pyclass(name = "BlockedResult", module = "tcarod._core", frozen, eq)]
pub struct PyBlockedResult {
    /// The forward solution with the contact force applied at the tip.
    ///
    /// Returns
    /// -------
    /// Solution
    ///     Its `stable` is the verdict with the tip held.
    #[pyo3(get)]
    pub(crate) solution: Py<PySolution>,
    /// Contact force [N] the tip presses with along the plane's normal.
    ///
    /// Returns
    /// -------
    /// float
    ///     Force [N].
    #[pyo3(get)]
    pub(crate) force: f64,
    /// Actuation variables.
    ///
    /// Returns
    /// -------
    /// list of float
    ///     Temperature [C] per group for TCAs.
    #[pyo3(get)]
    pub(crate) variables: Vec<f64>,
    /// Newton iterations or eq-43 increments (``nit``).
    ///
    /// Returns
    /// -------
    /// int
    ///     Iterations [-].
    #[pyo3(get)]
    pub(crate) iterations: usize,
    /// IVPs integrated in total (``nfev``).
    ///
    /// Returns
    /// -------
    /// int
    ///     IVPs [-].
    #[pyo3(get)]
    pub(crate) evaluations: usize,
}

impl Outcome for PyBlockedResult {
    fn status_code(&self) -> i64 {
        0
    }
    fn status_message(&self) -> String {
        format!(
            "converged: contact force {:.6e} N after {} iterations",
            self.force, self.iterations
        )
    }
    fn iteration_count(&self) -> usize {
        self.iterations
    }
    fn ivp_count(&self) -> usize {
        self.evaluations
    }
}

scipy_fields!(
    PyBlockedResult,
    "Status code of the blocked solve (SciPy naming).\n\n\
     Returns\n\
     -------\n\
     int\n    \
     Always `0` (converged); a solve that fails raises \
     `ConvergenceError` instead."
);
tip_of_solution!(PyBlockedResult);

#[pymethods]
impl PyBlockedResult {
    fn __repr__(&self) -> String {
        format!(
            "<BlockedResult success=True status=0 force={} variables={} nit={} nfev={}>",
            pf(self.force),
            pv(&self.variables),
            self.iterations,
            self.evaluations
        )
    }
    /// Pickle support (the solution travels with its robot).
    fn __reduce__<'py>(&self, py: Python<'py>) -> Reduce<'py, BlockedArgs> {
        let args = (
            self.solution.clone_ref(py),
            self.force,
            self.variables.clone(),
            self.iterations,
            self.evaluations,
        );
        reduce_with(py, "_restore_blocked_result", args)
    }
}

impl PartialEq for PyBlockedResult {
    fn eq(&self, o: &Self) -> bool {
        self.force.to_bits() == o.force.to_bits()
            && self.variables == o.variables
            && self.iterations == o.iterations
            && self.evaluations == o.evaluations
            && self.solution.get() == o.solution.get()
    }
}

/// `_restore_blocked_result` arguments (the fields in declaration order).
type BlockedArgs = (Py<PySolution>, f64, Vec<f64>, usize, usize);

/// Rebuild a `BlockedResult` (pickle support; not public API).
#[pyfunction]
#[pyo3(name = "_restore_blocked_result")]
fn restore_blocked_result(
    solution: Py<PySolution>,
    force: f64,
    variables: Vec<f64>,
    iterations: usize,
    evaluations: usize,
) -> PyBlockedResult {
    PyBlockedResult {
        solution,
        force,
        variables,
        iterations,
        evaluations,
    }
}
