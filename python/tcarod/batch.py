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
    """Yield the results of consecutive blocks of rows, ``block_chunks``
    chunks per block (default: 4 per thread), holding only one block at a
    time. ``inputs`` (and ``wrenches``) may be arrays, or iterables of
    ``(m, n_actuators)`` arrays (e.g. a generator making a huge sweep on the
    fly); then each yielded block corresponds to one given array.
    ``progress=True`` shows a tqdm bar (rows). The other arguments as for
    :func:`solve_batch`. Integer arguments accept any integer type (NumPy's
    included): ``TypeError`` for non-integers, ``ValueError`` naming the
    argument and its range outside ``chunk_size`` 1..10,000,000, ``threads``
    0..1024, ``block_chunks`` 1..1,000,000."""
    # integer-like arguments (NumPy integers included) become Python ints before
    # any arithmetic, so a uint8 cannot wrap or overflow in the block size
    chunk_size = V.integer("chunk_size", chunk_size, 1, MAX_CHUNK_SIZE)
    threads = V.integer("threads", threads, 0, MAX_THREADS)
    if block_chunks is not None:
        block_chunks = V.integer("block_chunks", block_chunks, 1, MAX_BLOCK_CHUNKS)
    cfg = _Settings(steps, tol, max_iter, chunk_size, stability, _shapes_flag(shapes))
    nthreads = threads if threads > 0 else _core.default_threads()
    block = chunk_size * (block_chunks if block_chunks is not None else 4 * nthreads)
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
    """Solve every row of ``inputs`` (``(n, n_actuators)``; temperatures [C]
    for TCAs) with optional tip ``wrenches`` (``(n, 6)``: force [N], moment
    [N m], world frame) and return the stacked results.

    ``threads``: worker threads (0: all cores). ``progress``: tqdm bar.
    ``client``: a ``dask.distributed.Client``; the chunks are then spread over
    its workers (install the ``dask`` extra) with the same results as the
    local path. The robot pickles, so it is shipped to the workers as it is;
    ``robot`` may also be a zero-argument callable returning the robot, which
    each worker then calls to build its own.

    ``stability``: ``"report"`` (the default) gives every converged row its
    stability verdict (``stable``, ``margin``), as ``Robot.solve`` does, so a
    batch never hands back an unstable equilibrium without saying so: a
    sweep through buckling is exactly where the warm-started chain may
    follow a shape the robot cannot hold. It costs one tangent integration
    per row, about as much as a warm solve (a sweep takes about twice as
    long); ``"off"`` skips it (``stable`` and ``margin`` are then ``None``)
    for hot loops that do not use it. ``"require"`` and ``"continue"`` are
    not offered for batches: filter on ``stable``, or re-solve the unstable
    rows with ``Robot.solve(..., stability="continue")``.

    ``shapes=True`` keeps every row's centre line (``BatchResult.arc_length``
    ``(nodes,)`` [m], ``positions`` ``(n, nodes, 3)`` [m], NaN where a solve
    did not converge), rebuilt by one more IVP per converged row (counted in
    ``evaluations``), at ``24 * nodes`` bytes per row (2.4 kB at 100 steps):
    sweeps of millions of rows keep tips only (the default) or stream.

    Invalid inputs raise ``ValueError`` naming the row; a solve that does not
    converge gives NaN pose and ``converged = False``.

    Examples
    --------
    >>> import numpy as np
    >>> from tcarod.batch import fig6_square_robot, solve_batch
    >>> temps = np.linspace(25.0, 60.0, 5)
    >>> res = solve_batch(fig6_square_robot(), np.column_stack([temps, 25.0 + 0 * temps]), shapes=True)
    >>> res.positions.shape == (5, len(res.arc_length), 3)
    True
    >>> bool(np.array_equal(res.positions[:, -1], res.tip_positions))
    True
    """
    cfg = _Settings(steps, tol, max_iter, chunk_size, stability, _shapes_flag(shapes))
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
        steps=steps,
        tol=tol,
        max_iter=max_iter,
        chunk_size=chunk_size,
        threads=threads,
        progress=True,
        stability=stability,
        shapes=shapes,
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
    """The paper's Fig. 6 square manipulator (Section V-B) with the default
    turns reading, from the core's fixtures (``src/experiments.rs``), standing
    upright (gravity ``-z``) if ``gravity``. A module-level function, so it
    can also serve as the robot factory of a batch."""
    return (
        _c.fixture_manipulator("fig6_square") if gravity else _c.fixture_manipulator("fig6_square", gravity=(0, 0, 0))
    )
