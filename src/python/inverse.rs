//! Bindings of the inverse kinetostatics.

use nalgebra::{Matrix3, Vector3};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;

use super::rod::{options, PyRobot, PySolution};
use crate::error::Error;
use crate::inverse::{self, Block, BlockedResult, Groups, InverseOptions, Scheme};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyInverseResult>()?;
    m.add_class::<PyBlockedResult>()?;
    m.add_function(wrap_pyfunction!(sensitivities, m)?)?;
    m.add_function(wrap_pyfunction!(tip_inverse, m)?)?;
    m.add_function(wrap_pyfunction!(blocked_force, m)?)?;
    m.add_function(wrap_pyfunction!(blocked_temperature, m)?)?;
    m.add_function(wrap_pyfunction!(blocked_temperature_direct, m)?)?;
    Ok(())
}

fn groups_for(robot: &PyRobot, groups: Option<Vec<usize>>) -> PyResult<Groups> {
    let g = groups.map_or_else(|| Groups::identity(robot.inner.actuators.len()), Groups);
    g.validate(&robot.inner)?;
    Ok(g)
}

fn dmat<'py>(py: Python<'py>, m: &nalgebra::DMatrix<f64>) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = (0..m.nrows()).flat_map(|i| (0..m.ncols()).map(move |j| m[(i, j)])).collect();
    PyArray1::from_vec(py, flat).reshape([m.nrows(), m.ncols()]).expect("shape")
}

fn vec3(name: &str, a: [f64; 3]) -> PyResult<Vector3<f64>> {
    for (k, x) in a.iter().enumerate() {
        crate::error::finite(&format!("{name}[{k}]"), *x)?;
    }
    Ok(Vector3::from(a))
}

fn wrap(robot: &Bound<'_, PyRobot>, s: crate::shooting::Solution) -> PySolution {
    PySolution {
        inner: s,
        robot: robot.clone().unbind(),
    }
}

/// `(J, C)` at `solution` (eqs 41-42): `J` is `6 x n_vars` (tip `[dp (m); dtheta (rad)]`
/// per unit actuation variable, per C for TCAs), `C` is `6 x 6` (per unit tip wrench
/// `[F (N); M (N m)]`), world frame. `groups[i]` is the variable driving actuator `i`.
#[pyfunction]
#[pyo3(signature = (solution, groups=None, scheme="forward"))]
fn sensitivities<'py>(py: Python<'py>, solution: PyRef<'py, PySolution>, groups: Option<Vec<usize>>, scheme: &str) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<f64>>)> {
    let robot = solution.robot.bind(py).get().clone();
    let g = groups_for(&robot, groups)?;
    let sch = match scheme {
        "forward" => Scheme::Forward,
        "central" => Scheme::Central,
        "exact" => Scheme::Exact,
        _ => return Err(Error::input("scheme", format!("{scheme:?} is not 'forward', 'central' or 'exact'")).into()),
    };
    let sol = solution.inner.clone();
    let s = py.detach(|| inverse::sensitivities(&robot.inner, &sol, &sol.loads, &g, sol.steps, sch))?;
    Ok((dmat(py, &s.jacobian), dmat(py, &s.compliance)))
}

/// Result of a tip-position inverse.
#[pyclass(name = "InverseResult", module = "tcarod._core", frozen)]
pub struct PyInverseResult {
    #[pyo3(get)]
    solution: Py<PySolution>,
    #[pyo3(get)]
    variables: Vec<f64>,
    /// Remaining tip error [m] (plus weighted angle if orientation was asked).
    #[pyo3(get)]
    error: f64,
    #[pyo3(get)]
    iterations: usize,
    #[pyo3(get)]
    reached: bool,
    #[pyo3(get)]
    at_bound: Vec<bool>,
    #[pyo3(get)]
    evaluations: usize,
}

#[pymethods]
impl PyInverseResult {
    fn __repr__(&self) -> String {
        format!(
            "InverseResult(variables={:?}, error={:.3e} m, reached={}, iterations={}, at_bound={:?})",
            self.variables, self.error, self.reached, self.iterations, self.at_bound
        )
    }
}

/// Iterate the local inverse to put the tip at `target` [m] (and, if given,
/// orientation `target_rotation` weighted by `orientation_weight` [m/rad]).
#[pyfunction]
#[pyo3(signature = (robot, target, *, start=None, groups=None, target_rotation=None, orientation_weight=0.01,
    tol=1e-7, max_iter=50, damping=1e-6, steps=100))]
#[allow(clippy::too_many_arguments)]
fn tip_inverse(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    target: [f64; 3],
    start: Option<Vec<f64>>,
    groups: Option<Vec<usize>>,
    target_rotation: Option<[[f64; 3]; 3]>,
    orientation_weight: f64,
    tol: f64,
    max_iter: usize,
    damping: f64,
    steps: usize,
) -> PyResult<PyInverseResult> {
    let r = robot.get();
    let g = groups_for(r, groups)?;
    let t = vec3("target [m]", target)?;
    let rot = match target_rotation {
        Some(m) => {
            let mm = Matrix3::from_fn(|i, j| m[i][j]);
            if !mm.iter().all(|x| x.is_finite()) || (mm.transpose() * mm - Matrix3::identity()).norm() > 1e-6 {
                return Err(Error::input("target_rotation", "must be a 3x3 rotation matrix").into());
            }
            crate::error::positive("orientation_weight [m/rad]", orientation_weight)?;
            Some(mm)
        }
        None => None,
    };
    crate::error::positive("tol [m]", tol)?;
    crate::error::non_negative("damping", damping)?;
    let z0 = start.unwrap_or_else(|| g.vars(&r.inner.reference_inputs()));
    let opts = InverseOptions {
        forward: options(steps, 1e-10, 50)?,
        tol,
        max_iter,
        damping,
    };
    let rr = r.inner.clone();
    let res = super::errors::detach_interruptible(py, || inverse::tip_position_inverse(&rr, &g, &t, rot.as_ref().map(|m| (m, orientation_weight)), &z0, &opts))?;
    Ok(PyInverseResult {
        solution: Py::new(py, wrap(robot, res.solution))?,
        variables: res.variables,
        error: res.error,
        iterations: res.iterations,
        reached: res.reached,
        at_bound: res.at_bound,
        evaluations: res.evaluations,
    })
}

/// A blocked-tip solution: contact `force` [N] and actuation `variables`.
#[pyclass(name = "BlockedResult", module = "tcarod._core", frozen)]
pub struct PyBlockedResult {
    #[pyo3(get)]
    solution: Py<PySolution>,
    #[pyo3(get)]
    force: f64,
    #[pyo3(get)]
    variables: Vec<f64>,
    #[pyo3(get)]
    iterations: usize,
    #[pyo3(get)]
    evaluations: usize,
}

#[pymethods]
impl PyBlockedResult {
    fn __repr__(&self) -> String {
        format!("BlockedResult(force={:.6e} N, variables={:?}, iterations={})", self.force, self.variables, self.iterations)
    }
}

fn blocked(py: Python<'_>, robot: &Bound<'_, PyRobot>, b: BlockedResult) -> PyResult<PyBlockedResult> {
    Ok(PyBlockedResult {
        solution: Py::new(py, wrap(robot, b.solution))?,
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
#[pyo3(signature = (robot, point, normal, variables, *, groups=None, steps=100, tol=1e-10, max_iter=50, warm_start=None))]
#[allow(clippy::too_many_arguments)]
fn blocked_force(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    point: [f64; 3],
    normal: [f64; 3],
    variables: Vec<f64>,
    groups: Option<Vec<usize>>,
    steps: usize,
    tol: f64,
    max_iter: usize,
    warm_start: Option<PyRef<'_, PyBlockedResult>>,
) -> PyResult<PyBlockedResult> {
    let r = robot.get();
    let g = groups_for(r, groups)?;
    let block = Block::new(vec3("point [m]", point)?, vec3("normal", normal)?)?;
    if variables.len() != g.n_vars() {
        return Err(Error::input("variables", format!("expected {} values, got {}", g.n_vars(), variables.len())).into());
    }
    let opts = options(steps, tol, max_iter)?;
    let warm = warm_start.map(|w| (w.solution.bind(py).get().inner.clone(), w.force));
    let rr = r.inner.clone();
    let res = super::errors::detach_interruptible(py, || inverse::blocked_force(&rr, &g, &block, &variables, &opts, warm.as_ref().map(|(s, f)| (s, *f))))?;
    blocked(py, robot, res)
}

/// The paper's incremental method (eq 43, `dx = 0`): from `start` (a solution
/// whose tip touches the block with no force), the single actuation variable at
/// which the tip presses with `force` [N].
#[pyfunction]
#[pyo3(signature = (robot, point, normal, force, start, *, groups=None, increments=10, steps=100, tol=1e-10, max_iter=50))]
#[allow(clippy::too_many_arguments)]
fn blocked_temperature(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    point: [f64; 3],
    normal: [f64; 3],
    force: f64,
    start: PyRef<'_, PySolution>,
    groups: Option<Vec<usize>>,
    increments: usize,
    steps: usize,
    tol: f64,
    max_iter: usize,
) -> PyResult<PyBlockedResult> {
    let r = robot.get();
    let g = groups_for(r, groups)?;
    let block = Block::new(vec3("point [m]", point)?, vec3("normal", normal)?)?;
    let opts = options(steps, tol, max_iter)?;
    let st = start.inner.clone();
    let rr = r.inner.clone();
    let res = super::errors::detach_interruptible(py, || inverse::blocked_temperature(&rr, &g, &block, &st, force, increments, &opts))?;
    blocked(py, robot, res)
}

/// Direct solve (independent check of `blocked_temperature`): the actuation
/// variable is a shooting unknown, the contact force [N] is given.
#[pyfunction]
#[pyo3(signature = (robot, point, normal, force, guess, *, groups=None, steps=100, tol=1e-10, max_iter=50))]
#[allow(clippy::too_many_arguments)]
fn blocked_temperature_direct(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    point: [f64; 3],
    normal: [f64; 3],
    force: f64,
    guess: f64,
    groups: Option<Vec<usize>>,
    steps: usize,
    tol: f64,
    max_iter: usize,
) -> PyResult<PyBlockedResult> {
    let r = robot.get();
    let g = groups_for(r, groups)?;
    let block = Block::new(vec3("point [m]", point)?, vec3("normal", normal)?)?;
    let opts = options(steps, tol, max_iter)?;
    let rr = r.inner.clone();
    let res = super::errors::detach_interruptible(py, || inverse::blocked_variable_direct(&rr, &g, &block, force, guess, &opts, None))?;
    blocked(py, robot, res)
}
