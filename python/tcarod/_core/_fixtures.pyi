"""The paper's fixtures of ``tcarod._core`` (src/python/fixtures.rs)."""

from collections.abc import Sequence
from typing import Any, Literal

from ._common import _FloatArray
from ._rod import Robot
from ._tca import Material, Tca

# The paper's fixtures, defined once in the core (src/experiments.rs).

_Manipulator = Literal["square", "fig6_circle", "fig6_square", "fig8", "table1_finger"]
_TurnsReading = Literal["per_tca", "per_leg", "per_length"]

def fixture_constants() -> dict[str, Any]:
    """The paper's constants by name, SI units (temperatures in C).

    Returns
    -------
    dict
        ``ecoflex10_density`` [kg/m^3], ``ecoflex10_youngs_modulus`` [Pa],
        ``ecoflex10_poisson`` [-], ``gravity`` [m/s^2], ``tca_offset`` [m],
        ``u_leg_half_spacing`` [m], ``square_side`` [m], ``circle_diameter``
        [m], ``circle_precurvature_radius`` [m], ``manipulator_turns`` [-],
        ``turns_anchor_length`` [m], ``manipulator_coil_diameter`` [m],
        ``manipulator_pitch_deg`` [deg], ``fig6_length``, ``fig8_length``,
        ``table1_length`` [m], ``table1_mu`` [-], ``table1_fingers`` [-],
        ``table1_contact_temperature`` [C], and the benchmarks' values.

    Examples
    --------
    >>> from tcarod import _core
    >>> c = _core.fixture_constants()
    >>> c["ecoflex10_youngs_modulus"], c["tca_offset"]      # [Pa], [m]
    (37800.0, 0.003)
    """

def fixture_manipulator(
    name: _Manipulator,
    *,
    length: float | None = None,
    gravity: Sequence[float] | _FloatArray | None = None,
    material: Material | None = None,
    youngs_modulus: float | None = None,
    tca_offset: float | None = None,
    coil_diameter: float | None = None,
    turns_reading: _TurnsReading = "per_tca",
) -> Robot:
    """One of the paper's manipulator designs, with any parameter replaced.

    Parameters
    ----------
    name : {"square", "fig6_square", "fig6_circle", "fig8", "table1_finger"}
        The design: the Fig. 6 square and circle manipulators, the Fig. 8
        blocked-force manipulator, the Table I gripper finger.
    length : float, optional
        Body length [m] (default the design's; ``"square"``: 40 mm).
    gravity : sequence of 3 float, optional
        Gravity [m/s^2] in the body-aligned world frame (default: upright,
        the finger hanging).
    material : Material, optional
        TCA fibre material (default: the documented default material).
    youngs_modulus : float, optional
        Body Young's modulus [Pa].
    tca_offset : float, optional
        TCA distance from the neutral axis [m].
    coil_diameter : float, optional
        TCA coil diameter [m].
    turns_reading : {"per_tca", "per_leg", "per_length"}, optional
        How the paper's 76.4 turns are read (default ``"per_tca"``).

    Returns
    -------
    Robot
        The design.

    Raises
    ------
    ValueError
        An unknown ``name`` or ``turns_reading``, or a value out of range.

    Examples
    --------
    >>> from tcarod import _core
    >>> robot = _core.fixture_manipulator("fig6_square")
    >>> robot.body.length, len(robot.actuators)     # [m], the U-shaped TCA's two legs
    (0.04, 2)
    """

def fixture_leg_turns(length: float, legs: int, reading: _TurnsReading = "per_tca") -> float:
    """Turns of one leg of a manipulator TCA [-].

    Parameters
    ----------
    length : float
        Coiled length of the leg [m].
    legs : int
        Legs of the TCA (1 straight, 2 U-shaped).
    reading : {"per_tca", "per_leg", "per_length"}, optional
        How the paper's 76.4 turns are read (default ``"per_tca"``).

    Returns
    -------
    float
        Turns of the leg [-].

    Raises
    ------
    ValueError
        A non-positive ``length``, ``legs`` < 1 or an unknown ``reading``.

    Examples
    --------
    >>> from tcarod import _core
    >>> _core.fixture_leg_turns(0.040, 2), _core.fixture_leg_turns(0.060, 1, "per_length")
    (38.2, 114.6...)
    """

def fixture_fig5_tca(threads: Literal[3, 4]) -> Tca:
    """The whole Fig. 5 TCA of ``threads`` threads.

    Parameters
    ----------
    threads : {3, 4}
        Threads of the TCA.

    Returns
    -------
    Tca
        The TCA.

    Raises
    ------
    ValueError
        ``threads`` other than 3 or 4.

    Examples
    --------
    >>> from tcarod import _core
    >>> _core.fixture_fig5_tca(3).chirality
    'extension'
    """

def fixture_fig5_half_tca(threads: Literal[3, 4]) -> Tca:
    """One folded half of the Fig. 5 TCA of ``threads`` threads.

    ``Tca.segment(0.5)`` of the whole: the displacement measured is one
    half's elongation.

    Parameters
    ----------
    threads : {3, 4}
        Threads of the TCA.

    Returns
    -------
    Tca
        The half TCA.

    Raises
    ------
    ValueError
        ``threads`` other than 3 or 4.

    Examples
    --------
    >>> from tcarod import _core
    >>> half, whole = _core.fixture_fig5_half_tca(4), _core.fixture_fig5_tca(4)
    >>> round(half.coiled_length / whole.coiled_length, 6)
    0.5
    """

def fixture_tendon_robot(name: Literal["steel", "soft"]) -> Robot:
    """A tendon robot of the speed benchmarks (not from the paper).

    Parameters
    ----------
    name : {"steel", "soft"}
        ``"steel"``: L 0.5 m, radius 1 mm, E 200 GPa, G 80 GPa, 8000 kg/m^3,
        gravity along ``+x``, four tendons at 15.06 mm on spacer disks
        (benchmark tensions ``fixture_constants()["steel_tendon_tensions"]``
        [N]); ``"soft"``: 0.2 m, 10 mm, 1 MPa, one tendon at 4 mm.

    Returns
    -------
    Robot
        The robot.

    Raises
    ------
    ValueError
        An unknown ``name``.

    Examples
    --------
    >>> from tcarod import _core
    >>> robot = _core.fixture_tendon_robot("soft")
    >>> robot.body.length, len(robot.actuators)     # [m]
    (0.2, 1)
    """
