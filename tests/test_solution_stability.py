"""`Solution.stable` and `Solution.stability_margin` (issue 16): the verdict
is computed on first access with the solution's own robot, cached, equal to
`tcarod.models.stability`, and survives pickle."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

import tcarod._core as core

# Self-weight buckling of an upright clamped-free column (Greenhill):
# rho A g L^3 / (E I) = 7.837. The heavy column below carries 10, past it.
GREENHILL = 7.837
HEAVY = 10.0


def heavy_column() -> core.Robot:
    """An upright rectangular soft column (10 x 9 mm, L = 0.5 m) under
    gravity scaled to rho A g L^3 / (E I_min) = HEAVY."""
    section = core.Section.rectangle(0.01, 0.009)
    area, ix, iy, _ = section.properties
    length, youngs, density = 0.5, 1e6, 1000.0
    g = HEAVY * youngs * min(ix, iy) / (density * area * length**3)
    body = core.Body(length, section, youngs, poisson=0.5, density=density, gravity=[0.0, 0.0, -g])
    return core.Robot(body, [])


def test_fig6_square_at_100c_is_stable() -> None:
    robot = core._experiment_robot("fig6_square", True)
    sol = robot.solve([100.0, 100.0])
    assert "stable=" not in repr(sol)  # repr never triggers the computation
    assert sol.stable is True
    assert isinstance(sol.stability_margin, float) and sol.stability_margin > 0
    assert sol.stable == core.stability(robot, sol).stable
    assert sol.stability_margin == core.stability(robot, sol).margin
    assert "stable=True" in repr(sol)  # shown once computed


def test_straight_heavy_column_past_buckling_is_unstable() -> None:
    robot = heavy_column()
    assert HEAVY > GREENHILL
    sol = robot.solve([])
    # the cold solve from the straight guess stays straight (no lateral
    # load breaks the symmetry): the tip is on the axis to round-off
    assert np.hypot(*sol.tip_position[:2]) < 1e-9
    assert sol.stable is False
    assert sol.stability_margin < 0
    st = core.stability(robot, sol)
    assert sol.stable == st.stable and sol.stability_margin == st.margin
    assert "stable=False" in repr(sol)


def test_cached_value_is_stable_across_accesses() -> None:
    robot = heavy_column()
    sol = robot.solve([])
    first = (sol.stable, sol.stability_margin)
    assert (sol.stable, sol.stability_margin) == first


@pytest.mark.parametrize("touch", [False, True])
def test_verdict_survives_pickle(touch: bool) -> None:
    robot = heavy_column()
    sol = robot.solve([])
    if touch:
        _ = sol.stable
    back = pickle.loads(pickle.dumps(sol))
    # recomputed from the bit-identical rebuilt profile: identical verdict
    assert back.stable is False
    assert back.stability_margin == core.stability(robot, sol).margin
    assert back == sol


def test_require_stable_raises_on_the_unstable_straight_column() -> None:
    import tcarod

    robot = heavy_column()
    with pytest.raises(tcarod.UnstableEquilibriumError, match="unstable") as info:
        robot.solve([], require_stable=True)
    assert isinstance(info.value, RuntimeError)
    assert info.value.margin < 0
    assert info.value.solution.stable is False
    assert info.value.margin == info.value.solution.stability_margin


def test_require_stable_returns_a_stable_solution_with_its_verdict() -> None:
    robot = core._experiment_robot("fig6_square", True)
    sol = robot.solve([100.0, 100.0], require_stable=True)
    assert "stable=True" in repr(sol)  # verdict already cached
    assert sol.stability_margin > 0
