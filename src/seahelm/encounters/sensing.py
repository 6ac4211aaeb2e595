"""What one vessel knows of the others: an AIS-like report (position, course and speed over
ground, heading) broadcast every ``update_interval``, received ``delay`` later, with noise.

A report belongs to the vessel that sends it (AIS is a broadcast: every receiver gets the same
message), so one view of every vessel serves every receiver. The report of interval ``j`` is
the sender's true state at ``j`` plus Gaussian noise drawn when it is sent (from the sensor's
``seed``); the view at interval ``k`` is the latest report sent at or before ``k - delay``
(nothing — NaN — before the first has arrived).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from ..errors import ParameterError

__all__ = ["AIS", "REPORT_FIELDS"]

#: What a report holds, in this order (the last axis of :class:`AISView` arrays).
REPORT_FIELDS = ("north", "east", "course", "speed", "heading")


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
        Seed of the noise (``numpy.random.default_rng``).
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

    def start(self, n_runs: int, controller_dt: float, t_final: float) -> "AISView":
        """The sensor's state for a batch of vessels (validated against the run).

        Parameters
        ----------
        n_runs : int
            Vessels (every encounter's).
        controller_dt : float
            Controller interval [s].
        t_final : float
            Duration of the run [s].

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
        return AISView(self, n_runs, every, int(round(lag)))


class AISView:
    """The reports in flight and the view they give (:meth:`AIS.start`)."""

    def __init__(self, sensor: AIS, n_runs: int, every: int, lag: int) -> None:
        self.sensor, self.every, self.lag = sensor, every, lag
        self.size = lag // every + 2  # reports kept (a ring)
        self.reports = np.full((self.size, n_runs, len(REPORT_FIELDS)), np.nan)
        self.sent = np.full(self.size, -1, dtype=np.int64)  # interval each slot was sent at
        self.rng = np.random.default_rng(sensor.seed)
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
                report += self.rng.standard_normal(report.shape) * sd
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
