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
    """The paper's constants by name, SI units (temperatures in C)."""

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
    """The paper's manipulator ``name`` with any of its parameters replaced."""

def fixture_leg_turns(length: float, legs: int, reading: _TurnsReading = "per_tca") -> float:
    """Turns [-] of one leg of a manipulator TCA of coiled length ``length`` [m]."""

def fixture_fig5_tca(threads: Literal[3, 4]) -> Tca:
    """The whole Fig. 5 TCA of 3 or 4 threads."""

def fixture_fig5_half_tca(threads: Literal[3, 4]) -> Tca:
    """One folded half of the Fig. 5 TCA: ``Tca.segment(0.5)`` of the whole."""

def fixture_tendon_robot(name: Literal["steel", "soft"]) -> Robot:
    """The speed-benchmark tendon robots (not from the paper): ``"steel"`` (on spacer disks) or ``"soft"``."""
