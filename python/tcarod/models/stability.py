"""Elastic stability of equilibria and branch following (beyond the paper).

* :func:`stability` -- the verdict of one equilibrium: Till and Rucker's
  conjugate-point test (IEEE T-RO 2017) extended to embedded actuators whose
  tension depends on strain, dead loads and a blocked tip (see
  ``docs/stability.md``). ``margin`` is the smallest eigenvalue of the
  dimensionless tip stiffness: > 0 iff stable.
* :func:`follow_branch` -- pseudo-arclength continuation in one scalar
  parameter (the actuators' input, a gravity scale or a tip-load scale)
  through folds, with the stability of each point and the located folds and
  bifurcations; ``stable_only=True`` sweeps like a physical robot, staying on
  stable equilibria and recording where it jumps.
* :func:`plot_branch` -- a tip coordinate against the parameter, stable parts
  solid, unstable dashed (needs the ``plot`` extra).

Every solve carries the verdict: ``Robot.solve(..., stability=...)`` and
``Robot.sweep`` take a policy, ``"report"`` (default: the verdict is part of
the solve; an unstable equilibrium warns :class:`UnstableEquilibriumWarning`),
``"require"`` (raise :class:`UnstableEquilibriumError`), ``"continue"`` (move
to a stable equilibrium at the same inputs; ``Solution.continued`` is the
:class:`Continuation`) or ``"off"`` (hot loops). Blocked-tip solutions carry
the verdict with the tip held.

Units: SI (m, N); temperatures in degrees C; scales dimensionless.
"""

from __future__ import annotations

from typing import Any, Literal, Sequence

from .. import _core
from .._optional import require

Stability = _core.Stability
Branch = _core.Branch
Continuation = _core.Continuation
UnstableEquilibriumWarning = _core.UnstableEquilibriumWarning
UnstableEquilibriumError = _core.UnstableEquilibriumError

__all__ = [
    "POLICIES",
    "Branch",
    "Continuation",
    "Stability",
    "UnstableEquilibriumError",
    "UnstableEquilibriumWarning",
    "follow_branch",
    "plot_branch",
    "stability",
]

Parameter = Literal["inputs", "gravity_scale", "tip_load_scale"]
#: The ``stability=`` policies of ``Robot.solve`` and ``Robot.sweep``, default first.
POLICIES: tuple[str, ...] = ("report", "require", "continue", "off")


def stability(
    robot: _core.Robot, solution: _core.Solution, *, blocked: Sequence[Sequence[float]] | None = None
) -> Stability:
    """Stability verdict of ``solution``, an equilibrium of ``robot``.

    Till and Rucker's conjugate-point test extended to the actuators, dead
    loads and a blocked tip: one tangent integration.

    Parameters
    ----------
    robot : Robot
        The robot solved.
    solution : Solution
        One of ``robot``'s equilibria.
    blocked : sequence of (3,) sequences of float, optional
        World directions [-] along which the tip translation is held (e.g.
        the block normal of a blocked-tip solution); default none.

    Returns
    -------
    Stability
        ``stable``, ``margin`` [-], ``conjugate_point`` [m] or None, and the
        profiles ``s`` [m], ``determinant`` [-] and ``min_stiffness`` [-].

    Raises
    ------
    ValueError
        ``solution`` is not an equilibrium of ``robot``.

    Examples
    --------
    >>> from tcarod.paper.buckling import column_robot
    >>> from tcarod.models.stability import stability
    >>> column = column_robot()                     # 50 mm soft column, upright under 1 g
    >>> verdict = stability(column, column.solve([], steps=20, stability="off"))
    >>> verdict.stable, round(verdict.margin, 2)    # [-]
    (True, 0.33)
    """
    return _core.stability(robot, solution, blocked=None if blocked is None else [list(b) for b in blocked])


def follow_branch(
    robot: _core.Robot,
    parameter: Parameter,
    start: float,
    end: float,
    *,
    actuators: Sequence[int] | None = None,
    inputs: Sequence[float] | None = None,
    warm_start: _core.Solution | None = None,
    stable_only: bool = False,
    step: float = 0.02,
    max_step: float = 0.1,
    max_points: int = 500,
    steps: int = 100,
    tol: float = 1e-10,
    max_iter: int = 50,
) -> Branch:
    """Follow the equilibria of ``robot`` as ``parameter`` goes from ``start`` to ``end``.

    Pseudo-arclength continuation through folds, with each point's stability:
    the solver's own continuation on multiple shooting (``docs/solver.md``),
    so heavy soft bodies are followed like light ones.

    Parameters
    ----------
    robot : Robot
        The robot.
    parameter : {"inputs", "gravity_scale", "tip_load_scale"}
        ``"inputs"`` drives the inputs of ``actuators`` together (temperature
        [C] for TCAs); ``"gravity_scale"`` [-] multiplies the body's gravity
        vector, ``"tip_load_scale"`` [-] its tip force and moment.
    start, end : float
        The parameter's range (its unit).
    actuators, inputs : sequence, optional
        The actuators driven by ``"inputs"`` (default all); the other
        actuators' inputs (default the reference inputs).
    warm_start : Solution, optional
        An equilibrium at ``start`` to begin on (one of coexisting shapes).
    stable_only : bool, optional
        Sweep like a physical robot: leave a branch where it loses stability
        or folds back for the nearest stable equilibrium (``Branch.jumps``).
    step, max_step, max_points : optional
        First and largest arclength step in units of ``|end - start|``
        (0.02, 0.1) and the point budget (500).
    steps, tol, max_iter : optional
        RK4 steps (100), Newton tolerance on the dimensionless residual
        (1e-10) and iterations of each point's corrector (50, of which at
        most 8 are used), as for ``Robot.solve``.

    Returns
    -------
    Branch
        The points (tip [m], stability, margin [-]), folds, bifurcations, jumps.

    Raises
    ------
    ValueError
        An argument outside its range (named, with its unit).

    Examples
    --------
    >>> from tcarod.paper.buckling import column_robot
    >>> from tcarod.models.stability import follow_branch
    >>> sweep = follow_branch(column_robot(), "gravity_scale", 0.0, 3.0, steps=20, stable_only=True)
    >>> [round(p, 2) for p, before, after in sweep.jumps], bool(sweep.stable.all())   # buckles at 1.54 g
    ([1.54], True)
    """
    return _core.follow_branch(
        robot,
        parameter=parameter,
        start=start,
        end=end,
        actuators=None if actuators is None else list(actuators),
        inputs=None if inputs is None else list(inputs),
        step=step,
        max_step=max_step,
        max_points=max_points,
        stable_only=stable_only,
        warm_start=warm_start,
        steps=steps,
        tol=tol,
        max_iter=max_iter,
    )


def plot_branch(
    branch: Branch,
    *,
    component: int = 2,
    ax: Any = None,
    label: str | None = None,
    color: str | None = None,
    scale: float = 1e3,
) -> Any:
    """Plot a tip coordinate against the branch's parameter.

    Stable runs solid, unstable dashed, folds as circles, bifurcations as
    crosses, jumps as dotted arrows (the ``plot`` extra).

    Parameters
    ----------
    branch : Branch
        From :func:`follow_branch`.
    component : {0, 1, 2}, optional
        Tip coordinate: 0 x, 1 y, 2 z (default).
    ax : matplotlib.axes.Axes, optional
        Axes to draw into (default: a new figure's).
    label, color : str, optional
        Legend label and line colour.
    scale : float, optional
        Factor on the coordinate (default 1e3: mm).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn into.

    Raises
    ------
    ValueError
        ``component`` other than 0, 1 or 2.

    Examples
    --------
    >>> from tcarod.paper.buckling import column_robot
    >>> from tcarod.models.stability import follow_branch, plot_branch
    >>> branch = follow_branch(column_robot(), "gravity_scale", 0.0, 3.0, steps=20)
    >>> ax = plot_branch(branch, component=2, label="tip z")
    >>> ax.get_legend_handles_labels()[1]
    ['tip z']
    """
    if component not in (0, 1, 2):
        raise ValueError(f"component must be 0, 1 or 2, got {component!r}")
    plt = require("matplotlib.pyplot")
    if ax is None:
        _, ax = plt.subplots(figsize=(6.0, 4.0))
    lam = branch.parameter
    y = branch.tip_positions[:, component] * scale
    stable = branch.stable
    first = True
    i = 0
    while i < len(lam):
        j = i
        while j + 1 < len(lam) and stable[j + 1] == stable[i]:
            j += 1
        hi = min(j + 2, len(lam))  # join to the next run
        (line,) = ax.plot(lam[i:hi], y[i:hi], "-" if stable[i] else "--", color=color, label=label if first else None)
        color = line.get_color()
        first = False
        i = j + 1
    for kind, par, tip in branch.events:
        ax.plot([par], [tip[component] * scale], "o" if kind == "fold" else "x", color=color, mfc="none")
    for par, before, after in branch.jumps:
        y0 = before.positions[-1][component] * scale
        y1 = after.positions[-1][component] * scale
        ax.annotate(
            "", xy=(par, y1), xytext=(par, y0), arrowprops={"arrowstyle": "->", "linestyle": ":", "color": color}
        )
    return ax
