"""Stability and branch following of ``tcarod._core`` (src/python/stability/)."""

from collections.abc import Sequence
from typing import Any, final

import numpy as np
import numpy.typing as npt

from ._common import _FloatArray
from ._rod import Robot
from ._solution import Solution

# --- stability and branch following (src/python/stability/; see tcarod.models.stability) ---

class UnstableEquilibriumWarning(UserWarning):
    """A solve handed back an unstable equilibrium (`stability='report'`, the default): a shape the physical robot cannot hold. Its `Solution.stable` is False; ask for `stability='continue'` to move to a stable one."""

@final
class Continuation:
    """How ``stability="continue"`` reached the stable equilibrium it handed back.

    ``Solution.continued``: the unstable equilibrium Newton found first, its
    margin, the route taken and the work.

    Examples
    --------
    >>> from tcarod import Body, Robot, Section
    >>> heavy = Robot(Body(0.05, Section.rectangle(0.01, 0.009), 37.8e3, density=3120.0,
    ...                    gravity=(0.0, 0.0, -9.81)), [])     # past self-weight buckling
    >>> sol = heavy.solve([], steps=20, stability="continue")
    >>> sol.stable, sol.continued.margin < 0, sol.continued.unstable.stable
    (True, True, False)
    """

    @property
    def route(self) -> str: ...
    @property
    def unstable(self) -> Solution: ...
    @property
    def margin(self) -> float:
        """Stability margin of the unstable equilibrium [-].

        Returns
        -------
        float
            ``< 0``.
        """
    @property
    def candidates(self) -> int: ...
    @property
    def evaluations(self) -> int: ...
    def __eq__(self, value: object, /) -> bool: ...

@final
class Stability:
    """Stability verdict of one equilibrium (see ``tcarod.models.stability``).

    Till and Rucker's conjugate-point test (IEEE T-RO 2017) extended to
    embedded actuators, dead loads and a blocked tip: one tangent integration
    along the body. Built by ``tcarod.models.stability.stability``; a solve's
    own verdict is ``Solution.stable`` and ``Solution.stability_margin``.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> from tcarod.models.stability import stability
    >>> robot = fig6_square_robot()
    >>> verdict = stability(robot, robot.solve([60.0, 25.0], steps=20))
    >>> verdict.stable, verdict.margin > 0, verdict.conjugate_point
    (True, True, None)
    """

    @property
    def stable(self) -> bool: ...
    @property
    def margin(self) -> float:
        """Stability margin [-].

        Returns
        -------
        float
            Smallest eigenvalue of the dimensionless tip stiffness [-]: ``> 0``
            if and only if stable.
        """
    @property
    def conjugate_point(self) -> float | None:
        """Arc length [m] of the first conjugate point, if there is one.

        Returns
        -------
        float or None
            Where ``determinant`` first changes sign [m]; ``None`` if it does not.
        """
    @property
    def s(self) -> _FloatArray: ...
    @property
    def determinant(self) -> _FloatArray:
        """Till and Rucker's determinant ``det(Y(s) Y(0)^-1)`` at the nodes [-].

        Returns
        -------
        numpy.ndarray
            Shape ``(n,)`` [-]; a sign change marks a conjugate point.
        """
    @property
    def min_stiffness(self) -> _FloatArray: ...
    @property
    def mode(self) -> _FloatArray:
        """Softest tip mode ``(dp / L, dtheta)`` [-, rad], world frame.

        Returns
        -------
        numpy.ndarray
            Shape ``(6,)``: tip translation over body length, then rotation.
        """
    @property
    def evaluations(self) -> int: ...
    def __reduce__(self) -> tuple[Any, ...]: ...
    def __eq__(self, value: object, /) -> bool: ...

@final
class Branch:
    """A followed branch of equilibria, or a stable sweep.

    Arrays over its ``k`` points (``parameter``, ``tip_positions`` [m],
    ``stable``, ``margin`` [-]), the located folds and bifurcations and, for a
    stable sweep, the jumps. Built by ``tcarod.models.stability.follow_branch``;
    ``len(branch)`` is ``k``.

    Examples
    --------
    >>> from tcarod.paper.buckling import column_robot
    >>> from tcarod.models.stability import follow_branch
    >>> column = column_robot()          # a soft column, 50 mm, standing up under 1 g
    >>> branch = follow_branch(column, "gravity_scale", 0.0, 3.0, steps=20)
    >>> bool(branch.stable[0]), bool(branch.stable[-1])    # straight: stable, then not
    (True, False)
    >>> round(float(branch.bifurcations[0]), 2)          # buckles at 1.54 g
    1.54
    """

    @property
    def parameter(self) -> _FloatArray: ...
    @property
    def tip_positions(self) -> _FloatArray:
        """Tip position of each point [m].

        Returns
        -------
        numpy.ndarray
            Shape ``(k, 3)`` [m], world frame.
        """
    @property
    def stable(self) -> npt.NDArray[np.bool_]: ...
    @property
    def margin(self) -> _FloatArray: ...
    @property
    def solutions(self) -> list[Solution]: ...
    @property
    def events(self) -> list[tuple[str, float, _FloatArray]]:
        """Located events along the branch.

        Returns
        -------
        list of tuple
            ``(kind, parameter, tip position (3,) [m])``, ``kind`` ``"fold"`` or
            ``"bifurcation"``.
        """
    @property
    def folds(self) -> _FloatArray: ...
    @property
    def bifurcations(self) -> _FloatArray: ...
    @property
    def jumps(self) -> list[tuple[float, Solution, Solution]]:
        """Jumps of a stable sweep.

        Returns
        -------
        list of tuple
            ``(parameter, before, after)``: the last stable solution before the
            robot jumps and the stable one it lands on (empty for a branch).
        """
    @property
    def evaluations(self) -> int: ...
    def __len__(self) -> int: ...
    def __reduce__(self) -> tuple[Any, ...]: ...
    def __eq__(self, value: object, /) -> bool: ...

def _restore_stability(
    stable: bool,
    margin: float,
    conjugate_point: float | None,
    s: Sequence[float],
    determinant: Sequence[float],
    min_stiffness: Sequence[float],
    evaluations: int,
    mode: Sequence[float],
) -> Stability: ...
def _restore_branch(
    points: Sequence[tuple[float, Sequence[float], bool, float]],
    solutions: Sequence[Solution],
    events: Sequence[tuple[str, float, Sequence[float]]],
    jumps: Sequence[tuple[float, Solution, Solution]],
    evaluations: int,
) -> Branch: ...
def stability(robot: Robot, solution: Solution, *, blocked: Sequence[Sequence[float]] | None = None) -> Stability:
    """Stability verdict of ``solution``, an equilibrium of ``robot``.

    The public form is ``tcarod.models.stability.stability``.

    Parameters
    ----------
    robot : Robot
        The robot solved.
    solution : Solution
        One of ``robot``'s equilibria.
    blocked : sequence of (3,) sequences of float, optional
        World directions [-] along which the tip translation is held (a
        blocked-tip solution's block normal); default none.

    Returns
    -------
    Stability
        The verdict, its margin [-] and the profiles along the body.

    Raises
    ------
    ValueError
        ``solution`` is not an equilibrium of ``robot``.

    Examples
    --------
    >>> from tcarod import _core
    >>> from tcarod.batch import fig6_square_robot
    >>> robot = fig6_square_robot()
    >>> _core.stability(robot, robot.solve([60.0, 25.0], steps=20, stability="off")).stable
    True
    """

def follow_branch(
    robot: Robot,
    *,
    parameter: str,
    start: float,
    end: float,
    actuators: Sequence[int] | None = None,
    inputs: float | Sequence[float] | None = None,
    step: float = 0.02,
    max_step: float = 0.1,
    max_points: int = 500,
    stable_only: bool = False,
    warm_start: Solution | None = None,
    steps: int = 100,
    tol: float = 1e-10,
    max_iter: int = 50,
) -> Branch:
    """Follow the equilibria of ``robot`` in one scalar parameter.

    Pseudo-arclength continuation from ``start`` to ``end`` through folds,
    with the stability of every point; the public form is
    ``tcarod.models.stability.follow_branch``.

    Parameters
    ----------
    robot : Robot
        The robot.
    parameter : {"inputs", "gravity_scale", "tip_load_scale"}
        ``"inputs"``: the inputs of ``actuators`` (a temperature [C], tension
        [N] or pull [m]); ``"gravity_scale"`` and ``"tip_load_scale"`` [-]
        multiply the body's gravity and its tip load.
    start, end : float
        The parameter's range.
    actuators : sequence of int, optional
        The actuators driven by ``"inputs"`` (default all).
    inputs : sequence of float, optional
        The other actuators' inputs (default the reference inputs).
    step, max_step : float, optional
        First and largest arclength step, in units of ``|end - start|``
        (defaults 0.02 and 0.1).
    max_points : int, optional
        Point budget (default 500).
    stable_only : bool, optional
        Sweep mode: stay on stable equilibria and record the jumps.
    warm_start : Solution, optional
        An equilibrium at ``start`` to begin on (one of coexisting shapes).
    steps : int, optional
        RK4 steps over the body (default 100).
    tol : float, optional
        Newton tolerance on the dimensionless residual (default 1e-10).
    max_iter : int, optional
        Newton iterations per point (default 50).

    Returns
    -------
    Branch
        The points, events and jumps.

    Raises
    ------
    ValueError
        An argument outside its range (named, with its unit).

    Examples
    --------
    >>> from tcarod import _core
    >>> from tcarod.paper.buckling import column_robot
    >>> branch = _core.follow_branch(column_robot(), parameter="gravity_scale", start=0.0, end=3.0, steps=20)
    >>> round(float(branch.bifurcations[0]), 2)       # gravity scale [-] where the column buckles
    1.54
    """
