"""The paper's soft bodies (Section V) as :class:`tcarod.Robot` builders,
presented from the core: the designs and constants are defined once, in
``src/experiments.rs`` (shared by the Rust tests and benches), and reach
Python through ``tcarod._core.fixture_*``: EcoFlex 10 bodies (``psi = 1040 kg/m^3``, ``E_B = 37.8 kPa``,
Poisson 0.5) of square section, 10 mm side, with a U-shaped extension TCA
whose two legs run straight at body ``x = +3 mm``, ``y = +-2.5 mm`` (the leg
spacing is not printed in the paper; any symmetric spacing gives the same
planar bending). The manipulators' TCA: ``D = 1.7 mm``, ``alpha0 = 15 deg``,
``N = 76.4`` turns, coiled length = body length (Section V-B).

Turns of a U-shaped TCA (:data:`TURNS_READINGS`; the paper does not say):

* ``"per_tca"`` (default, :data:`DEFAULT_TURNS_READING`): 76.4 turns per
  fabricated TCA, shared by a U's two legs (38.2 per leg), as the folded
  Fig. 5 TCA's halves share theirs. The paper calls the U "a TCA" (V-B),
  "a single extension TCA" (V-C) and each finger "actuated by one TCA"
  (V-D); it considers the halves "as separate TCAs" only to give their length.
* ``"per_leg"``: 76.4 turns in every leg, the literal reading of "N = 76.4"
  for each of the two TCAs the U is split into.
* ``"per_length"``: a twist density, 76.4 turns per 40 mm (the circle's
  single 40 mm TCA), so a leg of length ``L`` has ``76.4 L / 40 mm``.

For the 20 mm Table I finger ``per_tca`` and ``per_length`` coincide (38.2
per leg); for the 26 mm Fig. 8 manipulator they give 38.2 and 49.66; the
circle's single TCA has 76.4 in every reading.

Heating bends the body toward ``-x`` (the TCA side lengthens). Frame: base at
the origin, reference tangent ``+z``. Gravity is given in this body-aligned
frame: ``(0, 0, -9.81)`` for a body standing upright, ``(0, 0, +9.81)`` for a
finger hanging down (the gripper of Section V-D).
"""

from __future__ import annotations

import math
from typing import Any, Final, Literal, Sequence, get_args

from .. import _core
from ..rod import Robot
from ..tca import Material, Tca

__all__ = [
    "PAPER_CONSTANTS",
    "DEFAULT_TURNS_READING",
    "MATERIAL_PRESETS",
    "TURNS_ANCHOR_LENGTH_M",
    "TURNS_READINGS",
    "TurnsReading",
    "leg_turns",
    "material_preset",
    "ECOFLEX10_DENSITY_KG_PER_M3",
    "ECOFLEX10_POISSON",
    "ECOFLEX10_YOUNGS_MODULUS_PA",
    "GRAVITY_M_PER_S2",
    "HANGING",
    "SIDE_M",
    "TCA_COIL_DIAMETER_M",
    "TCA_OFFSET_M",
    "TCA_PITCH_ANGLE_RAD",
    "TCA_TURNS",
    "U_LEG_HALF_SPACING_M",
    "UPRIGHT",
    "manipulator_tca",
    "square_manipulator",
]

#: The paper's constants, defined once in the core (``src/experiments.rs``), SI units.
PAPER_CONSTANTS: Final[dict[str, Any]] = _core.fixture_constants()
#: EcoFlex 10 (Section V): density [kg/m^3], Young's modulus [Pa], Poisson ratio [-].
ECOFLEX10_DENSITY_KG_PER_M3: Final[float] = PAPER_CONSTANTS["ecoflex10_density"]
ECOFLEX10_YOUNGS_MODULUS_PA: Final[float] = PAPER_CONSTANTS["ecoflex10_youngs_modulus"]
ECOFLEX10_POISSON: Final[float] = PAPER_CONSTANTS["ecoflex10_poisson"]
#: Standard gravity [m/s^2].
GRAVITY_M_PER_S2: Final[float] = PAPER_CONSTANTS["gravity"]
#: Gravity [m/s^2] in the body-aligned frame for an upright body / a hanging finger.
UPRIGHT: Final[tuple[float, float, float]] = (0.0, 0.0, -GRAVITY_M_PER_S2)
HANGING: Final[tuple[float, float, float]] = (0.0, 0.0, GRAVITY_M_PER_S2)
#: Side of the square section [m].
SIDE_M: Final[float] = PAPER_CONSTANTS["square_side"]
#: Offset of the TCA legs from the neutral axis along body x [m] (Section V-B).
TCA_OFFSET_M: Final[float] = PAPER_CONSTANTS["tca_offset"]
#: Half the spacing of the two legs along body y [m] (not printed in the paper).
U_LEG_HALF_SPACING_M: Final[float] = PAPER_CONSTANTS["u_leg_half_spacing"]
#: The manipulators' TCA (Section V-B): coil diameter [m], pitch angle [rad], turns [-].
TCA_COIL_DIAMETER_M: Final[float] = PAPER_CONSTANTS["manipulator_coil_diameter"]
TCA_PITCH_ANGLE_RAD: Final[float] = math.radians(PAPER_CONSTANTS["manipulator_pitch_deg"])
TCA_TURNS: Final[float] = PAPER_CONSTANTS["manipulator_turns"]
#: Coiled length [m] of the circle's single TCA, the anchor of the ``"per_length"`` reading.
TURNS_ANCHOR_LENGTH_M: Final[float] = PAPER_CONSTANTS["turns_anchor_length"]

TurnsReading = Literal["per_tca", "per_leg", "per_length"]
#: The readings of the printed turns, default first (see the module docstring).
TURNS_READINGS: Final[tuple[TurnsReading, ...]] = get_args(TurnsReading)
DEFAULT_TURNS_READING: Final[TurnsReading] = "per_tca"

#: Material presets by name: the documented default (Sun & Zhao's diameter
#: fit) and the measured radial CTE of oriented nylon 6,6 (Choy et al. 1984).
MATERIAL_PRESETS: Final[dict[str, str]] = {
    "sun_zhao": "Material.silver_coated_nylon(): rho(T) from Sun & Zhao's fibre-diameter fit (default)",
    "measured_cte": "Material.nylon66_measured_cte(): rho(T) fitted to the measured radial CTE of oriented "
    "nylon 6,6 (Choy et al. 1984)",
}


def material_preset(name: str) -> Material:
    """The TCA fibre material preset ``name``.

    Parameters
    ----------
    name : {"sun_zhao", "measured_cte"}
        A key of :data:`MATERIAL_PRESETS`: the documented default (Sun & Zhao's
        fibre-diameter fit) or the measured radial CTE of oriented nylon 6,6.

    Returns
    -------
    Material
        The material (moduli [Pa], expansion [1/C], temperature range [C]).

    Raises
    ------
    ValueError
        An unknown ``name``.

    Examples
    --------
    >>> from tcarod.models.manipulators import material_preset
    >>> material_preset("sun_zhao") == tcarod.Material.silver_coated_nylon()
    True
    """
    if name == "sun_zhao":
        return Material.silver_coated_nylon()
    if name == "measured_cte":
        return Material.nylon66_measured_cte()
    raise ValueError(f"invalid material preset = {name!r}: choose from {list(MATERIAL_PRESETS)}")


def leg_turns(length_m: float, legs: int, reading: TurnsReading = DEFAULT_TURNS_READING) -> float:
    """Turns of one leg of a manipulator TCA [-].

    The core's rule for reading the paper's 76.4 printed turns.

    Parameters
    ----------
    length_m : float
        Coiled length of the leg [m].
    legs : int
        Legs of the TCA: 1 straight, 2 U-shaped.
    reading : {"per_tca", "per_leg", "per_length"}, optional
        ``"per_tca"`` (default): 76.4 turns per fabricated TCA, shared by its
        legs; ``"per_leg"``: 76.4 per leg; ``"per_length"``: the twist per
        length of 76.4 turns over 40 mm.

    Returns
    -------
    float
        Turns of the leg [-].

    Raises
    ------
    ValueError
        A non-positive ``length_m``, ``legs`` < 1 or an unknown ``reading``.

    Examples
    --------
    >>> from tcarod.models.manipulators import leg_turns
    >>> leg_turns(0.040, 2), leg_turns(0.040, 2, "per_leg"), round(leg_turns(0.060, 1, "per_length"), 1)
    (38.2, 76.4, 114.6)
    """
    return float(_core.fixture_leg_turns(length_m, legs, reading))


def manipulator_tca(
    length_m: float,
    *,
    turns: float = TCA_TURNS,
    coil_diameter_m: float = TCA_COIL_DIAMETER_M,
    material: Material | None = None,
) -> Tca:
    """The manipulators' extension TCA, or one leg of it (Section V-B).

    Pitch angle ``alpha0 = 15 deg``, fibre length ``l = L / sin(alpha0)``.

    Parameters
    ----------
    length_m : float
        Coiled length ``L`` [m].
    turns : float, optional
        Turns [-] (default 76.4; see :func:`leg_turns` for a U's legs).
    coil_diameter_m : float, optional
        Coil diameter [m] (default 1.7 mm).
    material : Material, optional
        Fibre material (default :meth:`Material.silver_coated_nylon`).

    Returns
    -------
    Tca
        The TCA.

    Raises
    ------
    ValueError
        A geometry out of range (named, with its unit).

    Examples
    --------
    >>> from tcarod.models.manipulators import manipulator_tca
    >>> tca = manipulator_tca(0.040)
    >>> round(tca.fibre_length * 1e3, 1), tca.turns, tca.chirality     # [mm], [-]
    (154.5, 76.4, 'extension')
    """
    return Tca.from_pitch_angle(length_m, TCA_PITCH_ANGLE_RAD, coil_diameter_m, turns, "extension", material)


def square_manipulator(
    length_m: float,
    *,
    gravity_m_per_s2: Sequence[float] | None = UPRIGHT,
    material: Material | None = None,
    body_youngs_modulus_pa: float = ECOFLEX10_YOUNGS_MODULUS_PA,
    tca_offset_m: float = TCA_OFFSET_M,
    coil_diameter_m: float = TCA_COIL_DIAMETER_M,
    turns_reading: TurnsReading = DEFAULT_TURNS_READING,
) -> Robot:
    """A square EcoFlex manipulator with a U-shaped TCA (the paper's Fig. 6 square).

    A body of 10 mm side with the TCA's two legs at body ``x = tca_offset_m``,
    ``y = +-2.5 mm``, anchored at base and tip, each with :func:`leg_turns`
    turns. One temperature drives both legs: use ``groups=[0, 0]`` in the
    inverse functions. Built by the core (``Manipulator::square`` in
    ``src/experiments.rs``).

    Parameters
    ----------
    length_m : float
        Body length [m].
    gravity_m_per_s2 : sequence of 3 float or None, optional
        Gravity [m/s^2] in the body-aligned frame: :data:`UPRIGHT` (default),
        :data:`HANGING` for a finger hanging down, ``None`` for none.
    material : Material, optional
        TCA fibre material.
    body_youngs_modulus_pa : float, optional
        Body Young's modulus [Pa] (default EcoFlex 10's 37.8 kPa).
    tca_offset_m : float, optional
        Leg offset from the neutral axis [m] (default 3 mm).
    coil_diameter_m : float, optional
        TCA coil diameter [m] (default 1.7 mm).
    turns_reading : {"per_tca", "per_leg", "per_length"}, optional
        How the paper's turns are read (default ``"per_tca"``).

    Returns
    -------
    Robot
        The manipulator.

    Raises
    ------
    ValueError
        A parameter out of range (named, with its unit).

    Examples
    --------
    >>> from tcarod.models.manipulators import square_manipulator
    >>> robot = square_manipulator(0.040)
    >>> sol = robot.solve([100.0, 100.0])          # both legs at 100 C
    >>> round(float(sol.tip_position[0]) * 1e3, 2)  # tip x [mm]: bent away from the TCA
    -6.13
    """
    return _core.fixture_manipulator(
        "square",
        length=length_m,
        gravity=(0.0, 0.0, 0.0) if gravity_m_per_s2 is None else gravity_m_per_s2,
        material=material,
        youngs_modulus=body_youngs_modulus_pa,
        tca_offset=tca_offset_m,
        coil_diameter=coil_diameter_m,
        turns_reading=turns_reading,
    )
