"""What every plot shares: a new Agg ``Figure`` and PNG output.

Figures are built with matplotlib's object-oriented API (``Figure`` rendered by
the Agg canvas), never through ``pyplot``: nothing here needs a display or
changes the user's global matplotlib backend.
"""

from __future__ import annotations

import os
from pathlib import Path

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

__all__ = ["new_figure", "save_png"]


def new_figure(width_in: float, height_in: float) -> Figure:
    """A constrained-layout ``Figure`` of ``width_in`` x ``height_in`` inches on an Agg canvas."""
    fig = Figure(figsize=(width_in, height_in), layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def save_png(fig: Figure, path: str | os.PathLike[str], dpi: int = 150) -> Path:
    """Save ``fig`` as a PNG at ``path`` (parent directories created); return the path."""
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, format="png", dpi=dpi)
    return out
