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
    """A converged forward solution: the robot's shape and what held it there.

    Returned by `Robot.solve`. Arrays are NumPy, SI units, world frame unless
    noted; `n` nodes along the body. SciPy-style fields: `success` (always
    `True`: a failed solve raises `ConvergenceError`), `status`, `message`,
    `nit` (Newton iterations), `nfev` (IVPs). Naming: `tip_position` [m] per
    solve, `tip_positions` per batch (`tcarod.batch.BatchResult`). Stability:
    `stable` and `stability_margin`, computed by the solve (policy
    `"report"`, the default) or on first access (one tangent IVP), cached;
    `continued` records a `stability="continue"` solve's route. Picklable
    (with its robot) and comparable with `==`.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> sol = fig6_square_robot().solve([100.0, 100.0])   # the paper's Fig. 6 square
    >>> sol.positions.shape, sol.tensions.shape            # (n, 3) [m], one tension per TCA [N]
    ((101, 3), (2,))
    >>> round(float(sol.tip_position[0]) * 1e3, 2), sol.stable   # tip x [mm]
    (-6.13, True)
    """

    @property
    def robot(self) -> Robot: ...
    @property
    def s(self) -> _FloatArray:
        """Arc length of each node [m].

        Returns
        -------
        numpy.ndarray
            Shape ``(n,)``, from 0 at the base to the body length at the tip [m].
        """
    @property
    def positions(self) -> _FloatArray:
        """Centre-line positions [m], world frame.

        Returns
        -------
        numpy.ndarray
            Shape ``(n, 3)``: the position ``p(s)`` of each node [m].
        """
    @property
    def rotations(self) -> _FloatArray:
        """Body-to-world rotation matrices [-].

        Returns
        -------
        numpy.ndarray
            Shape ``(n, 3, 3)``; column 3 of each is the tangent ``R e3``.
        """
    @property
    def nu(self) -> _FloatArray:
        """Linear strain ``nu`` [-], body frame.

        Returns
        -------
        numpy.ndarray
            Shape ``(n, 3)``; ``(0, 0, 1)`` where the body is neither sheared nor
            stretched.
        """
    @property
    def omega(self) -> _FloatArray:
        """Angular strain (curvature and twist) ``omega`` [1/m], body frame.

        Returns
        -------
        numpy.ndarray
            Shape ``(n, 3)`` [1/m].
        """
    @property
    def internal_force(self) -> _FloatArray:
        """Internal force ``n`` [N], world frame.

        Returns
        -------
        numpy.ndarray
            Shape ``(n, 3)`` [N]: the force the distal part exerts on the proximal
            part across each section.
        """
    @property
    def internal_moment(self) -> _FloatArray:
        """Internal moment ``m`` [N m], world frame.

        Returns
        -------
        numpy.ndarray
            Shape ``(n, 3)`` [N m].
        """
    @property
    def elongation_profile(self) -> _FloatArray:
        """Elongation of each actuator accumulated up to each node [m].

        Returns
        -------
        numpy.ndarray
            Shape ``(n, n_actuators)`` [m]; the last row is ``elongations``.
        """
    @property
    def actuator_paths(self) -> list[_FloatArray]:
        """Path ``p + R r_i`` of each actuator over its span [m], world frame.

        Returns
        -------
        list of numpy.ndarray
            One ``(k_i, 3)`` array per actuator [m].
        """
    @property
    def tensions(self) -> _FloatArray:
        """Actuator tensions [N] (negative: the actuator pushes).

        Returns
        -------
        numpy.ndarray
            Shape ``(n_actuators,)`` [N].
        """
    @property
    def elongations(self) -> _FloatArray:
        """Total elongation of each actuator [m].

        Returns
        -------
        numpy.ndarray
            Shape ``(n_actuators,)`` [m].
        """
    @property
    def inputs(self) -> _FloatArray:
        """The inputs solved for, one per actuator.

        Returns
        -------
        numpy.ndarray
            Shape ``(n_actuators,)``: temperature [C] for a TCA, tension [N] for a
            tendon, pull [m] for a linear tendon.
        """
    @property
    def base_force(self) -> _FloatArray:
        """Force [N] transmitted to the base by the body and the actuators.

        Returns
        -------
        numpy.ndarray
            Shape ``(3,)`` [N], world frame; the base reaction is its negative.
        """
    @property
    def base_moment(self) -> _FloatArray:
        """Moment [N m] about the origin transmitted to the base.

        Returns
        -------
        numpy.ndarray
            Shape ``(3,)`` [N m], world frame.
        """
    @property
    def tip_position(self) -> _FloatArray:
        """Tip position [m], world frame.

        Returns
        -------
        numpy.ndarray
            Shape ``(3,)`` [m].
        """
    @property
    def tip_rotation(self) -> _FloatArray:
        """Tip rotation matrix (body to world) [-].

        Returns
        -------
        numpy.ndarray
            Shape ``(3, 3)``; column 3 is the tip tangent.
        """
    @property
    def iterations(self) -> int:
        """Newton iterations used (same as ``nit``).

        Returns
        -------
        int
            Iterations of the last Newton solve [-].
        """
    @property
    def evaluations(self) -> int:
        """IVPs integrated (same as ``nfev``).

        Returns
        -------
        int
            Integrations of the rod's ODE over the body, continuation included [-].
        """
    @property
    def residual(self) -> float:
        """Final residual of the shooting problem [-].

        Returns
        -------
        float
            Max-norm of the dimensionless shooting residual [-].
        """
    @property
    def floor(self) -> float:
        """Estimated rounding floor of the dimensionless residual [-].

        Returns
        -------
        float
            The residual cannot be computed more accurately than this at the
            solution; a ``tol`` below it converges to it (``status == 1``).
        """
    @property
    def continuation_steps(self) -> _FloatArray:
        """Homotopy parameters of the continuation path the solve took [-].

        Returns
        -------
        numpy.ndarray
            Each ``lambda`` in (0, 1], ending at 1, when the direct Newton solve
            failed and continuation took over; empty if it did not.
        """
    @property
    def unknowns(self) -> _FloatArray:
        """Scaled shooting unknowns ``[nu(0), L omega(0), delta_i / L]`` [-].

        Returns
        -------
        numpy.ndarray
            Shape ``(6 + n_actuators,)`` [-]: the base strains and the actuators'
            scaled elongations Newton converged to.
        """
    def to_dict(self, *, stability: bool | None = None) -> dict[str, Any]:
        """The shape and everything solved as a dict of plain numbers and lists.

        Every key names its unit (``positions_m``, ``tensions_n``, ...); the
        document is JSON-ready. See ``tcarod.io.results.solution_dict`` and the
        table in the documentation page "Exporting shapes".

        Parameters
        ----------
        stability : bool or None, optional
            ``None`` (default) includes the stability verdict if it is already
            known, ``True`` computes it if needed (one tangent IVP), ``False``
            leaves it out (``null``).

        Returns
        -------
        dict
            The document, format ``"tcarod.solution/1"``.

        Examples
        --------
        >>> from tcarod.batch import fig6_square_robot
        >>> doc = fig6_square_robot().solve([60.0, 25.0], steps=20).to_dict()
        >>> doc["format"], doc["nodes"], len(doc["positions_m"])
        ('tcarod.solution/1', 21, 21)
        """
    def to_json(
        self, path: str | os.PathLike[str] | None = None, *, stability: bool | None = None, indent: int | None = 2
    ) -> str:
        """``to_dict()`` as JSON text, also written to ``path`` if given.

        Parameters
        ----------
        path : str or os.PathLike, optional
            File to write (UTF-8); default: none, the text is only returned.
        stability : bool or None, optional
            As in ``to_dict``.
        indent : int or None, optional
            JSON indentation (default 2; ``None``: one line).

        Returns
        -------
        str
            The JSON document (NaN never occurs).

        Examples
        --------
        >>> import json
        >>> from tcarod.batch import fig6_square_robot
        >>> sol = fig6_square_robot().solve([60.0, 25.0], steps=20)
        >>> doc = json.loads(sol.to_json("shape.json"))
        >>> " ".join(doc["input_units"])
        'C C'
        """
    def to_csv(self, path: str | os.PathLike[str] | None = None) -> str:
        """One row per node as CSV text, columns named with their units.

        The columns: arc length, position, rotation, strains, internal wrench,
        actuator elongations (``tcarod.io.results.solution_csv``).

        Parameters
        ----------
        path : str or os.PathLike, optional
            File to write; default: none, the text is only returned.

        Returns
        -------
        str
            The CSV text, one header line and ``n`` rows.

        Examples
        --------
        >>> from tcarod.batch import fig6_square_robot
        >>> lines = fig6_square_robot().solve([60.0, 25.0], steps=20).to_csv().splitlines()
        >>> len(lines), lines[0].startswith("s_m,x_m,y_m,z_m,r11,")
        (22, True)
        """
    def to_vtk(self, path: str | os.PathLike[str]) -> Path:
        """Write the centre line as a VTK polyline with the node data, for ParaView.

        Needs meshio (the ``export`` extra); see ``tcarod.io.results.write_vtk``.

        Parameters
        ----------
        path : str or os.PathLike
            ``.vtu`` (XML) or ``.vtk`` (legacy) file.

        Returns
        -------
        pathlib.Path
            The path written.

        Raises
        ------
        ValueError
            A suffix other than ``.vtu`` or ``.vtk``.
        ImportError
            meshio is not installed (names the ``export`` extra).
        """
    @property
    def _verdict(self) -> tuple[bool, float] | None:
        """The stability verdict ``(stable, margin)`` if known (never computed here)."""
    def plot(self, **kwargs: Any) -> Figure:
        """Plot the shape with the actuators (the ``plot`` extra, matplotlib).

        The keywords are those of ``tcarod.plotting.plot_solution``.

        Parameters
        ----------
        **kwargs
            ``view`` (``"3d"``, ``"xz"``, ``"yz"``, ``"xy"`` or ``"interactive"``),
            ``ax``, ``show_actuators``, ...

        Returns
        -------
        matplotlib.figure.Figure
            The figure (a plotly figure for ``view="interactive"``).

        Examples
        --------
        >>> from tcarod.batch import fig6_square_robot
        >>> fig = fig6_square_robot().solve([60.0, 25.0], steps=20).plot(view="xz")
        >>> fig.axes[0].get_xlabel()
        'x [mm]'
        """
    @property
    def success(self) -> bool:
        """`True` if the solve succeeded (see `status` for the success
        codes), SciPy naming.
        """
    @property
    def status(self) -> int:
        """Status code of the solve (SciPy naming).

        Returns
        -------
        int
            `0` converged to `tol`; `1` `tol` lies below the estimated rounding floor and the residual reached the floor (`floor`). Both are successes, as in `scipy.optimize.least_squares`; a solve that fails raises `ConvergenceError` instead.
        """
    @property
    def message(self) -> str: ...
    @property
    def nit(self) -> int:
        """Iterations (same as `iterations`), SciPy naming."""
    @property
    def nfev(self) -> int:
        """IVPs integrated, i.e. function evaluations (same as `evaluations`), SciPy naming."""
    @property
    def steps(self) -> int:
        """RK4 steps over the body used by the solve [-].

        Returns
        -------
        int
            The ``steps`` argument, or the finer grid an ``equilibrium_tol``
            solve needed.
        """
    @property
    def stable(self) -> bool:
        """Whether this equilibrium is stable.

        Returns
        -------
        bool
            ``True`` at a strict local minimum of the potential energy (Till and
            Rucker's criterion, extended to the actuators and dead loads; see
            ``tcarod.models.stability``). Computed by the solve (policy ``"report"``,
            the default) or on first access from one tangent integration, then
            cached. A ``BlockedResult.solution`` carries the verdict with the tip
            held on its plane (mixed boundary condition).
        """
    @property
    def stability_margin(self) -> float:
        """Stability margin [-].

        Returns
        -------
        float
            The smallest eigenvalue of the dimensionless tip stiffness [-],
            ``> 0`` if and only if ``stable``; computed and cached with ``stable``.
        """
    @property
    def continued(self) -> Continuation | None:
        """How ``stability="continue"`` reached this equilibrium, if it moved.

        Returns
        -------
        Continuation or None
            The route from the unstable equilibrium Newton found first; ``None``
            if the solve did not move.
        """
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
    outcome: tuple[int, float, Sequence[float]] | None = None,
    blocked: Sequence[Sequence[float]] | None = None,
    tensions: Sequence[float] | None = None,
    segments: Sequence[Sequence[float]] | None = None,
) -> Solution: ...
