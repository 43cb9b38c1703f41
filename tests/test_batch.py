"""Batch API (tcarod.batch), the NumPy/SciPy baseline and `tcarod bench`.

No timing assertions: only results and structure.
"""

from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest

from tcarod import _core
from tcarod.batch import BatchResult, fig6_square_robot, iter_batches, solve_batch
from tcarod.cli import main

ROOT = Path(__file__).resolve().parents[1]


def _baseline() -> ModuleType:
    spec = importlib.util.spec_from_file_location("numpy_baseline", ROOT / "benches" / "numpy_baseline.py")
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    return mod


def _sweep(n: int) -> np.ndarray:
    t = np.linspace(40.0, 150.0, n)
    t[n // 2] = 30.0  # a jump back along the sweep
    return np.column_stack([t, t + 2.0])


def test_batch_equals_individual_solves() -> None:
    robot = fig6_square_robot()
    q = _sweep(21)
    res = solve_batch(robot, q, chunk_size=4, threads=2)
    assert res.tip_positions.shape == (21, 3)
    assert res.tip_rotations.shape == (21, 3, 3)
    assert res.converged.all()
    assert (res.iterations >= 0).all()
    for k in range(len(q)):
        s = robot.solve(list(q[k]))
        # both converge to the same residual tolerance: ~1e-12 m apart
        np.testing.assert_allclose(res.tip_positions[k], s.positions[-1], rtol=0, atol=1e-9)
        np.testing.assert_allclose(res.tip_rotations[k], s.rotations[-1], rtol=0, atol=1e-9)


def test_batch_tensions_equal_individual_solves() -> None:
    robot = fig6_square_robot()
    q = _sweep(21)
    res = solve_batch(robot, q, chunk_size=4, threads=2)
    assert res.tensions is not None and res.tensions.shape == (21, 2) and res.tensions.dtype == np.float64
    single = np.array([robot.solve(list(row)).tensions for row in q])
    # The batch warm-starts, the single solves start cold: both stop at the
    # Newton residual tolerance (1e-10), so the tensions differ by ~1e-12 N
    # (measured) against ~0.07 N at most; 1e-9 of the largest tension bounds it.
    atol = 1e-9 * float(np.abs(single).max())
    np.testing.assert_allclose(res.tensions, single, rtol=0, atol=atol)
    # the table has one tension column per actuator [N]
    pd = pytest.importorskip("pandas", reason="pandas is in the test extra; the table export needs it")
    df = res.to_pandas()
    assert isinstance(df, pd.DataFrame)
    np.testing.assert_array_equal(df[["tension_0_n", "tension_1_n"]].to_numpy(), res.tensions)


def test_batch_does_not_depend_on_threads_and_streams_in_blocks() -> None:
    robot = fig6_square_robot()
    q = _sweep(30)
    a = solve_batch(robot, q, chunk_size=5, threads=1)
    b = solve_batch(robot, q, chunk_size=5, threads=2)
    assert a == b  # every array (tensions included), exactly
    parts = list(iter_batches(robot, q, chunk_size=5, block_chunks=2))
    assert [len(p) for p in parts] == [10, 10, 10]
    c = BatchResult.concatenate(parts)
    assert c == a
    # an iterable of blocks (e.g. a generator of a huge sweep) streams the same way
    d = BatchResult.concatenate(iter_batches(robot, (q[i : i + 10] for i in range(0, 30, 10)), chunk_size=5))
    np.testing.assert_array_equal(a.tip_positions, d.tip_positions)


def test_progress_bar_and_wrenches(capsys: pytest.CaptureFixture[str]) -> None:
    robot = fig6_square_robot()
    q = _sweep(6)
    w = np.zeros((6, 6))
    w[:, 0] = 1e-3
    res = solve_batch(robot, q, w, chunk_size=2, progress=True)
    assert res.converged.all()
    assert "6/6" in capsys.readouterr().err
    plain = solve_batch(robot, q, chunk_size=2)
    assert np.all(res.tip_positions[:, 0] > plain.tip_positions[:, 0])  # pushed toward +x


def test_batch_rejects_bad_input() -> None:
    robot = fig6_square_robot()
    with pytest.raises(ValueError, match="row 1"):
        solve_batch(robot, [[50.0, 50.0], [50.0, 500.0]])
    with pytest.raises(ValueError, match="shape"):
        solve_batch(robot, np.zeros((3, 3)))
    with pytest.raises(ValueError, match="chunk_size"):
        solve_batch(robot, [[50.0, 50.0]], chunk_size=0)


@pytest.mark.xdist_group("dask")
def test_dask_client_gives_the_local_results(dask_client: Any) -> None:
    robot = fig6_square_robot()
    q = _sweep(12)
    local = solve_batch(robot, q, chunk_size=3)
    # a robot factory: each worker process builds its own robot
    remote = solve_batch(fig6_square_robot, q, chunk_size=3, client=dask_client)
    assert remote == local  # every array (tensions included), exactly


@pytest.mark.parametrize(("gravity", "temperature"), [(True, 60.0), (True, 130.0), (False, 100.0)])
def test_numpy_baseline_matches_the_core(gravity: bool, temperature: float) -> None:
    nb = _baseline()
    steps = 20  # the same RK4 grid on both sides; 20 steps keeps the NumPy solve short
    p, r, _, _ = nb.solve(nb.Fig6Square(gravity), np.array([temperature, temperature]), steps=steps)
    s = fig6_square_robot(gravity).solve([temperature, temperature], steps=steps)
    np.testing.assert_allclose(p, s.positions[-1], rtol=0, atol=1e-8)
    np.testing.assert_allclose(r, s.rotations[-1], rtol=0, atol=1e-8)


def test_bench_rows_and_cli_json(capsys: pytest.CaptureFixture[str]) -> None:
    names = [r[0] for r in _core.bench_rows()]
    assert names == ["ivp", "cold", "warm", "jc", "grasp", "cold_1um"]
    times = _core.bench_time("ivp", 2, 0.0)
    assert len(times) == 2 and all(t > 0 for t in times)
    with pytest.raises(ValueError, match="unknown bench row"):
        _core.bench_time("nope")
    # the memory batch on 1,000 rows here (the default 100,000 is for `tcarod bench`)
    argv = ["bench", "--json", "--repeats", "1", "--min-time", "0", "--batch", "8", "--memory-rows", "1000"]
    assert main([*argv, "--no-baseline"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert [r["name"] for r in doc["rows"]] == names
    assert set(doc["batch_throughput"]) == {"threads_1", "threads_2"}
    assert doc["python_overhead"]["python_warm_solve_s"] > 0
    assert doc["numpy_baseline"] is None
    mem = doc["batch_memory"]
    assert mem["rows"] == 1000 and mem["all_converged"]
    assert mem["peak_rss_increase_mb"] >= 0 and mem["peak_rss_mb"] > 0


def test_batch_result_carries_inputs_status_and_a_table() -> None:
    robot = fig6_square_robot()
    q = _sweep(5)
    w = np.zeros((5, 6))
    w[:, 0] = 1e-3  # 1 mN along +x on every row
    res = solve_batch(robot, q, w, chunk_size=2)
    assert res.inputs is not None and res.wrenches is not None
    np.testing.assert_array_equal(res.inputs, q)
    np.testing.assert_array_equal(res.wrenches, w)
    assert res.success and res.status.tolist() == [0] * 5 and "all 5" in res.message
    np.testing.assert_array_equal(res.nit, res.iterations)
    np.testing.assert_array_equal(res.nfev, res.evaluations)
    pd = pytest.importorskip("pandas", reason="pandas is in the test extra; the table export needs it")
    df = res.to_pandas()
    assert isinstance(df, pd.DataFrame) and len(df) == 5
    assert list(df.columns[:2]) == ["input_0", "input_1"]
    np.testing.assert_array_equal(df[["tip_x_m", "tip_y_m", "tip_z_m"]].to_numpy(), res.tip_positions)
    assert df["force_x_n"].tolist() == [1e-3] * 5 and df["status"].tolist() == [0] * 5
    # a sweep streamed in blocks stacks to the same result, inputs included
    blocks = BatchResult.concatenate(iter_batches(robot, q, w, chunk_size=2, block_chunks=1))
    assert blocks == res


def test_failed_rows_have_status_one_and_nan_pose() -> None:
    robot = fig6_square_robot()
    # a 10 N compressive tip force on the 40 mm silicone body, far past its
    # buckling load, on every other row: no equilibrium is found there
    w = np.zeros((6, 6))
    w[1::2, 2] = -10.0
    res = solve_batch(robot, _sweep(6), w, chunk_size=1)
    bad = ~res.converged
    assert bad.any()
    assert (res.status[bad] == 1).all() and np.isnan(res.tip_positions[bad]).all()
    assert res.tensions is not None and res.tensions.shape == (6, 2)
    assert np.isnan(res.tensions[bad]).all() and not np.isnan(res.tensions[~bad]).any()
    assert not res.success and "did not converge" in res.message
    # a failed row reports the work it spent (each row integrates at least one IVP), not zeros
    assert (res.evaluations[bad] >= 1).all(), res.evaluations
    # the repr summarises (a batch may hold millions of rows): counts, never arrays
    text = repr(res)
    assert text.startswith("<BatchResult: 6 rows") and f"converged {int(np.count_nonzero(~bad))}/6" in text, text
    assert "array(" not in text and len(text) < 300, text


def test_batch_repr_and_notebook_view_summarise_without_arrays() -> None:
    robot = fig6_square_robot()
    res = solve_batch(robot, _sweep(400), chunk_size=400)
    text = repr(res)
    # 400 rows x 10 fields would print as truncated numpy arrays; the summary is one short line
    assert len(text) < 300 and "\n" not in text and "array(" not in text, text
    assert "400 rows" in text and "converged 400/400" in text and "actuators 2" in text, text
    assert f"max {int(res.evaluations.max())}" in text and "stable 400/400" in text, text
    lo = res.tip_positions.min(axis=0) * 1e3
    assert f"{lo[0]:.4g}.." in text  # the tip range [mm] is the converged rows' min..max
    page = res._repr_html_()
    assert page.startswith("<div><b>tcarod BatchResult</b>") and "<td>converged</td><td>400/400</td>" in page


# ---------------------------------------------------------------- shapes=True and plot_tips

SQUARE = fig6_square_robot()
SWEEP = np.column_stack([np.linspace(25.0, 90.0, 7), np.full(7, 25.0)])


def test_shapes_keep_every_rows_centre_line() -> None:
    res = solve_batch(SQUARE, SWEEP, shapes=True, threads=1)
    tips = solve_batch(SQUARE, SWEEP, threads=1)
    assert res.success and res.positions is not None and res.arc_length is not None
    one = SQUARE.solve(SWEEP[3].tolist())
    assert np.array_equal(res.arc_length, one.s)
    assert res.positions.shape == (len(SWEEP), len(one.s), 3)
    # the shape is the row's own solution: its last node is the tip
    assert np.array_equal(res.positions[:, -1], res.tip_positions)
    # a cold Robot.solve converges to the same equilibrium within its tol (1e-10,
    # dimensionless): the centre lines agree to far below a micrometre
    assert np.abs(res.positions[3] - one.positions).max() < 1e-9
    # the same solves: every solve records its shape, at no extra IVP
    assert np.array_equal(res.tip_positions, tips.tip_positions)
    assert np.array_equal(res.evaluations, tips.evaluations)
    assert tips.positions is None and tips.arc_length is None
    assert "nodes per row" in repr(res)


def test_shapes_stream_and_pickle_the_same() -> None:
    import pickle

    whole = solve_batch(SQUARE, SWEEP, shapes=True, chunk_size=2, threads=1)
    parts = list(iter_batches(SQUARE, SWEEP, shapes=True, chunk_size=2, block_chunks=1, threads=1))
    assert len(parts) == 4
    assert BatchResult.concatenate(parts) == whole
    assert pickle.loads(pickle.dumps(whole)) == whole


def test_concatenate_pads_a_block_without_converged_rows() -> None:
    ok = solve_batch(SQUARE, SWEEP[:2], shapes=True)
    assert ok.arc_length is not None and ok.positions is not None
    nan = np.full((1, 3), np.nan)
    failed = BatchResult(
        nan,
        np.full((1, 3, 3), np.nan),
        np.zeros(1, np.int64),
        np.zeros(1, np.int64),
        np.zeros(1, bool),
        arc_length=np.empty(0),
        positions=np.empty((1, 0, 3)),
    )
    both = BatchResult.concatenate([ok, failed])
    assert both.positions is not None and both.positions.shape == (3, len(ok.arc_length), 3)
    assert np.isnan(both.positions[2]).all() and np.array_equal(both.positions[:2], ok.positions)
    assert BatchResult.concatenate([ok, solve_batch(SQUARE, SWEEP[:1])]).positions is None


def test_shapes_must_be_a_bool() -> None:
    with pytest.raises(TypeError, match="shapes"):
        solve_batch(SQUARE, SWEEP, shapes="yes")


def test_plot_tips_draws_the_trajectory_shapes_and_unstable_rows() -> None:
    pytest.importorskip("matplotlib", reason="matplotlib (the `plot` extra) is not installed")
    res = solve_batch(SQUARE, SWEEP, shapes=True)
    fig = res.plot_tips(shapes=3)
    ax = fig.axes[0]
    gids = [line.get_gid() for line in ax.lines]
    assert "tips" in gids and sum(str(g).startswith("shape-") for g in gids) == 3
    (tips,) = [line for line in ax.lines if line.get_gid() == "tips"]
    x, y, z = tips.get_data_3d()
    assert np.allclose(np.column_stack([x, y, z]), res.tip_positions * 1e3)  # [mm]; float scaling only
    assert ax.get_xlabel() == "x [mm]"
    assert "unstable" not in [c.get_gid() for c in ax.collections]  # every row of this sweep is stable
    stable = np.ones(len(res), bool)
    stable[2] = False
    marked = BatchResult(**{**res.__dict__, "stable": stable})
    assert "unstable" in [c.get_gid() for c in marked.plot_tips().axes[0].collections]


def test_plot_tips_refuses_bad_arguments() -> None:
    pytest.importorskip("matplotlib", reason="matplotlib (the `plot` extra) is not installed")
    res = solve_batch(SQUARE, SWEEP[:2])
    with pytest.raises(ValueError, match="shapes"):
        res.plot_tips(shapes=-1)
    with pytest.raises(TypeError, match="shapes"):
        res.plot_tips(shapes=2.5)
    nothing = BatchResult(**{**res.__dict__, "converged": np.zeros(2, bool)})
    with pytest.raises(ValueError, match="no row converged"):
        nothing.plot_tips()
