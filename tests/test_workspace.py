"""Workspace maps (``tcarod.models.workspace``): grid order, results, and the
bounded-work contract (a grid beyond ``MAX_GRID_POINTS`` is refused before any
solve)."""

from __future__ import annotations

import numpy as np
import pytest

from tcarod.batch import fig6_square_robot
from tcarod.plotting import plot_workspace
from tcarod.models.workspace import snake_grid, solve_rows, workspace_map

ROBOT = fig6_square_robot(gravity=False)


def test_snake_grid_neighbours_differ_in_one_input() -> None:
    g = snake_grid([[1.0, 2.0, 3.0], [10.0, 20.0]])
    assert g.shape == (6, 2)
    assert {tuple(r) for r in g} == {(a, b) for a in (1.0, 2.0, 3.0) for b in (10.0, 20.0)}
    assert np.all(np.sum(np.diff(g, axis=0) != 0.0, axis=1) == 1)


def test_workspace_map_is_symmetric_for_the_mirrored_legs() -> None:
    ws = workspace_map(ROBOT, [25.0, 100.0])
    assert ws.n_failed == 0
    # legs at y = +-2.5 mm: heating one or the other mirrors the tip in y
    k_a = int(np.flatnonzero((ws.temperatures_c == [100.0, 25.0]).all(axis=1))[0])
    k_b = int(np.flatnonzero((ws.temperatures_c == [25.0, 100.0]).all(axis=1))[0])
    a, b = ws.tip_positions_m[k_a], ws.tip_positions_m[k_b]
    # mirrored equations: equal to the solver tolerance (1e-10 in strain, ~1e-12 m)
    assert a[1] == pytest.approx(-b[1], abs=1e-12) and a[0] == pytest.approx(b[0], abs=1e-12)  # solver tolerance
    assert plot_workspace(ws).axes


def test_grid_beyond_the_cap_is_a_value_error_before_any_solve() -> None:
    from tcarod._validate import MAX_GRID_POINTS

    with pytest.raises(ValueError, match="grid_c"):
        workspace_map(ROBOT, np.linspace(25.0, 160.0, int(MAX_GRID_POINTS**0.5) + 2))
    with pytest.raises(ValueError, match="levels"):
        snake_grid([list(range(1000))] * 3)


@pytest.mark.parametrize(
    ("call", "exc", "name"),
    [
        (lambda: workspace_map(None, [25.0]), TypeError, "robot"),
        (lambda: workspace_map(ROBOT, "25"), TypeError, "grid_c"),
        (lambda: workspace_map(ROBOT, [float("nan")]), ValueError, "grid_c"),
        (lambda: workspace_map(ROBOT, [25.0], steps=-1), ValueError, "steps"),
        (lambda: workspace_map(ROBOT, [25.0], steps=10**30), ValueError, "steps"),
        (lambda: solve_rows(ROBOT, [[25.0, 1j]]), TypeError, "inputs"),
        (lambda: plot_workspace(ws=None), TypeError, "ws"),  # type: ignore[arg-type]
    ],
)
def test_bad_arguments_name_the_argument(call: object, exc: type, name: str) -> None:
    with pytest.raises(exc, match=name):
        call()  # type: ignore[operator]
