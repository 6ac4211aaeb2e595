"""What an encounter run gives: tracks, the own ship's pair metrics, outcomes and verdicts.

:class:`Recorder` follows the run at every controller interval (ranges, CPA, domain distance
and the course alterations the verdicts need are reduced as they come, so memory does not grow
with the horizon) and keeps the tracks every ``record_every`` intervals; :class:`EncounterResult`
holds them.

Verdicts (:class:`VerdictRules`), per pair (own ship, target j), from each vessel's own view at
the start (its :class:`~seahelm.encounters.geometry.Situation`):

- a **give-way** vessel *acted* if it altered course from its route's heading by more than
  ``action`` before the pair's closest point of approach; ``action_time`` and
  ``action_range`` say when (Rule 16: "take early and substantial action"), the largest
  alteration ``alteration`` how much; *substantial* if it reached ``substantial`` (Rule 8(b):
  "large enough to be readily apparent"; 30° by default, a common reading, stated as a
  parameter) and *early* if it started beyond ``early_range``;
- a **stand-on** vessel *kept course* if its heading stayed within ``keep`` of its route's
  heading until the pair's closest point of approach (Rule 17(a)(i));
- a vessel stand-on in a **crossing** situation (the other on its port side at the start:
  :attr:`~seahelm.encounters.geometry.Situation.CROSSING_STAND_ON`) *altered to port* if it
  turned to port of its route's heading by more than ``action`` before the pair's closest
  point of approach while the other was on its port side (Rule 17(c): such a vessel "shall,
  if the circumstances of the case admit, not alter course to port for a vessel on her own
  port side"); ``port_alteration`` is that largest turn to port [rad]. A turn to port once
  the other has drawn to the starboard side, and a vessel overtaken, head-on or giving way,
  are not counted.

A collision is a least range below the sum of half the two lengths (circles; coarse); a near
miss, the target inside the own ship's domain without a collision.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from ..errors import ParameterError
from .geometry import (GIVE_WAY, STAND_ON, Situation, classify_bearings, cpa_tcpa,
                       relative_bearing, velocity, wrap_pi)

__all__ = ["VerdictRules", "EncounterResult", "wilson_interval", "is_encounter_dataset",
           "DATASET_FORMAT"]

#: The ``format`` attribute of an encounter result file (``encounters.nc``).
DATASET_FORMAT = "seahelm-encounters-1"


@dataclasses.dataclass(frozen=True, kw_only=True)
class VerdictRules:
    """Thresholds of the verdicts (module notes) [rad, m].

    Attributes
    ----------
    action : float
        A course alteration larger than this is an action (default 5°).
    substantial : float
        Rule 8(b) "readily apparent" (default 30°).
    early_range : float
        An action started beyond this range is early (default 3704 m, 2 nmi).
    keep : float
        A stand-on vessel within this of its route's heading kept course (default 5°).
    """

    action: float = math.radians(5.0)
    substantial: float = math.radians(30.0)
    early_range: float = 3704.0
    keep: float = math.radians(5.0)

    def __post_init__(self) -> None:
        for name, unit in (("action", "rad"), ("substantial", "rad"), ("early_range", "m"),
                           ("keep", "rad")):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise ParameterError(f"must be > 0 [{unit}], got {v!r}",
                                     field=f"verdicts.{name}", unit=unit, value=v)


def wilson_interval(k: Any, n: Any, z: float = 1.959963984540054) -> tuple[np.ndarray, np.ndarray]:
    """Wilson score interval of a proportion k/n (Wilson 1927, J. Am. Stat. Assoc. 22).

    Parameters
    ----------
    k, n : array_like
        Successes and trials.
    z : float
        Normal quantile (default: 95 % two-sided).

    Returns
    -------
    (low, high) : ndarrays
    """
    k, n = np.asarray(k, dtype=float), np.asarray(n, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        p = k / n
        centre = (p + z * z / (2 * n)) / (1 + z * z / n)
        half = z * np.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return np.clip(centre - half, 0.0, 1.0), np.clip(centre + half, 0.0, 1.0)


class Recorder:
    """Follows an encounter run (module notes)."""

    TRACK = ("north", "east", "course", "speed", "heading", "yaw_rate", "desired_heading",
             "route_heading", "rudder_command")

    def __init__(self, encounter: Any, n_intervals: int) -> None:
        self.enc = encounter
        ne, nv = encounter.n_encounters, encounter.n_vessels
        every = encounter.record_every
        self.ks = sorted(set(range(0, n_intervals + 1, every)) | {n_intervals})
        self.slot = {k: m for m, k in enumerate(self.ks)}
        nt, nrec = nv - 1, len(self.ks)
        self.time = np.full(nrec, np.nan)
        self.tracks = np.full((len(self.TRACK), ne, nv, nrec), np.nan)
        self.pair = {name: np.full((ne, nt, nrec), np.nan)
                     for name in ("range", "dcpa", "tcpa", "domain_distance")}
        self.pair["situation"] = np.zeros((ne, nt, nrec), dtype=np.int8)
        inf = np.full((ne, nt), np.inf)
        self.min_range, self.min_domain = inf.copy(), inf.copy()
        self.t_min = np.zeros((ne, nt))
        self.situation0 = None
        self.role0 = None  # (ne, nt, 2): situation of own, of target, at the start
        self.alter = np.zeros((ne, nt, 2))       # largest alteration before CPA (own, target)
        self.port = np.zeros((ne, nt, 2))        # largest alteration to port before CPA
        self.action_time = np.full((ne, nt, 2), np.nan)
        self.action_range = np.full((ne, nt, 2), np.nan)
        self.before_cpa = np.ones((ne, nt), dtype=bool)

    def add(self, k: int, time: float, truth: np.ndarray, desired: np.ndarray,
            route: np.ndarray, rudder: np.ndarray) -> None:
        enc = self.enc
        ne, nv = enc.n_encounters, enc.n_vessels
        t = truth.reshape(ne, nv, 6)
        if nv > 1:
            self._pairs(time, t, route)
        m = self.slot.get(k)
        if m is None:
            return
        self.time[m] = time
        for j, arr in enumerate((t[..., 0], t[..., 1], t[..., 2], t[..., 3], t[..., 4],
                                 t[..., 5], desired, route, rudder.reshape(ne, nv))):
            self.tracks[j, :, :, m] = arr
        if nv > 1:
            for name, arr in self._last.items():
                self.pair[name][:, :, m] = arr

    def _pairs(self, time: float, t: np.ndarray, route: np.ndarray) -> None:
        enc = self.enc
        own, tgt = t[:, :1], t[:, 1:]
        p_o, p_t = own[..., 0:2], tgt[..., 0:2]
        dcpa, tcpa = cpa_tcpa(p_o, velocity(own[..., 2], own[..., 3]), p_t,
                              velocity(tgt[..., 2], tgt[..., 3]))
        rng = np.hypot(p_t[..., 0] - p_o[..., 0], p_t[..., 1] - p_o[..., 1])
        dom = enc.domain.distance(p_o, own[..., 4], enc.lengths[0], p_t)
        # the target's bearing from the own bow, and the own ship's from the target's
        beta = relative_bearing(p_o, own[..., 4], p_t)
        alpha = relative_bearing(p_t, tgt[..., 4], p_o)
        sit = classify_bearings(beta, alpha, enc.sectors)
        if self.situation0 is None:
            sit_t = classify_bearings(alpha, beta, enc.sectors)
            self.situation0 = sit.copy()
            self.role0 = np.stack([sit, sit_t], axis=-1)
        closer = rng < self.min_range
        self.min_range = np.where(closer, rng, self.min_range)
        self.t_min = np.where(closer, time, self.t_min)
        self.min_domain = np.minimum(self.min_domain, dom)
        # course alterations before the pair's CPA (own: index 0, target: 1)
        self.before_cpa &= tcpa > 0
        signed = wrap_pi(np.stack([np.broadcast_to(own[..., 4] - route[:, :1], rng.shape),
                                   tgt[..., 4] - route[:, 1:]], axis=-1))
        dev = np.abs(signed)
        live = self.before_cpa[..., None]
        self.alter = np.where(live, np.maximum(self.alter, dev), self.alter)
        # (headings clockwise from north: a turn to port is a heading below the route's)
        # Rule 17(c) counts a turn to port only "for a vessel on her own port side": while the
        # other is on the port side (relative bearing beyond 180°) at that interval
        port_side = np.stack([beta > math.pi, alpha > math.pi], axis=-1)
        self.port = np.where(live & port_side, np.maximum(self.port, -signed), self.port)
        first = live & np.isnan(self.action_time) & (dev > enc.verdict_rules.action)
        self.action_time = np.where(first, time, self.action_time)
        self.action_range = np.where(first, rng[..., None], self.action_range)
        self._last = {"range": rng, "dcpa": dcpa, "tcpa": tcpa, "domain_distance": dom,
                      "situation": sit}

    def finish(self, status: np.ndarray) -> "EncounterResult":
        return EncounterResult(self, status)


class EncounterResult:
    """The outcome of :meth:`Encounter.run` (every array leads with the encounter axis).

    Attributes
    ----------
    time : ndarray (records,)
        Times of the recorded tracks [s].
    tracks : dict name -> ndarray (encounters, vessels, records)
        ``north``, ``east`` [m], ``course`` (over ground), ``heading``, ``desired_heading``,
        ``route_heading`` [rad], ``speed`` (over ground) [m/s], ``yaw_rate`` [rad/s],
        ``rudder_command`` [rad].
    pair : dict name -> ndarray (encounters, targets, records)
        Own ship vs each target: ``range``, ``dcpa`` [m], ``tcpa`` [s], ``domain_distance``
        (< 1: inside the own ship's domain) and ``situation`` (own view, codes).
    min_range, t_min_range, min_domain_distance : ndarray (encounters, targets)
    situation : ndarray (encounters, targets)
        The own ship's situation at the start (:class:`Situation` codes).
    collision, near_miss : ndarray of bool (encounters, targets)
    verdicts : dict name -> ndarray (encounters, targets, 2)
        For the own ship (index 0) and the target (index 1) of each pair: ``role`` (1 give-way,
        -1 stand-on, 0 neither), ``alteration`` [rad], ``action_time`` [s], ``action_range``
        [m], ``acted``, ``substantial``, ``early`` (give-way), ``kept_course`` (stand-on),
        ``port_alteration`` [rad] and ``altered_to_port`` (stand-on in a crossing situation,
        Rule 17(c); module notes).
    status : ndarray (encounters, vessels)
        Each run's :class:`~seahelm.simulation.engine.RunStatus`.
    names, lengths : the vessels' labels and lengths [m]
    domain_axes : (along, across)
        The own ship's domain semi-axes [ship lengths].
    """

    def __init__(self, rec: Recorder, status: np.ndarray) -> None:
        enc = rec.enc
        self.names, self.lengths = enc.names, enc.lengths
        self.domain_axes = (enc.domain.along, enc.domain.across)
        self.time = rec.time
        self.tracks = {name: rec.tracks[j] for j, name in enumerate(Recorder.TRACK)}
        self.pair = rec.pair
        self.status = status
        self.min_range, self.t_min_range = rec.min_range, rec.t_min
        self.min_domain_distance = rec.min_domain
        ne, nt = rec.min_range.shape
        self.situation = (rec.situation0 if rec.situation0 is not None
                          else np.zeros((ne, nt), dtype=np.int8))
        touch = 0.5 * (enc.lengths[0] + enc.lengths[1:])
        self.collision = rec.min_range < touch[None, :]
        self.near_miss = (rec.min_domain < 1.0) & ~self.collision
        rules = enc.verdict_rules
        roles = rec.role0 if rec.role0 is not None else np.zeros((ne, nt, 2), dtype=np.int8)
        role = np.where(np.isin(roles, GIVE_WAY), 1, np.where(np.isin(roles, STAND_ON), -1, 0))
        acted = rec.alter > rules.action
        self.verdicts = {
            "role": role, "alteration": rec.alter, "action_time": rec.action_time,
            "action_range": rec.action_range,
            "acted": (role == 1) & acted,
            "substantial": (role == 1) & (rec.alter >= rules.substantial),
            "early": (role == 1) & acted & (rec.action_range >= rules.early_range),
            "kept_course": (role == -1) & (rec.alter <= rules.keep),
            "port_alteration": rec.port,
            "altered_to_port": (roles == Situation.CROSSING_STAND_ON) & (rec.port > rules.action),
        }

    @property
    def n_encounters(self) -> int:
        return self.status.shape[0]

    def summary(self) -> list[dict[str, Any]]:
        """Outcome rates by the own ship's situation at the start (and over all), with 95 %
        Wilson intervals: one row per situation."""
        rows = []
        sit = self.situation[:, 0] if self.situation.shape[1] else np.zeros(0)
        groups = [(s.name.lower().replace("_", "-"), sit == s) for s in Situation]
        for name, mask in groups + [("all", np.ones_like(sit, dtype=bool))]:
            n = int(mask.sum())
            if n == 0:
                continue
            row: dict[str, Any] = {"situation": name, "encounters": n}
            for what, arr in (("collision", self.collision[:, 0]),
                              ("near_miss", self.near_miss[:, 0])):
                k = int(arr[mask].sum())
                lo, hi = wilson_interval(k, n)
                row[what] = k / n
                row[f"{what}_ci"] = (float(lo), float(hi))
            v = self.verdicts
            give = v["role"][mask, 0, 0] == 1
            stand = v["role"][mask, 0, 0] == -1
            row["own_acted"] = float(v["acted"][mask, 0, 0][give].mean()) if give.any() else None
            row["own_substantial"] = (float(v["substantial"][mask, 0, 0][give].mean())
                                      if give.any() else None)
            row["own_kept_course"] = (float(v["kept_course"][mask, 0, 0][stand].mean())
                                      if stand.any() else None)
            # Rule 17(c): of the crossing stand-on encounters, the share turning to port
            crossing = sit[mask] == Situation.CROSSING_STAND_ON
            row["own_altered_to_port"] = (
                float(v["altered_to_port"][mask, 0, 0][crossing].mean())
                if crossing.any() and "altered_to_port" in v else None)
            row["min_range_median"] = float(np.median(self.min_range[mask, 0]))
            rows.append(row)
        return rows

    def to_xarray(self) -> Any:
        """The result as an xarray Dataset (dims ``encounter``, ``vessel``, ``target``,
        ``time``)."""
        from .._optional import optional_import
        xr = optional_import("xarray", purpose="EncounterResult.to_xarray()")
        data: dict[str, Any] = {name: (("encounter", "vessel", "time"), arr)
                                for name, arr in self.tracks.items()}
        data.update({f"pair_{name}": (("encounter", "target", "time"), arr)
                     for name, arr in self.pair.items()})
        for name in ("min_range", "t_min_range", "min_domain_distance", "situation",
                     "collision", "near_miss"):
            data[name] = (("encounter", "target"), getattr(self, name))
        for name, arr in self.verdicts.items():
            data[f"verdict_{name}"] = (("encounter", "target", "party"), arr)
        data["status"] = (("encounter", "vessel"), self.status)
        data["length"] = (("vessel",), np.asarray(self.lengths, dtype=float), {"units": "m"})
        return xr.Dataset(data, coords={"time": self.time, "vessel": list(self.names),
                                        "party": ["own", "target"]},
                          attrs={"format": DATASET_FORMAT,
                                 "domain_along_L": float(self.domain_axes[0]),
                                 "domain_across_L": float(self.domain_axes[1])})

    @classmethod
    def from_xarray(cls, ds: Any) -> "EncounterResult":
        """The result of a Dataset of :meth:`to_xarray` (``encounters.nc`` of ``seahelm
        encounter --out``), so that its :meth:`summary` and plots work on a file.

        Parameters
        ----------
        ds : xarray.Dataset

        Returns
        -------
        EncounterResult

        Raises
        ------
        ParameterError
            If ``ds`` is not an encounter result (its ``format`` attribute, a variable
            missing).
        """
        if not is_encounter_dataset(ds):
            raise ParameterError(f": not an encounter result (attribute format = "
                                 f"{ds.attrs.get('format')!r}, expected {DATASET_FORMAT!r})",
                                 field="format", value=ds.attrs.get("format"))
        need = ([*Recorder.TRACK, "length", "status", "min_range", "t_min_range",
                 "min_domain_distance", "situation", "collision", "near_miss"]
                + [f"pair_{n}" for n in ("range", "dcpa", "tcpa", "domain_distance",
                                         "situation")]
                + [f"verdict_{n}" for n in ("role", "alteration", "action_time",
                                            "action_range", "acted", "substantial", "early",
                                            "kept_course")])
        missing = [n for n in need if n not in ds.variables]
        if missing:
            raise ParameterError(f": not an encounter result: no variable {missing[0]!r}",
                                 field=missing[0])
        self = cls.__new__(cls)

        def arr(name: str) -> np.ndarray:
            return np.asarray(ds[name].values)

        self.names = tuple(str(v) for v in ds["vessel"].values)
        self.lengths = arr("length").astype(float)
        self.domain_axes = (float(ds.attrs["domain_along_L"]),
                            float(ds.attrs["domain_across_L"]))
        self.time = np.asarray(ds["time"].values, dtype=float)
        self.tracks = {n: arr(n).astype(float) for n in Recorder.TRACK}
        self.pair = {n: arr(f"pair_{n}") for n in ("range", "dcpa", "tcpa", "domain_distance",
                                                   "situation")}
        self.status = arr("status")
        self.min_range, self.t_min_range = arr("min_range"), arr("t_min_range")
        self.min_domain_distance = arr("min_domain_distance")
        self.situation = arr("situation").astype(np.int8)
        self.collision, self.near_miss = arr("collision").astype(bool), \
            arr("near_miss").astype(bool)
        self.verdicts = {n: arr(f"verdict_{n}") for n in ("role", "alteration", "action_time",
                                                          "action_range")}
        self.verdicts.update({n: arr(f"verdict_{n}").astype(bool)
                              for n in ("acted", "substantial", "early", "kept_course")})
        if "verdict_altered_to_port" in ds.variables:  # (files written before it: without)
            self.verdicts["port_alteration"] = arr("verdict_port_alteration")
            self.verdicts["altered_to_port"] = arr("verdict_altered_to_port").astype(bool)
        return self


def is_encounter_dataset(ds: Any) -> bool:
    """Whether ``ds`` is an encounter result (:meth:`EncounterResult.to_xarray`).

    Parameters
    ----------
    ds : xarray.Dataset
        A dataset read from a file.
    """
    return ds.attrs.get("format") == DATASET_FORMAT
