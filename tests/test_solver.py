"""Solver contract seen from Python: ConvergenceError's attributes survive
pickling, and Ctrl-C (SIGINT) interrupts long batches and sweeps promptly.

No timing assertions on speed: the wall-time bounds below only check that an
interrupt is answered long before the work would have finished.
"""

from __future__ import annotations

import os
import pickle
import signal
import threading
import time

import numpy as np
import pytest

from tcarod import _core
from tcarod.batch import fig6_square_robot


def test_convergence_error_attributes_survive_pickle() -> None:
    robot = fig6_square_robot()
    # a budget of one IVP is too little for a cold solve at 150 C (it needs 3)
    with pytest.raises(_core.ConvergenceError) as info:
        robot.solve([150.0, 150.0], max_evaluations=1)
    err = info.value
    assert err.residual > 0.0 and not np.isnan(err.residual)
    assert err.evaluations >= 1
    assert err.reason == "budget"
    back = pickle.loads(pickle.dumps(err))
    assert type(back) is _core.ConvergenceError
    assert back.residual == err.residual
    assert (back.iterations, back.evaluations, back.reason) == (err.iterations, err.evaluations, err.reason)


def _interrupt_after(seconds: float) -> threading.Timer:
    timer = threading.Timer(seconds, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    return timer


@pytest.mark.parametrize(
    ("threads", "n", "after"),
    [
        (1, 200_000, 0.2),  # minutes of work on one core
        (2, 200_000, 0.2),
        # 2M rows, interrupted while they are checked and their outputs
        # allocated (0.3-1 s before any solve; polled there too)
        (1, 2_000_000, 0.05),
    ],
)
def test_ctrl_c_interrupts_a_long_batch(threads: int, n: int, after: float) -> None:
    robot = fig6_square_robot()
    t = np.linspace(40.0, 150.0, n)
    inputs = np.column_stack([t, t])
    timer = _interrupt_after(after)
    start = time.monotonic()
    try:
        with pytest.raises(KeyboardInterrupt):
            _core.solve_batch(robot, inputs, chunk_size=256, threads=threads)
    finally:
        timer.cancel()
    # answered within the 20 ms poll interval plus one row's solve; 5 s is
    # generous for a loaded machine and far below the batch's duration
    assert time.monotonic() - start < 5.0


def test_ctrl_c_interrupts_a_long_sweep() -> None:
    robot = fig6_square_robot()
    t = np.linspace(40.0, 150.0, 100_000)
    timer = _interrupt_after(0.2)
    start = time.monotonic()
    try:
        with pytest.raises(KeyboardInterrupt):
            robot.sweep(np.column_stack([t, t]))
    finally:
        timer.cancel()
    assert time.monotonic() - start < 5.0


def test_solution_reports_status_floor_and_path() -> None:
    robot = fig6_square_robot()
    sol = robot.solve([100.0, 100.0])
    # the default tol 1e-10 lies above the floor: converged to tol, direct
    assert sol.status == 0 and sol.success
    assert 0.0 < sol.floor < 1e-10
    assert sol.continuation_steps.shape == (0,)
    # a tol far below the rounding floor converges to the floor and says so
    deep = robot.solve([100.0, 100.0], tol=1e-16)
    assert deep.status == 1 and deep.success and "rounding floor" in deep.message
    assert deep.residual <= 100.0 * deep.floor
    # same shape to far below a micrometre (1e-9 m: the floor is ~1e-13 of
    # order-one strains on a 0.1 m body)
    assert np.abs(deep.tip_position - sol.tip_position).max() < 1e-9
    # two iterations are too few from the cold guess at 140 C (at 150 C they
    # suffice: the pre-solve's first coarse run stops at 1e-5): the path of
    # the continuation is recorded, increasing to 1
    cont = robot.solve([140.0, 140.0], max_iter=2)
    path = cont.continuation_steps
    assert path.size >= 1 and path[-1] == 1.0 and (np.diff(path) > 0).all()
    assert "continuation" in cont.message
    # pickling keeps them
    for s in (deep, cont):
        back = pickle.loads(pickle.dumps(s))
        assert back == s
        assert (back.status, back.floor) == (s.status, s.floor)
        assert np.array_equal(back.continuation_steps, s.continuation_steps)


def test_budget_bounds_a_solve() -> None:
    robot = fig6_square_robot()
    # a cold solve at 150 C needs about 3 IVPs (coarse ones counted in
    # full-grid IVPs)
    with pytest.raises(_core.ConvergenceError) as info:
        robot.solve([150.0, 150.0], max_evaluations=1)
    err = info.value
    assert err.reason == "budget" and "budget" in str(err)
    # stopped at the first check past the budget: one Newton step's IVPs at most
    assert 1 <= err.evaluations <= 3
    # the best full-grid residual, infinite where none was evaluated
    assert err.residual > 0.0 and not np.isnan(err.residual)
    # a time limit far below one IVP's time stops it too
    with pytest.raises(_core.ConvergenceError) as info:
        robot.solve([150.0, 150.0], time_limit=1e-9)
    assert info.value.reason == "budget"
    # generous budgets change nothing
    a = robot.solve([150.0, 150.0])
    b = robot.solve([150.0, 150.0], max_evaluations=10_000, time_limit=60.0)
    assert a == b
    for bad in (0.0, -1.0, float("nan"), float("inf"), 1e10):
        with pytest.raises(ValueError, match="time_limit"):
            robot.solve([100.0, 100.0], time_limit=bad)
    with pytest.raises(ValueError, match="max_evaluations"):
        robot.solve([100.0, 100.0], max_evaluations=0)
    with pytest.raises(TypeError):
        robot.solve([100.0, 100.0], max_evaluations=2.5)


def test_equilibrium_tol_refines_the_grid() -> None:
    from tcarod import Actuator, Body, Robot, Routing, Section

    # a 25 mm body, gravity, a tendon on a tight helix (1.3 turns in 5 mm):
    # RK4's truncation error on 100 steps is far above 1e-8 of the loads (the
    # physics of the check is tested in tests/integration/designs.rs); here the
    # binding
    body = Body(
        0.0249,
        Section.rectangle(1.87e-3, 2.14e-3),
        9.86e5,
        poisson=0.5,
        density=1085.0,
        gravity=(-7.55, -5.96, 1.92),
    )
    helix = Routing.helix(0.521e-3, -1623.6, 0.43)
    robot = Robot(body, [Actuator.tendon(helix, 1.74e-3, 6.76e-3)])
    plain = robot.solve([0.3946])
    fine = robot.solve([0.3946], equilibrium_tol=1e-8)
    assert plain.steps == 100 and fine.steps > 100
    assert fine.evaluations > plain.evaluations  # the refinement's IVPs count
    # the refined solution is the solve on its grid (both to tol 1e-10 of a
    # 25 mm body: tips within ~1e-12 m)
    direct = robot.solve([0.3946], steps=fine.steps)
    assert np.allclose(direct.tip_position, fine.tip_position, rtol=0, atol=1e-12)
    # and it moved by RK4's truncation error on 100 steps (micrometres, not more)
    assert 0.0 < np.linalg.norm(fine.tip_position - plain.tip_position) < 1e-4 * body.length
    # a paper fixture holds 1e-8 on 100 steps already: the same solution
    sq = fig6_square_robot()
    assert sq.solve([100.0, 100.0], equilibrium_tol=1e-8) == sq.solve([100.0, 100.0])
    for bad in (0.0, 1e-13, 1.0, float("nan")):
        with pytest.raises(ValueError, match="equilibrium_tol"):
            robot.solve([0.3946], equilibrium_tol=bad)
    with pytest.raises(TypeError):
        robot.solve([0.3946], equilibrium_tol="tight")  # type: ignore[arg-type]


def test_equilibrium_refinement_keeps_the_continuation_path() -> None:
    # two iterations are too few from the cold guess at 140 C: the first
    # solve takes the continuation path; 1e-11 is below the Fig. 6 square's
    # global equilibrium error on 100 RK4 steps, so the grid is refined by a
    # warm re-solve that needs no path of its own
    sq = fig6_square_robot()
    first = sq.solve([140.0, 140.0], max_iter=2)
    fine = sq.solve([140.0, 140.0], max_iter=2, equilibrium_tol=1e-11)
    assert fine.steps > first.steps
    assert first.continuation_steps[-1] == 1.0
    np.testing.assert_array_equal(fine.continuation_steps, first.continuation_steps)
