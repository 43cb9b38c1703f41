"""Fig. 8 of the paper (Section V-C): blocked-tip force of a TCA manipulator.

The 26 mm square manipulator (10 mm EcoFlex section, U-shaped TCA at body
``x = +3 mm``) stands upright in an oven with gravity. A thin copper wire
tied to its tip runs to a force gauge; it is loose from 25 C to about 55 C
(no force), then taut, and the gauge reads the force the bending tip pulls
with as the temperature rises in 5 C steps. The paper prints no data points,
only the rms difference of 0.74 mN between its model and the mean measured
force.

Blocking geometry (a modelling choice; the paper gives no wire geometry):
the wire becomes taut exactly when the free tip reaches it, assumed at 55 C,
so the block point is the free tip position at 55 C. The wire is horizontal
and pulls the tip toward ``+x``; heating bends the body toward ``-x``, so the
tip presses along ``-x`` against it. A taut wire fixes the tip's
displacement along the wire only (small motions across it are free), which is
the plane contact ``normal . (p(L) - point) = 0`` with ``normal = -x`` of
:mod:`tcarod.inverse`. A wire cannot push: the force is 0 below 55 C.

Method: at each temperature 55..160 C the direct mixed solve
(:func:`tcarod.inverse.blocked_force`, the force is a shooting unknown),
warm-started from the previous temperature; cross-checked at a few
temperatures by the paper's incremental eq-43 method
(:func:`tcarod.inverse.blocked_temperature`), which must return the
temperature from that force.
"""

from __future__ import annotations

import os
import textwrap
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Final

import numpy as np

from ..models.manipulators import (
    PAPER_CONSTANTS,
    DEFAULT_TURNS_READING,
    MATERIAL_PRESETS,
    TURNS_READINGS,
    UPRIGHT,
    TurnsReading,
    material_preset,
    square_manipulator,
)
from ..inverse import blocked_force, blocked_temperature
from ..rod import Robot
from ..tca import Material
from ._common import PAPER_SOURCE, identity_json, PAPER_TEMPERATURES_C, FloatArray

__all__ = ["FIG8", "Fig8CrossCheck", "Fig8Experiment", "Fig8Reading", "Fig8Result", "fig8_forces", "predict_fig8"]

_BLOCKING: Final[str] = (
    "The wire is loose until the free tip reaches it, assumed at 55 C (paper: loose from 25 to "
    "about 55 C); the block point is the free tip position at 55 C. The wire is horizontal and "
    "pulls toward +x, so the tip (bending toward -x when heated) presses along -x; a taut wire "
    "fixes the tip displacement along it only (plane contact, normal -x). Force 0 below 55 C "
    "(a wire cannot push)."
)


@dataclass(frozen=True)
class Fig8Experiment:
    """The Fig. 8 set-up: the blocked-tip force of a 26 mm square manipulator.

    See the module docstring for the blocking geometry; :data:`FIG8` is the
    paper's.

    Examples
    --------
    >>> import dataclasses
    >>> from tcarod.paper.fig8 import FIG8
    >>> small = dataclasses.replace(FIG8, temperatures_c=(25.0, 100.0, 160.0), cross_check_temperatures_c=(100.0,))
    >>> small.length_m, small.taut_temperature_c      # [m], [C]
    (0.026, 55.0)
    """

    length_m: float = PAPER_CONSTANTS["fig8_length"]
    #: Temperature [C] at which the wire becomes taut (the paper: about 55 C).
    taut_temperature_c: float = 55.0
    temperatures_c: tuple[float, ...] = PAPER_TEMPERATURES_C
    #: Temperatures [C] at which the incremental eq-43 method re-derives the temperature from the force.
    cross_check_temperatures_c: tuple[float, ...] = (70.0, 100.0, 130.0, 160.0)
    #: Direction in which the tip presses on the wire (world frame); the wire pulls along its negative.
    normal: tuple[float, float, float] = (-1.0, 0.0, 0.0)
    #: Gravity [m/s^2] in the body-aligned frame: upright.
    gravity_m_per_s2: tuple[float, float, float] = UPRIGHT
    #: The paper's only number for Fig. 8: rms of model minus mean measured force [N].
    published_rms_n: float = 0.74e-3
    #: ``None``: the paper prints no data points for Fig. 8.
    published_data: None = None
    published_data_note: str = (
        "The paper prints no data points for Fig. 8, only the plot and the rms difference "
        "0.74 mN between its model and the mean measured force."
    )
    blocking: str = field(default=_BLOCKING)
    name: str = "fig8"
    title: str = "Fig. 8: blocked-tip force of the 26 mm square manipulator"
    source: str = f"{PAPER_SOURCE}, Section V-C, Fig. 8"

    #: How the printed 76.4 turns apply to the U's legs (:mod:`tcarod.models.manipulators`).
    turns_reading: TurnsReading = DEFAULT_TURNS_READING
    #: Temperatures [C] at which every reading's force is reported.
    reading_temperatures_c: tuple[float, ...] = (100.0, 140.0)

    def robot(self, material: Material | None = None, turns_reading: TurnsReading | None = None) -> Robot:
        """The manipulator: :func:`tcarod.models.manipulators.square_manipulator` of ``length_m``, upright."""
        reading = self.turns_reading if turns_reading is None else turns_reading
        return square_manipulator(
            self.length_m, gravity_m_per_s2=self.gravity_m_per_s2, material=material, turns_reading=reading
        )

    def predict(self, material: Material | None = None) -> Fig8Result:
        """Predicted force against temperature; see :func:`predict_fig8`."""
        return predict_fig8(self, material)


#: The paper's Fig. 8 experiment (Section V-C).
FIG8: Final[Fig8Experiment] = Fig8Experiment()


@dataclass(frozen=True)
class Fig8CrossCheck:
    """The incremental eq-43 method fed the direct solve's force at one temperature.

    Examples
    --------
    >>> import dataclasses
    >>> from tcarod.paper.fig8 import FIG8
    >>> small = dataclasses.replace(FIG8, temperatures_c=(25.0, 100.0, 160.0), cross_check_temperatures_c=(100.0,))
    >>> from tcarod.paper.fig8 import predict_fig8
    >>> check = predict_fig8(small, readings=False).cross_checks[0]
    >>> check.temperature_c, abs(check.difference_c) < 0.01      # [C]
    (100.0, True)
    """

    temperature_c: float
    force_n: float
    #: Temperature [C] the incremental method returns for ``force_n``.
    incremental_temperature_c: float

    @property
    def difference_c(self) -> float:
        """``incremental_temperature_c - temperature_c`` [C].

        Returns
        -------
        float
            Difference [C].
        """
        return self.incremental_temperature_c - self.temperature_c


@dataclass(frozen=True)
class Fig8Reading:
    """Blocked force of one reading (turns, material) at a few temperatures.

    Forces in N, temperatures in C.

    Examples
    --------
    >>> import dataclasses
    >>> from tcarod.paper.fig8 import FIG8
    >>> small = dataclasses.replace(FIG8, temperatures_c=(25.0, 100.0, 160.0), cross_check_temperatures_c=(100.0,))
    >>> reading = small.predict().readings[0]
    >>> reading.turns_reading, reading.material, reading.temperatures_c
    ('per_tca', 'sun_zhao', (100.0, 140.0))
    """

    turns_reading: str
    material: str
    temperatures_c: tuple[float, ...]
    forces_n: tuple[float, ...]

    def to_json(self) -> dict[str, Any]:
        """JSON-serialisable; forces in N."""
        return {
            "turns_reading": self.turns_reading,
            "material": self.material,
            "force_n_at_c": {f"{t:g}": f for t, f in zip(self.temperatures_c, self.forces_n)},
        }


def fig8_forces(
    temperatures_c: tuple[float, ...],
    material: Material | None = None,
    turns_reading: TurnsReading | None = None,
    experiment: Fig8Experiment | None = None,
) -> tuple[float, ...]:
    """Blocked-tip force of the Fig. 8 set-up at each temperature.

    0 below the taut temperature, else the direct mixed solve at the free
    tip's position at the taut temperature (warm-started).

    Parameters
    ----------
    temperatures_c : tuple of float
        Temperatures [C], ascending.
    material : Material, optional
        Fibre material (default :meth:`Material.silver_coated_nylon`).
    turns_reading : ('per_tca', 'per_leg', 'per_length'), optional
        How the paper's turns are read (default the experiment's).
    experiment : Fig8Experiment, optional
        The set-up (default :data:`FIG8`).

    Returns
    -------
    tuple of float
        Forces [N].

    Examples
    --------
    >>> from tcarod.paper.fig8 import fig8_forces
    >>> [round(f * 1e3, 2) for f in fig8_forces((50.0, 100.0))]     # [mN]: slack, then pulling
    [0.0, 15.07]
    """
    exp = FIG8 if experiment is None else experiment
    robot = exp.robot(material, turns_reading)
    n = len(robot.actuators)
    tip = robot.solve([exp.taut_temperature_c] * n).tip_position
    point = (float(tip[0]), float(tip[1]), float(tip[2]))
    out, warm = [], None
    for t in temperatures_c:
        if t <= exp.taut_temperature_c:
            out.append(0.0)
            continue
        warm = blocked_force(robot, point, exp.normal, [float(t)], groups=[0] * n, warm_start=warm)
        out.append(max(warm.force, 0.0))
    return tuple(out)


@dataclass(frozen=True, eq=False)
class Fig8Result:
    """Predicted Fig. 8: the blocked-tip force against temperature.

    Examples
    --------
    >>> import dataclasses
    >>> from tcarod.paper.fig8 import FIG8
    >>> small = dataclasses.replace(FIG8, temperatures_c=(25.0, 100.0, 160.0), cross_check_temperatures_c=(100.0,))
    >>> from tcarod.paper.fig8 import predict_fig8
    >>> result = predict_fig8(small, readings=False)
    >>> result.name, round(result.force_at(160.0) * 1e3, 2)     # [mN]
    ('fig8', 45.09)
    """

    experiment: Fig8Experiment
    temperatures_c: FloatArray
    #: Force [N] the tip pulls the wire with (0 while the wire is slack).
    forces_n: FloatArray
    #: Block point [m]: the free tip position at the taut temperature.
    block_point_m: tuple[float, float, float]
    cross_checks: tuple[Fig8CrossCheck, ...]
    #: Every turns reading x material preset at ``reading_temperatures_c``.
    readings: tuple[Fig8Reading, ...] = ()

    @property
    def name(self) -> str:
        """Registry name.

        Returns
        -------
        str
            ``"fig8"``.
        """
        return self.experiment.name

    def force_at(self, temperature_c: float) -> float:
        """Predicted force [N] at a temperature [C] of the sweep."""
        k = int(np.argmin(np.abs(self.temperatures_c - temperature_c)))
        if abs(self.temperatures_c[k] - temperature_c) > 1e-9:
            raise ValueError(f"temperature {temperature_c} C is not in the sweep")
        return float(self.forces_n[k])

    def table(self) -> str:
        """Force [mN] against temperature [C], the blocking geometry and the cross-checks."""
        exp = self.experiment
        p = self.block_point_m
        lines = [
            f"{exp.title} ({exp.source})",
            *textwrap.wrap(f"Blocking: {exp.blocking}", 78),
            f"Block point [mm]: ({p[0] * 1e3:.3f}, {p[1] * 1e3:.3f}, {p[2] * 1e3:.3f})",
            "-" * 24,
            f"{'T [C]':>8} | {'force [mN]':>11}",
            "-" * 24,
        ]
        for t, f in zip(self.temperatures_c, self.forces_n):
            lines.append(f"{t:>8.0f} | {f * 1e3:>11.3f}")
        lines.append("-" * 24)
        lines.append("Cross-check, incremental eq-43 method fed the direct force:")
        for c in self.cross_checks:
            lines.append(
                f"  {c.temperature_c:.0f} C: {c.force_n * 1e3:.3f} mN -> {c.incremental_temperature_c:.6f} C "
                f"(difference {c.difference_c:.2e} C)"
            )
        lines.append(f"Turns read {exp.turns_reading!r} (default; see tcarod.models.manipulators). Every reading [mN]:")
        for r in self.readings:
            vals = ", ".join(f"{f * 1e3:.2f} at {t:g} C" for t, f in zip(r.temperatures_c, r.forces_n))
            lines.append(f"  {r.turns_reading:>10} / {r.material:<12}: {vals}")
        lines.append(f"Published data: none. {exp.published_data_note}")
        return "\n".join(lines)

    def to_json(self) -> dict[str, Any]:
        """JSON-serialisable prediction; temperatures in C, forces in N, lengths in m."""
        exp = self.experiment
        return {
            **identity_json(exp),
            "length_m": exp.length_m,
            "gravity_m_per_s2": list(exp.gravity_m_per_s2),
            "blocking": exp.blocking,
            "taut_temperature_c": exp.taut_temperature_c,
            "turns_reading": exp.turns_reading,
            "readings": [r.to_json() for r in self.readings],
            "block_point_m": list(self.block_point_m),
            "normal": list(exp.normal),
            "method": "direct mixed solve (force as shooting unknown), warm-started along the sweep",
            "temperature_c": [float(t) for t in self.temperatures_c],
            "force_n": [float(f) for f in self.forces_n],
            "cross_checks": [
                {
                    "temperature_c": c.temperature_c,
                    "force_n": c.force_n,
                    "incremental_temperature_c": c.incremental_temperature_c,
                    "difference_c": c.difference_c,
                }
                for c in self.cross_checks
            ],
            "published_data": None,
            "published_rms_n": exp.published_rms_n,
            "published_data_note": exp.published_data_note,
        }

    def plot(self, path: str | os.PathLike[str]) -> Path:
        """Write force [mN] against temperature [C] (:func:`tcarod.plotting.plot_fig8`) as PNG to ``path``."""
        from ..plotting import plot_fig8, save_png  # matplotlib only when plotting

        return save_png(plot_fig8(self), path)


def predict_fig8(
    experiment: Fig8Experiment = FIG8, material: Material | None = None, *, readings: bool = True
) -> Fig8Result:
    """Blocked-tip force at each temperature of ``experiment``.

    Below the taut temperature the force is 0 (slack wire). From it on, the
    direct mixed solve (:func:`tcarod.inverse.blocked_force`) warm-started
    along the sweep; a negative solved force (the tip would move away from
    the wire) is reported as 0. At ``cross_check_temperatures_c`` the
    incremental eq-43 method (:func:`tcarod.inverse.blocked_temperature`, 10
    increments) is fed the force and must return the temperature.

    Parameters
    ----------
    experiment : Fig8Experiment, optional
        The set-up (default the paper's, :data:`FIG8`).
    material : Material, optional
        Fibre material (default :meth:`Material.silver_coated_nylon`).
    readings : bool, optional
        Also the force of every turns reading x material preset at
        ``reading_temperatures_c`` (default).

    Returns
    -------
    Fig8Result
        Forces [N] at the temperatures [C], cross-checks and readings.

    Examples
    --------
    >>> import dataclasses
    >>> from tcarod.paper.fig8 import FIG8
    >>> small = dataclasses.replace(FIG8, temperatures_c=(25.0, 100.0, 160.0), cross_check_temperatures_c=(100.0,))
    >>> from tcarod.paper.fig8 import predict_fig8
    >>> (predict_fig8(small, readings=False).forces_n * 1e3).round(2).tolist()     # [mN]
    [0.0, 15.07, 45.09]
    """
    robot = experiment.robot(material)
    groups = [0] * len(robot.actuators)
    t_taut = experiment.taut_temperature_c
    free = robot.solve([t_taut] * len(robot.actuators))
    tip = free.tip_position
    point = (float(tip[0]), float(tip[1]), float(tip[2]))
    temps = np.asarray(experiment.temperatures_c, dtype=np.float64)
    forces = np.zeros_like(temps)
    warm = None
    for k, t in enumerate(temps):
        if t < t_taut:
            continue
        warm = blocked_force(robot, point, experiment.normal, [float(t)], groups=groups, warm_start=warm)
        forces[k] = max(warm.force, 0.0)
    checks = []
    for t in experiment.cross_check_temperatures_c:
        f = float(np.interp(t, temps, forces)) if t in temps else None
        if f is None or f <= 0.0:
            continue
        inc = blocked_temperature(robot, point, experiment.normal, f, free, groups=groups)
        checks.append(
            Fig8CrossCheck(temperature_c=float(t), force_n=f, incremental_temperature_c=float(inc.variables[0]))
        )
    rd = []
    if readings:
        ts = experiment.reading_temperatures_c
        for tr in TURNS_READINGS:
            for mat in MATERIAL_PRESETS:
                fr = fig8_forces(ts, material_preset(mat), tr, experiment)
                rd.append(Fig8Reading(turns_reading=tr, material=mat, temperatures_c=ts, forces_n=fr))
    return Fig8Result(
        experiment=experiment,
        temperatures_c=temps,
        forces_n=forces,
        block_point_m=point,
        cross_checks=tuple(checks),
        readings=tuple(rd),
    )
