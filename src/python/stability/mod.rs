//! Bindings of the stability verdict and of branch following (beyond the
//! paper; the criterion is in `src/stability/mod.rs` and `docs/stability.md`).

use nalgebra::Vector3;
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use super::rod::{PyRobot, PySolution};
use super::Real;
use crate::stability::{stability as stability_core, Stability};

mod branch;
mod policy;

pub(crate) use policy::{blocked_verdict, parse_policy, solve_policy, sweep_policy, Continuation};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyStability>()?;
    m.add_function(wrap_pyfunction!(stability, m)?)?;
    m.add_function(wrap_pyfunction!(restore_stability, m)?)?;
    branch::register(m)?;
    policy::register(m)
}

/// Stability verdict of one equilibrium (see ``tcarod.models.stability``).
///
/// Till and Rucker's conjugate-point test (IEEE T-RO 2017) extended to
/// embedded actuators, dead loads and a blocked tip: one tangent integration
/// along the body. Built by ``tcarod.models.stability.stability``; a solve's
/// own verdict is ``Solution.stable`` and ``Solution.stability_margin``.
///
/// Examples
/// --------
/// >>> from tcarod.batch import fig6_square_robot
/// >>> from tcarod.models.stability import stability
/// >>> robot = fig6_square_robot()
/// >>> verdict = stability(robot, robot.solve([60.0, 25.0], steps=20))
/// >>> verdict.stable, verdict.margin > 0, verdict.conjugate_point
/// (True, True, None)
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
    /// Whether the equilibrium is stable.
    ///
    /// Returns
    /// -------
    /// bool
    ///     ``True`` at a strict local minimum of the potential energy, up to
    ///     neutral symmetry modes.
    #[getter]
    fn stable(&self) -> bool {
        self.inner.stable
    }
    /// Stability margin [-].
    ///
    /// Returns
    /// -------
    /// float
    ///     Smallest eigenvalue of the dimensionless tip stiffness [-]: ``> 0``
    ///     if and only if stable.
    #[getter]
    fn margin(&self) -> f64 {
        self.inner.margin
    }
    /// Arc length [m] of the first conjugate point, if there is one.
    ///
    /// Returns
    /// -------
    /// float or None
    ///     Where ``determinant`` first changes sign [m]; ``None`` if it does not.
    #[getter]
    fn conjugate_point(&self) -> Option<f64> {
        self.inner.conjugate_point
    }
    /// Arc length of the nodes [m].
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(n,)`` [m].
    #[getter]
    fn s<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arr1(py, &self.inner.s)
    }
    /// Till and Rucker's determinant ``det(Y(s) Y(0)^-1)`` at the nodes [-].
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(n,)`` [-]; a sign change marks a conjugate point.
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
    /// Smallest eigenvalue of the truncated rod's tip stiffness at the nodes [-].
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(n,)`` [-]; the base node, where it is infinite, carries the
    ///     largest float.
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
    /// Softest tip mode ``(dp / L, dtheta)`` [-, rad], world frame.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(6,)``: tip translation over body length, then rotation.
    #[getter]
    fn mode<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arr1(py, &self.inner.mode)
    }
    /// Integrations spent on the verdict [-].
    ///
    /// Returns
    /// -------
    /// int
    ///     One tangent IVP.
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

/// Stability verdict of ``solution``, an equilibrium of ``robot``.
///
/// The public form is ``tcarod.models.stability.stability``.
///
/// Parameters
/// ----------
/// robot : Robot
///     The robot solved.
/// solution : Solution
///     One of ``robot``'s equilibria.
/// blocked : sequence of (3,) sequences of float, optional
///     World directions [-] along which the tip translation is held (a
///     blocked-tip solution's block normal); default none.
///
/// Returns
/// -------
/// Stability
///     The verdict, its margin [-] and the profiles along the body.
///
/// Raises
/// ------
/// ValueError
///     ``solution`` is not an equilibrium of ``robot``.
///
/// Examples
/// --------
/// >>> from tcarod import _core
/// >>> from tcarod.batch import fig6_square_robot
/// >>> robot = fig6_square_robot()
/// >>> _core.stability(robot, robot.solve([60.0, 25.0], steps=20, stability="off")).stable
/// True
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
