"""A 10,000-solve sweep on a Dask cluster with 2 process workers equals the
serial result bit for bit (the chunks, and so the warm-start chains, are the
same). Prints the timings and the verdict; the test suite runs the same check
on 1,000 rows
(tests/test_pickle.py::test_batch_on_dask_process_workers_equals_serial_bit_for_bit).

    python benches/dask_batch.py [rows]
"""

from __future__ import annotations

import os
import sys
import time

import numpy as np
from distributed import Client, LocalCluster

from tcarod.batch import fig6_square_robot, solve_batch


def main() -> int:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 10_000
    robot = fig6_square_robot()
    t = np.linspace(25.0, 160.0, n)
    q = np.column_stack([t, t[::-1]])
    t0 = time.perf_counter()
    serial = solve_batch(robot, q, chunk_size=256, threads=1)
    t1 = time.perf_counter()
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            t2 = time.perf_counter()
            remote = solve_batch(robot, q, chunk_size=256, client=client)
            t3 = time.perf_counter()
    same = remote == serial
    print(f"rows {n}, converged {int(serial.converged.sum())}, load {os.getloadavg()[0]:.2f}")
    print(f"serial (1 thread) {t1 - t0:.2f} s; dask 2 process workers {t3 - t2:.2f} s (cluster start excluded)")
    print(f"bit-for-bit equal: {same}")
    return 0 if same else 1


if __name__ == "__main__":
    raise SystemExit(main())
