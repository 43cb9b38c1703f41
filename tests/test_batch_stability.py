"""Batch rows carry the stability verdict (docs/stability.md, "The stability
of every solve"): ``solve_batch(..., stability="report")`` (the default) gives
every converged row ``stable`` and ``margin``, the same verdict as
``Robot.solve``; ``stability="off"`` says "not computed" (``None``). The
physics of the verdict is tested in tests/integration/stability_batch.rs."""

from __future__ import annotations

import numpy as np
import pytest

from tcarod.batch import BatchResult, fig6_square_robot, iter_batches, solve_batch

# the upright column past self-weight buckling (rho A g L^3 / (E I) = 10 >
# Greenhill's 7.837), without actuators, as in tests/test_solution_stability.py
from test_solution_stability import heavy_column  # noqa: E402  (tests/ is on sys.path under pytest)


def test_buckled_column_rows_are_unstable() -> None:
    robot = heavy_column()
    # no tip wrench: the cold solve of the perfect column stays straight,
    # an equilibrium past self-weight buckling, so unstable (on the axis to
    # rounding: 1e-9 m)
    res = solve_batch(robot, np.zeros((3, 0)), np.zeros((3, 6)))
    assert res.stable is not None and res.margin is not None
    assert res.converged.all()
    assert np.all(np.hypot(res.tip_positions[:, 0], res.tip_positions[:, 1]) < 1e-9)
    assert not res.stable.any()
    assert np.all(res.margin < 0)
    sol = robot.solve([], stability="off")
    assert res.margin[0] == sol.stability_margin  # the same cold equilibrium, the same verdict


def test_fig6_rows_are_stable_and_match_solve() -> None:
    robot = fig6_square_robot()
    temps = np.array([40.0, 100.0, 160.0])
    res = solve_batch(robot, np.column_stack([temps, temps]), threads=1)
    assert res.stable is not None and res.margin is not None
    assert res.stable.dtype == np.bool_ and res.margin.dtype == np.float64
    assert res.stable.all() and np.all(res.margin > 0)
    for k, t in enumerate(temps):
        sol = robot.solve([t, t])
        # warm batch row vs cold solve, both converged to 1e-10: the margins
        # (order 1) agree to ~1e-8; 1e-6 relative bounds it
        assert res.margin[k] == pytest.approx(sol.stability_margin, rel=1e-6)
    df_cols = set(res.to_pandas().columns) if _has_pandas() else {"stable", "margin"}
    assert {"stable", "margin"} <= df_cols


def test_off_says_not_computed_and_costs_one_integration_less() -> None:
    robot = fig6_square_robot()
    q = np.full((4, 2), 90.0)
    on = solve_batch(robot, q, threads=1)
    off = solve_batch(robot, q, threads=1, stability="off")
    assert off.stable is None and off.margin is None
    np.testing.assert_array_equal(on.tip_positions, off.tip_positions)
    np.testing.assert_array_equal(on.evaluations, off.evaluations + 1)


def test_verdict_survives_blocks_and_concatenation() -> None:
    robot = fig6_square_robot()
    t = np.linspace(40.0, 160.0, 6)
    q = np.column_stack([t, t])
    whole = solve_batch(robot, q, chunk_size=2, threads=1)
    parts = BatchResult.concatenate(iter_batches(robot, q, chunk_size=2, block_chunks=1, threads=1))
    assert parts == whole
    assert parts.stable is not None and parts.stable.all()


def test_bad_stability_names_the_argument() -> None:
    robot = fig6_square_robot()
    with pytest.raises(ValueError, match="stability"):
        solve_batch(robot, np.full((1, 2), 90.0), stability="require")


def _has_pandas() -> bool:
    try:
        import pandas  # noqa: F401
    except ImportError:
        return False
    return True
