"""Plots of the paper's experiments in the paper's style (matplotlib).

Figures are built with matplotlib's object-oriented API (``Figure`` rendered by
the Agg canvas), never through ``pyplot``: nothing here needs a display or
changes the user's global matplotlib backend.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from ._optional import require

require("matplotlib")  # one clear line naming the `plot` extra if it is missing
from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

if TYPE_CHECKING:
    from mpl_toolkits.mplot3d.axes3d import Axes3D  # type: ignore[import-untyped]  # untyped: Any

    from .experiments import Fig5Result
    from .experiments.fig6 import Fig6Result
    from .rod import Section, Solution

__all__ = ["plot_fig5", "plot_fig6", "plot_solution", "save_png"]

_LOAD_STYLES = ("-", "--", "-.", ":")


def plot_fig5(result: Fig5Result) -> Figure:
    """Fig. 5: displacement [mm] against temperature [C], one panel per TCA
    (3 and 4 threads), one line per load, the onset of extension marked.

    The paper's figure also shades the measured mean +- standard deviation;
    it prints no numbers for them, so only the model is drawn unless the
    experiment carries published data.
    """
    tca_labels: list[str] = []
    for c in result.curves:
        if c.case.tca.label not in tca_labels:
            tca_labels.append(c.case.tca.label)
    fig = Figure(figsize=(4.0 * max(1, len(tca_labels)), 3.4), layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(1, max(1, len(tca_labels)), sharey=True, squeeze=False)[0]
    for ax, tca_label in zip(axes, tca_labels):
        curves = [c for c in result.curves if c.case.tca.label == tca_label]
        for k, c in enumerate(curves):
            load = c.case.load
            line_label = f"{load.label} (+{load.friction_equivalent_kg * 1e3:g} g friction)"
            temps = list(c.temperatures_c)
            disps = list(c.displacements_m * 1e3)
            if c.onset_temperature_c is not None:
                # the curve leaves zero at the onset, not at the next grid point
                k_on = sum(1 for t in temps if t < c.onset_temperature_c)
                temps.insert(k_on, c.onset_temperature_c)
                disps.insert(k_on, 0.0)
            (line,) = ax.plot(
                temps,
                disps,
                linestyle=_LOAD_STYLES[k % len(_LOAD_STYLES)],
                color="black",
                label=line_label,
            )
            if c.onset_temperature_c is not None:
                ax.plot(
                    [c.onset_temperature_c],
                    [0.0],
                    marker="o",
                    markerfacecolor="white",
                    color=line.get_color(),
                    linestyle="none",
                    label=f"onset {c.onset_temperature_c:.1f} °C",
                )
        published = result.experiment.published_data
        if published is not None:
            for p in published:
                if p.label.startswith(tca_label):
                    mean = [m * 1e3 for m in p.mean]
                    std = [s * 1e3 for s in p.std]
                    ax.fill_between(
                        p.temperatures_c,
                        [m - s for m, s in zip(mean, std)],
                        [m + s for m, s in zip(mean, std)],
                        color="0.8",
                        label=f"experiment {p.label}",
                    )
        ax.set_title(f"Extension TCA, {tca_label}")
        ax.set_xlabel("Temperature [°C]")
        ax.grid(True, linewidth=0.3)
        ax.legend(fontsize="small", loc="upper left")
    axes[0].set_ylabel("Displacement [mm]")
    if result.experiment.published_data is None:
        fig.suptitle("Model prediction (the paper prints no numeric data for Fig. 5)", fontsize="small")
    return fig


def plot_fig6(result: Fig6Result) -> Figure:
    """Fig. 6: inner-edge bending radius [mm] against temperature [C], one
    panel per manipulator (circle above, square below, as in the paper), the
    model with gravity (upright, as in the oven; solid) and without (dashed).

    The radius spans two decades (nearly straight when cool), so the radius
    axis is logarithmic; a straight body (infinite radius) leaves a gap. The
    paper's figure also shades the measured mean +- standard deviation; it
    prints no numbers for them, so only the model is drawn.
    """
    n = max(1, len(result.curves))
    fig = Figure(figsize=(4.6, 2.9 * n), layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(n, 1, sharex=True, squeeze=False)[:, 0]
    for ax, (with_g, without) in zip(axes, result.curves):
        m = with_g.manipulator
        for curve, style, label in ((with_g, "-", "model, gravity (upright)"), (without, "--", "model, no gravity")):
            radii_mm = np.where(np.isfinite(curve.radii_m), curve.radii_m * 1e3, np.nan)
            ax.plot(
                curve.temperatures_c, radii_mm, linestyle=style, color="black", marker=".", markersize=3, label=label
            )
        published = result.experiment.published_data
        if published is not None:
            for p in published:
                if p.label.startswith(m.section):
                    mean = [v * 1e3 for v in p.mean]
                    std = [v * 1e3 for v in p.std]
                    ax.fill_between(
                        p.temperatures_c,
                        [a - b for a, b in zip(mean, std)],
                        [a + b for a, b in zip(mean, std)],
                        color="0.8",
                        label=f"experiment {p.label}",
                    )
        ax.set_yscale("log")
        title = m.label
        if m.precurvature_is_assumption and m.precurvature_radius_m is not None:
            title += f"; pre-curvature radius {m.precurvature_radius_m * 1e3:g} mm assumed"
        ax.set_title(title, fontsize="small")
        ax.set_ylabel("Radius [mm]")
        ax.grid(True, which="both", linewidth=0.3)
        ax.legend(fontsize="small", loc="upper right")
    axes[-1].set_xlabel("Temperature [°C]")
    if result.experiment.published_data is None:
        fig.suptitle("Model prediction (the paper prints no numeric data for Fig. 6)", fontsize="small")
    return fig


def save_png(fig: Figure, path: str | os.PathLike[str], dpi: int = 150) -> Path:
    """Save ``fig`` as a PNG at ``path`` (parent directories created); return the path."""
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, format="png", dpi=dpi)
    return out


def _outline_angles(section: Section) -> list[float]:
    """Body-frame angles [rad] of the edge lines drawn along the body: the four
    corners of a rectangle, eight directions otherwise."""
    if section.kind == "rectangle":
        area, ix, iy, _ = section.properties
        half_w, half_h = 0.5 * math.sqrt(12.0 * iy / area), 0.5 * math.sqrt(12.0 * ix / area)
        c = math.atan2(half_h, half_w)
        return [c, math.pi - c, math.pi + c, 2.0 * math.pi - c]
    return [k * math.pi / 4.0 for k in range(8)]


_DEFAULT_VIEW = (15.0, -60.0)


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
    from . import _validate as V
    from .rod import Solution as _Solution

    V.instance("solution", solution, _Solution, "a tcarod.Solution")
    rings = V.integer("rings", rings, 0, 1000)
    if title is not None and not isinstance(title, str):
        raise TypeError(f"title must be a str, not {type(title).__name__}")
    view_given = view is not _DEFAULT_VIEW
    view = (V.real("view[0] (elevation)", view[0], unit="deg"), V.real("view[1] (azimuth)", view[1], unit="deg"))
    first = True
    if ax is None:
        fig = Figure(figsize=(5.0, 5.0), layout="constrained")
        FigureCanvasAgg(fig)
        ax = fig.add_subplot(projection="3d")
    else:
        if not hasattr(ax, "set_zlim"):
            raise TypeError(f"ax must be a 3-D matplotlib axes (projection='3d'), not {type(ax).__name__}")
        first = getattr(ax, "_tcarod_bounds", None) is None
    figure = ax.get_figure()
    if not isinstance(figure, Figure):
        raise ValueError("ax: must belong to a matplotlib Figure")
    had_title = bool(ax.get_title())
    mm = 1e3
    pos = solution.positions
    rot = solution.rotations
    section = solution.robot.body.section
    ax.plot(
        pos[:, 0] * mm, pos[:, 1] * mm, pos[:, 2] * mm, "k--", linewidth=1.0, label="centre line", gid="centre-line"
    )
    points = [pos * mm]

    def edge_point(theta: float) -> npt.NDArray[np.float64]:
        r = section.edge_distance(theta)
        return np.array([r * math.cos(theta), r * math.sin(theta), 0.0])

    # edge lines along the body
    for k, theta in enumerate(_outline_angles(section)):
        pts = (pos + rot @ edge_point(theta)) * mm
        points.append(pts)
        ax.plot(
            pts[:, 0],
            pts[:, 1],
            pts[:, 2],
            color="0.55",
            linewidth=0.8,
            label="body outline" if k == 0 else None,
            gid=f"outline-{k}",
        )
    # cross-section rings at evenly spaced nodes (base and tip included)
    ring_angles = np.linspace(0.0, 2.0 * math.pi, 73)
    ring_local = np.array([edge_point(float(t)) for t in ring_angles])  # (73, 3), body frame
    n = len(solution.s)
    for k, i in enumerate(sorted({round(j) for j in np.linspace(0, n - 1, max(2, rings))})):
        ring = (pos[i] + ring_local @ rot[i].T) * mm
        ax.plot(ring[:, 0], ring[:, 1], ring[:, 2], color="0.55", linewidth=0.8, gid=f"ring-{k}")
    # actuators
    colours = [f"C{k}" for k in range(10)]
    for k, (path, tension) in enumerate(zip(solution.actuator_paths, solution.tensions)):
        p = path * mm
        points.append(p)
        ax.plot(
            p[:, 0],
            p[:, 1],
            p[:, 2],
            color=colours[k % len(colours)],
            linewidth=2.0,
            label=f"actuator {k}: {tension * 1e3:.1f} mN",
            gid=f"actuator-{k}",
        )
    # equal aspect: a cube around the drawn points (of every overlaid shape)
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
    if first or view_given:
        ax.view_init(elev=view[0], azim=view[1])
    names = [a.input_name for a in solution.robot.actuators]
    inputs = ", ".join(f"{name} {x:g}" for name, x in zip(names, solution.inputs))
    if title is not None:
        ax.set_title(title, fontsize="small")
    elif not had_title:
        ax.set_title(inputs or "no actuators", fontsize="small")
    # one legend entry per label, however many shapes share the axes
    handles, labels = ax.get_legend_handles_labels()
    unique: dict[str, object] = {}
    for h, lab in zip(handles, labels):
        unique.setdefault(lab, h)
    ax.legend(list(unique.values()), list(unique.keys()), fontsize="x-small", loc="upper left")
    return figure
