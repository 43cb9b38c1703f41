"""Inverse kinetostatics (paper Section IV, eqs 34-43), on the Rust core.

* :func:`jacobian_and_compliance`: the actuation Jacobian ``J`` and the
  compliance ``C`` of eqs (41)-(42) at a converged solution, from finite
  differences of IVP solves around it (Rucker & Webster, ICRA 2011).
* :func:`tip_position`: temperatures that put the tip at a target position,
  iterating the local inverse ``dq = J^+ dx`` (damped least squares, within the
  temperature range).
* Blocked tip (Section V-C/V-D): the tip is held on a plane through ``point``
  with unit ``normal``; the tip presses on it along ``+normal`` with contact
  force ``f >= 0`` [N] (the environment pushes back with ``-f normal``).
  :func:`blocked_force` gives ``f`` at given temperatures (direct mixed
  solve: ``f`` is a shooting unknown); :func:`blocked_temperature` gives the
  temperature for a wanted ``f`` by the paper's incremental method, eq (43)
  with ``dx = 0``; :func:`blocked_temperature_direct` solves the same
  equations directly (the temperature is a shooting unknown) as a check.
  Each result's ``solution`` carries the core's stability verdict of the
  equilibrium with the tip held along ``normal`` (``solution.stable``,
  ``solution.stability_margin``); an unstable one raises
  :class:`tcarod.UnstableEquilibriumWarning`.

Conventions: world frame with the base at the origin and the reference
tangent along ``+z``; tip poses ``[dp (m); dtheta (rad)]``, tip wrenches
``[F (N); M (N m)]``, temperatures in degrees C. ``groups[i]`` is the
actuation variable driving actuator ``i``: the two legs of a U-shaped TCA
share one temperature with ``groups=[0, 0]``; the default is one variable per
actuator. ``fixed_inputs={i: value}`` holds actuator ``i`` at a fixed input
(C for a TCA) with no variable: ``groups`` then lists ``None`` for it, or
maps only the other actuators (``fixed_inputs={1: 25.0}`` alone heats
actuator 0 of a two-TCA finger and keeps actuator 1 at 25 C). Argument errors raise ``ValueError``; a failed solve raises
:class:`tcarod.ConvergenceError`.
"""

from __future__ import annotations

from typing import Any, Literal, Mapping, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from . import _core
from ._core import BlockedResult, InverseResult, blocked_force, tip_position  # the bindings: no defaults to fill
from .rod import Robot, Solution
from .tca import _as_float_array
from . import _validate as V

__all__ = [
    "BlockedResult",
    "InverseResult",
    "blocked_force",
    "blocked_temperature",
    "blocked_temperature_direct",
    "jacobian_and_compliance",
    "tip_position",
]

FloatArray = npt.NDArray[np.float64]
Vector = Union[Sequence[float], FloatArray]


def _vector(name: str, value: Vector | float, size: int | None = None) -> list[float]:
    """``value`` as a list of floats (``size`` of them if given).

    ``TypeError`` for str, bytes, complex (incl. NumPy complex) or None;
    ``ValueError`` naming ``name`` for a wrong shape."""
    arr = _as_float_array(name, value)
    if arr.ndim == 0:
        arr = arr.reshape(1)
    if arr.ndim != 1 or (size is not None and arr.shape[0] != size):
        want = f"{size} values" if size is not None else "a 1-D sequence of numbers"
        raise ValueError(f"{name}: expected {want}, got shape {arr.shape}")
    return [float(x) for x in arr]


def _groups(groups: Sequence[int | None] | None) -> Optional[list[int | None]]:
    """``groups`` as a list of ints and ``None`` (an actuator in ``fixed_inputs``):
    ``TypeError`` for other entries (bool, float, str), ``ValueError`` for
    negative ones (the core checks the rest)."""
    if groups is None:
        return None
    if isinstance(groups, (str, bytes, bytearray)):
        raise TypeError(f"groups: expected a sequence of integers, not {type(groups).__name__}")
    out: list[int | None] = []
    for g in groups:
        if g is None:
            out.append(None)
            continue
        if isinstance(g, (bool, np.bool_)) or not isinstance(g, (int, np.integer)):
            raise TypeError(f"groups: expected integers (or None for an actuator in fixed_inputs), got {g!r}")
        if g < 0:
            raise ValueError(f"groups: invalid groups entry {g}: allowed 0 <= groups[i] < number of actuators")
        out.append(int(g))
    return out


def _fixed(fixed_inputs: Mapping[int, float] | None) -> Optional[dict[Any, Any]]:
    """``fixed_inputs`` as a dict (``TypeError`` unless a mapping; the core
    checks its keys and values)."""
    if fixed_inputs is None:
        return None
    if not isinstance(fixed_inputs, Mapping):
        raise TypeError(f"fixed_inputs: expected a dict {{actuator index: input}}, not {type(fixed_inputs).__name__}")
    return dict(fixed_inputs)


def _with_fixed(inputs: Sequence[float], fixed_inputs: Mapping[int, float] | None) -> list[float]:
    """``inputs`` with the actuators in ``fixed_inputs`` at their fixed inputs
    (keys that are no actuator index are left to the core's check)."""
    out = [float(x) for x in inputs]
    for i, v in (fixed_inputs or {}).items():
        if isinstance(i, (int, np.integer)) and not isinstance(i, bool) and 0 <= i < len(out):
            out[int(i)] = v
    return out


def _plane(point: Vector, normal: Vector) -> tuple[list[float], list[float]]:
    """The blocking plane's ``point`` [m] and ``normal`` as lists of 3 floats."""
    return _vector("point [m]", point, 3), _vector("normal", normal, 3)


def _solver(
    groups: Sequence[int | None] | None,
    fixed_inputs: Mapping[int, float] | None,
    steps: int,
    tol: float,
    max_iter: int,
) -> dict[str, Any]:
    """The keyword arguments every blocked-tip solve passes to the core."""
    return {
        "groups": _groups(groups),
        "fixed_inputs": _fixed(fixed_inputs),
        "steps": steps,
        "tol": tol,
        "max_iter": max_iter,
    }


def jacobian_and_compliance(
    solution: Solution,
    groups: Sequence[int | None] | None = None,
    scheme: Literal["forward", "central"] = "forward",
    *,
    fixed_inputs: Mapping[int, float] | None = None,
) -> tuple[FloatArray, FloatArray]:
    """``(J, C)`` at a converged ``solution`` (eqs 41-42).

    ``J = E_q - E_u B_u^-1 B_q`` is ``6 x n_vars``: tip ``[dp (m); dtheta (rad)]``
    per unit actuation variable (per C for TCAs), one column per variable (an
    actuator in ``fixed_inputs`` has none). ``C = E_W - E_u B_u^-1 B_W`` is
    ``6 x 6``: tip pose per unit tip wrench ``[F (N); M (N m)]``. World frame;
    evaluated at the solution's own tip loads (a blocked solution includes its
    contact force). ``scheme="forward"`` integrates ``12 + 2N`` IVPs (the
    paper's count; relative error ~1e-8), ``"central"`` twice as many (~1e-11).

    Parameters
    ----------
    solution : Solution
        A converged solution of the robot.
    groups : sequence of int or None, optional
        ``groups[i]`` is the actuation variable driving actuator ``i`` (e.g.
        ``[0, 0]``: the two legs of a U-shaped TCA share one temperature),
        ``None`` for an actuator in ``fixed_inputs``: one entry per actuator,
        or one per actuator not in ``fixed_inputs`` (in order). Default: one variable per actuator not in ``fixed_inputs``.
    fixed_inputs : dict of int to float, optional
        ``{actuator index: input}``: actuators held at a fixed input (C for a
        TCA, N for a tendon; the range ``Robot.solve`` accepts), with no
        actuation variable, e.g. ``{1: 25.0}`` keeps the opposite TCA of a
        two-TCA finger at ambient. An actuator both grouped and fixed, or
        neither, raises ``ValueError`` naming ``groups`` / ``fixed_inputs``.
        Each fixed input must equal the solution's input of that actuator.
    scheme : {"forward", "central"}
        Finite-difference scheme.

    Returns
    -------
    J : ndarray, shape (6, n_vars)
        Tip pose per unit actuation variable [m/C; rad/C for TCAs].
    C : ndarray, shape (6, 6)
        Tip pose per unit tip wrench [m/N, rad/N; m/(N m), rad/(N m)].

    Raises
    ------
    ValueError
        Bad ``groups``, ``fixed_inputs`` or ``scheme``.
    TypeError
        ``groups`` or ``fixed_inputs`` of the wrong type.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> sol = fig6_square_robot().solve([100.0, 100.0], steps=50)
    >>> J, C = tcarod.jacobian_and_compliance(sol, groups=[0, 0])   # both legs: one temperature
    >>> J.shape, C.shape
    ((6, 1), (6, 6))
    >>> round(float(J[0, 0]) * 1e3, 3)       # tip x per degree [mm/C]: heating bends towards -x
    -0.117
    """
    if scheme not in ("forward", "central"):
        raise ValueError(f"scheme must be 'forward' or 'central', got {scheme!r}")
    j, c = _core.sensitivities(solution, _groups(groups), scheme, _fixed(fixed_inputs))
    return np.asarray(j, dtype=np.float64), np.asarray(c, dtype=np.float64)


def blocked_temperature(
    robot: Robot,
    point: Vector,
    normal: Vector,
    force: float,
    start: Solution | None = None,
    *,
    groups: Sequence[int | None] | None = None,
    fixed_inputs: Mapping[int, float] | None = None,
    increments: int = 10,
    steps: int = 100,
    tol: float = 1e-10,
    max_iter: int = 50,
) -> BlockedResult:
    """The actuation variable (temperature [C]) at which the blocked tip presses with ``force`` [N].

    The paper's incremental method, eq (43). From ``start``, a solution whose tip touches the plane with no force,
    the contact force rises to ``force`` in ``increments`` steps; each step
    is ``dq = -(n^T J)^-1 n^T C dW`` with ``J`` and ``C`` exact (one tangent
    IVP), then one BVP solve and a position correction that keeps the tip
    on the plane. Needs exactly one actuation variable (e.g. ``groups=[0,
    0]`` for a U-shaped TCA, or ``fixed_inputs={1: 25.0}`` for one of two
    TCAs heated).

    Parameters
    ----------
    robot : Robot
        The robot.
    point, normal : sequence of 3 float
        The blocking plane: a point [m] and the unit direction [-] the tip presses in.
    force : float
        Contact force [N].
    start : Solution, optional
        Default: the free solution at the reference inputs with the fixed
        inputs applied (its tip must then lie on the plane).
    groups : sequence of int or None, optional
        ``groups[i]`` is the actuation variable driving actuator ``i`` (e.g.
        ``[0, 0]``: the two legs of a U-shaped TCA share one temperature),
        ``None`` for an actuator in ``fixed_inputs``: one entry per actuator,
        or one per actuator not in ``fixed_inputs`` (in order). Default: one variable per actuator not in ``fixed_inputs``.
    fixed_inputs : dict of int to float, optional
        ``{actuator index: input}``: actuators held at a fixed input (C for a
        TCA, N for a tendon; the range ``Robot.solve`` accepts), with no
        actuation variable, e.g. ``{1: 25.0}`` keeps the opposite TCA of a
        two-TCA finger at ambient. An actuator both grouped and fixed, or
        neither, raises ``ValueError`` naming ``groups`` / ``fixed_inputs``.
    increments, steps, tol, max_iter : int, int, float, int
        Force steps [-], RK4 steps per solve [-], Newton tolerance [-]
        (dimensionless residual), Newton iterations [-].

    Returns
    -------
    BlockedResult
        ``variables[0]`` the temperature [C], ``force`` [N].

    Raises
    ------
    ValueError
        If the force needs a temperature outside the material's range, or
        for bad arguments.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> robot = fig6_square_robot()
    >>> tip = robot.solve([25.0, 25.0], steps=20).tip_position       # blocked where it rests [m]
    >>> res = tcarod.blocked_temperature(robot, tip, [-1.0, 0.0, 0.0], 0.002, groups=[0, 0], steps=20)
    >>> round(res.variables[0], 1), round(res.force * 1e3, 3)         # [C] to press with [mN]
    (54.3, 2.0)
    """
    V.instance("robot", robot, Robot, "a tcarod.Robot")
    if start is None:
        inputs = _with_fixed(robot.reference_inputs, _fixed(fixed_inputs))
        start = robot.solve(inputs, steps=steps, tol=tol, max_iter=max_iter)
    solver = _solver(groups, fixed_inputs, steps, tol, max_iter)
    return _core.blocked_temperature(robot, *_plane(point, normal), force, start, increments=increments, **solver)


def blocked_temperature_direct(
    robot: Robot,
    point: Vector,
    normal: Vector,
    force: float,
    guess: float | None = None,
    *,
    groups: Sequence[int | None] | None = None,
    fixed_inputs: Mapping[int, float] | None = None,
    steps: int = 100,
    tol: float = 1e-10,
    max_iter: int = 50,
) -> BlockedResult:
    """The temperature [C] of :func:`blocked_temperature`, solved directly.

    The single actuation variable is an extra unknown of the mixed
    boundary-value problem with the contact ``force`` [N] given, the tip's
    contact an extra condition: Newton's method on the multiple-shooting
    system bordered by them (docs/solver.md, "Blocked tip"), with
    continuation in the variable where Newton fails.

    Newton from a poor guess may fail with :class:`tcarod.ConvergenceError`;
    the incremental method is the robust one.

    Parameters
    ----------
    robot : Robot
        The robot (with at least one actuator: ``ValueError`` otherwise).
    point, normal : sequence of 3 float
        The blocking plane: a point [m] and the unit direction [-] the tip presses in.
    force : float
        Contact force [N].
    guess : float, optional
        Starting temperature [C] (default: the midpoint of the input range of
        the first actuator not in ``fixed_inputs``).
    groups : sequence of int or None, optional
        ``groups[i]`` is the actuation variable driving actuator ``i`` (e.g.
        ``[0, 0]``: the two legs of a U-shaped TCA share one temperature),
        ``None`` for an actuator in ``fixed_inputs``: one entry per actuator,
        or one per actuator not in ``fixed_inputs`` (in order). Default: one variable per actuator not in ``fixed_inputs``.
    fixed_inputs : dict of int to float, optional
        ``{actuator index: input}``: actuators held at a fixed input (C for a
        TCA, N for a tendon; the range ``Robot.solve`` accepts), with no
        actuation variable, e.g. ``{1: 25.0}`` keeps the opposite TCA of a
        two-TCA finger at ambient. An actuator both grouped and fixed, or
        neither, raises ``ValueError`` naming ``groups`` / ``fixed_inputs``.
    steps, tol, max_iter : int, float, int
        RK4 steps per solve [-], Newton tolerance [-] (dimensionless
        residual), Newton iterations [-].

    Returns
    -------
    BlockedResult
        ``variables[0]`` the temperature [C], ``force`` [N].

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> robot = fig6_square_robot()
    >>> tip = robot.solve([25.0, 25.0], steps=20).tip_position       # blocked where it rests [m]
    >>> res = tcarod.blocked_temperature_direct(robot, tip, [-1.0, 0.0, 0.0], 0.002, guess=50.0,
    ...                                         groups=[0, 0], steps=20)
    >>> round(res.variables[0], 1)                                   # the same 54.3 C as eq (43)
    54.3
    """
    V.instance("robot", robot, Robot, "a tcarod.Robot")
    if not robot.actuators:
        raise ValueError("invalid robot: it has no actuator to heat (the temperature is the unknown solved for)")
    fixed = _fixed(fixed_inputs) or {}
    if guess is None:
        free = [a for i, a in enumerate(robot.actuators) if i not in fixed] or list(robot.actuators)
        lo, hi = free[0].input_bounds
        guess = 0.5 * (lo + hi)
    return _core.blocked_temperature_direct(
        robot, *_plane(point, normal), force, guess, **_solver(groups, fixed_inputs, steps, tol, max_iter)
    )
