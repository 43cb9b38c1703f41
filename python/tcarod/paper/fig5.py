"""Fig. 5 of the paper (Section V-A): extension TCAs under dead weights.

The fixture :data:`FIG5` holds what the paper specifies (TCAs, loads,
temperatures; the paper prints no numbers for Fig. 5); :func:`predict_fig5` runs the
TCA law on one folded half of each TCA and returns a :class:`Fig5Result`
(``table()``, ``to_json()``, ``plot(path)``).
"""

from __future__ import annotations

import os
import textwrap
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Final, Literal

import numpy as np

from .. import _core
from ..tca import Material, Tca
from ._common import GRAVITY_M_PER_S2, DeadWeight, FloatArray, PublishedCurve, TcaSpec, onset_temperature_c
from ._common import PAPER_SOURCE, identity_json, PAPER_TEMPERATURES_C, published_json

__all__ = ["FIG5", "Fig5Case", "Fig5Curve", "Fig5Experiment", "Fig5Result", "predict_fig5"]

_FIG5_LOAD_SHARING: Final[str] = (
    "The TCA is folded into two halves (55 mm coiled each) standing side by side on "
    "guide rods; the weight hangs at the fold, so each half carries half of "
    "(mass + friction equivalent) * g as a compressive force, and the measured "
    "displacement is one half's elongation. A half is Tca(l/2, L/2, D, N/2): same "
    "alpha0 and d0, half the coils and turns."
)


@dataclass(frozen=True)
class Fig5Case:
    """One curve of Fig. 5: a TCA under one dead weight.

    The weight is shared by the TCA's two folded halves as
    :attr:`Fig5Experiment.load_sharing` states (a modelling choice; the paper
    does not state it).

    Examples
    --------
    >>> from tcarod.paper.fig5 import FIG5
    >>> case = FIG5.cases[0]
    >>> case.label, round(case.force_per_half_n, 4)       # [N], compressive
    ('3 threads, 5 g', -0.0368)
    """

    tca: TcaSpec
    load: DeadWeight

    @property
    def label(self) -> str:
        """The curve's label.

        Returns
        -------
        str
            E.g. ``"3 threads, 5 g"``.
        """
        return f"{self.tca.label}, {self.load.label}"

    @property
    def force_per_half_n(self) -> float:
        """Axial force on each half [N].

        Returns
        -------
        float
            ``-(mass + friction equivalent) g / 2`` [N] (compressive, < 0).
        """
        return -0.5 * self.load.weight_n

    def half_tca(self, material: Material | None = None) -> Tca:
        """One folded half, ``Tca(l/2, L/2, D, N/2)``: :meth:`Tca.segment` of the whole TCA at 0.5.

        Parameters
        ----------
        material : Material, optional
            Fibre material (default :meth:`Material.silver_coated_nylon`).

        Returns
        -------
        Tca
            The half TCA (lengths [m]).
        """
        return self.tca.build(material).segment(0.5)


@dataclass(frozen=True)
class Fig5Experiment:
    """Fig. 5 of the paper: free extension TCAs under dead weights, heated in an oven.

    See :class:`Fig5Case` for the load sharing; :data:`FIG5` is the paper's.

    Examples
    --------
    >>> import dataclasses
    >>> from tcarod.paper.fig5 import FIG5
    >>> small = dataclasses.replace(FIG5, temperatures_c=(25.0, 90.0, 160.0))    # [C]
    >>> [case.label for case in small.cases]
    ['3 threads, 5 g', '3 threads, 10 g', '4 threads, 5 g', '4 threads, 10 g']
    """

    tcas: tuple[TcaSpec, ...]
    loads: tuple[DeadWeight, ...]
    temperatures_c: tuple[float, ...] = PAPER_TEMPERATURES_C
    #: ``None``: the paper prints no numeric data for Fig. 5; the
    #: curves exist only as a plot. Fill with digitised :class:`PublishedCurve`
    #: objects if such data become available.
    published_data: tuple[PublishedCurve, ...] | None = None
    published_data_note: str = "The paper prints no numeric data for Fig. 5, only the plotted curves."
    name: str = "fig5"
    title: str = "Fig. 5: extension TCAs under dead weights"
    source: str = f"{PAPER_SOURCE}, Section V-A, Fig. 5"
    load_sharing: str = field(default=_FIG5_LOAD_SHARING)

    @property
    def cases(self) -> tuple[Fig5Case, ...]:
        """Every TCA under every load, TCA-major.

        Returns
        -------
        tuple of Fig5Case
            In the order of the table and the JSON.
        """
        return tuple(Fig5Case(t, w) for t in self.tcas for w in self.loads)

    def predict(self, material: Material | None = None) -> Fig5Result:
        """Predicted displacement curves and onset temperatures; see :func:`predict_fig5`.

        Parameters
        ----------
        material : Material, optional
            Fibre material (default :meth:`Material.silver_coated_nylon`).

        Returns
        -------
        Fig5Result
            One curve per case.
        """
        return predict_fig5(self, material)


def _paper_tca(threads: Literal[3, 4]) -> TcaSpec:
    """The Fig. 5 TCA of ``threads`` threads as the core defines it (``fig5_tca`` in ``src/experiments.rs``)."""
    t = _core.fixture_fig5_tca(threads)
    return TcaSpec(f"{threads} threads", threads, t.fibre_length, t.coiled_length, t.coil_diameter, t.turns)


#: The paper's Fig. 5 experiment (Section V-A, whose text swaps ``l`` and ``L``;
#: see docs/choices.md: coiled length ``L = 110 mm``, fibre length ``l = 497 / 471 mm``;
#: the TCAs from the core). Friction equivalents 2.5 g (5 g case) and 5 g (10 g case).
FIG5: Final[Fig5Experiment] = Fig5Experiment(
    tcas=(_paper_tca(3), _paper_tca(4)),
    loads=(
        DeadWeight(mass_kg=5e-3, friction_equivalent_kg=2.5e-3),
        DeadWeight(mass_kg=10e-3, friction_equivalent_kg=5e-3),
    ),
)


@dataclass(frozen=True, eq=False)
class Fig5Curve:
    """Prediction of Fig. 5 for one :class:`Fig5Case`.

    Examples
    --------
    >>> import dataclasses
    >>> from tcarod.paper.fig5 import FIG5
    >>> small = dataclasses.replace(FIG5, temperatures_c=(25.0, 90.0, 160.0))    # [C]
    >>> curve = small.predict().curves[0]
    >>> curve.final_temperature_c, round(curve.displacement_at_final_temperature_m * 1e3, 2)   # [C], [mm]
    (160.0, 16.09)
    """

    case: Fig5Case
    temperatures_c: FloatArray
    #: Elongation [m] of one folded half at each temperature.
    displacements_m: FloatArray
    #: Temperature [C] at which the coils separate; ``None`` if not in range.
    onset_temperature_c: float | None
    #: Largest possible elongation [m] of one half (fibre straight), ``l/2 (1 - sin alpha0)``.
    straight_fibre_limit_m: float

    @property
    def final_temperature_c(self) -> float:
        """Last (highest) temperature of the sweep [C].

        Returns
        -------
        float
            Temperature [C].
        """
        return float(self.temperatures_c[-1])

    @property
    def displacement_at_final_temperature_m(self) -> float:
        """Displacement at :attr:`final_temperature_c` [m].

        Returns
        -------
        float
            Elongation of one half [m].
        """
        return float(self.displacements_m[-1])


def _fmt_onset(t: float | None) -> str:
    return "none" if t is None else f"{t:.1f}"


@dataclass(frozen=True, eq=False)
class Fig5Result:
    """Predicted Fig. 5: one :class:`Fig5Curve` per case.

    Examples
    --------
    >>> import dataclasses
    >>> from tcarod.paper.fig5 import FIG5
    >>> small = dataclasses.replace(FIG5, temperatures_c=(25.0, 90.0, 160.0))    # [C]
    >>> result = small.predict()
    >>> result.name, len(result.curves), result.temperatures_c.tolist()
    ('fig5', 4, [25.0, 90.0, 160.0])
    """

    experiment: Fig5Experiment
    curves: tuple[Fig5Curve, ...]

    @property
    def name(self) -> str:
        """Registry name.

        Returns
        -------
        str
            ``"fig5"``.
        """
        return self.experiment.name

    @property
    def temperatures_c(self) -> FloatArray:
        """Temperatures of the sweep [C], shared by all curves.

        Returns
        -------
        numpy.ndarray
            Shape ``(k,)`` [C].
        """
        return np.asarray(self.experiment.temperatures_c, dtype=np.float64)

    def table(self) -> str:
        """The prediction as a text table.

        Returns
        -------
        str
            Displacement [mm] against temperature [C] for every case, then the
            onset temperatures [C] and the final-temperature displacements [mm].
        """
        exp = self.experiment
        labels = [c.case.label for c in self.curves]
        width = max(14, *(len(s) for s in labels))
        t_final = self.curves[0].final_temperature_c if self.curves else float("nan")
        final_label = f"displacement at {t_final:.0f} C [mm]"
        first = max(len("straight-fibre limit [mm]"), len(final_label))
        head = f"{'T [C]':>{first}} | " + " | ".join(f"{s:>{width}}" for s in labels)
        rule = "-" * len(head)
        forces = " | ".join(f"{c.case.force_per_half_n:>{width}.5f}" for c in self.curves)
        lines = [
            f"{exp.title} ({exp.source})",
            "Predicted displacement [mm] of one folded half.",
            *textwrap.wrap(f"Load sharing: {exp.load_sharing}", width=max(len(rule), 60)),
            rule,
            head,
            f"{'force per half [N]':>{first}} | {forces}",
            rule,
        ]
        for i, t in enumerate(self.temperatures_c):
            row = " | ".join(f"{c.displacements_m[i] * 1e3:>{width}.3f}" for c in self.curves)
            lines.append(f"{t:>{first}.0f} | {row}")
        lines.append(rule)
        lines.append(
            f"{'onset temperature [C]':>{first}} | "
            + " | ".join(f"{_fmt_onset(c.onset_temperature_c):>{width}}" for c in self.curves)
        )
        lines.append(
            f"{final_label:>{first}} | "
            + " | ".join(f"{c.displacement_at_final_temperature_m * 1e3:>{width}.3f}" for c in self.curves)
        )
        lines.append(
            f"{'straight-fibre limit [mm]':>{first}} | "
            + " | ".join(f"{c.straight_fibre_limit_m * 1e3:>{width}.1f}" for c in self.curves)
        )
        lines.append(rule)
        if exp.published_data is None:
            lines.append(f"Published data: none. {exp.published_data_note}")
        return "\n".join(lines)

    def to_json(self) -> dict[str, Any]:
        """JSON-serialisable prediction; temperatures in C, lengths in m, forces in N, masses in kg."""
        exp = self.experiment
        return {
            **identity_json(exp),
            "gravity_m_per_s2": GRAVITY_M_PER_S2,
            "load_sharing": exp.load_sharing,
            "temperature_c": [float(t) for t in self.temperatures_c],
            "published_data": published_json(exp.published_data),
            "published_data_note": exp.published_data_note,
            "cases": [
                {
                    "label": c.case.label,
                    "threads": c.case.tca.threads,
                    "fibre_length_m": c.case.tca.fibre_length_m,
                    "coiled_length_m": c.case.tca.coiled_length_m,
                    "coil_diameter_m": c.case.tca.coil_diameter_m,
                    "turns": c.case.tca.turns,
                    "chirality": c.case.tca.chirality,
                    "mass_kg": c.case.load.mass_kg,
                    "friction_equivalent_kg": c.case.load.friction_equivalent_kg,
                    "force_per_half_n": c.case.force_per_half_n,
                    "displacement_m": [float(d) for d in c.displacements_m],
                    "onset_temperature_c": c.onset_temperature_c,
                    "final_temperature_c": c.final_temperature_c,
                    "displacement_at_final_temperature_m": c.displacement_at_final_temperature_m,
                    "straight_fibre_limit_m": c.straight_fibre_limit_m,
                }
                for c in self.curves
            ],
        }

    def plot(self, path: str | os.PathLike[str]) -> Path:
        """Write the Fig. 5 plot (see :func:`tcarod.plotting.plot_fig5`) as PNG to ``path``."""
        from ..plotting import plot_fig5, save_png  # matplotlib only when plotting

        return save_png(plot_fig5(self), path)


def predict_fig5(experiment: Fig5Experiment = FIG5, material: Material | None = None) -> Fig5Result:
    """Predicted displacement of one folded half against temperature, for every case.

    Parameters
    ----------
    experiment : Fig5Experiment, optional
        The set-up (default the paper's, :data:`FIG5`).
    material : Material, optional
        Fibre material (default :meth:`Material.silver_coated_nylon`).

    Returns
    -------
    Fig5Result
        Displacements [m] at each temperature [C], with onset temperatures
        [C] from :meth:`Tca.onset_temperature` (``None`` if no onset in the
        material's range).

    Raises
    ------
    ValueError
        A temperature outside the material's range, or a load that
        straightens the fibre.

    Examples
    --------
    >>> import dataclasses
    >>> from tcarod.paper.fig5 import FIG5
    >>> small = dataclasses.replace(FIG5, temperatures_c=(25.0, 90.0, 160.0))    # [C]
    >>> from tcarod.paper.fig5 import predict_fig5
    >>> [round(c.onset_temperature_c, 1) for c in predict_fig5(small).curves]    # [C]
    [32.4, 38.0, 30.8, 35.4]
    """
    temps = np.asarray(experiment.temperatures_c, dtype=np.float64)
    curves = []
    for case in experiment.cases:
        half = case.half_tca(material)
        force = case.force_per_half_n
        disp = np.asarray(half.displacement(force, temps), dtype=np.float64)
        curves.append(
            Fig5Curve(
                case=case,
                temperatures_c=temps,
                displacements_m=disp,
                onset_temperature_c=onset_temperature_c(half, force),
                straight_fibre_limit_m=half.max_displacement,
            )
        )
    return Fig5Result(experiment=experiment, curves=tuple(curves))
