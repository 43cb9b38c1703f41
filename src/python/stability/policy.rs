//! The stability policy of `Robot.solve` / `Robot.sweep` and the verdict of
//! blocked-tip solutions (the core's is `src/stability/policy.rs`): a
//! solution handed back carries its verdict, and an unstable one is
//! announced (warning, error) or replaced by a stable one at the same inputs.

use std::ffi::CString;

use nalgebra::Vector3;
use pyo3::prelude::*;

use crate::error::Result;
use crate::python::errors::{detach_interruptible, UnstableEquilibriumError};
use crate::python::pv;
use crate::python::rod::{checked_solution, PyRobot, PySolution};
use crate::shooting::{Loads, Solution, SolveOptions};
use crate::stability::{solve_checked, sweep_checked, Checked, Policy, Stability};

pyo3::create_exception!(
    tcarod._core,
    UnstableEquilibriumWarning,
    pyo3::exceptions::PyUserWarning,
    "A solve handed back an unstable equilibrium (`stability='report'`, the \
     default): a shape the physical robot cannot hold. Its `Solution.stable` is \
     False; ask for `stability='continue'` to move to a stable one."
);

pub(super) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add(
        "UnstableEquilibriumWarning",
        m.py().get_type::<UnstableEquilibriumWarning>(),
    )?;
    m.add_class::<Continuation>()?;
    Ok(())
}

/// How ``stability="continue"`` reached the stable equilibrium it handed back.
///
/// ``Solution.continued``: the unstable equilibrium Newton found first, its
/// margin, the route taken and the work.
///
/// Examples
/// --------
/// >>> from tcarod import Body, Robot, Section
/// >>> heavy = Robot(Body(0.05, Section.rectangle(0.01, 0.009), 37.8e3, density=3120.0,
/// ...                    gravity=(0.0, 0.0, -9.81)), [])     # past self-weight buckling
/// >>> sol = heavy.solve([], steps=20, stability="continue")
/// >>> sol.stable, sol.continued.margin < 0, sol.continued.unstable.stable
/// (True, True, False)
#[pyclass(name = "Continuation", module = "tcarod._core", frozen)]
pub struct Continuation {
    /// The route taken, in words.
    ///
    /// Returns
    /// -------
    /// str
    ///     Loading from rest with an imperfection along the softest mode, or a
    ///     perturbed Newton start.
    #[pyo3(get)]
    route: String,
    /// The unstable equilibrium found first.
    ///
    /// Returns
    /// -------
    /// Solution
    ///     Its ``stable`` is ``False``.
    #[pyo3(get)]
    unstable: Py<PySolution>,
    /// Stability margin of the unstable equilibrium [-].
    ///
    /// Returns
    /// -------
    /// float
    ///     ``< 0``.
    #[pyo3(get)]
    margin: f64,
    /// Stable equilibria found [-].
    ///
    /// Returns
    /// -------
    /// int
    ///     The one nearest the unstable tip is kept.
    #[pyo3(get)]
    candidates: usize,
    /// IVPs integrated to get there, verdicts included [-].
    ///
    /// Returns
    /// -------
    /// int
    ///     The work of the continuation.
    #[pyo3(get)]
    evaluations: usize,
}

#[pymethods]
impl Continuation {
    fn __repr__(&self) -> String {
        format!(
            "<Continuation route={:?} margin={:.3e} candidates={} nfev={}>",
            self.route, self.margin, self.candidates, self.evaluations
        )
    }
}

/// The policy named by `stability` (`ValueError` naming the argument).
pub(crate) fn parse_policy(name: &str) -> Result<Policy> {
    name.parse()
}

fn warn(py: Python<'_>, msg: String) -> PyResult<()> {
    PyErr::warn(
        py,
        &py.get_type::<UnstableEquilibriumWarning>(),
        &CString::new(msg)?,
        1,
    )
}

fn unstable_message(sol: &Solution, margin: f64) -> String {
    format!(
        "the equilibrium found (inputs {}, tip at {} m) is unstable (stability margin {margin:.3e} < 0): \
         a shape the robot cannot hold; stability='continue' moves to a stable one",
        pv(&sol.inputs),
        pv(sol.tip_position().as_slice())
    )
}

/// `UnstableEquilibriumError` carrying `margin` and the `solution`.
fn unstable_error(py: Python<'_>, sol: PySolution, margin: f64) -> PyResult<PyErr> {
    let err = UnstableEquilibriumError::new_err(unstable_message(&sol.inner, margin));
    let value = err.value(py);
    value.setattr("margin", margin)?;
    value.setattr("solution", Py::new(py, sol)?)?;
    Ok(err)
}

/// A `Solution` with its verdict cached and, after a continuation, its route.
fn wrap(py: Python<'_>, robot: &Bound<'_, PyRobot>, c: Checked) -> PyResult<PySolution> {
    let mut s = PySolution::new(c.solution, robot.clone().unbind());
    if let Some(st) = c.stability {
        let st = super::finite_margin(st);
        let _ = s.verdict.set((st.stable, st.margin));
    }
    if let Some(k) = c.continued {
        let from_margin = super::finite_margin(k.from_stability).margin;
        let from = PySolution::new(k.from, robot.clone().unbind());
        let _ = from.verdict.set((false, from_margin));
        s.continued = Some(Py::new(
            py,
            Continuation {
                route: k.route.to_string(),
                unstable: Py::new(py, from)?,
                margin: from_margin,
                candidates: k.candidates,
                evaluations: k.evaluations,
            },
        )?);
    }
    Ok(s)
}

/// The core policy `Require` is run as `Report` so that the error can carry
/// the unstable solution.
fn core_policy(p: Policy) -> Policy {
    if p == Policy::Require {
        Policy::Report
    } else {
        p
    }
}

fn checked(mut c: Checked) -> Result<Checked> {
    c.solution = checked_solution(c.solution)?;
    Ok(c)
}

/// `Robot.solve` under `policy` (see `tcarod.models.stability`).
pub(crate) fn solve_policy(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    inputs: &[f64],
    opts: &SolveOptions,
    warm: Option<Solution>,
    policy: Policy,
) -> PyResult<PySolution> {
    let r = robot.get().inner.clone();
    let c = detach_interruptible(py, || {
        solve_checked(
            &r,
            inputs,
            &Loads::of(&r),
            opts,
            warm.as_ref(),
            core_policy(policy),
        )
        .and_then(checked)
    })?;
    let s = wrap(py, robot, c)?;
    match (policy, s.verdict.get().copied()) {
        (Policy::Require, Some((false, m))) => Err(unstable_error(py, s, m)?),
        (Policy::Report, Some((false, m))) => {
            warn(py, unstable_message(&s.inner, m))?;
            Ok(s)
        }
        _ => Ok(s),
    }
}

/// `Robot.sweep` under `policy`: one warning naming the unstable rows
/// (`report`), the error at the first unstable row (`require`), the
/// physical robot's path (`continue`).
pub(crate) fn sweep_policy(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    rows: &[Vec<f64>],
    opts: &SolveOptions,
    policy: Policy,
) -> PyResult<Vec<PySolution>> {
    let r = robot.get().inner.clone();
    let cs = detach_interruptible(py, || {
        sweep_checked(&r, rows, opts, core_policy(policy))?
            .into_iter()
            .map(checked)
            .collect::<Result<Vec<_>>>()
    })?;
    let mut out = Vec::with_capacity(cs.len());
    let mut unstable = vec![];
    for (k, c) in cs.into_iter().enumerate() {
        let s = wrap(py, robot, c)?;
        if let Some((false, m)) = s.verdict.get().copied() {
            if policy == Policy::Require {
                return Err(unstable_error(py, s, m)?);
            }
            unstable.push(k);
        }
        out.push(s);
    }
    if policy == Policy::Report && !unstable.is_empty() {
        warn(
            py,
            format!(
                "{} of {} equilibria of the sweep are unstable (rows {:?}): shapes the robot \
                 cannot hold; stability='continue' follows the stable ones",
                unstable.len(),
                out.len(),
                unstable
            ),
        )?;
    }
    Ok(out)
}

/// A blocked-tip `Solution` with the core's verdict `st` of the tip held
/// along `normal` (`report` policy: an unstable one warns).
pub(crate) fn blocked_verdict(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    sol: Solution,
    normal: Vector3<f64>,
    st: Stability,
) -> PyResult<PySolution> {
    let st = super::finite_margin(st);
    let mut s = PySolution::new(sol, robot.clone().unbind());
    s.blocked = vec![normal];
    let _ = s.verdict.set((st.stable, st.margin));
    if !st.stable {
        warn(
            py,
            format!(
                "the blocked-tip equilibrium found is unstable (stability margin {:.3e} < 0, \
                 tip held along {}): a shape the robot cannot hold",
                st.margin,
                pv(normal.as_slice())
            ),
        )?;
    }
    Ok(s)
}
