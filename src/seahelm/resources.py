"""What this process may use: memory, whatever limits it (the machine, a cgroup, ``ulimit``).

A guard that compares a batch's memory with the machine's physical memory accepts jobs that a
container's cgroup limit or an address-space limit (``ulimit -v``) will kill or fail late:
:func:`memory_limit` is the smallest of the machine's memory, what the cgroup still allows
(``memory.max`` − ``memory.current``, cgroup v2; ``memory.limit_in_bytes`` − usage, v1) and what
the address-space limit still allows (``RLIMIT_AS`` − the process's mapped size), with the name
of the one that binds.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import NamedTuple

__all__ = ["MemoryLimit", "memory_limit"]

_CGROUP = Path("/sys/fs/cgroup")


class MemoryLimit(NamedTuple):
    """The memory this process may still use [bytes], and what sets it."""

    bytes: int
    source: str


def _read_int(path: Path) -> int | None:
    try:
        text = path.read_text().strip()
    except OSError:
        return None
    return int(text) if text.isdigit() else None  # ("max": no limit)


def _physical() -> int | None:
    try:
        return int(os.sysconf("SC_PHYS_PAGES")) * int(os.sysconf("SC_PAGE_SIZE"))
    except (AttributeError, ValueError, OSError):  # pragma: no cover - not POSIX
        return None


def _cgroup_room(root: Path = _CGROUP) -> int | None:
    limit = _read_int(root / "memory.max")  # v2
    if limit is not None:
        used = _read_int(root / "memory.current") or 0
        return max(limit - used, 0)
    limit = _read_int(root / "memory" / "memory.limit_in_bytes")  # v1 (2**63-ish: none)
    if limit is not None and limit < 1 << 60:
        used = _read_int(root / "memory" / "memory.usage_in_bytes") or 0
        return max(limit - used, 0)
    return None


def _mapped_size() -> int:
    """The process's mapped virtual memory [bytes] (VmSize; 0 where /proc does not say)."""
    try:
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("VmSize:"):
                return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    return 0


def _address_space_room() -> int | None:
    try:
        import resource
    except ImportError:  # pragma: no cover - not POSIX
        return None
    soft, _ = resource.getrlimit(resource.RLIMIT_AS)
    if soft == resource.RLIM_INFINITY or soft < 0:
        return None
    return max(int(soft) - _mapped_size(), 0)


def memory_limit() -> MemoryLimit | None:
    """The memory this process may still use, and what limits it (None if nothing says).

    Returns
    -------
    MemoryLimit or None
        ``bytes``: the smallest of the machine's physical memory, the room its cgroup leaves
        and the room its address-space limit leaves; ``source``: which one, in words
        (``"this machine's memory"``, ``"the cgroup's memory limit"``,
        ``"this process's address-space limit (ulimit -v)"``).
    """
    found = [MemoryLimit(v, s) for v, s in (
        (_physical(), "this machine's memory"),
        (_cgroup_room(), "the cgroup's memory limit"),
        (_address_space_room(), "this process's address-space limit (ulimit -v)"))
        if v is not None]
    return min(found, key=lambda m: m.bytes) if found else None
