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
    """A solve handed back an unstable equilibrium (``stability="report"``,
    the default); ``stability="continue"`` moves to a stable one."""

@final
class Continuation:
    """Route of a ``stability="continue"`` solve from the unstable
    equilibrium Newton found first to the stable one handed back."""

    @property
    def route(self) -> str: ...
    @property
    def unstable(self) -> Solution: ...
    @property
    def margin(self) -> float:
        """Stability margin of the unstable equilibrium [-] (< 0)."""
    @property
    def candidates(self) -> int: ...
    @property
    def evaluations(self) -> int: ...
    def __eq__(self, value: object, /) -> bool: ...

@final
class Stability:
    """Stability verdict of one equilibrium (see ``tcarod.models.stability``)."""

    @property
    def stable(self) -> bool: ...
    @property
    def margin(self) -> float:
        """Smallest eigenvalue of the dimensionless tip stiffness [-]: > 0 iff stable."""
    @property
    def conjugate_point(self) -> float | None:
        """Arc length [m] of the first conjugate point, or None."""
    @property
    def s(self) -> _FloatArray: ...
    @property
    def determinant(self) -> _FloatArray:
        """Till and Rucker's ``det(Y(s) Y(0)^-1)`` [-] at the nodes."""
    @property
    def min_stiffness(self) -> _FloatArray: ...
    @property
    def mode(self) -> _FloatArray:
        """Softest tip mode ``(dp / L, dtheta)``, shape ``(6,)``."""
    @property
    def evaluations(self) -> int: ...
    def __reduce__(self) -> tuple[Any, ...]: ...
    def __eq__(self, value: object, /) -> bool: ...

@final
class Branch:
    """A followed branch or a stable sweep (see ``tcarod.models.stability.follow_branch``)."""

    @property
    def parameter(self) -> _FloatArray: ...
    @property
    def tip_positions(self) -> _FloatArray:
        """Tip positions [m], shape ``(k, 3)``."""
    @property
    def stable(self) -> npt.NDArray[np.bool_]: ...
    @property
    def margin(self) -> _FloatArray: ...
    @property
    def solutions(self) -> list[Solution]: ...
    @property
    def events(self) -> list[tuple[str, float, _FloatArray]]:
        """``(kind, parameter, tip position [m])``, kind ``"fold"`` or ``"bifurcation"``."""
    @property
    def folds(self) -> _FloatArray: ...
    @property
    def bifurcations(self) -> _FloatArray: ...
    @property
    def jumps(self) -> list[tuple[float, Solution, Solution]]:
        """Stable sweeps: ``(parameter, before, after)``."""
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
    """Stability of ``solution``; ``blocked``: world directions of held tip translation."""

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
    """Pseudo-arclength continuation in ``parameter`` (``"inputs"``,
    ``"gravity_scale"``, ``"tip_load_scale"``) from ``start`` to ``end``."""
