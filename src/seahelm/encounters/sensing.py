"""What one vessel knows of the others: an AIS-like report (position, course and speed over
ground, heading) broadcast every ``update_interval``, received ``delay`` later, with noise.

A report belongs to the vessel that sends it (AIS is a broadcast: every receiver gets the same
message), so one view of every vessel serves every receiver. The report of interval ``j`` is
the sender's true state at ``j`` plus Gaussian noise drawn when it is sent; the view at
interval ``k`` is the latest report sent at or before ``k - delay`` (nothing — NaN — before the
first has arrived).

The noise of a report is a function of (the sensor's ``seed``, the encounter's index in its
study, the vessel, the interval, the field) alone -- a counter-based generator, not a stream
drawn in order -- so an encounter sees the same noise whatever batch or chunk it runs in and
wherever (a chunked or Dask run equals the whole batch bit for bit with noise on). The counter
is hashed by the SplitMix64 finaliser (Steele, Lea & Flood 2014, "Fast splittable
pseudorandom number generators", OOPSLA; Stafford's Mix13 constants),
chained over the five keys; two 53-bit uniforms make one normal deviate by the Box-Muller
transform (Box & Muller 1958, Ann. Math. Statist. 29(2)).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from ..errors import ParameterError

__all__ = ["AIS", "REPORT_FIELDS", "report_noise", "seed_key"]

#: What a report holds, in this order (the last axis of :class:`AISView` arrays).
REPORT_FIELDS = ("north", "east", "course", "speed", "heading")

_GOLDEN = np.uint64(0x9E3779B97F4A7C15)
_MIX1, _MIX2 = np.uint64(0xBF58476D1CE4E5B9), np.uint64(0x94D049BB133111EB)


def _mix(x: np.ndarray) -> np.ndarray:
    """SplitMix64's finaliser on uint64 arrays (module notes; arithmetic modulo 2**64)."""
    x = x ^ (x >> np.uint64(30))
    x = x * _MIX1
    x = x ^ (x >> np.uint64(27))
    x = x * _MIX2
    return x ^ (x >> np.uint64(31))


def _chain(h: np.ndarray, value: np.ndarray) -> np.ndarray:
    return _mix(h + _GOLDEN * (np.asarray(value, dtype=np.uint64) + np.uint64(1)))


def seed_key(seed: int | None) -> int:
    """The 64-bit key of a sensor seed.

    Parameters
    ----------
    seed : int or None
        The sensor's seed (None: a fresh random key).

    Returns
    -------
    int
    """
    return int(np.random.SeedSequence(seed).generate_state(1, dtype=np.uint64)[0])


def report_noise(key: int, encounter: np.ndarray, vessel: np.ndarray, interval: int,
                 n_fields: int = len(REPORT_FIELDS)) -> np.ndarray:
    """Standard normal deviates of reports, one per (run, field), from their counters alone
    (module notes).

    Parameters
    ----------
    key : int
        The sensor's key (:func:`seed_key` of its seed).
    encounter, vessel : ndarray of int (runs,)
        Each run's encounter index in its study and vessel index.
    interval : int
        The controller interval the report is sent at.
    n_fields : int
        Fields per report.

    Returns
    -------
    ndarray (runs, n_fields)
    """
    h = np.full(np.shape(encounter), key, dtype=np.uint64)
    h = _chain(_chain(_chain(h, encounter), vessel), np.full(h.shape, interval))
    pair = np.arange(2 * n_fields, dtype=np.uint64)
    bits = _chain(h[:, None], pair[None, :]) >> np.uint64(11)  # (runs, 2 n_fields), 53 bits
    u = bits.astype(np.float64) * 2.0 ** -53
    u1, u2 = 1.0 - u[:, 0::2], u[:, 1::2]  # u1 in (0, 1]
    return np.sqrt(-2.0 * np.log(u1)) * np.cos(2.0 * np.pi * u2)


@dataclasses.dataclass(frozen=True, kw_only=True)
class AIS:
    """An AIS-like sensor: what each vessel's controller sees of the others.

    Attributes
    ----------
    update_interval : float
        Time between reports [s] (default 0: every controller interval); rounded up to whole
        controller intervals.
    delay : float
        Time from sending to receiving [s] (default 0), a whole multiple of the controller
        interval, shorter than the run.
    position_noise : float
        Standard deviation of the reported north and east [m] (default 0).
    course_noise, heading_noise : float
        Standard deviation of the reported course over ground and heading [rad] (default 0).
    speed_noise : float
        Standard deviation of the reported speed over ground [m/s] (default 0).
    seed : int, optional
        Seed of the noise (module notes; None: a fresh one per run, or per chunked study).
    """

    update_interval: float = 0.0
    delay: float = 0.0
    position_noise: float = 0.0
    course_noise: float = 0.0
    speed_noise: float = 0.0
    heading_noise: float = 0.0
    seed: int | None = None

    def __post_init__(self) -> None:
        for name, unit in (("update_interval", "s"), ("delay", "s"), ("position_noise", "m"),
                           ("course_noise", "rad"), ("speed_noise", "m/s"),
                           ("heading_noise", "rad")):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v >= 0):
                raise ParameterError(f"must be >= 0 [{unit}], got {v!r}", field=f"sensor.{name}",
                                     unit=unit, value=v)

    @property
    def noisy(self) -> bool:
        return any((self.position_noise, self.course_noise, self.speed_noise,
                    self.heading_noise))

    def start(self, n_runs: int, controller_dt: float, t_final: float, *, n_vessels: int = 1,
              first_encounter: int = 0) -> "AISView":
        """The sensor's state for a batch of vessels (validated against the run).

        Parameters
        ----------
        n_runs : int
            Vessels (every encounter's), flat: run ``e * n_vessels + v`` is vessel ``v`` of
            encounter ``e``.
        controller_dt : float
            Controller interval [s].
        t_final : float
            Duration of the run [s].
        n_vessels : int, optional
            Vessels per encounter (default 1).
        first_encounter : int, optional
            The index of the batch's first encounter in its study (default 0): a chunk's
            encounters draw the noise they draw in the whole batch.

        Returns
        -------
        AISView
        """
        every = max(1, int(math.ceil(self.update_interval / controller_dt - 1e-9)))
        lag = self.delay / controller_dt
        if abs(lag - round(lag)) > 1e-9:
            raise ParameterError(f"must be a whole multiple of the controller interval "
                                 f"({controller_dt:g} s) [s], got {self.delay!r}",
                                 field="sensor.delay", unit="s", value=self.delay)
        if self.delay >= t_final:
            raise ParameterError(f"must be shorter than the run (t_final = {t_final:g} s) "
                                 f"[s], got {self.delay!r}", field="sensor.delay", unit="s",
                                 value=self.delay)
        return AISView(self, n_runs, every, int(round(lag)), n_vessels=n_vessels,
                       first_encounter=first_encounter)


class AISView:
    """The reports in flight and the view they give (:meth:`AIS.start`)."""

    def __init__(self, sensor: AIS, n_runs: int, every: int, lag: int, *, n_vessels: int = 1,
                 first_encounter: int = 0) -> None:
        self.sensor, self.every, self.lag = sensor, every, lag
        self.size = lag // every + 2  # reports kept (a ring)
        self.reports = np.full((self.size, n_runs, len(REPORT_FIELDS)), np.nan)
        self.sent = np.full(self.size, -1, dtype=np.int64)  # interval each slot was sent at
        self.key = seed_key(sensor.seed) if sensor.noisy else 0
        runs = np.arange(n_runs)
        self.encounter = first_encounter + runs // n_vessels
        self.vessel = runs % n_vessels
        self.view = np.full((n_runs, len(REPORT_FIELDS)), np.nan)

    def update(self, k: int, truth: np.ndarray) -> np.ndarray:
        """Send the report of interval ``k`` (if one is due) from ``truth`` (runs, 5), and
        return the view every receiver has at ``k`` (runs, 5) (NaN before the first report
        arrives)."""
        if k % self.every == 0:
            report = truth.copy()
            s = self.sensor
            if s.noisy:
                sd = np.array([s.position_noise, s.position_noise, s.course_noise,
                               s.speed_noise, s.heading_noise])
                report += report_noise(self.key, self.encounter, self.vessel, k) * sd
                report[:, 3] = np.abs(report[:, 3])
            slot = (k // self.every) % self.size
            self.reports[slot] = report
            self.sent[slot] = k
        due = k - self.lag
        if due >= 0:
            j = due // self.every
            slot = j % self.size
            if self.sent[slot] == j * self.every:
                self.view = self.reports[slot]
        return self.view
