"""Brute-force inverse kinetostatics: the baseline the paper compares against.

Section IV: "A straightforward solution is to leverage forward kinetostatics
to iteratively update the guess for the temperatures until the desired
configuration is achieved (brute-force optimization)". These functions do
exactly that with scipy's derivative-free optimisers over full BVP solves of
the same forward model (each warm-started from the previous one), with no
Jacobian, so that :mod:`tcarod.inverse` (finite differences of IVPs, the
paper's method) can be checked and timed against them
(``benches/inverse_vs_bruteforce.py``).

* :func:`brute_force_blocked_temperature`: the temperature at which a tip
  held on a plane presses with a given force: the force is applied as a dead
  tip load ``-force * normal`` and ``|normal . (p(L) - point)|`` is minimised
  over the temperature (bounded Brent, ``minimize_scalar``).
* :func:`brute_force_tip_position`: the temperatures minimising the tip error
  ``|p(L) - target|`` (Nelder-Mead, ``minimize``, inputs clipped to their range).

scipy is needed (the ``fit`` extra: ``pip install 'tcarod[fit]'``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np
import numpy.typing as npt

from .. import _validate as V
from .._optional import require
from ..rod import Robot, Solution

__all__ = ["BruteForceResult", "brute_force_blocked_temperature", "brute_force_tip_position"]


@dataclass(frozen=True, eq=False)
class BruteForceResult:
    """Outcome of a brute-force inverse.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> robot = fig6_square_robot()
    >>> from tcarod.models.bruteforce import brute_force_tip_position
    >>> target = robot.solve([80.0, 80.0], steps=20).tip_position         # [m]
    >>> res = brute_force_tip_position(robot, target, groups=[0, 0], steps=20)
    >>> round(res.variables[0], 2), res.error_m < 1e-6, res.forward_solves > 10   # [C], [m]
    (80.0, True, True)
    """

    #: Actuation variables found (temperatures [C]), one per group.
    variables: tuple[float, ...]
    #: Final objective: tip gap or tip distance [m].
    error_m: float
    #: Forward (BVP) solves performed.
    forward_solves: int
    solution: Solution


@dataclass
class _Forward:
    """Forward solves of one robot, each warm-started from the previous; counted."""

    robot: Robot
    steps: int
    warm: Solution | None = None
    count: int = 0

    def solve(self, inputs: list[float]) -> Solution:
        # the objective reads the tip only: no stability verdict
        sol = self.robot.solve(inputs, steps=self.steps, warm_start=self.warm, stability="off")
        self.warm = sol
        self.count += 1
        return sol


def _groups(robot: Robot, groups: Sequence[int] | None, default: list[int]) -> list[int]:
    """Validated ``groups``: one non-negative int per actuator, variables numbered 0..k-1 without gaps."""
    n = len(robot.actuators)
    if n == 0:
        raise ValueError("robot: has no actuators to invert for")
    if groups is None:
        return default
    grp = [V.integer(f"groups[{i}]", g, 0, n - 1) for i, g in enumerate(V.sequence("groups", groups, n))]
    if len(grp) != n:
        raise ValueError(f"invalid groups: expected {n} values (one per actuator), got {len(grp)}")
    if sorted(set(grp)) != list(range(max(grp) + 1)):
        raise ValueError(f"invalid groups = {grp}: variables must be numbered 0..k-1 without gaps")
    return grp


def _inputs(groups: Sequence[int], z: Sequence[float]) -> list[float]:
    return [float(z[g]) for g in groups]


def brute_force_blocked_temperature(
    robot: Robot,
    point: Sequence[float],
    normal: Sequence[float],
    force: float,
    *,
    groups: Sequence[int] | None = None,
    xatol: float = 1e-6,
    steps: int = 100,
) -> BruteForceResult:
    """Temperature at which the loaded tip lies on a plane, by bounded Brent minimisation.

    The tip, loaded with ``-force * normal`` [N], must lie on the plane
    through ``point``: the gap [m] is minimised over the temperature range.
    The baseline of :func:`tcarod.blocked_temperature`.

    Parameters
    ----------
    robot : Robot
        The robot.
    point, normal : sequence of 3 float
        A point of the plane [m] and its normal [-], along which the tip presses.
    force : float
        Contact force [N].
    groups : sequence of int, optional
        One actuation variable for all actuators (default all in one).
    xatol, steps : optional
        Temperature tolerance [C] (default 1e-6); RK4 steps per solve (100).

    Returns
    -------
    BruteForceResult
        The temperature [C], the remaining gap [m] and the work.

    Raises
    ------
    ValueError
        More than one actuation variable, or arguments out of range.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> robot = fig6_square_robot()
    >>> from tcarod.models.bruteforce import brute_force_blocked_temperature
    >>> tip = robot.solve([25.0, 25.0], steps=20).tip_position            # blocked where it rests [m]
    >>> res = brute_force_blocked_temperature(robot, tip, [-1.0, 0.0, 0.0], 0.002, groups=[0, 0], steps=20)
    >>> round(res.variables[0], 1)         # [C] to press with 2 mN
    54.3
    """
    return _blocked_temperature(robot, point, normal, force, groups, xatol, steps)


def _blocked_temperature(
    robot: Robot,
    point: Sequence[float],
    normal: Sequence[float],
    force: float,
    groups: Sequence[int] | None,
    xatol: float,
    steps: int,
) -> BruteForceResult:
    """The body of :func:`brute_force_blocked_temperature`, its arguments as given."""
    minimize_scalar = require("scipy.optimize").minimize_scalar

    V.instance("robot", robot, Robot, "a tcarod.Robot")
    grp = _groups(robot, groups, [0] * len(robot.actuators))
    if max(grp) != 0:
        raise ValueError(f"invalid groups = {grp}: the blocked temperature has one variable (all groups 0)")
    n = np.asarray(V.vector("normal", normal, 3), dtype=np.float64)
    norm = float(np.linalg.norm(n))
    if not (math.isfinite(norm) and norm > 0.0):
        raise ValueError(f"invalid normal = {n.tolist()}: need a non-zero, finite vector")
    n = n / norm
    p0 = np.asarray(V.vector("point", point, 3, "m"), dtype=np.float64)
    force = V.real("force", force, unit="N")
    xatol = V.positive("xatol", xatol, "C")
    steps = V.integer("steps", steps, 1, 100_000)
    body = robot.body
    tip = np.asarray(body.tip_force, dtype=np.float64) - force * n
    loaded = Robot(body.replace(tip_force=[float(x) for x in tip]), robot.actuators)
    lo, hi = robot.actuators[0].input_bounds
    fwd = _Forward(loaded, steps)

    def gap(t: float) -> float:
        sol = fwd.solve(_inputs(grp, [t]))
        return abs(float(n @ (np.asarray(sol.tip_position) - p0)))

    res = minimize_scalar(gap, bounds=(lo, hi), method="bounded", options={"xatol": xatol})
    t = float(res.x)
    sol = loaded.solve(_inputs(grp, [t]), steps=steps)
    return BruteForceResult(
        variables=(t,),
        error_m=abs(float(n @ (np.asarray(sol.tip_position) - p0))),
        forward_solves=fwd.count + 1,
        solution=sol,
    )


def brute_force_tip_position(
    robot: Robot,
    target: Sequence[float],
    *,
    start: Sequence[float] | None = None,
    groups: Sequence[int] | None = None,
    xatol: float = 1e-4,
    fatol: float = 1e-10,
    simplex_size_c: float = 10.0,
    max_solves: int = 3000,
    steps: int = 100,
) -> BruteForceResult:
    """Temperatures that minimise the tip's distance to ``target``, by Nelder-Mead.

    Over full forward solves; the inputs are clipped to their range with a
    penalty of 1 mm per C outside it (a clipped simplex collapses on a bound
    and stalls). The baseline of :func:`tcarod.tip_position`.

    Parameters
    ----------
    robot : Robot
        The robot.
    target : sequence of 3 float
        Target tip position [m].
    start, groups : sequence, optional
        Initial variables [C] (default the reference inputs); the actuation
        variable of each actuator (default one each).
    xatol, fatol, simplex_size_c : float, optional
        Tolerances on the temperatures [C] (1e-4) and the distance [m]
        (1e-10); edge of the initial simplex [C] (10).
    max_solves, steps : int, optional
        Forward-solve budget (3000); RK4 steps per solve (100).

    Returns
    -------
    BruteForceResult
        The temperatures [C], the distance left [m] and the work.

    Raises
    ------
    ValueError
        Arguments out of range.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> robot = fig6_square_robot()
    >>> from tcarod.models.bruteforce import brute_force_tip_position
    >>> target = robot.solve([80.0, 80.0], steps=20).tip_position         # [m]
    >>> round(brute_force_tip_position(robot, target, groups=[0, 0], steps=20).variables[0], 2)   # [C]
    80.0
    """
    return _tip_position(robot, target, start, groups, xatol, fatol, simplex_size_c, max_solves, steps)


def _tip_position(
    robot: Robot,
    target: Sequence[float],
    start: Sequence[float] | None,
    groups: Sequence[int] | None,
    xatol: float,
    fatol: float,
    simplex_size_c: float,
    max_solves: int,
    steps: int,
) -> BruteForceResult:
    """The body of :func:`brute_force_tip_position`, its arguments as given."""
    minimize = require("scipy.optimize").minimize

    V.instance("robot", robot, Robot, "a tcarod.Robot")
    grp = _groups(robot, groups, list(range(len(robot.actuators))))
    nz = max(grp) + 1
    refs = robot.reference_inputs
    x0 = np.asarray(
        V.vector("start", start, nz) if start is not None else [refs[grp.index(k)] for k in range(nz)], dtype=np.float64
    )
    target = V.vector("target", target, 3, "m")
    xatol = V.positive("xatol", xatol, "C")
    fatol = V.positive("fatol", fatol, "m")
    simplex_size_c = V.positive("simplex_size_c", simplex_size_c, "C")
    max_solves = V.integer("max_solves", max_solves, 1, 100_000)
    steps = V.integer("steps", steps, 1, 100_000)
    bounds = [robot.actuators[grp.index(k)].input_bounds for k in range(nz)]
    lo = np.array([b[0] for b in bounds])
    hi = np.array([b[1] for b in bounds])
    tgt = np.asarray(target, dtype=np.float64)
    fwd = _Forward(robot, steps)

    def distance(z: npt.NDArray[np.float64]) -> float:
        zc = np.clip(z, lo, hi)
        sol = fwd.solve(_inputs(grp, [float(v) for v in zc]))
        return float(np.linalg.norm(np.asarray(sol.tip_position) - tgt)) + 1e-3 * float(np.linalg.norm(z - zc))

    simplex = [x0] + [
        x0 + simplex_size_c * np.eye(nz)[k] * (1.0 if x0[k] + simplex_size_c <= hi[k] else -1.0) for k in range(nz)
    ]
    res = minimize(
        distance,
        x0,
        method="Nelder-Mead",
        options={"xatol": xatol, "fatol": fatol, "maxfev": max_solves, "initial_simplex": np.asarray(simplex)},
    )
    z = tuple(float(v) for v in np.clip(res.x, lo, hi))
    sol = robot.solve(_inputs(grp, z), steps=steps)
    return BruteForceResult(
        variables=z,
        error_m=float(np.linalg.norm(np.asarray(sol.tip_position) - tgt)),
        forward_solves=fwd.count + 1,
        solution=sol,
    )
