//! Bindings of the inverse kinetostatics: J and C (eqs 41-42), the
//! tip-position inverse and the blocked tip (eq 43). Results in `results.rs`.

use nalgebra::{Matrix3, Vector3};
use numpy::PyArray2;
use pyo3::prelude::*;

use super::results::{PyBlockedResult, PyInverseResult};
use super::rod::{solve_options, PyRobot, PySolution};
use super::to_py::dmat;
use super::{count_or, reals, vec3_arg, Real};
use crate::error::Error;
use crate::inverse::{self, Block, BlockedResult, Groups, InverseOptions, Scheme};
use crate::limits::{MAX_INCREMENTS, MAX_ITER};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(sensitivities, m)?)?;
    m.add_function(wrap_pyfunction!(tip_position, m)?)?;
    m.add_function(wrap_pyfunction!(blocked_force, m)?)?;
    m.add_function(wrap_pyfunction!(blocked_temperature, m)?)?;
    m.add_function(wrap_pyfunction!(blocked_temperature_direct, m)?)?;
    m.add_function(wrap_pyfunction!(grasp_temperature, m)?)?;
    Ok(())
}

/// `groups` and `fixed_inputs` from Python: `groups` a sequence of
/// variable indices (each in `0..n_actuators`) or `None` for an actuator
/// with a fixed input, one per actuator or one per actuator not in
/// `fixed_inputs`; `fixed_inputs` a dict `{actuator index: input}` (input in
/// the actuator's unit, checked as `Robot.solve` checks inputs). Both
/// absent: one variable per actuator.
fn groups_for(
    robot: &PyRobot,
    groups: Option<&Bound<'_, PyAny>>,
    fixed_inputs: Option<&Bound<'_, PyAny>>,
) -> PyResult<Groups> {
    let na = robot.inner.actuators.len();
    let map = match groups.filter(|o| !o.is_none()) {
        Some(o) => Some(group_entries(o, na.max(1) - 1)?),
        None => None,
    };
    let fixed = match fixed_inputs.filter(|o| !o.is_none()) {
        Some(o) => fixed_entries(o)?,
        None => Vec::new(),
    };
    // without fixed inputs `groups` is a sequence of integers: None there is
    // a wrong type, not a missing actuator
    if fixed.is_empty() && map.as_ref().is_some_and(|m| m.contains(&None)) {
        return Err(pyo3::exceptions::PyTypeError::new_err(
            "groups: expected integers; None marks an actuator in fixed_inputs, and none was given",
        ));
    }
    Ok(Groups::with_fixed(&robot.inner, map.as_deref(), &fixed)?)
}

/// `groups` entries: integers in `0..=hi` or `None` (`TypeError` for
/// text, bool, floats; `ValueError` naming `groups[k]` out of range).
fn group_entries(obj: &Bound<'_, PyAny>, hi: usize) -> PyResult<Vec<Option<usize>>> {
    if obj.is_instance_of::<pyo3::types::PyString>() || obj.is_instance_of::<pyo3::types::PyBytes>()
    {
        return Err(pyo3::exceptions::PyTypeError::new_err(format!(
            "groups: expected a sequence of integers (or None for an actuator in fixed_inputs), not {}",
            obj.get_type().name()?
        )));
    }
    let iter = obj.try_iter().map_err(|_| {
        pyo3::exceptions::PyTypeError::new_err(
            "groups: expected a sequence of integers (or None for an actuator in fixed_inputs)",
        )
    })?;
    let mut out = Vec::new();
    for (k, item) in iter.enumerate() {
        if k >= super::MAX_SEQUENCE {
            return Err(Error::input("groups", "more than the cap of values per call").into());
        }
        let item = item?;
        out.push(if item.is_none() {
            None
        } else {
            Some(super::args::count(&format!("groups[{k}]"), &item, 0, hi)?)
        });
    }
    Ok(out)
}

/// `fixed_inputs` entries `(actuator index, input)`: a dict (`TypeError`
/// otherwise), integer keys, real values (`TypeError` naming the entry).
fn fixed_entries(obj: &Bound<'_, PyAny>) -> PyResult<Vec<(usize, f64)>> {
    let dict = obj.cast::<pyo3::types::PyDict>().map_err(|_| {
        pyo3::exceptions::PyTypeError::new_err(format!(
            "fixed_inputs: expected a dict {{actuator index: input}}, not {}",
            obj.get_type()
                .name()
                .map(|n| n.to_string())
                .unwrap_or_default()
        ))
    })?;
    let mut out = Vec::with_capacity(dict.len());
    for (key, value) in dict.iter() {
        let i = super::args::count(
            "fixed_inputs key (actuator index)",
            &key,
            0,
            super::MAX_SEQUENCE,
        )?;
        let v = value.extract::<Real>().map_err(|e| {
            if e.is_instance_of::<pyo3::exceptions::PyTypeError>(obj.py()) {
                pyo3::exceptions::PyTypeError::new_err(format!(
                    "fixed_inputs[{i}]: {}",
                    e.value(obj.py())
                ))
            } else {
                e
            }
        })?;
        out.push((i, v.0));
    }
    out.sort_by_key(|e| e.0);
    Ok(out)
}

/// A required 3-vector argument (`None` is a `TypeError`, not the origin).
fn vec3(name: &str, a: &Bound<'_, PyAny>) -> PyResult<Vector3<f64>> {
    if a.is_none() {
        let msg = format!("{name}: expected a sequence of 3 real numbers, not NoneType");
        return Err(pyo3::exceptions::PyTypeError::new_err(msg));
    }
    Ok(Vector3::from(vec3_arg(name, Some(a), [0.0; 3])?))
}

/// A required direction argument: a [`vec3`] scaled by its largest
/// component's magnitude, so that its norm neither overflows (components
/// near 1e308) nor underflows (subnormal components) where the core
/// normalises it. Zero stays zero and is refused by the core.
fn direction(name: &str, a: &Bound<'_, PyAny>) -> PyResult<Vector3<f64>> {
    let v = vec3(name, a)?;
    let m = v.amax();
    Ok(if m > 0.0 { v / m } else { v })
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

/// The actuation Jacobian and the compliance `(J, C)` at `solution` (eqs 41-42).
///
/// `J` is `6 x n_vars` (tip `[dp (m); dtheta (rad)]`
/// per unit actuation variable, per C for TCAs), `C` is `6 x 6` (per unit tip wrench
/// `[F (N); M (N m)]`), world frame. `groups[i]` is the variable driving actuator `i`.
///
/// Parameters
/// ----------
/// groups : sequence of int or None, optional
///     ``groups[i]`` is the actuation variable driving actuator ``i`` (e.g.
///     ``[0, 0]``: the two legs of a U-shaped TCA share one temperature),
///     ``None`` for an actuator in ``fixed_inputs``: one entry per actuator,
///     or one per actuator not in ``fixed_inputs`` (in order). Default: one
///     variable per actuator not in ``fixed_inputs``.
/// fixed_inputs : dict of int to float, optional
///     ``{actuator index: input}``: actuators held at a fixed input (C for a
///     TCA, N for a tendon; the range ``Robot.solve`` accepts, same message)
///     that take no actuation variable, e.g. ``{1: 25.0}`` keeps the
///     opposite TCA of a two-TCA finger at ambient. An actuator both grouped
///     and fixed, or neither, is a ``ValueError`` naming ``groups`` /
///     ``fixed_inputs``; a non-dict, a non-integer key or a non-real value a
///     ``TypeError``.
#[pyfunction]
#[pyo3(signature = (solution, groups=None, scheme="forward", fixed_inputs=None))]
#[allow(clippy::type_complexity)]
fn sensitivities<'py>(
    py: Python<'py>,
    solution: PyRef<'py, PySolution>,
    groups: Option<Bound<'py, PyAny>>,
    scheme: &str,
    fixed_inputs: Option<Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<f64>>)> {
    let robot = solution.robot.bind(py).get().clone();
    let g = groups_for(&robot, groups.as_ref(), fixed_inputs.as_ref())?;
    g.check_fixed(&solution.inner.inputs, "solution")?;
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

/// How far from orthogonal (`|R^T R - I|`, Frobenius norm) and from
/// determinant +1 a target rotation may be: rounding of a typed-in or
/// single-precision matrix passes, a reflection or a scaled matrix does not.
const ROTATION_TOLERANCE: f64 = 1e-6;

/// A 3x3 proper rotation matrix from Python (rows of 3 finite reals,
/// orthogonal and of determinant +1 within [`ROTATION_TOLERANCE`]).
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
    for (k, x) in mm.iter().enumerate() {
        crate::error::finite(&format!("target_rotation[{}][{}]", k % 3, k / 3), *x)?;
    }
    let off = (mm.transpose() * mm - Matrix3::identity()).norm();
    if off > ROTATION_TOLERANCE {
        return Err(Error::param(
            "target_rotation (|R^T R - I|, Frobenius norm)",
            off,
            format!("<= {ROTATION_TOLERANCE:e} (an orthogonal matrix)"),
        )
        .into());
    }
    // an orthogonal matrix with determinant -1 is a reflection: no pose of the tip
    let det = mm.determinant();
    if (det - 1.0).abs() > ROTATION_TOLERANCE {
        return Err(Error::param(
            "target_rotation (determinant)",
            det,
            format!("1 +- {ROTATION_TOLERANCE:e} (a proper rotation, not a reflection)"),
        )
        .into());
    }
    Ok(mm)
}

/// Actuation variables (temperatures [C]) that put the tip at `target` [m].
///
/// Iterates the paper's local inverse: at each iterate, `J` (exact, one
/// tangent IVP), a damped least-squares step
/// `dz = (J^T J + damping^2 I)^-1 J^T dx` with variables frozen at a bound
/// they would cross, a backtracking line search on the tip error, one BVP
/// solve per trial. The iteration stops as soon as the local inverse can no
/// longer get closer (the linearised decrease below 1e-10 of the error, or
/// less than 1e-6 of it over 5 iterations): a target off the bending plane
/// of a planar robot ends in a few iterations, not at `max_iter`.
///
/// An unreachable target is not an error: the result has `reached=False`
/// (`success=False`), the closest configuration found (its `solution`,
/// `variables`, `tip_position` [m] and distance `error` [m]) and which
/// variables rest on a bound (`at_bound`). `status` tells why it stopped,
/// as in SciPy: 0 reached; 1 unreachable (no descent left with a variable
/// on its bound: the closest point within the range); 2 out of budget
/// (`max_iter` used up while the error still decreased: continue with
/// `start=result.variables`); 3 stalled (no descent left with no variable
/// on a bound: the target is off the set the tip reaches near the closest
/// point, e.g. off the plane of a planar robot, or a local minimum).
/// `message` says the same in words; `nit` / `nfev` count iterations and
/// IVPs. The default budget reaches reachable targets on the paper's
/// manipulators in 4-7 iterations.
///
/// Parameters
/// ----------
/// robot : Robot
///     The robot.
/// target : sequence of 3 float
///     Target tip position [m], world frame, within 1000 body lengths.
/// start : sequence of float, optional
///     Initial actuation variables, one per variable (default: the reference
///     inputs, ambient temperature).
/// groups : sequence of int or None, optional
///     ``groups[i]`` is the actuation variable driving actuator ``i`` (e.g.
///     ``[0, 0]``: the two legs of a U-shaped TCA share one temperature),
///     ``None`` for an actuator in ``fixed_inputs``: one entry per actuator,
///     or one per actuator not in ``fixed_inputs`` (in order). Default: one
///     variable per actuator not in ``fixed_inputs``.
/// fixed_inputs : dict of int to float, optional
///     ``{actuator index: input}``: actuators held at a fixed input (C for a
///     TCA, N for a tendon; the range ``Robot.solve`` accepts, same message)
///     that take no actuation variable, e.g. ``{1: 25.0}`` keeps the
///     opposite TCA of a two-TCA finger at ambient. An actuator both grouped
///     and fixed, or neither, is a ``ValueError`` naming ``groups`` /
///     ``fixed_inputs``; a non-dict, a non-integer key or a non-real value a
///     ``TypeError``.
/// target_rotation : 3x3 array, optional
///     Target tip orientation: a proper rotation matrix (orthogonal and of
///     determinant +1 within 1e-6; anything else, a reflection included, is
///     a ``ValueError`` naming it).
/// orientation_weight : float, optional
///     Weight [m/rad] of orientation errors against position errors.
/// tol : float, optional
///     Position tolerance [m].
/// max_iter : int, optional
///     Iterations, 1 to 100,000 (default 50).
/// damping : float, optional
///     Damping [m per unit variable] of the least squares.
/// steps : int, optional
///     RK4 steps per forward solve, 1 to 100,000 (default 100).
///
/// Returns
/// -------
/// InverseResult
///     The closest configuration found and its status.
///
/// Raises
/// ------
/// ValueError
///     An argument outside its range (named, with its unit).
/// TypeError
///     An argument of the wrong type.
///
/// Examples
/// --------
/// >>> from tcarod.batch import fig6_square_robot
/// >>> robot = fig6_square_robot()                 # two TCA legs, one variable with groups
/// >>> target = robot.solve([100.0, 100.0], steps=50).tip_position   # [m]
/// >>> res = tcarod.tip_position(robot, target, groups=[0, 0], steps=50)
/// >>> res.success, round(res.variables[0], 3)     # temperature [C]
/// (True, 100.0)
/// >>> bool(res.error < 1e-7)                      # distance to the target [m]
/// True
#[pyfunction]
#[pyo3(signature = (robot, target, *, start=None, groups=None, fixed_inputs=None, target_rotation=None, orientation_weight=Real(0.01),
    tol=Real(1e-7), max_iter=None, damping=Real(1e-6), steps=None),
    text_signature = "(robot, target, *, start=None, groups=None, fixed_inputs=None, target_rotation=None, orientation_weight=0.01, \
        tol=1e-07, max_iter=50, damping=1e-06, steps=100)")]
#[allow(clippy::too_many_arguments)]
fn tip_position(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    target: Bound<'_, PyAny>,
    start: Option<Bound<'_, PyAny>>,
    groups: Option<Bound<'_, PyAny>>,
    fixed_inputs: Option<Bound<'_, PyAny>>,
    target_rotation: Option<Bound<'_, PyAny>>,
    orientation_weight: Real,
    tol: Real,
    max_iter: Option<Bound<'_, PyAny>>,
    damping: Real,
    steps: Option<Bound<'_, PyAny>>,
) -> PyResult<PyInverseResult> {
    let r = robot.get();
    let g = groups_for(r, groups.as_ref(), fixed_inputs.as_ref())?;
    let t = vec3("target [m]", &target)?;
    // checked even without a target rotation: a bad keyword is never ignored
    crate::error::positive("orientation_weight [m/rad]", orientation_weight.0)?;
    let rot = match target_rotation.as_ref().filter(|o| !o.is_none()) {
        Some(o) => Some(rotation_arg(o)?),
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

/// The Python result; its solution carries the core's stability verdict
/// with the tip held along the block normal (an unstable one warns).
fn blocked(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    b: BlockedResult,
    normal: Vector3<f64>,
) -> PyResult<PyBlockedResult> {
    let solution = match b.stability {
        Some(st) => super::stability::blocked_verdict(py, robot, b.solution, normal, st)?,
        None => PySolution::new(b.solution, robot.clone().unbind()),
    };
    Ok(PyBlockedResult {
        solution: Py::new(py, solution)?,
        force: b.force,
        variables: b.variables,
        iterations: b.iterations,
        evaluations: b.evaluations,
    })
}

/// What every blocked-tip binding reads: the robot's groups and the solve
/// options; the block from `point` [m] and `normal` when given.
struct BlockedArgs {
    robot: std::sync::Arc<crate::rod::Robot>,
    groups: Groups,
    opts: crate::shooting::SolveOptions,
}

/// The optional arguments `groups`, `fixed_inputs`, `steps`, `max_iter` of a blocked-tip binding.
type Optional<'py> = [Option<Bound<'py, PyAny>>; 4];

impl BlockedArgs {
    /// Groups and solve options (`[groups, fixed_inputs, steps, max_iter]` and `tol`).
    fn read_options(robot: &PyRobot, optional: Optional<'_>, tol: Real) -> PyResult<Self> {
        let [groups, fixed_inputs, steps, max_iter] = optional;
        Ok(BlockedArgs {
            groups: groups_for(robot, groups.as_ref(), fixed_inputs.as_ref())?,
            opts: solve_options(steps.as_ref(), tol, max_iter.as_ref())?,
            robot: robot.inner.clone(),
        })
    }
    /// [`BlockedArgs::read_options`] and the plane through `point` [m] with unit `normal`.
    fn read(
        robot: &PyRobot,
        (point, normal): (&Bound<'_, PyAny>, &Bound<'_, PyAny>),
        optional: Optional<'_>,
        tol: Real,
    ) -> PyResult<(Self, Block)> {
        let a = Self::read_options(robot, optional, tol)?;
        let block = Block::new(vec3("point [m]", point)?, direction("normal", normal)?)?;
        Ok((a, block))
    }
}

/// Contact force [N] of a tip held on a plane, at given actuation variables.
///
/// The plane passes through `point` [m] with unit `normal` (the direction
/// the tip presses in).
///
/// A mixed boundary-value problem solved directly: the contact force is an
/// extra shooting unknown and `normal . (p(L) - point) = 0` an extra
/// residual. The force comes out negative if the tip would pull away from
/// the plane; whether contact holds is the caller's decision.
///
/// Parameters
/// ----------
/// robot : Robot
///     The robot.
/// point, normal : sequence of 3 float
///     A point [m] of the blocking plane and its normal (the direction the
///     tip presses in).
/// variables : float or sequence of float
///     Actuation variables (temperatures [C]), one per variable of
///     ``groups``; a number for one variable.
/// groups : sequence of int or None, optional
///     ``groups[i]`` is the actuation variable driving actuator ``i`` (e.g.
///     ``[0, 0]``: the two legs of a U-shaped TCA share one temperature),
///     ``None`` for an actuator in ``fixed_inputs``: one entry per actuator,
///     or one per actuator not in ``fixed_inputs`` (in order). Default: one
///     variable per actuator not in ``fixed_inputs``.
/// fixed_inputs : dict of int to float, optional
///     ``{actuator index: input}``: actuators held at a fixed input (C for a
///     TCA, N for a tendon; the range ``Robot.solve`` accepts, same message)
///     that take no actuation variable, e.g. ``{1: 25.0}`` keeps the
///     opposite TCA of a two-TCA finger at ambient. An actuator both grouped
///     and fixed, or neither, is a ``ValueError`` naming ``groups`` /
///     ``fixed_inputs``; a non-dict, a non-integer key or a non-real value a
///     ``TypeError``.
/// steps, tol, max_iter : int, float, int, optional
///     RK4 steps, Newton tolerance, Newton iterations.
/// warm_start : BlockedResult, optional
///     A nearby blocked result (e.g. the previous temperature of a sweep).
///
/// Returns
/// -------
/// BlockedResult
///     ``force`` [N] and the blocked solution.
///
/// Raises
/// ------
/// ValueError
///     An argument outside its range (named, with its unit).
///
/// Examples
/// --------
/// >>> from tcarod.batch import fig6_square_robot
/// >>> robot = fig6_square_robot()
/// >>> tip = robot.solve([25.0, 25.0], steps=20).tip_position   # blocked where it rests [m]
/// >>> res = tcarod.blocked_force(robot, tip, [-1.0, 0.0, 0.0], [80.0], groups=[0, 0], steps=20)
/// >>> round(res.force * 1e3, 3)                   # contact force at 80 C [mN]
/// 5.393
#[pyfunction]
#[pyo3(signature = (robot, point, normal, variables, *, groups=None, fixed_inputs=None, steps=None, tol=Real(1e-10), max_iter=None, warm_start=None),
    text_signature = "(robot, point, normal, variables, *, groups=None, fixed_inputs=None, steps=100, tol=1e-10, max_iter=50, warm_start=None)")]
#[allow(clippy::too_many_arguments)]
fn blocked_force(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    point: Bound<'_, PyAny>,
    normal: Bound<'_, PyAny>,
    variables: Bound<'_, PyAny>,
    groups: Option<Bound<'_, PyAny>>,
    fixed_inputs: Option<Bound<'_, PyAny>>,
    steps: Option<Bound<'_, PyAny>>,
    tol: Real,
    max_iter: Option<Bound<'_, PyAny>>,
    warm_start: Option<PyRef<'_, PyBlockedResult>>,
) -> PyResult<PyBlockedResult> {
    let (a, block) = BlockedArgs::read(
        robot.get(),
        (&point, &normal),
        [groups, fixed_inputs, steps, max_iter],
        tol,
    )?;
    let variables = reals("variables", &variables, Some(a.groups.n_vars()))?;
    if let Some(w) = &warm_start {
        same_robot(py, robot.get(), w.solution.bind(py).get(), "warm_start")?;
    }
    let warm = warm_start.map(|w| (w.solution.bind(py).get().inner.clone(), w.force));
    let res = super::errors::detach_interruptible(py, || {
        let w = warm.as_ref().map(|(s, f)| (s, *f));
        inverse::blocked_force(&a.robot, &a.groups, &block, &variables, &a.opts, w)
    })?;
    blocked(py, robot, res, block.normal)
}

/// The actuation variable at which the blocked tip presses with `force` [N].
///
/// The paper's incremental method (eq 43, `dx = 0`): from `start` (a solution
/// of this robot whose tip touches the block with no force), the single
/// actuation variable at which the tip presses with `force` [N], in
/// `increments` steps (1 to 10,000).
///
/// Parameters
/// ----------
/// groups : sequence of int or None, optional
///     ``groups[i]`` is the actuation variable driving actuator ``i`` (e.g.
///     ``[0, 0]``: the two legs of a U-shaped TCA share one temperature),
///     ``None`` for an actuator in ``fixed_inputs``: one entry per actuator,
///     or one per actuator not in ``fixed_inputs`` (in order). Default: one
///     variable per actuator not in ``fixed_inputs``.
/// fixed_inputs : dict of int to float, optional
///     ``{actuator index: input}``: actuators held at a fixed input (C for a
///     TCA, N for a tendon; the range ``Robot.solve`` accepts, same message)
///     that take no actuation variable, e.g. ``{1: 25.0}`` keeps the
///     opposite TCA of a two-TCA finger at ambient. An actuator both grouped
///     and fixed, or neither, is a ``ValueError`` naming ``groups`` /
///     ``fixed_inputs``; a non-dict, a non-integer key or a non-real value a
///     ``TypeError``.
#[pyfunction]
#[pyo3(signature = (robot, point, normal, force, start, *, groups=None, fixed_inputs=None, increments=None, steps=None, tol=Real(1e-10), max_iter=None),
    text_signature = "(robot, point, normal, force, start, *, groups=None, fixed_inputs=None, increments=10, steps=100, tol=1e-10, max_iter=50)")]
#[allow(clippy::too_many_arguments)]
fn blocked_temperature(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    point: Bound<'_, PyAny>,
    normal: Bound<'_, PyAny>,
    force: Real,
    start: PyRef<'_, PySolution>,
    groups: Option<Bound<'_, PyAny>>,
    fixed_inputs: Option<Bound<'_, PyAny>>,
    increments: Option<Bound<'_, PyAny>>,
    steps: Option<Bound<'_, PyAny>>,
    tol: Real,
    max_iter: Option<Bound<'_, PyAny>>,
) -> PyResult<PyBlockedResult> {
    let (a, block) = BlockedArgs::read(
        robot.get(),
        (&point, &normal),
        [groups, fixed_inputs, steps, max_iter],
        tol,
    )?;
    same_robot(py, robot.get(), &start, "start")?;
    let increments = count_or("increments", increments.as_ref(), 10, 1, MAX_INCREMENTS)?;
    let st = start.inner.clone();
    let res = super::errors::detach_interruptible(py, || {
        let (r, g) = (&a.robot, &a.groups);
        inverse::blocked_temperature(r, g, &block, &st, force.0, increments, &a.opts)
    })?;
    blocked(py, robot, res, block.normal)
}

/// The actuation variable of `blocked_temperature`, solved directly.
///
/// Direct solve (independent check of `blocked_temperature`): the actuation
/// variable is a shooting unknown starting from `guess` (temperature [C]),
/// the contact force [N] is given.
///
/// Parameters
/// ----------
/// groups : sequence of int or None, optional
///     ``groups[i]`` is the actuation variable driving actuator ``i`` (e.g.
///     ``[0, 0]``: the two legs of a U-shaped TCA share one temperature),
///     ``None`` for an actuator in ``fixed_inputs``: one entry per actuator,
///     or one per actuator not in ``fixed_inputs`` (in order). Default: one
///     variable per actuator not in ``fixed_inputs``.
/// fixed_inputs : dict of int to float, optional
///     ``{actuator index: input}``: actuators held at a fixed input (C for a
///     TCA, N for a tendon; the range ``Robot.solve`` accepts, same message)
///     that take no actuation variable, e.g. ``{1: 25.0}`` keeps the
///     opposite TCA of a two-TCA finger at ambient. An actuator both grouped
///     and fixed, or neither, is a ``ValueError`` naming ``groups`` /
///     ``fixed_inputs``; a non-dict, a non-integer key or a non-real value a
///     ``TypeError``.
#[pyfunction]
#[pyo3(signature = (robot, point, normal, force, guess, *, groups=None, fixed_inputs=None, steps=None, tol=Real(1e-10), max_iter=None),
    text_signature = "(robot, point, normal, force, guess, *, groups=None, fixed_inputs=None, steps=100, tol=1e-10, max_iter=50)")]
#[allow(clippy::too_many_arguments)]
fn blocked_temperature_direct(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    point: Bound<'_, PyAny>,
    normal: Bound<'_, PyAny>,
    force: Real,
    guess: Real,
    groups: Option<Bound<'_, PyAny>>,
    fixed_inputs: Option<Bound<'_, PyAny>>,
    steps: Option<Bound<'_, PyAny>>,
    tol: Real,
    max_iter: Option<Bound<'_, PyAny>>,
) -> PyResult<PyBlockedResult> {
    let (a, block) = BlockedArgs::read(
        robot.get(),
        (&point, &normal),
        [groups, fixed_inputs, steps, max_iter],
        tol,
    )?;
    let res = super::errors::detach_interruptible(py, || {
        let (r, g) = (&a.robot, &a.groups);
        inverse::blocked_variable_direct(r, g, &block, force.0, guess.0, &a.opts, None)
    })?;
    blocked(py, robot, res, block.normal)
}

/// Grasp temperature [C] (eq 44) of `fingers` identical fingers holding `mass` [kg].
///
/// The actuation variable at which `fingers`
/// identical fingers (this `robot`) with friction coefficient `mu` [-] hold
/// a mass `mass` [kg] under `gravity` [m/s^2], `mu n F(T) = m g`, each
/// finger's tip blocked where it rests at the `contact` inputs (default: the
/// reference inputs) and pressing along `normal`. `method`: `"incremental"`
/// (eq 43 in `increments` steps, 1 to 10,000) or `"direct"` (one bordered
/// Newton solve of the multiple-shooting system: the variable an extra
/// unknown, the tip's contact an extra condition, from an eq-43
/// predictor). Returns `(blocked result of one finger, block point [m])`;
/// the result's `force` [N] is `m g / (mu n)`.
///
/// Parameters
/// ----------
/// groups : sequence of int or None, optional
///     ``groups[i]`` is the actuation variable driving actuator ``i`` (e.g.
///     ``[0, 0]``: the two legs of a U-shaped TCA share one temperature),
///     ``None`` for an actuator in ``fixed_inputs``: one entry per actuator,
///     or one per actuator not in ``fixed_inputs`` (in order). Default: one
///     variable per actuator not in ``fixed_inputs``.
/// fixed_inputs : dict of int to float, optional
///     ``{actuator index: input}``: actuators held at a fixed input (C for a
///     TCA, N for a tendon; the range ``Robot.solve`` accepts, same message)
///     that take no actuation variable, e.g. ``{1: 25.0}`` keeps the
///     opposite TCA of a two-TCA finger at ambient. An actuator both grouped
///     and fixed, or neither, is a ``ValueError`` naming ``groups`` /
///     ``fixed_inputs``; a non-dict, a non-integer key or a non-real value a
///     ``TypeError``.
#[pyfunction]
#[pyo3(signature = (robot, normal, mass, mu, fingers, *, gravity=Real(crate::experiments::G0), groups=None, fixed_inputs=None,
    contact=None, method="incremental", increments=None, steps=None, tol=Real(1e-10), max_iter=None),
    text_signature = "(robot, normal, mass, mu, fingers, *, gravity=9.81, groups=None, fixed_inputs=None, contact=None, \
        method='incremental', increments=8, steps=100, tol=1e-10, max_iter=50)")]
#[allow(clippy::too_many_arguments)]
fn grasp_temperature(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    normal: Bound<'_, PyAny>,
    mass: Real,
    mu: Real,
    fingers: Bound<'_, PyAny>,
    gravity: Real,
    groups: Option<Bound<'_, PyAny>>,
    fixed_inputs: Option<Bound<'_, PyAny>>,
    contact: Option<Bound<'_, PyAny>>,
    method: &str,
    increments: Option<Bound<'_, PyAny>>,
    steps: Option<Bound<'_, PyAny>>,
    tol: Real,
    max_iter: Option<Bound<'_, PyAny>>,
) -> PyResult<(PyBlockedResult, [f64; 3])> {
    let a = BlockedArgs::read_options(robot.get(), [groups, fixed_inputs, steps, max_iter], tol)?;
    let na = a.robot.actuators.len();
    let spec = inverse::Grasp {
        normal: direction("normal", &normal)?,
        mass: mass.0,
        mu: mu.0,
        fingers: super::args::count("fingers", &fingers, 1, super::MAX_SEQUENCE)?,
        gravity: gravity.0,
        contact: contact
            .map(|c| super::reals("contact", &c, Some(na)))
            .transpose()?,
        stability: crate::stability::Policy::Report,
    };
    let method = match method {
        "incremental" => inverse::GraspMethod::Incremental(count_or(
            "increments",
            increments.as_ref(),
            8,
            1,
            MAX_INCREMENTS,
        )?),
        "direct" => inverse::GraspMethod::Direct,
        _ => {
            return Err(crate::error::Error::input(
                "method",
                format!("{method:?} is not 'incremental' or 'direct'"),
            )
            .into())
        }
    };
    let (res, point) = super::errors::detach_interruptible(py, || {
        spec.solve(&a.robot, &a.groups, method, &a.opts)
    })?;
    Ok((
        blocked(py, robot, res, spec.normal)?,
        [point.x, point.y, point.z],
    ))
}
