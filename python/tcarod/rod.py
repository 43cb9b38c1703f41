"""Forward kinetostatics (paper Section III): a Cosserat rod with embedded
string-like actuators, solved by Newton shooting in the Rust core.

Frames: the base is at the origin with the reference tangent along world
``+z``; body-frame ``x`` and ``y`` span the cross-section. Actuator forces
are tensions (N, negative when the actuator pushes); elongations (m) are an
actuator's length minus its relaxed length (0 with the coils touching,
positive when stretched or pre-tensioned, slightly negative when pressed
into coil contact inside a body). SI units; temperatures in degrees C.

Pre-tension: ``Actuator.tca(tca, routing, pretension_n=F)`` installs a TCA
stretched so that it carries ``F`` [N] at the reference temperature in the
undeformed body -- what a contraction TCA needs to act at all.

Value objects: ``Section``, ``Routing``, ``Body``, ``Actuator``, ``Robot``
(and ``Tca``, ``Material``) are immutable, compare with ``==`` (two robots
built alike are equal), hash, pickle and deep-copy; their ``repr`` is the
constructor call. A ``Solution`` pickles with its robot and compares equal
bit for bit after the round trip.

Contract at the boundary: a bad value raises ``ValueError`` naming the
argument and its allowed range; a wrong type (``str``, ``bytes``,
``complex``, ``None``, another class) raises ``TypeError``. Caps per call:
``steps`` <= 100,000 RK4 steps, ``max_iter`` <= 100,000, eq-43
``increments`` <= 10,000, batch rows <= 10,000,000 (stream more with
``tcarod.batch.iter_batches``), sequences <= 10,000 values. Messages read
``invalid NAME = VALUE UNIT: allowed RANGE (reason)``. Geometry is checked
when a ``Robot`` is built: routings inside the section, each TCA's whole coil
(routing offset plus half the coil's outer diameter) inside the section
unless ``Robot(..., spacer_disks=True)``, TCAs no longer than 1.1x their
anchored span. Sizes that look like millimetres (a body longer than 10 m, a
section or a routing offset above 1 m, an anchor above 10 m, a coil diameter
above 0.1 m) warn with ``tcarod.UnitsWarning``, and a length error then asks
"millimetres? lengths are in metres: 4 mm is 0.004 m"; so does a body with a
``density`` but no ``gravity`` (weightless: pass ``gravity``, zero if meant). An ambient below a material's ``t_min`` (the
preset starts at 25 C and is not extrapolated) is a ``ValueError`` pointing
to a custom ``Material(..., t_ref=..., t_min=...)``.
"""

from __future__ import annotations

from typing import Sequence

import numpy as np
import numpy.typing as npt

from . import _core
from . import _validate as V

Section = _core.Section
Routing = _core.Routing
Body = _core.Body
Actuator = _core.Actuator
Robot = _core.Robot
Solution = _core.Solution

FloatArray = npt.NDArray[np.float64]

__all__ = [
    "Actuator",
    "Body",
    "Robot",
    "Routing",
    "Section",
    "Solution",
    "circle_radius",
    "inner_edge_radius",
]


def circle_radius(
    a: Sequence[float] | FloatArray, b: Sequence[float] | FloatArray, c: Sequence[float] | FloatArray
) -> float:
    """Radius [m] of the circle through three points [m]; ``inf`` if collinear.

    Coordinates are limited to ``|x| <= 1e150`` m (``ValueError`` beyond), so
    that the arithmetic below, done on coordinates scaled to order one, cannot
    overflow.

    Parameters
    ----------
    a, b, c : sequence of 3 float
        The three points [m].

    Returns
    -------
    float
        The radius [m]; ``inf`` for collinear or coincident points.

    Examples
    --------
    >>> from tcarod.rod import circle_radius
    >>> round(circle_radius([0.01, 0, 0], [0, 0.01, 0], [-0.01, 0, 0]), 6)   # [m]
    0.01
    >>> circle_radius([0, 0, 0], [1, 0, 0], [2, 0, 0])
    inf
    """
    pts = [np.asarray(V.vector(n, x, 3, "m")) for n, x in (("a", a), ("b", b), ("c", c))]
    for n, p in zip("abc", pts):
        if float(np.max(np.abs(p))) > 1e150:
            raise ValueError(f"invalid {n} = {p.tolist()}: coordinates must be at most 1e150 m in magnitude")
    scale = max(float(np.max(np.abs(p - pts[0]))) for p in pts)
    if scale == 0.0:
        return float("inf")
    pa, pb, pc = ((p - pts[0]) / scale for p in pts)
    ab = float(np.linalg.norm(pb - pa))
    bc = float(np.linalg.norm(pc - pb))
    ca = float(np.linalg.norm(pa - pc))
    area2 = float(np.linalg.norm(np.cross(pb - pa, pc - pa)))
    if area2 <= 1e-15 * max(ab, bc, ca) ** 2:
        return float("inf")
    return scale * ab * bc * ca / (2.0 * area2)


def inner_edge_radius(solution: Solution) -> float:
    """Bending radius [m] as measured in the paper (Section V-B).

    The radius of the circle through three points on the inner (concave) edge
    of the body, at the base, the middle and the tip. The inner edge is taken
    on the body-frame direction of the mean curvature vector (``omega``
    projected on the cross-section, averaged along the body), at the section's
    edge distance in that direction.

    Parameters
    ----------
    solution : Solution
        A solution of a robot (positions [m], frames, strains [1/m]).

    Returns
    -------
    float
        The bending radius [m]; ``inf`` for a straight body.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> from tcarod.rod import inner_edge_radius
    >>> sol = fig6_square_robot().solve([100.0, 100.0], steps=50)   # both legs at 100 C
    >>> round(inner_edge_radius(sol) * 1e3, 1)                      # [mm]
    140.2
    """
    V.instance("solution", solution, Solution, "a tcarod.Solution")
    omega = solution.omega
    mean = omega[:, :2].mean(axis=0)
    if not np.all(np.isfinite(mean)) or float(np.hypot(*mean)) == 0.0:
        return float("inf")
    # curvature omega about body axis w bends the tangent toward w x e3
    toward = np.array([mean[1], -mean[0], 0.0])
    toward /= np.linalg.norm(toward)
    theta = float(np.arctan2(toward[1], toward[0]))
    edge = solution.robot.body.section.edge_distance(theta) * toward
    s = solution.s
    length = s[-1]
    idx = [0, int(np.argmin(np.abs(s - 0.5 * length))), len(s) - 1]
    pts = [solution.positions[i] + solution.rotations[i] @ edge for i in idx]
    return circle_radius(*pts)
