"""seahelm's local Dask cluster (seahelm._dask.local_cluster): one home for the sweeps', the
encounter studies' and DP level 3's, quiet when another cluster holds distributed's default
HTTP port (a fresh-clone suite: "Port 8787 is already in use" and an unclosed socket, two
warning lines beside an interrupted sweep's one line)."""

from __future__ import annotations

import socket
import warnings

import pytest

from seahelm._dask import local_cluster


def test_no_warning_when_the_default_http_port_is_taken():
    pytest.importorskip("distributed")
    holder = socket.socket()
    holder.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        holder.bind(("0.0.0.0", 8787))
        holder.listen()
    except OSError:  # (another process holds it already: the case under test all the same)
        pass
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            with local_cluster(1, purpose="a test") as cluster:
                assert len(cluster.workers) == 1
                assert cluster.scheduler.http_server.port != 8787
    finally:
        holder.close()
