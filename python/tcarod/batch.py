"""Many forward solves in one call, in parallel, returning stacked arrays.

:func:`solve_batch` solves the forward kinetostatics for every row of an
``(n, n_actuators)`` array of inputs (temperatures [C] for TCAs), optionally
with one tip wrench per row, in the Rust core with the GIL released and on
all cores. Rows are cut into chunks of ``chunk_size``; each chunk is solved in
order, every row warm-started from the previous one, so a sweep (rows in
order of temperature) costs a fraction of independent solves. The chunking
depends on ``chunk_size`` only, so results do not depend on the number of
threads, nor on whether the chunks ran here or on Dask workers.

:func:`iter_batches` streams: it yields one :class:`BatchResult` per block of
rows and keeps nothing, so a 1,000,000-solve sweep runs in flat memory.

Example::

    import numpy as np
    from tcarod.batch import solve_batch
    temps = np.linspace(25, 160, 10_000)
    res = solve_batch(robot, np.column_stack([temps, temps]))
    res.tip_positions  # (10000, 3) [m]
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Iterable, Iterator, Literal, Union

import numpy as np
import numpy.typing as npt

from . import _core
from . import _validate as V
from ._batch_result import BatchResult
from ._optional import require
from .tca import _as_float_array

__all__ = ["BatchResult", "fig6_square_robot", "iter_batches", "solve_batch"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]
BoolArray = npt.NDArray[np.bool_]
# A batch takes a robot or a zero-argument factory returning one (Dask workers
# rebuild it): typed loosely as Any.
_c: Any = _core
Robot = Any
RobotLike = Union[Robot, Callable[[], Robot]]

DEFAULT_CHUNK_SIZE = 256
#: Ranges of the integer arguments of a batch: ``chunk_size`` in
#: ``1..MAX_CHUNK_SIZE``, ``threads`` in ``0..MAX_THREADS`` (as the core checks
#: them), ``block_chunks`` (chunks per streamed block) in ``1..MAX_BLOCK_CHUNKS``.
MAX_CHUNK_SIZE = 10_000_000
MAX_THREADS = 1024
MAX_BLOCK_CHUNKS = 1_000_000
# what a batch does with the stability verdict (see solve_batch)
BatchStability = Literal["report", "off"]


def _robot(robot: RobotLike) -> Robot:
    return robot if isinstance(robot, _c.Robot) else robot()


def _as_rows(x: Any, width: int, name: str) -> FloatArray:
    # TypeError for str, bytes, complex (incl. NumPy complex), None; ValueError for ragged rows
    a = np.ascontiguousarray(_as_float_array(name, x))
    if a.ndim == 1 and width == 1:
        a = a[:, None]
    if a.ndim != 2 or a.shape[1] != width:
        raise ValueError(f"{name}: expected shape (n, {width}), got {a.shape}")
    return a


@dataclass(frozen=True)
class _Settings:
    """What every row of a batch is solved with (see :func:`solve_batch`)."""

    steps: int
    tol: float
    max_iter: int
    chunk_size: int
    stability: BatchStability
    shapes: bool = False


def _solve_block(
    robot: RobotLike, inputs: FloatArray, wrenches: FloatArray | None, cfg: _Settings, threads: int
) -> BatchResult:
    pos, rot, tens, it, ev, ok, stable, margin, shape = _core.solve_batch(
        _robot(robot),
        inputs,
        wrenches,
        steps=cfg.steps,
        tol=cfg.tol,
        max_iter=cfg.max_iter,
        chunk_size=cfg.chunk_size,
        threads=threads,
        stability=cfg.stability,
        shapes=cfg.shapes,
    )
    arc_length, positions = (None, None) if shape is None else shape
    return BatchResult(
        pos,
        rot,
        it,
        ev,
        ok,
        inputs=inputs,
        wrenches=wrenches,
        tensions=tens,
        stable=stable,
        margin=margin,
        arc_length=arc_length,
        positions=positions,
    )


def _blocks(n: int, block: int) -> list[tuple[int, int]]:
    return [(a, min(a + block, n)) for a in range(0, n, block)]


def iter_batches(
    robot: RobotLike,
    inputs: Any,
    wrenches: Any = None,
    *,
    steps: int = 100,
    tol: float = 1e-10,
    max_iter: int = 50,
    chunk_size: int = DEFAULT_CHUNK_SIZE,
    block_chunks: int | None = None,
    threads: int = 0,
    progress: bool = False,
    stability: BatchStability = "report",
    shapes: bool = False,
) -> Iterator[BatchResult]:
    """Solve a batch block by block, holding only one block at a time.

    Streams: a 1,000,000-row sweep runs in flat memory. The arguments not
    listed are those of :func:`solve_batch`.

    Parameters
    ----------
    robot : Robot or callable
        The robot, or a zero-argument callable returning it.
    inputs : array_like or iterable of array_like
        ``(n, n_actuators)`` inputs (temperatures [C] for TCAs), or an
        iterable of ``(m, n_actuators)`` arrays (e.g. a generator making a
        huge sweep on the fly); then each yielded block is one given array.
    wrenches : array_like or iterable of array_like, optional
        ``(n, 6)`` tip force [N] and moment [N m] per row, world frame.
    steps, tol, max_iter, chunk_size, threads, stability, shapes : optional
        As for :func:`solve_batch`.
    block_chunks : int, optional
        Chunks per block, 1 to 1,000,000 (default: 4 per thread).
    progress : bool, optional
        Show a tqdm bar counting rows (the ``progress`` extra).

    Yields
    ------
    BatchResult
        The results of one block of rows, in order.

    Raises
    ------
    TypeError
        A non-integer integer argument (NumPy integers are accepted).
    ValueError
        ``chunk_size`` outside 1..10,000,000, ``threads`` outside 0..1024,
        ``block_chunks`` outside 1..1,000,000, or a bad row (named).

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot, iter_batches
    >>> temps = np.linspace(25.0, 60.0, 10)
    >>> rows = np.column_stack([temps, temps])
    >>> tuple(len(b) for b in iter_batches(fig6_square_robot(), rows, steps=20, chunk_size=4, block_chunks=1))
    (4, 4, 2)
    """
    # integer-like arguments (NumPy integers included) become Python ints before
    # any arithmetic, so a uint8 cannot wrap or overflow in the block size
    chunk_size = V.integer("chunk_size", chunk_size, 1, MAX_CHUNK_SIZE)
    threads = V.integer("threads", threads, 0, MAX_THREADS)
    if block_chunks is not None:
        block_chunks = V.integer("block_chunks", block_chunks, 1, MAX_BLOCK_CHUNKS)
    cfg = _Settings(steps, tol, max_iter, chunk_size, stability, _shapes_flag(shapes))
    nthreads = threads if threads > 0 else _core.default_threads()
    block = chunk_size * (block_chunks if block_chunks is not None else 4 * nthreads)
    yield from _stream(robot, inputs, wrenches, block, cfg, threads, progress)


def _stream(
    robot: RobotLike, inputs: Any, wrenches: Any, block: int, cfg: _Settings, threads: int, progress: bool
) -> Iterator[BatchResult]:
    """The blocks of :func:`iter_batches`: ``block`` rows of an array at a time,
    or one given array at a time, each solved as it is reached."""
    if isinstance(inputs, np.ndarray) or (
        isinstance(inputs, (list, tuple)) and inputs and not hasattr(inputs[0], "shape")
    ):
        parts: Iterable[tuple[Any, Any]] = _array_parts(inputs, wrenches, block, robot)
        total: int | None = int(np.asarray(inputs).shape[0])
    else:
        if wrenches is not None:
            parts = zip(inputs, wrenches)
        else:
            parts = ((q, None) for q in inputs)
        total = None
    bar = _progress_bar(total) if progress else None
    try:
        for q, w in parts:
            r = _robot(robot)
            na = len(r.actuators)
            qa = _as_rows(q, na, "inputs")
            wa = None if w is None else _as_rows(w, 6, "wrenches")
            res = _solve_block(r, qa, wa, cfg, threads)
            if bar is not None:
                bar.update(len(res))
            yield res
    finally:
        if bar is not None:
            bar.close()


def _array_parts(
    inputs: Any, wrenches: Any, block: int, robot: RobotLike
) -> Iterator[tuple[FloatArray, FloatArray | None]]:
    na = len(_robot(robot).actuators)
    q = _as_rows(inputs, na, "inputs")
    w = None if wrenches is None else _as_rows(wrenches, 6, "wrenches")
    if w is not None and w.shape[0] != q.shape[0]:
        raise ValueError(f"wrenches: expected {q.shape[0]} rows, got {w.shape[0]}")
    for a, b in _blocks(q.shape[0], block):
        yield q[a:b], (None if w is None else w[a:b])


def _progress_bar(total: int | None) -> Any:
    # optional dependency, imported only when a bar is asked for (untyped)
    tqdm: Any = require("tqdm").tqdm
    return tqdm(total=total, unit="solve", smoothing=0.1)


def solve_batch(
    robot: RobotLike,
    inputs: Any,
    wrenches: Any = None,
    *,
    steps: int = 100,
    tol: float = 1e-10,
    max_iter: int = 50,
    chunk_size: int = DEFAULT_CHUNK_SIZE,
    threads: int = 0,
    progress: bool = False,
    client: Any = None,
    stability: BatchStability = "report",
    shapes: bool = False,
) -> BatchResult:
    """Solve the forward kinetostatics for every row of ``inputs``.

    In the Rust core, with the GIL released, on all cores. Rows are cut into
    chunks of ``chunk_size``, each solved in order with warm starts; the
    results depend on ``chunk_size`` only, not on the threads or Dask workers.

    Parameters
    ----------
    robot : Robot or callable
        The robot, or a zero-argument callable returning it (each Dask worker
        then builds its own; the robot itself pickles too).
    inputs : array_like
        ``(n, n_actuators)``: one row of inputs per solve (temperature [C] for
        a TCA, tension [N] for a tendon, pull [m] for a linear tendon).
    wrenches : array_like, optional
        ``(n, 6)``: tip force [N] and moment [N m] per row, world frame.
    steps, tol, max_iter : optional
        RK4 steps (1 to 100,000; default 100), Newton tolerance on the
        dimensionless residual (1e-10) and iterations per row (1 to 100,000;
        50), as for ``Robot.solve``.
    chunk_size, threads : int, optional
        Rows per warm-started chunk, 1 to 10,000,000 (default 256); worker
        threads, 0 (default: all cores) to 1024.
    progress : bool, optional
        Show a tqdm bar (the ``progress`` extra).
    client : dask.distributed.Client, optional
        Spread the chunks over its workers (the ``dask`` extra).
    stability : {"report", "off"}, optional
        ``"report"`` (default): each converged row gets its verdict
        (``stable``, ``margin`` [-]) for one tangent integration, so a sweep
        through buckling never hands back an unstable shape unsaid; re-solve
        such rows with ``Robot.solve(..., stability="continue")``. ``"off"``:
        none (``stable`` and ``margin`` are ``None``).
    shapes : bool, optional
        Keep every row's centre line (``arc_length`` [m], ``positions``
        ``(n, nodes, 3)`` [m]; 2.4 kB per row at 100 steps).

    Returns
    -------
    BatchResult
        One row per input row; a row that did not converge has a NaN pose and
        ``converged = False``.

    Raises
    ------
    ValueError
        An argument outside its range, or an invalid row (named).
    TypeError
        An argument of the wrong type.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot, solve_batch
    >>> temps = np.linspace(25.0, 60.0, 5)
    >>> res = solve_batch(fig6_square_robot(), np.column_stack([temps, 25.0 + 0 * temps]), shapes=True)
    >>> res.positions.shape == (5, len(res.arc_length), 3)
    True
    >>> bool(np.array_equal(res.positions[:, -1], res.tip_positions)), bool(res.stable.all())
    (True, True)
    """
    cfg = _Settings(steps, tol, max_iter, chunk_size, stability, _shapes_flag(shapes))
    return _solve_all(robot, inputs, wrenches, cfg, threads, progress, client)


def _solve_all(
    robot: RobotLike, inputs: Any, wrenches: Any, cfg: _Settings, threads: int, progress: bool, client: Any
) -> BatchResult:
    """:func:`solve_batch` once its settings are gathered: on Dask, in one
    block, or block by block behind a progress bar."""
    if client is not None:
        return _solve_dask(robot, inputs, wrenches, client, cfg, progress)
    r = _robot(robot)
    na = len(r.actuators)
    q = _as_rows(inputs, na, "inputs")
    if not progress:
        w = None if wrenches is None else _as_rows(wrenches, 6, "wrenches")
        return _solve_block(r, q, w, cfg, threads)
    parts = iter_batches(
        r,
        q,
        wrenches,
        steps=cfg.steps,
        tol=cfg.tol,
        max_iter=cfg.max_iter,
        chunk_size=cfg.chunk_size,
        threads=threads,
        progress=True,
        stability=cfg.stability,
        shapes=cfg.shapes,
    )
    return BatchResult.concatenate(parts)


def _shapes_flag(shapes: Any) -> bool:
    if not isinstance(shapes, (bool, np.bool_)):
        raise TypeError(f"shapes must be True or False, not {type(shapes).__name__}")
    return bool(shapes)


def _dask_task(robot: RobotLike, inputs: FloatArray, wrenches: FloatArray | None, cfg: _Settings) -> BatchResult:
    # one chunk per task, solved on one thread of the worker
    return _solve_block(robot, inputs, wrenches, cfg, 1)


def _solve_dask(
    robot: RobotLike, inputs: Any, wrenches: Any, client: Any, cfg: _Settings, progress: bool
) -> BatchResult:
    na = len(_robot(robot).actuators)
    q = _as_rows(inputs, na, "inputs")
    w = None if wrenches is None else _as_rows(wrenches, 6, "wrenches")
    # the same chunks as the local path: warm-start chains restart at each
    futures = [
        client.submit(_dask_task, robot, q[a:b], None if w is None else w[a:b], cfg, pure=False)
        for a, b in _blocks(q.shape[0], cfg.chunk_size)
    ]
    if progress:
        as_completed: Any = require("distributed").as_completed
        bar = _progress_bar(q.shape[0])
        for f in as_completed(futures):
            bar.update(len(f.result()))
        bar.close()
    parts: list[BatchResult] = client.gather(futures)
    return BatchResult.concatenate(parts)


def fig6_square_robot(gravity: bool = True) -> Robot:
    """The paper's Fig. 6 square manipulator (Section V-B), 40 mm long.

    From the core's fixtures (``src/experiments.rs``), with the default turns
    reading. A module-level function, so it can also serve as the robot
    factory of a batch.

    Parameters
    ----------
    gravity : bool, optional
        Standing upright under gravity ``-z`` (default), or weightless.

    Returns
    -------
    Robot
        The EcoFlex 10 body (10 mm square, 40 mm) with its U-shaped TCA's two
        legs 3 mm off the neutral layer.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> robot = fig6_square_robot()
    >>> robot.body.length, len(robot.actuators), robot.body.gravity.tolist()     # [m], [m/s^2]
    (0.04, 2, [0.0, 0.0, -9.81])
    """
    return (
        _c.fixture_manipulator("fig6_square") if gravity else _c.fixture_manipulator("fig6_square", gravity=(0, 0, 0))
    )
