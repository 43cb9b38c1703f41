"""Table I of the paper (Section V-D): grip temperatures of a two-finger gripper.

Each finger is a 20 mm long square EcoFlex body (10 mm side) with a U-shaped
TCA at body ``x = +3 mm``, hanging down. The gripper holds a mass ``m`` when
``mu n F(T) = m g`` (eq 44), ``mu = 1.1``, ``n = 2``. ``F(T)`` is one
finger's contact force: the free fingertip closes as the TCA heats until it
touches the object at the *contact temperature*; below it the force is zero,
above it the tip is blocked at its position at contact and presses along
``-x`` (:func:`tcarod.models.grasp.blocked_force_curve`).

Defaults (documented, not tuned; ``docs/table1.md``):

* contact at 72.33 C, the zero-force intercept of the paper's own
  predictions, which are linear in the force (0.209 mN/C); the paper prints
  no gap between fingertip and object;
* turns read per U-shaped TCA (38.2 per 20 mm leg; :mod:`tcarod.models.manipulators`);
* the documented default material (Sun & Zhao's ``rho(T)``).

With them the finger's force rises several times faster than the paper's
(see the force slope in the table), so the grip temperatures are far below
the paper's. The readings (turns x ``rho(T)`` preset) and the
*identification* of at most two parameters per reading
(:mod:`tcarod.models.identification`) are reported beside them, never used as
defaults.
"""

from __future__ import annotations

import os
import textwrap
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Final

from ..models.grasp import (
    FRICTION_COEFFICIENT,
    TABLE1_CONTACT_TEMPERATURE_C,
    TABLE1_EXPERIMENT_C,
    TABLE1_MASSES_KG,
    TABLE1_PAPER_PREDICTIONS_C,
    Grasp,
    force_line,
    grasp,
    table1_finger,
)
from ..models.identification import IDENTIFICATION_READINGS, Identification, identify
from ..models.manipulators import (
    GRAVITY_M_PER_S2,
    DEFAULT_TURNS_READING,
    MATERIAL_PRESETS,
    TURNS_READINGS,
    TurnsReading,
    material_preset,
)
from ..models.studies import Sensitivity, table1_sensitivity
from ..tca import Material
from ._common import PAPER_SOURCE, identity_json
from .fig8 import fig8_forces

__all__ = ["TABLE1", "Table1Experiment", "Table1Reading", "Table1Result", "Table1Row", "predict_table1"]

_CONTACT: Final[str] = (
    "The free fingertip closes until it touches the object at the contact temperature (default "
    "72.33 C: the zero-force intercept of the paper's predictions, linear in the force per finger; the "
    "paper prints no gap); zero force below it, then the tip is blocked at its position at contact and "
    "presses along -x (plane contact)."
)


@dataclass(frozen=True)
class Table1Experiment:
    """The Table I set-up (a two-finger TCA gripper) and the paper's numbers.

    :data:`TABLE1` is the paper's.

    Examples
    --------
    >>> from tcarod.paper.table1 import TABLE1
    >>> TABLE1.masses_kg, TABLE1.experiment_c, TABLE1.paper_prediction_c     # [kg], [C], [C]
    ((0.001, 0.002, 0.003), (95.0, 120.0, 135.0), (93.7, 114.8, 136.3))
    """

    masses_kg: tuple[float, ...] = TABLE1_MASSES_KG
    #: Measured firm-grip temperatures [C] (oven steps of 5 C).
    experiment_c: tuple[float, ...] = TABLE1_EXPERIMENT_C
    #: The paper's own model predictions [C].
    paper_prediction_c: tuple[float, ...] = TABLE1_PAPER_PREDICTIONS_C
    mu: float = FRICTION_COEFFICIENT
    fingers: int = 2
    gravity_m_per_s2: float = GRAVITY_M_PER_S2
    #: Temperature [C] at which the fingertip touches the object (see ``blocking``).
    contact_temperature_c: float = TABLE1_CONTACT_TEMPERATURE_C
    turns_reading: TurnsReading = DEFAULT_TURNS_READING
    name: str = "table1"
    title: str = "Table I: grip temperature of a two-finger TCA gripper"
    source: str = f"{PAPER_SOURCE}, Section V-D, Table I, eq (44)"
    blocking: str = field(default=_CONTACT)

    def predict(
        self, material: Material | None = None, *, study: bool = False, identification: bool = False
    ) -> Table1Result:
        """Predicted grip temperatures; see :func:`predict_table1`."""
        return predict_table1(self, material, study=study, identification=identification)


#: The paper's Table I.
TABLE1: Final[Table1Experiment] = Table1Experiment()


@dataclass(frozen=True, eq=False)
class Table1Row:
    """One mass: tcarod's grip temperature beside the paper's numbers.

    Examples
    --------
    >>> from tcarod.paper.table1 import TABLE1
    >>> row = TABLE1.predict().rows[1]                    # 2 g
    >>> round(row.predicted_c, 1), round(row.error_vs_experiment_c, 1)     # [C]
    (88.7, -31.3)
    """

    mass_kg: float
    grasp: Grasp
    #: The direct blocked-tip solve's temperature [C] (check of the incremental one).
    direct_c: float
    experiment_c: float
    paper_prediction_c: float

    @property
    def predicted_c(self) -> float:
        """tcarod's grip temperature [C] (incremental eq-43 method).

        Returns
        -------
        float
            Temperature [C].
        """
        return self.grasp.temperature_c

    @property
    def error_vs_experiment_c(self) -> float:
        """``predicted - experiment`` [C].

        Returns
        -------
        float
            Difference [C].
        """
        return self.predicted_c - self.experiment_c

    @property
    def error_vs_paper_c(self) -> float:
        """``predicted - paper's prediction`` [C].

        Returns
        -------
        float
            Difference [C].
        """
        return self.predicted_c - self.paper_prediction_c


@dataclass(frozen=True)
class Table1Reading:
    """Grip temperatures of one reading (turns x material preset) at the default contact.

    Temperatures in C.

    Examples
    --------
    >>> from tcarod.paper.table1 import TABLE1
    >>> reading = TABLE1.predict().readings[0]
    >>> reading.turns_reading, reading.material
    ('per_tca', 'sun_zhao')
    """

    turns_reading: str
    material: str
    grip_c: tuple[float, ...]
    #: Force slope after contact [N/C] (line through the grips).
    slope_n_per_c: float

    def to_json(self) -> dict[str, Any]:
        """JSON-serialisable; temperatures in C."""
        return {
            "turns_reading": self.turns_reading,
            "material": self.material,
            "grip_temperature_c": list(self.grip_c),
            "force_slope_mn_per_c": self.slope_n_per_c * 1e3,
        }


@dataclass(frozen=True, eq=False)
class Table1Result:
    """Predicted Table I, the readings, and optionally the study and identification.

    Examples
    --------
    >>> from tcarod.paper.table1 import TABLE1
    >>> result = TABLE1.predict()
    >>> result.name, [round(r.predicted_c, 1) for r in result.rows]     # [C] for 1, 2, 3 g
    ('table1', [80.9, 88.7, 96.0])
    """

    experiment: Table1Experiment
    rows: tuple[Table1Row, ...]
    readings: tuple[Table1Reading, ...] = ()
    sensitivities: tuple[Sensitivity, ...] = ()
    identifications: tuple[Identification, ...] = ()
    #: Fig. 8 blocked force [N] at 100 and 140 C of each identification's material and turns.
    identification_fig8_n: tuple[tuple[float, ...], ...] = ()

    @property
    def name(self) -> str:
        """Registry name.

        Returns
        -------
        str
            ``"table1"``.
        """
        return self.experiment.name

    def _lines(self, masses: tuple[float, ...], temps: tuple[float, ...]) -> tuple[float, float]:
        exp = self.experiment
        return force_line(masses, temps, exp.mu, exp.fingers, exp.gravity_m_per_s2)

    def force_slopes_n_per_c(self) -> dict[str, tuple[float, float]]:
        """``(force slope [N/C], zero-force intercept [C])`` of tcarod, the paper's model and the experiment."""
        exp = self.experiment
        return {
            "tcarod": self._lines(exp.masses_kg, tuple(r.predicted_c for r in self.rows)),
            "paper_model": self._lines(exp.masses_kg, exp.paper_prediction_c),
            "experiment": self._lines(exp.masses_kg, exp.experiment_c),
        }

    def table(self) -> str:
        """Grip temperatures [C] and force slopes [mN/C]; readings; identification."""
        exp = self.experiment
        head = (
            f"{'mass [g]':>8} | {'F/finger [mN]':>13} | {'tcarod [C]':>10} | {'experiment [C]':>14} | "
            f"{'paper model [C]':>15} | {'tcarod-exp [C]':>14} | {'tcarod-paper [C]':>16}"
        )
        rule = "-" * len(head)
        lines = [f"{exp.title} ({exp.source})", *textwrap.wrap(f"Contact: {exp.blocking}", len(rule)), rule, head, rule]
        for r in self.rows:
            lines.append(
                f"{r.mass_kg * 1e3:>8.0f} | {r.grasp.force_per_finger_n * 1e3:>13.3f} | {r.predicted_c:>10.1f} | "
                f"{r.experiment_c:>14.0f} | {r.paper_prediction_c:>15.1f} | {r.error_vs_experiment_c:>14.1f} | "
                f"{r.error_vs_paper_c:>16.1f}"
            )
        lines.append(rule)
        sl = self.force_slopes_n_per_c()
        lines.append(
            "Force slope after contact [mN/C] (zero-force intercept [C]): "
            + ", ".join(f"{k} {v[0] * 1e3:.3f} ({v[1]:.1f})" for k, v in sl.items())
        )
        lines += textwrap.wrap(
            f"Defaults: contact {exp.contact_temperature_c:.2f} C, turns read {exp.turns_reading!r}, default "
            "material (documented, not tuned). Incremental eq-43 and direct solves agree to "
            f"{max(abs(r.predicted_c - r.direct_c) for r in self.rows):.1e} C.",
            len(rule),
        )
        if self.readings:
            lines += [rule, f"Readings at contact {exp.contact_temperature_c:.2f} C (grip [C] for 1/2/3 g; slope):"]
            for rd in self.readings:
                g = " / ".join(f"{t:.1f}" for t in rd.grip_c)
                lines.append(f"  {rd.turns_reading:>10} / {rd.material:<12}: {g}  ({rd.slope_n_per_c * 1e3:.3f} mN/C)")
        if self.sensitivities:
            lines += [rule, "Sensitivity (each parameter x 0.9 and x 1.1): elasticity of the rise T - T_contact"]
            for s in self.sensitivities:
                el = ", ".join(f"{e:+.3f}" for e in s.elasticity)
                lines.append(f"  {s.parameter.key:>14}: {el}")
        if self.identifications:
            lines += [rule, "IDENTIFICATION (identified, not defaults; tcarod.models.identification):"]
            for i, f8 in zip(self.identifications, self.identification_fig8_n or [()] * len(self.identifications)):
                ps = ", ".join(
                    f"{k} = {p.value:.4g} [{p.plausible_range[0]:.3g}, {p.plausible_range[1]:.3g}] "
                    f"{'plausible' if p.plausible else 'NOT plausible'}"
                    for k, p in i.parameters.items()
                )
                loo = ", ".join(f"{v:+.1f}" for v in i.leave_one_out_c)
                fit = " / ".join(f"{t:.1f}" for t in i.fitted_c)
                lines += textwrap.wrap(f"* {i.reading.text}; fitted to {i.fitted_to}:", len(rule))
                lines.append(f"    {ps}")
                f8s = " / ".join(f"{f * 1e3:.2f}" for f in f8)
                lines.append(
                    f"    fitted {fit} C, rms {i.rms_c:.2f} C, leave-one-out {loo} C; "
                    f"d'/d / measured CTE {min(i.cte_ratio):.2f}-{max(i.cte_ratio):.2f}; Fig. 8 at 100/140 C: {f8s} mN"
                )
        return "\n".join(lines)

    def to_json(self) -> dict[str, Any]:
        """JSON-serialisable; temperatures in C, masses in kg, forces in N (slopes in mN/C)."""
        exp = self.experiment
        sl = self.force_slopes_n_per_c()
        idents = []
        for k, i in enumerate(self.identifications):
            d = i.to_json()
            if self.identification_fig8_n:
                d["fig8_force_n_at_c"] = {
                    "100": self.identification_fig8_n[k][0],
                    "140": self.identification_fig8_n[k][1],
                }
            idents.append(d)
        return {
            **identity_json(exp),
            "mu": exp.mu,
            "fingers": exp.fingers,
            "gravity_m_per_s2": exp.gravity_m_per_s2,
            "blocking": exp.blocking,
            "contact_temperature_c": exp.contact_temperature_c,
            "contact_temperature_source": "zero-force intercept of the paper's Table I predictions (force_line)",
            "turns_reading": exp.turns_reading,
            "method": "incremental eq 43 (10 increments) from the free solution at contact, checked by the direct solve",
            "force_slope_mn_per_c": {k: v[0] * 1e3 for k, v in sl.items()},
            "zero_force_intercept_c": {k: v[1] for k, v in sl.items()},
            "rows": [
                {
                    "mass_kg": r.mass_kg,
                    "force_per_finger_n": r.grasp.force_per_finger_n,
                    "predicted_c": r.predicted_c,
                    "direct_solve_c": r.direct_c,
                    "experiment_c": r.experiment_c,
                    "paper_prediction_c": r.paper_prediction_c,
                    "error_vs_experiment_c": r.error_vs_experiment_c,
                    "error_vs_paper_c": r.error_vs_paper_c,
                    "block_point_m": list(r.grasp.block_point_m),
                    "normal": list(r.grasp.normal),
                }
                for r in self.rows
            ],
            "readings": [r.to_json() for r in self.readings],
            "sensitivity": [s.to_json() for s in self.sensitivities],
            "identification": idents,
        }

    def plot(self, path: str | os.PathLike[str]) -> Path:
        """Write grip temperature [C] against mass [g] (:func:`tcarod.plotting.plot_table1`) as PNG."""
        from ..plotting import plot_table1, save_png  # matplotlib only when plotting

        return save_png(plot_table1(self), path)


def _grips(exp: Table1Experiment, finger: Any, method: str) -> list[Grasp]:
    kw: dict[str, Any] = {"mu": exp.mu, "fingers": exp.fingers, "gravity": exp.gravity_m_per_s2}
    return [
        grasp(m, finger, method=method, contact_temperature_c=exp.contact_temperature_c, **kw)  # type: ignore[arg-type]
        for m in exp.masses_kg
    ]


def predict_table1(
    experiment: Table1Experiment = TABLE1,
    material: Material | None = None,
    *,
    study: bool = False,
    identification: bool = False,
) -> Table1Result:
    """Grip temperature for each mass of ``experiment`` on the Table I finger.

    By the incremental eq-43 method from the free solution at contact, each
    checked by the direct solve; every turns reading x material preset at the
    same contact.

    Parameters
    ----------
    experiment : Table1Experiment, optional
        The set-up (default the paper's, :data:`TABLE1`).
    material : Material, optional
        Fibre material (default :meth:`Material.silver_coated_nylon`).
    study : bool, optional
        Also the sensitivity ranking (default material only, about 1 s).
    identification : bool, optional
        Also the fits of :data:`tcarod.models.identification.IDENTIFICATION_READINGS`
        to the paper's model and to the experiment (about a minute), each
        applied to Fig. 8.

    Returns
    -------
    Table1Result
        Grip temperatures [C] per mass [kg], with the paper's numbers.

    Raises
    ------
    ValueError
        A force that needs a temperature outside the material's range.

    Examples
    --------
    >>> from tcarod.paper.table1 import predict_table1
    >>> [round(r.direct_c, 1) for r in predict_table1().rows]     # [C], the direct solve
    [80.9, 88.7, 96.0]
    """
    finger = table1_finger(material=material, turns_reading=experiment.turns_reading)
    inc, direct = _grips(experiment, finger, "incremental"), _grips(experiment, finger, "direct")
    rows = tuple(
        Table1Row(mass_kg=m, grasp=g, direct_c=d.temperature_c, experiment_c=te, paper_prediction_c=tp)
        for m, g, d, te, tp in zip(
            experiment.masses_kg, inc, direct, experiment.experiment_c, experiment.paper_prediction_c
        )
    )
    readings = []
    for tr in TURNS_READINGS:
        for mat in MATERIAL_PRESETS:
            f = table1_finger(material=material_preset(mat), turns_reading=tr)
            grips = tuple(g.temperature_c for g in _grips(experiment, f, "incremental"))
            slope = force_line(
                experiment.masses_kg, grips, experiment.mu, experiment.fingers, experiment.gravity_m_per_s2
            )[0]
            readings.append(Table1Reading(turns_reading=tr, material=mat, grip_c=grips, slope_n_per_c=slope))
    sens = table1_sensitivity() if study and material is None else ()
    idents: list[Identification] = []
    fig8: list[tuple[float, ...]] = []
    if identification:
        for reading in IDENTIFICATION_READINGS:
            for target in ("paper_model", "experiment"):
                ident = identify(reading, target)
                idents.append(ident)
                fig8.append(fig8_forces((100.0, 140.0), ident.material(), reading.turns_reading))
    return Table1Result(
        experiment=experiment,
        rows=rows,
        readings=tuple(readings),
        sensitivities=tuple(sens),
        identifications=tuple(idents),
        identification_fig8_n=tuple(fig8),
    )
