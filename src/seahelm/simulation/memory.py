"""The memory guard: recordings that cannot fit are refused before anything is allocated."""

from __future__ import annotations

from ..errors import ParameterError
from ..resources import memory_limit

__all__ = ["RECORD_PEAK_FACTOR", "ASK_ABOVE", "RECORD_MEMORY_SHARE", "physical_memory",
           "RecordingTooLarge", "check_record_memory"]

#: The engine's peak memory per byte of recorded time series: the recordings themselves, the
#: results Dataset made from them and the NetCDF file built in memory before it is written
#: (:func:`seahelm.results.netcdf_bytes`). Measured (tracemalloc, 2,000 and 500 runs of
#: Nomoto-2 + PID, 0.3 GB of recordings, 2026-11-27): simulate 0.74x the estimate below (it
#: counts every channel at 8 B), to_xarray 1.47-1.63x, simulate then to_netcdf 2.33x in all;
#: 2.5 leaves room for HDF5's own buffers.
RECORD_PEAK_FACTOR = 2.5

#: A peak below this [bytes] is not checked against the memory limit (every limit that matters
#: is larger; asking the OS costs more than a short run).
ASK_ABOVE = 1 << 26


#: Share of the memory this process may use (:func:`seahelm.resources.memory_limit`) that the
#: engine's peak may take.
RECORD_MEMORY_SHARE = 0.8


def physical_memory() -> int | None:
    """The memory this process may use [bytes]: the smallest of the machine's memory, its
    cgroup's room and its address-space room (:func:`seahelm.resources.memory_limit`; None
    where the OS does not say)."""
    limit = memory_limit()
    return None if limit is None else limit.bytes


class RecordingTooLarge(ParameterError):
    """The recorded time series would not fit in memory (raised before anything is allocated).

    ``need`` and ``total`` [B] are the recording's size and the memory this process may use,
    ``source`` what limits it, so a caller can name its own options in the advice (a
    manoeuvre's approach speed, say).
    """

    def __init__(self, message: str, *, need: int, total: int, source: str = "") -> None:
        super().__init__(message, field="record_every", unit="B", value=need)
        self.need, self.total, self.source = need, total, source

    def size_text(self) -> str:
        """"62.3 GB (a peak of about 2.5x that), more than 80% of the 25.3 GB this process
        may use (this machine's memory)"."""
        return (f"{self.need / 1e9:.3g} GB (a peak of about {RECORD_PEAK_FACTOR:g}x that), "
                f"more than {RECORD_MEMORY_SHARE:.0%} of the {self.total / 1e9:.3g} GB this "
                f"process may use ({self.source})")


def check_record_memory(n_runs: int, n_rec: int, channels: int) -> None:
    """Refuse, before anything is allocated, recordings that cannot fit in memory.

    Parameters
    ----------
    n_runs, n_rec, channels : int
        Runs, records per run and recorded channels (states, outputs, commands, references,
        disturbances).

    Raises
    ------
    RecordingTooLarge
        A :class:`~seahelm.errors.ParameterError`: the engine's peak (:data:`RECORD_PEAK_FACTOR`
        × the recorded arrays at 8 B a value) would take more than :data:`RECORD_MEMORY_SHARE`
        of the memory this process may use — the smallest of the machine's memory, its cgroup's
        limit and its address-space limit (:func:`seahelm.resources.memory_limit`).
    """
    need = 8 * n_runs * n_rec * channels
    if RECORD_PEAK_FACTOR * need <= ASK_ABOVE:  # (asking the OS takes ~60 us)
        return
    limit = memory_limit()
    if limit is None or RECORD_PEAK_FACTOR * need <= RECORD_MEMORY_SHARE * limit.bytes:
        return
    err = RecordingTooLarge("", need=need, total=limit.bytes, source=limit.source)
    raise RecordingTooLarge(
        f": the recorded time series would need {err.size_text()} ({n_runs:,} run(s) x "
        f"{n_rec:,} records x {channels} channels x 8 B); record fewer samples (a larger "
        "record_every), fewer runs or a shorter t_final", need=need, total=limit.bytes,
        source=limit.source)
