"""Every plot of tcarod, in one place (needs the ``plot`` extra, matplotlib).

* :mod:`~tcarod.plotting.solution`: the 3-D shape of a forward solution
  (:func:`plot_solution`, also ``Solution.plot()``);
* :mod:`~tcarod.plotting.paper`: the paper's experiments (Fig. 5, Fig. 6,
  Fig. 8, Table I), drawn by each result's ``plot(path)``;
* :mod:`~tcarod.plotting.models`: workspace maps, thermal step responses and
  shape trajectories.

Plots take results and draw them; nothing in the API or the models imports
this package (the arrows run plotting -> models -> API). Figures are built
with matplotlib's object-oriented API on the Agg canvas, never ``pyplot``.
"""

from __future__ import annotations

from .._optional import require

require("matplotlib")  # one clear line naming the `plot` extra if it is missing

from ._figure import new_figure, save_png  # noqa: E402
from .models import plot_shape_trajectory, plot_step_response, plot_workspace, save_trajectory_frames  # noqa: E402
from .paper import plot_fig5, plot_fig6, plot_fig8, plot_table1  # noqa: E402
from .solution import plot_solution  # noqa: E402

__all__ = [
    "new_figure",
    "plot_fig5",
    "plot_fig6",
    "plot_fig8",
    "plot_shape_trajectory",
    "plot_solution",
    "plot_step_response",
    "plot_table1",
    "plot_workspace",
    "save_png",
    "save_trajectory_frames",
]
