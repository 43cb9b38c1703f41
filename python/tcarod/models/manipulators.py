"""The paper's soft bodies (Section V) as :class:`tcarod.Robot` builders.

The same designs as ``src/experiments.rs`` (shared by the Rust tests and
benches): EcoFlex 10 bodies (``psi = 1040 kg/m^3``, ``E_B = 37.8 kPa``,
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
* ``"per_leg"``: 76.4 turns in every leg (the reading before issue 13).
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
from typing import Final, Literal, Sequence, get_args

from ..rod import Actuator, Body, Robot, Routing, Section
from ..tca import Material, Tca

__all__ = [
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

#: EcoFlex 10 (Section V): density [kg/m^3], Young's modulus [Pa], Poisson ratio [-].
ECOFLEX10_DENSITY_KG_PER_M3: Final[float] = 1040.0
ECOFLEX10_YOUNGS_MODULUS_PA: Final[float] = 37.8e3
ECOFLEX10_POISSON: Final[float] = 0.5
#: Standard gravity [m/s^2].
GRAVITY_M_PER_S2: Final[float] = 9.81
#: Gravity [m/s^2] in the body-aligned frame for an upright body / a hanging finger.
UPRIGHT: Final[tuple[float, float, float]] = (0.0, 0.0, -GRAVITY_M_PER_S2)
HANGING: Final[tuple[float, float, float]] = (0.0, 0.0, GRAVITY_M_PER_S2)
#: Side of the square section [m].
SIDE_M: Final[float] = 10e-3
#: Offset of the TCA legs from the neutral axis along body x [m] (Section V-B).
TCA_OFFSET_M: Final[float] = 3e-3
#: Half the spacing of the two legs along body y [m] (not printed in the paper).
U_LEG_HALF_SPACING_M: Final[float] = 2.5e-3
#: The manipulators' TCA (Section V-B): coil diameter [m], pitch angle [rad], turns [-].
TCA_COIL_DIAMETER_M: Final[float] = 1.7e-3
TCA_PITCH_ANGLE_RAD: Final[float] = math.radians(15.0)
TCA_TURNS: Final[float] = 76.4
#: Coiled length [m] of the circle's single TCA, the anchor of the ``"per_length"`` reading.
TURNS_ANCHOR_LENGTH_M: Final[float] = 0.040

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
    """The material preset ``name`` (a key of :data:`MATERIAL_PRESETS`)."""
    if name == "sun_zhao":
        return Material.silver_coated_nylon()
    if name == "measured_cte":
        return Material.nylon66_measured_cte()
    raise ValueError(f"invalid material preset = {name!r}: choose from {list(MATERIAL_PRESETS)}")


def leg_turns(length_m: float, legs: int, reading: TurnsReading = DEFAULT_TURNS_READING) -> float:
    """Turns [-] of one leg of coiled length ``length_m`` [m] of a manipulator
    TCA with ``legs`` legs (1 straight, 2 U-shaped) under ``reading``."""
    if reading == "per_tca":
        return TCA_TURNS / legs
    if reading == "per_leg":
        return TCA_TURNS
    if reading == "per_length":
        return TCA_TURNS * length_m / TURNS_ANCHOR_LENGTH_M
    raise ValueError(f"invalid turns reading = {reading!r}: choose from {list(TURNS_READINGS)}")


def manipulator_tca(
    length_m: float,
    *,
    turns: float = TCA_TURNS,
    coil_diameter_m: float = TCA_COIL_DIAMETER_M,
    material: Material | None = None,
) -> Tca:
    """The manipulators' extension TCA (or one leg of it) of coiled length
    ``length_m`` [m]: ``alpha0 = 15 deg``, ``turns`` turns (default 76.4; see
    :func:`leg_turns` for a U's legs), coil diameter ``coil_diameter_m`` [m],
    fibre length ``l = L / sin(alpha0)`` (default material:
    :meth:`Material.silver_coated_nylon`)."""
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
    """A square EcoFlex body (10 mm side) of length ``length_m`` [m] with a
    U-shaped TCA: two legs at body ``x = tca_offset_m`` [m],
    ``y = +-2.5 mm``, anchored at base and tip (one temperature drives both:
    use ``groups=[0, 0]`` in :mod:`tcarod.inverse`), each with
    :func:`leg_turns` turns under ``turns_reading``.

    ``gravity_m_per_s2``: gravity in the body-aligned frame (default
    :data:`UPRIGHT`; :data:`HANGING` for a finger hanging down; ``None`` for
    none). The other keywords replace one parameter for sensitivity studies.
    Same design as ``square_manipulator`` in ``src/experiments.rs``.
    """
    gravity = None if gravity_m_per_s2 is None else [float(g) for g in gravity_m_per_s2]
    body = Body(
        length_m,
        Section.rectangle(SIDE_M, SIDE_M),
        body_youngs_modulus_pa,
        poisson=ECOFLEX10_POISSON,
        density=ECOFLEX10_DENSITY_KG_PER_M3,
        gravity=gravity,
    )
    turns = leg_turns(length_m, 2, turns_reading)
    tca = manipulator_tca(length_m, turns=turns, coil_diameter_m=coil_diameter_m, material=material)
    legs = [Actuator.tca(tca, Routing.straight(tca_offset_m, y)) for y in (U_LEG_HALF_SPACING_M, -U_LEG_HALF_SPACING_M)]
    return Robot(body, legs)
