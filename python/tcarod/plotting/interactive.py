"""Interactive 3-D view of a forward solution for notebooks (plotly).

Needs plotly (the ``interactive`` extra: ``pip install 'tcarod[interactive]'``);
reached through ``plot_solution(sol, view="interactive")`` or
``plot_solution(sol, backend="plotly")``. The figure rotates and zooms in the
notebook and in the HTML it writes (``fig.write_html(path)``).
"""

from __future__ import annotations

import importlib
from typing import Any

from .._optional import MissingDependencyError
from ..rod import Solution
from ._shapes import input_title, shape_lines

__all__ = ["plot_solution_plotly"]


def _graph_objects() -> Any:
    """``plotly.graph_objects``, or an ImportError naming the extra that installs it."""
    try:
        return importlib.import_module("plotly.graph_objects")
    except ImportError as exc:
        raise MissingDependencyError(
            "plotly is needed for the interactive view and is not installed: pip install 'tcarod[interactive]'"
        ) from exc


def plot_solution_plotly(solution: Solution, *, rings: int = 5, title: str | None = None) -> Any:
    """The shape of ``solution`` as an interactive plotly 3-D figure, axes in mm.

    The same lines as :func:`tcarod.plotting.plot_solution`: centre line
    (dashed), body outline (edge lines and ``rings`` rings), each actuator
    with its tension [mN] in the legend; equal aspect in x, y, z.

    Parameters
    ----------
    solution : Solution
        A forward solution.
    rings : int
        Number of cross-section rings (0 to 1000).
    title : str, optional
        Title; default the inputs with their units.

    Returns
    -------
    plotly.graph_objects.Figure
        The figure; in a notebook it rotates and zooms.

    Raises
    ------
    ImportError
        If plotly is not installed (the message names ``tcarod[interactive]``).

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> from tcarod.plotting.interactive import plot_solution_plotly
    >>> fig = plot_solution_plotly(fig6_square_robot().solve([100.0, 100.0], steps=20))
    >>> fig.layout.scene.xaxis.title.text
    'x [mm]'
    """
    go = _graph_objects()
    fig = go.Figure()
    for gid, label, p in shape_lines(solution, rings):
        if gid == "centre-line":
            line: dict[str, Any] = {"color": "black", "width": 3, "dash": "dash"}
        elif gid.startswith("actuator-"):
            line = {"width": 6}
        else:
            line = {"color": "rgb(140,140,140)", "width": 2}
        fig.add_trace(
            go.Scatter3d(
                x=p[:, 0],
                y=p[:, 1],
                z=p[:, 2],
                mode="lines",
                line=line,
                name=label if label is not None else gid,
                legendgroup="body outline" if gid.startswith(("outline", "ring")) else gid,
                showlegend=label is not None,
                hovertemplate="x %{x:.2f} mm<br>y %{y:.2f} mm<br>z %{z:.2f} mm",
            )
        )
    fig.update_layout(
        title=title if title is not None else input_title(solution),
        scene={
            "xaxis_title": "x [mm]",
            "yaxis_title": "y [mm]",
            "zaxis_title": "z [mm]",
            "aspectmode": "data",
        },
        legend={"font": {"size": 10}},
        margin={"l": 0, "r": 0, "t": 40, "b": 0},
    )
    return fig
