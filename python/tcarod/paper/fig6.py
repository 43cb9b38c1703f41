"""Fig. 6 of the paper (Section V-B): bending radius of TCA-actuated soft
manipulators against temperature.

Two EcoFlex 10 manipulators (``psi = 1040 kg/m^3``, ``E_B = 37.8 kPa``,
Poisson 0.5), 40 mm long, each with the paper's manipulator TCA
(``D = 1.7 mm``, ``alpha0 = 15 deg``, ``N = 76.4`` turns, coiled length = body
length, extension type), heated from 25 to 160 C in 5 C steps:

* **circle** (Fig. 6 top): solid circle of 8 mm diameter, one TCA 3 mm off
  the axis at body ``+x``, *pre-curved* toward ``-x`` (the paper: "the
  manipulator with a circular cross section has some initial bending");
* **square** (Fig. 6 bottom): 10 mm square, a U-shaped TCA = two TCAs
  (the legs) 3 mm off the neutral layer on the same side (``x = +3 mm``).

Assumptions (the paper does not print these; they match ``src/experiments.rs``):

* the circle's pre-curvature radius is **0.2 m** (:data:`CIRCLE_PRECURVATURE_RADIUS_M`),
  an assumed value: the paper prints none;
* the U legs sit at ``y = +-2.5 mm`` (:data:`U_LEG_HALF_SPACING_M`); any
  symmetric spacing gives the same planar bending.

The measured quantity is the paper's bending radius: the circle through three
points on the inner (concave) edge -- base, middle, tip
(:func:`tcarod.inner_edge_radius`). The manipulators stood base-down in an
oven, so the model runs upright with gravity ``(0, 0, -9.81) m/s^2`` and, for
comparison, without gravity. Each sweep is solved warm-started
(:meth:`Robot.sweep`) and, as a check, cold (every temperature from the
reference guess); both iteration counts are reported.

The paper prints no numeric data for Fig. 6 (``published_data = None``).
"""

from __future__ import annotations

import math
import os
import textwrap
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Final, Literal

import numpy as np
import numpy.typing as npt

from .. import _core
from ..models.manipulators import (
    DEFAULT_TURNS_READING,
    PAPER_CONSTANTS,
    TCA_OFFSET_M,
    TURNS_READINGS,
    U_LEG_HALF_SPACING_M,
    UPRIGHT,
    TurnsReading,
    manipulator_tca,
)
from ..rod import Robot, Solution, inner_edge_radius
from ._common import PAPER_SOURCE, identity_json, PAPER_TEMPERATURES_C, PublishedCurve, published_json
from ._common import finite_or_none, mm_text, relative_difference

__all__ = [
    "CIRCLE_PRECURVATURE_RADIUS_M",
    "FIG6",
    "Fig6Curve",
    "Fig6Experiment",
    "Fig6Manipulator",
    "Fig6Result",
    "U_LEG_HALF_SPACING_M",
    "manipulator_tca",
    "predict_fig6",
]

FloatArray = npt.NDArray[np.float64]

#: ASSUMPTION: pre-curvature radius of the circular manipulator [m]; the paper
#: says it was initially bent but prints no value.
CIRCLE_PRECURVATURE_RADIUS_M: Final[float] = PAPER_CONSTANTS["circle_precurvature_radius"]

_ASSUMPTIONS: Final[tuple[str, ...]] = (
    f"The circular manipulator's pre-curvature radius is {CIRCLE_PRECURVATURE_RADIUS_M} m (bent toward "
    "-x, away from its TCA), an ASSUMED value: the paper states only that it had some initial bending.",
    f"The U-shaped TCA's two legs sit at x = +{TCA_OFFSET_M * 1e3:g} mm, y = +-{U_LEG_HALF_SPACING_M * 1e3:g} mm "
    "(the leg spacing is not printed; any symmetric spacing gives the same planar bending).",
    "Each TCA (and each U leg) runs the whole body length, anchored at base and tip.",
    "Turns: 76.4 per fabricated TCA (default reading 'per_tca'): the circle's single TCA has 76.4, each "
    "leg of the square's U-shaped TCA 38.2 (tcarod.models.manipulators; the other readings are shown beside).",
    "TCA material: Material.silver_coated_nylon() (values the paper does not print; see docs/choices.md).",
)


@dataclass(frozen=True)
class Fig6Manipulator:
    """One manipulator of Fig. 6, lengths in m.

    ``section`` is ``"circle"`` (``size_m`` = diameter) or ``"square"``
    (``size_m`` = side). ``tca_y_m`` lists the body-frame ``y`` [m] of each
    TCA leg, all at ``x = tca_offset_m``. ``precurvature_radius_m``: radius
    [m] of the reference shape, bent toward ``-x`` (``None``: straight).

    Examples
    --------
    >>> from tcarod.paper.fig6 import FIG6
    >>> FIG6.manipulators[1].section, FIG6.manipulators[1].size_m, FIG6.manipulators[1].tca_y_m      # [m]
    ('square', 0.01, (0.0025, -0.0025))
    """

    label: str
    #: The core's fixture (``src/experiments.rs``) that builds the robot.
    fixture: Literal["fig6_circle", "fig6_square"]
    section: Literal["circle", "square"]
    size_m: float
    tca_y_m: tuple[float, ...]
    #: Both manipulators of Fig. 6 are 40 mm long, their TCAs 3 mm off the axis.
    length_m: float = PAPER_CONSTANTS["fig6_length"]
    tca_offset_m: float = TCA_OFFSET_M
    precurvature_radius_m: float | None = None
    #: Whether ``precurvature_radius_m`` is an assumption (not printed in the paper).
    precurvature_is_assumption: bool = False

    def robot(self, gravity: bool = True, turns_reading: TurnsReading = DEFAULT_TURNS_READING) -> Robot:
        """The manipulator as a :class:`Robot`, built by the core's fixture.

        Parameters
        ----------
        gravity : bool, optional
            Upright (base down, gravity ``(0, 0, -9.81)`` m/s^2; default), or weightless.
        turns_reading : {"per_tca", "per_leg", "per_length"}, optional
            Each leg has :func:`tcarod.models.manipulators.leg_turns` turns under it.

        Returns
        -------
        Robot
            The manipulator.
        """
        g = UPRIGHT if gravity else (0.0, 0.0, 0.0)
        return _core.fixture_manipulator(self.fixture, gravity=g, turns_reading=turns_reading)


@dataclass(frozen=True)
class Fig6Experiment:
    """Fig. 6: bending radius against temperature of the circular (pre-curved) and square manipulators.

    See the module docstring; :data:`FIG6` is the paper's.

    Examples
    --------
    >>> from tcarod.paper.fig6 import FIG6
    >>> [m.label for m in FIG6.manipulators]
    ['circle (8 mm, pre-curved)', 'square (10 mm, U-shaped TCA)']
    """

    manipulators: tuple[Fig6Manipulator, ...]
    temperatures_c: tuple[float, ...] = PAPER_TEMPERATURES_C
    assumptions: tuple[str, ...] = _ASSUMPTIONS
    #: ``None``: the paper prints no numeric data for Fig. 6.
    published_data: tuple[PublishedCurve, ...] | None = None
    published_data_note: str = "The paper prints no numeric data for Fig. 6, only the plotted curves."
    name: str = "fig6"
    title: str = "Fig. 6: bending radius of the soft manipulators"
    source: str = f"{PAPER_SOURCE}, Section V-B, Fig. 6"
    #: RK4 steps over the body length.
    steps: int = 100
    #: How the printed 76.4 turns apply to a U's legs (:mod:`tcarod.models.manipulators`).
    turns_reading: TurnsReading = DEFAULT_TURNS_READING
    #: Temperatures [C] at which every reading's radius (with gravity) is reported.
    reading_temperatures_c: tuple[float, ...] = (60.0, 100.0, 140.0)

    def predict(self, *, readings: bool = True) -> Fig6Result:
        """Predicted radii; see :func:`predict_fig6`."""
        return predict_fig6(self, readings=readings)


#: The paper's Fig. 6 experiment, 25-160 C in 5 C steps.
FIG6: Final[Fig6Experiment] = Fig6Experiment(
    manipulators=(
        Fig6Manipulator(
            label="circle (8 mm, pre-curved)",
            fixture="fig6_circle",
            section="circle",
            size_m=PAPER_CONSTANTS["circle_diameter"],
            tca_y_m=(0.0,),
            precurvature_radius_m=CIRCLE_PRECURVATURE_RADIUS_M,
            precurvature_is_assumption=True,
        ),
        Fig6Manipulator(
            label="square (10 mm, U-shaped TCA)",
            fixture="fig6_square",
            section="square",
            size_m=PAPER_CONSTANTS["square_side"],
            tca_y_m=(U_LEG_HALF_SPACING_M, -U_LEG_HALF_SPACING_M),
        ),
    ),
)


@dataclass(frozen=True, eq=False)
class Fig6Curve:
    """Prediction of Fig. 6 for one manipulator, with or without gravity.

    Examples
    --------
    >>> import dataclasses
    >>> from tcarod.paper.fig6 import FIG6
    >>> result = dataclasses.replace(FIG6, temperatures_c=(25.0, 90.0, 160.0), steps=20).predict(readings=False)
    >>> curve = result.curves[1][0]     # the square, with gravity
    >>> curve.gravity, (curve.radii_m * 1e3).round(1).tolist()  # inner-edge radius [mm]
    (True, [967.4, 171.8, 55.9])
    """

    manipulator: Fig6Manipulator
    gravity: bool
    temperatures_c: FloatArray
    #: Inner-edge bending radius [m] at each temperature (``inf``: straight).
    radii_m: FloatArray
    #: Tip position [m] at each temperature, shape ``(k, 3)``.
    tip_positions_m: FloatArray
    #: Tension [N] of each TCA leg at each temperature, shape ``(k, n_legs)`` (< 0: pushes).
    tensions_n: FloatArray
    #: Newton iterations per temperature of the warm-started sweep (``Robot.sweep``).
    iterations_warm: tuple[int, ...]
    #: Newton iterations per temperature solved cold (from the reference guess).
    iterations_cold: tuple[int, ...]
    #: Largest relative difference of the cold and warm radii (same equations, same tolerance).
    cold_warm_max_relative_difference: float
    #: The warm-started solutions themselves.
    solutions: tuple[Solution, ...]


@dataclass(frozen=True, eq=False)
class Fig6Result:
    """Predicted Fig. 6: per manipulator, a curve with and one without gravity.

    Examples
    --------
    >>> import dataclasses
    >>> from tcarod.paper.fig6 import FIG6
    >>> result = dataclasses.replace(FIG6, temperatures_c=(25.0, 90.0, 160.0), steps=20).predict(readings=False)
    >>> result.name, len(result.curves), result.temperatures_c.tolist()
    ('fig6', 2, [25.0, 90.0, 160.0])
    """

    experiment: Fig6Experiment
    #: ``(with gravity, without gravity)`` per manipulator, in the experiment's order.
    curves: tuple[tuple[Fig6Curve, Fig6Curve], ...]
    #: ``(manipulator label, turns reading) -> radii [m]`` with gravity at ``reading_temperatures_c``.
    readings: dict[tuple[str, str], tuple[float, ...]] = field(default_factory=dict)

    @property
    def name(self) -> str:
        """Registry name, ``"fig6"``.

        Returns
        -------
        str
        """
        return self.experiment.name

    @property
    def temperatures_c(self) -> FloatArray:
        """Temperatures of the sweep [C], shape ``(k,)``.

        Returns
        -------
        numpy.ndarray
        """
        return np.asarray(self.experiment.temperatures_c, dtype=np.float64)

    def gravity_radius_change_m(self, index: int) -> FloatArray:
        """Radius with gravity minus radius without, for one manipulator [m].

        Parameters
        ----------
        index : int
            The manipulator (0 circle, 1 square).

        Returns
        -------
        numpy.ndarray
            Shape ``(k,)`` [m]; NaN where either radius is infinite.
        """
        with_g, without = self.curves[index]
        diff = np.full(len(with_g.radii_m), np.nan)
        ok = np.isfinite(with_g.radii_m) & np.isfinite(without.radii_m)
        diff[ok] = with_g.radii_m[ok] - without.radii_m[ok]
        return diff

    def table(self) -> str:
        """The prediction as a text table.

        Returns
        -------
        str
            Per manipulator: radius [mm] with and without gravity against
            temperature [C], the change gravity makes, the readings, and the
            Newton iterations of the warm-started sweep and of cold solves.
        """
        exp = self.experiment
        lines = [f"{exp.title} ({exp.source})"]
        lines.append("Inner-edge bending radius (circle through base, middle and tip of the concave edge).")
        for a in exp.assumptions:
            lines.extend(textwrap.wrap(f"Assumption: {a}", width=100))
        head = (
            f"{'T [C]':>6} | {'R gravity [mm]':>14} | {'R no gravity [mm]':>17} | {'gravity change [mm]':>19} | "
            f"{'Newton it. warm g/no-g':>22} | {'cold g/no-g':>11}"
        )
        rule = "-" * len(head)
        for k, (with_g, without) in enumerate(self.curves):
            m = with_g.manipulator
            lines += [
                "",
                f"{m.label}: {m.length_m * 1e3:g} mm long, TCA {m.tca_offset_m * 1e3:g} mm off the axis"
                + (
                    f", pre-curvature radius {m.precurvature_radius_m * 1e3:g} mm (assumed)"
                    if m.precurvature_radius_m is not None
                    else ""
                ),
                rule,
                head,
                rule,
            ]
            change = self.gravity_radius_change_m(k)
            for i, t in enumerate(self.temperatures_c):
                ch = "n/a" if not math.isfinite(change[i]) else f"{change[i] * 1e3:+.2f}"
                its = f"{with_g.iterations_warm[i]}/{without.iterations_warm[i]}"
                cold = f"{with_g.iterations_cold[i]}/{without.iterations_cold[i]}"
                lines.append(
                    f"{t:>6.0f} | {mm_text(with_g.radii_m[i]):>14} | {mm_text(without.radii_m[i]):>17} | {ch:>19} | "
                    f"{its:>22} | {cold:>11}"
                )
            lines.append(rule)
            lines.append(
                f"Newton iterations in total: warm {sum(with_g.iterations_warm)}/{sum(without.iterations_warm)}, "
                f"cold {sum(with_g.iterations_cold)}/{sum(without.iterations_cold)} (gravity/no gravity); "
                f"cold and warm radii agree to "
                f"{max(with_g.cold_warm_max_relative_difference, without.cold_warm_max_relative_difference):.1e} "
                "(relative)."
            )
            lines.append(_gravity_summary(with_g, without))
        lines.append("")
        if self.readings:
            ts = ", ".join(f"{t:g}" for t in exp.reading_temperatures_c)
            lines.append(f"Turns readings (default {exp.turns_reading!r}): radius [mm] with gravity at {ts} C")
            for (label, reading), radii in self.readings.items():
                lines.append(f"  {label:<30} {reading:>10}: " + ", ".join(mm_text(r) for r in radii))
        if exp.published_data is None:
            lines.append(f"Published data: none. {exp.published_data_note}")
        return "\n".join(lines)

    def to_json(self) -> dict[str, Any]:
        """JSON-serialisable prediction, every key naming its unit.

        Returns
        -------
        dict
            Temperatures in C, lengths in m, forces in N; ``null`` for an
            infinite radius (straight body).
        """
        exp = self.experiment
        manipulators = []
        for k, (with_g, without) in enumerate(self.curves):
            m = with_g.manipulator

            def case(c: Fig6Curve) -> dict[str, Any]:
                return {
                    "gravity_m_per_s2": list(UPRIGHT) if c.gravity else [0.0, 0.0, 0.0],
                    "radius_m": [finite_or_none(r) for r in c.radii_m],
                    "tip_position_m": [[float(x) for x in p] for p in c.tip_positions_m],
                    "tension_n": [[float(x) for x in row] for row in c.tensions_n],
                    "newton_iterations_warm": list(c.iterations_warm),
                    "newton_iterations_cold": list(c.iterations_cold),
                    "cold_warm_max_relative_difference": c.cold_warm_max_relative_difference,
                }

            manipulators.append(
                {
                    "label": m.label,
                    "section": m.section,
                    "size_m": m.size_m,
                    "length_m": m.length_m,
                    "tca_offset_m": m.tca_offset_m,
                    "tca_y_m": list(m.tca_y_m),
                    "precurvature_radius_m": m.precurvature_radius_m,
                    "precurvature_is_assumption": m.precurvature_is_assumption,
                    "with_gravity": case(with_g),
                    "without_gravity": case(without),
                    "gravity_radius_change_m": [finite_or_none(d) for d in self.gravity_radius_change_m(k)],
                    "gravity_summary": _gravity_summary(with_g, without),
                }
            )
        return {
            **identity_json(exp),
            "radius_definition": "circle through base, middle and tip points on the inner (concave) edge",
            "assumptions": list(exp.assumptions),
            "temperature_c": [float(t) for t in self.temperatures_c],
            "rk4_steps": exp.steps,
            "turns_reading": exp.turns_reading,
            "readings": [
                {
                    "manipulator": label,
                    "turns_reading": reading,
                    "temperature_c": list(exp.reading_temperatures_c),
                    "radius_with_gravity_m": [finite_or_none(r) for r in radii],
                }
                for (label, reading), radii in self.readings.items()
            ],
            "published_data": published_json(exp.published_data),
            "published_data_note": exp.published_data_note,
            "manipulators": manipulators,
        }

    def plot(self, path: str | os.PathLike[str]) -> Path:
        """Write the Fig. 6 plot (see :func:`tcarod.plotting.plot_fig6`) as PNG to ``path``."""
        from ..plotting import plot_fig6, save_png  # matplotlib only when plotting

        return save_png(plot_fig6(self), path)


def _gravity_summary(with_g: Fig6Curve, without: Fig6Curve) -> str:
    """One sentence: what gravity changes for one manipulator."""
    t = with_g.temperatures_c
    ok = np.isfinite(with_g.radii_m) & np.isfinite(without.radii_m)
    rel = np.full(len(t), np.nan)
    rel[ok] = (with_g.radii_m[ok] - without.radii_m[ok]) / without.radii_m[ok]
    i_hot = len(t) - 1
    text = (
        f"Gravity (body upright) changes the radius by {rel[i_hot] * 100:+.1f}% at {t[i_hot]:.0f} C"
        if ok[i_hot]
        else "Gravity changes the radius"
    )
    if ok.any():
        worst = int(np.nanargmax(np.abs(rel)))
        text += f" and by up to {rel[worst] * 100:+.1f}% (at {t[worst]:.0f} C)"
    r0_g, r0 = with_g.radii_m[0], without.radii_m[0]
    text += f"; at {t[0]:.0f} C the radius is {mm_text(r0_g)} mm with gravity, {mm_text(r0)} mm without."
    return text


def _curve(experiment: Fig6Experiment, m: Fig6Manipulator, gravity: bool) -> Fig6Curve:
    robot = m.robot(gravity, experiment.turns_reading)
    temps = np.asarray(experiment.temperatures_c, dtype=np.float64)
    n = len(m.tca_y_m)
    rows = [[float(t)] * n for t in temps]
    warm = robot.sweep(rows, steps=experiment.steps)
    cold = [robot.solve(row, steps=experiment.steps) for row in rows]
    radii = np.array([inner_edge_radius(s) for s in warm])
    radii_cold = np.array([inner_edge_radius(s) for s in cold])
    return Fig6Curve(
        manipulator=m,
        gravity=gravity,
        temperatures_c=temps,
        radii_m=radii,
        tip_positions_m=np.array([s.tip_position for s in warm]),
        tensions_n=np.array([s.tensions for s in warm]),
        iterations_warm=tuple(s.iterations for s in warm),
        iterations_cold=tuple(s.iterations for s in cold),
        cold_warm_max_relative_difference=relative_difference(radii_cold, radii),
        solutions=tuple(warm),
    )


def predict_fig6(experiment: Fig6Experiment = FIG6, *, readings: bool = True) -> Fig6Result:
    """Bending radius against temperature of every manipulator, with gravity (upright, as in the oven) and without.

    Parameters
    ----------
    experiment : Fig6Experiment, optional
        The set-up (default the paper's, :data:`FIG6`).
    readings : bool, optional
        Also the radius with gravity of every turns reading at ``reading_temperatures_c`` (default).

    Returns
    -------
    Fig6Result
        Radii [m], tips [m] and tensions [N] at each temperature [C].

    Raises
    ------
    ValueError
        A temperature outside the TCA material's range.
    ConvergenceError
        A solve fails.

    Examples
    --------
    >>> import dataclasses
    >>> from tcarod.paper.fig6 import FIG6, predict_fig6
    >>> small = dataclasses.replace(FIG6, temperatures_c=(25.0, 90.0, 160.0), steps=20)    # [C]
    >>> predict_fig6(small, readings=False).gravity_radius_change_m(1).round(4).tolist()   # [m], the square
    [nan, -0.0595, -0.0107]
    """
    curves = tuple((_curve(experiment, m, True), _curve(experiment, m, False)) for m in experiment.manipulators)
    rd: dict[tuple[str, str], tuple[float, ...]] = {}
    if readings:
        for m in experiment.manipulators:
            for reading in TURNS_READINGS:
                robot = m.robot(True, reading)
                sols = robot.sweep(
                    [[t] * len(m.tca_y_m) for t in experiment.reading_temperatures_c], steps=experiment.steps
                )
                rd[(m.label, reading)] = tuple(float(inner_edge_radius(s)) for s in sols)
    return Fig6Result(experiment=experiment, curves=curves, readings=rd)
