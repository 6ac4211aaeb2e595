"""A DP vessel's thrusters in the horizontal plane: positions, directions, limits, forbidden
azimuth sectors (merged, their allowed arcs), and the layout left by a single failure.

Used by :mod:`seahelm.control.dp_allocation` (the constrained allocation) and the level-1
capability (:mod:`seahelm.analysis.dp.level1`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import ParameterError

__all__ = ["ThrusterLayout", "THRUSTER_KINDS"]

_TWO_PI = 2.0 * math.pi

#: The kinds of thruster: a tunnel thruster (fixed, sideways, reversible), an azimuth thruster
#: (its direction free, thrust ahead only), a main propeller (fixed, along its shaft).
THRUSTER_KINDS: tuple[str, ...] = ("tunnel", "azimuth", "main")


@dataclass(frozen=True)
class ThrusterLayout:
    """Thrusters of a DP vessel in the horizontal plane (body frame, x forward, y starboard).

    Parameters
    ----------
    names : tuple of str
        One per thruster.
    x, y : tuple of float
        Positions [m] relative to the reference point of the loads.
    direction : tuple of float
        Direction α [rad] of a fixed thruster's positive thrust (0 forward, π/2 starboard); an
        azimuth thruster's initial azimuth.
    azimuthing : tuple of bool
        True: the direction is free (azimuth thruster, thrust ahead only).
    max_thrust : tuple of float
        Largest thrust [N] (> 0).
    min_thrust : tuple of float, optional
        Smallest thrust [N] of a fixed thruster (≤ max; negative: astern; default −max_thrust
        for a tunnel thruster). Ignored for an azimuth (0).
    forbidden : tuple of tuple of (float, float), optional
        Per thruster, forbidden azimuth sectors (start, end) [rad], counter-clockwise from
        start to end.
    kinds : tuple of str, optional
        Per thruster, one of :data:`THRUSTER_KINDS` (``tunnel``, ``azimuth``, ``main``);
        default ``azimuth`` for an azimuthing thruster, else ``tunnel`` when its direction is
        sideways and ``main`` otherwise.
    max_thrust_rate : tuple of float, optional
        Largest thrust rate Ṫ [N/s] per thruster (> 0; default inf: none).
    max_azimuth_rate : tuple of float, optional
        Largest azimuth turning rate α̇ [rad/s] per thruster (> 0; default inf: none; ignored
        for a fixed thruster).
    """

    names: tuple
    x: tuple
    y: tuple
    direction: tuple
    azimuthing: tuple
    max_thrust: tuple
    min_thrust: tuple = None
    forbidden: tuple = field(default=None)
    kinds: tuple = None
    max_thrust_rate: tuple = None
    max_azimuth_rate: tuple = None

    def __post_init__(self) -> None:
        n = len(self.names)
        for key in ("x", "y", "direction", "azimuthing", "max_thrust"):
            if len(getattr(self, key)) != n:
                raise ParameterError(f"must have {n} entries (one per "
                                     f"thruster), got {len(getattr(self, key))}",
                                     field=f"thrusters.{key}")
        if n == 0:
            raise ParameterError("must list at least one thruster, got none",
                                 field="thrusters")
        if len(set(self.names)) != n:
            dup = sorted({nm for nm in self.names if list(self.names).count(nm) > 1})
            raise ParameterError(f"must be unique, got {', '.join(map(repr, dup))} more "
                                 "than once", field="thrusters.name", value=dup[0])
        if self.kinds is None:
            object.__setattr__(self, "kinds", tuple(
                "azimuth" if az else ("tunnel" if abs(math.sin(d)) > 0.5 else "main")
                for az, d in zip(self.azimuthing, self.direction)))
        if len(self.kinds) != n:
            raise ParameterError(f"must have {n} entries, got {len(self.kinds)}",
                                 field="thrusters.kind")
        for i, kind in enumerate(self.kinds):
            if kind not in THRUSTER_KINDS:
                raise ParameterError(f"of thruster {self.names[i]!r} must be one of "
                                     f"{', '.join(THRUSTER_KINDS)}, got {kind!r}",
                                     field="thrusters.kind", value=kind)
            if (kind == "azimuth") != bool(self.azimuthing[i]):
                raise ParameterError(f"of thruster {self.names[i]!r}: {kind!r} does not agree "
                                     f"with azimuthing={bool(self.azimuthing[i])}",
                                     field="thrusters.kind", value=kind)
        for key, unit in (("max_thrust_rate", "N/s"), ("max_azimuth_rate", "rad/s")):
            val = getattr(self, key)
            if val is None:
                object.__setattr__(self, key, (math.inf,) * n)
                continue
            arr = np.asarray(val, dtype=float)
            if arr.shape != (n,) or np.any(np.isnan(arr)) or np.any(arr <= 0):
                raise ParameterError(f"must be {n} values > 0 [{unit}], got {list(val)}",
                                     field=f"thrusters.{key}", unit=unit)
            object.__setattr__(self, key, tuple(float(v) for v in arr))
        tmax = np.asarray(self.max_thrust, dtype=float)
        if not np.all(np.isfinite(tmax) & (tmax > 0)):
            raise ParameterError(f"must be > 0 [N], got "
                                 f"{list(self.max_thrust)}", field="thrusters.max_thrust",
                                 unit="N")
        if self.min_thrust is None:
            object.__setattr__(self, "min_thrust", tuple(-float(t) for t in self.max_thrust))
        tmin = np.asarray(self.min_thrust, dtype=float)
        if tmin.shape != (n,) or np.any(tmin > tmax):
            raise ParameterError(f"must be {n} values ≤ max_thrust [N], "
                                 f"got {list(self.min_thrust)}", field="thrusters.min_thrust",
                                 unit="N")
        sectors = self.forbidden if self.forbidden is not None else ((),) * n
        if len(sectors) != n:
            raise ParameterError(f"must have {n} entries, got "
                                 f"{len(sectors)}", field="thrusters.forbidden")
        clean = []
        for i, secs in enumerate(sectors):
            secs = tuple((float(a) % _TWO_PI, float(b) % _TWO_PI) for a, b in secs)
            covered = sum(b - a for a, b in _merge(secs))
            if secs and covered >= _TWO_PI - 1e-9:
                raise ParameterError(
                    f"of thruster {self.names[i]!r} cover 360 [deg] "
                    f"(sectors {[(round(math.degrees(a), 3), round(math.degrees(b), 3)) for a, b in secs]} deg)",
                    field="thrusters.forbidden", unit="deg", value=360.0)
            if secs and not self.azimuthing[i]:
                raise ParameterError(f"of thruster {self.names[i]!r}: "
                                     "only an azimuth thruster has forbidden sectors",
                                     field="thrusters.forbidden")
            clean.append(secs)
        object.__setattr__(self, "forbidden", tuple(clean))

    @property
    def count(self) -> int:
        """Number of thrusters."""
        return len(self.names)

    def allowed_arcs(self, i: int) -> list[tuple[float, float]]:
        """Allowed azimuth arcs (start, end) [rad], end > start (end may exceed 2π).

        Parameters
        ----------
        i : int
            Thruster index.

        Returns
        -------
        list of (float, float)
        """
        return _allowed(self.forbidden[i])

    def without(self, name: str) -> "ThrusterLayout":
        """The layout with thruster ``name`` lost (a single failure).

        Parameters
        ----------
        name : str
            The thruster lost.

        Returns
        -------
        ThrusterLayout

        Raises
        ------
        ParameterError
            For a name that is not one of the layout's thrusters.
        """
        if name not in self.names:
            raise ParameterError(f"names no thruster of the layout: {name!r} (the "
                                 f"thrusters: {', '.join(self.names)})", field="failure",
                                 value=name)
        keep = [k for k, nm in enumerate(self.names) if nm != name]
        pick = lambda seq: tuple(seq[k] for k in keep)  # noqa: E731
        return ThrusterLayout(pick(self.names), pick(self.x), pick(self.y),
                              pick(self.direction), pick(self.azimuthing),
                              pick(self.max_thrust), pick(self.min_thrust),
                              pick(self.forbidden), pick(self.kinds),
                              pick(self.max_thrust_rate), pick(self.max_azimuth_rate))


def _merge(secs):
    """Forbidden sectors as disjoint sorted intervals of [0, 2π] (a wrapping one split)."""
    ivs = []
    for a, b in secs:
        w = (b - a) % _TWO_PI
        if w == 0.0:
            continue
        if a + w <= _TWO_PI:
            ivs.append((a, a + w))
        else:
            ivs += [(a, _TWO_PI), (0.0, a + w - _TWO_PI)]
    ivs.sort()
    merged = []
    for a, b in ivs:
        if merged and a <= merged[-1][1]:
            merged[-1] = (merged[-1][0], max(merged[-1][1], b))
        else:
            merged.append((a, b))
    return merged


def _allowed(secs):
    """Allowed arcs (start, end), end > start (end may pass 2π), of the forbidden ``secs``."""
    merged = _merge(secs)
    if not merged:
        return [(0.0, _TWO_PI)]
    gaps = [(merged[k][1], merged[k + 1][0]) for k in range(len(merged) - 1)]
    first, last = merged[0][0], merged[-1][1]
    wrap = (last, first + _TWO_PI)
    gaps = [gp for gp in gaps if gp[1] > gp[0]]
    if wrap[1] > wrap[0]:
        gaps.append(wrap)
    return sorted(gaps)
