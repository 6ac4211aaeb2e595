"""IMO Resolution MSC.137(76) (Standards for Ship Manoeuvrability, 2002): the check of a model.

:func:`imo_check` runs, for one ship at its test speed V, in two compiled batches:

* turning circles with 35° rudder (or the steering gear's maximum, if smaller) and the initial
  turning test with 10° rudder, to both sides (:func:`~seahelm.analysis.maneuvers.turning_circle`);
* the 10°/10° and 20°/20° zig-zags, first execute to both sides
  (:func:`~seahelm.analysis.maneuvers.zigzag`);
* for a ship that can stop, the full-astern stopping test with the rudder amidships
  (:func:`~seahelm.analysis.maneuvers.crash_stop`);

and compares with the criteria of the resolution (L the ship length [m], V the test speed
[m/s]):

turning ability
    advance ≤ 4.5 L and tactical diameter ≤ 5 L (35° rudder, both sides);
initial turning ability
    ≤ 2.5 L travelled by the time the heading has changed 10° (10° rudder);
10°/10° zig-zag, first overshoot
    ≤ 10° if L/V < 10 s; ≤ 5° + ½ (L/V) deg if 10 s ≤ L/V < 30 s; ≤ 20° if L/V ≥ 30 s
    (:func:`imo_overshoot_limits`, L/V in seconds in the formulas);
10°/10° zig-zag, second overshoot
    ≤ 25° if L/V < 10 s; ≤ 17.5° + 0.75 (L/V) deg if 10 s ≤ L/V < 30 s; ≤ 40° if L/V ≥ 30 s;
20°/20° zig-zag, first overshoot
    ≤ 25°;
stopping ability
    track reach in the full-astern stopping test ≤ 15 L.

Each criterion is reported per side with its value, limit, margin (limit − value: positive
passes) and status ``"pass"``, ``"fail"`` or ``"not evaluated"``. A metric the run did not
reach (NaN) fails, with the run's message as the note. **Stopping is not evaluated**: the
models have no astern propulsion — the MMG standard method covers ahead motion only (its
surge speed is bounded below by 0, going astern ends the run as out of bounds) and the Mariner
model has no propeller input — and seahelm does not invent one.

A constant-speed steering model (Nomoto 1 or 2, Voitkunsky; :mod:`.constant_speed`) is checked
at its own speed, which does not change in the manoeuvres: turning, initial turning and the
zig-zags are evaluated, and the report says that the speed is constant (no speed loss).

The "distance travelled" of the initial turning test is taken along the track of the midship
point (the chord sum of :func:`~seahelm.analysis.maneuvers.track_distance`). The test speed V
is the approach speed used (default: the parameter set's test speed); the resolution asks for
at least 90 % of the speed at 85 % of the maximum engine output, which the models do not
know. The resolution applies to ships of 100 m and over; for a model-scale parameter set
(e.g. the KVLCC2 L7 model, 7 m) the report says so, and L/V is the model's own (Froude scaling
keeps lengths in L and angles, but not L/V, which grows with the square root of the scale).

References
----------
IMO (2002). Resolution MSC.137(76), Standards for Ship Manoeuvrability. IMO (2002).
MSC/Circ.1053, Explanatory notes to the Standards for Ship Manoeuvrability.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any, NamedTuple

import numpy as np

from ..._validate import as_float_array
from ...errors import ParameterError
from ...simulation.compile_ahead import CompileAhead
from ..equilibria.constant_speed import is_constant_speed
from ..maneuvers import (
    ManeuverResult,
    crash_stop,
    maneuver_ship,
    stopping_ship,
    turning_circle,
    zigzag,
)

__all__ = [
    "ADVANCE_LIMIT",
    "TACTICAL_DIAMETER_LIMIT",
    "INITIAL_TURNING_LIMIT",
    "STOPPING_LIMIT",
    "ZIGZAG_20_FIRST_OVERSHOOT_LIMIT",
    "OvershootLimits",
    "ImoCriterion",
    "ImoReport",
    "imo_overshoot_limits",
    "imo_check",
]

#: Advance ≤ 4.5 L (turning ability).
ADVANCE_LIMIT = 4.5
#: Tactical diameter ≤ 5 L (turning ability).
TACTICAL_DIAMETER_LIMIT = 5.0
#: Distance travelled to a 10° heading change with 10° rudder ≤ 2.5 L (initial turning).
INITIAL_TURNING_LIMIT = 2.5
#: Track reach of the full-astern stopping test ≤ 15 L.
STOPPING_LIMIT = 15.0
#: First overshoot of the 20°/20° zig-zag ≤ 25° [rad].
ZIGZAG_20_FIRST_OVERSHOOT_LIMIT = math.radians(25.0)

_SIDES = {1: "starboard", -1: "port"}


class OvershootLimits(NamedTuple):
    """Overshoot limits of the 10°/10° zig-zag [rad] (floats or arrays of L/V's shape)."""

    first: Any
    """Limit of the first overshoot angle [rad]."""
    second: Any
    """Limit of the second overshoot angle [rad]."""


def imo_overshoot_limits(L_over_V: Any) -> OvershootLimits:
    """Limits of the first and second overshoot of the 10°/10° zig-zag, MSC.137(76).

    First overshoot: 10° if L/V < 10 s; 5° + ½ (L/V) deg if 10 s ≤ L/V < 30 s; 20° if
    L/V ≥ 30 s. Second overshoot: 25° if L/V < 10 s; 17.5° + 0.75 (L/V) deg if
    10 s ≤ L/V < 30 s; 40° if L/V ≥ 30 s (L/V in seconds in the formulas). Both are continuous
    at 10 s and 30 s.

    Parameters
    ----------
    L_over_V : float or array_like
        Ship length over test speed L/V [s], > 0.

    Returns
    -------
    OvershootLimits
        ``first`` and ``second`` [rad]; floats for a scalar, arrays of its shape otherwise.

    Raises
    ------
    ParameterError
        If ``L_over_V`` is not finite and > 0.
    """
    lv = as_float_array("L_over_V", L_over_V, "s")
    if not np.all(lv > 0):
        raise ParameterError(f"must be > 0 [s], got {L_over_V!r}", field='L_over_V')
    first = np.where(lv < 10.0, 10.0, np.where(lv < 30.0, 5.0 + 0.5 * lv, 20.0))
    second = np.where(lv < 10.0, 25.0, np.where(lv < 30.0, 17.5 + 0.75 * lv, 40.0))
    first, second = np.radians(first), np.radians(second)
    if lv.ndim == 0:
        return OvershootLimits(float(first), float(second))
    return OvershootLimits(first, second)


@dataclasses.dataclass(frozen=True)
class ImoCriterion:
    """One criterion of MSC.137(76) for one side.

    Attributes
    ----------
    ability : str
        ``"turning"``, ``"initial turning"``, ``"10/10 zig-zag"``, ``"20/20 zig-zag"`` or
        ``"stopping"``.
    criterion : str
        What is measured, e.g. ``"advance"``, ``"first overshoot"``.
    side : str
        ``"starboard"``, ``"port"`` (first execute, for a zig-zag) or ``"-"``.
    value, limit, margin : float
        Measured value, limit and limit − value (NaN when not evaluated or not reached), in
        ``unit``.
    unit : str
        ``"L"`` (ship lengths) or ``"rad"``.
    status : str
        ``"pass"``, ``"fail"`` or ``"not evaluated"``.
    note : str
        Why not evaluated, what was not reached, or "".
    """

    ability: str
    criterion: str
    side: str
    value: float
    limit: float
    margin: float
    unit: str
    status: str
    note: str = ""

    def as_dict(self) -> dict[str, Any]:
        """The criterion as a plain dict (for JSON).

        Returns
        -------
        dict
        """
        return dataclasses.asdict(self)


@dataclasses.dataclass(frozen=True, eq=False)
class ImoReport:
    """The MSC.137(76) check of one ship.

    Attributes
    ----------
    ship : str
        Ship name.
    length : float
        Ship length L [m].
    speed : float
        Test speed V [m/s] (the approach speed).
    L_over_V : float
        L/V [s].
    criteria : tuple of ImoCriterion
        Every criterion, both sides.
    notes : tuple of str
        Conditions of the check (speed, rudder angle, applicability).
    turning : ManeuverResult
        The 35° turning circles and 10° initial turning runs (``rudder`` × ``side``).
    zigzag : ManeuverResult
        The 10/10 and 20/20 zig-zags (``pair`` × ``side``).
    stopping : ManeuverResult or None
        The full-astern stopping test (None for a ship that cannot stop).
    """

    ship: str
    length: float
    speed: float
    L_over_V: float
    criteria: tuple[ImoCriterion, ...]
    notes: tuple[str, ...]
    turning: ManeuverResult
    zigzag: ManeuverResult
    stopping: ManeuverResult | None = None

    def _summary(self) -> tuple[str, list[tuple[str, object]]]:
        counts = {s: sum(c.status == s for c in self.criteria)
                  for s in ("pass", "fail", "not evaluated")}
        verdict = "PASSED" if self.passed else "FAILED"
        title = (f"ImoReport: {self.ship}, {verdict} ({counts['pass']} pass, "
                 f"{counts['fail']} fail, {counts['not evaluated']} not evaluated)")
        rows: list[tuple[str, object]] = [
            ("ship", f"L = {self.length:g} m, V = {self.speed:.4g} m/s, "
                     f"L/V = {self.L_over_V:.3g} s")]
        groups: dict[str, list[str]] = {}
        for c in self.criteria:
            scale, unit = (math.degrees(1.0), "°") if c.unit == "rad" else (1.0, f" {c.unit}")
            value = ("—" if not np.isfinite(c.value) else f"{c.value * scale:.3g}{unit}")
            side = "" if c.side in ("-", "") else f"{c.side} "
            groups.setdefault(f"{c.ability}: {c.criterion}", []).append(
                f"{side}{value} {c.status}")
        limit = {f"{c.ability}: {c.criterion}": c for c in self.criteria}
        for key, entries in groups.items():
            c = limit[key]
            scale, unit = (math.degrees(1.0), "°") if c.unit == "rad" else (1.0, f" {c.unit}")
            bound = f" (limit {c.limit * scale:.3g}{unit})" if np.isfinite(c.limit) else ""
            rows.append((key, "; ".join(entries) + bound))
        rows.append(("runs", ", ".join(n for n in ("turning", "zigzag", "stopping")
                                       if getattr(self, n) is not None)
                     + " (a ManeuverResult each); to_dict() for JSON"))
        if self.notes:
            rows.append(("notes", f"{len(self.notes)} (.notes)"))
        return title, rows

    def __repr__(self) -> str:
        from ..._repr import summary_text

        return summary_text(*self._summary())

    def _repr_html_(self) -> str:
        from ..._repr import summary_html

        return summary_html(*self._summary())

    @property
    def passed(self) -> bool:
        """True if every evaluated criterion passes (the stopping criterion counts where it is
        evaluated)."""
        return all(c.status == "pass" for c in self.criteria if c.status != "not evaluated")

    def to_dict(self) -> dict[str, Any]:
        """The report as plain data (for JSON): ship, L, V, L/V, criteria, notes, passed.

        Returns
        -------
        dict
        """
        return {"ship": self.ship, "length": self.length, "speed": self.speed,
                "L_over_V": self.L_over_V, "passed": self.passed,
                "criteria": [c.as_dict() for c in self.criteria], "notes": list(self.notes)}


def _row(ability: str, criterion: str, side: str, value: float, limit: float, unit: str,
         message: str) -> ImoCriterion:
    if not math.isfinite(value):
        return ImoCriterion(ability, criterion, side, math.nan, limit, math.nan, unit, "fail",
                            f"not reached: {message}")
    margin = limit - value
    return ImoCriterion(ability, criterion, side, float(value), float(limit), float(margin),
                        unit, "pass" if margin >= 0.0 else "fail")


def _stopping_note(ship: Any) -> str:
    model = ship.model
    if "propeller_rps" not in model.input_labels:
        return (f"model '{model.name}' has no propeller input: no astern propulsion to stop "
                "with")
    states = model.state_labels
    j = states.index("surge_speed") if "surge_speed" in states else None
    if j is not None and model.state_lower[j] >= 0.0:
        return (f"model '{model.name}' covers ahead motion only (surge speed bounded below by "
                "0; the MMG standard method has no astern propeller/rudder model)")
    return f"model '{model.name}': no validated astern propulsion model"  # pragma: no cover


def imo_check(ship: Any, *, speed: float | None = None, rps: float | None = None,
              dt: float | None = None) -> ImoReport:
    """Check a ship model against IMO MSC.137(76) (see the module docstring).

    Parameters
    ----------
    ship : Ship, str (catalog name or ship file path) or Params
        The ship (:func:`~seahelm.analysis.maneuvers.maneuver_ship`), e.g. ``"kvlcc2-l7"``.
    speed : float, optional
        Test speed V [m/s] (default: the parameter set's test speed).
    rps : float, optional
        Instead of ``speed``: the propeller rps [1/s] of the approach (MMG).
    dt : float, optional
        Integration step [s] (default: :func:`~seahelm.analysis.maneuvers.default_time_step`).

    Returns
    -------
    ImoReport

    Raises
    ------
    ParameterError
        On an invalid speed, rps or step.
    """
    s = maneuver_ship(ship)
    if np.ndim(speed) or np.ndim(rps):
        raise ParameterError("[m/s] and `rps` [1/s] must be scalars for the IMO check",
        field="speed")
    hard = min(math.radians(35.0), s.max_rudder)
    ten = math.radians(10.0)
    # on a cold kernel cache the crash stop's kernel compiles in a second process meanwhile
    with CompileAhead(_warm_stopping_kernel, s, dt) as ahead:
        turning = turning_circle(s, np.array([hard, ten]), sides=(1, -1), speed=speed,
                                 rps=rps, dt=dt, heading_change=math.pi)
        zz = zigzag(s, np.radians([10.0, 20.0]), np.radians([10.0, 20.0]), sides=(1, -1),
                    speed=speed, rps=rps, dt=dt)
        ahead.wait()
    tm, zm = turning.metrics, zz.metrics
    L = s.length
    V = float(tm["approach_speed_value"].values.ravel()[0])
    lv = L / V
    limits = imo_overshoot_limits(lv)
    rows: list[ImoCriterion] = []
    for side in (1, -1):
        t35 = tm.isel(rudder=0).sel(side=side)
        t10 = tm.isel(rudder=1).sel(side=side)
        name = _SIDES[side]
        msg35, msg10 = str(t35["message"].item()), str(t10["message"].item())
        rows.append(_row("turning", "advance", name, float(t35["advance"]) / L,
                         ADVANCE_LIMIT, "L", msg35))
        rows.append(_row("turning", "tactical diameter", name,
                         float(t35["tactical_diameter"]) / L, TACTICAL_DIAMETER_LIMIT, "L",
                         msg35))
        rows.append(_row("initial turning", "distance to 10 deg heading change", name,
                         float(t10["distance_10"]) / L, INITIAL_TURNING_LIMIT, "L", msg10))
    for side in (1, -1):
        z10 = zm.isel(pair=0).sel(side=side)
        name = _SIDES[side]
        msg = str(z10["message"].item())
        rows.append(_row("10/10 zig-zag", "first overshoot", name,
                         float(z10["overshoot"].sel(n=1)), limits.first, "rad", msg))
        rows.append(_row("10/10 zig-zag", "second overshoot", name,
                         float(z10["overshoot"].sel(n=2)), limits.second, "rad", msg))
    for side in (1, -1):
        z20 = zm.isel(pair=1).sel(side=side)
        rows.append(_row("20/20 zig-zag", "first overshoot", _SIDES[side],
                         float(z20["overshoot"].sel(n=1)), ZIGZAG_20_FIRST_OVERSHOOT_LIMIT,
                         "rad", str(z20["message"].item())))
    stopping, stop_notes = _stopping(s, V, dt)
    if stopping is None:
        rows.append(ImoCriterion("stopping", "track reach (full astern)", "-", math.nan,
                                 STOPPING_LIMIT, math.nan, "L", "not evaluated",
                                 _stopping_note(s)))
    else:
        sm = stopping.metrics
        rows.append(_row("stopping", "track reach (full astern)", "-",
                         float(sm["track_reach"]) / L, STOPPING_LIMIT, "L",
                         str(sm["message"].item())))
    notes = [f"test speed V = approach speed {V:.6g} m/s; MSC.137(76) asks for >= 90 % of the "
             "speed at 85 % of the maximum engine output, which the model does not know",
             f"turning with {math.degrees(hard):g} deg rudder"
             + ("" if hard >= math.radians(35.0) - 1e-12
                else " (the steering gear's maximum, below 35 deg)"),
             f"L/V = {lv:.4g} s: 10/10 limits {math.degrees(limits.first):.4g} deg (first), "
             f"{math.degrees(limits.second):.4g} deg (second)",
             "distances at the midship point, from the rudder order; initial turning distance "
             "along the track"]
    notes.extend(stop_notes)
    if is_constant_speed(s.model):
        notes.append(f"constant-speed model '{s.model.name}': the speed stays V = {V:.6g} m/s "
                     "through every manoeuvre (no speed loss in the turn), so advance and "
                     "tactical diameter are those of a ship that keeps its speed")
    depth = float(s.water_depth)
    if math.isfinite(depth):
        notes.append(f"water depth {depth:g} m: MSC.137(76) applies in deep, unrestricted water; "
                     "the criteria are shown against the shallow-water manoeuvres for "
                     "information")
    if L < 100.0:
        notes.append(f"L = {L:g} m < 100 m: MSC.137(76) applies to ships of 100 m and over; "
                     "the criteria are applied to this parameter set as given, with its own "
                     "L/V (a Froude-scaled ship has L/V larger by the square root of the scale)")
    return ImoReport(ship=s.name, length=L, speed=V, L_over_V=lv, criteria=tuple(rows),
                     notes=tuple(notes), turning=turning, zigzag=zz, stopping=stopping)


def _warm_stopping_kernel(ship: Any, dt: float | None) -> None:
    """A crash stop of ``ship`` at its test speed, for its compiled kernel alone (run by
    :class:`~seahelm.simulation.compile_ahead.CompileAhead` in a second process)."""
    try:
        stopper = stopping_ship(ship)
    except ParameterError:
        return
    crash_stop(stopper, dt=dt)


def _stopping(ship: Any, speed: float, dt: float | None
              ) -> tuple[ManeuverResult | None, list[str]]:
    """The stopping test of a ship that can stop at the test speed, and its notes (None and
    no notes for a ship that cannot: :func:`_stopping_note` says why)."""
    try:
        stopper = stopping_ship(ship)
    except ParameterError as exc:
        if exc.field != "ship":
            raise
        return None, []
    result = crash_stop(stopper, speed=speed, dt=dt)
    m = result.metrics
    p = stopper.params
    L = ship.length
    notes = [f"stopping: full astern ordered at the test speed, rudder amidships, on model "
             f"'{stopper.model.name}'; track reach to dead in the water (surge speed <= "
             f"{m.attrs['dead_fraction']:g} V); head reach {float(m['head_reach']) / L:.4g} "
             f"L, lateral deviation {float(m['lateral_deviation']) / L:.3g} L, time "
             f"{float(m['time_dead']):.4g} s"]
    if ship.model.name != stopper.model.name:
        notes.append(f"stopping: the engine is an estimate, not the ship's data (reversal "
                     f"delay {p.reversal_delay:.3g} s, full astern {p.astern_rps:.3g} 1/s, MCR "
                     f"{p.max_power / 1e6:.4g} MW; seahelm.vessels.mmg_four_quadrant.from_mmg); "
                     "astern and at large drift the hull forces are extrapolated")
    return result, notes
