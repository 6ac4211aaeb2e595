"""What this process may use: memory, whatever limits it (the machine, a cgroup, ``ulimit``).

A guard that compares a batch's memory with the machine's physical memory accepts jobs that a
container's cgroup limit or an address-space limit (``ulimit -v``) will kill or fail late:
:func:`memory_limit` is the smallest of the machine's memory, what the cgroup still allows
(``memory.max`` − ``memory.current``, cgroup v2; ``memory.limit_in_bytes`` − usage, v1) and what
the address-space limit still allows (``RLIMIT_AS`` − the process's mapped size), with the name
of the one that binds.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import NamedTuple

from .errors import ParameterError

__all__ = ["MemoryLimit", "memory_limit", "WORK_BUDGET", "WORK_BUDGET_ENV", "WorkTooLarge",
           "check_work", "work_budget", "work_estimate"]

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


# ------------------------------------------------------------------------------------------
# work: what this machine can do in reasonable time
# ------------------------------------------------------------------------------------------
#: The most work one batch may take unless asked for more: integration steps × runs of one
#: call of :func:`seahelm.simulation.engine.simulate` (a manoeuvre's batch, one chunk of a
#: sweep). 1e9 is some 13 minutes of a KVLCC2 MMG ship on one core of a 2026 laptop
#: (:data:`TYPICAL_RATE`), 2 minutes of a Nomoto ship; an IMO check of a catalog ship at its
#: usual step takes some 1e5, a 1,000-sample Monte-Carlo check some 1e8. The environment
#: variable :data:`WORK_BUDGET_ENV` sets another budget.
WORK_BUDGET = 1e9

#: The environment variable that sets the work budget (steps × runs; ``inf`` for none).
WORK_BUDGET_ENV = "SEAHELM_WORK_BUDGET"

#: Steps × runs per second per core used for the time in a refusal's estimate: a KVLCC2 MMG
#: ship with its steering gear, RK4 (1.3e6 measured 2026-12-01 on a shared 2-core machine;
#: a Nomoto ship runs some 10 times faster, a ship in waves slower).
TYPICAL_RATE = 1.3e6


def work_budget() -> float:
    """The work budget [steps × runs]: :data:`WORK_BUDGET`, or the number in the environment
    variable :data:`WORK_BUDGET_ENV` (``inf`` for none).

    Raises
    ------
    ParameterError
        When the variable is set to something that is not a number > 0.
    """
    text = os.environ.get(WORK_BUDGET_ENV, "").strip()
    if not text:
        return WORK_BUDGET
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not value > 0:
        raise ParameterError(f"must be a number of steps x runs > 0 (or inf), got {text!r}",
                             field=WORK_BUDGET_ENV, value=text)
    return value


def _duration(seconds: float) -> str:
    if seconds < 120:
        return f"{seconds:.2g} s"
    if seconds < 7200:
        return f"{seconds / 60:.2g} min"
    if seconds < 2 * 86400:
        return f"{seconds / 3600:.2g} h"
    return f"{seconds / 86400:.2g} days"


def work_estimate(n_runs: int, n_steps: float, record_bytes: float | None = None) -> str:
    """A batch's work in words: "14 run(s) x 1e+08 steps = 1.4e+09 steps x runs (about 18 min
    at 1.3e+06 steps x runs/s per core; recording 0.11 GB)".

    Parameters
    ----------
    n_runs : int
        Runs of the batch.
    n_steps : float
        Integration steps of a run.
    record_bytes : float, optional
        The size of its recorded time series [B].
    """
    work = float(n_runs) * float(n_steps)
    memory = "" if record_bytes is None else f"; recording {record_bytes / 1e9:.3g} GB"
    return (f"{n_runs:,} run(s) x {float(n_steps):.3g} steps = {work:.3g} steps x runs (about "
            f"{_duration(work / TYPICAL_RATE)} at {TYPICAL_RATE:.2g} steps x runs/s per "
            f"core{memory})")


def check_work(n_runs: int, n_steps: float, *, field: str = "t_final",
               record_bytes: float | None = None, advice: str = "") -> None:
    """Refuse, before anything runs, a batch of more work than :func:`work_budget`.

    The one check of the work budget, called by the engine for every batch (so by every
    command and study) and by the scenario loader and the sweep before a batch is expanded.

    Parameters
    ----------
    n_runs : int
        Runs of the batch.
    n_steps : float
        Integration steps of a run (``t_final / dt``).
    field : str
        The parameter the refusal is about (``t_final``; a caller names its own).
    record_bytes : float, optional
        The recorded time series' size [B], shown in the estimate.
    advice : str
        What to change, in the caller's words (default: ``t_final``, ``dt`` or the runs).

    Raises
    ------
    WorkTooLarge
        A :class:`~seahelm.errors.ParameterError` with the estimate.
    """
    budget = work_budget()
    work = float(n_runs) * float(n_steps)
    if work <= budget:
        return
    over = (f"{work_estimate(n_runs, n_steps, record_bytes)} is more than the work budget of "
            f"{budget:.3g} steps x runs")
    anyway = f"(or set {WORK_BUDGET_ENV}={10 ** math.ceil(math.log10(work)):.0e} to run it anyway)"
    raise WorkTooLarge(
        f": {over}; {advice or 'a shorter `t_final`, a larger `dt` or fewer runs'} {anyway}",
        field=field, work=work, budget=budget, over=over, anyway=anyway)


class WorkTooLarge(ParameterError):
    """A batch of more work (steps × runs) than the budget (:func:`check_work`): ``work`` and
    ``budget`` [steps × runs]."""

    def __init__(self, message: str, *, field: str, work: float, budget: float,
                 over: str = "", anyway: str = "") -> None:
        super().__init__(message, field=field, value=work)
        self.work, self.budget = work, budget
        #: "... steps x runs (about ...) is more than the work budget of ..." and
        #: "(or set SEAHELM_WORK_BUDGET=... to run it anyway)", for a caller's own advice
        self.over, self.anyway = over, anyway
