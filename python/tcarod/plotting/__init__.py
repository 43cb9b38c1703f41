"""Every plot of tcarod, in one place (needs the ``plot`` extra, matplotlib).

* :mod:`~tcarod.plotting.solution`: the shape of a forward solution in 3-D
  or as a side view (:func:`plot_solution`, also ``Solution.plot()``);
* :mod:`~tcarod.plotting.interactive`: the same shape as an interactive
  plotly figure for notebooks (``view="interactive"``; the ``interactive``
  extra);
* :mod:`~tcarod.plotting.paper`: the paper's experiments (Fig. 5, Fig. 6,
  Fig. 8, Table I), drawn by each result's ``plot(path)``;
* :mod:`~tcarod.plotting.models`: workspace maps, thermal step responses and
  shape trajectories.

Plots take results and draw them; nothing in the API or the models imports
this package (the arrows run plotting -> models -> API). Figures are built
with matplotlib's object-oriented API. Where a figure lives: when
``matplotlib.pyplot`` is imported (a script that calls ``plt.show()``) it is
made by ``pyplot.figure``, so ``fig.show()`` and ``plt.show()`` work and
``plt.close(fig)`` releases it; otherwise, and in Jupyter's inline backend,
it is a plain figure on the Agg canvas, which needs no display and is shown
once as a cell's result. Figures drawn only to be written to PNG files are
closed after writing (:func:`save_png`).
"""

from __future__ import annotations

from .._optional import require

require("matplotlib")  # one clear line naming the `plot` extra if it is missing

from ._figure import detached, new_figure, save_png, uses_pyplot  # noqa: E402
from .models import plot_shape_trajectory, plot_step_response, plot_workspace, save_trajectory_frames  # noqa: E402
from .paper import plot_fig5, plot_fig6, plot_fig8, plot_table1  # noqa: E402
from .solution import plot_solution  # noqa: E402

__all__ = [
    "detached",
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
    "uses_pyplot",
]
