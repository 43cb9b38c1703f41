"""Aliases, errors and warnings of ``tcarod._core`` (private stub module)."""

from collections.abc import Sequence
from typing import Literal

import numpy as np
import numpy.typing as npt

from ._solution import Solution

_Chirality = Literal["extension", "contraction"]
_FloatArray = npt.NDArray[np.float64]

_Vec3 = Sequence[float] | _FloatArray

_Policy = Literal["report", "require", "continue", "off"]

class ConvergenceError(RuntimeError):
    """A solve stopped without meeting its tolerance.

    Attributes
    ----------
    residual : float
        Best residual norm reached [-] (dimensionless).
    iterations : int
        Iterations done [-].
    evaluations : int
        IVPs integrated [-], failed attempts included.
    reason : str
        Why it stopped: `"iteration_limit"`, `"line_search"`,
        `"singular_jacobian"`, `"non_finite"`, `"budget"` (the IVP budget or
        the time limit ran out), `"other"`, or `"integration"` (an IVP could
        not be integrated).
    """

    #: Best residual norm reached (dimensionless unless the solver says otherwise).
    residual: float
    #: Iterations performed.
    iterations: int
    #: IVPs integrated, failed attempts included.
    evaluations: int
    #: Why it stopped: "iteration_limit", "line_search", "singular_jacobian",
    #: "non_finite", "budget" (``max_evaluations`` or ``time_limit`` spent),
    #: "integration" or "other".
    reason: str

class UnstableEquilibriumError(RuntimeError):
    """A solve required a stable equilibrium and converged to an unstable one.

    Raised by `Robot.solve(..., stability="require")` (or
    `require_stable=True`).

    Attributes
    ----------
    margin : float
        The equilibrium's stability margin [-], negative.
    solution : Solution
        The unstable equilibrium (shape [m], tensions [N]).
    """

    #: Stability margin of the equilibrium found [-] (< 0).
    margin: float
    #: The unstable equilibrium found.
    solution: Solution

class UnitsWarning(UserWarning):
    """Inputs that are valid SI numbers but look like a unit mix-up.

    Sizes that look like millimetres (a body longer than 10 m, a section wider
    than 1 m, a TCA coil diameter above 0.1 m, a routing offset or helix radius
    above 1 m, an anchor or a TCA length above 10 m), a Young's modulus outside
    1 kPa-1 TPa, temperatures above 273 C (kelvin typed as Celsius), and a
    density given without gravity (a weightless body).
    """
