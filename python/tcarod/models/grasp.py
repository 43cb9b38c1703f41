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

import inspect
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Callable, Final, Literal, Mapping, Sequence

from .. import _core
from .manipulators import DEFAULT_TURNS_READING, GRAVITY_M_PER_S2, PAPER_CONSTANTS, TurnsReading
from ..inverse import BlockedResult, blocked_force, _fixed, _groups
from ..rod import Robot
from .. import _validate as V
from ..tca import Material

if TYPE_CHECKING:  # typing.ParamSpec is Python >= 3.10; at run time only the annotations (strings) name it
    from typing import ParamSpec

    _P = ParamSpec("_P")

__all__ = [
    "FRICTION_COEFFICIENT",
    "GRASP_NORMAL",
    "TABLE1_FINGER_LENGTH_M",
    "Grasp",
    "grasp",
    "grasp_temperature",
    "table1_finger",
    "blocked_force_curve",
    "force_line",
    "TABLE1_CONTACT_TEMPERATURE_C",
    "TABLE1_EXPERIMENT_C",
    "TABLE1_MASSES_KG",
    "TABLE1_PAPER_PREDICTIONS_C",
]

#: Length of each gripper finger [m] (Section V-D; from the core, as the rest but the measurements).
TABLE1_FINGER_LENGTH_M: Final[float] = PAPER_CONSTANTS["table1_length"]
#: Friction coefficient between VeroClear RGD810 and EcoFlex 10 [-] (Section V-D).
FRICTION_COEFFICIENT: Final[float] = PAPER_CONSTANTS["table1_mu"]
#: Direction [-] (body-aligned frame) in which the fingertip presses on the object.
GRASP_NORMAL: Final[tuple[float, float, float]] = tuple(PAPER_CONSTANTS["table1_normal"])
#: Table I masses [kg], measured firm-grip temperatures [C] (oven steps of 5 C)
#: and the paper's own model predictions [C] (Section V-D).
TABLE1_MASSES_KG: Final[tuple[float, ...]] = tuple(PAPER_CONSTANTS["table1_masses"])
TABLE1_EXPERIMENT_C: Final[tuple[float, ...]] = (95.0, 120.0, 135.0)
TABLE1_PAPER_PREDICTIONS_C: Final[tuple[float, ...]] = tuple(PAPER_CONSTANTS["table1_paper_predictions"])


def table1_finger(
    *,
    material: Material | None = None,
    body_youngs_modulus_pa: float | None = None,
    tca_offset_m: float | None = None,
    coil_diameter_m: float | None = None,
    turns_reading: TurnsReading = DEFAULT_TURNS_READING,
) -> Robot:
    """The Table I gripper finger (see the module docstring), hanging down.

    Keywords replace one design parameter (default: the paper's / the
    documented default material; turns per :mod:`tcarod.models.manipulators`).

    Parameters
    ----------
    material : Material, optional
        Fibre material of the TCA (default: the documented default material).
    body_youngs_modulus_pa : float, optional
        Young's modulus [Pa] of the EcoFlex body (default: the paper's).
    tca_offset_m : float, optional
        Offset [m] of the TCA legs from the centre line along body ``x``
        (default 3 mm).
    coil_diameter_m : float, optional
        Outer coil diameter [m] of the TCA (default: the paper's).
    turns_reading : {"per_tca", "per_leg", "per_length"}, optional
        How the paper's inserted twist [turns] is read (see
        :mod:`tcarod.models.manipulators`).

    Returns
    -------
    Robot
        A 20 mm finger [m] with one U-shaped TCA (two legs, inputs in C).

    Examples
    --------
    >>> from tcarod.models.grasp import table1_finger
    >>> finger = table1_finger()
    >>> finger.body.length, len(finger.actuators)      # [m], the U-shaped TCA's two legs
    (0.02, 2)
    >>> finger.reference_inputs                         # ambient [C]
    [25.0, 25.0]
    """
    return _core.fixture_manipulator(
        "table1_finger",
        material=material,
        youngs_modulus=body_youngs_modulus_pa,
        tca_offset=tca_offset_m,
        coil_diameter=coil_diameter_m,
        turns_reading=turns_reading,
    )


@dataclass(frozen=True, eq=False)
class Grasp:
    """Solution of eq (44) for one mass: what :func:`grasp` returns.

    Fields: ``mass_kg`` [kg], ``mu`` [-], ``fingers``, ``gravity_m_per_s2``
    [m/s^2], ``force_per_finger_n`` [N], ``temperature_c`` [C],
    ``block_point_m`` [m], ``normal`` [-], ``method`` and ``blocked`` (the
    blocked solution of one finger).

    Examples
    --------
    >>> from tcarod.models.grasp import grasp
    >>> g = grasp(0.002, steps=30)                      # 2 g on the Table I fingers
    >>> round(g.force_per_finger_n * 1e3, 3)            # m g / (mu n) [mN]
    8.918
    >>> round(g.temperature_c, 1)                       # grip temperature [C]
    59.6
    """

    mass_kg: float
    mu: float
    fingers: int
    gravity_m_per_s2: float
    #: Normal force [N] each finger must exert, ``m g / (mu n)``.
    force_per_finger_n: float
    #: Grip temperature [C] of the TCA(s) of each finger.
    temperature_c: float
    #: Where the fingertip is blocked [m] (its free position at contact) and the unit direction it presses in.
    block_point_m: tuple[float, float, float]
    normal: tuple[float, float, float]
    method: Literal["incremental", "direct"]
    #: The blocked solution of one finger.
    blocked: BlockedResult


def _positive(name: str, value: float) -> float:
    return V.real(name, value, lo=0.0, lo_open=True)


def _unit_normal(normal: Sequence[float]) -> list[float]:
    """``normal`` as a unit vector: finite and non-zero (``ValueError``;
    Python ints beyond the double range are inf, refused, never
    ``OverflowError``), normalised without overflow for large components."""
    nrm = V.vector("normal", normal, 3)
    n = math.hypot(*nrm)
    if n == 0.0:
        raise ValueError("invalid normal = [0, 0, 0]: allowed a non-zero direction (the tip presses along it)")
    return [x / n for x in nrm]


def grasp(
    mass_kg: float,
    finger: Robot | None = None,
    mu: float = FRICTION_COEFFICIENT,
    fingers: int = 2,
    gravity: float = GRAVITY_M_PER_S2,
    *,
    normal: Sequence[float] = GRASP_NORMAL,
    groups: Sequence[int | None] | None = None,
    fixed_inputs: Mapping[int, float] | None = None,
    method: Literal["incremental", "direct"] = "incremental",
    increments: int = 10,
    steps: int = 100,
    tol: float = 1e-10,
    contact_temperature_c: float | None = None,
) -> Grasp:
    """Grip temperature [C] for a mass ``mass_kg`` [kg] (eq 44), with its blocked-tip solution.

    The mass is held by ``fingers`` identical fingers with friction
    coefficient ``mu`` [-] under gravity ``gravity`` [m/s^2].

    The fingertip touches the object at the contact inputs (below them the
    force is zero), is blocked there and presses along ``normal``; the
    temperature of its heated TCA(s) at which the blocked force is
    ``m g / (mu n)`` is solved for. ``blocked.solution`` carries the core's
    stability verdict of the finger with its tip held (an unstable one
    warns).

    Parameters
    ----------
    mass_kg : float
        Mass held [kg].
    finger : Robot, optional
        The finger design (default :func:`table1_finger`).
    mu : float
        Friction coefficient [-] between fingertip and object.
    fingers : int
        Number of identical fingers [-].
    gravity : float
        Gravitational acceleration [m/s^2].
    normal : sequence of 3 float
        Direction [-] the fingertip presses in (world frame).
    groups : sequence of int or None, optional
        ``groups[i]`` is the actuation variable of actuator ``i``; all
        heated actuators must share the one variable ``0``. ``None`` for an
        actuator in ``fixed_inputs``: one entry per actuator, or one per
        actuator not in ``fixed_inputs``. Default: every actuator not in
        ``fixed_inputs`` shares variable ``0`` (one grip temperature).
    fixed_inputs : dict of int to float, optional
        ``{actuator index: input}``: actuators held at a fixed input (C for
        a TCA; the range ``Robot.solve`` accepts) at contact and while
        gripping, e.g. ``{1: 25.0}`` heats only actuator 0 of a finger with
        two opposite TCAs (heating both together cancels their bending).
        An actuator both grouped and fixed, or neither, raises
        ``ValueError`` naming ``groups`` / ``fixed_inputs``.
    method : {"incremental", "direct"}
        ``"incremental"``: the paper's eq 43 in ``increments`` steps;
        ``"direct"``: one Newton solve of the blocked finger with the
        temperature as an extra shooting unknown and the exact Jacobian,
        started from one eq-43 step of the whole force (the same
        temperature to ~1e-10 C in about a quarter of the IVPs).
    increments, steps : int
        Force steps [-] of the incremental method; RK4 steps [-] per solve.
    tol : float
        Newton tolerance [-] of the blocked solves (dimensionless residual).
    contact_temperature_c : float, optional
        Temperature [C] of the heated actuators at which the freely closing
        fingertip touches the object (default: the finger's reference
        inputs, i.e. contact at ambient).

    Returns
    -------
    Grasp
        ``temperature_c`` the grip temperature [C], ``blocked`` the blocked
        solution of one finger.

    Raises
    ------
    ValueError
        For bad arguments, or if no temperature in the material's range
        holds the mass: the message gives the largest blocked force [N],
        the mass it holds [g] and the temperature [C] where it peaks, e.g.
        ``the finger cannot hold 50 g (...): the largest blocked force in
        [25, 160] C is 0.00891818 N (0.909312 g) at 160 C`` (both methods alike).

    Examples
    --------
    >>> from tcarod.models.grasp import grasp
    >>> round(grasp(0.01, method="direct").temperature_c)   # 10 g on the Table I fingers [C]
    123
    """
    m = _positive("mass_kg [kg]", mass_kg)
    mu_ = _positive("mu [-]", mu)
    g = _positive("gravity [m/s^2]", gravity)
    if isinstance(fingers, bool) or not isinstance(fingers, int) or fingers < 1:
        raise ValueError(f"invalid fingers = {fingers!r}: must be an integer >= 1")
    if method not in ("incremental", "direct"):
        raise ValueError(f"method must be 'incremental' or 'direct', got {method!r}")
    robot = table1_finger() if finger is None else V.instance("finger", finger, Robot, "a tcarod.Robot")
    fixed = _fixed(fixed_inputs) or {}
    grp = _groups(groups) if groups is not None else [None if i in fixed else 0 for i in range(len(robot.actuators))]
    contact = None
    if contact_temperature_c is not None:
        tc = float(contact_temperature_c)
        free = [a for i, a in enumerate(robot.actuators) if i not in fixed] or list(robot.actuators)
        lo, hi = free[0].input_bounds
        if not (math.isfinite(tc) and lo <= tc <= hi):
            raise ValueError(f"invalid contact_temperature_c = {contact_temperature_c!r}: must be in [{lo}, {hi}] C")
        # the core sets the fixed actuators to their fixed inputs
        contact = [tc] * len(robot.actuators)
    nrm = _unit_normal(normal)
    # eq (44) and the blocked solve live in the core (inverse::Grasp)
    res, point = _core.grasp_temperature(
        robot,
        nrm,
        m,
        mu_,
        fingers,
        gravity=g,
        groups=grp,
        fixed_inputs=fixed or None,
        contact=contact,
        method=method,
        increments=increments,
        steps=steps,
        tol=tol,
    )
    return Grasp(
        mass_kg=m,
        mu=mu_,
        fingers=fingers,
        gravity_m_per_s2=g,
        force_per_finger_n=res.force,
        temperature_c=float(res.variables[0]),
        block_point_m=(point[0], point[1], point[2]),
        normal=(nrm[0], nrm[1], nrm[2]),
        method=method,
        blocked=res,
    )


def force_line(
    masses_kg: Sequence[float],
    temperatures_c: Sequence[float],
    mu: float = FRICTION_COEFFICIENT,
    fingers: int = 2,
    gravity: float = GRAVITY_M_PER_S2,
) -> tuple[float, float]:
    """Least-squares line through grip temperatures: force per finger [N] against temperature [C].

    The force per finger is ``m g / (mu n)`` [N]. The slope says how fast a
    finger's force rises after contact, the intercept where it touches. The
    paper's Table I predictions give 0.209 mN/C and 72.3 C, its experiment
    0.223 mN/C and 76.7 C.

    Parameters
    ----------
    masses_kg : sequence of float
        Masses held [kg], at least two, distinct.
    temperatures_c : sequence of float
        Grip temperature [C] of each mass.
    mu : float
        Friction coefficient [-] between fingertip and object.
    fingers : int
        Number of identical fingers [-].
    gravity : float
        Gravitational acceleration [m/s^2].

    Returns
    -------
    slope : float
        Force per finger per degree [N/C].
    intercept : float
        Temperature [C] at zero force (where the fingertip touches).

    Raises
    ------
    ValueError
        Fewer than two masses, lengths that differ, or no spread.

    Examples
    --------
    >>> from tcarod.models.grasp import TABLE1_MASSES_KG, TABLE1_PAPER_PREDICTIONS_C, force_line
    >>> slope, intercept = force_line(TABLE1_MASSES_KG, TABLE1_PAPER_PREDICTIONS_C)
    >>> round(slope * 1e3, 3), round(intercept, 1)    # [mN/C], [C]
    (0.209, 72.3)
    """
    f = [m * gravity / (mu * fingers) for m in masses_kg]
    t = [float(x) for x in temperatures_c]
    if len(f) != len(t) or len(f) < 2:
        raise ValueError("force_line needs at least two masses_kg and one temperature [C] per mass")
    fm, tm = sum(f) / len(f), sum(t) / len(t)
    sff = sum((x - fm) ** 2 for x in f)
    sft = sum((x - fm) * (y - tm) for x, y in zip(f, t))
    if sff == 0.0 or sft == 0.0:
        raise ValueError("force_line needs distinct masses_kg and temperatures [C]")
    dt_df = sft / sff  # temperature on force, as table1_contact_temperature() in src/experiments.rs
    return 1.0 / dt_df, tm - dt_df * fm


#: Default contact temperature [C] of the Table I fingers: the zero-force
#: intercept of the paper's predictions, linear in the force per finger
#: (72.33 C, ``table1_contact_temperature()`` in ``src/experiments.rs``; the
#: same line as :func:`force_line`). The paper prints no gap between fingertip and object.
TABLE1_CONTACT_TEMPERATURE_C: Final[float] = PAPER_CONSTANTS["table1_contact_temperature"]


def blocked_force_curve(
    finger: Robot,
    contact_temperature_c: float,
    temperatures_c: Sequence[float],
    *,
    normal: Sequence[float] = GRASP_NORMAL,
    steps: int = 100,
) -> list[float]:
    """Contact force [N] of one finger at each temperature [C] (ascending).

    Zero up to ``contact_temperature_c`` (the fingertip closes freely until
    it touches the object there), then the blocked-tip force at the free
    tip position at contact (direct mixed solve, warm-started).

    Parameters
    ----------
    finger : Robot
        The finger design, e.g. :func:`table1_finger`.
    contact_temperature_c : float
        Temperature [C] at which the freely closing fingertip touches the object.
    temperatures_c : sequence of float
        Temperatures [C], ascending.
    normal : sequence of 3 float
        Direction [-] the fingertip presses in (world frame).
    steps : int
        RK4 steps [-] per solve.

    Returns
    -------
    list of float
        Contact force [N] at each temperature (``>= 0``).

    Examples
    --------
    >>> from tcarod.models.grasp import blocked_force_curve, table1_finger
    >>> forces = blocked_force_curve(table1_finger(), 72.33, [60.0, 100.0, 140.0], steps=30)
    >>> [round(f * 1e3, 2) for f in forces]           # [mN]: no contact below 72.33 C
    [0.0, 15.95, 44.93]
    """
    tc = float(contact_temperature_c)
    n = len(finger.actuators)
    point = tuple(float(x) for x in finger.solve([tc] * n, steps=steps).tip_position)
    out: list[float] = []
    warm = None
    for t in temperatures_c:
        if t <= tc:
            out.append(0.0)
            continue
        warm = blocked_force(finger, point, normal, [float(t)], groups=[0] * n, steps=steps, warm_start=warm)
        out.append(max(warm.force, 0.0))
    return out


def _temperature_of(solve: Callable[_P, Grasp]) -> Callable[_P, float]:
    """``solve`` returning only the grip temperature [C], with ``solve``'s
    parameters, visible to ``inspect.signature`` (Jupyter, ``help``) and,
    through the ``ParamSpec``, to type checkers."""

    def grasp_temperature(*args: _P.args, **kwargs: _P.kwargs) -> float:
        """Grip temperature [C] for ``mass_kg`` [kg]: ``mu n F(T) = m g`` (eq 44).

        Solved on the blocked-tip finger, i.e. ``grasp(...).temperature_c``;
        the parameters are :func:`grasp`'s.

        Parameters
        ----------
        mass_kg : float
            Mass held [kg].
        finger : Robot, optional
            The finger design (default: the Table I finger).
        mu : float
            Friction coefficient [-] between fingertip and object.
        fingers : int
            Number of identical fingers [-].
        gravity : float
            Gravitational acceleration [m/s^2].
        **kwargs
            ``normal`` [-], ``groups``, ``fixed_inputs`` (inputs in C),
            ``method``, ``increments``, ``steps``, ``tol`` and
            ``contact_temperature_c`` [C], as for :func:`grasp`.

        Returns
        -------
        float
            The grip temperature [C].

        Raises
        ------
        ValueError
            For bad arguments, or if no temperature in the material's range
            holds the mass (the message gives the largest blocked force [N]).

        Examples
        --------
        >>> round(tcarod.grasp_temperature(0.001, steps=30), 1)   # 1 g, Table I fingers [C]
        46.4
        """
        return solve(*args, **kwargs).temperature_c

    grasp_temperature.__qualname__ = "grasp_temperature"
    setattr(grasp_temperature, "__signature__", inspect.signature(solve).replace(return_annotation="float"))
    return grasp_temperature


grasp_temperature = _temperature_of(grasp)
"""``grasp_temperature(mass_kg, finger=None, mu=FRICTION_COEFFICIENT, fingers=2,
gravity=GRAVITY_M_PER_S2, *, normal=GRASP_NORMAL, groups=None,
fixed_inputs=None, method="incremental", increments=10, steps=100, tol=1e-10,
contact_temperature_c=None) -> float``: grip temperature [C] for ``mass_kg``
[kg], ``mu n F(T) = m g`` (eq 44) solved on the blocked-tip finger, i.e.
``grasp(...).temperature_c`` with :func:`grasp`'s parameters (the same
signature for ``inspect.signature`` and type checkers)."""
