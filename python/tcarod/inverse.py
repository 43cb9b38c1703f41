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
actuator. Argument errors raise ``ValueError``; a failed solve raises
:class:`tcarod.ConvergenceError`.
"""

from __future__ import annotations

from typing import Any, Literal, Optional, Sequence, Union

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


def _groups(groups: Sequence[int] | None) -> Optional[list[int]]:
    """``groups`` as a list of ints: ``TypeError`` for non-integers (bool,
    float, str), ``ValueError`` for negative ones (the core checks the rest)."""
    if groups is None:
        return None
    if isinstance(groups, (str, bytes, bytearray)):
        raise TypeError(f"groups: expected a sequence of integers, not {type(groups).__name__}")
    out = []
    for g in groups:
        if isinstance(g, (bool, np.bool_)) or not isinstance(g, (int, np.integer)):
            raise TypeError(f"groups: expected integers, got {g!r}")
        if g < 0:
            raise ValueError(f"groups: invalid groups entry {g}: allowed 0 <= groups[i] < number of actuators")
        out.append(int(g))
    return out


def _plane(point: Vector, normal: Vector) -> tuple[list[float], list[float]]:
    """The blocking plane's ``point`` [m] and ``normal`` as lists of 3 floats."""
    return _vector("point [m]", point, 3), _vector("normal", normal, 3)


def _solver(groups: Sequence[int] | None, steps: int, tol: float, max_iter: int) -> dict[str, Any]:
    """The keyword arguments every blocked-tip solve passes to the core."""
    return {"groups": _groups(groups), "steps": steps, "tol": tol, "max_iter": max_iter}


def jacobian_and_compliance(
    solution: Solution,
    groups: Sequence[int] | None = None,
    scheme: Literal["forward", "central"] = "forward",
) -> tuple[FloatArray, FloatArray]:
    """``(J, C)`` at a converged ``solution`` (eqs 41-42).

    ``J = E_q - E_u B_u^-1 B_q`` is ``6 x n_vars``: tip ``[dp (m); dtheta (rad)]``
    per unit actuation variable (per C for TCAs). ``C = E_W - E_u B_u^-1 B_W`` is
    ``6 x 6``: tip pose per unit tip wrench ``[F (N); M (N m)]``. World frame;
    evaluated at the solution's own tip loads (a blocked solution includes its
    contact force). ``scheme="forward"`` integrates ``12 + 2N`` IVPs (the
    paper's count; relative error ~1e-8), ``"central"`` twice as many (~1e-11).
    """
    if scheme not in ("forward", "central"):
        raise ValueError(f"scheme must be 'forward' or 'central', got {scheme!r}")
    j, c = _core.sensitivities(solution, _groups(groups), scheme)
    return np.asarray(j, dtype=np.float64), np.asarray(c, dtype=np.float64)


def blocked_temperature(
    robot: Robot,
    point: Vector,
    normal: Vector,
    force: float,
    start: Solution | None = None,
    *,
    groups: Sequence[int] | None = None,
    increments: int = 10,
    steps: int = 100,
    tol: float = 1e-10,
    max_iter: int = 50,
) -> BlockedResult:
    """The actuation variable (temperature [C]) at which the blocked tip
    presses with ``force`` [N]: the paper's incremental method, eq (43).

    From ``start``, a solution whose tip touches the plane with no force
    (default: the free solution at the reference inputs, whose tip must then
    lie on the plane), the contact force rises to ``force`` in ``increments``
    steps; each step is ``dq = -(n^T J)^-1 n^T C dW`` with ``J`` and ``C``
    exact (one tangent IVP), then one BVP solve and a position correction
    that keeps the tip on the plane. Needs exactly one actuation variable
    (e.g. ``groups=[0, 0]`` for a U-shaped TCA). Raises ``ValueError`` if the
    force needs a temperature outside the material's range.
    """
    V.instance("robot", robot, Robot, "a tcarod.Robot")
    if start is None:
        start = robot.solve(robot.reference_inputs, steps=steps, tol=tol, max_iter=max_iter)
    solver = _solver(groups, steps, tol, max_iter)
    return _core.blocked_temperature(robot, *_plane(point, normal), force, start, increments=increments, **solver)


def blocked_temperature_direct(
    robot: Robot,
    point: Vector,
    normal: Vector,
    force: float,
    guess: float | None = None,
    *,
    groups: Sequence[int] | None = None,
    steps: int = 100,
    tol: float = 1e-10,
    max_iter: int = 50,
) -> BlockedResult:
    """The same unknown as :func:`blocked_temperature`, solved directly: the
    single actuation variable is an extra shooting unknown of the mixed
    boundary-value problem with the contact ``force`` [N] given (Newton
    with the exact Jacobian of the augmented system).

    ``guess``: starting temperature [C] (default: the midpoint of the first
    actuator's input range). A robot without actuators raises ``ValueError``. Newton from a poor guess may fail with
    :class:`tcarod.ConvergenceError`; the incremental method is the robust one.
    """
    V.instance("robot", robot, Robot, "a tcarod.Robot")
    if not robot.actuators:
        raise ValueError("invalid robot: it has no actuator to heat (the temperature is the unknown solved for)")
    if guess is None:
        lo, hi = robot.actuators[0].input_bounds
        guess = 0.5 * (lo + hi)
    return _core.blocked_temperature_direct(
        robot, *_plane(point, normal), force, guess, **_solver(groups, steps, tol, max_iter)
    )
