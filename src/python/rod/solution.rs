//! Bindings of a converged forward solution.

use std::sync::OnceLock;

use nalgebra::Vector3;
use numpy::{PyArray1, PyArray2, PyArray3, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use super::robot::PyRobot;
use crate::error::{Error, Result};
use crate::python::outcome::{scipy_fields, Outcome};
use crate::python::to_py::{mat3, reduce_with, stack3, vec3, Reduce};
use crate::python::{pb, pv};
use crate::shooting::{Solution, Status};

/// Every number of a solution is finite (the IVP rejects non-finite
/// derivatives, so this holds by construction; checked once more at the
/// boundary so that no getter can hand NaN to Python).
pub(crate) fn checked_solution(sol: Solution) -> Result<Solution> {
    let vecs = sol
        .positions
        .iter()
        .chain(&sol.nu)
        .chain(&sol.omega)
        .chain(&sol.internal_force)
        .chain(&sol.internal_moment)
        .chain(sol.actuator_paths.iter().flatten())
        .chain([&sol.base_force, &sol.base_moment]);
    let ok = vecs.flat_map(|v| v.iter()).all(|x| x.is_finite())
        && sol
            .rotations
            .iter()
            .all(|r| r.iter().all(|x| x.is_finite()))
        && sol
            .s
            .iter()
            .chain(&sol.tensions)
            .chain(&sol.elongations)
            .chain(&sol.unknowns)
            .all(|x| x.is_finite())
        && sol.elongation_profile.iter().all(|x| x.is_finite())
        && sol.residual.is_finite();
    if ok {
        Ok(sol)
    } else {
        Err(Error::Integration {
            s: sol.s.last().copied().unwrap_or(0.0),
            reason: "the solution holds a non-finite value".into(),
        })
    }
}

/// A converged forward solution: the robot's shape and what held it there.
///
/// Returned by `Robot.solve`. Arrays are NumPy, SI units, world frame unless
/// noted; `n` nodes along the body. SciPy-style fields: `success` (always
/// `True`: a failed solve raises `ConvergenceError`), `status`, `message`,
/// `nit` (Newton iterations), `nfev` (IVPs). Naming: `tip_position` [m] per
/// solve, `tip_positions` per batch (`tcarod.batch.BatchResult`). Stability:
/// `stable` and `stability_margin`, computed by the solve (policy
/// `"report"`, the default) or on first access (one tangent IVP), cached;
/// `continued` records a `stability="continue"` solve's route. Picklable
/// (with its robot) and comparable with `==`.
///
/// Examples
/// --------
/// >>> from tcarod.batch import fig6_square_robot
/// >>> sol = fig6_square_robot().solve([100.0, 100.0])   # the paper's Fig. 6 square
/// >>> sol.positions.shape, sol.tensions.shape            # (n, 3) [m], one tension per TCA [N]
/// ((101, 3), (2,))
/// >>> round(float(sol.tip_position[0]) * 1e3, 2), sol.stable   # tip x [mm]
/// (-6.13, True)
#[pyclass(name = "Solution", module = "tcarod._core", frozen, eq)]
pub struct PySolution {
    pub(crate) inner: Solution,
    pub(crate) robot: Py<PyRobot>,
    /// Cached stability verdict `(stable, margin)` (`crate::stability`).
    pub(crate) verdict: OnceLock<(bool, f64)>,
    /// World directions along which the tip translation is held (the block
    /// normal of a blocked-tip solution; empty for a free tip).
    pub(crate) blocked: Vec<Vector3<f64>>,
    /// How `stability="continue"` reached this equilibrium, if it moved.
    pub(crate) continued: Option<Py<crate::python::stability::Continuation>>,
}

impl PySolution {
    /// A solution of `robot`; its stability verdict is computed lazily.
    pub(crate) fn new(inner: Solution, robot: Py<PyRobot>) -> Self {
        PySolution {
            inner,
            robot,
            verdict: OnceLock::new(),
            blocked: Vec::new(),
            continued: None,
        }
    }

    /// The cached verdict, computing it (GIL released) on first use.
    pub(crate) fn verdict(&self, py: Python<'_>) -> PyResult<(bool, f64)> {
        if let Some(v) = self.verdict.get() {
            return Ok(*v);
        }
        let robot = self.robot.bind(py).get().inner.clone();
        let sol = &self.inner;
        let blocked = &self.blocked;
        let st = py.detach(|| crate::stability::stability(&robot, sol, blocked))?;
        let st = crate::python::stability::finite_margin(st);
        Ok(*self.verdict.get_or_init(|| (st.stable, st.margin)))
    }
}

/// SciPy-style status code of a converged solve: 0 = `tol` met, 1 = `tol`
/// lies below the estimated rounding floor and the residual reached the
/// floor (both successes, as in `scipy.optimize.least_squares`).
fn status_code(s: Status) -> i64 {
    match s {
        Status::Converged => 0,
        Status::ConvergedAtFloor => 1,
    }
}

impl Outcome for PySolution {
    fn status_code(&self) -> i64 {
        status_code(self.inner.status)
    }
    fn status_message(&self) -> String {
        let how = match self.inner.status {
            Status::Converged => "converged".to_string(),
            Status::ConvergedAtFloor => format!(
                "converged at the rounding floor {:.3e} (tol below it)",
                self.inner.floor
            ),
        };
        let path = if self.inner.continuation_steps.is_empty() {
            String::new()
        } else {
            format!(
                " ({} continuation steps)",
                self.inner.continuation_steps.len()
            )
        };
        format!(
            "{how}: residual {:.3e} after {} Newton iterations{path}",
            self.inner.residual, self.inner.iterations
        )
    }
    fn iteration_count(&self) -> usize {
        self.inner.iterations
    }
    fn ivp_count(&self) -> usize {
        self.inner.evaluations
    }
    /// Every `Solution` is a success (a failed solve raises).
    fn succeeded(&self) -> bool {
        true
    }
}

scipy_fields!(
    PySolution,
    "Status code of the solve (SciPy naming).\n\n\
     Returns\n\
     -------\n\
     int\n    \
     `0` converged to `tol`; `1` `tol` lies below the estimated rounding \
     floor and the residual reached the floor (`floor`). Both are \
     successes, as in `scipy.optimize.least_squares`; a solve that fails \
     raises `ConvergenceError` instead."
);

#[pymethods]
impl PySolution {
    /// The robot that was solved.
    ///
    /// Returns
    /// -------
    /// Robot
    ///     The design (`body`, `actuators`) this solution belongs to.
    #[getter]
    fn robot(&self, py: Python<'_>) -> Py<PyRobot> {
        self.robot.clone_ref(py)
    }
    /// Arc length of each node [m].
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(n,)``, from 0 at the base to the body length at the tip [m].
    #[getter]
    fn s<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.inner.s)
    }
    /// Centre-line positions [m], world frame.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(n, 3)``: the position ``p(s)`` of each node [m].
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        stack3(py, &self.inner.positions)
    }
    /// Body-to-world rotation matrices [-].
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(n, 3, 3)``; column 3 of each is the tangent ``R e3``.
    #[getter]
    fn rotations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f64>> {
        let flat: Vec<f64> = self
            .inner
            .rotations
            .iter()
            .flat_map(|r| (0..3).flat_map(move |i| (0..3).map(move |j| r[(i, j)])))
            .collect();
        PyArray1::from_vec(py, flat)
            .reshape([self.inner.rotations.len(), 3, 3])
            .expect("n x 3 x 3")
    }
    /// Linear strain ``nu`` [-], body frame.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(n, 3)``; ``(0, 0, 1)`` where the body is neither sheared nor
    ///     stretched.
    #[getter]
    fn nu<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        stack3(py, &self.inner.nu)
    }
    /// Angular strain (curvature and twist) ``omega`` [1/m], body frame.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(n, 3)`` [1/m].
    #[getter]
    fn omega<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        stack3(py, &self.inner.omega)
    }
    /// Internal force ``n`` [N], world frame.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(n, 3)`` [N]: the force the distal part exerts on the proximal
    ///     part across each section.
    #[getter]
    fn internal_force<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        stack3(py, &self.inner.internal_force)
    }
    /// Internal moment ``m`` [N m], world frame.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(n, 3)`` [N m].
    #[getter]
    fn internal_moment<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        stack3(py, &self.inner.internal_moment)
    }
    /// Elongation of each actuator accumulated up to each node [m].
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(n, n_actuators)`` [m]; the last row is ``elongations``.
    #[getter]
    fn elongation_profile<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let na = self.inner.tensions.len();
        // (nodes x actuators, column-major: rows to the flat row-major array)
        let flat: Vec<f64> = self
            .inner
            .elongation_profile
            .transpose()
            .as_slice()
            .to_vec();
        PyArray1::from_vec(py, flat)
            .reshape([self.inner.s.len(), na])
            .expect("n x na")
    }
    /// Path ``p + R r_i`` of each actuator over its span [m], world frame.
    ///
    /// Returns
    /// -------
    /// list of numpy.ndarray
    ///     One ``(k_i, 3)`` array per actuator [m].
    #[getter]
    fn actuator_paths<'py>(&self, py: Python<'py>) -> Vec<Bound<'py, PyArray2<f64>>> {
        self.inner
            .actuator_paths
            .iter()
            .map(|p| stack3(py, p))
            .collect()
    }
    /// Actuator tensions [N] (negative: the actuator pushes).
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(n_actuators,)`` [N].
    #[getter]
    fn tensions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.inner.tensions)
    }
    /// Total elongation of each actuator [m].
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(n_actuators,)`` [m].
    #[getter]
    fn elongations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.inner.elongations)
    }
    /// The inputs solved for, one per actuator.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(n_actuators,)``: temperature [C] for a TCA, tension [N] for a
    ///     tendon, pull [m] for a linear tendon.
    #[getter]
    fn inputs<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.inner.inputs)
    }
    /// Force [N] transmitted to the base by the body and the actuators.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(3,)`` [N], world frame; the base reaction is its negative.
    #[getter]
    fn base_force<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.base_force)
    }
    /// Moment [N m] about the origin transmitted to the base.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(3,)`` [N m], world frame.
    #[getter]
    fn base_moment<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.base_moment)
    }
    /// Tip position [m], world frame.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(3,)`` [m].
    #[getter]
    fn tip_position<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.tip_position())
    }
    /// Tip rotation matrix (body to world) [-].
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(3, 3)``; column 3 is the tip tangent.
    #[getter]
    fn tip_rotation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        mat3(py, &self.inner.tip_rotation())
    }
    /// Newton iterations used (same as ``nit``).
    ///
    /// Returns
    /// -------
    /// int
    ///     Iterations of the last Newton solve [-].
    #[getter]
    fn iterations(&self) -> usize {
        self.inner.iterations
    }
    /// IVPs integrated (same as ``nfev``).
    ///
    /// Returns
    /// -------
    /// int
    ///     Integrations of the rod's ODE over the body, continuation included [-].
    #[getter]
    fn evaluations(&self) -> usize {
        self.inner.evaluations
    }
    /// Final residual of the shooting problem [-].
    ///
    /// Returns
    /// -------
    /// float
    ///     Max-norm of the dimensionless shooting residual [-].
    #[getter]
    fn residual(&self) -> f64 {
        self.inner.residual
    }
    /// Estimated rounding floor of the dimensionless residual [-].
    ///
    /// Returns
    /// -------
    /// float
    ///     The residual cannot be computed more accurately than this at the
    ///     solution; a ``tol`` below it converges to it (``status == 1``).
    #[getter]
    fn floor(&self) -> f64 {
        self.inner.floor
    }
    /// Homotopy parameters of the continuation path the solve took [-].
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Each ``lambda`` in (0, 1], ending at 1, when the direct Newton solve
    ///     failed and continuation took over; empty if it did not.
    #[getter]
    fn continuation_steps<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.inner.continuation_steps)
    }
    /// Scaled shooting unknowns ``[nu(0), L omega(0), delta_i / L]`` [-].
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(6 + n_actuators,)`` [-]: the base strains and the actuators'
    ///     scaled elongations Newton converged to.
    #[getter]
    fn unknowns<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.inner.unknowns)
    }
    /// The shape and everything solved as a dict of plain numbers and lists.
    ///
    /// Every key names its unit (``positions_m``, ``tensions_n``, ...); the
    /// document is JSON-ready. See ``tcarod.io.results.solution_dict`` and the
    /// table in the documentation page "Exporting shapes".
    ///
    /// Parameters
    /// ----------
    /// stability : bool or None, optional
    ///     ``None`` (default) includes the stability verdict if it is already
    ///     known, ``True`` computes it if needed (one tangent IVP), ``False``
    ///     leaves it out (``null``).
    ///
    /// Returns
    /// -------
    /// dict
    ///     The document, format ``"tcarod.solution/1"``.
    ///
    /// Examples
    /// --------
    /// >>> from tcarod.batch import fig6_square_robot
    /// >>> doc = fig6_square_robot().solve([60.0, 25.0], steps=20).to_dict()
    /// >>> doc["format"], doc["nodes"], len(doc["positions_m"])
    /// ('tcarod.solution/1', 21, 21)
    #[pyo3(signature = (*, stability=None))]
    fn to_dict<'py>(
        slf: &Bound<'py, Self>,
        stability: Option<bool>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let kw = PyDict::new(slf.py());
        kw.set_item("stability", stability)?;
        export(slf, "to_dict", PyTuple::empty(slf.py()), &kw)
    }
    /// ``to_dict()`` as JSON text, also written to ``path`` if given.
    ///
    /// Parameters
    /// ----------
    /// path : str or os.PathLike, optional
    ///     File to write (UTF-8); default: none, the text is only returned.
    /// stability : bool or None, optional
    ///     As in ``to_dict``.
    /// indent : int or None, optional
    ///     JSON indentation (default 2; ``None``: one line).
    ///
    /// Returns
    /// -------
    /// str
    ///     The JSON document (NaN never occurs).
    ///
    /// Examples
    /// --------
    /// >>> import json
    /// >>> from tcarod.batch import fig6_square_robot
    /// >>> sol = fig6_square_robot().solve([60.0, 25.0], steps=20)
    /// >>> doc = json.loads(sol.to_json("shape.json"))
    /// >>> " ".join(doc["input_units"])
    /// 'C C'
    #[pyo3(signature = (path=None, *, stability=None, indent=Some(2)),
        text_signature = "(self, path=None, *, stability=None, indent=2)")]
    fn to_json<'py>(
        slf: &Bound<'py, Self>,
        path: Option<Bound<'py, PyAny>>,
        stability: Option<bool>,
        indent: Option<i64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        let kw = PyDict::new(py);
        kw.set_item("stability", stability)?;
        kw.set_item("indent", indent)?;
        export(slf, "to_json", PyTuple::new(py, [path])?, &kw)
    }
    /// One row per node as CSV text, columns named with their units.
    ///
    /// The columns: arc length, position, rotation, strains, internal wrench,
    /// actuator elongations (``tcarod.io.results.solution_csv``).
    ///
    /// Parameters
    /// ----------
    /// path : str or os.PathLike, optional
    ///     File to write; default: none, the text is only returned.
    ///
    /// Returns
    /// -------
    /// str
    ///     The CSV text, one header line and ``n`` rows.
    ///
    /// Examples
    /// --------
    /// >>> from tcarod.batch import fig6_square_robot
    /// >>> lines = fig6_square_robot().solve([60.0, 25.0], steps=20).to_csv().splitlines()
    /// >>> len(lines), lines[0].startswith("s_m,x_m,y_m,z_m,r11,")
    /// (22, True)
    #[pyo3(signature = (path=None))]
    fn to_csv<'py>(
        slf: &Bound<'py, Self>,
        path: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        export(slf, "to_csv", PyTuple::new(py, [path])?, &PyDict::new(py))
    }
    /// Write the centre line as a VTK polyline with the node data, for ParaView.
    ///
    /// Needs meshio (the ``export`` extra); see ``tcarod.io.results.write_vtk``.
    ///
    /// Parameters
    /// ----------
    /// path : str or os.PathLike
    ///     ``.vtu`` (XML) or ``.vtk`` (legacy) file.
    ///
    /// Returns
    /// -------
    /// pathlib.Path
    ///     The path written.
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     A suffix other than ``.vtu`` or ``.vtk``.
    /// ImportError
    ///     meshio is not installed (names the ``export`` extra).
    fn to_vtk<'py>(slf: &Bound<'py, Self>, path: Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        export(slf, "to_vtk", PyTuple::new(py, [path])?, &PyDict::new(py))
    }
    /// The stability verdict `(stable, margin)` if it is already known, else
    /// None (never computes it).
    #[getter]
    fn _verdict(&self) -> Option<(bool, f64)> {
        self.verdict.get().copied()
    }
    /// Plot the shape with the actuators (the ``plot`` extra, matplotlib).
    ///
    /// The keywords are those of ``tcarod.plotting.plot_solution``.
    ///
    /// Parameters
    /// ----------
    /// **kwargs
    ///     ``view`` (``"3d"``, ``"xz"``, ``"yz"``, ``"xy"`` or ``"interactive"``),
    ///     ``ax``, ``show_actuators``, ...
    ///
    /// Returns
    /// -------
    /// matplotlib.figure.Figure
    ///     The figure (a plotly figure for ``view="interactive"``).
    ///
    /// Examples
    /// --------
    /// >>> from tcarod.batch import fig6_square_robot
    /// >>> fig = fig6_square_robot().solve([60.0, 25.0], steps=20).plot(view="xz")
    /// >>> fig.axes[0].get_xlabel()
    /// 'x [mm]'
    #[pyo3(signature = (**kwargs))]
    fn plot<'py>(
        slf: &Bound<'py, Self>,
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        let plotter = PLOTTER.get(py).ok_or_else(|| {
            pyo3::exceptions::PyRuntimeError::new_err(
                "no plotter registered: import tcarod (the package), not tcarod._core alone",
            )
        })?;
        plotter.bind(py).call((slf,), kwargs)
    }
    /// Whether this equilibrium is stable.
    ///
    /// Returns
    /// -------
    /// bool
    ///     ``True`` at a strict local minimum of the potential energy (Till and
    ///     Rucker's criterion, extended to the actuators and dead loads; see
    ///     ``tcarod.models.stability``). Computed by the solve (policy ``"report"``,
    ///     the default) or on first access from one tangent integration, then
    ///     cached. A ``BlockedResult.solution`` carries the verdict with the tip
    ///     held on its plane (mixed boundary condition).
    #[getter]
    fn stable(&self, py: Python<'_>) -> PyResult<bool> {
        Ok(self.verdict(py)?.0)
    }
    /// How ``stability="continue"`` reached this equilibrium, if it moved.
    ///
    /// Returns
    /// -------
    /// Continuation or None
    ///     The route from the unstable equilibrium Newton found first; ``None``
    ///     if the solve did not move.
    #[getter]
    fn continued(&self, py: Python<'_>) -> Option<Py<crate::python::stability::Continuation>> {
        self.continued.as_ref().map(|c| c.clone_ref(py))
    }
    /// Stability margin [-].
    ///
    /// Returns
    /// -------
    /// float
    ///     The smallest eigenvalue of the dimensionless tip stiffness [-],
    ///     ``> 0`` if and only if ``stable``; computed and cached with ``stable``.
    #[getter]
    fn stability_margin(&self, py: Python<'_>) -> PyResult<f64> {
        Ok(self.verdict(py)?.1)
    }
    fn __repr__(&self) -> String {
        let p = self.inner.tip_position();
        let stable = match self.verdict.get() {
            Some((s, _)) => format!(" stable={}", pb(*s)),
            None => String::new(),
        };
        format!(
            "<Solution success=True nit={} nfev={} residual={:.2e} inputs={} tip_position={}{}>",
            self.inner.iterations,
            self.inner.evaluations,
            self.inner.residual,
            pv(&self.inner.inputs),
            pv(p.as_slice()),
            stable
        )
    }
    /// RK4 steps over the body used by the solve [-].
    ///
    /// Returns
    /// -------
    /// int
    ///     The ``steps`` argument, or the finer grid an ``equilibrium_tol``
    ///     solve needed.
    #[getter]
    fn steps(&self) -> usize {
        self.inner.steps
    }
    /// Pickle support: the robot and the converged shooting unknowns; the
    /// profile is rebuilt by one IVP from them (bit-identical: the IVP is
    /// deterministic), or for a solution of several shooting segments by
    /// one integration of each segment from its pickled first state; the
    /// stability verdict kept if it was computed.
    fn __reduce__<'py>(&self, py: Python<'py>) -> Reduce<'py, Bound<'py, PyTuple>> {
        let s = &self.inner;
        let model = (
            self.robot.clone_ref(py),
            s.inputs.clone(),
            s.unknowns.clone(),
            s.loads.tip_force.as_slice().to_vec(),
            s.loads.tip_moment.as_slice().to_vec(),
            s.steps,
        )
            .into_pyobject(py)?;
        let outcome = (
            s.iterations,
            s.evaluations,
            (status_code(s.status), s.floor, s.continuation_steps.clone()),
            self.blocked
                .iter()
                .map(|b| [b.x, b.y, b.z])
                .collect::<Vec<_>>(),
            s.tensions.clone(),
            segment_states(&self.robot.get().inner, s),
        )
            .into_pyobject(py)?;
        let args = PyTuple::new(py, model.iter().chain(outcome.iter()).collect::<Vec<_>>())?;
        match self.verdict.get() {
            None => reduce_with(py, "_restore_solution", args),
            // the verdict travels with the state: no tangent IVP after unpickling
            Some((stable, margin)) => reduce_with(
                py,
                "_restore_solution_verdict",
                (args, *stable, *margin).into_pyobject(py)?,
            ),
        }
    }
}

/// The rod states at the first nodes of the shooting segments after the
/// first (`p`, the quaternion `q` as `w, x, y, z`, `nu`, `omega`, the
/// elongations), for unpickling a solution of several segments: its
/// profile is integrated from them, segment by segment, as the solve's
/// last evaluation did. `None` for one segment, which the base unknowns
/// rebuild alone.
fn segment_states(
    robot: &crate::rod::Robot,
    s: &crate::shooting::Solution,
) -> Option<Vec<Vec<f64>>> {
    let starts = crate::solve::segments::segment_starts(robot, &s.loads, s.steps);
    (starts.len() > 1).then(|| {
        let flat = |j: usize| {
            let st = crate::solve::forward::node_state(s, j);
            let q = [st.q.w, st.q.i, st.q.j, st.q.k];
            let parts = [
                st.p.as_slice(),
                &q,
                st.v.as_slice(),
                st.u.as_slice(),
                &st.delta,
            ];
            parts.concat()
        };
        starts[1..].iter().map(|&j| flat(j)).collect()
    })
}

impl PartialEq for PySolution {
    /// Same robot, same inputs and loads, and bit-identical results.
    fn eq(&self, o: &Self) -> bool {
        let (a, b) = (&self.inner, &o.inner);
        self.robot.get().same_as(o.robot.get())
            && a.inputs == b.inputs
            && a.unknowns == b.unknowns
            && a.loads == b.loads
            && a.steps == b.steps
            && a.iterations == b.iterations
            && a.evaluations == b.evaluations
            && a.residual.to_bits() == b.residual.to_bits()
            && a.s == b.s
            && a.positions == b.positions
            && a.rotations == b.rotations
            && a.nu == b.nu
            && a.omega == b.omega
            && a.internal_force == b.internal_force
            && a.internal_moment == b.internal_moment
            && a.tensions == b.tensions
            && a.elongations == b.elongations
            && a.elongation_profile == b.elongation_profile
            && a.actuator_paths == b.actuator_paths
            && a.base_force == b.base_force
            && a.base_moment == b.base_moment
            && a.status == b.status
            && a.floor.to_bits() == b.floor.to_bits()
            && a.continuation_steps == b.continuation_steps
    }
}

/// The Python function behind `Solution.plot`, registered by the package at
/// import (`tcarod._display`): plotting lives in Python and the bindings never
/// import back up into it (the package imports `tcarod._core`, never the
/// other way round, so there is no import cycle).
static PLOTTER: pyo3::sync::PyOnceLock<Py<PyAny>> = pyo3::sync::PyOnceLock::new();

/// Register the function `Solution.plot` calls (not public API; the first
/// registration wins).
#[pyfunction]
#[pyo3(name = "_register_plotter")]
pub(crate) fn register_plotter(py: Python<'_>, plotter: Bound<'_, PyAny>) -> PyResult<()> {
    if !plotter.is_callable() {
        return Err(pyo3::exceptions::PyTypeError::new_err(
            "plotter must be callable",
        ));
    }
    let _ = PLOTTER.set(py, plotter.unbind());
    Ok(())
}

/// The Python function behind `Solution.to_dict`, `to_json`, `to_csv` and
/// `to_vtk`, registered by the package at import (`tcarod.io.results`), for
/// the reason given at [`PLOTTER`]. It is called as
/// `exporter(name, solution, *args, **kwargs)`.
static EXPORTER: pyo3::sync::PyOnceLock<Py<PyAny>> = pyo3::sync::PyOnceLock::new();

/// Register the function the export methods call (not public API; the first
/// registration wins).
#[pyfunction]
#[pyo3(name = "_register_exporter")]
pub(crate) fn register_exporter(py: Python<'_>, exporter: Bound<'_, PyAny>) -> PyResult<()> {
    if !exporter.is_callable() {
        return Err(pyo3::exceptions::PyTypeError::new_err(
            "exporter must be callable",
        ));
    }
    let _ = EXPORTER.set(py, exporter.unbind());
    Ok(())
}

/// `exporter(name, slf, *args, **kwargs)`.
fn export<'py>(
    slf: &Bound<'py, PySolution>,
    name: &str,
    args: Bound<'py, PyTuple>,
    kwargs: &Bound<'py, PyDict>,
) -> PyResult<Bound<'py, PyAny>> {
    let py = slf.py();
    let exporter = EXPORTER.get(py).ok_or_else(|| {
        pyo3::exceptions::PyRuntimeError::new_err(
            "no exporter registered: import tcarod (the package), not tcarod._core alone",
        )
    })?;
    let mut all: Vec<Bound<'py, PyAny>> =
        vec![name.into_pyobject(py)?.into_any(), slf.clone().into_any()];
    all.extend(args.iter());
    exporter.bind(py).call(PyTuple::new(py, all)?, Some(kwargs))
}

/// Unpickle a `Solution` whose stability verdict was computed: the solution
/// from `state` (the arguments of `_restore_solution`) with the verdict
/// `(stable, margin)` cached (not public API).
#[pyfunction]
#[pyo3(name = "_restore_solution_verdict")]
pub(crate) fn restore_solution_verdict<'py>(
    py: Python<'py>,
    state: Bound<'py, PyTuple>,
    stable: bool,
    margin: f64,
) -> PyResult<Bound<'py, PySolution>> {
    if !margin.is_finite() {
        return Err(Error::input("margin", "the stability margin [-] must be finite").into());
    }
    let sol = py
        .import("tcarod._core")?
        .getattr("_restore_solution")?
        .call1(state)?
        .cast_into::<PySolution>()?;
    let _ = sol.get().verdict.set((stable, margin));
    Ok(sol)
}
