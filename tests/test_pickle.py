"""Every public object of tcarod._core pickles, copies and compares.

State comes from the constructor arguments (a Solution from its robot and
converged shooting unknowns, rebuilt by one deterministic IVP), so a
round trip is exact: ``==`` compares every field bit for bit. Robots and
solutions travel to process pools (spawn) and Dask process workers and solve
there exactly as here.
"""

from __future__ import annotations

import concurrent.futures as cf
import copy
import math
import multiprocessing
import pickle
from typing import Any, Callable

import numpy as np
import pytest

from tcarod import (
    Actuator,
    Body,
    Material,
    Robot,
    Routing,
    Section,
    Tca,
    blocked_force,
    tip_position,
)
from tcarod import _core
from tcarod.batch import BatchResult, fig6_square_robot, solve_batch

CUSTOM_MATERIAL = Material(
    youngs_modulus=1.2e9,
    shear_modulus=2.2e8,
    expansion=1e-4,
    youngs_modulus_slope=-1.3e6,
    expansion_slope=3.5e-6,
    t_ref=20.0,
    t_min=20.0,
    t_max=150.0,
    name="my nylon",
)
TCA = Tca(0.497, 0.110, 2e-3, 300.0)
SQUARE = fig6_square_robot()


def _body() -> Any:
    return Body(
        0.05,
        Section.circle(0.014),
        60e3,
        density=1100.0,
        shear_coefficient=0.9,
        omega_star=[0.0, 2.0, 0.0],
        gravity=[0.0, 0.0, -9.81],
        distributed_force=[0.01, 0.0, 0.0],
        distributed_moment=[0.0, 0.001, 0.0],
        tip_force=[0.0, 0.001, 0.0],
        tip_moment=[1e-5, 0.0, 0.0],
    )


def _column() -> Robot:
    """A slender round rod under a tip load along its axis (cheap branches)."""
    body = _core.Body(
        0.5,
        _core.Section.circle(0.01),
        1e6,
        poisson=0.5,
        density=1000.0,
        gravity=(0.0, 0.0, 0.0),
        tip_force=[0.0, 0.0, -0.01],
    )
    return _core.Robot(body, [])


def _short_branch() -> _core.Branch:
    return _core.follow_branch(_column(), parameter="tip_load_scale", start=0.5, end=1.0, step=0.2, max_step=0.5)


def _objects() -> dict[str, Callable[[], Any]]:
    """Builders of one instance of every public class (fresh each call)."""
    return {
        "material_preset": Material.silver_coated_nylon,
        "material_custom": lambda: CUSTOM_MATERIAL,
        "tca": lambda: Tca(0.497, 0.110, 2e-3, 300.0, "contraction", CUSTOM_MATERIAL),
        "tca_core": lambda: _core.Tca(0.497, 0.110, 2e-3, 300.0),
        "section_circle": lambda: Section.circle(0.01),
        "section_rectangle": lambda: Section.rectangle(0.01, 0.02),
        "section_custom": lambda: Section.custom(1e-4, 1e-9, 2e-9, 3e-9),
        "routing_straight": lambda: Routing.straight(0.003, -0.001),
        "routing_helix": lambda: Routing.helix(0.003, 50.0, 0.5),
        "body": _body,
        "actuator_tca": lambda: Actuator.tca(TCA, Routing.straight(0.003, 0.0), 0.0, 0.04, 0.99),
        "actuator_pretension": lambda: Actuator.tca(TCA, Routing.straight(0.003, 0.0), pretension_n=0.01),
        "actuator_tendon": lambda: Actuator.tendon(Routing.straight(0.0, 0.003), 0.01),
        "actuator_linear": lambda: Actuator.linear_tendon(500.0, Routing.helix(0.003, 20.0), 0.0, 0.03),
        "robot": fig6_square_robot,
        "robot_tendons": lambda: Robot(_body(), [Actuator.tendon(Routing.straight(0.003, 0.0))]),
        "solution": lambda: SQUARE.solve([90.0, 90.0]),
        "solution_loaded": lambda: Robot(_body(), [Actuator.tendon(Routing.straight(0.003, 0.0))]).solve([0.02]),
        "inverse_result": lambda: tip_position(SQUARE, SQUARE.solve([60.0, 60.0]).tip_position, groups=[0, 0]),
        "blocked_result": lambda: blocked_force(
            SQUARE, SQUARE.solve([25.0, 25.0]).tip_position, [-1.0, 0.0, 0.0], 60.0, groups=[0, 0]
        ),
        "stability": lambda: _core.stability(SQUARE, SQUARE.solve([90.0, 90.0])),
        "branch": _short_branch,
        "batch_result": lambda: solve_batch(SQUARE, [[40.0, 40.0], [90.0, 95.0], [130.0, 120.0]], chunk_size=2),
    }


OBJECTS = _objects()


@pytest.mark.parametrize("name", sorted(OBJECTS))
def test_round_trips_through_pickle_copy_and_deepcopy(name: str) -> None:
    obj = OBJECTS[name]()
    for protocol in (2, pickle.HIGHEST_PROTOCOL):
        back = pickle.loads(pickle.dumps(obj, protocol=protocol))
        assert type(back) is type(obj)
        assert back == obj
    assert copy.copy(obj) == obj
    assert copy.deepcopy(obj) == obj


@pytest.mark.parametrize("name", sorted(OBJECTS))
def test_identically_built_objects_are_equal(name: str) -> None:
    a, b = OBJECTS[name](), OBJECTS[name]()
    assert a == b
    assert not (a != b)
    assert a != "something else"
    if type(a).__hash__ is not None:
        assert hash(a) == hash(b)


def test_different_objects_are_unequal() -> None:
    assert fig6_square_robot(True) != fig6_square_robot(False)
    assert Section.circle(0.01) != Section.circle(0.0100001)
    assert Routing.straight(0.003, 0.0) != Routing.helix(0.003, 0.0)
    assert SQUARE.solve([90.0, 90.0]) != SQUARE.solve([91.0, 90.0])
    a = Actuator.tca(TCA, Routing.straight(0.003, 0.0))
    assert a != Actuator.tca(TCA, Routing.straight(0.003, 0.0), pretension_n=0.01)
    assert a != Actuator.tca(TCA, Routing.straight(0.003, 0.0), s_end=0.04)


def test_a_pickled_solution_keeps_every_array_and_warm_starts_the_same() -> None:
    sol = SQUARE.solve([90.0, 90.0])
    back = pickle.loads(pickle.dumps(sol))
    # every public array getter, so that a new one cannot be forgotten here
    fields = [n for n in dir(sol) if not n.startswith("_") and isinstance(getattr(sol, n), np.ndarray)]
    assert {"positions", "rotations", "tensions", "elongation_profile", "unknowns"} <= set(fields)
    for field in fields:
        np.testing.assert_array_equal(getattr(back, field), getattr(sol, field))
    assert (back.iterations, back.evaluations, back.residual) == (sol.iterations, sol.evaluations, sol.residual)
    assert back.robot == SQUARE
    # the Newton Jacobian travels too: a warm start from the copy is the same solve
    assert SQUARE.solve([95.0, 95.0], warm_start=back) == SQUARE.solve([95.0, 95.0], warm_start=sol)


def test_convergence_error_keeps_its_fields_through_pickle() -> None:
    # a real one: a budget of one IVP cannot reach 160 C from the straight guess
    with pytest.raises(_core.ConvergenceError) as info:
        SQUARE.solve([160.0, 160.0], max_evaluations=1)
    err = info.value
    back = pickle.loads(pickle.dumps(err))
    assert str(back) == str(err)
    assert back.residual == err.residual > 0 and back.evaluations == err.evaluations > 0


def test_stability_and_branch_keep_every_field_through_pickle() -> None:
    st = _core.stability(SQUARE, SQUARE.solve([90.0, 90.0]))
    back = pickle.loads(pickle.dumps(st))
    assert back == st and back.stable is st.stable and back.margin == st.margin
    assert back.conjugate_point == st.conjugate_point and back.evaluations == st.evaluations
    for name in ("s", "determinant", "min_stiffness", "mode"):
        np.testing.assert_array_equal(getattr(back, name), getattr(st, name))
    assert st != _core.stability(SQUARE, SQUARE.solve([91.0, 90.0]))
    br = _short_branch()
    assert len(br) >= 2
    back_br = copy.deepcopy(pickle.loads(pickle.dumps(br)))
    assert back_br == br and len(back_br) == len(br) and back_br.evaluations == br.evaluations
    for name in ("parameter", "tip_positions", "stable", "margin", "folds", "bifurcations"):
        np.testing.assert_array_equal(getattr(back_br, name), getattr(br, name))
    assert back_br.solutions == br.solutions and back_br.jumps == br.jumps
    assert [(k, p) for k, p, _ in back_br.events] == [(k, p) for k, p, _ in br.events]
    assert br != st


def test_unstable_equilibrium_error_keeps_its_fields_through_pickle() -> None:
    import tcarod

    section = _core.Section.rectangle(0.01, 0.009)
    area, ix, iy, _ = section.properties
    g = 10.0 * 1e6 * min(ix, iy) / (1000.0 * area * 0.5**3)
    body = _core.Body(0.5, section, 1e6, poisson=0.5, density=1000.0, gravity=[0.0, 0.0, -g])
    with pytest.raises(tcarod.UnstableEquilibriumError) as info:
        _core.Robot(body, []).solve([], require_stable=True)
    err = info.value
    back = pickle.loads(pickle.dumps(err))
    assert type(back) is type(err) and isinstance(back, RuntimeError)
    assert str(back) == str(err)
    assert back.margin == err.margin < 0
    assert back.solution == err.solution and back.solution.stable is False


def test_robot_and_solution_travel_to_a_spawned_process_pool() -> None:
    q, q2 = [90.0, 95.0], [100.0, 100.0]
    here = SQUARE.solve(q)
    warm_here = SQUARE.solve(q2, warm_start=here)
    ctx = multiprocessing.get_context("spawn")
    with cf.ProcessPoolExecutor(max_workers=1, mp_context=ctx) as pool:
        # bound methods pickle as getattr(robot, "solve"): the robot travels
        there = pool.submit(SQUARE.solve, q).result()
        warm_there = pool.submit(SQUARE.solve, q2, warm_start=here).result()
    assert there == here
    assert warm_there == warm_here


@pytest.mark.xdist_group("dask")
def test_batch_on_dask_process_workers_equals_serial_bit_for_bit(dask_client: Any) -> None:
    # 1,000 rows: ten chunks over two process workers, so the robot is pickled
    # to both; benches/dask_batch.py runs a 10,000-row sweep.
    t = np.linspace(25.0, 160.0, 1000)
    q = np.column_stack([t, t[::-1]])
    serial = solve_batch(SQUARE, q, chunk_size=100, threads=1)
    remote = solve_batch(SQUARE, q, chunk_size=100, client=dask_client)
    assert serial.success and len(serial) == 1000
    assert remote == serial  # every array, exactly


def test_batch_result_pickles_with_nan_rows() -> None:
    nan = np.full((1, 3), math.nan)
    r = BatchResult(nan, np.full((1, 3, 3), math.nan), np.zeros(1, np.int64), np.zeros(1, np.int64), np.zeros(1, bool))
    assert pickle.loads(pickle.dumps(r)) == r
    assert not r.success and r.status.tolist() == [1]


# ---------------------------------------------------------------- the stability verdict travels


def _tall_finger() -> Robot:
    """The Fig. 6 square stretched to 90 mm: at 25 C Newton finds it upright, an
    unstable equilibrium (it stands past its self-weight buckling length)."""
    from tcarod.io.design import loads_design
    from pathlib import Path

    text = (Path(__file__).resolve().parents[1] / "examples" / "designs" / "fig6_square.toml").read_text()
    text = text.replace("length_m = 0.040\n", "length_m = 0.090\n").replace(
        "coiled_length_m = 0.040", "coiled_length_m = 0.090"
    )
    robot: Robot = loads_design(text).robot
    return robot


@pytest.mark.parametrize("stable", [True, False], ids=["stable", "unstable"])
def test_an_unpickled_solution_keeps_its_verdict(stable: bool) -> None:
    import warnings

    import tcarod

    robot = SQUARE if stable else _tall_finger()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tcarod.UnstableEquilibriumWarning)  # the unstable case is the point
        sol = robot.solve([25.0, 25.0])
    assert sol._verdict == (stable, sol.stability_margin)
    back = pickle.loads(pickle.dumps(sol))
    # `_verdict` never computes: a verdict here came through the pickle
    assert back._verdict == sol._verdict
    assert f"stable={stable}" in repr(back) and repr(back) == repr(sol)
    assert back == sol and copy.deepcopy(sol)._verdict == sol._verdict


def test_an_unpickled_solution_without_a_verdict_computes_it_on_demand() -> None:
    sol = SQUARE.solve([60.0, 25.0], stability="off")
    back = pickle.loads(pickle.dumps(sol))
    assert back._verdict is None and "stable=" not in repr(back)
    assert back.stable is True and "stable=True" in repr(back)


def test_a_forged_verdict_margin_is_refused() -> None:
    sol = SQUARE.solve([60.0, 25.0])
    restore, (state, stable, margin) = sol.__reduce__()
    assert restore is _core._restore_solution_verdict and stable is True
    with pytest.raises(ValueError, match="margin"):
        restore(state, True, math.nan)


def test_a_heavy_body_on_several_shooting_segments_pickles_to_its_shape() -> None:
    # a soft rod hanging 5 degrees off vertical, weight ratio q L^3 / EI ~ 670:
    # its single IVP from the base amplifies rounding by ~e^17, so the solve
    # shoots from several nodes, and the pickle carries the state at each
    # segment's first node; unpickling integrates each segment from it (no
    # solve: the same work counts), which reproduces the shape to the
    # rounding of those states (a few eps) times the growth bound of a
    # segment (100): 1e-12 of the length
    length, g, tilt = 0.2, 9.81, math.radians(5.0)
    body = _core.Body(
        length,
        _core.Section.circle(0.01),
        20e3,
        poisson=0.5,
        density=1070.0,
        gravity=[g * math.sin(tilt), 0.0, g * math.cos(tilt)],
    )
    sol = _core.Robot(body, []).solve([])
    back = pickle.loads(pickle.dumps(sol))
    assert np.abs(back.positions - sol.positions).max() <= 1e-12 * length
    assert (back.iterations, back.evaluations) == (sol.iterations, sol.evaluations)
    restore, state = sol.__reduce__()
    if restore is _core._restore_solution_verdict:
        state = state[0]  # (the verdict travels beside the state)
    assert state[-1] is not None and len(state[-1]) >= 2
    with pytest.raises(ValueError, match="segment states"):
        _core._restore_solution(*state[:-1], [row[:-1] for row in state[-1]])
    with pytest.raises(ValueError, match="several shooting segments"):
        _core._restore_solution(*state[:-1], None)
    assert back.tip_position[0] > 0.01  # it hangs bent toward the tilt, 17.7 mm
