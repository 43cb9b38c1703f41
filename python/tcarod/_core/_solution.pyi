"""Solutions of ``tcarod._core`` (src/python/rod/solution.rs)."""

import os
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, final

from matplotlib.figure import Figure

from ._common import _FloatArray
from ._rod import Robot
from ._stability import Continuation

@final
class Solution:
    """A converged forward solution at ``n`` nodes; NumPy arrays, SI units,
    world frame unless noted."""

    @property
    def robot(self) -> Robot: ...
    @property
    def s(self) -> _FloatArray:
        """Arc length of each node [m], shape ``(n,)``."""
    @property
    def positions(self) -> _FloatArray:
        """Centre-line positions [m], shape ``(n, 3)``."""
    @property
    def rotations(self) -> _FloatArray:
        """Rotation matrices (body to world), shape ``(n, 3, 3)``."""
    @property
    def nu(self) -> _FloatArray:
        """Linear strain [-], body frame, shape ``(n, 3)``."""
    @property
    def omega(self) -> _FloatArray:
        """Angular strain [1/m], body frame, shape ``(n, 3)``."""
    @property
    def internal_force(self) -> _FloatArray:
        """Internal force ``n`` [N], shape ``(n, 3)``."""
    @property
    def internal_moment(self) -> _FloatArray:
        """Internal moment ``m`` [N m], shape ``(n, 3)``."""
    @property
    def elongation_profile(self) -> _FloatArray:
        """Elongation of each actuator up to each node [m], shape ``(n, n_actuators)``."""
    @property
    def actuator_paths(self) -> list[_FloatArray]:
        """Path ``p + R r_i`` [m] of each actuator over its span, ``(k_i, 3)`` each."""
    @property
    def tensions(self) -> _FloatArray:
        """Actuator tensions [N] (negative: pushes), shape ``(n_actuators,)``."""
    @property
    def elongations(self) -> _FloatArray:
        """Actuator total elongations [m], shape ``(n_actuators,)``."""
    @property
    def inputs(self) -> _FloatArray:
        """Inputs solved for (temperature [C] for TCAs)."""
    @property
    def base_force(self) -> _FloatArray:
        """Force [N] transmitted to the base by body and actuators (the reaction is its negative)."""
    @property
    def base_moment(self) -> _FloatArray:
        """Moment [N m] about the origin transmitted to the base."""
    @property
    def tip_position(self) -> _FloatArray:
        """Tip position [m], shape ``(3,)``."""
    @property
    def tip_rotation(self) -> _FloatArray:
        """Tip rotation, shape ``(3, 3)``."""
    @property
    def iterations(self) -> int:
        """Newton iterations used (including any fallback continuation)."""
    @property
    def evaluations(self) -> int:
        """IVPs integrated."""
    @property
    def residual(self) -> float:
        """Final residual (max-norm, dimensionless strain units)."""
    @property
    def floor(self) -> float:
        """Estimated rounding floor of the dimensionless residual at the solution [-];
        a ``tol`` below it converges to it (``status == 1``)."""
    @property
    def continuation_steps(self) -> _FloatArray:
        """Homotopy parameters in (0, 1], ending at 1, of the continuation path
        taken when the direct Newton solve failed; empty if it did not."""
    @property
    def unknowns(self) -> _FloatArray:
        """Scaled shooting unknowns ``[nu(0), L omega(0), delta_i / L]``."""
    def to_dict(self, *, stability: bool | None = None) -> dict[str, Any]:
        """The shape and everything solved as a JSON-ready dict, every key
        naming its unit; see ``tcarod.io.results.solution_dict``. ``stability``:
        ``None`` includes the verdict if known, ``True`` computes it if
        needed, ``False`` leaves it out."""
    def to_json(
        self, path: str | os.PathLike[str] | None = None, *, stability: bool | None = None, indent: int | None = 2
    ) -> str:
        """``to_dict()`` as JSON text, also written to ``path`` if given."""
    def to_csv(self, path: str | os.PathLike[str] | None = None) -> str:
        """One row per node, columns named with units, as CSV text; also
        written to ``path`` if given; see ``tcarod.io.results.solution_csv``."""
    def to_vtk(self, path: str | os.PathLike[str]) -> Path:
        """The centre line as a VTK polyline (``.vtu`` / ``.vtk``) for ParaView,
        with meshio (the ``export`` extra); see ``tcarod.io.results.write_vtk``."""
    @property
    def _verdict(self) -> tuple[bool, float] | None:
        """The stability verdict ``(stable, margin)`` if known (never computed here)."""
    def plot(self, **kwargs: Any) -> Figure:
        """Plot of the shape with the actuators: 3-D (default) or a side view
        (``view="xz"`` / ``"yz"``); see ``tcarod.plotting.plot_solution``, which
        also gives a plotly figure with ``view="interactive"``."""
    @property
    def success(self) -> bool:
        """Always ``True`` (a failed solve raises ``ConvergenceError``)."""
    @property
    def status(self) -> int:
        """``0``: converged to ``tol``; ``1``: ``tol`` lies below the estimated
        rounding floor and the residual reached the floor (``floor``). Both are
        successes (as in ``scipy.optimize.least_squares``)."""
    @property
    def message(self) -> str: ...
    @property
    def nit(self) -> int:
        """Newton iterations (``iterations``)."""
    @property
    def nfev(self) -> int:
        """IVPs integrated (``evaluations``)."""
    @property
    def steps(self) -> int:
        """RK4 steps over the body."""
    @property
    def stable(self) -> bool:
        """True if the equilibrium is stable (strict local energy minimum);
        computed by the solve (``stability="report"``, the default) or on
        first access (one tangent IVP, GIL released), and cached. A
        ``BlockedResult.solution`` carries the verdict with its tip held."""
    @property
    def stability_margin(self) -> float:
        """Smallest eigenvalue of the dimensionless tip stiffness [-], ``> 0``
        iff ``stable``; computed and cached with ``stable``."""
    @property
    def continued(self) -> Continuation | None:
        """How ``stability="continue"`` reached this equilibrium from an
        unstable one, or None."""
    def __reduce__(self) -> tuple[Any, ...]: ...

def _register_plotter(plotter: Callable[..., Any]) -> None:
    """Register the function ``Solution.plot`` calls (the package does it at import)."""

def _register_exporter(exporter: Callable[..., Any]) -> None:
    """Register the function the export methods call (the package does it at import)."""

def _restore_solution_verdict(state: tuple[Any, ...], stable: bool, margin: float) -> Solution:
    """Unpickle a ``Solution`` with its stability verdict."""

def _restore_solution(
    robot: Robot,
    inputs: Sequence[float],
    unknowns: Sequence[float],
    tip_force: Sequence[float],
    tip_moment: Sequence[float],
    steps: int,
    iterations: int,
    evaluations: int,
    jacobian: tuple[int, int, Sequence[float]] | None,
    outcome: tuple[int, float, Sequence[float]] | None = None,
    blocked: Sequence[Sequence[float]] | None = None,
) -> Solution: ...
