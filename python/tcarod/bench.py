"""``tcarod bench``: the performance table of the rod model, measured here.

Rows (Fig. 6 square manipulator, 2 TCAs, gravity, 100 RK4 steps unless the
row says otherwise, one core) are timed in Rust (``_core.bench_time``; the
problems are defined in ``benches/rows/mod.rs`` of the source tree, shared
with the criterion benches) as the median of ``--repeats`` runs. Besides the
rows: the Python call overhead on a warm solve, batch throughput on 1 and 2
threads, the peak memory of a 100,000-row batch, and the ratio to the
NumPy/SciPy baseline (``benches/numpy_baseline.py`` of a source checkout, if
present).

Peak memory (``batch_memory`` in the JSON document; ``--memory-rows``, 0
skips it): a fresh interpreter imports tcarod, builds the robot and the
``(rows, 2)`` input array of a 40-140 C sweep, then solves it with
:func:`tcarod.batch.solve_batch` (all cores, default chunks, no stability
verdict) and returns the tip poses. ``peak_rss_increase_mb`` is the increase
of that process's peak resident set size (``resource.getrusage`` ``ru_maxrss``,
KiB on Linux) over the batch: everything the batch allocates, Rust and NumPy
alike. A fresh process is used so that the peak before the batch is that of
the imports only, not of an earlier, larger measurement; a batch too small to
rise above that peak reads 0. ``python_peak_mb`` is
the peak of the allocations traced by :mod:`tracemalloc` during the batch:
Python objects and buffers NumPy allocates itself; result arrays whose buffers
Rust allocated and hands to NumPy are not traced, so this is a lower bound of
the Python-visible memory, and the RSS figure is the one to quote (it
includes tracemalloc's own bookkeeping, small for a batch's few large
arrays). MB are 10^6 bytes.

``--json`` prints one JSON document instead of the table (times in s).
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path
from types import ModuleType
from typing import Any, Callable

import numpy as np

from . import __version__, _core
from ._optional import require
from .batch import fig6_square_robot, solve_batch

__all__ = ["add_parser", "measure", "run"]

BASELINE = Path(__file__).resolve().parents[2] / "benches" / "numpy_baseline.py"
#: Rows of the peak-memory batch (``--memory-rows``).
MEMORY_ROWS = 100_000
#: Bytes per MB in the reported memory figures.
MB = 1e6


def add_parser(sub: Any) -> None:
    """Register the ``bench`` subcommand on an argparse subparsers object."""
    p = sub.add_parser(
        "bench",
        help="time the rod model (forward solves, J and C, grasp, batches) against its targets",
        description="Time the rod model's operations (medians of repeats) against the performance "
        "targets; batch throughput on 1 and 2 threads; ratio to the NumPy/SciPy baseline.",
    )
    p.add_argument("--repeats", type=int, default=7, metavar="N", help="timed runs per row (default 7)")
    p.add_argument("--min-time", type=float, default=0.05, metavar="S", help="seconds per run (default 0.05)")
    p.add_argument(
        "--batch", type=int, default=2000, metavar="N", help="solves per throughput batch (default 2000; 0: skip)"
    )
    p.add_argument(
        "--memory-rows",
        type=int,
        default=MEMORY_ROWS,
        metavar="N",
        help=f"rows of the peak-memory batch, solved in a fresh process (default {MEMORY_ROWS}; 0: skip)",
    )
    p.add_argument("--no-baseline", action="store_true", help="skip the (slow) NumPy/SciPy baseline")
    p.add_argument("--progress", action="store_true", help="show a progress bar for the throughput batches")
    p.add_argument("--json", action="store_true", help="print one JSON document instead of the table (times in s)")


def _median_time(f: Callable[[], object], repeats: int, min_time: float) -> float:
    f()
    t0 = time.perf_counter()
    f()
    inner = max(1, int(min_time / max(time.perf_counter() - t0, 1e-9)))
    runs = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(inner):
            f()
        runs.append((time.perf_counter() - t0) / inner)
    return statistics.median(runs)


def _load_baseline() -> ModuleType | None:
    if not BASELINE.is_file():
        return None
    spec = importlib.util.spec_from_file_location("tcarod_numpy_baseline", BASELINE)
    if spec is None or spec.loader is None:
        return None
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod  # dataclasses look their module up
    require("scipy")  # the baseline solves with scipy.optimize (the `fit` extra)
    spec.loader.exec_module(mod)
    return mod


def _peak_rss_bytes() -> int:
    """Peak resident set size of this process so far [bytes] (``ru_maxrss``: KiB on Linux, bytes on macOS)."""
    import resource

    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return int(peak) if sys.platform == "darwin" else int(peak) * 1024


def _memory_child(rows: int) -> None:
    """Body of the peak-memory process: one ``rows``-row sweep batch; prints one JSON line."""
    import tracemalloc

    robot = fig6_square_robot(True)
    temps = np.linspace(40.0, 140.0, rows)
    q = np.column_stack([temps, temps])
    before = _peak_rss_bytes()
    tracemalloc.start()
    t0 = time.perf_counter()
    res = solve_batch(robot, q, stability="off")
    seconds = time.perf_counter() - t0
    after = _peak_rss_bytes()
    python_peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    doc = {
        "rows": rows,
        "threads": _core.default_threads(),
        "seconds": seconds,
        "all_converged": bool(res.converged.all()),
        "peak_rss_before_mb": before / MB,
        "peak_rss_mb": after / MB,
        "peak_rss_increase_mb": (after - before) / MB,
        "python_peak_mb": python_peak / MB,
    }
    print(json.dumps(doc))


def _batch_memory(rows: int) -> dict[str, Any] | None:
    """Peak memory of a ``rows``-row batch, measured in a fresh interpreter (see the module docstring)."""
    if sys.platform == "win32":  # no ``resource`` module
        return None
    package_root = str(Path(__file__).resolve().parents[1])
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (package_root, env.get("PYTHONPATH", "")) if p)
    code = "import sys; from tcarod.bench import _memory_child; _memory_child(int(sys.argv[1]))"
    proc = subprocess.run([sys.executable, "-c", code, str(rows)], capture_output=True, text=True, env=env, check=False)
    if proc.returncode != 0:
        tail = " ".join(proc.stderr.strip().splitlines()[-3:])
        raise ChildProcessError(f"the peak-memory batch failed (exit status {proc.returncode}): {tail}")
    doc: dict[str, Any] = json.loads(proc.stdout.strip().splitlines()[-1])
    doc["method"] = (
        "increase of the peak RSS (getrusage ru_maxrss) of a fresh process over the batch; "
        "python_peak_mb: tracemalloc peak during the batch"
    )
    return doc


def measure(
    repeats: int = 7,
    min_time: float = 0.05,
    batch: int = 2000,
    baseline: bool = True,
    progress: bool = False,
    memory_rows: int = MEMORY_ROWS,
) -> dict[str, Any]:
    """Measure everything ``tcarod bench`` prints; returns the JSON document."""
    rows = []
    medians: dict[str, float] = {}
    for name, description, target in _core.bench_rows():
        runs = _core.bench_time(name, repeats, min_time)
        med = statistics.median(runs)
        medians[name] = med
        rows.append(
            {
                "name": name,
                "description": description,
                "target_s": target,
                "median_s": med,
                "runs_s": runs,
                "meets_target": med <= target,
            }
        )
    # Python call overhead on a warm solve: the same solve as row "warm", called from Python
    robot = fig6_square_robot(True)
    # the Rust rows time the solve alone: no stability verdict here either
    warm = robot.solve([95.0, 95.0], stability="off")
    py_warm = _median_time(lambda: robot.solve([100.0, 100.0], warm_start=warm, stability="off"), repeats, min_time)
    overhead = {
        "python_warm_solve_s": py_warm,
        "rust_warm_solve_s": medians["warm"],
        "fraction": py_warm / medians["warm"] - 1.0,
        "target_fraction": 0.10,
    }
    throughput: dict[str, Any] = {}
    if batch > 0:
        temps = np.linspace(40.0, 140.0, batch)
        q = np.column_stack([temps, temps])
        for threads in (1, 2):
            t0 = time.perf_counter()
            res = solve_batch(
                robot, q, chunk_size=max(1, batch // 16), threads=threads, progress=progress, stability="off"
            )
            dt = time.perf_counter() - t0
            throughput[f"threads_{threads}"] = {
                "solves": batch,
                "seconds": dt,
                "solves_per_s": batch / dt,
                "all_converged": bool(res.converged.all()),
            }
    memory = _batch_memory(memory_rows) if memory_rows > 0 else None
    numpy: dict[str, Any] | None = None
    if baseline:
        mod = _load_baseline()
        if mod is not None:
            m = mod.Fig6Square(True)
            t = np.array([100.0, 100.0])
            _, _, x, _ = mod.solve(m, t)
            tau = np.array([m.tension(x[6 + i] * mod.LENGTH, t[i]) for i in range(2)])
            np_ivp = _median_time(lambda: mod.integrate(m, x, tau, 100), max(1, repeats // 2), 0.0)
            np_cold = _median_time(lambda: mod.solve(m, t), 1, 0.0)
            numpy = {
                "numpy_ivp_s": np_ivp,
                "numpy_cold_solve_s": np_cold,
                "ivp_ratio": np_ivp / medians["ivp"],
                "cold_solve_ratio": np_cold / medians["cold"],
            }
    return {
        "tcarod_version": __version__,
        "threads_available": _core.default_threads(),
        "rows": rows,
        "python_overhead": overhead,
        "batch_throughput": throughput,
        "batch_memory": memory,
        "numpy_baseline": numpy,
    }


def _fmt(s: float) -> str:
    return f"{s * 1e3:.2f} ms" if s >= 1e-3 else f"{s * 1e6:.1f} us"


def _table(doc: dict[str, Any]) -> str:
    lines = [f"{'operation':<74} {'median':>10} {'target':>10}  ok"]
    for r in doc["rows"]:
        lines.append(
            f"{r['description']:<74} {_fmt(r['median_s']):>10} {_fmt(r['target_s']):>10}  {'yes' if r['meets_target'] else 'NO'}"
        )
    o = doc["python_overhead"]
    lines.append(
        f"{'Python call overhead on a warm solve':<74} {o['fraction'] * 100:>9.1f}% {'10%':>10}  {'yes' if o['fraction'] < 0.1 else 'NO'}"
    )
    for k, v in doc["batch_throughput"].items():
        lines.append(f"batch of {v['solves']} sweep solves, {k.replace('_', ' ')}: {v['solves_per_s']:.0f} solves/s")
    m = doc["batch_memory"]
    if m is not None:
        lines.append(
            f"batch of {m['rows']} sweep solves returning tip poses, {m['threads']} threads: peak RSS "
            f"+{m['peak_rss_increase_mb']:.1f} MB over the batch (process peak {m['peak_rss_mb']:.1f} MB; "
            f"traced Python/NumPy allocations {m['python_peak_mb']:.1f} MB)"
        )
    nb = doc["numpy_baseline"]
    if nb is not None:
        lines.append(
            f"NumPy/SciPy baseline: IVP {_fmt(nb['numpy_ivp_s'])} ({nb['ivp_ratio']:.0f}x the Rust IVP), "
            f"cold solve {_fmt(nb['numpy_cold_solve_s'])} ({nb['cold_solve_ratio']:.0f}x)"
        )
    return "\n".join(lines)


def run(args: argparse.Namespace) -> int:
    """Run ``tcarod bench`` with parsed arguments; returns the exit status."""
    import math

    if not (
        1 <= args.repeats <= 10_000
        and math.isfinite(args.min_time)
        and 0 <= args.min_time <= 60
        and 0 <= args.batch <= 1_000_000
        and 0 <= args.memory_rows <= 1_000_000
    ):
        raise ValueError(
            "--repeats must be in 1..10000, --min-time in [0, 60] s, --batch and --memory-rows in 0..1000000"
        )
    if args.progress:
        require("tqdm")  # one line naming the extra, before any work
    doc = measure(args.repeats, args.min_time, args.batch, not args.no_baseline, args.progress, args.memory_rows)
    print(json.dumps(doc, indent=2, allow_nan=False) if args.json else _table(doc))
    return 0
