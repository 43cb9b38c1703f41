"""Plots of the paper's experiments in the paper's style.

Each function takes an experiment's result (duck-typed: this package imports
nothing from :mod:`tcarod.paper`, which calls it from ``Result.plot(path)``)
and returns a matplotlib ``Figure``.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure

from ._figure import new_figure

__all__ = ["plot_fig5", "plot_fig6", "plot_fig8", "plot_table1"]

_LOAD_STYLES = ("-", "--", "-.", ":")


def _shade_published(ax: Any, published: Any, prefix: str) -> None:
    """Shade the measured mean +- standard deviation [mm] of each published
    curve whose label starts with ``prefix`` (``published``: ``None`` or
    :class:`tcarod.paper._common.PublishedCurve` objects, values in m)."""
    for p in published or ():
        if p.label.startswith(prefix):
            mean = [v * 1e3 for v in p.mean]
            std = [v * 1e3 for v in p.std]
            low = [a - b for a, b in zip(mean, std)]
            high = [a + b for a, b in zip(mean, std)]
            ax.fill_between(p.temperatures_c, low, high, color="0.8", label=f"experiment {p.label}")


def plot_fig5(result: Any) -> Figure:
    """Fig. 5: TCA displacement [mm] against temperature [C].

    One panel per TCA (3 and 4 threads), one line per load, the onset of
    extension marked. The paper's figure also shades the measured mean +-
    standard deviation; it prints no numbers for them, so only the model is
    drawn unless the experiment carries published data.

    Parameters
    ----------
    result : Fig5Result
        A prediction of :mod:`tcarod.paper.fig5`.

    Returns
    -------
    matplotlib.figure.Figure
        Two panels.

    Examples
    --------
    >>> import dataclasses
    >>> from tcarod.paper.fig5 import FIG5
    >>> from tcarod.plotting import plot_fig5
    >>> result = dataclasses.replace(FIG5, temperatures_c=(25.0, 90.0, 160.0)).predict()
    >>> fig = plot_fig5(result)
    >>> len(fig.axes), fig.axes[0].get_xlabel()
    (2, 'Temperature [°C]')
    """
    tca_labels: list[str] = []
    for c in result.curves:
        if c.case.tca.label not in tca_labels:
            tca_labels.append(c.case.tca.label)
    fig = new_figure(4.0 * max(1, len(tca_labels)), 3.4)
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
        _shade_published(ax, result.experiment.published_data, tca_label)
        ax.set_title(f"Extension TCA, {tca_label}")
        ax.set_xlabel("Temperature [°C]")
        ax.grid(True, linewidth=0.3)
        ax.legend(fontsize="small", loc="upper left")
    axes[0].set_ylabel("Displacement [mm]")
    if result.experiment.published_data is None:
        fig.suptitle("Model prediction (the paper prints no numeric data for Fig. 5)", fontsize="small")
    return fig


def plot_fig6(result: Any) -> Figure:
    """Fig. 6: inner-edge bending radius [mm] against temperature [C].

    One panel per manipulator (circle above, square below, as in the paper),
    the model with gravity (upright, as in the oven; solid) and without
    (dashed). The radius spans two decades (nearly straight when cool), so
    the radius axis is logarithmic; a straight body (infinite radius) leaves
    a gap. The paper's figure also shades the measured mean +- standard
    deviation; it prints no numbers for them, so only the model is drawn.

    Parameters
    ----------
    result : Fig6Result
        A prediction of :mod:`tcarod.paper.fig6`.

    Returns
    -------
    matplotlib.figure.Figure
        One panel per manipulator.

    Examples
    --------
    >>> import dataclasses
    >>> from tcarod.paper.fig6 import FIG6
    >>> from tcarod.plotting import plot_fig6
    >>> result = dataclasses.replace(FIG6, temperatures_c=(25.0, 90.0, 160.0), steps=20).predict(readings=False)
    >>> len(plot_fig6(result).axes)
    2
    """
    n = max(1, len(result.curves))
    fig = new_figure(4.6, 2.9 * n)
    axes = fig.subplots(n, 1, sharex=True, squeeze=False)[:, 0]
    for ax, (with_g, without) in zip(axes, result.curves):
        m = with_g.manipulator
        for curve, style, label in ((with_g, "-", "model, gravity (upright)"), (without, "--", "model, no gravity")):
            radii_mm = np.where(np.isfinite(curve.radii_m), curve.radii_m * 1e3, np.nan)
            ax.plot(
                curve.temperatures_c, radii_mm, linestyle=style, color="black", marker=".", markersize=3, label=label
            )
        _shade_published(ax, result.experiment.published_data, m.section)
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


def plot_fig8(result: Any) -> Figure:
    """Fig. 8: blocked-tip force [mN] against temperature [C].

    The incremental eq-43 cross-checks are marked.

    Parameters
    ----------
    result : Fig8Result
        A prediction of :mod:`tcarod.paper.fig8`.

    Returns
    -------
    matplotlib.figure.Figure
        One panel.

    Examples
    --------
    >>> import dataclasses
    >>> from tcarod.paper.fig8 import FIG8
    >>> from tcarod.plotting import plot_fig8
    >>> small = dataclasses.replace(FIG8, temperatures_c=(25.0, 90.0, 160.0), cross_check_temperatures_c=(100.0,))
    >>> plot_fig8(small.predict()).axes[0].get_ylabel()
    'Tip force [mN]'
    """
    exp = result.experiment
    fig = new_figure(4.5, 3.4)
    ax = fig.add_subplot()
    ax.plot(result.temperatures_c, result.forces_n * 1e3, "k-", marker=".", label="model (direct solve)")
    ax.plot(
        [c.temperature_c for c in result.cross_checks],
        [c.force_n * 1e3 for c in result.cross_checks],
        "o",
        markerfacecolor="none",
        color="tab:red",
        label="incremental eq 43 check",
    )
    ax.axvline(exp.taut_temperature_c, color="0.6", linestyle=":", label=f"wire taut ({exp.taut_temperature_c:g} °C)")
    ax.set_xlabel("Temperature [°C]")
    ax.set_ylabel("Tip force [mN]")
    ax.set_title("Fig. 8: blocked-tip force, 26 mm manipulator", fontsize="medium")
    ax.grid(True, linewidth=0.3)
    ax.legend(fontsize="small", loc="upper left")
    fig.suptitle("Model prediction (the paper prints no data points; its rms: 0.74 mN)", fontsize="small")
    return fig


def plot_table1(result: Any) -> Figure:
    """Table I: grip temperature [C] against mass [g].

    tcarod's prediction, the experiment, the paper's model and the first
    plausible identified reading (when the result carries identifications).

    Parameters
    ----------
    result : Table1Result
        A prediction of :mod:`tcarod.paper.table1`.

    Returns
    -------
    matplotlib.figure.Figure
        One panel.

    Examples
    --------
    >>> from tcarod.paper.table1 import TABLE1
    >>> from tcarod.plotting import plot_table1
    >>> plot_table1(TABLE1.predict()).axes[0].get_xlabel()
    'Grasped mass [g]'
    """
    fig = new_figure(4.8, 3.6)
    ax = fig.add_subplot()
    rows = result.rows
    grams = [r.mass_kg * 1e3 for r in rows]
    ax.plot(grams, [r.experiment_c for r in rows], "ks", label="experiment (firm grip)")
    ax.plot(grams, [r.paper_prediction_c for r in rows], "k^--", markerfacecolor="none", label="paper's model")
    ax.plot(grams, [r.predicted_c for r in rows], "o-", color="tab:red", label="tcarod (defaults)")
    for i in result.identifications:
        if i.fitted_to == "paper_model" and i.all_plausible and len(i.parameters) == 2:
            ax.plot(grams, i.fitted_c, ":", label=f"identified ({i.reading.turns_reading}, {i.reading.material})")
            break
    ax.set_xlabel("Grasped mass [g]")
    ax.set_ylabel("Grip temperature [°C]")
    ax.set_xticks(grams)
    ax.set_title("Table I: grip temperature", fontsize="medium")
    ax.grid(True, linewidth=0.3)
    ax.legend(fontsize="small", loc="lower right")
    return fig
