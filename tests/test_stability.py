"""Binding contract of the stability verdict and branch following
(docs/stability.md): types, shapes, errors, the ``buckling`` experiment and
the page's examples. The physics (Euler and Greenhill loads, elastica) is
tested in tests/integration/stability.rs."""

from __future__ import annotations

import math

import numpy as np
import pytest

import tcarod._core as core
from tcarod.models.stability import follow_branch, stability


def column(tip_force_n: float = 0.0, rectangular: bool = False) -> core.Robot:
    """A slender round column (L/r = 100): Euler load pi^2 EI / (4 L^2).
    ``rectangular``: 10 x 9 mm instead, so that its buckled shapes are
    isolated (a round column's form a circle about the vertical)."""
    section = core.Section.rectangle(0.01, 0.009) if rectangular else core.Section.circle(0.01)
    body = core.Body(
        0.5, section, 1e6, poisson=0.5, density=1000.0, gravity=(0.0, 0.0, 0.0), tip_force=[0.0, 0.0, -tip_force_n]
    )
    return core.Robot(body, [])


def euler_load(robot: core.Robot) -> float:
    _, ix, iy, _ = robot.body.section.properties
    return math.pi**2 * robot.body.youngs_modulus * min(ix, iy) / (4 * robot.body.length**2)


def test_stability_result_types_and_shapes() -> None:
    r = column()
    sol = r.solve([])
    st = stability(r, sol)
    assert isinstance(st, core.Stability)
    assert st.stable is True and isinstance(st.margin, float) and st.margin > 0
    assert st.conjugate_point is None
    n = len(sol.s)
    for arr in (st.s, st.determinant, st.min_stiffness):
        assert isinstance(arr, np.ndarray) and arr.shape == (n,) and np.isfinite(arr).all()
    assert st.mode.shape == (6,)
    # the unloaded cantilever's smallest dimensionless tip stiffness is its
    # torsion, G J / (E I) = 1 / (1 + nu) = 2/3 (J = 2 I for a circle); exact
    # for the straight rod, up to the tangent integration's rounding
    assert st.margin == pytest.approx(2.0 / 3.0, rel=1e-6)
    assert st.evaluations == 1
    assert "Stability(stable=True" in repr(st)


def test_verdict_flips_at_the_euler_load() -> None:
    pc = euler_load(column())
    below, above = column(0.98 * pc), column(1.02 * pc)
    s_below = stability(below, below.solve([]))
    # the straight column above the load is unstable: solved without the
    # verdict (no warning) to test the function on its own
    s_above = stability(above, above.solve([], stability="off"))
    assert s_below.stable and s_below.margin > 0
    assert not s_above.stable and s_above.margin < 0
    assert s_above.conjugate_point is not None and 0 < s_above.conjugate_point <= 0.5


def test_blocked_directions_are_accepted_and_checked() -> None:
    r = column()
    sol = r.solve([])
    st = stability(r, sol, blocked=[[1.0, 0.0, 0.0]])
    assert st.stable
    with pytest.raises(ValueError, match="blocked"):
        stability(r, sol, blocked=[[0.0, 0.0, 0.0]])
    with pytest.raises(ValueError, match="blocked"):
        stability(r, sol, blocked=[[math.nan, 0.0, 1.0]])


def test_solution_of_another_robot_is_refused() -> None:
    tca_robot = core._experiment_robot("fig6_square", False)
    sol = tca_robot.solve([60.0, 60.0])
    with pytest.raises(ValueError, match="solution"):
        stability(column(), sol)


def test_wrong_types_raise_type_error() -> None:
    r = column()
    with pytest.raises(TypeError):
        core.stability(r, "not a solution")  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        core.follow_branch(r, parameter="tip_load_scale", start="a", end=1.0)  # type: ignore[arg-type]


def test_follow_branch_arrays_and_events() -> None:
    pc = euler_load(column())
    r = column(pc)  # tip load scale 1 = the Euler load
    br = follow_branch(r, "tip_load_scale", 0.5, 1.5, step=0.05, max_step=0.2)
    k = len(br)
    assert k >= 3
    assert br.parameter.shape == (k,) and br.tip_positions.shape == (k, 3)
    assert br.stable.dtype == np.bool_ and br.margin.shape == (k,)
    assert len(br.solutions) == k and isinstance(br.solutions[0], core.Solution)
    # one located bifurcation near the Euler load; stable below, unstable above
    assert br.bifurcations.shape == (1,) and br.folds.shape == (0,)
    # 0.5 %: as tests/integration/stability.rs locates Euler's load
    assert br.bifurcations[0] == pytest.approx(1.0, rel=5e-3)
    assert all(s == (p < br.bifurcations[0]) for p, s in zip(br.parameter, br.stable))
    kind, par, tip = br.events[0]
    assert kind == "bifurcation" and isinstance(par, float) and tip.shape == (3,)
    assert br.jumps == []
    assert br.evaluations > 0


def test_follow_branch_bad_arguments() -> None:
    r = column()
    with pytest.raises(ValueError, match="parameter"):
        core.follow_branch(r, parameter="density", start=0.0, end=1.0)
    with pytest.raises(ValueError, match="end"):
        core.follow_branch(r, parameter="tip_load_scale", start=1.0, end=1.0)
    with pytest.raises(ValueError, match="step"):
        core.follow_branch(r, parameter="tip_load_scale", start=0.0, end=1.0, step=-1.0)
    with pytest.raises(ValueError, match="start"):
        core.follow_branch(r, parameter="tip_load_scale", start=math.inf, end=1.0)
    with pytest.raises(ValueError, match="max_points"):
        core.follow_branch(r, parameter="tip_load_scale", start=0.0, end=1.0, max_points=1)
    with pytest.raises(ValueError, match="actuators"):  # names the argument
        core.follow_branch(r, parameter="inputs", start=0.0, end=1.0, actuators=[3])


def test_stable_sweep_refuses_an_unstable_start() -> None:
    pc = euler_load(column())
    r = column(pc)
    with pytest.raises(ValueError, match="start"):
        follow_branch(r, "tip_load_scale", 1.5, 2.0, stable_only=True)


def test_stable_sweep_jumps_at_buckling() -> None:
    # the sweep in tip-load scale stays on stable points and jumps onto the
    # buckled branch at the Euler load (weak axis)
    pc = euler_load(column(rectangular=True))
    r = column(pc, rectangular=True)
    sw = follow_branch(r, "tip_load_scale", 0.5, 1.3, stable_only=True, step=0.05, max_step=0.1)
    assert sw.stable.all()
    assert np.all(np.diff(sw.parameter) > 0)
    assert len(sw.jumps) == 1
    par, before, after = sw.jumps[0]
    assert par == pytest.approx(1.0, rel=5e-3)  # 0.5 %, as above
    assert isinstance(before, core.Solution) and isinstance(after, core.Solution)
    # after the jump the column is bent (tip moved sideways)
    assert np.hypot(*after.positions[-1][:2]) > 1e-3


def test_buckling_experiment_registered_and_physical() -> None:
    from tcarod.paper import REGISTRY
    from tcarod.paper.buckling import GREENHILL, predict_buckling

    assert "buckling" in REGISTRY
    r = predict_buckling()
    q = r.column_critical_scale() * r.column_weight_per_g
    # shear and axial compliance of the stubby soft column can only lower
    # Greenhill's inextensible, unshearable load; by a few percent at L/h = 5.6
    assert 0.95 * GREENHILL < q < GREENHILL
    # the straight column is stable below the located load, unstable above
    for p, s in zip(r.column_branch.parameter, r.column_branch.stable):
        assert s == (p < r.column_critical_scale())
    # the stable sweep is monotone in gravity and jumps once, at the load
    assert np.all(np.diff(r.column_sweep.parameter) > 0) and r.column_sweep.stable.all()
    assert [round(p, 6) for p, _, _ in r.column_sweep.jumps] == [round(r.column_critical_scale(), 6)]
    # heated variant: the in-plane shape turns stable at one temperature
    tc = r.circle_critical_c()
    assert 25.0 < tc < 160.0
    for t, s in zip(r.circle_planar.parameter, r.circle_planar.stable):
        assert s == (t > tc)
    doc = r.to_json()
    assert doc["name"] == "buckling" and "column_branch_gravity_scale" in doc
    assert "Greenhill" in r.table()


def test_stability_page_example_runs() -> None:
    """The ``python`` blocks of docs/stability.md run as doctests (their
    printed verdicts, warning class and tip positions are checked)."""
    import doctest
    import re
    from pathlib import Path

    page = Path(__file__).resolve().parent.parent / "docs" / "stability.md"
    blocks = re.findall(r"^```python\n(.*?)^```", page.read_text(encoding="utf-8"), flags=re.MULTILINE | re.DOTALL)
    assert blocks, "docs/stability.md has no python example"
    for i, block in enumerate(blocks):
        test = doctest.DocTestParser().get_doctest(block, {}, f"stability.md:{i}", "docs/stability.md", 0)
        runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
        runner.run(test)
        assert runner.summarize(verbose=False).failed == 0
