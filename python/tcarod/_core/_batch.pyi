"""Batch solves and bench timings of ``tcarod._core`` (src/python/batch.rs)."""

from typing import Literal

import numpy as np
import numpy.typing as npt

from ._common import _FloatArray
from ._rod import Robot

# --- batch solves and bench timings (src/python/batch.rs; see tcarod.batch) ---

def solve_batch(
    robot: Robot,
    inputs: _FloatArray,
    wrenches: _FloatArray | None = None,
    *,
    steps: int = 100,
    tol: float = 1e-10,
    max_iter: int = 50,
    chunk_size: int = 256,
    threads: int = 0,
    warm: bool = True,
    stability: Literal["report", "off"] = "report",
    shapes: bool = False,
) -> tuple[
    _FloatArray,
    _FloatArray,
    _FloatArray,
    npt.NDArray[np.int64],
    npt.NDArray[np.int64],
    npt.NDArray[np.bool_],
    npt.NDArray[np.bool_] | None,
    _FloatArray | None,
    tuple[_FloatArray, _FloatArray] | None,
]:
    """Solve every row of ``inputs`` ``(n, n_actuators)`` in parallel; returns
    ``(tip_positions (n, 3) [m], tip_rotations (n, 3, 3), tensions (n, n_actuators) [N],
    iterations, evaluations, converged, stable, margin)``. ``stability="report"``
    gives each converged row its verdict: ``stable`` ``(n,)`` and ``margin``
    ``(n,)`` [-] (> 0 iff stable; NaN where there is none), one tangent
    integration per row; ``"off"`` skips it and returns ``None`` for both.
    ``shapes=True`` appends ``(arc_length (nodes,) [m], positions (n, nodes, 3)
    [m])`` (NaN rows where a solve did not converge; one more IVP per
    converged row), else ``None``."""

def default_threads() -> int:
    """Worker threads ``solve_batch`` uses for ``threads=0``."""

def bench_rows() -> list[tuple[str, str, float]]:
    """Rows of the performance table: ``(name, description, target [s])``."""

def bench_time(name: str, repeats: int = 7, min_time: float = 0.05) -> list[float]:
    """Seconds per operation of row ``name``, one value per run (timed in Rust)."""
