"""Grasping with TCA-actuated fingers (paper Section V-D, eq 44).

A gripper of ``n`` identical fingers holds a mass ``m`` by friction when each
finger presses on the object with the normal force ``F`` of

    mu n F(T) = m g                                              (eq 44)

``F(T)`` is the blocked-tip force of one finger at TCA temperature ``T``: the
finger's tip is held at its reference position (the object's surface touches
the relaxed finger) and presses along ``normal``. :func:`grasp` solves for
``T`` with the paper's incremental inverse (eq 43, :func:`tcarod.inverse.
blocked_temperature`) or directly (:func:`tcarod.inverse.
blocked_temperature_direct`).

The default finger (:func:`table1_finger`) is the Table I finger: a 20 mm
long square EcoFlex body (10 mm side) with a U-shaped TCA at body
``x = +3 mm``, ``y = +-2.5 mm``, hanging down (gravity ``(0, 0, +9.81)`` in
the body-aligned frame), pressing along ``-x`` (heating bends it toward
``-x``). Units: kg, N, m, m/s^2; temperatures in C.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Final, Literal, Sequence

from .manipulators import HANGING, square_manipulator
from .inverse import BlockedResult, blocked_temperature, blocked_temperature_direct
from .rod import Robot
from .tca import Material

__all__ = [
    "FRICTION_COEFFICIENT",
    "GRASP_NORMAL",
    "TABLE1_FINGER_LENGTH_M",
    "Grasp",
    "grasp",
    "grasp_temperature",
    "table1_finger",
]

#: Length of each gripper finger [m] (Section V-D).
TABLE1_FINGER_LENGTH_M: Final[float] = 0.020
#: Friction coefficient between VeroClear RGD810 and EcoFlex 10 [-] (Section V-D).
FRICTION_COEFFICIENT: Final[float] = 1.1
#: Direction [-] (body-aligned frame) in which the fingertip presses on the object.
GRASP_NORMAL: Final[tuple[float, float, float]] = (-1.0, 0.0, 0.0)


def table1_finger(
    *,
    material: Material | None = None,
    body_youngs_modulus_pa: float | None = None,
    tca_offset_m: float | None = None,
    coil_diameter_m: float | None = None,
) -> Robot:
    """The Table I gripper finger (see the module docstring), hanging down.
    Keywords replace one design parameter (default: the paper's / the
    documented default material)."""
    kw: dict[str, Any] = {}
    if body_youngs_modulus_pa is not None:
        kw["body_youngs_modulus_pa"] = body_youngs_modulus_pa
    if tca_offset_m is not None:
        kw["tca_offset_m"] = tca_offset_m
    if coil_diameter_m is not None:
        kw["coil_diameter_m"] = coil_diameter_m
    return square_manipulator(TABLE1_FINGER_LENGTH_M, gravity_m_per_s2=HANGING, material=material, **kw)


@dataclass(frozen=True, eq=False)
class Grasp:
    """Solution of eq (44) for one mass."""

    mass_kg: float
    mu: float
    fingers: int
    gravity_m_per_s2: float
    #: Normal force [N] each finger must exert, ``m g / (mu n)``.
    force_per_finger_n: float
    #: Grip temperature [C] of the TCA(s) of each finger.
    temperature_c: float
    #: Where the fingertip is blocked [m] (its reference position) and the unit direction it presses in.
    block_point_m: tuple[float, float, float]
    normal: tuple[float, float, float]
    method: Literal["incremental", "direct"]
    #: The blocked solution of one finger.
    blocked: BlockedResult


def _positive(name: str, value: float) -> float:
    v = float(value)
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"invalid {name} = {value!r}: must be finite and > 0")
    return v


def grasp(
    mass_kg: float,
    finger: Robot | None = None,
    mu: float = FRICTION_COEFFICIENT,
    fingers: int = 2,
    gravity: float = 9.81,
    *,
    normal: Sequence[float] = GRASP_NORMAL,
    groups: Sequence[int] | None = None,
    method: Literal["incremental", "direct"] = "incremental",
    increments: int = 10,
    steps: int = 100,
    tol: float = 1e-10,
) -> Grasp:
    """Grip temperature [C] for a mass ``mass_kg`` [kg] held by ``fingers``
    identical fingers with friction coefficient ``mu`` [-] under gravity
    ``gravity`` [m/s^2] (eq 44), with its blocked-tip solution.

    ``finger``: the finger design (default :func:`table1_finger`); its tip is
    blocked at its position at the reference (ambient) inputs and presses
    along ``normal``. ``groups``: actuation variables (default: all actuators
    of the finger share one temperature). ``method``: ``"incremental"`` (the
    paper's eq 43, ``increments`` steps) or ``"direct"`` (the temperature as a
    shooting unknown, started from the incremental result's neighbourhood-free
    guess of mid-range). Raises ``ValueError`` if the force needs a
    temperature outside the material's range.
    """
    m = _positive("mass_kg [kg]", mass_kg)
    mu_ = _positive("mu [-]", mu)
    g = _positive("gravity [m/s^2]", gravity)
    if isinstance(fingers, bool) or not isinstance(fingers, int) or fingers < 1:
        raise ValueError(f"invalid fingers = {fingers!r}: must be an integer >= 1")
    if method not in ("incremental", "direct"):
        raise ValueError(f"method must be 'incremental' or 'direct', got {method!r}")
    robot = table1_finger() if finger is None else finger
    grp = list(groups) if groups is not None else [0] * len(robot.actuators)
    force = m * g / (mu_ * fingers)  # eq (44)
    start = robot.solve(robot.reference_inputs, steps=steps, tol=tol)
    point = tuple(float(x) for x in start.tip_position)
    nrm = [float(x) for x in normal]
    if method == "incremental":
        res = blocked_temperature(
            robot, point, nrm, force, start, groups=grp, increments=increments, steps=steps, tol=tol
        )
    else:
        res = blocked_temperature_direct(robot, point, nrm, force, groups=grp, steps=steps, tol=tol)
    n = math.sqrt(sum(x * x for x in nrm))
    return Grasp(
        mass_kg=m,
        mu=mu_,
        fingers=fingers,
        gravity_m_per_s2=g,
        force_per_finger_n=force,
        temperature_c=float(res.variables[0]),
        block_point_m=(point[0], point[1], point[2]),
        normal=(nrm[0] / n, nrm[1] / n, nrm[2] / n),
        method=method,
        blocked=res,
    )


def grasp_temperature(
    mass_kg: float,
    finger: Robot | None = None,
    mu: float = FRICTION_COEFFICIENT,
    fingers: int = 2,
    gravity: float = 9.81,
    *,
    normal: Sequence[float] = GRASP_NORMAL,
    groups: Sequence[int] | None = None,
    method: Literal["incremental", "direct"] = "incremental",
    increments: int = 10,
    steps: int = 100,
    tol: float = 1e-10,
) -> float:
    """Grip temperature [C] for ``mass_kg`` [kg]: ``mu n F(T) = m g`` (eq 44)
    solved on the blocked-tip finger; see :func:`grasp` for the arguments."""
    return grasp(
        mass_kg,
        finger,
        mu,
        fingers,
        gravity,
        normal=normal,
        groups=groups,
        method=method,
        increments=increments,
        steps=steps,
        tol=tol,
    ).temperature_c
