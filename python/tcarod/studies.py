"""Parameter studies of the Table I grasp prediction (paper Section V-D).

The paper does not print the TCA material values behind its Table I
predictions (93.7 / 114.8 / 136.3 C for 1 / 2 / 3 g); with tcarod's documented
default material (README, NOTES.md section 5) the same model predicts about
38 / 47 / 54 C. Two questions, answered separately:

1. :func:`table1_sensitivity`: which material or geometry parameter moves the
   prediction most? Each parameter is scaled by ``1 +- step`` (default 10 %),
   all others held (``dG_T/dT`` is held too when ``E_T`` or ``dE_T/dT`` move),
   and the grip temperature recomputed for each mass. Reported per parameter
   and mass: ``dT/dln p`` [C per unit relative change] (central difference)
   and the elasticity of the temperature *rise* above ambient,
   ``d ln(T - 25) / d ln p`` [-] (the rise, not T in C, has a meaningful zero).
2. :func:`identify_table1`: an *identification*, not a default. Scale factors
   on the one or two most sensitive parameters are fitted in least squares
   to the paper's own predictions, with residuals, and the fitted values are
   compared with what is known for nylon 6,6 (radial CTE of oriented nylon
   6,6: 15.5e-5 to 43.7e-5 1/K, NOTES.md section 5).

Both use the direct blocked-tip solve (:func:`tcarod.inverse.
blocked_temperature_direct`, falling back on the incremental eq-43 method if
Newton fails); the two agree to ~1e-9 C. Nothing here changes a default.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable, Final, Sequence

import numpy as np

from ._core import ConvergenceError
from .manipulators import TCA_COIL_DIAMETER_M, TCA_OFFSET_M, ECOFLEX10_YOUNGS_MODULUS_PA
from .grasp import grasp_temperature, table1_finger
from .rod import Robot
from . import _validate as V
from ._optional import require
from .tca import Material

__all__ = [
    "PAPER_TABLE1_PREDICTIONS_C",
    "PARAMETERS",
    "TABLE1_MASSES_KG",
    "Identification",
    "Parameter",
    "Sensitivity",
    "identify_table1",
    "perturbed_finger",
    "table1_grip_temperatures",
    "table1_sensitivity",
]

#: Table I masses [kg] and the paper's own model predictions [C] for them.
TABLE1_MASSES_KG: Final[tuple[float, ...]] = (1e-3, 2e-3, 3e-3)
PAPER_TABLE1_PREDICTIONS_C: Final[tuple[float, ...]] = (93.7, 114.8, 136.3)
#: Ambient (reference) temperature [C] of the default material.
_AMBIENT_C: Final[float] = 25.0


@dataclass(frozen=True)
class Parameter:
    """A design parameter that a study scales."""

    key: str
    description: str
    #: Value in the default design [SI unit in ``unit``].
    default: float
    unit: str


def _default_material_coefficients() -> tuple[float, float, float, float, float, float]:
    return Material.silver_coated_nylon().coefficients


_C0 = _default_material_coefficients()

#: The parameters of the sensitivity study, in report order.
PARAMETERS: Final[tuple[Parameter, ...]] = (
    Parameter("E_T", "fibre Young's modulus E_T at 25 C", _C0[0], "Pa"),
    Parameter("dE_T/dT", "slope of E_T with temperature", _C0[1], "Pa/C"),
    Parameter("G_T", "fibre shear modulus G_T at 25 C", _C0[2], "Pa"),
    Parameter("rho", "fibre radial expansion coefficient rho at 25 C", _C0[4], "1/C"),
    Parameter("drho/dT", "slope of rho with temperature", _C0[5], "1/C^2"),
    Parameter("rho(T)", "the whole expansion law: rho and drho/dT scaled together", _C0[4], "1/C (at 25 C)"),
    Parameter("E_B", "body (EcoFlex 10) Young's modulus", ECOFLEX10_YOUNGS_MODULUS_PA, "Pa"),
    Parameter("tca_offset", "TCA offset from the neutral axis", TCA_OFFSET_M, "m"),
    Parameter("coil_diameter", "TCA coil diameter D", TCA_COIL_DIAMETER_M, "m"),
)
_KEYS: Final[tuple[str, ...]] = tuple(p.key for p in PARAMETERS)


def perturbed_finger(scales: dict[str, float] | None = None) -> Robot:
    """The Table I finger with parameters multiplied by ``scales``
    (``{"rho": 0.5}`` halves ``rho(25 C)``); keys from :data:`PARAMETERS`.
    Material coefficients not scaled keep their default values (``dG_T/dT``
    included)."""
    if scales is not None and not isinstance(scales, dict):
        raise TypeError(f"scales must be a dict {{parameter: factor}}, not {type(scales).__name__}")
    s = dict(scales or {})
    unknown = set(s) - set(_KEYS)
    if unknown:
        raise ValueError(f"unknown parameter(s) {sorted(map(repr, unknown))}; choose from {list(_KEYS)}")
    for k in list(s):
        # scale factors within 1e-3..1e3: beyond that the finger is no longer a finger
        s[k] = V.real(f"scales[{k!r}]", s[k], lo=1e-3, hi=1e3)
    e, de, g, dg, rho, drho = _C0
    base = Material.silver_coated_nylon()
    material = Material(
        youngs_modulus=e * s.get("E_T", 1.0),
        youngs_modulus_slope=de * s.get("dE_T/dT", 1.0),
        shear_modulus=g * s.get("G_T", 1.0),
        shear_modulus_slope=dg,
        expansion=rho * s.get("rho", 1.0) * s.get("rho(T)", 1.0),
        expansion_slope=drho * s.get("drho/dT", 1.0) * s.get("rho(T)", 1.0),
        t_ref=base.t_ref,
        t_min=base.t_min,
        t_max=base.t_max,
        name="scaled silver-coated nylon",
    )
    return table1_finger(
        material=material,
        body_youngs_modulus_pa=ECOFLEX10_YOUNGS_MODULUS_PA * s.get("E_B", 1.0),
        tca_offset_m=TCA_OFFSET_M * s.get("tca_offset", 1.0),
        coil_diameter_m=TCA_COIL_DIAMETER_M * s.get("coil_diameter", 1.0),
    )


def _grip(finger: Robot, mass_kg: float) -> float:
    try:
        return grasp_temperature(mass_kg, finger, method="direct")
    except ConvergenceError:
        return grasp_temperature(mass_kg, finger, method="incremental")


def table1_grip_temperatures(
    scales: dict[str, float] | None = None, masses_kg: Sequence[float] = TABLE1_MASSES_KG
) -> tuple[float, ...]:
    """Grip temperatures [C] (eq 44, ``mu = 1.1``, two fingers) of the Table I
    finger with ``scales`` applied (see :func:`perturbed_finger`). Raises
    ``ValueError`` if a mass needs a temperature above the material's range."""
    finger = perturbed_finger(scales)
    masses = V.real_array("masses_kg", masses_kg, ndim=1, max_size=100, unit="kg")
    return tuple(_grip(finger, float(m)) for m in masses)


@dataclass(frozen=True)
class Sensitivity:
    """Response of the Table I prediction to one parameter."""

    parameter: Parameter
    step: float
    #: Grip temperatures [C] per mass at the default, at ``1 - step`` and ``1 + step`` times the parameter.
    base_c: tuple[float, ...]
    minus_c: tuple[float, ...]
    plus_c: tuple[float, ...]

    @property
    def slope_c(self) -> tuple[float, ...]:
        """``dT / d ln p`` [C] per mass (central difference)."""
        return tuple((p - m) / (2.0 * self.step) for p, m in zip(self.plus_c, self.minus_c))

    @property
    def elasticity(self) -> tuple[float, ...]:
        """``d ln(T - 25 C) / d ln p`` [-] per mass."""
        return tuple(s / (b - _AMBIENT_C) for s, b in zip(self.slope_c, self.base_c))

    @property
    def mean_abs_elasticity(self) -> float:
        """Mean over the masses of ``|elasticity|`` [-]: the ranking key."""
        return float(np.mean(np.abs(self.elasticity)))

    def to_json(self) -> dict[str, Any]:
        """JSON-serialisable; temperatures in C."""
        p = self.parameter
        return {
            "parameter": p.key,
            "description": p.description,
            "default": p.default,
            "unit": p.unit,
            "relative_step": self.step,
            "grip_temperature_minus_c": list(self.minus_c),
            "grip_temperature_plus_c": list(self.plus_c),
            "dT_dlnp_c": list(self.slope_c),
            "elasticity_of_rise": list(self.elasticity),
            "mean_abs_elasticity": self.mean_abs_elasticity,
        }


def table1_sensitivity(
    step: float = 0.10, masses_kg: Sequence[float] = TABLE1_MASSES_KG
) -> tuple[Sensitivity, ...]:
    """Every parameter of :data:`PARAMETERS` scaled by ``1 -+ step``; sorted
    by :attr:`Sensitivity.mean_abs_elasticity`, largest first."""
    step = V.real("step", step, lo=0.0, hi=0.5, lo_open=True, hi_open=True)
    base = table1_grip_temperatures(None, masses_kg)
    out = []
    for p in PARAMETERS:
        minus = table1_grip_temperatures({p.key: 1.0 - step}, masses_kg)
        plus = table1_grip_temperatures({p.key: 1.0 + step}, masses_kg)
        out.append(Sensitivity(parameter=p, step=step, base_c=base, minus_c=minus, plus_c=plus))
    return tuple(sorted(out, key=lambda s: -s.mean_abs_elasticity))


@dataclass(frozen=True)
class Identification:
    """Least-squares scale factors that make the model reproduce a target set
    of grip temperatures. An identification, not a default."""

    keys: tuple[str, ...]
    scales: tuple[float, ...]
    target_c: tuple[float, ...]
    fitted_c: tuple[float, ...]
    #: Evaluations of the three-mass prediction used by the fit.
    evaluations: int

    @property
    def residuals_c(self) -> tuple[float, ...]:
        """``fitted - target`` [C] per mass."""
        return tuple(f - t for f, t in zip(self.fitted_c, self.target_c))

    @property
    def rms_c(self) -> float:
        """Root-mean-square residual [C]."""
        return float(np.sqrt(np.mean(np.square(self.residuals_c))))

    def values(self) -> dict[str, float]:
        """Fitted parameter values (default x scale), in their SI units."""
        default = {p.key: p.default for p in PARAMETERS}
        return {k: default[k] * s for k, s in zip(self.keys, self.scales)}

    def to_json(self) -> dict[str, Any]:
        """JSON-serialisable; temperatures in C."""
        units = {p.key: p.unit for p in PARAMETERS}
        return {
            "parameters": list(self.keys),
            "scale_factors": list(self.scales),
            "fitted_values": {k: {"value": v, "unit": units[k]} for k, v in self.values().items()},
            "target_c": list(self.target_c),
            "fitted_c": list(self.fitted_c),
            "residuals_c": list(self.residuals_c),
            "rms_c": self.rms_c,
            "evaluations": self.evaluations,
        }


def identify_table1(
    keys: Sequence[str] = ("rho", "drho/dT"),
    target_c: Sequence[float] = PAPER_TABLE1_PREDICTIONS_C,
    masses_kg: Sequence[float] = TABLE1_MASSES_KG,
    start: Sequence[float] | None = None,
) -> Identification:
    """Scale factors on the parameters ``keys`` (one or two) minimising
    ``sum (T_model(m) - target(m))^2`` over the masses (scipy
    ``least_squares``, trust-region reflective, scales in [0.01, 100], log
    parameterised). Where a trial needs more than the material's top
    temperature, its residual is the distance of that top temperature plus the
    missing margin, so the fit is steered back into range.

    ``start``: initial scale factors (default 1).
    """
    least_squares = require("scipy.optimize").least_squares

    ks = tuple(V.sequence("keys", keys, 3))
    if not all(isinstance(k, str) for k in ks):
        raise TypeError(f"keys must be parameter names (str), got {list(ks)}")
    if not 1 <= len(ks) <= 2 or any(k not in _KEYS for k in ks):
        raise ValueError(f"keys must be one or two of {list(_KEYS)}, got {list(ks)}")
    masses_kg = tuple(float(m) for m in V.real_array("masses_kg", masses_kg, ndim=1, max_size=100, unit="kg"))
    tgt = V.real_array("target_c", target_c, ndim=1, max_size=100, unit="C")
    if tgt.shape != (len(masses_kg),):
        raise ValueError("target_c needs one temperature [C] per mass")
    start_v = np.asarray(V.vector("start", start, len(ks)) if start is not None else [1.0] * len(ks), dtype=np.float64)
    if not np.all(start_v > 0.0):
        raise ValueError(f"invalid start = {start_v.tolist()}: scale factors must be > 0")
    x0 = np.log(start_v)
    count = [0]
    cache: dict[tuple[float, ...], np.ndarray] = {}

    def model(x: np.ndarray) -> np.ndarray:
        key = tuple(float(v) for v in x)
        if key not in cache:
            count[0] += 1
            scales = {k: math.exp(v) for k, v in zip(ks, x)}
            try:
                cache[key] = np.asarray(table1_grip_temperatures(scales, masses_kg))
            except ValueError:
                cache[key] = np.full(len(masses_kg), 250.0)  # out of range: far above any target
        return cache[key]

    res_fn: Callable[[np.ndarray], np.ndarray] = lambda x: model(x) - tgt  # noqa: E731
    fit = least_squares(res_fn, x0, bounds=(math.log(0.01), math.log(100.0)), x_scale=1.0, diff_step=1e-4, xtol=1e-10)
    fitted = model(fit.x)
    return Identification(
        keys=ks,
        scales=tuple(float(math.exp(v)) for v in fit.x),
        target_c=tuple(float(t) for t in tgt),
        fitted_c=tuple(float(t) for t in fitted),
        evaluations=count[0],
    )
