"""The lines of a solution's shape [mm] and its title, shared by the
matplotlib views (:mod:`.solution`) and the plotly view (:mod:`.interactive`)."""

from __future__ import annotations

import math
import re

import numpy as np
import numpy.typing as npt

from ..rod import Section, Solution

__all__ = ["input_title", "shape_lines"]

FloatArray = npt.NDArray[np.float64]

_MM = 1e3
_UNIT = re.compile(r"^(?P<name>.*?)\s*\[(?P<unit>[^\]]*)\]\s*$")


def _outline_angles(section: Section) -> list[float]:
    """Body-frame angles [rad] of the edge lines drawn along the body: the four
    corners of a rectangle, eight directions otherwise."""
    if section.kind == "rectangle":
        area, ix, iy, _ = section.properties
        half_w, half_h = 0.5 * math.sqrt(12.0 * iy / area), 0.5 * math.sqrt(12.0 * ix / area)
        c = math.atan2(half_h, half_w)
        return [c, math.pi - c, math.pi + c, 2.0 * math.pi - c]
    return [k * math.pi / 4.0 for k in range(8)]


def _edge_point(section: Section, theta: float) -> FloatArray:
    """Body-frame point [m] of the section's edge in direction ``theta`` [rad]."""
    r = section.edge_distance(theta)
    return np.array([r * math.cos(theta), r * math.sin(theta), 0.0])


def _ring_nodes(solution: Solution, rings: int) -> list[int]:
    """Indices of ``rings`` evenly spaced nodes, base and tip included (none if ``rings`` is 0)."""
    if rings == 0:
        return []
    n = len(solution.s)
    return sorted({round(j) for j in np.linspace(0, n - 1, max(2, rings))})


def shape_lines(solution: Solution, rings: int) -> list[tuple[str, str | None, FloatArray]]:
    """Every line of the shape [mm], world frame: ``(gid, legend label or None,
    points (n, 3))`` for the centre line, the body outline (edge lines along
    the body and ``rings`` cross-section rings) and each actuator path; the
    actuators' labels carry their tension [mN]."""
    pos, rot = solution.positions, solution.rotations
    section = solution.robot.body.section
    lines: list[tuple[str, str | None, FloatArray]] = [("centre-line", "centre line", pos * _MM)]
    for k, theta in enumerate(_outline_angles(section)):
        pts = (pos + rot @ _edge_point(section, theta)) * _MM
        lines.append((f"outline-{k}", "body outline" if k == 0 else None, pts))
    ring_local = np.array([_edge_point(section, float(t)) for t in np.linspace(0.0, 2.0 * math.pi, 73)])
    for k, i in enumerate(_ring_nodes(solution, rings)):
        lines.append((f"ring-{k}", None, (pos[i] + ring_local @ rot[i].T) * _MM))
    for k, (path, tension) in enumerate(zip(solution.actuator_paths, solution.tensions)):
        lines.append((f"actuator-{k}", f"actuator {k}: {tension * 1e3:.1f} mN", path * _MM))
    return lines


def input_title(solution: Solution) -> str:
    """The inputs of ``solution`` with their units, e.g. ``"inputs: 120 °C, 25 °C"``
    (``"no actuators"`` for a robot without actuators)."""
    parts = []
    for actuator, x in zip(solution.robot.actuators, solution.inputs):
        match = _UNIT.match(actuator.input_name)
        unit = match.group("unit") if match else ""
        if unit == "C":
            parts.append(f"{x:g} °C")
        elif unit == "m":  # a pulled length: millimetres read better
            parts.append(f"{x * _MM:g} mm")
        else:
            parts.append(f"{x:g} {unit}".rstrip())
    return "inputs: " + ", ".join(parts) if parts else "no actuators"
