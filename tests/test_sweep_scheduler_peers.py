"""A --scheduler address that is not a dask scheduler is named as such within --timeout
(issue 33, part 3): a silent peer (an HTTP server waits for a request) and a peer that sends
garbage. The peers listen on the loopback only, accept a bounded number of connections and stop
with the test."""

from __future__ import annotations

import socket
import threading
import time

import pytest

pytest.importorskip("distributed")

from seahelm.errors import ParameterError  # noqa: E402
from seahelm.sweep import run_sweep  # noqa: E402

SCENARIO = """
title = "peer"
[vessel]
ship = "mariner-nomoto2"
[simulation]
t_final = 10.0
dt = 0.1
[batch.grid]
"vessel.params.gain" = [0.1, 0.2]
"""


class Peer:
    """A loopback listener that accepts up to 4 connections and answers with ``reply``."""

    def __init__(self, reply: bytes) -> None:
        self.sock = socket.socket()
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(4)
        self.sock.settimeout(0.2)
        self.reply, self.conns, self.stop = reply, [], threading.Event()
        self.thread = threading.Thread(target=self._serve, daemon=True)
        self.thread.start()

    @property
    def address(self) -> str:
        return f"tcp://127.0.0.1:{self.sock.getsockname()[1]}"

    def _serve(self) -> None:
        deadline = time.monotonic() + 60.0  # it stops by itself
        while not self.stop.is_set() and time.monotonic() < deadline and len(self.conns) < 4:
            try:
                conn, _ = self.sock.accept()
            except OSError:
                continue
            self.conns.append(conn)
            if self.reply:
                conn.sendall(self.reply)

    def close(self) -> None:
        self.stop.set()
        self.thread.join(2.0)
        for conn in self.conns:
            conn.close()
        self.sock.close()


@pytest.mark.parametrize(("reply", "match"), [
    (b"", "did not answer as a dask scheduler within 2 s"),
    (b"\xff" * 64 + b"HTTP/1.0 400 Bad Request\r\n\r\n",
     "is not a dask scheduler: its answer is not dask's protocol"),
])
def test_a_peer_that_is_not_a_scheduler_is_named_within_the_timeout(tmp_path, reply, match):
    scenario = tmp_path / "s.toml"
    scenario.write_text(SCENARIO)
    peer = Peer(reply)
    try:
        t0 = time.monotonic()
        with pytest.raises(ParameterError, match=match):
            run_sweep(scenario, tmp_path / "s.zarr", scheduler=peer.address, timeout=2.0)
        assert time.monotonic() - t0 < 10.0
    finally:
        peer.close()
    assert not (tmp_path / "s.zarr").exists()
