"""One home for the local Dask cluster seahelm starts (sweeps, encounter studies, DP level 3).

The workers are processes with one thread each, on 127.0.0.1, their logs at ERROR. No
dashboard; the scheduler's HTTP server (distributed starts one whatever the dashboard) on a
port the system picks: on its default, 8787, a second cluster on the machine -- another
command, a test beside it -- made distributed warn "Port 8787 is already in use" (and leave an
unclosed socket), two warning lines beside a command's output.
"""

from __future__ import annotations

import logging
from typing import Any

from ._optional import optional_import

__all__ = ["local_cluster"]


def local_cluster(workers: int, *, purpose: str) -> Any:
    """A ``distributed.LocalCluster`` of ``workers`` single-threaded worker processes.

    Parameters
    ----------
    workers : int
        Worker processes.
    purpose : str
        What it is for (named in the error if distributed is not installed).

    Returns
    -------
    distributed.LocalCluster
        Running; close it (or use it as a context manager).
    """
    distributed = optional_import("distributed", extra="dask", purpose=purpose)
    return distributed.LocalCluster(
        n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1",
        dashboard_address=None, scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
        silence_logs=logging.ERROR)
