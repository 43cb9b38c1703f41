"""Workspace maps: the tip positions a robot reaches over a grid of actuator
inputs (temperatures [C] for TCAs), as arrays and as a 3-D scatter plot.

The solves go through one function, :func:`solve_rows`, which walks the grid
with :meth:`Robot.sweep` (each solve warm-started from the previous one, rows
ordered as a snake so that neighbours differ in one input) and, if the sweep
stops, solves the points one at a time (warm-started from the last success,
else cold).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any, Sequence

import numpy as np
import numpy.typing as npt

from .. import _validate as V
from .._core import ConvergenceError

__all__ = ["Workspace", "snake_grid", "solve_rows", "workspace_map"]

FloatArray = npt.NDArray[np.float64]


def snake_grid(levels: Sequence[Sequence[float]]) -> FloatArray:
    """All combinations of the input levels, in boustrophedon order.

    Consecutive rows differ in one input by one level, which keeps warm
    starts close.

    Parameters
    ----------
    levels : sequence of sequences of float
        ``levels[i]``: the values of input ``i`` (temperature [C] for a TCA).

    Returns
    -------
    numpy.ndarray
        Shape ``(prod(len(levels[i])), len(levels))``.

    Raises
    ------
    ValueError
        More than ``MAX_GRID_POINTS`` (100,000) rows.

    Examples
    --------
    >>> from tcarod.models.workspace import snake_grid
    >>> snake_grid([[25.0, 60.0], [25.0, 60.0, 100.0]]).tolist()
    [[25.0, 25.0], [25.0, 60.0], [25.0, 100.0], [60.0, 100.0], [60.0, 60.0], [60.0, 25.0]]
    """
    lists = [V.real_array(f"levels[{i}]", lv, ndim=1).tolist() for i, lv in enumerate(V.sequence("levels", levels, 64))]
    total = 1
    for lv in lists:
        total *= len(lv)
        if total > V.MAX_GRID_POINTS:
            raise ValueError(f"invalid levels: more than {V.MAX_GRID_POINTS} grid points")
    rows: list[list[float]] = [[]]
    for lv in lists:
        new: list[list[float]] = []
        for k, r in enumerate(rows):
            seq = list(lv) if k % 2 == 0 else list(lv)[::-1]
            new.extend(r + [float(x)] for x in seq)
        rows = new
    return np.asarray(rows, dtype=np.float64)


def solve_rows(robot: Any, inputs: FloatArray, steps: int = 100) -> list[Any | None]:
    """Forward solutions for each row of ``inputs``, ``None`` where a solve fails.

    The one place the workspace's solves happen: a warm-started
    :meth:`Robot.sweep` over all rows; if it raises, the rows are solved one
    by one, warm-started where possible. No stability verdict (tip positions
    only).

    Parameters
    ----------
    robot : Robot
        The robot.
    inputs : numpy.ndarray
        ``(n, n_actuators)`` inputs (temperature [C] for TCAs); at most
        100,000 rows.
    steps : int, optional
        RK4 steps per solve (default 100).

    Returns
    -------
    list of Solution or None
        One per row.

    Raises
    ------
    ValueError
        Too many rows, or rows of the wrong width.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> from tcarod.models.workspace import solve_rows
    >>> sols = solve_rows(fig6_square_robot(), np.array([[25.0, 25.0], [100.0, 100.0]]), steps=20)
    >>> tuple(round(float(s.tip_position[0]) * 1e3, 1) for s in sols)      # tip x [mm]
    (-0.9, -6.1)
    """
    _check_robot(robot)
    steps = V.integer("steps", steps, 1, 100_000)
    arr = V.real_array("inputs", inputs, ndim=2, max_size=V.MAX_GRID_POINTS * 64)
    if arr.shape[0] > V.MAX_GRID_POINTS:
        raise ValueError(f"invalid inputs: {arr.shape[0]} rows, at most {V.MAX_GRID_POINTS} allowed")
    rows = [list(map(float, r)) for r in arr]
    try:
        # tip positions only: no stability verdict (it would double the cost)
        return list(robot.sweep(rows, steps=steps, stability="off"))
    except (ValueError, ConvergenceError):
        pass
    out: list[Any | None] = []
    warm = None
    for r in rows:
        try:
            sol = robot.solve(r, steps=steps, warm_start=warm, stability="off")
        except ConvergenceError:
            try:
                sol = robot.solve(r, steps=steps, stability="off")
            except ConvergenceError:
                out.append(None)
                continue
        out.append(sol)
        warm = sol
    return out


@dataclass(frozen=True, eq=False)
class Workspace:
    """Tip positions of a robot over a grid of inputs.

    Made by :func:`workspace_map`.

    Attributes
    ----------
    grid_c : numpy.ndarray
        The values each input takes [C for TCAs].
    temperatures_c : numpy.ndarray
        One row of inputs per point, shape ``(n, n_inputs)`` [C for TCAs].
    tip_positions_m : numpy.ndarray
        Shape ``(n, 3)`` [m], NaN where the solve failed.
    tip_tangents : numpy.ndarray
        Unit tip tangent (third column of the tip rotation), shape ``(n, 3)``.
    elapsed_s : float
        Wall time of the solves [s].

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> from tcarod.models.workspace import workspace_map
    >>> ws = workspace_map(fig6_square_robot(), [25.0, 100.0], steps=20)
    >>> ws.temperatures_c.shape, ws.n_failed
    ((4, 2), 0)
    """

    grid_c: FloatArray
    temperatures_c: FloatArray
    tip_positions_m: FloatArray
    tip_tangents: FloatArray
    elapsed_s: float

    @property
    def n_failed(self) -> int:
        """Points whose solve failed.

        Returns
        -------
        int
            Rows of ``tip_positions_m`` that are NaN [-].
        """
        return int(np.sum(~np.all(np.isfinite(self.tip_positions_m), axis=1)))

    @property
    def bending_angle_rad(self) -> FloatArray:
        """Angle between the tip tangent and the base tangent ``+z`` [rad].

        Returns
        -------
        numpy.ndarray
            Shape ``(n,)`` [rad].
        """
        return np.asarray(np.arccos(np.clip(self.tip_tangents[:, 2], -1.0, 1.0)), dtype=np.float64)


#: Most RK4 steps per solve of a workspace map: a map needs tip positions, and
#: 10 steps already put the Fig. 6 tip within 1 um of a 5,000-step reference.
MAX_MAP_STEPS = 1000


def workspace_map(robot: Any, grid_c: Sequence[float] | FloatArray, steps: int = 100) -> Workspace:
    """Tip positions of ``robot`` over the ``k^n`` grid of inputs.

    Each input takes every value of ``grid_c`` (``n`` = number of actuators).

    Parameters
    ----------
    robot : Robot
        The robot.
    grid_c : sequence of float
        The ``k`` values of each input [C for TCAs].
    steps : int, optional
        RK4 steps per solve, at most ``MAX_MAP_STEPS`` (1,000; default 100).

    Returns
    -------
    Workspace
        The tips [m], tangents and bending angles [rad] of the grid.

    Raises
    ------
    ValueError
        More than 100,000 points, more than 1,000 steps, or more than
        10,000,000 RK4 steps over the whole map.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> from tcarod.models.workspace import workspace_map
    >>> ws = workspace_map(fig6_square_robot(), [25.0, 60.0, 100.0], steps=20)
    >>> round(float(np.degrees(ws.bending_angle_rad.max())), 1)     # [deg] at 100 C
    16.1
    """
    _check_robot(robot)
    grid = V.real_array("grid_c", grid_c, ndim=1, unit="C")
    if grid.size == 0:
        raise ValueError("invalid grid_c: need at least one value [C]")
    steps = V.integer("steps", steps, 1, MAX_MAP_STEPS)
    n = len(robot.actuators)
    if float(grid.size) ** n > V.MAX_GRID_POINTS:
        raise ValueError(f"invalid grid_c: {grid.size}^{n} grid points, at most {V.MAX_GRID_POINTS} allowed")
    if float(grid.size) ** n * steps > V.MAX_RK4_STEPS:
        raise ValueError(
            f"invalid steps = {steps}: {grid.size}^{n} points x {steps} steps exceeds {V.MAX_RK4_STEPS} RK4 steps per map"
        )
    inputs = snake_grid([[float(x) for x in grid]] * n)
    t0 = time.perf_counter()
    sols = solve_rows(robot, inputs, steps=steps)
    elapsed = time.perf_counter() - t0
    tips = np.full((len(sols), 3), np.nan)
    tangents = np.full((len(sols), 3), np.nan)
    for k, s in enumerate(sols):
        if s is not None:
            tips[k] = np.asarray(s.tip_position, dtype=np.float64)
            tangents[k] = np.asarray(s.tip_rotation, dtype=np.float64)[:, 2]
    return Workspace(grid, inputs, tips, tangents, elapsed)


def _check_robot(robot: Any) -> None:
    from ..rod import Robot

    V.instance("robot", robot, Robot, "a tcarod.Robot")
