"""A ship file's ``[[thrusters]]``: the thruster layout of a DP vessel, read and written.

Each ``[[thrusters]]`` table is one thruster (body axes: x forward, y starboard, from the
origin of the ship's model)::

    [[thrusters]]
    name = "bow-tunnel-1"
    kind = "tunnel"              # tunnel | azimuth | main
    x = 30.0                     # [m]
    y = 0.0                      # [m]
    max_thrust = 200000.0        # [N]
    min_thrust = -200000.0       # [N] optional (tunnel, main: default −max_thrust; azimuth: 0)
    direction_deg = 90           # optional: direction of positive thrust (tunnel default 90,
                                 # main 0); an azimuth's initial azimuth (default 0)
    max_thrust_rate = 50000.0    # [N/s] optional (default: none)
    max_azimuth_rate_deg = 12    # [deg/s] optional, azimuth only (default: none)
    forbidden_sectors_deg = [[80, 100]]   # optional, azimuth only: (start, end) counter-clockwise

Angles are radians, or degrees as ``<key>_deg``. Errors name the key path (``thrusters[2].x``),
its unit and the value.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from ..control.thruster_layout import THRUSTER_KINDS, ThrusterLayout, _merge
from ..errors import ParameterError

__all__ = ["THRUSTER_KEYS", "layout_from_tables", "layout_to_tables"]

#: Every key of a ``[[thrusters]]`` table: (key, unit, required, what it is).
THRUSTER_KEYS: tuple[tuple[str, str, str, str], ...] = (
    ("name", "", "yes", "the thruster's name (unique; failure cases name it)"),
    ("kind", "", "yes", "tunnel, azimuth or main (propeller)"),
    ("x", "m", "yes", "position forward of the model's origin"),
    ("y", "m", "yes", "position to starboard"),
    ("max_thrust", "N", "yes", "largest thrust (> 0)"),
    ("min_thrust", "N", "no", "smallest thrust (negative: astern; default −max_thrust; "
                              "not for an azimuth)"),
    ("direction", "rad", "no", "direction of positive thrust, 0 ahead, π/2 starboard (tunnel "
                               "default π/2, main 0); an azimuth's initial azimuth; or "
                               "direction_deg"),
    ("max_thrust_rate", "N/s", "no", "largest thrust rate (default: none)"),
    ("max_azimuth_rate", "rad/s", "no", "largest azimuth rate, azimuth only (or "
                                        "max_azimuth_rate_deg [deg/s])"),
    ("forbidden_sectors", "rad", "no", "azimuth only: forbidden sectors [[start, end], ...], "
                                       "counter-clockwise (or forbidden_sectors_deg)"),
)
_KEYS = {k for k, *_ in THRUSTER_KEYS}
_ANGLE_KEYS = {"direction", "max_azimuth_rate", "forbidden_sectors"}


def _num(value: Any, path: str, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ParameterError(f"must be a finite number [{unit}], got {value!r}", field=path,
                             unit=unit, value=value)
    return float(value)


def _get(tab: Mapping[str, Any], key: str, path: str, unit: str, default: Any = None) -> Any:
    """A number given as ``key`` (SI) or ``key_deg`` (degrees, for angles)."""
    deg = f"{key}_deg"
    if key in tab and deg in tab:
        raise ParameterError(f"is given both as `{key}` and `{deg}`: give one",
                             field=f"{path}.{key}")
    if deg in tab:
        return math.radians(_num(tab[deg], f"{path}.{deg}", "deg" + unit[3:]))
    if key in tab:
        return _num(tab[key], f"{path}.{key}", unit)
    return default


def _sectors(tab: Mapping[str, Any], path: str) -> tuple:
    key = "forbidden_sectors_deg" if "forbidden_sectors_deg" in tab else "forbidden_sectors"
    if key not in tab:
        return ()
    if "forbidden_sectors_deg" in tab and "forbidden_sectors" in tab:
        raise ParameterError("is given both in radians and in degrees: give one",
                             field=f"{path}.forbidden_sectors")
    unit = "deg" if key.endswith("_deg") else "rad"
    value = tab[key]
    if not isinstance(value, list) or not all(isinstance(v, list) and len(v) == 2
                                              for v in value):
        raise ParameterError(f"must be a list of [start, end] pairs [{unit}], got {value!r}",
                             field=f"{path}.{key}", unit=unit)
    out = []
    for k, (a, b) in enumerate(value):
        a = _num(a, f"{path}.{key}[{k}]", unit)
        b = _num(b, f"{path}.{key}[{k}]", unit)
        turn = 360.0 if unit == "deg" else 2 * math.pi
        if abs(b - a) >= turn - 1e-9:
            raise ParameterError(f"spans {abs(b - a):g} [{unit}], a full turn or more (no "
                                 f"admissible direction left): give [start, end] less than "
                                 f"{turn:g} {unit} apart", field=f"{path}.{key}[{k}]",
                                 unit=unit, value=[a, b])
        out.append((math.radians(a), math.radians(b)) if unit == "deg" else (a, b))
    covered = sum(e - s for s, e in _merge(tuple((a % (2 * math.pi), b % (2 * math.pi))
                                                 for a, b in out)))
    if covered >= 2 * math.pi - 1e-9:
        raise ParameterError(f"cover 360 [deg] together (no admissible direction left), got "
                             f"{value!r}", field=f"{path}.{key}", unit=unit, value=value)
    return tuple(out)


def layout_from_tables(tables: Any, *, field: str = "thrusters") -> ThrusterLayout:
    """The :class:`ThrusterLayout` of a ship file's ``[[thrusters]]`` tables (see module).

    Parameters
    ----------
    tables : list of mapping
        The parsed ``[[thrusters]]`` array.
    field : str, optional
        The key path for messages.

    Returns
    -------
    ThrusterLayout

    Raises
    ------
    ParameterError
        Naming the key path (``thrusters[i].key``), unit and value: an unknown or missing key,
        a kind not tunnel/azimuth/main, a number out of range, forbidden sectors on a fixed
        thruster or covering 360°, names not unique.
    """
    if not isinstance(tables, list) or not tables:
        raise ParameterError(f"must be one or more [[{field}]] tables, got {tables!r}",
                             field=field)
    cols: dict[str, list] = {k: [] for k in ("names", "x", "y", "direction", "azimuthing",
                                             "max_thrust", "min_thrust", "forbidden", "kinds",
                                             "max_thrust_rate", "max_azimuth_rate")}
    for i, tab in enumerate(tables):
        path = f"{field}[{i}]"
        if not isinstance(tab, Mapping):
            raise ParameterError(f"must be a table, got {tab!r}", field=path)
        for key in tab:
            base = key[:-4] if key.endswith("_deg") else key
            if base not in _KEYS or (key.endswith("_deg") and base not in _ANGLE_KEYS):
                import difflib

                close = difflib.get_close_matches(key, sorted(_KEYS), n=1)
                hint = f" (did you mean `{close[0]}`?)" if close else ""
                raise ParameterError(f"is an unknown key{hint}; valid here: "
                                     f"{', '.join(sorted(_KEYS))}", field=f"{path}.{key}")
        for key in ("name", "kind", "x", "y", "max_thrust"):
            if key not in tab:
                raise ParameterError("is required", field=f"{path}.{key}")
        name, kind = tab["name"], tab["kind"]
        if not isinstance(name, str) or not name.strip():
            raise ParameterError(f"must be a non-empty text, got {name!r}", field=f"{path}.name",
                                 value=name)
        if kind not in THRUSTER_KINDS:
            raise ParameterError(f"must be one of {', '.join(THRUSTER_KINDS)}, got {kind!r}",
                                 field=f"{path}.kind", value=kind)
        azimuth = kind == "azimuth"
        tmax = _num(tab["max_thrust"], f"{path}.max_thrust", "N")
        if not tmax > 0:
            raise ParameterError(f"must be > 0 [N], got {tmax!r}", field=f"{path}.max_thrust",
                                 unit="N", value=tmax)
        tmin = _get(tab, "min_thrust", path, "N")
        if azimuth and tmin is not None:
            raise ParameterError("is not for an azimuth thruster (its thrust is ahead only, "
                                 f"≥ 0) [N], got {tmin!r}", field=f"{path}.min_thrust",
                                 unit="N", value=tmin)
        if tmin is not None and tmin > tmax:
            raise ParameterError(f"must be ≤ max_thrust = {tmax!r} [N], got {tmin!r}",
                                 field=f"{path}.min_thrust", unit="N", value=tmin)
        rate = _get(tab, "max_thrust_rate", path, "N/s", math.inf)
        if not rate > 0:
            raise ParameterError(f"must be > 0 [N/s], got {rate!r}",
                                 field=f"{path}.max_thrust_rate", unit="N/s", value=rate)
        az_rate = _get(tab, "max_azimuth_rate", path, "rad/s", math.inf)
        if not azimuth and math.isfinite(az_rate):
            raise ParameterError(f"is for an azimuth thruster only, not a {kind} [rad/s], got "
                                 f"{az_rate!r}", field=f"{path}.max_azimuth_rate",
                                 unit="rad/s", value=az_rate)
        if not az_rate > 0:
            raise ParameterError(f"must be > 0 [rad/s], got {az_rate!r}",
                                 field=f"{path}.max_azimuth_rate", unit="rad/s", value=az_rate)
        sectors = _sectors(tab, path)
        if sectors and not azimuth:
            raise ParameterError(f"is for an azimuth thruster only, not a {kind} [rad], got "
                                 f"{[list(sc) for sc in sectors]}",
                                 field=f"{path}.forbidden_sectors", unit="rad")
        direction = _get(tab, "direction", path, "rad",
                         0.5 * math.pi if kind == "tunnel" else 0.0)
        cols["names"].append(name)
        cols["kinds"].append(kind)
        cols["x"].append(_num(tab["x"], f"{path}.x", "m"))
        cols["y"].append(_num(tab["y"], f"{path}.y", "m"))
        cols["direction"].append(direction)
        cols["azimuthing"].append(azimuth)
        cols["max_thrust"].append(tmax)
        cols["min_thrust"].append(0.0 if azimuth else (-tmax if tmin is None else tmin))
        cols["forbidden"].append(sectors)
        cols["max_thrust_rate"].append(rate)
        cols["max_azimuth_rate"].append(az_rate)
    try:
        return ThrusterLayout(**{k: tuple(v) for k, v in cols.items()})
    except ParameterError as exc:       # (a layout-wide rule: duplicate names, 360° sectors)
        sub = (exc.field or field).split(".", 1)
        key = f"{field}.{sub[1]}" if len(sub) > 1 else field
        raise ParameterError(exc.reason, field=key, unit=exc.unit, value=exc.value) from None


def layout_to_tables(layout: ThrusterLayout) -> list[dict[str, Any]]:
    """The ``[[thrusters]]`` tables of ``layout`` (what :func:`layout_from_tables` reads back
    to the same layout).

    Parameters
    ----------
    layout : ThrusterLayout

    Returns
    -------
    list of dict
    """
    out = []
    for i in range(layout.count):
        kind = layout.kinds[i]
        tab: dict[str, Any] = {"name": layout.names[i], "kind": kind,
                               "x": float(layout.x[i]), "y": float(layout.y[i]),
                               "max_thrust": float(layout.max_thrust[i])}
        if kind != "azimuth":
            tab["min_thrust"] = float(layout.min_thrust[i])
        tab["direction"] = float(layout.direction[i])
        if math.isfinite(layout.max_thrust_rate[i]):
            tab["max_thrust_rate"] = float(layout.max_thrust_rate[i])
        if math.isfinite(layout.max_azimuth_rate[i]):
            tab["max_azimuth_rate"] = float(layout.max_azimuth_rate[i])
        if layout.forbidden[i]:
            tab["forbidden_sectors"] = [[float(a), float(b)] for a, b in layout.forbidden[i]]
        out.append(tab)
    return out
