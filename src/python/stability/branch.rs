//! Bindings of branch following and of the stable sweep (`src/branch/`).

use std::sync::Arc;

use nalgebra::Vector3;
use numpy::{PyArray1, PyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use super::{arr1, arr3, finite_margin, same, same_vec3, Reduce};
use crate::branch::{
    follow_branch as follow_core, sweep_stable, BranchOptions, BranchPoint, EventKind, Parameter,
    Problem,
};
use crate::error::{Error, Result};
use crate::python::rod::{solve_options, PyActuator, PyBody, PyRobot, PySolution};
use crate::python::Real;
use crate::python::{count_or, counts, reals};
use crate::rod::Robot;
use crate::shooting::Solution;

pub(super) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyBranch>()?;
    m.add_function(wrap_pyfunction!(follow_branch, m)?)?;
    m.add_function(wrap_pyfunction!(restore_branch, m)?)?;
    Ok(())
}

/// A followed branch of equilibria, or a stable sweep.
///
/// Arrays over its ``k`` points (``parameter``, ``tip_positions`` [m],
/// ``stable``, ``margin`` [-]), the located folds and bifurcations and, for a
/// stable sweep, the jumps. Built by ``tcarod.models.stability.follow_branch``;
/// ``len(branch)`` is ``k``.
///
/// Examples
/// --------
/// >>> from tcarod.paper.buckling import column_robot
/// >>> from tcarod.models.stability import follow_branch
/// >>> column = column_robot()          # a soft column, 50 mm, standing up under 1 g
/// >>> branch = follow_branch(column, "gravity_scale", 0.0, 3.0, steps=20)
/// >>> bool(branch.stable[0]), bool(branch.stable[-1])    # straight: stable, then not
/// (True, False)
/// >>> round(float(branch.bifurcations[0]), 2)          # buckles at 1.54 g
/// 1.54
#[pyclass(name = "Branch", module = "tcarod._core", frozen)]
pub struct PyBranch {
    points: Vec<(f64, Vector3<f64>, bool, f64)>,
    solutions: Vec<Py<PySolution>>,
    events: Vec<(String, f64, Vector3<f64>)>,
    jumps: Vec<(f64, Py<PySolution>, Py<PySolution>)>,
    evaluations: usize,
}

impl PyBranch {
    /// Parameters of the located events of `kind`, shape `(j,)`.
    fn events_of<'py>(&self, py: Python<'py>, kind: &str) -> Bound<'py, PyArray1<f64>> {
        let p: Vec<f64> = self
            .events
            .iter()
            .filter(|e| e.0 == kind)
            .map(|e| e.1)
            .collect();
        arr1(py, &p)
    }
}

#[pymethods]
impl PyBranch {
    /// Parameter value of each point.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(k,)``: input [C, N or m] or scale [-], as followed.
    #[getter]
    fn parameter<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arr1(py, &self.points.iter().map(|p| p.0).collect::<Vec<_>>())
    }
    /// Tip position of each point [m].
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(k, 3)`` [m], world frame.
    #[getter]
    fn tip_positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        arr3(py, &self.points.iter().map(|p| p.1).collect::<Vec<_>>())
    }
    /// Stability of each point.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(k,)``, bool.
    #[getter]
    fn stable<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<bool>> {
        PyArray1::from_vec(py, self.points.iter().map(|p| p.2).collect())
    }
    /// Stability margin of each point [-].
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(k,)`` [-], ``> 0`` where stable.
    #[getter]
    fn margin<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arr1(py, &self.points.iter().map(|p| p.3).collect::<Vec<_>>())
    }
    /// The equilibrium at each point.
    ///
    /// Returns
    /// -------
    /// list of Solution
    ///     ``k`` solutions, in order along the branch.
    #[getter]
    fn solutions(&self, py: Python<'_>) -> Vec<Py<PySolution>> {
        self.solutions.iter().map(|s| s.clone_ref(py)).collect()
    }
    /// Located events along the branch.
    ///
    /// Returns
    /// -------
    /// list of tuple
    ///     ``(kind, parameter, tip position (3,) [m])``, ``kind`` ``"fold"`` or
    ///     ``"bifurcation"``.
    #[getter]
    fn events<'py>(&self, py: Python<'py>) -> Vec<(String, f64, Bound<'py, PyArray1<f64>>)> {
        self.events
            .iter()
            .map(|(k, p, t)| (k.clone(), *p, arr1(py, t.as_slice())))
            .collect()
    }
    /// Parameters of the located folds.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(j,)``, in the parameter's unit.
    #[getter]
    fn folds<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.events_of(py, "fold")
    }
    /// Parameters of the located bifurcations.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(j,)``, in the parameter's unit.
    #[getter]
    fn bifurcations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.events_of(py, "bifurcation")
    }
    /// Jumps of a stable sweep.
    ///
    /// Returns
    /// -------
    /// list of tuple
    ///     ``(parameter, before, after)``: the last stable solution before the
    ///     robot jumps and the stable one it lands on (empty for a branch).
    #[getter]
    fn jumps(&self, py: Python<'_>) -> Vec<(f64, Py<PySolution>, Py<PySolution>)> {
        self.jumps
            .iter()
            .map(|(p, a, b)| (*p, a.clone_ref(py), b.clone_ref(py)))
            .collect()
    }
    /// Integrations spent (IVPs and tangent IVPs) [-].
    ///
    /// Returns
    /// -------
    /// int
    ///     The work of the whole branch.
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

/// Follow the equilibria of ``robot`` in one scalar parameter.
///
/// Pseudo-arclength continuation on multiple shooting from ``start`` to
/// ``end`` through folds, with the stability of every point; the public form is
/// ``tcarod.models.stability.follow_branch``.
///
/// Parameters
/// ----------
/// robot : Robot
///     The robot.
/// parameter : {"inputs", "gravity_scale", "tip_load_scale"}
///     ``"inputs"``: the inputs of ``actuators`` (a temperature [C], tension
///     [N] or pull [m]); ``"gravity_scale"`` and ``"tip_load_scale"`` [-]
///     multiply the body's gravity and its tip load.
/// start, end : float
///     The parameter's range.
/// actuators : sequence of int, optional
///     The actuators driven by ``"inputs"`` (default all).
/// inputs : sequence of float, optional
///     The other actuators' inputs (default the reference inputs).
/// step, max_step : float, optional
///     First and largest arclength step, in units of ``|end - start|``
///     (defaults 0.02 and 0.1).
/// max_points : int, optional
///     Point budget (default 500).
/// stable_only : bool, optional
///     Sweep mode: stay on stable equilibria and record the jumps.
/// warm_start : Solution, optional
///     An equilibrium at ``start`` to begin on (one of coexisting shapes).
/// steps : int, optional
///     RK4 steps over the body (default 100).
/// tol : float, optional
///     Newton tolerance on the dimensionless residual (default 1e-10).
/// max_iter : int, optional
///     Iterations of each point's corrector (default 50; at most 8 are used).
///
/// Returns
/// -------
/// Branch
///     The points, events and jumps.
///
/// Raises
/// ------
/// ValueError
///     An argument outside its range (named, with its unit).
///
/// Examples
/// --------
/// >>> from tcarod import _core
/// >>> from tcarod.paper.buckling import column_robot
/// >>> branch = _core.follow_branch(column_robot(), parameter="gravity_scale", start=0.0, end=3.0, steps=20)
/// >>> round(float(branch.bifurcations[0]), 2)       # gravity scale [-] where the column buckles
/// 1.54
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
    let par = parameter_arg(parameter, actuators.as_ref(), &r)?;
    let n_act = r.actuators.len();
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
        if w.unknowns.len() != 6 + n_act {
            return Err(Error::input(
                "warm_start",
                "solution of a robot with a different number of actuators",
            )
            .into());
        }
    }
    let run = Run {
        pb: &pb,
        acts: &acts,
        opts: &opts,
        warm: warm.as_ref(),
    };
    if stable_only {
        run.stable_sweep(py)
    } else {
        run.branch(py)
    }
}

/// The `parameter` (and `actuators`) arguments.
fn parameter_arg(
    parameter: &str,
    actuators: Option<&Bound<'_, PyAny>>,
    r: &Robot,
) -> PyResult<Parameter> {
    let n_act = r.actuators.len();
    let actuators = match actuators.filter(|o| !o.is_none()) {
        Some(o) => {
            if n_act == 0 {
                return Err(Error::input("actuators", "the robot has no actuators").into());
            }
            Some(counts("actuators", o, n_act - 1)?)
        }
        None => None,
    };
    Ok(parse_parameter(parameter, actuators, r)?)
}

/// One `follow_branch` call: the problem, the actuators its robots are
/// rebuilt with, the options and the equilibrium to start on.
struct Run<'a, 'r> {
    pb: &'a Problem<'r>,
    acts: &'a [PyActuator],
    opts: &'a BranchOptions,
    warm: Option<&'a Solution>,
}

impl Run<'_, '_> {
    /// The stable sweep as a `Branch` with its jumps.
    fn stable_sweep(&self, py: Python<'_>) -> PyResult<PyBranch> {
        let (pb, acts) = (self.pb, self.acts);
        let sw = super::super::errors::detach_interruptible(py, || {
            sweep_stable(pb, self.opts, self.warm)
        })?;
        let mut out = collect(py, pb, acts, sw.points, vec![], sw.evaluations)?;
        for j in sw.jumps {
            out.jumps.push((
                j.parameter,
                wrap(py, pb, acts, j.parameter, j.before)?,
                wrap(py, pb, acts, j.parameter, j.after)?,
            ));
        }
        Ok(out)
    }

    /// The followed branch with its located events.
    fn branch(&self, py: Python<'_>) -> PyResult<PyBranch> {
        let (pb, acts) = (self.pb, self.acts);
        let br = super::super::errors::detach_interruptible(py, || {
            follow_core(pb, self.opts, self.warm)
        })?;
        let events = br
            .events
            .iter()
            .map(|e| {
                let kind = match e.kind {
                    EventKind::Fold => "fold",
                    EventKind::Bifurcation => "bifurcation",
                };
                (kind.to_string(), e.parameter, e.tip_position)
            })
            .collect();
        collect(py, pb, acts, br.points, events, br.evaluations)
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
        let robot = robot_at(py, pb, acts, p.parameter)?;
        let sol = PySolution::new(p.solution, robot);
        // the point's verdict is the solution's (no second tangent IVP)
        let _ = sol.verdict.set((st.stable, st.margin));
        out.solutions.push(Py::new(py, sol)?);
    }
    Ok(out)
}
