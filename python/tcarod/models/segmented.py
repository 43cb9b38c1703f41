"""Segmented (distributed) actuation: one TCA divided into segments in series,
each anchored to the body at its ends and heated on its own (the leftmost TCA
of the paper's Fig. 1(b): "we can apply different voltages to different
segments of each TCA ... to enable distributed actuation").

Each segment is an actuator of its own, from ``s_k`` to ``s_{k+1}`` [m] along
the body, with the TCA law of :meth:`Tca.segment`: the whole TCA's fibre
length, coiled length and turns scaled by the segment's share of the span,
so the same pitch angle, fibre diameter and twist density. Anchoring every
segment to the body is what makes the actuation *distributed*: a segment's
force acts only between its own anchors.
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np

from .. import _core
from .. import _validate as V
from ..rod import Actuator, Routing
from ..tca import Tca

__all__ = ["segment_bounds", "segmented_actuators"]


def segment_bounds(segments: int | Sequence[float], s_start: float, s_end: float) -> list[tuple[float, float]]:
    """Consecutive ``(s_start, s_end)`` [m] of the segments over ``[s_start, s_end]``.

    Parameters
    ----------
    segments : int or sequence of float
        A number of equal segments, or the fractions of the span (positive,
        summing to 1), proximal first; at most 1000 segments.
    s_start, s_end : float
        The span along the body [m], ``0 <= s_start < s_end``.

    Returns
    -------
    list of (float, float)
        The segments' bounds [m], proximal first.

    Raises
    ------
    TypeError
        ``segments`` a float or bool.
    ValueError
        Fractions not positive or not summing to 1, too many segments, or a
        segment of zero length in floating point.

    Examples
    --------
    >>> from tcarod.models.segmented import segment_bounds
    >>> tuple(segment_bounds((0.25, 0.75), 0.0, 0.040))      # [m]
    ((0.0, 0.01), (0.01, 0.04))
    """
    s_start = V.real("s_start", s_start, lo=0.0, unit="m")
    s_end = V.real("s_end", s_end, lo=s_start, lo_open=True, unit="m")
    if isinstance(segments, (bool, float, np.floating)):
        raise TypeError(f"segments must be an integer count or a sequence of fractions, not {type(segments).__name__}")
    if isinstance(segments, (int, np.integer)):
        count = V.integer("segments", segments, 1, V.MAX_SEGMENTS)
        fractions = np.full(count, 1.0 / count)
    else:
        fractions = V.real_array("segments", segments, max_size=V.MAX_SEGMENTS)
        if fractions.ndim != 1 or fractions.size == 0 or np.any(fractions <= 0.0):
            raise ValueError(f"invalid segments = {fractions.tolist()}: need positive fractions of the span")
        if abs(float(fractions.sum()) - 1.0) > 1e-9:
            raise ValueError(f"invalid segments = {list(segments)}: fractions sum to {fractions.sum()}, not 1")
    edges = s_start + (s_end - s_start) * np.concatenate(([0.0], np.cumsum(fractions)))
    edges[-1] = s_end  # exact distal anchor despite rounding
    if not (np.all(np.isfinite(edges)) and np.all(np.diff(edges) > 0.0)):
        raise ValueError(
            f"invalid span [s_start, s_end] = [{s_start:g}, {s_end:g}] m: a segment would have zero or non-finite length"
        )
    return [(float(a), float(b)) for a, b in zip(edges[:-1], edges[1:])]


def segmented_actuators(
    tca: Tca,
    routing: Any,
    segments: int | Sequence[float],
    s_start: float,
    s_end: float,
) -> list[Any]:
    """Actuators for one TCA divided into segments in series, proximal first.

    Segment ``k`` is ``Actuator.tca(tca.segment(f_k), routing, s_k, s_{k+1})``:
    give it its own temperature [C] when solving. With one segment this is
    the whole TCA between the same anchors.

    Parameters
    ----------
    tca : Tca
        The whole TCA.
    routing : Routing
        Its path in the body.
    segments : int or sequence of float
        A number of equal segments or the fractions of the span.
    s_start, s_end : float
        The span along the body [m].

    Returns
    -------
    list of Actuator
        One per segment.

    Raises
    ------
    TypeError
        ``tca`` or ``routing`` of the wrong type.
    ValueError
        As for :func:`segment_bounds`.

    Examples
    --------
    >>> from tcarod import Robot, Routing
    >>> from tcarod.batch import fig6_square_robot
    >>> from tcarod.models.manipulators import manipulator_tca
    >>> from tcarod.models.segmented import segmented_actuators
    >>> acts = segmented_actuators(manipulator_tca(0.040), Routing.straight(0.003, 0.0), 2, 0.0, 0.040)
    >>> robot = Robot(fig6_square_robot().body, acts)
    >>> sol = robot.solve([120.0, 25.0], steps=20)   # heat the proximal half only
    >>> len(acts), bool(sol.tip_position[0] < 0)
    (2, True)
    """
    V.instance("tca", tca, _core.Tca, "a tcarod.Tca")
    V.instance("routing", routing, Routing, "a tcarod.Routing")
    bounds = segment_bounds(segments, s_start, s_end)
    span = bounds[-1][1] - bounds[0][0]
    return [Actuator.tca(tca.segment((b - a) / span) if len(bounds) > 1 else tca, routing, a, b) for a, b in bounds]
