"""Plots of the paper's experiments in the paper's style (matplotlib).

Figures are built with matplotlib's object-oriented API (``Figure`` rendered by
the Agg canvas), never through ``pyplot``: nothing here needs a display or
changes the user's global matplotlib backend.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

if TYPE_CHECKING:
    from .experiments import Fig5Result

__all__ = ["plot_fig5", "save_png"]

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


def save_png(fig: Figure, path: str | os.PathLike[str], dpi: int = 150) -> Path:
    """Save ``fig`` as a PNG at ``path`` (parent directories created); return the path."""
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, format="png", dpi=dpi)
    return out
