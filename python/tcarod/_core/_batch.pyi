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
    """Solve the forward problem for every row of ``inputs``, in the core.

    The binding behind ``tcarod.batch.solve_batch`` (which returns a
    ``BatchResult``); the GIL is released. Rows are cut into chunks of
    ``chunk_size``, each solved in order with warm starts.

    Parameters
    ----------
    robot : Robot
        The robot.
    inputs : numpy.ndarray
        Shape ``(n, n_actuators)``: temperatures [C] for TCAs; at most
        10,000,000 rows per call.
    wrenches : numpy.ndarray, optional
        Shape ``(n, 6)``: tip force [N] and moment [N m], world frame.
    steps, tol, max_iter : optional
        As for ``Robot.solve`` (``steps`` and ``max_iter`` 1 to 100,000).
    chunk_size : int, optional
        Rows per warm-started chunk, 1 to 10,000,000 (default 256).
    threads : int, optional
        Worker threads, 0 (default: all cores) to 1024.
    warm : bool, optional
        Warm-start each row from the previous row of its chunk (default).
    stability : {"report", "off"}, optional
        ``"report"``: one tangent integration per converged row for its
        verdict; ``"off"``: none.
    shapes : bool, optional
        Also return every row's centre line (recorded by the solve: no extra IVP).

    Returns
    -------
    tuple
        ``(tip_positions (n, 3) [m], tip_rotations (n, 3, 3) [-], tensions
        (n, n_actuators) [N], iterations (n,), evaluations (n,), converged
        (n,), stable (n,), margin (n,) [-], shapes)``: NaN pose and tensions
        and ``converged = False`` where a row does not converge; ``stable``
        and ``margin`` ``None`` with ``stability="off"`` (NaN margin where
        there is no verdict); ``shapes`` is ``(arc_length (nodes,) [m],
        positions (n, nodes, 3) [m])`` with ``shapes=True``, else ``None``.

    Raises
    ------
    ValueError
        An argument outside its range, or a row of ``inputs`` (named).

    Examples
    --------
    >>> from tcarod import _core
    >>> from tcarod.batch import fig6_square_robot
    >>> out = _core.solve_batch(fig6_square_robot(), np.array([[25.0, 25.0], [60.0, 60.0]]), steps=20)
    >>> out[0].shape, out[5].tolist()           # tip positions (n, 3) [m], converged
    ((2, 3), [True, True])
    """

def default_threads() -> int:
    """Worker threads ``solve_batch`` uses for ``threads=0``.

    Returns
    -------
    int
        The available cores [-].

    Examples
    --------
    >>> from tcarod import _core
    >>> _core.default_threads() >= 1
    True
    """

def bench_rows() -> list[tuple[str, str, float]]:
    """Rows of the performance table.

    Returns
    -------
    list of tuple
        ``(name, description, target [s])`` per row.

    Examples
    --------
    >>> from tcarod import _core
    >>> name, description, target = _core.bench_rows()[0]
    >>> isinstance(name, str) and target > 0      # [s]
    True
    """

def bench_time(name: str, repeats: int = 7, min_time: float = 0.05) -> list[float]:
    """Time one row of the performance table in Rust.

    The GIL is released while timing.

    Parameters
    ----------
    name : str
        A row of ``bench_rows()``.
    repeats : int, optional
        Runs, 1 to 1000 (default 7).
    min_time : float, optional
        Shortest loop of each run [s], 0 to 60 (default 0.05).

    Returns
    -------
    list of float
        Seconds per operation of each run [s].

    Raises
    ------
    ValueError
        An unknown ``name`` or an argument out of range.

    Examples
    --------
    >>> from tcarod import _core
    >>> times = _core.bench_time("ivp", repeats=2, min_time=0.0)     # [s] per IVP
    >>> len(times), all(t > 0 for t in times)
    (2, True)
    """
