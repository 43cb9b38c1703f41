"""Fig. 1(b)-type 3-D manipulator (illustrative): symmetry, bending direction,
3-D tip-position inverse, workspace map."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from tcarod import _core
from tcarod.paper import REGISTRY
from tcarod.paper.fig1b import FIG1B
from tcarod.plotting import plot_workspace
from tcarod.models.workspace import snake_grid, workspace_map

ROBOT = FIG1B.robot()  # standing base-down, gravity -z


@pytest.mark.parametrize("t", [25.0, 70.0, 130.0, 160.0])
def test_equal_temperatures_do_not_bend(t: float) -> None:
    sol = ROBOT.solve([t, t, t])
    tip = sol.tip_position
    # Three identical TCAs at 120 degrees and gravity along the axis: the
    # problem is symmetric, so the tip stays on the axis. Only rounding and
    # the Newton tolerance (1e-10 in strain) break the symmetry: 1e-9 m is
    # six orders below the 60 mm length and far below any real bending
    # (one TCA at 60 C moves the tip by millimetres).
    assert abs(tip[0]) < 1e-9 and abs(tip[1]) < 1e-9
    assert np.max(np.abs(sol.omega[:, :2])) < 1e-6  # curvature [1/m], vs ~10 1/m when bent
    # heating all three lengthens the body (extension TCAs push) from 25 C on
    if t > 25.0:
        assert tip[2] > ROBOT.solve([25.0, 25.0, 25.0]).tip_position[2]


@pytest.mark.parametrize("k", [0, 1, 2])
def test_single_heated_tca_bends_away_from_its_side(k: int) -> None:
    temps = [25.0, 25.0, 25.0]
    temps[k] = 120.0
    tip = ROBOT.solve(temps).tip_position
    a = math.radians(FIG1B.angles_deg[k])
    side = np.array([math.cos(a), math.sin(a)])  # body-frame direction of TCA k (= world at the base)
    lateral = tip[:2]
    # it lengthens, so the body bends away from it: the tip moves opposite
    # to the TCA's side, and (symmetry) not sideways of that line
    assert float(lateral @ side) < -5e-3  # more than 5 mm away (about 20 mm in fact)
    perp = np.array([-side[1], side[0]])
    assert abs(float(lateral @ perp)) < 1e-9  # [m]: rounding and Newton tolerance only


def test_3d_inverse_reaches_a_target_from_a_forward_solve() -> None:
    true = [120.0, 60.0, 40.0]
    target = ROBOT.solve(true).tip_position
    res = _core.tip_position(ROBOT, list(target), tol=1e-7)
    assert res.reached
    tip = res.solution.tip_position
    # tol is 1e-7 m on the tip distance: the solver stops below it
    assert np.linalg.norm(tip - target) <= 1e-7
    # three temperatures, three coordinates: locally unique, so the
    # temperatures come back too (0.05 C: 1e-7 m of tip error over a tip
    # sensitivity of ~0.3 mm/C is 3e-4 C; the margin covers conditioning)
    assert np.allclose(res.variables, true, atol=0.05)


def test_snake_grid_covers_the_grid_in_unit_steps() -> None:
    g = snake_grid([[1.0, 2.0, 3.0]] * 3)
    assert g.shape == (27, 3)
    assert len({tuple(r) for r in g}) == 27
    # consecutive rows differ in exactly one input by one level
    steps = np.abs(np.diff(g, axis=0))
    assert np.all((steps > 0).sum(axis=1) == 1) and np.all(steps.max(axis=1) == 1.0)


def test_workspace_map_matches_individual_solves(tmp_path: Path) -> None:
    ws = workspace_map(ROBOT, [25.0, 100.0, 160.0])
    assert ws.temperatures_c.shape == (27, 3) and ws.n_failed == 0
    for row in (0, 13, 26):
        direct = ROBOT.solve(list(ws.temperatures_c[row])).tip_position
        # warm- and cold-started solves converge to the same root to the
        # Newton tolerance; 1e-8 m is far below the workspace's mm scale
        assert np.allclose(ws.tip_positions_m[row], direct, atol=1e-8)
    # equal temperatures lie on the axis, unequal ones off it
    eq = np.all(ws.temperatures_c == ws.temperatures_c[:, :1], axis=1)
    r = np.hypot(ws.tip_positions_m[:, 0], ws.tip_positions_m[:, 1])
    assert np.all(r[eq] < 1e-9) and np.all(r[~eq] > 1e-4)
    fig = plot_workspace(ws)
    out = tmp_path / "ws.png"
    fig.savefig(out)
    assert out.stat().st_size > 1000


def test_fig1b_is_registered_and_serialisable(tmp_path: Path) -> None:
    import json

    assert "fig1b" in REGISTRY
    result = REGISTRY["fig1b"]()
    doc = json.dumps(result.to_json(), allow_nan=False)
    assert '"illustrative": true' in doc
    assert "workspace map" in result.table()
    assert result.plot(tmp_path / "fig1b.png").stat().st_size > 1000
