"""The memory this process may use: the machine, its cgroup, its address-space limit."""

from __future__ import annotations

import subprocess
import sys
import textwrap

from seahelm import resources


def test_the_cgroup_limit_counts_what_is_in_use(tmp_path):
    (tmp_path / "memory.max").write_text("4000000000\n")
    (tmp_path / "memory.current").write_text("1000000000\n")
    assert resources._cgroup_room(tmp_path) == 3_000_000_000
    (tmp_path / "memory.max").write_text("max\n")  # v2 without a limit
    assert resources._cgroup_room(tmp_path) is None
    v1 = tmp_path / "v1"
    (v1 / "memory").mkdir(parents=True)
    (v1 / "memory" / "memory.limit_in_bytes").write_text(str(2 ** 63 - 4096))  # no limit
    assert resources._cgroup_room(v1) is None
    (v1 / "memory" / "memory.limit_in_bytes").write_text("2000000000")
    (v1 / "memory" / "memory.usage_in_bytes").write_text("500000000")
    assert resources._cgroup_room(v1) == 1_500_000_000


def test_the_smallest_limit_binds_and_is_named(monkeypatch):
    monkeypatch.setattr(resources, "_physical", lambda: 24_000_000_000)
    monkeypatch.setattr(resources, "_cgroup_room", lambda: 3_000_000_000)
    monkeypatch.setattr(resources, "_address_space_room", lambda: None)
    assert resources.memory_limit() == (3_000_000_000, "the cgroup's memory limit")
    monkeypatch.setattr(resources, "_address_space_room", lambda: 1_000_000_000)
    assert resources.memory_limit().source == "this process's address-space limit (ulimit -v)"
    monkeypatch.setattr(resources, "_physical", lambda: None)
    monkeypatch.setattr(resources, "_cgroup_room", lambda: None)
    monkeypatch.setattr(resources, "_address_space_room", lambda: None)
    assert resources.memory_limit() is None


def test_an_address_space_limit_refuses_a_batch_before_it_runs():
    # a process limited to its current size + 2 GB is refused a batch whose peak is ~3 GB,
    # before anything is allocated (it would fail with MemoryError after the run otherwise)
    code = textwrap.dedent("""
        import resource, time
        import numpy as np
        from seahelm.errors import ParameterError
        from seahelm.resources import _mapped_size
        from seahelm.simulation.engine import simulate
        from seahelm.ships import get_ship
        from seahelm.vessels.nomoto import NOMOTO2
        resource.setrlimit(resource.RLIMIT_AS, (_mapped_size() + 2_000_000_000,
                                                resource.RLIM_INFINITY))
        t0 = time.perf_counter()
        try:
            simulate(NOMOTO2, get_ship("mariner-nomoto2").params, np.zeros((10_000, 5)),
                     t_final=1000.0, dt=0.1, record_every=1)
        except ParameterError as exc:
            print("refused", round(time.perf_counter() - t0, 2), exc)
    """)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("refused"), out.stdout
    assert "this process's address-space limit (ulimit -v)" in out.stdout
    assert float(out.stdout.split()[1]) < 5.0  # at once, not after running
