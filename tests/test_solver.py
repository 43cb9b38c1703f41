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
    # one Newton iteration per solve is too few for a cold solve at 150 C
    # (it needs 3) and for every continuation step
    with pytest.raises(_core.ConvergenceError) as info:
        robot.solve([150.0, 150.0], max_iter=1)
    err = info.value
    assert err.residual > 0.0 and np.isfinite(err.residual)
    assert err.iterations >= 1
    assert err.evaluations >= err.iterations  # every iteration integrates
    assert err.reason == "iteration_limit"
    back = pickle.loads(pickle.dumps(err))
    assert type(back) is _core.ConvergenceError
    assert back.residual == err.residual
    assert (back.iterations, back.evaluations, back.reason) == (err.iterations, err.evaluations, err.reason)


def _interrupt_after(seconds: float) -> threading.Timer:
    timer = threading.Timer(seconds, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    return timer


@pytest.mark.parametrize("threads", [1, 2])
def test_ctrl_c_interrupts_a_long_batch(threads: int) -> None:
    robot = fig6_square_robot()
    n = 200_000  # minutes of work on one core
    t = np.linspace(40.0, 150.0, n)
    inputs = np.column_stack([t, t])
    timer = _interrupt_after(0.2)
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
