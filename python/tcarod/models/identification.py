"""Identification of the Table I set-up: at most two free
parameters, fitted separately to the paper's model predictions and to the
experiment, each with leave-one-out errors and a plausibility check.

A *reading* fixes what the paper leaves open -- how its "N = 76.4 rotations"
apply to a U-shaped TCA (:data:`tcarod.models.manipulators.TURNS_READINGS`) and the
shape of ``rho(T)`` (:data:`tcarod.models.manipulators.MATERIAL_PRESETS`) -- and
names the free parameters:

* ``contact_temperature_c`` [C]: the freely closing fingertip touches the
  object at this temperature; zero force below, the blocked-tip force above.
  Plausible range: from ambient (25 C) to the lowest grip temperature of the
  target (the tip must touch before the lightest mass is held).
* ``rho_scale`` [-]: ``rho(T)`` of the preset times this factor
  (:meth:`Material.with_expansion_scale`). Plausible range: the factors for
  which the *instantaneous* coefficient ``d'(T)/d(T)`` stays within 0.5x to
  2x the measured radial CTE of oriented nylon 6,6 (Choy et al. 1984) at
  every data point of the Table I working range (64, 92, 116, 137 C): like
  with like. The lower end is about where an unoriented (isotropic) nylon
  6,6 lies (about 8e-5 1/K near room temperature, a typical datasheet value
  for unfilled PA66, half the oriented fibre's 15.5e-5 at 32 C); a drawn
  fibre's radial CTE exceeds the isotropic one. The upper end is the same
  factor above: the 4-ply silver-coated twisted yarn itself was not measured.

Each fit is scipy ``least_squares`` (trust region reflective) over
``(contact, log rho_scale)`` with wide bounds (25..150 C, 0.05..20), so a
fitted value outside its plausible range is reported, not hidden. Leave one
out: fit two masses, predict the third. Nothing here becomes a default.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Final, Literal, Sequence

import numpy as np

from .._core import ConvergenceError
from .._optional import require
from .grasp import (
    TABLE1_EXPERIMENT_C,
    TABLE1_MASSES_KG,
    TABLE1_PAPER_PREDICTIONS_C,
    grasp_temperature,
    table1_finger,
)
from .manipulators import TurnsReading, material_preset
from ..tca import Material

__all__ = [
    "CTE_CHECK_TEMPERATURES_C",
    "CTE_FACTOR_RANGE",
    "IDENTIFICATION_READINGS",
    "FitParameter",
    "Identification",
    "Reading",
    "contact_range_c",
    "cte_ratio",
    "identify",
    "reading_grip_temperatures",
    "rho_scale_range",
]

#: Temperatures [C] of the measured CTE data inside the Table I working range.
CTE_CHECK_TEMPERATURES_C: Final[tuple[float, ...]] = (64.0, 92.0, 116.0, 137.0)
#: Plausible instantaneous CTE relative to the measured one at the same temperature [-].
CTE_FACTOR_RANGE: Final[tuple[float, float]] = (0.5, 2.0)
_AMBIENT_C: Final[float] = 25.0
_CTE_SOURCE: Final[str] = (
    "d'(T)/d(T) of the scaled rho(T) within 0.5x-2x of the measured radial CTE of oriented nylon 6,6 "
    "(Choy et al. 1984, see docs/table1.md) at 64, 92, 116, 137 C; 0.5x is about unoriented (isotropic) "
    "PA66, ~8e-5 1/K (typical datasheet value)"
)
_CONTACT_SOURCE: Final[str] = (
    "between ambient (25 C, fingers relaxed) and the lowest grip temperature of the target "
    "(contact must precede the lightest grip); the paper prints no gap"
)

Target = Literal["paper_model", "experiment"]


def cte_ratio(material: Material, temperature_c: float) -> float:
    """Radial expansion rate ``d'(T)/d(T)`` of ``material`` over the measured CTE of oriented nylon 6,6 [-].

    Parameters
    ----------
    material, temperature_c : Material, float
        The fibre material and the temperature [C] (like with like).

    Returns
    -------
    float
        The ratio [-]; 1 matches the measurement.

    Examples
    --------
    >>> from tcarod.models.identification import cte_ratio
    >>> round(cte_ratio(tcarod.Material.silver_coated_nylon(), 100.0), 2)
    2.33
    """
    return material.instantaneous_expansion(temperature_c) / Material.measured_radial_cte(temperature_c)


def rho_scale_range(
    material: Material,
    temperatures_c: Sequence[float] = CTE_CHECK_TEMPERATURES_C,
    factors: tuple[float, float] = CTE_FACTOR_RANGE,
) -> tuple[float, float]:
    """Range of ``rho_scale`` [-] that keeps the expansion within ``factors`` of the measured CTE.

    ``d'/d`` of ``material`` scaled by ``rho_scale`` must lie within
    ``factors`` times the measured CTE at every temperature. With
    ``x = T - t_ref`` and ``rho(T) x = d/d0 - 1``, scaling by ``k`` gives
    ``d'/d = k d1 / (1 + k e)`` (``d1 = rho_ref + 2 rho_slope x``,
    ``e = rho(T) x``), increasing in ``k``; ``d'/d = c`` at
    ``k = c / (d1 - c e)``.

    Parameters
    ----------
    material : Material
        The fibre material.
    temperatures_c, factors : optional
        Temperatures [C] of the check (default the grip range); the plausible
        band around the measured CTE [-] (default 0.5 to 2).

    Returns
    -------
    (float, float)
        The lowest and highest plausible ``rho_scale`` [-].

    Examples
    --------
    >>> from tcarod.models.identification import rho_scale_range
    >>> [round(k, 3) for k in rho_scale_range(tcarod.Material.silver_coated_nylon())]
    [0.254, 0.836]
    """
    *_, r0, r1 = material.coefficients
    lo, hi = 0.0, math.inf
    for t in temperatures_c:
        x = t - material.t_ref
        d1, e = r0 + 2.0 * r1 * x, (r0 + r1 * x) * x
        a = Material.measured_radial_cte(t)
        c_lo, c_hi = factors[0] * a, factors[1] * a
        lo = max(lo, c_lo / (d1 - c_lo * e))
        hi = min(hi, c_hi / (d1 - c_hi * e) if d1 > c_hi * e else math.inf)
    return lo, hi


def contact_range_c(target_c: Sequence[float]) -> tuple[float, float]:
    """Plausible contact temperature [C]: ambient to the lowest target grip temperature.

    Parameters
    ----------
    target_c : sequence of float
        Target grip temperatures [C].

    Returns
    -------
    (float, float)
        Ambient (25 C) and the lowest target [C].

    Examples
    --------
    >>> from tcarod.models.identification import contact_range_c
    >>> contact_range_c((95.0, 120.0, 135.0))          # [C]
    (25.0, 95.0)
    """
    return _AMBIENT_C, float(min(target_c))


@dataclass(frozen=True)
class Reading:
    """How the paper's Table I set-up is read: turns, ``rho(T)`` shape, free parameters.

    Examples
    --------
    >>> from tcarod.models.identification import Reading
    >>> Reading("per_tca", "sun_zhao").free
    ('contact_temperature_c', 'rho_scale')
    """

    turns_reading: TurnsReading
    material: str
    #: Free parameters, from ``("contact_temperature_c", "rho_scale")``.
    free: tuple[str, ...] = ("contact_temperature_c", "rho_scale")

    @property
    def text(self) -> str:
        """One line describing the reading: turns, material and free parameters in words.

        Returns
        -------
        str
        """
        turns = {
            "per_tca": "76.4 turns per U-shaped TCA (38.2 per 20 mm leg)",
            "per_leg": "76.4 turns per leg",
            "per_length": "76.4 turns per 40 mm (38.2 per 20 mm leg)",
        }[self.turns_reading]
        rho = {
            "measured_cte": "rho(T) fitted to the measured CTE (Choy 1984)",
            "sun_zhao": "rho(T) of Sun & Zhao's diameter fit (default)",
        }[self.material]
        free = " and ".join(self.free)
        return f"{turns}; {rho}; free: {free}"

    def base_material(self) -> Material:
        """The unscaled material preset (:func:`tcarod.models.manipulators.material_preset`).

        Returns
        -------
        Material
        """
        return material_preset(self.material)


#: The readings identified by ``tcarod reproduce table1`` (two free parameters
#: each, then one with the contact temperature alone as evidence that a gap
#: by itself does not suffice).
IDENTIFICATION_READINGS: Final[tuple[Reading, ...]] = (
    Reading("per_tca", "measured_cte"),
    Reading("per_leg", "measured_cte"),
    Reading("per_tca", "sun_zhao"),
    Reading("per_tca", "sun_zhao", free=("contact_temperature_c",)),
)


def reading_grip_temperatures(
    reading: Reading,
    contact_temperature_c: float,
    rho_scale: float = 1.0,
    masses_kg: Sequence[float] = TABLE1_MASSES_KG,
) -> tuple[float, ...]:
    """Grip temperatures of the Table I finger under a reading (eq 44, ``mu = 1.1``, two fingers).

    Parameters
    ----------
    reading : Reading
        Turns and material.
    contact_temperature_c : float
        Contact temperature [C].
    rho_scale, masses_kg : optional
        Factor on the material's radial expansion [-] (default 1); masses [kg]
        (default Table I's).

    Returns
    -------
    tuple of float
        Grip temperature [C] per mass.

    Raises
    ------
    ValueError
        A grip that needs more than 160 C.

    Examples
    --------
    >>> from tcarod.models.identification import Reading, reading_grip_temperatures
    >>> [round(t, 1) for t in reading_grip_temperatures(Reading("per_tca", "sun_zhao"), 70.0)]   # [C]
    [78.8, 86.8, 94.3]
    """
    material = reading.base_material().with_expansion_scale(rho_scale)
    finger = table1_finger(material=material, turns_reading=reading.turns_reading)
    out = []
    for m in masses_kg:
        try:
            out.append(grasp_temperature(m, finger, contact_temperature_c=contact_temperature_c))
        except ConvergenceError:
            out.append(grasp_temperature(m, finger, contact_temperature_c=contact_temperature_c, method="direct"))
    return tuple(out)


@dataclass(frozen=True)
class FitParameter:
    """A fitted value with its unit, plausible range and source.

    Examples
    --------
    >>> from tcarod.models.identification import FitParameter
    >>> FitParameter(102.4, (25.0, 93.7), "C", "contact precedes the lightest grip").plausible
    False
    """

    value: float
    plausible_range: tuple[float, float]
    unit: str
    source: str

    @property
    def plausible(self) -> bool:
        """Whether the value lies inside :attr:`plausible_range`: ``lo <= value <= hi``.

        Returns
        -------
        bool
        """
        return self.plausible_range[0] <= self.value <= self.plausible_range[1]

    def to_json(self) -> dict[str, Any]:
        """JSON-serialisable (an infinite bound as ``None``)."""
        lo, hi = self.plausible_range
        return {
            "value": self.value,
            "plausible_range": [lo, hi if math.isfinite(hi) else None],
            "plausible": self.plausible,
            "unit": self.unit,
            "source": self.source,
        }


@dataclass(frozen=True)
class Identification:
    """One identified reading (by :func:`identify`): fitted parameters, residuals, leave-one-out errors.

    Examples
    --------
    >>> from tcarod.models.identification import Identification
    >>> [f for f in Identification.__dataclass_fields__][:4]
    ['reading', 'fitted_to', 'parameters', 'target_c']
    """

    reading: Reading
    fitted_to: Target
    parameters: dict[str, FitParameter]
    target_c: tuple[float, ...]
    fitted_c: tuple[float, ...]
    #: ``predicted - target`` [C] of each mass when fitted to the other two.
    leave_one_out_c: tuple[float, ...]
    #: Instantaneous CTE over the measured one at :data:`CTE_CHECK_TEMPERATURES_C` [-].
    cte_ratio: tuple[float, ...]
    evaluations: int

    @property
    def rms_c(self) -> float:
        """Root-mean-square of ``fitted - target`` [C].

        Returns
        -------
        float
        """
        return float(np.sqrt(np.mean(np.square(np.subtract(self.fitted_c, self.target_c)))))

    @property
    def all_plausible(self) -> bool:
        """Whether every fitted parameter lies inside its plausible range.

        Returns
        -------
        bool
        """
        return all(p.plausible for p in self.parameters.values())

    def material(self) -> Material:
        """The identified material (preset with the fitted ``rho`` scale)."""
        k = self.parameters["rho_scale"].value if "rho_scale" in self.parameters else 1.0
        return self.reading.base_material().with_expansion_scale(k)

    def to_json(self) -> dict[str, Any]:
        """JSON-serialisable identification.

        Returns
        -------
        dict
            Reading, fitted_to, parameters, rms_c, leave_one_out_c, and the
            detail (targets, fitted temperatures [C], CTE ratios, evaluations).
        """
        return {
            "reading": self.reading.text,
            "turns_reading": self.reading.turns_reading,
            "material": self.reading.material,
            "fitted_to": self.fitted_to,
            "label": "identified (not a default)",
            "parameters": {k: p.to_json() for k, p in self.parameters.items()},
            "rms_c": self.rms_c,
            "leave_one_out_c": list(self.leave_one_out_c),
            "target_c": list(self.target_c),
            "fitted_c": list(self.fitted_c),
            "cte_ratio_at_c": dict(zip([str(t) for t in CTE_CHECK_TEMPERATURES_C], self.cte_ratio)),
            "all_plausible": self.all_plausible,
            "evaluations": self.evaluations,
        }


_PENALTY_C: Final[float] = 250.0  # a grip beyond 160 C: far above every target


def _fit(
    reading: Reading, masses: Sequence[float], target: Sequence[float], x0: Sequence[float], count: list[int]
) -> tuple[np.ndarray, np.ndarray]:
    """Least squares over the free parameters; returns (x, model(x))."""
    opt = require("scipy.optimize")
    tgt = np.asarray(target, dtype=np.float64)
    free = reading.free
    cache: dict[tuple[float, ...], np.ndarray] = {}

    def model(x: np.ndarray) -> np.ndarray:
        key = tuple(float(v) for v in x)
        if key not in cache:
            count[0] += 1
            tc = key[0]
            k = math.exp(key[1]) if "rho_scale" in free else 1.0
            try:
                cache[key] = np.asarray(reading_grip_temperatures(reading, tc, k, masses))
            except ValueError:
                cache[key] = np.full(len(masses), _PENALTY_C)
        return cache[key]

    lo = [25.0, math.log(0.05)][: len(free)]
    hi = [150.0, math.log(20.0)][: len(free)]
    x_start = np.clip(np.asarray(x0[: len(free)], dtype=np.float64), np.add(lo, 1e-9), np.subtract(hi, 1e-9))
    fit = opt.least_squares(
        lambda x: model(x) - tgt,
        x_start,
        bounds=(lo, hi),
        x_scale=[10.0, 0.3][: len(free)],
        diff_step=1e-5,
        xtol=1e-8,
        ftol=1e-10,
    )
    return fit.x, model(fit.x)


def identify(
    reading: Reading,
    fitted_to: Target = "paper_model",
    masses_kg: Sequence[float] = TABLE1_MASSES_KG,
    target_c: Sequence[float] | None = None,
    start: Sequence[float] = (65.0, 0.0),
) -> Identification:
    """Fit the free parameters of ``reading`` to grip temperatures, then leave each mass out.

    Parameters
    ----------
    reading : Reading
        Turns, material and free parameters.
    fitted_to : {"paper_model", "experiment"}, optional
        The target: the paper's predictions (default) or the measurement.
    masses_kg, target_c : sequence of float, optional
        Masses [kg] (default Table I's); target grip temperatures [C] (default
        per ``fitted_to``).
    start : (float, float), optional
        ``(contact [C], log rho_scale)`` to start from.

    Returns
    -------
    Identification
        The fitted parameters with their plausibility, residuals [C] and
        leave-one-out errors [C].

    Raises
    ------
    ValueError
        An unknown ``fitted_to`` or a target of the wrong length.

    Examples
    --------
    >>> from tcarod.models.identification import Reading, identify
    >>> fit = identify(Reading("per_tca", "sun_zhao", free=("contact_temperature_c",)))   # about 2 s
    >>> round(fit.parameters["contact_temperature_c"].value, 1), fit.all_plausible      # [C]
    (102.4, False)
    """
    if fitted_to not in ("paper_model", "experiment"):
        raise ValueError(f"invalid fitted_to = {fitted_to!r}: choose 'paper_model' or 'experiment'")
    if target_c is None:
        target_c = TABLE1_PAPER_PREDICTIONS_C if fitted_to == "paper_model" else TABLE1_EXPERIMENT_C
    tgt = tuple(float(t) for t in target_c)
    if len(tgt) != len(masses_kg) or len(tgt) < 3:
        raise ValueError("identify needs at least three masses_kg and one target temperature [C] per mass")
    count = [0]
    x, fitted = _fit(reading, masses_kg, tgt, start, count)
    loo = []
    for i in range(len(tgt)):
        keep = [j for j in range(len(tgt)) if j != i]
        xi, _ = _fit(reading, [masses_kg[j] for j in keep], [tgt[j] for j in keep], [float(v) for v in x], count)
        k = math.exp(xi[1]) if "rho_scale" in reading.free else 1.0
        try:
            pred = reading_grip_temperatures(reading, float(xi[0]), k, [masses_kg[i]])[0]
        except ValueError:
            pred = _PENALTY_C
        loo.append(pred - tgt[i])
    params = {
        "contact_temperature_c": FitParameter(float(x[0]), contact_range_c(tgt), "C", _CONTACT_SOURCE),
    }
    base = reading.base_material()
    k = 1.0
    if "rho_scale" in reading.free:
        k = math.exp(float(x[1]))
        params["rho_scale"] = FitParameter(k, rho_scale_range(base), "-", _CTE_SOURCE)
    scaled = base.with_expansion_scale(k)
    return Identification(
        reading=reading,
        fitted_to=fitted_to,
        parameters=params,
        target_c=tgt,
        fitted_c=tuple(float(t) for t in fitted),
        leave_one_out_c=tuple(float(v) for v in loo),
        cte_ratio=tuple(cte_ratio(scaled, t) for t in CTE_CHECK_TEMPERATURES_C),
        evaluations=count[0],
    )
