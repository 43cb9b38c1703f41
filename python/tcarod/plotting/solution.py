"""The shape of a forward solution: centre line, body outline, actuators, in
3-D or as a 2-D side view (``Solution.plot()`` calls :func:`plot_solution`).

Figures: with ``ax=None`` a new figure is made by ``matplotlib.pyplot`` when
pyplot is imported (so ``fig.show()`` and ``plt.show()`` work in a script),
otherwise on the Agg canvas (headless, and in Jupyter's inline backend, where
the returned figure is displayed once); see :mod:`tcarod.plotting`.

Overlays: drawing again on the same ``ax`` keeps what is there, grows the
limits to hold every shape (equal aspect), lists each legend label once
("centre line", "body outline", each actuator), keeps an existing title
unless ``title`` is given, and sets the 3-D camera only on the first shape or
when ``camera`` is given.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Literal, Union, overload

import numpy as np
import numpy.typing as npt
from matplotlib.figure import Figure

from .. import _validate as V
from ..rod import Solution
from ._figure import new_figure
from ._shapes import input_title, shape_lines

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = ["plot_solution"]

FloatArray = npt.NDArray[np.float64]
View = Union[Literal["3d", "xz", "yz", "interactive"], tuple[float, float]]

#: Default camera of the 3-D view: (elevation, azimuth) [deg].
DEFAULT_CAMERA: tuple[float, float] = (15.0, -60.0)
_MM = 1e3
#: Side views: view name -> (horizontal, vertical) world axis index.
_SIDE_AXES = {"xz": (0, 2), "yz": (1, 2)}
_AXIS_NAMES = "xyz"


def _style(gid: str) -> dict[str, Any]:
    """Line style of a shape line by its gid."""
    if gid == "centre-line":
        return {"color": "black", "linestyle": "--", "linewidth": 1.0}
    if gid.startswith("actuator-"):
        return {"color": f"C{int(gid.split('-')[1]) % 10}", "linewidth": 2.0}
    return {"color": "0.55", "linewidth": 0.8}


def _equal_cube(ax: Any, points: list[FloatArray]) -> None:
    """Equal aspect: a cube around the drawn points of every shape overlaid on ``ax``."""
    allp = np.concatenate(points)
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    previous = getattr(ax, "_tcarod_bounds", None)
    if previous is not None:
        lo, hi = np.minimum(lo, previous[0]), np.maximum(hi, previous[1])
    ax._tcarod_bounds = (lo, hi)
    centre, half = 0.5 * (lo + hi), 0.5 * float(np.max(hi - lo)) * 1.05
    ax.set_xlim(centre[0] - half, centre[0] + half)
    ax.set_ylim(centre[1] - half, centre[1] + half)
    ax.set_zlim(centre[2] - half, centre[2] + half)
    ax.set_box_aspect((1.0, 1.0, 1.0), zoom=0.85)  # zoom < 1: room for the z label
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_zlabel("z [mm]")


def _unique_legend(ax: Any) -> None:
    """One legend entry per label, however many shapes share the axes."""
    handles, labels = ax.get_legend_handles_labels()
    unique: dict[str, object] = {}
    for h, lab in zip(handles, labels):
        unique.setdefault(lab, h)
    ax.legend(list(unique.values()), list(unique.keys()), fontsize="x-small", loc="upper left")


def _axes(ax: Axes | None, three_d: bool) -> tuple[Any, Figure, bool]:
    """The axes to draw into (a new figure if ``ax`` is None), its figure, and
    whether this is the first shape drawn on it."""
    if ax is None:
        fig = new_figure(5.0, 5.0) if three_d else new_figure(4.5, 5.0)
        new_ax = fig.add_subplot(projection="3d") if three_d else fig.add_subplot()
        return new_ax, fig, True
    is_3d = hasattr(ax, "set_zlim")
    if three_d and not is_3d:
        raise TypeError(f"ax must be a 3-D matplotlib axes (projection='3d') for view='3d', not {type(ax).__name__}")
    if not three_d and (is_3d or not hasattr(ax, "set_aspect")):
        raise TypeError(f"ax must be a 2-D matplotlib axes for a side view, not {type(ax).__name__}")
    figure = ax.get_figure()
    if not isinstance(figure, Figure):
        raise ValueError("ax: must belong to a matplotlib Figure")
    first = not any(line.get_gid() == "centre-line" for line in ax.get_lines())
    return ax, figure, first


def _view_and_camera(
    view: object, camera: tuple[float, float] | None, backend: str
) -> tuple[str, tuple[float, float] | None]:
    """The checked view name (``"3d"``, ``"xz"``, ``"yz"`` or ``"interactive"``) and camera [deg]."""
    if not isinstance(backend, str):
        raise TypeError(f"backend must be a str, not {type(backend).__name__}")
    if backend not in ("matplotlib", "plotly"):
        raise ValueError(f"invalid backend = {backend!r}: use 'matplotlib' or 'plotly'")
    if isinstance(view, tuple):  # (elevation, azimuth) [deg]: the 3-D view from that camera
        if camera is not None:
            raise ValueError("give the 3-D camera [deg] once: view=(elevation, azimuth) or camera=(...), not both")
        if len(view) != 2:
            raise ValueError(f"invalid view = {view!r}: a camera is (elevation, azimuth) [deg]")
        pair: tuple[Any, Any] = (view[0], view[1])  # checked as reals [deg] below
        view, camera = "3d", pair
    if not isinstance(view, str):
        raise TypeError(f"view must be a str or an (elevation, azimuth) tuple [deg], not {type(view).__name__}")
    if view not in ("3d", "xz", "yz", "interactive"):
        raise ValueError(f"invalid view = {view!r}: use '3d', 'xz', 'yz' or 'interactive'")
    if backend == "plotly":
        if view not in ("3d", "interactive"):
            raise ValueError(f"invalid view = {view!r} with backend='plotly': the interactive view is 3-D")
        view = "interactive"
    if camera is not None:
        if view in _SIDE_AXES:
            raise ValueError(f"camera: only for the 3-D view, not view = {view!r}")
        camera = (
            V.real("camera[0] (elevation) [deg]", camera[0], unit="deg"),
            V.real("camera[1] (azimuth) [deg]", camera[1], unit="deg"),
        )
    return view, camera


def _draw(ax: Any, lines: list[tuple[str, str | None, FloatArray]], view: str, camera: Any, first: bool) -> None:
    """Draw ``lines`` [mm] on ``ax``: in 3-D (equal cube, the camera set on the
    first shape or when given) or projected on the side view ``view``."""
    if view == "3d":
        for gid, label, p in lines:
            ax.plot(p[:, 0], p[:, 1], p[:, 2], label=label, gid=gid, **_style(gid))
        _equal_cube(ax, [p for _, _, p in lines])
        if first or camera is not None:
            elev, azim = camera if camera is not None else DEFAULT_CAMERA
            ax.view_init(elev=elev, azim=azim)
        return
    h, v = _SIDE_AXES[view]
    for gid, label, p in lines:
        ax.plot(p[:, h], p[:, v], label=label, gid=gid, **_style(gid))
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"{_AXIS_NAMES[h]} [mm]")
    ax.set_ylabel(f"{_AXIS_NAMES[v]} [mm]")
    ax.grid(True, linewidth=0.3)


@overload
def plot_solution(
    solution: Solution,
    ax: Axes | None = None,
    *,
    view: Literal["3d", "xz", "yz"] | tuple[float, float] = "3d",
    rings: int = 5,
    camera: tuple[float, float] | None = None,
    title: str | None = None,
    backend: Literal["matplotlib"] = "matplotlib",
) -> Figure: ...
@overload
def plot_solution(
    solution: Solution,
    ax: None = None,
    *,
    view: View = "3d",
    rings: int = 5,
    camera: tuple[float, float] | None = None,
    title: str | None = None,
    backend: str = "matplotlib",
) -> Any: ...
def plot_solution(
    solution: Solution,
    ax: Axes | None = None,
    *,
    view: View = "3d",
    rings: int = 5,
    camera: tuple[float, float] | None = None,
    title: str | None = None,
    backend: str = "matplotlib",
) -> Any:
    """Plot the shape of a forward solution with its actuators (axes in mm).

    Draws the centre line (dashed), the body's outline (edge lines and
    ``rings`` cross-section rings) and each actuator path in its own colour;
    the legend gives each actuator's tension in mN (negative: it pushes), the
    title the inputs with their units (``"inputs: 120 °C, 25 °C"``). It is
    ``Solution.plot(**kwargs)``; figures and overlays: the module docstring.

    Parameters
    ----------
    solution : Solution
        A forward solution (``Robot.solve``).
    ax : matplotlib.axes.Axes, optional
        Axes to draw into (3-D for ``view="3d"``, 2-D for a side view).
    view : {"3d", "xz", "yz", "interactive"} or (float, float)
        ``"3d"``: 3-D, equal aspect. ``"xz"`` / ``"yz"``: side view along
        world -y / +x, ``z`` (the reference tangent) up, equal aspect.
        ``"interactive"``: a plotly 3-D figure (as ``backend="plotly"``).
        An ``(elevation, azimuth)`` pair [deg]: the 3-D view from there.
    rings : int
        Cross-section rings drawn (0 to 1000; base and tip included).
    camera : (float, float), optional
        ``(elevation, azimuth)`` [deg] of the 3-D view (default (15, -60)).
    title : str, optional
        Title; default the inputs with their units.
    backend : {"matplotlib", "plotly"}
        ``"plotly"``: an interactive ``plotly.graph_objects.Figure`` (3-D;
        the ``interactive`` extra).

    Returns
    -------
    matplotlib.figure.Figure or plotly.graph_objects.Figure
        The figure drawn into (``ax``'s figure if ``ax`` was given).

    Raises
    ------
    TypeError
        A wrong type, or ``ax`` not an axes of the view's kind.
    ValueError
        ``view``, ``backend``, ``rings`` or ``camera`` out of range.
    ImportError
        plotly needed and not installed (naming ``tcarod[interactive]``).

    Examples
    --------
    >>> from tcarod.paper.fig6 import FIG6
    >>> from tcarod.plotting import plot_solution
    >>> sol = FIG6.manipulators[1].robot().solve([100.0, 100.0])
    >>> ax = plot_solution(sol, view="xz").axes[0]
    >>> ax.get_xlabel(), ax.get_ylabel(), ax.get_title()
    ('x [mm]', 'z [mm]', 'inputs: 100 °C, 100 °C')
    """
    V.instance("solution", solution, Solution, "a tcarod.Solution")
    rings = V.integer("rings", rings, 0, 1000)
    if title is not None and not isinstance(title, str):
        raise TypeError(f"title must be a str, not {type(title).__name__}")
    view_name, cam = _view_and_camera(view, camera, backend)
    if view_name == "interactive":
        if ax is not None:
            raise TypeError("ax: the interactive (plotly) view makes its own figure; pass ax=None")
        from .interactive import plot_solution_plotly

        return plot_solution_plotly(solution, rings=rings, title=title)
    ax_, figure, first = _axes(ax, view_name == "3d")
    had_title = bool(ax_.get_title())
    _draw(ax_, shape_lines(solution, rings), view_name, cam, first)
    if title is not None or not had_title:  # an overlay keeps the first shape's title
        ax_.set_title(input_title(solution) if title is None else title, fontsize="small")
    _unique_legend(ax_)
    return figure
