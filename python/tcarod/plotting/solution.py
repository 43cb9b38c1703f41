"""The 3-D shape of a forward solution: centre line, body outline, actuators
(``Solution.plot()`` calls :func:`plot_solution`)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt
from matplotlib.figure import Figure

from .. import _validate as V
from ..rod import Section, Solution
from ._figure import new_figure

if TYPE_CHECKING:
    from mpl_toolkits.mplot3d.axes3d import Axes3D  # type: ignore[import-untyped]  # untyped: Any

__all__ = ["plot_solution"]

FloatArray = npt.NDArray[np.float64]

_DEFAULT_VIEW = (15.0, -60.0)
_MM = 1e3


def _outline_angles(section: Section) -> list[float]:
    """Body-frame angles [rad] of the edge lines drawn along the body: the four
    corners of a rectangle, eight directions otherwise."""
    if section.kind == "rectangle":
        area, ix, iy, _ = section.properties
        half_w, half_h = 0.5 * math.sqrt(12.0 * iy / area), 0.5 * math.sqrt(12.0 * ix / area)
        c = math.atan2(half_h, half_w)
        return [c, math.pi - c, math.pi + c, 2.0 * math.pi - c]
    return [k * math.pi / 4.0 for k in range(8)]


def _edge_point(section: Section, theta: float) -> FloatArray:
    """Body-frame point [m] of the section's edge in direction ``theta`` [rad]."""
    r = section.edge_distance(theta)
    return np.array([r * math.cos(theta), r * math.sin(theta), 0.0])


def _draw_body(ax: Any, solution: Solution, rings: int) -> list[FloatArray]:
    """Centre line, edge lines and ``rings`` cross-section rings [mm]; returns the drawn points."""
    pos, rot = solution.positions, solution.rotations
    section = solution.robot.body.section
    ax.plot(
        pos[:, 0] * _MM, pos[:, 1] * _MM, pos[:, 2] * _MM, "k--", linewidth=1.0, label="centre line", gid="centre-line"
    )
    points = [pos * _MM]
    for k, theta in enumerate(_outline_angles(section)):
        pts = (pos + rot @ _edge_point(section, theta)) * _MM
        points.append(pts)
        label = "body outline" if k == 0 else None
        ax.plot(pts[:, 0], pts[:, 1], pts[:, 2], color="0.55", linewidth=0.8, label=label, gid=f"outline-{k}")
    # cross-section rings at evenly spaced nodes (base and tip included)
    ring_local = np.array([_edge_point(section, float(t)) for t in np.linspace(0.0, 2.0 * math.pi, 73)])
    n = len(solution.s)
    for k, i in enumerate(sorted({round(j) for j in np.linspace(0, n - 1, max(2, rings))})):
        ring = (pos[i] + ring_local @ rot[i].T) * _MM
        ax.plot(ring[:, 0], ring[:, 1], ring[:, 2], color="0.55", linewidth=0.8, gid=f"ring-{k}")
    return points


def _draw_actuators(ax: Any, solution: Solution) -> list[FloatArray]:
    """Each actuator path [mm] in its own colour, labelled with its tension [mN]."""
    points = []
    for k, (path, tension) in enumerate(zip(solution.actuator_paths, solution.tensions)):
        p = path * _MM
        points.append(p)
        label = f"actuator {k}: {tension * 1e3:.1f} mN"
        ax.plot(p[:, 0], p[:, 1], p[:, 2], color=f"C{k % 10}", linewidth=2.0, label=label, gid=f"actuator-{k}")
    return points


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


def _axes(ax: Axes3D | None) -> tuple[Any, Figure, bool]:
    """The 3-D axes to draw into (a new Agg figure if ``ax`` is None), its
    figure, and whether this is the first shape drawn on it."""
    if ax is None:
        fig = new_figure(5.0, 5.0)
        return fig.add_subplot(projection="3d"), fig, True
    if not hasattr(ax, "set_zlim"):
        raise TypeError(f"ax must be a 3-D matplotlib axes (projection='3d'), not {type(ax).__name__}")
    figure = ax.get_figure()
    if not isinstance(figure, Figure):
        raise ValueError("ax: must belong to a matplotlib Figure")
    return ax, figure, getattr(ax, "_tcarod_bounds", None) is None


def plot_solution(
    solution: Solution,
    ax: Axes3D | None = None,
    *,
    rings: int = 5,
    view: tuple[float, float] = _DEFAULT_VIEW,
    title: str | None = None,
) -> Figure:
    """3-D plot of a forward solution (axes in mm): the centre line (dashed),
    the body's outline -- edge lines along the body and ``rings`` cross-section
    rings, from :meth:`Section.edge_distance` and the solution's rotations --
    and each actuator path (``solution.actuator_paths``) in its own colour,
    labelled with its tension [N]. Equal aspect in x, y, z.

    ``ax``: an existing 3-D axes (``projection="3d"``) to draw into; by
    default a new Agg ``Figure`` is made. ``view`` is ``(elevation, azimuth)``
    [deg]. Returns the ``Figure`` (``ax.figure`` if ``ax`` was given).

    Overlays: calling it again with the same ``ax`` adds the shape and keeps
    what is there: the limits grow to hold every shape drawn by this function
    on that axes (a cube, equal aspect), the legend lists each label once
    ("centre line", "body outline" and each actuator), an existing title is
    kept unless ``title`` is given, and the view is set only on the first call
    (or when ``view`` is given explicitly).
    """
    V.instance("solution", solution, Solution, "a tcarod.Solution")
    rings = V.integer("rings", rings, 0, 1000)
    if title is not None and not isinstance(title, str):
        raise TypeError(f"title must be a str, not {type(title).__name__}")
    view_given = view is not _DEFAULT_VIEW
    view = (V.real("view[0] (elevation)", view[0], unit="deg"), V.real("view[1] (azimuth)", view[1], unit="deg"))
    ax, figure, first = _axes(ax)
    had_title = bool(ax.get_title())
    _equal_cube(ax, _draw_body(ax, solution, rings) + _draw_actuators(ax, solution))
    if first or view_given:
        ax.view_init(elev=view[0], azim=view[1])
    names = [a.input_name for a in solution.robot.actuators]
    inputs = ", ".join(f"{name} {x:g}" for name, x in zip(names, solution.inputs))
    if title is not None:
        ax.set_title(title, fontsize="small")
    elif not had_title:
        ax.set_title(inputs or "no actuators", fontsize="small")
    _unique_legend(ax)
    return figure
