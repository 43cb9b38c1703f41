//! Bindings of the stability verdict and of branch following (issue 16).

use std::sync::Arc;

use nalgebra::Vector3;
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use super::rod::{solve_options, PyActuator, PyBody, PyRobot, PySolution};
use super::Real;
use super::{count_or, counts, reals};
use crate::branch::{
    follow_branch as follow_core, sweep_stable, BranchOptions, BranchPoint, EventKind, Parameter,
    Problem,
};
use crate::error::{Error, Result};
use crate::rod::Robot;
use crate::shooting::Solution;
use crate::stability::{stability as stability_core, Stability};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyStability>()?;
    m.add_class::<PyBranch>()?;
    m.add_function(wrap_pyfunction!(stability, m)?)?;
    m.add_function(wrap_pyfunction!(follow_branch, m)?)?;
    m.add_function(wrap_pyfunction!(restore_stability, m)?)?;
    m.add_function(wrap_pyfunction!(restore_branch, m)?)?;
    Ok(())
}

/// Stability verdict of one equilibrium (see `tcarod.stability`).
#[pyclass(name = "Stability", module = "tcarod._core", frozen)]
pub struct PyStability {
    inner: Stability,
}

/// Exact equality of two floats, NaN equal to NaN (pickle support).
fn same(a: f64, b: f64) -> bool {
    a == b || (a.is_nan() && b.is_nan())
}

fn same_all(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| same(*x, *y))
}

fn same_vec3(a: &Vector3<f64>, b: &Vector3<f64>) -> bool {
    same_all(a.as_slice(), b.as_slice())
}

/// What `__reduce__` returns: a rebuilding callable and its arguments.
type Reduce<'py> = PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)>;

fn arr1<'py>(py: Python<'py>, v: &[f64]) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, v)
}

fn arr3<'py>(py: Python<'py>, v: &[Vector3<f64>]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = v.iter().flat_map(|x| [x.x, x.y, x.z]).collect();
    PyArray1::from_vec(py, flat)
        .reshape([v.len(), 3])
        .expect("n x 3")
}

#[pymethods]
impl PyStability {
    /// True if the equilibrium is stable (a strict local energy minimum, up
    /// to neutral symmetry modes).
    #[getter]
    fn stable(&self) -> bool {
        self.inner.stable
    }
    /// Smallest eigenvalue of the dimensionless tip stiffness [-]: > 0 iff stable.
    #[getter]
    fn margin(&self) -> f64 {
        self.inner.margin
    }
    /// Arc length [m] of the first conjugate point, or None.
    #[getter]
    fn conjugate_point(&self) -> Option<f64> {
        self.inner.conjugate_point
    }
    /// Arc length of the nodes [m], shape `(n,)`.
    #[getter]
    fn s<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arr1(py, &self.inner.s)
    }
    /// Till and Rucker's determinant `det(Y(s) Y(0)^-1)` [-] at the nodes.
    #[getter]
    fn determinant<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let v: Vec<f64> = self
            .inner
            .determinant
            .iter()
            .map(|x| if x.is_finite() { *x } else { 0.0 })
            .collect();
        arr1(py, &v)
    }
    /// Smallest eigenvalue of the truncated rod's tip stiffness [-] at the
    /// nodes (the base node, where it is infinite, carries the largest float).
    #[getter]
    fn min_stiffness<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let v: Vec<f64> = self
            .inner
            .min_stiffness
            .iter()
            .map(|x| x.clamp(-f64::MAX, f64::MAX))
            .collect();
        arr1(py, &v)
    }
    /// Softest tip mode `(dp / L, dtheta)` (world frame), shape `(6,)`.
    #[getter]
    fn mode<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arr1(py, &self.inner.mode)
    }
    /// Integrations spent on the verdict (1 tangent IVP).
    #[getter]
    fn evaluations(&self) -> usize {
        self.inner.evaluations
    }
    fn __repr__(&self) -> String {
        format!(
            "Stability(stable={}, margin={:.6e}, conjugate_point={:?})",
            if self.inner.stable { "True" } else { "False" },
            self.inner.margin,
            self.inner.conjugate_point
        )
    }
    /// Pickle support.
    fn __reduce__<'py>(&self, py: Python<'py>) -> Reduce<'py> {
        let f = py.import("tcarod._core")?.getattr("_restore_stability")?;
        let s = &self.inner;
        let args = (
            s.stable,
            s.margin,
            s.conjugate_point,
            s.s.clone(),
            s.determinant.clone(),
            s.min_stiffness.clone(),
            s.evaluations,
            s.mode.to_vec(),
        )
            .into_pyobject(py)?;
        Ok((f, args))
    }
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        let Ok(o) = other.cast::<PyStability>() else {
            return false;
        };
        let (a, b) = (&self.inner, &o.get().inner);
        a.stable == b.stable
            && same(a.margin, b.margin)
            && match (a.conjugate_point, b.conjugate_point) {
                (Some(x), Some(y)) => same(x, y),
                (None, None) => true,
                _ => false,
            }
            && same_all(&a.s, &b.s)
            && same_all(&a.determinant, &b.determinant)
            && same_all(&a.min_stiffness, &b.min_stiffness)
            && a.evaluations == b.evaluations
            && same_all(&a.mode, &b.mode)
    }
}

/// Rebuild a `Stability` (pickle support; not public API).
#[pyfunction]
#[pyo3(name = "_restore_stability")]
#[allow(clippy::too_many_arguments)]
fn restore_stability(
    stable: bool,
    margin: f64,
    conjugate_point: Option<f64>,
    s: Vec<f64>,
    determinant: Vec<f64>,
    min_stiffness: Vec<f64>,
    evaluations: usize,
    mode: Vec<f64>,
) -> PyResult<PyStability> {
    let mode: [f64; 6] = mode
        .try_into()
        .map_err(|_| PyValueError::new_err("mode: expected 6 values"))?;
    if determinant.len() != s.len() || min_stiffness.len() != s.len() {
        return Err(PyValueError::new_err(
            "s, determinant and min_stiffness must have the same length",
        ));
    }
    Ok(PyStability {
        inner: Stability {
            stable,
            margin,
            conjugate_point,
            s,
            determinant,
            min_stiffness,
            evaluations,
            mode,
        },
    })
}

pub(crate) fn finite_margin(mut s: Stability) -> Stability {
    if !s.margin.is_finite() {
        s.margin = if s.margin > 0.0 { f64::MAX } else { -f64::MAX };
    }
    s
}

/// Stability of `solution`, an equilibrium of `robot`. `blocked`: world
/// directions `(k, 3)` along which the tip translation is held (a blocked-tip
/// solution's block normal). Raises ValueError if the solution is not one of
/// this robot's.
#[pyfunction]
#[pyo3(signature = (robot, solution, *, blocked=None), text_signature = "(robot, solution, *, blocked=None)")]
fn stability(
    py: Python<'_>,
    robot: PyRef<'_, PyRobot>,
    solution: PyRef<'_, PySolution>,
    blocked: Option<Vec<[Real; 3]>>,
) -> PyResult<PyStability> {
    let r = robot.inner.clone();
    let sol = solution.inner.clone();
    let blocked: Vec<Vector3<f64>> = blocked
        .unwrap_or_default()
        .into_iter()
        .map(|b| Vector3::new(b[0].0, b[1].0, b[2].0))
        .collect();
    let st = py.detach(|| stability_core(&r, &sol, &blocked))?;
    Ok(PyStability {
        inner: finite_margin(st),
    })
}

/// A followed branch or a stable sweep: arrays over its points, located
/// events and (sweep) jumps.
#[pyclass(name = "Branch", module = "tcarod._core", frozen)]
pub struct PyBranch {
    points: Vec<(f64, Vector3<f64>, bool, f64)>,
    solutions: Vec<Py<PySolution>>,
    events: Vec<(String, f64, Vector3<f64>)>,
    jumps: Vec<(f64, Py<PySolution>, Py<PySolution>)>,
    evaluations: usize,
}

#[pymethods]
impl PyBranch {
    /// Parameter value of each point, shape `(k,)`.
    #[getter]
    fn parameter<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arr1(py, &self.points.iter().map(|p| p.0).collect::<Vec<_>>())
    }
    /// Tip position of each point [m], shape `(k, 3)`.
    #[getter]
    fn tip_positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        arr3(py, &self.points.iter().map(|p| p.1).collect::<Vec<_>>())
    }
    /// Stability of each point, shape `(k,)`, bool.
    #[getter]
    fn stable<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<bool>> {
        PyArray1::from_vec(py, self.points.iter().map(|p| p.2).collect())
    }
    /// Stability margin of each point [-], shape `(k,)`.
    #[getter]
    fn margin<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arr1(py, &self.points.iter().map(|p| p.3).collect::<Vec<_>>())
    }
    /// The equilibrium at each point.
    #[getter]
    fn solutions(&self, py: Python<'_>) -> Vec<Py<PySolution>> {
        self.solutions.iter().map(|s| s.clone_ref(py)).collect()
    }
    /// Located events `(kind, parameter, tip position [m] (3,))`, kind
    /// `"fold"` or `"bifurcation"`.
    #[getter]
    fn events<'py>(&self, py: Python<'py>) -> Vec<(String, f64, Bound<'py, PyArray1<f64>>)> {
        self.events
            .iter()
            .map(|(k, p, t)| (k.clone(), *p, arr1(py, t.as_slice())))
            .collect()
    }
    /// Parameters of the located folds, shape `(j,)`.
    #[getter]
    fn folds<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arr1(
            py,
            &self
                .events
                .iter()
                .filter(|e| e.0 == "fold")
                .map(|e| e.1)
                .collect::<Vec<_>>(),
        )
    }
    /// Parameters of the located bifurcations, shape `(j,)`.
    #[getter]
    fn bifurcations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arr1(
            py,
            &self
                .events
                .iter()
                .filter(|e| e.0 == "bifurcation")
                .map(|e| e.1)
                .collect::<Vec<_>>(),
        )
    }
    /// Jumps of a stable sweep: `(parameter, before, after)` solutions.
    #[getter]
    fn jumps(&self, py: Python<'_>) -> Vec<(f64, Py<PySolution>, Py<PySolution>)> {
        self.jumps
            .iter()
            .map(|(p, a, b)| (*p, a.clone_ref(py), b.clone_ref(py)))
            .collect()
    }
    /// Integrations spent (IVPs and tangent IVPs).
    #[getter]
    fn evaluations(&self) -> usize {
        self.evaluations
    }
    fn __len__(&self) -> usize {
        self.points.len()
    }
    fn __repr__(&self) -> String {
        format!(
            "Branch({} points, {} events, {} jumps)",
            self.points.len(),
            self.events.len(),
            self.jumps.len()
        )
    }
    /// Pickle support (the solutions travel with their robots).
    fn __reduce__<'py>(&self, py: Python<'py>) -> Reduce<'py> {
        let f = py.import("tcarod._core")?.getattr("_restore_branch")?;
        let points: Vec<(f64, [f64; 3], bool, f64)> = self
            .points
            .iter()
            .map(|p| (p.0, [p.1.x, p.1.y, p.1.z], p.2, p.3))
            .collect();
        let events: Vec<(String, f64, [f64; 3])> = self
            .events
            .iter()
            .map(|e| (e.0.clone(), e.1, [e.2.x, e.2.y, e.2.z]))
            .collect();
        let args = (
            points,
            self.solutions(py),
            events,
            self.jumps(py),
            self.evaluations,
        )
            .into_pyobject(py)?;
        Ok((f, args))
    }
    fn __eq__(&self, py: Python<'_>, other: &Bound<'_, PyAny>) -> PyResult<bool> {
        let Ok(o) = other.cast::<PyBranch>() else {
            return Ok(false);
        };
        let o = o.get();
        let same_fields = self.evaluations == o.evaluations
            && self.points.len() == o.points.len()
            && self.points.iter().zip(&o.points).all(|(a, b)| {
                same(a.0, b.0) && same_vec3(&a.1, &b.1) && a.2 == b.2 && same(a.3, b.3)
            })
            && self.events.len() == o.events.len()
            && self
                .events
                .iter()
                .zip(&o.events)
                .all(|(a, b)| a.0 == b.0 && same(a.1, b.1) && same_vec3(&a.2, &b.2))
            && self.solutions.len() == o.solutions.len()
            && self.jumps.len() == o.jumps.len()
            && self.jumps.iter().zip(&o.jumps).all(|(a, b)| same(a.0, b.0));
        if !same_fields {
            return Ok(false);
        }
        for (a, b) in self.solutions.iter().zip(&o.solutions) {
            if !a.bind(py).eq(b.bind(py))? {
                return Ok(false);
            }
        }
        for (a, b) in self.jumps.iter().zip(&o.jumps) {
            if !a.1.bind(py).eq(b.1.bind(py))? || !a.2.bind(py).eq(b.2.bind(py))? {
                return Ok(false);
            }
        }
        Ok(true)
    }
}

/// A followed point as pickled: `(parameter, tip position, stable, margin)`.
type PointArgs = (f64, [f64; 3], bool, f64);

/// Rebuild a `Branch` (pickle support; not public API).
#[pyfunction]
#[pyo3(name = "_restore_branch")]
fn restore_branch(
    points: Vec<PointArgs>,
    solutions: Vec<Py<PySolution>>,
    events: Vec<(String, f64, [f64; 3])>,
    jumps: Vec<(f64, Py<PySolution>, Py<PySolution>)>,
    evaluations: usize,
) -> PyResult<PyBranch> {
    if solutions.len() != points.len() {
        return Err(PyValueError::new_err(
            "points and solutions must have the same length",
        ));
    }
    Ok(PyBranch {
        points: points
            .into_iter()
            .map(|(p, t, s, m)| (p, Vector3::from(t), s, m))
            .collect(),
        solutions,
        events: events
            .into_iter()
            .map(|(k, p, t)| (k, p, Vector3::from(t)))
            .collect(),
        jumps,
        evaluations,
    })
}

fn parse_parameter(name: &str, actuators: Option<Vec<usize>>, robot: &Robot) -> Result<Parameter> {
    match name {
        "gravity_scale" => Ok(Parameter::GravityScale),
        "tip_load_scale" => Ok(Parameter::TipLoadScale),
        "inputs" => Ok(Parameter::Inputs(
            actuators.unwrap_or_else(|| (0..robot.actuators.len()).collect()),
        )),
        _ => Err(Error::input(
            "parameter",
            format!("{name:?}: expected 'inputs', 'gravity_scale' or 'tip_load_scale'"),
        )),
    }
}

/// The robot at one parameter value, as a Python `Robot` (gravity and tip loads applied).
fn robot_at(
    py: Python<'_>,
    pb: &Problem<'_>,
    acts: &[PyActuator],
    lambda: f64,
) -> PyResult<Py<PyRobot>> {
    let (mut robot, _, loads) = pb.at(lambda)?;
    robot.body.tip_force = loads.tip_force;
    robot.body.tip_moment = loads.tip_moment;
    let body = PyBody {
        inner: robot.body.clone(),
    };
    Py::new(
        py,
        PyRobot {
            inner: Arc::new(robot),
            body,
            actuators: acts.to_vec(),
        },
    )
}

fn wrap(
    py: Python<'_>,
    pb: &Problem<'_>,
    acts: &[PyActuator],
    lambda: f64,
    s: Solution,
) -> PyResult<Py<PySolution>> {
    let robot = robot_at(py, pb, acts, lambda)?;
    Py::new(py, PySolution::new(s, robot))
}

/// Follow the equilibria of `robot` in one scalar `parameter` from `start`
/// to `end` by pseudo-arclength continuation, through folds, with the
/// stability of every point (see `tcarod.stability.follow_branch`).
/// `parameter`: `"inputs"` (the inputs of `actuators`, default all: a
/// temperature [C], tension [N] or pull [m]), `"gravity_scale"` or
/// `"tip_load_scale"` [-]. `inputs`: the other actuators' inputs (default
/// the reference inputs). `stable_only`: sweep mode, stay on stable
/// equilibria and record the jumps. `warm_start`: an equilibrium at `start`
/// (or near it) to begin on, e.g. one of several coexisting shapes.
#[pyfunction]
#[pyo3(signature = (robot, *, parameter, start, end, actuators=None, inputs=None, step=Real(0.02), max_step=Real(0.1), max_points=None, stable_only=false, warm_start=None, steps=None, tol=Real(1e-10), max_iter=None),
    text_signature = "(robot, *, parameter, start, end, actuators=None, inputs=None, step=0.02, max_step=0.1, max_points=500, stable_only=False, warm_start=None, steps=100, tol=1e-10, max_iter=50)")]
#[allow(clippy::too_many_arguments)]
fn follow_branch(
    py: Python<'_>,
    robot: PyRef<'_, PyRobot>,
    parameter: &str,
    start: Real,
    end: Real,
    actuators: Option<Bound<'_, PyAny>>,
    inputs: Option<Bound<'_, PyAny>>,
    step: Real,
    max_step: Real,
    max_points: Option<Bound<'_, PyAny>>,
    stable_only: bool,
    warm_start: Option<PyRef<'_, PySolution>>,
    steps: Option<Bound<'_, PyAny>>,
    tol: Real,
    max_iter: Option<Bound<'_, PyAny>>,
) -> PyResult<PyBranch> {
    let r = robot.inner.clone();
    let acts = robot.actuators.clone();
    let n_act = r.actuators.len();
    let actuators = match actuators.as_ref().filter(|o| !o.is_none()) {
        Some(o) => {
            if n_act == 0 {
                return Err(Error::input("actuators", "the robot has no actuators").into());
            }
            Some(counts("actuators", o, n_act - 1)?)
        }
        None => None,
    };
    let par = parse_parameter(parameter, actuators, &r)?;
    let q = match inputs.as_ref().filter(|o| !o.is_none()) {
        Some(o) => reals("inputs", o, Some(n_act))?,
        None => r.reference_inputs(),
    };
    let max_points = count_or("max_points", max_points.as_ref(), 500, 2, 100_000)?;
    let solve = solve_options(steps.as_ref(), tol, max_iter.as_ref())?;
    let opts = BranchOptions {
        start: start.0,
        end: end.0,
        step: step.0,
        max_step: max_step.0,
        min_step: (1e-6f64).min(step.0),
        max_points,
        stop_when_unstable: false,
        solve,
    };
    let pb = Problem::new(&r, par, &q)?;
    let warm = warm_start.map(|w| w.inner.clone());
    if let Some(w) = &warm {
        if w.unknowns.len() != 6 + r.actuators.len() {
            return Err(Error::input(
                "warm_start",
                "solution of a robot with a different number of actuators",
            )
            .into());
        }
    }
    if stable_only {
        let sw =
            super::errors::detach_interruptible(py, || sweep_stable(&pb, &opts, warm.as_ref()))?;
        let mut out = collect(py, &pb, &acts, sw.points, vec![], sw.evaluations)?;
        for j in sw.jumps {
            out.jumps.push((
                j.parameter,
                wrap(py, &pb, &acts, j.parameter, j.before)?,
                wrap(py, &pb, &acts, j.parameter, j.after)?,
            ));
        }
        Ok(out)
    } else {
        let br =
            super::errors::detach_interruptible(py, || follow_core(&pb, &opts, warm.as_ref()))?;
        let events = br
            .events
            .iter()
            .map(|e| {
                (
                    if e.kind == EventKind::Fold {
                        "fold"
                    } else {
                        "bifurcation"
                    }
                    .to_string(),
                    e.parameter,
                    e.tip_position,
                )
            })
            .collect();
        collect(py, &pb, &acts, br.points, events, br.evaluations)
    }
}

fn collect(
    py: Python<'_>,
    pb: &Problem<'_>,
    acts: &[PyActuator],
    points: Vec<BranchPoint>,
    events: Vec<(String, f64, Vector3<f64>)>,
    evaluations: usize,
) -> PyResult<PyBranch> {
    let mut out = PyBranch {
        points: vec![],
        solutions: vec![],
        events,
        jumps: vec![],
        evaluations,
    };
    for p in points {
        let st = finite_margin(p.stability);
        out.points
            .push((p.parameter, p.solution.tip_position(), st.stable, st.margin));
        out.solutions
            .push(wrap(py, pb, acts, p.parameter, p.solution)?);
    }
    Ok(out)
}
