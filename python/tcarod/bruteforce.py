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

scipy is needed (``pip install 'tcarod[test]'``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np
import numpy.typing as npt

from ._optional import require
from .rod import Robot, Solution

__all__ = ["BruteForceResult", "brute_force_blocked_temperature", "brute_force_tip_position"]


@dataclass(frozen=True, eq=False)
class BruteForceResult:
    """Outcome of a brute-force inverse."""

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
        sol = self.robot.solve(inputs, steps=self.steps, warm_start=self.warm)
        self.warm = sol
        self.count += 1
        return sol


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
    """Temperature [C] (one actuation variable) at which the tip, loaded with
    ``-force * normal`` [N], lies on the plane through ``point`` [m] with unit
    ``normal``: bounded Brent minimisation of the gap [m] over the
    temperature range, to ``xatol`` [C]."""
    require("scipy")  # optional: the `fit` extra
    from scipy.optimize import minimize_scalar

    grp = list(groups) if groups is not None else [0] * len(robot.actuators)
    n = np.asarray(normal, dtype=np.float64)
    n = n / np.linalg.norm(n)
    p0 = np.asarray(point, dtype=np.float64)
    body = robot.body
    tip = np.asarray(body.tip_force, dtype=np.float64) - float(force) * n
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
    """Temperatures [C] minimising ``|p(L) - target|`` [m]: Nelder-Mead over
    full forward solves, from ``start`` (default: the reference inputs) with
    an initial simplex of edge ``simplex_size_c`` [C], to ``xatol`` [C] and
    ``fatol`` [m].

    Bounds: the forward model is evaluated at the inputs clipped to their
    range, plus a penalty of 1 mm per C outside it (scipy's bounded
    Nelder-Mead clips the simplex itself, which collapses it on a bound and
    stalls, e.g. when starting at ambient temperature)."""
    require("scipy")  # optional: the `fit` extra
    from scipy.optimize import minimize

    grp = list(groups) if groups is not None else list(range(len(robot.actuators)))
    nz = max(grp) + 1
    refs = robot.reference_inputs
    x0 = np.asarray(start if start is not None else [refs[grp.index(k)] for k in range(nz)], dtype=np.float64)
    bounds = [robot.actuators[grp.index(k)].input_bounds for k in range(nz)]
    lo = np.array([b[0] for b in bounds])
    hi = np.array([b[1] for b in bounds])
    tgt = np.asarray(target, dtype=np.float64)
    fwd = _Forward(robot, steps)

    def distance(z: npt.NDArray[np.float64]) -> float:
        zc = np.clip(z, lo, hi)
        sol = fwd.solve(_inputs(grp, [float(v) for v in zc]))
        return float(np.linalg.norm(np.asarray(sol.tip_position) - tgt)) + 1e-3 * float(np.linalg.norm(z - zc))

    simplex = [x0] + [x0 + simplex_size_c * np.eye(nz)[k] * (1.0 if x0[k] + simplex_size_c <= hi[k] else -1.0) for k in range(nz)]
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
