"""The AIS view of the collision-avoidance environment (:mod:`seahelm.gym.encounter_env`): what
the agent -- and an avoiding target -- knows of the other vessel, through an
:class:`~seahelm.encounters.AIS` sensor (reports every ``update_interval``, received ``delay``
later, with noise).

:class:`~seahelm.encounters.sensing.AISView` keeps one clock for a whole batch, as
:meth:`Encounter.run <seahelm.encounters.Encounter.run>` runs every encounter from t = 0; the
sub-environments of a vector environment start their episodes at different times, so
:class:`EpisodeAIS` keeps the same ring of reports per sub-environment, on the episode's own
clock: the report of interval ``k`` of an episode is sent at ``k`` (every ``update_interval``,
the first at the episode's start), the view at ``k`` is the latest report sent at or before
``k - delay`` (NaN before the episode's first has arrived). An episode that starts clears its
sub-environment's reports (they were of the previous episode's target).

The noise is :func:`~seahelm.encounters.sensing.report_noise` of (the sensor's seed, the
episode's number, the vessel, the interval): episode ``j`` of sub-environment ``i`` of ``N`` is
number ``i + j N``, so the first episodes of a vector environment see the noise of
``Encounter.run`` of those encounters with that sensor, bit for bit, and every later episode
fresh noise; a ``reset`` with a seed numbers them from 0 again (:meth:`EpisodeAIS.renumber`:
the same seed, the same episodes).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..encounters.sensing import AIS, REPORT_FIELDS, report_noise, seed_key
from ..errors import ParameterError

__all__ = ["EpisodeAIS"]


class EpisodeAIS:
    """Per-sub-environment AIS reports of every vessel of N encounters (module docstring).

    Parameters
    ----------
    sensor : AIS
        The sensor (its ``delay`` a whole multiple of ``controller_dt``, shorter than an
        episode).
    num_envs, n_vessels : int
        Encounters and vessels per encounter; run ``e * n_vessels + v`` is vessel ``v`` of
        encounter ``e``.
    controller_dt, episode_seconds : float
        The interval between reports' chances [s] and an episode's length [s].

    Raises
    ------
    ParameterError
        Naming ``sensor`` when it is not an :class:`~seahelm.encounters.AIS`, else as
        :meth:`AIS.start <seahelm.encounters.AIS.start>` (``sensor.delay``).
    """

    def __init__(self, sensor: Any, num_envs: int, n_vessels: int, controller_dt: float,
                 episode_seconds: float) -> None:
        if not isinstance(sensor, AIS):
            raise ParameterError(f"must be a seahelm.encounters.AIS, got "
                                 f"{type(sensor).__name__}", field="sensor", value=sensor)
        batch = sensor.start(num_envs * n_vessels, controller_dt, episode_seconds,
                             n_vessels=n_vessels)  # (validated as the encounter's)
        self.sensor, self.every, self.lag = sensor, batch.every, batch.lag
        self.n, self.nv = num_envs, n_vessels
        n_runs = num_envs * n_vessels
        self.size = self.lag // self.every + 2  # reports kept a run (a ring)
        self.reports = np.full((self.size, n_runs, len(REPORT_FIELDS)), np.nan)
        self.sent = np.full((self.size, n_runs), -1, dtype=np.int64)
        self.view = np.full((n_runs, len(REPORT_FIELDS)), np.nan)
        self.key = seed_key(sensor.seed) if sensor.noisy else 0
        self.sd = np.array([sensor.position_noise, sensor.position_noise, sensor.course_noise,
                            sensor.speed_noise, sensor.heading_noise])
        self.vessel = np.arange(n_runs) % n_vessels
        self.k = np.zeros(n_runs, dtype=np.int64)  # each run's interval in its episode
        self.episodes = np.zeros(num_envs, dtype=np.int64)  # episodes begun per encounter
        self.number = np.zeros(n_runs, dtype=np.int64)  # each run's episode number

    def begin(self, sel: np.ndarray) -> None:
        """Start the episodes of encounters ``sel``: their reports cleared, their clocks at 0.

        Parameters
        ----------
        sel : ndarray of int
            The encounters starting.
        """
        runs = (sel[:, None] * self.nv + np.arange(self.nv)[None, :]).reshape(-1)
        self.reports[:, runs] = np.nan
        self.sent[:, runs] = -1
        self.view[runs] = np.nan
        self.k[runs] = 0
        self.number[runs] = np.repeat(sel + self.n * self.episodes[sel], self.nv)
        self.episodes[sel] += 1

    def renumber(self) -> None:
        """Number the episodes from 0 again, as when the sensor was made (a seeded
        ``reset``: the same seed and actions, the same reports, noise included)."""
        self.episodes[:] = 0

    def update(self, truth: np.ndarray, runs: np.ndarray | None = None) -> np.ndarray:
        """Send the reports due now from ``truth`` and return the view (every run's).

        Parameters
        ----------
        truth : ndarray (runs, 5)
            Every vessel's north, east [m], course [rad], speed [m/s], heading [rad] now.
        runs : ndarray of int, optional
            Update only these runs (the others keep their reports and view; default all).

        Returns
        -------
        ndarray (runs, 5)
            The view, by :data:`~seahelm.encounters.sensing.REPORT_FIELDS` (a view of the
            live array).
        """
        runs = np.arange(self.view.shape[0]) if runs is None else runs
        k = self.k[runs]
        send = runs[k % self.every == 0]
        if send.size:
            report = truth[send].copy()
            if self.sensor.noisy:  # (report_noise's interval broadcast per run)
                report += report_noise(self.key, self.number[send], self.vessel[send],
                                       self.k[send]) * self.sd
                report[:, 3] = np.abs(report[:, 3])
            slot = (self.k[send] // self.every) % self.size
            self.reports[slot, send] = report
            self.sent[slot, send] = self.k[send]
        due = k - self.lag
        ok = due >= 0
        j = due[ok] // self.every
        got = runs[ok]
        slot = j % self.size
        arrived = self.sent[slot, got] == j * self.every
        self.view[got[arrived]] = self.reports[slot[arrived], got[arrived]]
        return self.view

    def advance(self) -> None:
        """One interval on for every run."""
        self.k += 1
