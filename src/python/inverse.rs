//! Bindings of the inverse kinetostatics.
//!
//! Results read like SciPy's `OptimizeResult`: `success`, `status`,
//! `message`, `nit`, `nfev`, besides the physical fields. They are value
//! objects: `==`, picklable (with their `Solution` and its robot).

use nalgebra::{Matrix3, Vector3};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use super::rod::{solve_options, PyRobot, PySolution};
use super::{count_or, counts, pb, pf, ps, pv, reals, vec3_arg, Real};
use crate::error::Error;
use crate::inverse::{self, Block, BlockedResult, Groups, InverseOptions, Scheme};
use crate::validate::{MAX_INCREMENTS, MAX_ITER};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyInverseResult>()?;
    m.add_class::<PyBlockedResult>()?;
    m.add_function(wrap_pyfunction!(sensitivities, m)?)?;
    m.add_function(wrap_pyfunction!(tip_inverse, m)?)?;
    m.add_function(wrap_pyfunction!(blocked_force, m)?)?;
    m.add_function(wrap_pyfunction!(blocked_temperature, m)?)?;
    m.add_function(wrap_pyfunction!(blocked_temperature_direct, m)?)?;
    m.add_function(wrap_pyfunction!(restore_inverse_result, m)?)?;
    m.add_function(wrap_pyfunction!(restore_blocked_result, m)?)?;
    Ok(())
}

/// `groups` from Python (each in `0..n_actuators`), or one variable per actuator.
fn groups_for(robot: &PyRobot, groups: Option<&Bound<'_, PyAny>>) -> PyResult<Groups> {
    let na = robot.inner.actuators.len();
    let g = match groups {
        Some(o) if !o.is_none() => Groups(counts("groups", o, na.max(1) - 1)?),
        _ => Groups::identity(na),
    };
    g.validate(&robot.inner)?;
    Ok(g)
}

fn dmat<'py>(py: Python<'py>, m: &nalgebra::DMatrix<f64>) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = (0..m.nrows())
        .flat_map(|i| (0..m.ncols()).map(move |j| m[(i, j)]))
        .collect();
    PyArray1::from_vec(py, flat)
        .reshape([m.nrows(), m.ncols()])
        .expect("shape")
}

fn vec3(name: &str, a: &Bound<'_, PyAny>) -> PyResult<Vector3<f64>> {
    Ok(Vector3::from(vec3_arg(name, Some(a), [0.0; 3])?))
}

fn wrap(robot: &Bound<'_, PyRobot>, s: crate::shooting::Solution) -> PySolution {
    PySolution::new(s, robot.clone().unbind())
}

/// ValueError unless `solution` belongs to `robot` (equal robots count).
fn same_robot(py: Python<'_>, robot: &PyRobot, solution: &PySolution, name: &str) -> PyResult<()> {
    if solution.robot.bind(py).get().same_as(robot) {
        Ok(())
    } else {
        Err(Error::input(
            name,
            "a Solution of a different robot (solve this robot first)",
        )
        .into())
    }
}

/// `(J, C)` at `solution` (eqs 41-42): `J` is `6 x n_vars` (tip `[dp (m); dtheta (rad)]`
/// per unit actuation variable, per C for TCAs), `C` is `6 x 6` (per unit tip wrench
/// `[F (N); M (N m)]`), world frame. `groups[i]` is the variable driving actuator `i`.
#[pyfunction]
#[pyo3(signature = (solution, groups=None, scheme="forward"))]
#[allow(clippy::type_complexity)]
fn sensitivities<'py>(
    py: Python<'py>,
    solution: PyRef<'py, PySolution>,
    groups: Option<Bound<'py, PyAny>>,
    scheme: &str,
) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<f64>>)> {
    let robot = solution.robot.bind(py).get().clone();
    let g = groups_for(&robot, groups.as_ref())?;
    let sch = match scheme {
        "forward" => Scheme::Forward,
        "central" => Scheme::Central,
        "exact" => Scheme::Exact,
        _ => {
            return Err(Error::input(
                "scheme",
                format!("{scheme:?} is not 'forward', 'central' or 'exact'"),
            )
            .into())
        }
    };
    let sol = solution.inner.clone();
    let s =
        py.detach(|| inverse::sensitivities(&robot.inner, &sol, &sol.loads, &g, sol.steps, sch))?;
    Ok((dmat(py, &s.jacobian), dmat(py, &s.compliance)))
}

/// Result of a tip-position inverse (SciPy `OptimizeResult` naming).
///
/// * `success` / `reached`: the tip is within `tol` [m] of the target;
/// * `status`: 0 reached; 1 unreachable: no descent left and a variable rests
///   on its bound (the closest configuration within the temperature range);
///   2 out of budget: `max_iter` iterations without reaching (call again with
///   `start=result.variables` or a larger `max_iter`); 3 stalled: no descent
///   and no variable on a bound (a local minimum of the tip error, or `tol`
///   below the forward solver's accuracy);
/// * `message`: the same in words; `nit`: iterations (Jacobian evaluations);
///   `nfev`: IVPs integrated;
/// * `variables` (temperatures [C] per group), `error` [m] (plus weighted angle
///   if an orientation was asked), `at_bound`, `solution` (the final forward
///   `Solution`), `tip_position` [m].
#[pyclass(name = "InverseResult", module = "tcarod._core", frozen)]
pub struct PyInverseResult {
    /// The forward `Solution` at `variables` (the closest one found if not reached).
    #[pyo3(get)]
    solution: Py<PySolution>,
    /// Final actuation variables (temperature [C] per group for TCAs).
    #[pyo3(get)]
    variables: Vec<f64>,
    /// Remaining tip error [m] (plus weighted angle if orientation was asked).
    #[pyo3(get)]
    error: f64,
    /// Iterations (Jacobian evaluations) used (`nit`).
    #[pyo3(get)]
    iterations: usize,
    /// Whether the target was reached to `tol`.
    #[pyo3(get)]
    reached: bool,
    /// Whether each variable rests on a bound of its range at the end (`list[bool]`).
    #[pyo3(get)]
    at_bound: Vec<bool>,
    /// IVPs integrated in total (`nfev`).
    #[pyo3(get)]
    evaluations: usize,
    /// The iteration budget the solve had (`max_iter` argument).
    #[pyo3(get)]
    max_iter: usize,
}

impl PyInverseResult {
    fn code(&self) -> i64 {
        if self.reached {
            0
        } else if self.iterations >= self.max_iter {
            2
        } else if self.at_bound.iter().any(|b| *b) {
            1
        } else {
            3
        }
    }
}

#[pymethods]
impl PyInverseResult {
    /// `True` if the target was reached (same as `reached`).
    #[getter]
    fn success(&self) -> bool {
        self.reached
    }
    /// `0` reached, `1` unreachable (closest point at the bounds), `2` out of budget, `3` stalled.
    #[getter]
    fn status(&self) -> i64 {
        self.code()
    }
    /// Why the solve stopped, in words (`str`).
    #[getter]
    fn message(&self) -> String {
        match self.code() {
            0 => format!("target reached: error {:.3e} m", self.error),
            1 => format!(
                "target unreachable: the closest configuration found (error {:.3e} m) has variables {:?} at their bounds",
                self.error,
                self.at_bound.iter().enumerate().filter(|(_, b)| **b).map(|(k, _)| k).collect::<Vec<_>>()
            ),
            2 => format!(
                "iteration budget exhausted: max_iter = {} iterations, error {:.3e} m; continue with start=result.variables or a larger max_iter",
                self.max_iter, self.error
            ),
            _ => format!("stalled: no descent from error {:.3e} m with no variable at a bound (local minimum, or tol below the solver's accuracy)", self.error),
        }
    }
    /// Iterations (same as `iterations`), SciPy naming.
    #[getter]
    fn nit(&self) -> usize {
        self.iterations
    }
    /// IVPs integrated (same as `evaluations`), SciPy naming.
    #[getter]
    fn nfev(&self) -> usize {
        self.evaluations
    }
    /// Tip position [m] of `solution`, shape `(3,)`.
    #[getter]
    fn tip_position<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(
            py,
            self.solution.bind(py).get().inner.tip_position().as_slice(),
        )
    }
    fn __repr__(&self) -> String {
        format!(
            "<InverseResult success={} status={} message={} variables={} error={} nit={} nfev={} at_bound=[{}]>",
            pb(self.reached),
            self.code(),
            ps(&self.message()),
            pv(&self.variables),
            pf(self.error),
            self.iterations,
            self.evaluations,
            self.at_bound.iter().map(|b| pb(*b)).collect::<Vec<_>>().join(", ")
        )
    }
    /// Pickle support (the solution travels with its robot).
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let f = py
            .import("tcarod._core")?
            .getattr("_restore_inverse_result")?;
        let args = (
            self.solution.clone_ref(py),
            self.variables.clone(),
            self.error,
            self.iterations,
            self.reached,
            self.at_bound.clone(),
            self.evaluations,
            self.max_iter,
        )
            .into_pyobject(py)?;
        Ok((f, args))
    }
    fn __eq__(&self, py: Python<'_>, other: &Bound<'_, PyAny>) -> PyResult<bool> {
        let Ok(o) = other.cast::<PyInverseResult>() else {
            return Ok(false);
        };
        let o = o.get();
        let same = self.variables == o.variables
            && self.error.to_bits() == o.error.to_bits()
            && self.iterations == o.iterations
            && self.reached == o.reached
            && self.at_bound == o.at_bound
            && self.evaluations == o.evaluations
            && self.max_iter == o.max_iter;
        Ok(same && self.solution.bind(py).eq(o.solution.bind(py))?)
    }
}

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

/// A 3x3 rotation matrix from Python (rows of 3 reals).
fn rotation_arg(obj: &Bound<'_, PyAny>) -> PyResult<Matrix3<f64>> {
    let rows = obj.try_iter().map_err(|_| {
        pyo3::exceptions::PyTypeError::new_err("target_rotation: expected a 3x3 matrix")
    })?;
    let mut m = Vec::new();
    for (i, row) in rows.enumerate() {
        if i >= 3 {
            return Err(Error::input("target_rotation", "expected 3 rows").into());
        }
        m.push(reals(&format!("target_rotation[{i}]"), &row?, Some(3))?);
    }
    if m.len() != 3 {
        return Err(Error::input(
            "target_rotation",
            format!("expected 3 rows, got {}", m.len()),
        )
        .into());
    }
    let mm = Matrix3::from_fn(|i, j| m[i][j]);
    if !mm.iter().all(|x| x.is_finite())
        || (mm.transpose() * mm - Matrix3::identity()).norm() > 1e-6
    {
        return Err(Error::input("target_rotation", "must be a 3x3 rotation matrix").into());
    }
    Ok(mm)
}

/// Iterate the local inverse to put the tip at `target` [m] (and, if given,
/// orientation `target_rotation` weighted by `orientation_weight` [m/rad]).
/// `tol` [m]; `max_iter` iterations (1 to 100,000); `damping` [m per unit
/// variable]; `steps` RK4 steps per forward solve (1 to 100,000).
#[pyfunction]
#[pyo3(signature = (robot, target, *, start=None, groups=None, target_rotation=None, orientation_weight=Real(0.01),
    tol=Real(1e-7), max_iter=None, damping=Real(1e-6), steps=None),
    text_signature = "(robot, target, *, start=None, groups=None, target_rotation=None, orientation_weight=0.01, \
        tol=1e-07, max_iter=50, damping=1e-06, steps=100)")]
#[allow(clippy::too_many_arguments)]
fn tip_inverse(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    target: Bound<'_, PyAny>,
    start: Option<Bound<'_, PyAny>>,
    groups: Option<Bound<'_, PyAny>>,
    target_rotation: Option<Bound<'_, PyAny>>,
    orientation_weight: Real,
    tol: Real,
    max_iter: Option<Bound<'_, PyAny>>,
    damping: Real,
    steps: Option<Bound<'_, PyAny>>,
) -> PyResult<PyInverseResult> {
    let r = robot.get();
    let g = groups_for(r, groups.as_ref())?;
    let t = vec3("target [m]", &target)?;
    let rot = match target_rotation.as_ref().filter(|o| !o.is_none()) {
        Some(o) => {
            crate::error::positive("orientation_weight [m/rad]", orientation_weight.0)?;
            Some(rotation_arg(o)?)
        }
        None => None,
    };
    crate::error::positive("tol [m]", tol.0)?;
    crate::error::non_negative("damping", damping.0)?;
    let max_iter = count_or("max_iter", max_iter.as_ref(), 50, 1, MAX_ITER)?;
    let z0 = match start.as_ref().filter(|o| !o.is_none()) {
        Some(o) => reals("start", o, Some(g.n_vars()))?,
        None => g.vars(&r.inner.reference_inputs()),
    };
    let opts = InverseOptions {
        forward: solve_options(steps.as_ref(), Real(1e-10), None)?,
        tol: tol.0,
        max_iter,
        damping: damping.0,
    };
    let rr = r.inner.clone();
    let w = orientation_weight.0;
    let res = super::errors::detach_interruptible(py, || {
        inverse::tip_position_inverse(&rr, &g, &t, rot.as_ref().map(|m| (m, w)), &z0, &opts)
    })?;
    Ok(PyInverseResult {
        solution: Py::new(py, wrap(robot, res.solution))?,
        variables: res.variables,
        error: res.error,
        iterations: res.iterations,
        reached: res.reached,
        at_bound: res.at_bound,
        evaluations: res.evaluations,
        max_iter,
    })
}

/// A blocked-tip solution (SciPy naming): contact `force` [N] (the tip
/// presses along the plane's normal), actuation `variables` (temperature [C]
/// per group), the forward `solution` with the contact force as tip load,
/// `tip_position` [m]. `success` is always `True` and `status` 0 (a failed
/// solve raises `ConvergenceError`); `nit` Newton iterations or eq-43
/// increments, `nfev` IVPs integrated.
#[pyclass(name = "BlockedResult", module = "tcarod._core", frozen)]
pub struct PyBlockedResult {
    /// The forward `Solution` with the contact force applied at the tip.
    #[pyo3(get)]
    solution: Py<PySolution>,
    /// Contact force [N] the tip presses with along the plane's normal.
    #[pyo3(get)]
    force: f64,
    /// Actuation variables (temperature [C] per group for TCAs).
    #[pyo3(get)]
    variables: Vec<f64>,
    /// Iterations (Newton iterations or eq-43 increments; `nit`).
    #[pyo3(get)]
    iterations: usize,
    /// IVPs integrated in total (`nfev`).
    #[pyo3(get)]
    evaluations: usize,
}

#[pymethods]
impl PyBlockedResult {
    /// Always `True` (a failed solve raises `ConvergenceError`).
    #[getter]
    fn success(&self) -> bool {
        true
    }
    /// Always `0` (converged).
    #[getter]
    fn status(&self) -> i64 {
        0
    }
    /// Why the solve stopped, in words (`str`).
    #[getter]
    fn message(&self) -> String {
        format!(
            "converged: contact force {:.6e} N after {} iterations",
            self.force, self.iterations
        )
    }
    /// Iterations (same as `iterations`), SciPy naming.
    #[getter]
    fn nit(&self) -> usize {
        self.iterations
    }
    /// IVPs integrated (same as `evaluations`), SciPy naming.
    #[getter]
    fn nfev(&self) -> usize {
        self.evaluations
    }
    /// Tip position [m] of `solution`, shape `(3,)`.
    #[getter]
    fn tip_position<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(
            py,
            self.solution.bind(py).get().inner.tip_position().as_slice(),
        )
    }
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
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let f = py
            .import("tcarod._core")?
            .getattr("_restore_blocked_result")?;
        let args = (
            self.solution.clone_ref(py),
            self.force,
            self.variables.clone(),
            self.iterations,
            self.evaluations,
        )
            .into_pyobject(py)?;
        Ok((f, args))
    }
    fn __eq__(&self, py: Python<'_>, other: &Bound<'_, PyAny>) -> PyResult<bool> {
        let Ok(o) = other.cast::<PyBlockedResult>() else {
            return Ok(false);
        };
        let o = o.get();
        let same = self.force.to_bits() == o.force.to_bits()
            && self.variables == o.variables
            && self.iterations == o.iterations
            && self.evaluations == o.evaluations;
        Ok(same && self.solution.bind(py).eq(o.solution.bind(py))?)
    }
}

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

/// The Python result; its solution carries the stability verdict with the
/// tip held along `normal` (issue 16: one tangent IVP, an unstable one warns).
fn blocked(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    b: BlockedResult,
    normal: nalgebra::Vector3<f64>,
) -> PyResult<PyBlockedResult> {
    let solution = super::stability::blocked_verdict(py, robot, b.solution, normal)?;
    Ok(PyBlockedResult {
        solution: Py::new(py, solution)?,
        force: b.force,
        variables: b.variables,
        iterations: b.iterations,
        evaluations: b.evaluations,
    })
}

/// Contact force [N] with the tip held on the plane through `point` [m] with
/// unit `normal` (the direction the tip presses in), at actuation `variables`
/// (mixed boundary condition; the force is a shooting unknown).
#[pyfunction]
#[pyo3(signature = (robot, point, normal, variables, *, groups=None, steps=None, tol=Real(1e-10), max_iter=None, warm_start=None),
    text_signature = "(robot, point, normal, variables, *, groups=None, steps=100, tol=1e-10, max_iter=50, warm_start=None)")]
#[allow(clippy::too_many_arguments)]
fn blocked_force(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    point: Bound<'_, PyAny>,
    normal: Bound<'_, PyAny>,
    variables: Bound<'_, PyAny>,
    groups: Option<Bound<'_, PyAny>>,
    steps: Option<Bound<'_, PyAny>>,
    tol: Real,
    max_iter: Option<Bound<'_, PyAny>>,
    warm_start: Option<PyRef<'_, PyBlockedResult>>,
) -> PyResult<PyBlockedResult> {
    let r = robot.get();
    let g = groups_for(r, groups.as_ref())?;
    let block = Block::new(vec3("point [m]", &point)?, vec3("normal", &normal)?)?;
    let variables = reals("variables", &variables, Some(g.n_vars()))?;
    let opts = solve_options(steps.as_ref(), tol, max_iter.as_ref())?;
    if let Some(w) = &warm_start {
        same_robot(py, r, w.solution.bind(py).get(), "warm_start")?;
    }
    let warm = warm_start.map(|w| (w.solution.bind(py).get().inner.clone(), w.force));
    let rr = r.inner.clone();
    let res = super::errors::detach_interruptible(py, || {
        inverse::blocked_force(
            &rr,
            &g,
            &block,
            &variables,
            &opts,
            warm.as_ref().map(|(s, f)| (s, *f)),
        )
    })?;
    blocked(py, robot, res, block.normal)
}

/// The paper's incremental method (eq 43, `dx = 0`): from `start` (a solution
/// of this robot whose tip touches the block with no force), the single
/// actuation variable at which the tip presses with `force` [N], in
/// `increments` steps (1 to 10,000).
#[pyfunction]
#[pyo3(signature = (robot, point, normal, force, start, *, groups=None, increments=None, steps=None, tol=Real(1e-10), max_iter=None),
    text_signature = "(robot, point, normal, force, start, *, groups=None, increments=10, steps=100, tol=1e-10, max_iter=50)")]
#[allow(clippy::too_many_arguments)]
fn blocked_temperature(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    point: Bound<'_, PyAny>,
    normal: Bound<'_, PyAny>,
    force: Real,
    start: PyRef<'_, PySolution>,
    groups: Option<Bound<'_, PyAny>>,
    increments: Option<Bound<'_, PyAny>>,
    steps: Option<Bound<'_, PyAny>>,
    tol: Real,
    max_iter: Option<Bound<'_, PyAny>>,
) -> PyResult<PyBlockedResult> {
    let r = robot.get();
    let g = groups_for(r, groups.as_ref())?;
    same_robot(py, r, &start, "start")?;
    let block = Block::new(vec3("point [m]", &point)?, vec3("normal", &normal)?)?;
    let increments = count_or("increments", increments.as_ref(), 10, 1, MAX_INCREMENTS)?;
    let opts = solve_options(steps.as_ref(), tol, max_iter.as_ref())?;
    let st = start.inner.clone();
    let rr = r.inner.clone();
    let res = super::errors::detach_interruptible(py, || {
        inverse::blocked_temperature(&rr, &g, &block, &st, force.0, increments, &opts)
    })?;
    blocked(py, robot, res, block.normal)
}

/// Direct solve (independent check of `blocked_temperature`): the actuation
/// variable is a shooting unknown starting from `guess` (temperature [C]),
/// the contact force [N] is given.
#[pyfunction]
#[pyo3(signature = (robot, point, normal, force, guess, *, groups=None, steps=None, tol=Real(1e-10), max_iter=None),
    text_signature = "(robot, point, normal, force, guess, *, groups=None, steps=100, tol=1e-10, max_iter=50)")]
#[allow(clippy::too_many_arguments)]
fn blocked_temperature_direct(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    point: Bound<'_, PyAny>,
    normal: Bound<'_, PyAny>,
    force: Real,
    guess: Real,
    groups: Option<Bound<'_, PyAny>>,
    steps: Option<Bound<'_, PyAny>>,
    tol: Real,
    max_iter: Option<Bound<'_, PyAny>>,
) -> PyResult<PyBlockedResult> {
    let r = robot.get();
    let g = groups_for(r, groups.as_ref())?;
    let block = Block::new(vec3("point [m]", &point)?, vec3("normal", &normal)?)?;
    let opts = solve_options(steps.as_ref(), tol, max_iter.as_ref())?;
    let rr = r.inner.clone();
    let res = super::errors::detach_interruptible(py, || {
        inverse::blocked_variable_direct(&rr, &g, &block, force.0, guess.0, &opts, None)
    })?;
    blocked(py, robot, res, block.normal)
}
