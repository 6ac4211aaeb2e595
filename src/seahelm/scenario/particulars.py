"""``[vessel.particulars]``: the scenario's ship estimated from its main particulars.

::

    [vessel.particulars]            # instead of `ship = ...`
    length = 120.0                  # the keys of `seahelm ship estimate`'s particulars file
    beam = 18.0                     # (DESIGN_FIELDS; angles also as <name>_deg)
    draft = 7.0
    block_coefficient = 0.70
    speed = 6.5

The particulars become a :class:`~seahelm.ships.estimate.Design` and the ship is
:func:`~seahelm.ships.estimate.estimate_ship` of it, in the water depth of ``[vessel]
water_depth`` (or of the particulars' own ``water_depth``, not both); ``[vessel.params]`` then
override its estimated MMG coefficients (in deep water, as for a ship file). In a ``[maneuver]``
scenario ``[batch.monte_carlo]`` may draw ``vessel.particulars.<key>``: each sample is the ship
estimated from that sample's particulars (:class:`EstimatedSamples`); the regressions' range
warnings are said once per formula for all the samples, not once per sample. A ``[simulation]``
scenario runs the one estimated ship: its particulars cannot vary there
(:func:`refuse_varied_particulars`).
"""

from __future__ import annotations

import dataclasses
import difflib
import math
import re
import warnings
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from ..errors import ParameterError, ValidityRangeWarning
from .errors import ScenarioError, at_key
from .samples import drawn_kinds
from .schema import Scenario

__all__ = ["PREFIX", "estimated_ship", "EstimatedSamples", "check_drawn_particulars",
           "refuse_varied_particulars", "aggregate_warnings"]

#: The key path of a particular in a batch (``vessel.particulars.block_coefficient``).
PREFIX = "vessel.particulars."


def _fields() -> tuple[set[str], set[str]]:
    """The particulars' numeric keys and those that are angles (also taken as ``_deg``)."""
    from ..ships.estimate import DESIGN_FIELDS

    numeric = {n for n, _, _, _ in DESIGN_FIELDS if n != "name"}
    angles = {n for n, u, _, _ in DESIGN_FIELDS if u.startswith("rad")}
    return numeric, angles


def _key(exc: Exception, values: Mapping[str, Any], depth_in_vessel: bool) -> str:
    """The scenario key a :class:`Design`'s (or an estimate's) error is about."""
    from ..ships.estimate import DESIGN_FIELDS

    field = (getattr(exc, "field", None) or "").partition(".")[0]
    if field == "trim":  # (T_a - T_f, of the fore and aft draughts)
        field = "draft_aft"
    if field == "water_depth" and depth_in_vessel:
        return "vessel.water_depth"
    if field in values:
        return PREFIX + field
    if f"{field}_deg" in values:  # written in degrees
        return PREFIX + f"{field}_deg"
    if field in {n for n, _, _, _ in DESIGN_FIELDS}:
        return PREFIX + field
    return "vessel.particulars"


def _reason(exc: Exception, values: Mapping[str, Any], key: str) -> str:
    """What is wrong, said after ``key`` (the estimate's own error, where it is about no
    particular, whole: "the estimate fails: `w_P0` must be in [0, 0.99] [-], got 1.93")."""
    if key == "vessel.particulars" or not isinstance(exc, ParameterError):
        return f"the estimate fails: {exc}"
    reason = exc.reason.lstrip(": ")
    field = (exc.field or "").partition(".")[0]
    if field and field not in values and f"{field}_deg" in values:
        written = values[f"{field}_deg"]
        shown = f"{written:g}" if isinstance(written, (int, float)) else repr(written)
        reason += f" (as written: {field}_deg = {shown} deg)"
    return reason


def _design_and_ship(values: Mapping[str, Any], water_depth: float | None) -> Any:
    from ..ships.estimate import Design, estimate_ship

    given = dict(values)
    if water_depth is not None:
        given["water_depth"] = water_depth
    return estimate_ship(Design.from_mapping(given))


def estimated_ship(scn: Scenario, source: str) -> Any:
    """The ship of ``[vessel.particulars]``: :func:`~seahelm.ships.estimate.estimate_ship` of
    the particulars, in the scenario's water depth.

    Parameters
    ----------
    scn : Scenario
        Validated scenario with ``[vessel.particulars]``.
    source : str
        The scenario file (in error messages).

    Returns
    -------
    Ship
        An MMG ship with a steering gear (its regressions' range warnings said as they come).

    Raises
    ------
    ScenarioError
        At ``vessel.particulars.<key>`` (or ``vessel.water_depth``): an unknown key (naming
        the close match), a missing required one, a value that is not physical (its unit and
        the value).
    """
    v = scn.vessel
    values = dict(v.particulars or {})
    try:
        return _design_and_ship(values, v.water_depth)
    except (ValueError, ArithmeticError) as exc:  # (a formula outside its domain, unnamed)
        key = _key(exc, values, v.water_depth is not None)
        raise at_key(source, key, _reason(exc, values, key)) from None


def check_drawn_particulars(scn: Scenario, keys: Sequence[str], source: str) -> bool:
    """Check the ``vessel.particulars.*`` keys a ``[maneuver]`` scenario draws.

    Parameters
    ----------
    scn : Scenario
        Validated scenario.
    keys : sequence of str
        Every drawn key (of ``draws`` and ``correlated``).
    source : str
        The scenario file (in error messages).

    Returns
    -------
    bool
        Whether any particular is drawn.

    Raises
    ------
    ScenarioError
        At ``batch.monte_carlo.<key>``: particulars drawn without ``[vessel.particulars]``, a
        key that is not a numeric particular (naming the close match), the water depth drawn
        while ``[vessel]`` gives it.
    """
    drawn = [k for k in keys if k.startswith(PREFIX)]
    if not drawn:
        return False
    if scn.vessel.particulars is None:
        raise at_key(source, f"batch.monte_carlo.{drawn[0]}",
                     "draws of the particulars need a ship estimated from them: give "
                     "[vessel.particulars] (length, beam, draft, block_coefficient, speed, ...) "
                     "instead of `ship`")
    numeric, angles = _fields()
    valid = sorted(numeric | {f"{a}_deg" for a in angles})
    for key in drawn:
        name = key[len(PREFIX):]
        if name not in valid:
            close = difflib.get_close_matches(name, valid, n=1)
            hint = f" (did you mean '{PREFIX}{close[0]}'?)" if close else ""
            what = ("the ship's name is not drawn" if name == "name"
                    else f"'{name}' is not a particular{hint}")
            raise at_key(source, f"batch.monte_carlo.{key}",
                         f"{what}; the particulars drawn are numbers: {', '.join(valid)}")
        if name == "water_depth" and scn.vessel.water_depth is not None:
            raise at_key(source, f"batch.monte_carlo.{key}",
                         "the water depth is drawn here and given in [vessel] `water_depth`; "
                         "give it once (drawn: drop `water_depth` from [vessel])")
    return True


def refuse_varied_particulars(scn: Scenario, source: str) -> None:
    """Refuse batch keys ``vessel.particulars.*`` in a ``[simulation]`` scenario.

    Its runs share one model's compiled right-hand side with a parameter row per run, and the
    wind and wave loads take their windage and hull from the ship's particulars once: a run's
    own particulars would have to re-estimate the ship and re-derive those per run. A
    ``[maneuver]`` scenario draws them (one estimated ship per sample).

    Parameters
    ----------
    scn : Scenario
        Validated ``[simulation]`` scenario.
    source : str
        The scenario file (in error messages).

    Raises
    ------
    ScenarioError
        At ``batch.grid.<key>`` or ``batch.monte_carlo.<key>``.
    """
    mc = scn.batch.monte_carlo
    keys = [("grid", k) for k in scn.batch.grid] + [("monte_carlo", k)
                                                     for k in drawn_kinds(mc, source)]
    for where, key in keys:
        if key.startswith(PREFIX):
            raise at_key(source, f"batch.{where}.{key}",
                         "the particulars vary only in a [maneuver] scenario (one estimated "
                         "ship per Monte-Carlo sample); a [simulation] scenario runs the one "
                         "ship of [vessel.particulars] (vary its estimated coefficients as "
                         "vessel.params.<name>, or write a scenario per design)")


@dataclasses.dataclass(frozen=True, eq=False)
class EstimatedSamples:
    """The ships of Monte-Carlo samples of ``[vessel.particulars]``: each sample's particulars
    (the scenario's, with that sample's draws) estimated as a ship.

    Attributes
    ----------
    particulars : mapping
        ``[vessel.particulars]`` as written.
    water_depth : float or None
        ``[vessel] water_depth`` [m] (None: deep water, or the particulars' own).
    source : str
        The scenario file (in error messages).
    """

    particulars: Mapping[str, Any]
    water_depth: float | None
    source: str

    def values(self, drawn: Mapping[str, float]) -> dict[str, Any]:
        """A sample's particulars: the scenario's with the drawn ones (a drawn angle replaces
        the written one in either unit).

        Parameters
        ----------
        drawn : mapping of str to float
            The sample's drawn values by key path (keys other than particulars are ignored).

        Returns
        -------
        dict
        """
        out = dict(self.particulars)
        for key, value in drawn.items():
            if not key.startswith(PREFIX):
                continue
            name = key[len(PREFIX):]
            base = name[:-4] if name.endswith("_deg") else name
            out.pop(base, None)
            out.pop(f"{base}_deg", None)
            out[name] = float(value)
        return out

    def ships(self, drawn: Mapping[str, np.ndarray], indices: Sequence[int]) -> list[Any]:
        """The estimated ships of the samples ``indices``.

        Parameters
        ----------
        drawn : mapping of str to ndarray
            The drawn values of these samples by key path (:meth:`ManeuverJob.draws`).
        indices : sequence of int
            The samples' indices (in error messages).

        Returns
        -------
        list of Ship

        Raises
        ------
        ScenarioError
            ``[batch.monte_carlo] sample i: `vessel.particulars.<key>` ...`` for a sample whose
            particulars are not physical or cannot be estimated, with its drawn particulars.
        """
        out = []
        per_sample: list[list[warnings.WarningMessage]] = []
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            for n, i in enumerate(indices):
                sample = {k: float(v[n]) for k, v in drawn.items() if k.startswith(PREFIX)}
                values = self.values(sample)
                first = len(caught)
                try:
                    out.append(_design_and_ship(values, self.water_depth))
                except (ValueError, ArithmeticError) as exc:
                    key = _key(exc, values, self.water_depth is not None)
                    shown = ", ".join(f"{k[len(PREFIX):]} = {v:.6g}" for k, v in sample.items())
                    raise ScenarioError(
                        f"{self.source}: [batch.monte_carlo] sample {i}: `{key}` "
                        f"{_reason(exc, values, key)} (its drawn particulars: {shown})") from None
                per_sample.append(caught[first:])
        aggregate_warnings(per_sample)
        return out


_SAID = re.compile(r"^(?P<head>.*? used outside [^:]*): (?P<body>.*)$", re.DOTALL)
_NUMBER = re.compile(r"^(?P<before>.*?=\s*`?)(?P<value>[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)"
                     r"(?P<after>.*)$", re.DOTALL)


def aggregate_warnings(per_sample: Sequence[Sequence[warnings.WarningMessage]]) -> None:
    """Say the warnings of many samples once: a regression's range warning once per formula,
    with the number of samples it concerns and the range of the values outside its data
    ("Kijima et al. (1990) hull derivatives used outside the range of its data in 37 of 200
    samples: L/B = 8.1..8.6 outside 4..8"); any other warning once.

    Parameters
    ----------
    per_sample : sequence of sequences of warnings.WarningMessage
        The warnings recorded while each sample was made (one entry per sample).
    """
    n = len(per_sample)
    formulas: dict[str, dict[str, Any]] = {}
    others: dict[tuple[str, type[Warning]], None] = {}
    for i, caught in enumerate(per_sample):
        for w in caught:
            text = str(w.message)
            said = _SAID.match(text) if issubclass(w.category, ValidityRangeWarning) else None
            if said is None or n == 1:
                others[(text, w.category)] = None
                continue
            entry = formulas.setdefault(said["head"], {"samples": set(), "parts": {}})
            entry["samples"].add(i)
            for part in said["body"].split("; "):
                number = _NUMBER.match(part)
                if number is None:
                    entry["parts"].setdefault((part, ""), []).append((i, math.nan))
                    continue
                template = (number["before"], number["after"])
                entry["parts"].setdefault(template, []).append((i, float(number["value"])))
    for (text, category) in others:
        warnings.warn(text, category, stacklevel=3)
    for head, entry in formulas.items():
        k = len(entry["samples"])
        parts = []
        for (before, after), found in entry["parts"].items():
            values = [v for _, v in found if not math.isnan(v)]
            if not values:
                parts.append(before)
            else:
                lo, hi = min(values), max(values)
                shown = f"{lo:.4g}" if lo == hi else f"{lo:.4g}..{hi:.4g}"
                parts.append(f"{before}{shown}{after}")
            count = len({i for i, _ in found})
            if count != k:
                parts[-1] += f" (in {count} of them)"
        warnings.warn(f"{head} in {k} of {n} samples: " + "; ".join(parts),
                      ValidityRangeWarning, stacklevel=3)
