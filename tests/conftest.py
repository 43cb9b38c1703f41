"""Shared pytest fixtures.

``dask_client``: one small local Dask cluster (two single-threaded process
workers, as a user's laptop cluster would run) for every Dask test of the
session: starting a cluster costs seconds, the tests using it milliseconds.
The tests that use it carry ``@pytest.mark.xdist_group("dask")`` so that,
under ``pytest -n 2 --dist loadgroup`` (``make test``), they run in one pytest
worker and share the one cluster.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import pytest


@pytest.fixture(scope="session")
def dask_client() -> Iterator[Any]:
    distributed = pytest.importorskip("distributed")
    # dashboard_address=":0": the scheduler's HTTP server takes a free port, so
    # a dashboard already on the default port 8787 does not stop the cluster.
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster:
        with distributed.Client(cluster) as client:
            yield client
