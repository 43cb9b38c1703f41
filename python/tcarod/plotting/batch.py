"""The tip trajectory of a batch of forward solves (``BatchResult.plot_tips()``
calls :func:`plot_tips`)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.figure import Figure

from ._figure import new_figure

if TYPE_CHECKING:
    from ..batch import BatchResult

__all__ = ["plot_tips"]

_MM = 1e3


def plot_tips(result: BatchResult, *, shapes: int = 5, title: str | None = None) -> Figure:
    """Draw the tips of a batch in 3-D [mm], joined in row order.

    Rows that did not converge are left out (the line breaks there). With a
    stability verdict (``solve_batch(stability="report")``, the default) the
    unstable tips are marked with red crosses apart from the stable ones.
    When the batch kept its shapes (``shapes=True``), ``shapes`` centre
    lines evenly spread over the converged rows are drawn too.

    Parameters
    ----------
    result : BatchResult
        The batch (``tcarod.batch.solve_batch``).
    shapes : int, optional
        How many centre lines to draw (0 to 1000, default 5) when the batch
        kept shapes; ignored otherwise.
    title : str, optional
        The axes' title (default: the number of rows).

    Returns
    -------
    matplotlib.figure.Figure
        A 6 x 5 inch figure on the Agg canvas; ``fig.savefig(path)`` saves it.

    Raises
    ------
    TypeError
        If ``shapes`` is not an int.
    ValueError
        If ``shapes`` is outside 0 to 1000, or no row converged.

    Examples
    --------
    >>> import numpy as np
    >>> from tcarod.batch import fig6_square_robot, solve_batch
    >>> temps = np.linspace(25.0, 80.0, 12)
    >>> res = solve_batch(fig6_square_robot(), np.column_stack([temps, np.full(12, 25.0)]), shapes=True)
    >>> fig = res.plot_tips()
    >>> fig.axes[0].get_xlabel()
    'x [mm]'
    """
    if isinstance(shapes, bool) or not isinstance(shapes, (int, np.integer)):
        raise TypeError(f"shapes must be an int, not {type(shapes).__name__}")
    if not 0 <= shapes <= 1000:
        raise ValueError(f"shapes: {shapes} centre lines, allowed 0 to 1000")
    ok = np.asarray(result.converged, dtype=bool)
    if not ok.any():
        raise ValueError("result: no row converged, so there is no tip to draw")
    tips = np.where(ok[:, None], result.tip_positions, np.nan) * _MM  # NaN breaks the line
    fig = new_figure(6.0, 5.0)
    ax: Any = fig.add_subplot(projection="3d")
    ax.plot(tips[:, 0], tips[:, 1], tips[:, 2], color="C0", linewidth=1.2, label="tip trajectory", gid="tips")
    stable = result.stable
    if stable is not None:
        bad = ok & ~np.asarray(stable, dtype=bool)
        if bad.any():
            ax.scatter(*tips[bad].T, color="C3", marker="x", label="unstable", gid="unstable")
    first, last = np.flatnonzero(ok)[[0, -1]]
    ax.scatter(*tips[first], color="C2", marker="o", label=f"row {first}", gid="first")
    ax.scatter(*tips[last], color="k", marker="s", label=f"row {last}", gid="last")
    if result.positions is not None and shapes > 0:
        rows = np.flatnonzero(ok)
        for j in np.unique(rows[np.linspace(0, rows.size - 1, min(shapes, rows.size)).round().astype(int)]):
            p = result.positions[j] * _MM
            ax.plot(p[:, 0], p[:, 1], p[:, 2], color="0.6", linewidth=0.8, gid=f"shape-{j}")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_zlabel("z [mm]")
    ax.set_title(title if title is not None else f"tips of {len(result)} solves")
    ax.legend(loc="upper left", fontsize="small")
    return fig
