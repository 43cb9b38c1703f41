"""`Solution.stable` and `Solution.stability_margin` (docs/stability.md, "The
stability of every solve"): the verdict is computed by the solve (policy
``stability="report"``, the default) or, with ``stability="off"``, on first
access with the solution's own robot; cached, equal to
`tcarod.models.stability`, and survives pickle. The policies ``report``,
``require``, ``continue`` and ``off`` of `Robot.solve` and `Robot.sweep`, and
the blocked-tip verdict. The physics is tested in
tests/integration/stability.rs and tests/integration/stability_policy.rs."""

from __future__ import annotations

import pickle
import warnings

import numpy as np
import pytest

import tcarod
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
    sol = robot.solve([100.0, 100.0], stability="off")
    assert "stable=" not in repr(sol)  # repr never triggers the computation
    assert sol.stable is True
    assert isinstance(sol.stability_margin, float) and sol.stability_margin > 0
    assert sol.stable == core.stability(robot, sol).stable
    assert sol.stability_margin == core.stability(robot, sol).margin
    assert "stable=True" in repr(sol)  # shown once computed


def test_straight_heavy_column_past_buckling_is_unstable() -> None:
    robot = heavy_column()
    assert HEAVY > GREENHILL
    with pytest.warns(tcarod.UnstableEquilibriumWarning, match="unstable"):
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
    sol = robot.solve([], stability="off")
    first = (sol.stable, sol.stability_margin)
    assert (sol.stable, sol.stability_margin) == first


@pytest.mark.parametrize("touch", [False, True])
def test_verdict_survives_pickle(touch: bool) -> None:
    robot = heavy_column()
    sol = robot.solve([], stability="off")
    if touch:
        _ = sol.stable
    back = pickle.loads(pickle.dumps(sol))
    # recomputed from the bit-identical rebuilt profile: identical verdict
    assert back.stable is False
    assert back.stability_margin == core.stability(robot, sol).margin
    assert back == sol


@pytest.mark.parametrize("kwargs", [{"require_stable": True}, {"stability": "require"}])
def test_require_raises_on_the_unstable_straight_column(kwargs: dict[str, object]) -> None:
    robot = heavy_column()
    with pytest.raises(tcarod.UnstableEquilibriumError, match="unstable") as info:
        robot.solve([], **kwargs)  # type: ignore[arg-type]
    assert isinstance(info.value, RuntimeError)
    assert info.value.margin < 0
    assert info.value.solution.stable is False
    assert info.value.margin == info.value.solution.stability_margin


def test_require_stable_returns_a_stable_solution_with_its_verdict() -> None:
    robot = core._experiment_robot("fig6_square", True)
    sol = robot.solve([100.0, 100.0], require_stable=True)
    assert "stable=True" in repr(sol)  # verdict already cached
    assert sol.stability_margin > 0


def test_report_is_the_default_and_costs_one_tangent_ivp() -> None:
    robot = core._experiment_robot("fig6_square", True)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a stable solution warns nothing
        sol = robot.solve([100.0, 100.0])
    assert "stable=True" in repr(sol)  # the verdict came with the solve
    off = robot.solve([100.0, 100.0], stability="off")
    assert off.tip_position.tolist() == sol.tip_position.tolist()
    # the verdict is one integration (a tangent IVP of the solution, one
    # IVP more in the count)
    assert sol.nfev == off.nfev + 1
    assert sol.continued is None


def test_continue_moves_to_a_stable_shape_at_the_same_inputs() -> None:
    robot = heavy_column()
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the handed-back shape is stable: no warning
        sol = robot.solve([], stability="continue")
    # margins above -NEUTRAL = -1e-6 count as stable (src/stability/mod.rs: a
    # symmetry mode of the bent column is neutral, zero up to numerical noise)
    assert sol.stable is True and sol.stability_margin > -1e-6
    c = sol.continued
    assert isinstance(c, core.Continuation)
    assert c.unstable.stable is False and c.margin < 0 and c.margin == c.unstable.stability_margin
    # from the straight (unstable) column to a bent one: the tip moved
    # sideways by a fraction of the length and came down
    assert np.hypot(*c.unstable.tip_position[:2]) < 1e-9
    assert np.hypot(*sol.tip_position[:2]) > 0.1 * robot.body.length
    assert sol.tip_position[2] < c.unstable.tip_position[2]
    assert isinstance(c.route, str) and c.route and c.candidates >= 1
    assert sol.nfev > c.evaluations > 0
    # an equilibrium of the same problem: the verdict recomputed agrees
    assert core.stability(robot, sol).stable
    assert "Continuation" in repr(c)


def test_continue_keeps_a_stable_solution_unchanged() -> None:
    robot = core._experiment_robot("fig6_square", True)
    a = robot.solve([100.0, 100.0], stability="continue")
    b = robot.solve([100.0, 100.0])
    assert a.continued is None and a == b


def test_bad_policy_names_the_argument() -> None:
    robot = heavy_column()
    with pytest.raises(ValueError, match="stability"):
        robot.solve([], stability="stable")
    with pytest.raises(ValueError, match="stability"):
        robot.sweep([[]], stability="yes")
    with pytest.raises(TypeError):
        robot.solve([], stability=True)  # type: ignore[arg-type]


def test_sweep_policies() -> None:
    robot = heavy_column()
    with pytest.warns(tcarod.UnstableEquilibriumWarning, match=r"2 of 2 .*rows \[0, 1\]"):
        report = robot.sweep([[], []])
    assert [s.stable for s in report] == [False, False]
    with pytest.raises(tcarod.UnstableEquilibriumError):
        robot.sweep([[], []], stability="require")
    # continue: the first row lands on a stable shape, the next starts there
    cont = robot.sweep([[], []], stability="continue")
    assert [s.stable for s in cont] == [True, True]
    assert cont[0].continued is not None and cont[1].continued is None
    # the same equilibrium, warm-started from itself: to the solve tolerance
    assert np.allclose(cont[0].tip_position, cont[1].tip_position, atol=1e-9)
    off = robot.sweep([[], []], stability="off")
    assert all("stable=" not in repr(s) for s in off)


def test_blocked_tip_solution_carries_the_blocked_verdict() -> None:
    from tcarod.inverse import blocked_force
    from tcarod.models.manipulators import square_manipulator

    robot = square_manipulator(0.06)  # a picklable TCA robot (built from Python)
    free = robot.solve([100.0, 100.0])
    # a wall 2 mm beyond the free tip, across its sideways motion
    normal = np.array([np.sign(free.tip_position[0]) or 1.0, 0.0, 0.0])
    point = free.tip_position - 0.002 * normal
    res = blocked_force(robot, point, normal, [100.0], groups=[0, 0])
    sol = res.solution
    assert "stable=" in repr(sol)  # computed with the blocked solve
    held = core.stability(robot, sol, blocked=[normal])
    assert sol.stable == held.stable and sol.stability_margin == held.margin
    # holding the tip can only stiffen: the blocked margin is no smaller
    # than the free one at the same shape (restriction of a quadratic form)
    assert held.margin >= core.stability(robot, sol).margin - 1e-12  # rounding only
    back = pickle.loads(pickle.dumps(sol))
    assert back.stability_margin == held.margin  # the block normal survives pickle


def test_every_listed_policy_is_accepted() -> None:
    from tcarod.models.stability import POLICIES

    robot = core._experiment_robot("fig6_square", True)
    assert POLICIES[0] == "report"  # the default
    for p in POLICIES:
        assert robot.solve([100.0, 100.0], stability=p).stable is True  # type: ignore[arg-type]
