"""What every plot shares: a new ``Figure`` and PNG output.

Where a figure lives:

* **pyplot in use** (``matplotlib.pyplot`` imported, as in a script that
  calls ``plt.show()``): the figure is made by ``pyplot.figure`` so that
  pyplot manages it: ``fig.show()`` and ``plt.show()`` open it with the
  current backend (under the non-interactive Agg backend of a headless run,
  ``fig.show()`` only warns, as for any pyplot figure), and it stays open
  until ``plt.close(fig)``.
* **otherwise**, and in Jupyter's inline backend: a plain ``Figure`` on an Agg
  canvas. Nothing needs a display or changes the global backend; in a
  notebook the figure returned by the last line of a cell is shown once, by
  the display formatter (a pyplot figure would be shown a second time when
  the cell ends).

Figures drawn only to be written to a file (``Result.plot(path)``,
``tcarod reproduce``, animation frames, notebook previews) are never left
open in pyplot: :func:`save_png` closes a pyplot figure after writing it
unless told otherwise, and :func:`detached` makes figures outside pyplot.
"""

from __future__ import annotations

import contextlib
import os
import sys
from collections.abc import Iterator
from pathlib import Path

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

__all__ = ["detached", "is_pyplot_figure", "new_figure", "save_png", "uses_pyplot"]

_DETACHED = [0]  # depth of active ``detached()`` blocks


@contextlib.contextmanager
def detached() -> Iterator[None]:
    """Make figures outside pyplot inside this block, whatever the backend.

    For figures drawn only to be saved: :func:`new_figure` then draws on an
    Agg canvas that pyplot never sees, so nothing is left open.

    Yields
    ------
    None

    Examples
    --------
    >>> from tcarod.plotting import detached, new_figure, uses_pyplot
    >>> with detached():
    ...     fig = new_figure(3.0, 2.0)      # [in]
    ...     inside = uses_pyplot()
    >>> inside, fig.canvas.manager is None
    (False, True)
    """
    _DETACHED[0] += 1
    try:
        yield
    finally:
        _DETACHED[0] -= 1


def uses_pyplot() -> bool:
    """Whether :func:`new_figure` makes pyplot figures now.

    Returns
    -------
    bool
        ``True`` if ``matplotlib.pyplot`` is imported, its backend is not
        Jupyter's inline backend, and no :func:`detached` block is active.

    Examples
    --------
    >>> from tcarod.plotting import detached, uses_pyplot
    >>> with detached():
    ...     uses_pyplot()
    False
    """
    if _DETACHED[0] or "matplotlib.pyplot" not in sys.modules:
        return False
    import matplotlib

    return "inline" not in str(matplotlib.get_backend()).lower()


def is_pyplot_figure(fig: Figure) -> bool:
    """Whether pyplot manages ``fig`` (it has a figure manager, so ``fig.show()`` works).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        A figure.

    Returns
    -------
    bool
        ``True`` for a pyplot figure.

    Examples
    --------
    >>> from tcarod.plotting import detached, new_figure
    >>> from tcarod.plotting._figure import is_pyplot_figure
    >>> with detached():
    ...     is_pyplot_figure(new_figure(3.0, 2.0))
    False
    """
    return getattr(fig.canvas, "manager", None) is not None


def new_figure(width_in: float, height_in: float) -> Figure:
    """A constrained-layout ``Figure`` of ``width_in`` x ``height_in`` inches.

    Made by ``pyplot.figure`` when pyplot is in use (:func:`uses_pyplot`),
    otherwise on an Agg canvas (see the module docstring).

    Parameters
    ----------
    width_in, height_in : float
        Size [in].

    Returns
    -------
    matplotlib.figure.Figure
        The empty figure.

    Examples
    --------
    >>> from tcarod.plotting import new_figure
    >>> fig = new_figure(4.0, 3.0)
    >>> fig.get_size_inches().tolist()       # [in]
    [4.0, 3.0]
    """
    if uses_pyplot():
        import matplotlib.pyplot as plt

        return plt.figure(figsize=(width_in, height_in), layout="constrained")
    fig = Figure(figsize=(width_in, height_in), layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def save_png(fig: Figure, path: str | os.PathLike[str], dpi: int = 150, *, keep_open: bool = False) -> Path:
    """Save ``fig`` as a PNG at ``path``, creating parent directories.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure to write.
    path : str or os.PathLike
        Output file.
    dpi : int
        Resolution [dots per inch].
    keep_open : bool
        Keep a pyplot figure open after writing it; by default it is closed
        (``plt.close(fig)``), since tcarod's writers discard their figures.
        A figure outside pyplot is never affected.

    Returns
    -------
    pathlib.Path
        The path written.

    Examples
    --------
    >>> from tcarod.plotting import new_figure, save_png
    >>> fig = new_figure(2.0, 2.0)
    >>> save_png(fig, "out/empty.png", dpi=50).stat().st_size > 0
    True
    """
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, format="png", dpi=dpi)
    if not keep_open and is_pyplot_figure(fig) and "matplotlib.pyplot" in sys.modules:
        import matplotlib.pyplot as plt

        plt.close(fig)
    return out
