"""Parameter studies of the Table I grasp prediction (paper Section V-D).

The paper does not print the TCA material values behind its Table I
predictions (93.7 / 114.8 / 136.3 C for 1 / 2 / 3 g); with tcarod's documented
default material (``docs/choices.md``) and the default set-up of
``docs/table1.md`` (contact at 72.33 C, 76.4 turns per U-shaped TCA) the same
model predicts 80.9 / 88.7 / 96.0 C. Two questions, answered separately:

1. :func:`table1_sensitivity`: which material or geometry parameter moves the
   prediction most? Each parameter is scaled by ``1 +- step`` (default 10 %),
   all others held (``dG_T/dT`` is held too when ``E_T`` or ``dE_T/dT`` move),
   and the grip temperature recomputed for each mass. Reported per parameter
   and mass: ``dT/dln p`` [C per unit relative change] (central difference)
   and the elasticity of the temperature *rise* above contact,
   ``d ln(T - T_contact) / d ln p`` [-] (the rise has a meaningful zero).
2. :mod:`tcarod.models.identification`: an *identification*, not a default: at
   most two parameters (contact temperature, one ``rho`` scale) fitted to
   the paper's predictions and, separately, to the experiment, with
   leave-one-out errors and plausibility checks.

The sensitivity uses the default finger (turns read per TCA) touching the
object at :data:`tcarod.models.grasp.TABLE1_CONTACT_TEMPERATURE_C`, and the direct
blocked-tip solve (:func:`tcarod.inverse.blocked_temperature_direct`,
falling back on the incremental eq-43 method if Newton fails); the two agree
to ~1e-9 C. Nothing here changes a default.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Final, Sequence

import numpy as np

from .._core import ConvergenceError
from .manipulators import TCA_COIL_DIAMETER_M, TCA_OFFSET_M, ECOFLEX10_YOUNGS_MODULUS_PA
from .grasp import (
    TABLE1_CONTACT_TEMPERATURE_C,
    TABLE1_MASSES_KG,
    TABLE1_PAPER_PREDICTIONS_C,
    grasp_temperature,
    table1_finger,
)
from ..rod import Robot
from .. import _validate as V
from ..tca import Material

__all__ = [
    "PAPER_TABLE1_PREDICTIONS_C",
    "PARAMETERS",
    "TABLE1_MASSES_KG",
    "Parameter",
    "Sensitivity",
    "perturbed_finger",
    "table1_grip_temperatures",
    "table1_sensitivity",
]

#: The paper's own Table I predictions [C] (alias of :data:`tcarod.models.grasp.TABLE1_PAPER_PREDICTIONS_C`).
PAPER_TABLE1_PREDICTIONS_C: Final[tuple[float, ...]] = TABLE1_PAPER_PREDICTIONS_C


@dataclass(frozen=True)
class Parameter:
    """A design parameter of the Table I finger that a study scales.

    Examples
    --------
    >>> from tcarod.models.studies import PARAMETERS
    >>> p = PARAMETERS[6]
    >>> p.key, p.default, p.unit
    ('E_B', 37800.0, 'Pa')
    """

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
    """The Table I finger with parameters multiplied by ``scales``.

    Material coefficients not scaled keep their default values (``dG_T/dT``
    included).

    Parameters
    ----------
    scales : dict of str to float, optional
        Factors [-] by key of :data:`PARAMETERS` (``{"rho": 0.5}`` halves
        ``rho(25 C)``); default none.

    Returns
    -------
    Robot
        The finger, hanging.

    Raises
    ------
    TypeError
        ``scales`` not a dict.
    ValueError
        An unknown key.

    Examples
    --------
    >>> from tcarod.models.studies import perturbed_finger
    >>> perturbed_finger({"E_B": 1.1}).body.youngs_modulus      # [Pa], 10 % stiffer body
    41580.0
    """
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
    tc = TABLE1_CONTACT_TEMPERATURE_C
    try:
        return grasp_temperature(mass_kg, finger, method="direct", contact_temperature_c=tc)
    except ConvergenceError:
        return grasp_temperature(mass_kg, finger, method="incremental", contact_temperature_c=tc)


def table1_grip_temperatures(
    scales: dict[str, float] | None = None, masses_kg: Sequence[float] = TABLE1_MASSES_KG
) -> tuple[float, ...]:
    """Grip temperatures of the Table I finger with ``scales`` applied.

    Eq 44 with ``mu = 1.1`` and two fingers (see :func:`perturbed_finger`).

    Parameters
    ----------
    scales : dict of str to float, optional
        Factors [-] by key of :data:`PARAMETERS`.
    masses_kg : sequence of float, optional
        Masses [kg] (default Table I's 1, 2 and 3 g).

    Returns
    -------
    tuple of float
        Grip temperature [C] per mass.

    Raises
    ------
    ValueError
        A mass that needs a temperature above the material's range.

    Examples
    --------
    >>> from tcarod.models.studies import table1_grip_temperatures
    >>> [round(t, 1) for t in table1_grip_temperatures()]     # [C]
    [80.9, 88.7, 96.0]
    """
    finger = perturbed_finger(scales)
    masses = V.real_array("masses_kg", masses_kg, ndim=1, max_size=100, unit="kg")
    return tuple(_grip(finger, float(m)) for m in masses)


@dataclass(frozen=True)
class Sensitivity:
    """Response of the Table I prediction to one parameter.

    Grip temperatures [C] at the base value and at ``1 -+ step`` times it.

    Examples
    --------
    >>> from tcarod.models.studies import table1_sensitivity
    >>> top = table1_sensitivity()[0]                   # the most influential parameter
    >>> top.parameter.key, round(top.mean_abs_elasticity, 2)
    ('coil_diameter', 1.1)
    """

    parameter: Parameter
    step: float
    #: Grip temperatures [C] per mass at the default, at ``1 - step`` and ``1 + step`` times the parameter.
    base_c: tuple[float, ...]
    minus_c: tuple[float, ...]
    plus_c: tuple[float, ...]

    @property
    def slope_c(self) -> tuple[float, ...]:
        """``dT / d ln p`` per mass (central difference) [C].

        Returns
        -------
        tuple of float
            One slope [C] per mass.
        """
        return tuple((p - m) / (2.0 * self.step) for p, m in zip(self.plus_c, self.minus_c))

    @property
    def elasticity(self) -> tuple[float, ...]:
        """``d ln(T - T_contact) / d ln p`` per mass [-].

        Returns
        -------
        tuple of float
            One elasticity [-] per mass: of the rise above contact.
        """
        return tuple(s / (b - TABLE1_CONTACT_TEMPERATURE_C) for s, b in zip(self.slope_c, self.base_c))

    @property
    def mean_abs_elasticity(self) -> float:
        """Mean over the masses of ``|elasticity|`` [-]: the ranking key.

        Returns
        -------
        float
            Mean [-].
        """
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


def table1_sensitivity(step: float = 0.10, masses_kg: Sequence[float] = TABLE1_MASSES_KG) -> tuple[Sensitivity, ...]:
    """The sensitivity of the Table I prediction to every parameter, largest first.

    Every parameter of :data:`PARAMETERS` scaled by ``1 -+ step``, sorted by
    :attr:`Sensitivity.mean_abs_elasticity`.

    Parameters
    ----------
    step : float, optional
        Relative step [-], in (0, 0.5) (default 0.10).
    masses_kg : sequence of float, optional
        Masses [kg] (default Table I's).

    Returns
    -------
    tuple of Sensitivity
        One per parameter, largest first.

    Raises
    ------
    ValueError
        A step outside (0, 0.5).

    Examples
    --------
    >>> from tcarod.models.studies import table1_sensitivity
    >>> [s.parameter.key for s in table1_sensitivity()][:3]
    ['coil_diameter', 'rho(T)', 'E_B']
    """
    step = V.real("step", step, lo=0.0, hi=0.5, lo_open=True, hi_open=True)
    base = table1_grip_temperatures(None, masses_kg)
    out = []
    for p in PARAMETERS:
        minus = table1_grip_temperatures({p.key: 1.0 - step}, masses_kg)
        plus = table1_grip_temperatures({p.key: 1.0 + step}, masses_kg)
        out.append(Sensitivity(parameter=p, step=step, base_c=base, minus_c=minus, plus_c=plus))
    return tuple(sorted(out, key=lambda s: -s.mean_abs_elasticity))
