//! Bindings of the robot and its forward solve.

use std::sync::Arc;

use pyo3::prelude::*;

use super::actuator::PyActuator;
use super::body::{body_repr, PyBody};
use super::solution::PySolution;
use crate::error::Error;
use crate::python::args::{budget_options, one_per_actuator, solve_options};
use crate::python::to_py::{hash_by_text, positional_args, NewArgs};
use crate::python::{Real, MAX_SEQUENCE};
use crate::rod::{Actuator, Robot};

/// A body with its embedded actuators: `Robot(body, actuators=(), *, spacer_disks=False)`.
///
/// `body` is a `Body`; `actuators` a sequence of `Actuator` (inputs are given
/// in this order to `solve`: temperature [C] for TCAs, tension [N] for
/// tendons, pull [m] for linear tendons). Building checks the layout: anchors
/// inside the body, routings inside the section, each TCA's whole coil
/// (routing offset plus half the coil's outer diameter) inside the section,
/// TCAs no longer than their span (ValueError naming `actuators[i]`).
/// `spacer_disks=True`: a robot whose actuators run through spacer disks
/// outside the body's section (the routing- and coil-inside-the-section rule
/// is waived). Value object: immutable, `==`
/// (two identically built robots are equal), picklable, so it travels to
/// process pools and Dask workers.
///
/// Examples
/// --------
/// >>> body = tcarod.Body(0.05, tcarod.Section.circle(0.01), 5e4)   # [m], [m], [Pa]
/// >>> tendon = tcarod.Actuator.tendon(tcarod.Routing.straight(0.003, 0.0))
/// >>> robot = tcarod.Robot(body, [tendon])
/// >>> robot.reference_inputs[0]                       # passive input: zero tension [N]
/// 0.0
/// >>> sol = robot.solve([0.01], steps=20)             # pull with 10 mN
/// >>> round(float(sol.tip_position[0]) * 1e3, 2)     # tip x [mm]: bent towards the tendon
/// 1.52
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
    #[pyo3(signature = (body, actuators=None, *, spacer_disks=false),
        text_signature = "(body, actuators=(), *, spacer_disks=False)")]
    fn new(
        body: PyBody,
        actuators: Option<Bound<'_, PyAny>>,
        spacer_disks: bool,
    ) -> PyResult<Self> {
        let actuators = match actuators {
            None => Vec::new(),
            Some(seq) => actuator_list(&seq)?,
        };
        let acts: Vec<Actuator> = actuators.iter().map(|a| a.inner.clone()).collect();
        let robot = if spacer_disks {
            Robot::with_spacer_disks(body.inner.clone(), acts)?
        } else {
            Robot::new(body.inner.clone(), acts)?
        };
        Ok(PyRobot {
            inner: Arc::new(robot),
            body,
            actuators,
        })
    }
    /// The soft body.
    ///
    /// Returns
    /// -------
    /// Body
    ///     Its geometry [m], material [Pa, kg/m^3] and loads.
    #[getter]
    fn body(&self) -> PyBody {
        self.body.clone()
    }
    /// The actuators, in input order.
    ///
    /// Returns
    /// -------
    /// list of Actuator
    ///     One per input of `solve` (temperature [C], tension [N], pull [m]).
    #[getter]
    fn actuators(&self) -> Vec<PyActuator> {
        self.actuators.clone()
    }
    /// Whether the actuators run through spacer disks outside the section.
    ///
    /// Returns
    /// -------
    /// bool
    ///     `True`: the routing- and coil-inside-the-section rule is waived.
    #[getter]
    fn spacer_disks(&self) -> bool {
        self.inner.spacer_disks
    }
    /// Passive inputs of the actuators.
    ///
    /// Returns
    /// -------
    /// list of float
    ///     Ambient temperature [C] for TCAs, zero tension [N] / pull [m] for
    ///     tendons, in input order.
    #[getter]
    fn reference_inputs(&self) -> Vec<f64> {
        self.inner.reference_inputs()
    }

    /// Solve the forward kinetostatics: the robot's shape at the given inputs.
    ///
    /// Multiple shooting on the Cosserat rod (the paper's eqs 22-33), with
    /// continuation in the inputs and loads where Newton fails (docs: The solver).
    ///
    /// Parameters
    /// ----------
    /// inputs : float or sequence of float
    ///     One input per actuator: temperature [C] for a TCA, tension [N] for a
    ///     tendon, pull [m] for a linear tendon.
    /// steps : int, optional
    ///     RK4 steps over the body, 1 to 100,000 (default 100).
    /// tol : float, optional
    ///     Newton tolerance on the dimensionless residual (default 1e-10).
    /// max_iter : int, optional
    ///     Newton iterations per Newton run (a continuation corrector takes at
    ///     most 8), 1 to 100,000 (default 50).
    /// warm_start : Solution, optional
    ///     A nearby solution of this robot, or of a robot with the same actuators
    ///     under other loads (load continuation).
    /// stability : {"report", "require", "continue", "off"}, optional
    ///     ``"report"`` (default): the verdict comes with the solve (one tangent
    ///     IVP) in ``Solution.stable``; an unstable equilibrium also warns
    ///     ``UnstableEquilibriumWarning``. ``"require"``: raise
    ///     ``UnstableEquilibriumError`` (attributes ``margin`` [-] and
    ///     ``solution``). ``"continue"``: move from an unstable equilibrium to a
    ///     stable one at the same inputs; ``Solution.continued`` records how.
    ///     ``"off"``: no verdict (hot loops).
    /// require_stable : bool, optional
    ///     ``True`` is ``stability="require"``.
    /// max_evaluations : int, optional
    ///     IVP budget of the solve, continuation included, 1 to 1e8 (default
    ///     20,000).
    /// time_limit : float, optional
    ///     Wall-time limit [s] (default none).
    /// equilibrium_tol : float, optional
    ///     Opt-in accuracy control, 1e-12 to 1: the largest relative error of the
    ///     global equilibrium check (base wrench against the loads) the solution
    ///     may have; above it the solve is repeated on finer RK4 grids, and
    ///     ``Solution.steps`` reports the grid used.
    ///
    /// Returns
    /// -------
    /// Solution
    ///     The shape (centre line, frames, strains, internal wrench), the
    ///     actuators' tensions and elongations, and the solver's counts.
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     An argument outside its range (named, with its unit).
    /// TypeError
    ///     An argument of the wrong type.
    /// ConvergenceError
    ///     Newton and continuation fail, the budget (``reason == "budget"``) or
    ///     the time limit runs out, or ``equilibrium_tol`` cannot be met.
    /// UnstableEquilibriumError
    ///     With ``stability="require"``, an unstable equilibrium.
    ///
    /// Examples
    /// --------
    /// >>> from tcarod.batch import fig6_square_robot
    /// >>> robot = fig6_square_robot()      # the paper's Fig. 6 square, two TCA legs
    /// >>> sol = robot.solve([100.0, 100.0])
    /// >>> sol.stable, round(float(sol.tip_position[0]) * 1e3, 2)   # tip x [mm]
    /// (True, -6.13)
    #[pyo3(signature = (inputs, *, steps=None, tol=Real(1e-10), max_iter=None, warm_start=None, stability="report", require_stable=false, max_evaluations=None, time_limit=None, equilibrium_tol=None),
        text_signature = "($self, inputs, *, steps=100, tol=1e-10, max_iter=50, warm_start=None, stability='report', require_stable=False, max_evaluations=20000, time_limit=None, equilibrium_tol=None)")]
    #[allow(clippy::too_many_arguments)]
    fn solve(
        slf: &Bound<'_, Self>,
        py: Python<'_>,
        inputs: Bound<'_, PyAny>,
        steps: Option<Bound<'_, PyAny>>,
        tol: Real,
        max_iter: Option<Bound<'_, PyAny>>,
        warm_start: Option<PyRef<'_, PySolution>>,
        stability: &str,
        require_stable: bool,
        max_evaluations: Option<Bound<'_, PyAny>>,
        time_limit: Option<Real>,
        equilibrium_tol: Option<Real>,
    ) -> PyResult<PySolution> {
        let this = slf.get();
        let mut opts = solve_options(steps.as_ref(), tol, max_iter.as_ref())?;
        budget_options(&mut opts, max_evaluations.as_ref(), time_limit)?;
        opts.equilibrium_tol = equilibrium_tol.map(|t| t.0);
        opts.validate()?;
        let mut policy = crate::python::stability::parse_policy(stability)?;
        if require_stable {
            policy = crate::stability::Policy::Require;
        }
        let q = one_per_actuator("inputs", &inputs, this.inner.actuators.len())?;
        this.inner.check_inputs(&q)?;
        let warm = warm_start.map(|w| w.inner.clone());
        crate::python::stability::solve_policy(py, slf, &q, &opts, warm, policy)
    }

    /// Solve along rows of `inputs`, each warm-started from the previous one.
    ///
    /// `inputs` has shape `(k, n_actuators)` (at most 10,000,000 rows; units
    /// as for `solve`). Returns a
    /// list of `Solution`. Options as for `solve`; `stability`: `"report"`
    /// (default: every solution carries its verdict, one warning names the
    /// unstable rows), `"require"` (raise at the first unstable row),
    /// `"continue"` (the quasi-static path of the physical robot: where an
    /// equilibrium is unstable, move to a stable one and go on from it) or
    /// `"off"`.
    #[pyo3(signature = (inputs, *, steps=None, tol=Real(1e-10), max_iter=None, stability="report"),
        text_signature = "($self, inputs, *, steps=100, tol=1e-10, max_iter=50, stability='report')")]
    fn sweep(
        slf: &Bound<'_, Self>,
        py: Python<'_>,
        inputs: Bound<'_, PyAny>,
        steps: Option<Bound<'_, PyAny>>,
        tol: Real,
        max_iter: Option<Bound<'_, PyAny>>,
        stability: &str,
    ) -> PyResult<Vec<PySolution>> {
        let opts = solve_options(steps.as_ref(), tol, max_iter.as_ref())?;
        let policy = crate::python::stability::parse_policy(stability)?;
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
            let n = slf.get().inner.actuators.len();
            let row = one_per_actuator(&format!("inputs[{k}]"), &row?, n)?;
            slf.get().inner.check_inputs(&row)?;
            rows.push(row);
        }
        crate::python::stability::sweep_policy(py, slf, &rows, &opts, policy)
    }

    fn __repr__(&self) -> String {
        let acts: Vec<String> = self.actuators.iter().map(|a| a.__repr__()).collect();
        format!(
            "Robot(body={}, actuators=[{}]{})",
            body_repr(&self.body.inner),
            acts.join(", "),
            if self.inner.spacer_disks {
                ", spacer_disks=True"
            } else {
                ""
            }
        )
    }
    /// Constructor arguments, for pickle and copy.
    fn __getnewargs_ex__<'py>(&self, py: Python<'py>) -> NewArgs<'py> {
        let (args, kwargs) = positional_args((self.body.clone(), self.actuators.clone()), py)?;
        if self.inner.spacer_disks {
            kwargs.set_item("spacer_disks", true)?;
        }
        Ok((args, kwargs))
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
                && self.inner.spacer_disks == other.inner.spacer_disks
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
