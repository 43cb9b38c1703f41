"""Results as JSON documents: every key names its unit (``tip_position_m``,
``tensions_n``); NaN and infinity are refused (they are not JSON)."""

from __future__ import annotations

import json
from typing import Any

__all__ = ["dumps_json", "solution_json"]


def solution_json(solution: Any) -> dict[str, Any]:
    """Tip position [m], tip rotation (3 x 3, world frame), actuator tensions
    [N] and Newton iterations of a forward solution."""
    return {
        "tip_position_m": [float(x) for x in solution.tip_position],
        "tip_rotation": [[float(x) for x in row] for row in solution.tip_rotation],
        "tensions_n": [float(x) for x in solution.tensions],
        "iterations": int(solution.iterations),
    }


def dumps_json(doc: dict[str, Any]) -> str:
    """``doc`` as indented JSON; ``ValueError`` on NaN or infinity (invalid JSON: fail loudly)."""
    return json.dumps(doc, indent=2, allow_nan=False)
