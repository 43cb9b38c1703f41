"""Inverse kinetostatics of ``tcarod._core`` (src/python/inverse.rs)."""

from collections.abc import Mapping, Sequence
from typing import Any, Literal, final, type_check_only

import numpy as np
import numpy.typing as npt

from ._common import _FloatArray
from ._rod import Robot
from ._solution import Solution

# ---------------------------------------------------------------------------
# Inverse kinetostatics (src/python/inverse.rs; paper Section IV, eqs 34-43).
# `Robot` and `Solution` are the rod classes of _rod.pyi / _solution.pyi. Tip poses are
# `[dp (m); dtheta (rad)]` in the world frame; tip wrenches `[F (N); M (N m)]`.
# `groups[i]` is the actuation variable driving actuator `i` (the two legs of
# a U-shaped TCA share one temperature: `groups=[0, 0]`), `None` for an
# actuator in `fixed_inputs` (`{actuator index: input}`, held at that input,
# no variable); `groups` has one entry per actuator or one per actuator not in
# `fixed_inputs`; default: one variable per actuator not in `fixed_inputs`.
# ---------------------------------------------------------------------------

@type_check_only
class _Outcome:
    """What both results share at run time: the SciPy-style status fields
    (``scipy_fields!``), the tip of ``solution`` (``tip_of_solution!``; both
    in src/python/outcome.rs), pickling and equality. Stub-only."""

    @property
    def success(self) -> bool: ...
    @property
    def status(self) -> int: ...
    @property
    def message(self) -> str: ...
    @property
    def nit(self) -> int: ...
    @property
    def nfev(self) -> int: ...
    @property
    def tip_position(self) -> _FloatArray:
        """Tip position [m] of ``solution``, shape ``(3,)``."""
    def __reduce__(self) -> tuple[Any, ...]: ...
    def __eq__(self, value: object, /) -> bool: ...

@final
class InverseResult(_Outcome):
    """Result of :func:`tip_position`: the final (or closest reachable) configuration."""

    @property
    def solution(self) -> Solution:
        """Forward solution at :attr:`variables`."""
    @property
    def variables(self) -> list[float]:
        """Actuation variables (temperatures [C] for TCAs), one per group."""
    @property
    def error(self) -> float:
        """Remaining tip error [m] (plus weighted angle if an orientation was asked)."""
    @property
    def iterations(self) -> int:
        """Jacobian evaluations (outer iterations)."""
    @property
    def reached(self) -> bool:
        """Whether the target was reached to ``tol``."""
    @property
    def at_bound(self) -> list[bool]:
        """Per variable: resting on a bound of its input range at the end."""
    @property
    def evaluations(self) -> int:
        """IVPs integrated in total."""
    @property
    def max_iter(self) -> int:
        """The iteration budget of the solve."""
    @property
    def status(self) -> int:
        """0 reached, 1 unreachable (at the bounds), 2 out of budget (the error
        still decreasing), 3 stalled (no descent left, no variable at a bound:
        e.g. a target off the plane of a planar robot)."""

@final
class BlockedResult(_Outcome):
    """A blocked-tip solution: contact ``force`` [N] at actuation ``variables``."""

    @property
    def solution(self) -> Solution:
        """Forward solution with the contact force applied at the tip."""
    @property
    def force(self) -> float:
        """Contact force [N] with which the tip presses along the block normal."""
    @property
    def variables(self) -> list[float]:
        """Actuation variables (temperatures [C] for TCAs)."""
    @property
    def iterations(self) -> int:
        """Increments (incremental method) or Newton iterations (direct solves)."""
    @property
    def evaluations(self) -> int:
        """IVPs integrated."""

def sensitivities(
    solution: Solution,
    groups: Sequence[int | None] | npt.NDArray[np.integer] | None = None,
    scheme: Literal["forward", "central", "exact"] = "forward",
    fixed_inputs: Mapping[int, float] | None = None,
) -> tuple[_FloatArray, _FloatArray]:
    """The actuation Jacobian and the compliance ``(J, C)`` at ``solution`` (eqs 41-42).

    ``J`` is ``6 x n_vars`` [m or rad per C], ``C`` is ``6 x 6`` [m or rad per N or N m]."""

def tip_position(
    robot: Robot,
    target: Sequence[float] | _FloatArray,
    *,
    start: Sequence[float] | _FloatArray | None = None,
    groups: Sequence[int | None] | npt.NDArray[np.integer] | None = None,
    fixed_inputs: Mapping[int, float] | None = None,
    target_rotation: Sequence[Sequence[float]] | _FloatArray | None = None,
    orientation_weight: float = 0.01,
    tol: float = 1e-7,
    max_iter: int = 50,
    damping: float = 1e-6,
    steps: int = 100,
) -> InverseResult:
    """Actuation variables (temperatures [C]) that put the tip at ``target`` [m].

    Iterates the paper's local inverse: at each iterate, ``J`` (exact, one
    tangent IVP), a damped least-squares step
    ``dz = (J^T J + damping^2 I)^-1 J^T dx`` with variables frozen at a bound
    they would cross, a backtracking line search on the tip error, one BVP
    solve per trial. ``start``: initial variables (default: the reference
    inputs, ambient temperature). With ``target_rotation`` (a 3x3 rotation
    matrix) the orientation is matched too, angles weighted by
    ``orientation_weight`` [m/rad]. ``tol`` [m]; ``max_iter`` iterations (1 to
    100,000); ``damping`` [m per unit variable]; ``steps`` RK4 steps per
    forward solve (1 to 100,000); target coordinates within 1000 body lengths.

    An unreachable target is not an error: the result has ``reached=False``
    (``success=False``), the closest configuration found, its ``error`` [m]
    and which variables rest on a bound (``at_bound``). ``status`` tells why
    it stopped, as in SciPy: 0 reached; 1 unreachable (no descent left with a
    variable on its temperature bound: the closest point within the range);
    2 out of budget (``max_iter`` used up: continue with
    ``start=result.variables``); 3 stalled (no descent, no bound active).
    ``message`` says the same in words; ``nit`` / ``nfev`` count iterations
    and IVPs. The default budget reaches reachable targets on the paper's
    manipulators in 4-7 iterations.
    """

def blocked_force(
    robot: Robot,
    point: Sequence[float] | _FloatArray,
    normal: Sequence[float] | _FloatArray,
    variables: float | Sequence[float] | _FloatArray,
    *,
    groups: Sequence[int | None] | npt.NDArray[np.integer] | None = None,
    fixed_inputs: Mapping[int, float] | None = None,
    steps: int = 100,
    tol: float = 1e-10,
    max_iter: int = 50,
    warm_start: BlockedResult | None = None,
) -> BlockedResult:
    """Contact force [N] of a tip held on a plane, at given actuation variables.

    The plane passes through ``point`` [m] with unit ``normal`` (the direction
    the tip presses in); ``variables`` are temperatures [C], one per group (a
    number for one group).

    A mixed boundary-value problem solved directly: the contact force is an
    extra shooting unknown and ``normal . (p(L) - point) = 0`` an extra
    residual. The force comes out negative if the tip would pull away from
    the plane; whether contact holds is the caller's decision. ``warm_start``:
    a nearby :class:`BlockedResult` (e.g. the previous temperature of a sweep).
    """

def blocked_temperature(
    robot: Robot,
    point: Sequence[float] | _FloatArray,
    normal: Sequence[float] | _FloatArray,
    force: float,
    start: Solution,
    *,
    groups: Sequence[int | None] | npt.NDArray[np.integer] | None = None,
    fixed_inputs: Mapping[int, float] | None = None,
    increments: int = 10,
    steps: int = 100,
    tol: float = 1e-10,
    max_iter: int = 50,
) -> BlockedResult:
    """The actuation variable at which the blocked tip presses with ``force`` [N].

    The paper's incremental method (eq 43, ``dx = 0``), for a single actuation variable."""

def blocked_temperature_direct(
    robot: Robot,
    point: Sequence[float] | _FloatArray,
    normal: Sequence[float] | _FloatArray,
    force: float,
    guess: float,
    *,
    groups: Sequence[int | None] | npt.NDArray[np.integer] | None = None,
    fixed_inputs: Mapping[int, float] | None = None,
    steps: int = 100,
    tol: float = 1e-10,
    max_iter: int = 50,
) -> BlockedResult:
    """The actuation variable of :func:`blocked_temperature`, solved directly.

    Direct mixed solve: the actuation variable is a shooting unknown, the
    contact ``force`` [N] is given."""

def grasp_temperature(
    robot: Robot,
    normal: Sequence[float] | _FloatArray,
    mass: float,
    mu: float,
    fingers: int,
    *,
    gravity: float = 9.81,
    groups: Sequence[int | None] | npt.NDArray[np.integer] | None = None,
    fixed_inputs: Mapping[int, float] | None = None,
    contact: Sequence[float] | _FloatArray | None = None,
    method: Literal["incremental", "direct"] = "incremental",
    increments: int = 8,
    steps: int = 100,
    tol: float = 1e-10,
    max_iter: int = 50,
) -> tuple[BlockedResult, tuple[float, float, float]]:
    """Grasp temperature [C] (eq 44) of ``fingers`` identical fingers holding ``mass`` [kg].

    The actuation variable at which ``fingers`` fingers with friction ``mu``
    [-] hold ``mass`` [kg], ``mu n F(T) = m g``, each
    tip blocked where it rests at the ``contact`` inputs (default: the
    reference inputs), pressing along ``normal``; ``method``: eq 43 in
    ``increments`` steps or a direct solve. Returns (the blocked result of
    one finger, the block point [m])."""

def _restore_inverse_result(
    solution: Solution,
    variables: Sequence[float],
    error: float,
    iterations: int,
    reached: bool,
    at_bound: Sequence[bool],
    evaluations: int,
    max_iter: int,
) -> InverseResult: ...
def _restore_blocked_result(
    solution: Solution, force: float, variables: Sequence[float], iterations: int, evaluations: int
) -> BlockedResult: ...
