"""The unit of each output of seahelm and the unit a person reads it in: one source of truth.

**Stored units.** Results store SI units with angles in radians, each variable's unit in its
``units`` attribute (NetCDF files, sweep stores); ``--json`` output gives values as stored.
The per-run summary metrics of a simulation
(:func:`seahelm.analysis.maneuvers.summarize`) are named so that their unit follows from the
name (:func:`metric_unit`): a suffix that names it (``settling_time_s`` [s],
``overshoot_deg`` [deg], ``turning_diameter_m`` [m], ``rudder_reversals_per_min`` [1/min]),
or the signal the metric is a value of (``final_<signal>``, ``<signal>_error``: the signal's
unit, e.g. ``final_heading`` [rad]).

**Display units.** What a person reads -- the CLI's tables, ``seahelm inspect``, the HTML
report -- shows every value by the same rule (:func:`display_unit`): angles in degrees
(rad → deg, rad/s → deg/s, rad/s² → deg/s²), a shaft's rotation speed (unit rad/s of a
quantity named ``..._speed``, such as a thruster's ``propeller_port_speed``; the rate of an
angle is named ``..._rate``) in rpm, fractions (unit ``1`` of a quantity named in
:data:`FRACTIONS`, such as the speed loss of a turn) in per cent, every other unit as stored.
A label names the quantity in words with its display unit, ``final heading [deg]``
(:func:`metric_label`).

**Which summary metrics a table shows** (:func:`shown_metrics`): not a filter's internal
states (``final_yaw_aux``), and an angle once (``final_heading`` is shown in degrees, so
``heading_deg`` and ``final_heading_rad``, the same value, are not shown again).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np

__all__ = ["SUFFIX_UNITS", "FRACTIONS", "ANGLE_DISPLAY", "metric_unit", "metric_units",
           "display_unit", "to_display", "label", "metric_label", "shown_metrics",
           "noted_unreached"]

#: Units named by a metric's suffix (``settling_time_s``: s), longest suffixes first.
SUFFIX_UNITS: dict[str, str] = {
    "_per_min": "1/min", "_degps": "deg/s", "_mps": "m/s", "_deg": "deg", "_rad": "rad",
    "_pct": "%", "_s": "s", "_m": "m", "_L": "L"}
#: Quantities of unit ``1`` that are fractions of a whole, shown in per cent.
FRACTIONS = frozenset({"speed_loss"})
#: Angle units and the units they are shown in.
ANGLE_DISPLAY: dict[str, str] = {"rad": "deg", "rad/s": "deg/s", "rad/s²": "deg/s²",
                                 "rad/s^2": "deg/s^2", "rad/s**2": "deg/s**2"}


def metric_unit(key: str, signal_units: Mapping[str, str] | None = None) -> str:
    """The stored unit of a per-run summary metric, from its name.

    Parameters
    ----------
    key : str
        The metric's name (``settling_time_s``, ``final_heading``, ``yaw_rate_error``, ...).
    signal_units : mapping of str to str, optional
        The units of the result's signals (states, outputs, commands) by name, for
        ``final_<signal>`` and ``<signal>_error``.

    Returns
    -------
    str
        The unit ("" where the name says none).
    """
    units = signal_units or {}
    for prefix, suffix in (("final_", ""), ("", "_error")):
        if key.startswith(prefix) and key.endswith(suffix):
            name = key[len(prefix):len(key) - len(suffix)]
            if units.get(name):
                return str(units[name])
    for suffix, unit in SUFFIX_UNITS.items():
        if key.endswith(suffix) and len(key) > len(suffix):
            return unit
    return ""


def metric_units(keys: Iterable[str], signal_units: Mapping[str, str] | None = None
                 ) -> dict[str, str]:
    """:func:`metric_unit` of every key.

    Parameters
    ----------
    keys : iterable of str
        Metric names.
    signal_units : mapping of str to str, optional
        The units of the result's signals by name.

    Returns
    -------
    dict of str to str
    """
    return {k: metric_unit(k, signal_units) for k in keys}


def _words(name: str, unit: str) -> str:
    """A name without the suffix that names its unit (``settling_time_s`` of unit s:
    ``settling_time``)."""
    for suffix, named in SUFFIX_UNITS.items():
        if name.endswith(suffix) and len(name) > len(suffix) and named == unit:
            return name[:-len(suffix)]
    return name


def _is_shaft_speed(name: str) -> bool:
    """Whether a quantity of unit rad/s is a shaft's rotation speed (``propeller_speed``,
    ``final_propeller_port_speed``, ``max_abs_propeller_speed``) rather than an angle's rate."""
    return name.removesuffix("_command").endswith("_speed")


def display_unit(unit: str, name: str = "") -> tuple[str, float]:
    """The unit a value of ``unit`` is shown in, and the factor that converts it.

    Parameters
    ----------
    unit : str
        The stored unit.
    name : str, optional
        The quantity's name (a unit ``1`` is shown in per cent for the names in
        :data:`FRACTIONS`; rad/s of a ``..._speed`` in rpm).

    Returns
    -------
    (str, float)
        Display unit and factor (display value = factor × stored value).
    """
    unit = str(unit or "")
    if unit == "rad/s" and _is_shaft_speed(name):
        return "rpm", 60.0 / (2.0 * math.pi)
    if unit in ANGLE_DISPLAY:
        return ANGLE_DISPLAY[unit], 180.0 / math.pi
    if unit in ("1", "-") and name.removeprefix("final_") in FRACTIONS:
        return "%", 100.0
    return unit, 1.0


def to_display(value: Any, unit: str, name: str = "") -> tuple[Any, str]:
    """A value (number or array) in its display unit (:func:`display_unit`).

    Parameters
    ----------
    value : float, array_like or None
        The stored value(s); None and anything not numeric is returned as it is.
    unit : str
        The stored unit.
    name : str, optional
        The quantity's name.

    Returns
    -------
    (object, str)
        The value in the display unit, and that unit.
    """
    shown, factor = display_unit(unit, name)
    if factor == 1.0 or value is None or isinstance(value, (bool, np.bool_, str)):
        return value, shown
    if isinstance(value, (int, float, np.integer, np.floating)):
        return float(value) * factor, shown
    arr = np.asarray(value)
    if arr.dtype.kind in "fiu":
        return arr.astype(float) * factor, shown
    return value, shown


def label(name: str, unit: str) -> str:
    """``name [unit]``, or the name alone without a unit.

    Parameters
    ----------
    name : str
        What the value is.
    unit : str
        Its (display) unit.

    Returns
    -------
    str
    """
    return f"{name} [{unit}]" if unit else name


def metric_label(key: str, unit: str | None = None) -> str:
    """A metric's label in words with its display unit: ``settling_time_s`` → ``settling time
    [s]``, ``final_heading`` (rad) → ``final heading [deg]``, ``speed_loss`` (1) → ``speed
    loss [%]``.

    Parameters
    ----------
    key : str
        The metric's name.
    unit : str, optional
        Its stored unit (default: the unit its name says, :func:`metric_unit`).

    Returns
    -------
    str
    """
    if unit is None:
        unit = metric_unit(key)
    shown, _ = display_unit(unit, key)
    return label(_words(key, unit).replace("_", " "), shown)


def shown_metrics(keys: Iterable[str]) -> list[str]:
    """The summary metrics a table shows, in order: not a filter's internal states
    (``final_yaw_aux``), and each angle once (``heading_deg`` and ``final_heading_rad`` are
    ``final_heading`` again, which is shown in degrees).

    Parameters
    ----------
    keys : iterable of str
        Metric names (of :func:`seahelm.analysis.maneuvers.summarize`).

    Returns
    -------
    list of str
    """
    keys = list(keys)
    have = set(keys)
    out = []
    for key in keys:
        if key.endswith("_aux") or "_aux_" in key:
            continue
        if key.endswith("_deg") and not key.startswith("max_abs_") \
                and f"final_{key[:-4]}" in have:
            continue
        if key.startswith("final_") and key.endswith("_rad") and key[:-4] in have:
            continue
        out.append(key)
    return out


#: Metrics only a turn reaches (:func:`seahelm.analysis.maneuvers.summarize`).
TURN_ONLY = ("turning_diameter_m",)


def noted_unreached(unreached: Iterable[str], keys: Iterable[str]) -> list[str]:
    """The metrics not reached that are worth a note under a table.

    A course change (a run with a heading reference: ``heading_error_deg``) or a route (a
    cross-track error) never turns a full circle, so its turning diameter was not asked for:
    saying "not reached: turning_diameter_m" under every such run was noise. Every other
    unreached metric is kept.

    Parameters
    ----------
    unreached : iterable of str
        The metrics without a finite value.
    keys : iterable of str
        Every metric of the table (what tells a steered run from a turn).

    Returns
    -------
    list of str
        ``unreached`` in its order, without the turn-only metrics of a steered run.
    """
    have = set(keys)
    steered = "heading_error_deg" in have or any(
        k.startswith("max_abs_cross_track_error") for k in have)
    return [k for k in unreached if not (steered and k in TURN_ONLY)]
