"""Equilibria of 3-DOF ship models: self-propulsion point, steady turn, straight approach.

All three solve the model's own right-hand side (:meth:`VesselModel.derivative`, numpy), so
they hold for any model that declares the usual signals by name:

* states ``sway_speed``, ``yaw_rate`` and either ``surge_speed`` (MMG) or
  ``surge_perturbation`` about a parameter ``nominal_speed`` (Mariner);
* inputs ``rudder_angle`` and, optionally, ``propeller_rps``;
* outputs ``surge_speed``, ``speed`` and ``drift_angle``.

:func:`self_propulsion_rps`
    the propeller rps of a straight run at a given speed: zero surge force with v = r = 0,
    δ = 0 (``scipy.optimize.brentq`` on the surge equation, one speed after the other).
:func:`steady_turn`
    (u, v, r, U, β, R) of the steady turn at a rudder angle (and rps): u̇ = v̇ = ṙ = 0 by
    ``scipy.optimize.root``, continued from the straight run in rudder steps of at most
    ``rudder_step`` so that every solve starts from a nearby solution (the first step is the
    linear estimate's neighbourhood). Either rudder sign; an asymmetric ship (KVLCC2's γ_R by
    side, the Mariner's Y_0/N_0) turns differently to port and starboard.
:func:`approach_state`
    the initial state and inputs of a steady straight approach at speed U_0 (MMG: surge U_0
    at the self-propulsion rps; Mariner: zero surge perturbation), optionally trimmed with
    the rudder to zero yaw rate.
:func:`straight_run_speed`
    the inverse of :func:`self_propulsion_rps`: the speed of the straight run at a given rps.
:func:`steady_turn_state`
    the state vector and inputs of the steady turn at a rudder angle (the start of a pull-out).
:func:`rudder_for_yaw_rate`
    the spiral curve δ(r) point by point: the rudder angle (and u, v) of the steady turn with a
    prescribed yaw rate, by continuation in r from the straight run — the equilibria that
    Bech's reverse spiral measures, including the branch that is unstable at fixed rudder.

Inputs are validated at the boundary (:class:`~seahelm.errors.ParameterError` naming the
argument, its unit and the value); an equation without a solution raises
:class:`EquilibriumError`.

References
----------
Yasukawa, H., Yoshimura, Y. (2015). Introduction of MMG standard method for ship maneuvering
predictions. J. Mar. Sci. Technol. 20, 37–52.
Chislett, M. S., Strøm-Tejsen, J. (1965). Planar motion mechanism tests and full-scale steering
and manoeuvring predictions for a Mariner class vessel. Tech. Report Hy-5, Lyngby.
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import numpy as np

from ..._validate import as_float_array, check_finite, check_positive, check_range
from ...errors import ParameterError
from ...vessels.base import VesselModel
from . import fallback
from .approach import Approach
from .plant import EquilibriumError, Plant

# scipy.optimize (0.2 s to import) is imported inside the functions that use it

__all__ = [
    "EquilibriumError",
    "SteadyTurn",
    "SpiralCurve",
    "Approach",
    "self_propulsion_rps",
    "straight_run_speed",
    "steady_turn",
    "steady_turn_state",
    "rudder_for_yaw_rate",
    "approach_state",
]



class SteadyTurn(NamedTuple):
    """A steady turn (floats for a scalar rudder angle, arrays for an array of them)."""

    surge_speed: Any
    """Surge speed u [m/s] (total, U_0 + u for a perturbation model)."""
    sway_speed: Any
    """Sway speed v [m/s] (midship for the MMG model)."""
    yaw_rate: Any
    """Yaw rate r [rad/s] (positive to starboard)."""
    speed: Any
    """Speed U = √(u² + v²) [m/s]."""
    drift_angle: Any
    """Drift angle β = atan2(−v, u) [rad]."""
    radius: Any
    """Turning radius U/|r| of the reference point's path [m] (inf for r = 0)."""


class SpiralCurve(NamedTuple):
    """Steady turns at prescribed yaw rates (arrays of the yaw rates' shape)."""

    yaw_rate: Any
    """Yaw rate r [rad/s] (as requested)."""
    rudder: Any
    """Rudder angle δ of the steady turn [rad]."""
    surge_speed: Any
    """Surge speed u [m/s] (total)."""
    sway_speed: Any
    """Sway speed v [m/s]."""
    speed: Any
    """Speed U [m/s]."""
    drift_angle: Any
    """Drift angle β [rad]."""


# ------------------------------------------------------------------------------------------
# plumbing: which model, which signals (the one Plant of .equilibria.plant, a batch of one)
# ------------------------------------------------------------------------------------------
def _propelled_plant(model_or_params: Any, model: VesselModel | None) -> Plant:
    """The plant of a model that has a ``propeller_rps`` input (ParameterError otherwise)."""
    plant = Plant.of(model_or_params, model)
    if plant.j_rps is None:
        raise ParameterError(
            f"model '{plant.model.name}' has no input 'propeller_rps'; inputs: "
            f"{', '.join(plant.model.input_labels)}")
    return plant


def _check_rps(plant: Plant, rps: Any) -> float | None:
    if plant.j_rps is None:
        if rps is not None:
            raise ParameterError(
                f"`rps`: model '{plant.model.name}' has no propeller_rps input, got {rps!r}")
        return None
    if rps is None:
        raise ParameterError(f"`rps` [1/s] is required for model '{plant.model.name}'")
    check_positive("rps", rps, "1/s")
    return float(rps)


# ------------------------------------------------------------------------------------------
# public API
# ------------------------------------------------------------------------------------------
def self_propulsion_rps(model_or_params: Any, speed: Any, *, model: VesselModel | None = None,
                        max_rps: float = 1000.0) -> Any:
    """Propeller rps of a steady straight run at ``speed`` (zero surge force, v = r = δ = 0).

    Solves X_H + X_P + X_R = 0 (Yasukawa & Yoshimura 2015, surge equation with u̇ = 0) for the
    propeller rps n on the model's right-hand side, bracketing from n = 0 (the propeller drags:
    J_P → ∞) upwards by doubling: all speeds at once by the batched safeguarded Newton of
    :func:`~seahelm.analysis.equilibria.batch_equilibrium.approach_states` (to brentq's tolerance);
    a speed it does not solve, and a model with roll, by ``scipy.optimize.brentq``, whose
    error is the one raised.

    Parameters
    ----------
    model_or_params : Params, Ship or str
        Parameter set (e.g. :data:`~seahelm.vessels.mmg.KVLCC2_L7`), a ship, a catalog name
        (``"kvlcc2-l7"``) or a ship file path.
    speed : float or array_like
        Straight-run speed(s) [m/s], > 0.
    model : VesselModel, optional
        The model (default: the one for the parameter type, e.g. MMG for MMGParams); it must
        have a ``propeller_rps`` input.
    max_rps : float, optional
        Upper end of the search [1/s] (default 1000).

    Returns
    -------
    float or numpy.ndarray
        Propeller rps [1/s], with the shape of ``speed``.

    Raises
    ------
    ParameterError
        If ``speed`` or ``max_rps`` is not > 0, or the model has no propeller input.
    EquilibriumError
        If no rps in (0, ``max_rps``] gives zero surge force.
    """
    plant = _propelled_plant(model_or_params, model)
    speeds = as_float_array("speed", speed, "m/s")
    check_positive("speed", speeds, "m/s")
    check_positive("max_rps", max_rps, "1/s")
    flat = np.full(speeds.size, np.nan)
    if plant.heel is None and speeds.size:  # the batched Newton (a model with roll: scipy)
        from .batch_equilibrium import approach_states

        batch = approach_states(plant.model, plant.params * speeds.size, speeds.ravel(),
                                trim=False, max_rps=float(max_rps))
        flat[batch.ok] = batch.rps[batch.ok]
    for i in np.flatnonzero(~np.isfinite(flat)):  # the fallback: brentq, or its error
        flat[i] = fallback.self_propulsion(plant, float(speeds.flat[i]), float(max_rps))
    return float(flat[0]) if speeds.ndim == 0 else flat.reshape(speeds.shape)


def steady_turn(params: Any, rudder: Any, rps: float | None = None, *,
                model: VesselModel | None = None, max_rudder: float = math.radians(35.0),
                rudder_step: float = math.radians(2.5)) -> SteadyTurn:
    """The steady turn at a rudder angle: u̇ = v̇ = ṙ = 0 solved for (u, v, r).

    The three force balances are solved for all rudder angles at once by the batched damped
    Newton of :func:`~seahelm.analysis.equilibria.batch_steady_turn.steady_turns` (the same
    continuation, the same root to round-off); a rudder angle it does not solve, and a model with
    roll, by ``scipy.optimize.root``, whose error is the one raised. Each solve starts from a nearby
    solution, by continuation along the spiral curve δ(r) from the straight run:

    1. the straight run with zero yaw rate (its rudder angle δ_0 is 0 for a ship symmetric at
       rest, the trim angle for the Mariner with its Y_0/N_0 bias);
    2. the yaw rate is stepped (Δr L/U_0 = 0.01) in the direction that moves δ(r) from δ_0
       towards the requested angle, solving u̇ = v̇ = ṙ = 0 for (u, v, δ) at each r, until δ(r)
       passes the requested angle; the crossing is found by ``scipy.optimize.brentq`` on r and
       polished by solving for (u, v, r) at the requested δ;
    3. where δ(r) becomes steep (a step changes δ by more than ``rudder_step``, near the largest
       yaw rate the rudder can give), the continuation goes on in δ instead, solving for
       (u, v, r) in rudder steps of at most ``rudder_step``.

    Stepping in r first follows the branch that a turn from a straight approach reaches even
    where δ(r) is not monotonic near r = 0 (a course-unstable ship, or KVLCC2's γ_R and C_2
    switching with the sign of β_R, β_P, which put a small kink into δ(r) at the straight run):
    the first crossing is on the stable (rising) part of the curve. A plain continuation in
    δ from the straight run fails there.

    Parameters
    ----------
    params : Params, Ship or str
        Parameter set, ship, catalog name or ship file path.
    rudder : float or array_like
        Rudder angle(s) δ [rad]; positive turns to starboard.
    rps : float, optional
        Propeller rps [1/s], > 0; required for a model with a ``propeller_rps`` input (MMG),
        not allowed for one without (Mariner).
    model : VesselModel, optional
        The model (default: the one for the parameter type).
    max_rudder : float, optional
        Largest admissible |δ| [rad] (default 35°).
    rudder_step : float, optional
        Largest rudder change per continuation step [rad] (default 2.5°).

    Returns
    -------
    SteadyTurn
        Surge speed [m/s], sway speed [m/s], yaw rate [rad/s], speed [m/s], drift angle [rad]
        and turning radius [m]; floats for a scalar ``rudder``, arrays of its shape otherwise.

    Raises
    ------
    ParameterError
        If |``rudder``| > ``max_rudder``, ``rps`` ≤ 0 (or missing/not allowed), or the model
        lacks the signals named in the module docstring.
    EquilibriumError
        If the continuation fails to converge.
    """
    cs = fallback.constant_speed_plant(params, model, rps)
    if cs is not None:
        fields = cs.steady_turns(rudder, max_rudder, rudder_step)[0]
        if np.ndim(rudder) == 0:
            return SteadyTurn(*(float(f) for f in fields))
        return SteadyTurn(*fields)
    plant = Plant.of(params, model)
    check_positive("max_rudder", max_rudder, "rad")
    check_positive("rudder_step", rudder_step, "rad")
    deltas = as_float_array("rudder", rudder, "rad")
    check_range("rudder", deltas, -max_rudder, max_rudder, "rad")
    n = _check_rps(plant, rps)
    flat = np.full((6, deltas.size), np.nan)
    if plant.heel is None and deltas.size:
        from .batch_steady_turn import steady_turns

        turns = steady_turns(plant.model, plant.params[0], deltas.ravel(), n,
                             max_rudder=max_rudder, rudder_step=rudder_step, fallback=False)
        flat[:, turns.ok] = np.stack(
            [turns.surge_speed, turns.sway_speed, turns.yaw_rate, turns.speed,
             turns.drift_angle, turns.radius])[:, turns.ok]
    fields = flat.reshape((6,) + deltas.shape)
    todo = [idx for idx in np.ndindex(deltas.shape) if not np.isfinite(fields[(0,) + idx])]
    if todo:  # the fallback: scipy's continuation, or its error
        got = fallback.turn_fields(plant, np.array([deltas[idx] for idx in todo]), n,
                                   float(rudder_step))
        for k, idx in enumerate(todo):
            fields[(slice(None),) + idx] = got[:, k]
    if deltas.ndim == 0:
        return SteadyTurn(*(float(f) for f in fields))
    return SteadyTurn(*fields)


def approach_state(params: Any, speed: float | None = None, *, model: VesselModel | None = None,
                   heading: float = 0.0, trim: bool = False) -> Approach:
    """Initial state and inputs of a steady straight approach at speed U_0.

    For a model with a propeller (MMG) the surge speed is U_0 and the propeller turns at the
    self-propulsion rps (:func:`self_propulsion_rps`); for a perturbation model (Mariner) the
    surge perturbation is 0 at U_0 = ``nominal_speed``. Sway, yaw rate, position and rudder are
    zero. With ``trim=True`` the rudder angle, surge and sway speed are solved so that the run
    is an exact equilibrium with zero yaw rate (a biased model such as the Mariner needs a small
    rudder angle to keep a straight course; for the symmetric-at-zero MMG ship nothing changes).

    Solved as a batch of one by
    :func:`~seahelm.analysis.equilibria.batch_equilibrium.approach_states` (safeguarded Newton for
    the rps, damped Newton for the trim); where it finds no solution, and for a model with roll, by
    ``scipy.optimize`` (brentq, root), whose error is the one raised.

    Parameters
    ----------
    params : Params, Ship or str
        Parameter set, ship, catalog name or ship file path.
    speed : float, optional
        Approach speed U_0 [m/s] (default: ``approach_speed`` of an MMG set, ``nominal_speed``
        of the Mariner; the Mariner admits no other speed).
    model : VesselModel, optional
        The model (default: the one for the parameter type).
    heading : float, optional
        Initial heading ψ [rad] (default 0, north).
    trim : bool, optional
        Trim with the rudder to an exact straight equilibrium (default False).

    Returns
    -------
    Approach
        ``state`` (model state order) and ``inputs`` by name (``rudder_angle`` [rad], and
        ``propeller_rps`` [1/s] for a model with a propeller).

    Raises
    ------
    ParameterError
        If ``speed`` ≤ 0, or differs from the nominal speed of a perturbation model.
    EquilibriumError
        If the self-propulsion point or the trim is not found.
    """
    cs = fallback.constant_speed_plant(params, model)
    if cs is not None:  # no surge state: the model's own speed, at rest in yaw
        state, rudder = cs.approach(speed, heading=heading, trim=trim)
        return Approach(state, {"rudder_angle": rudder}, cs.speed)
    plant = Plant.of(params, model)
    U0 = float(plant.u_ref[0]) if speed is None else speed
    check_positive("speed", U0, "m/s")
    check_finite("heading", heading, "rad")
    U0 = float(U0)
    offset = float(plant.u_offset[0])
    if offset and not math.isclose(U0, offset, rel_tol=1e-12):
        raise ParameterError(
            f"`speed` must be the nominal speed U_0 = {offset!r} [m/s] of the "
            f"perturbation model '{plant.model.name}', got {U0!r}")
    if plant.heel is None:  # the batched Newton (a model with roll: scipy)
        from .batch_equilibrium import approach_states

        batch = approach_states(plant.model, plant.params, U0, trim=trim,
                                heading=float(heading))
        if batch.ok[0]:
            inputs = {"rudder_angle": float(batch.rudder[0])}
            if plant.j_rps is not None:
                inputs["propeller_rps"] = float(batch.rps[0])
            return Approach(batch.state[0], inputs, U0)
    # the fallback: scipy (brentq, root), or its error
    inputs = {"rudder_angle": 0.0}
    n = None
    if plant.j_rps is not None:
        n = float(fallback.self_propulsion(plant, U0, 1000.0))
        inputs["propeller_rps"] = n
    surge, v = U0, 0.0
    if trim:
        surge, v, delta = fallback.solve(plant, {"r": 0.0}, ("surge", "v", "rudder"),
                                 np.array([U0, 0.0, 0.0]), n)
        inputs["rudder_angle"] = float(delta)
    return Approach(plant.state(surge, v, 0.0, float(heading),
                                plant.inputs(inputs["rudder_angle"], n)), inputs, U0)


def straight_run_speed(model_or_params: Any, rps: Any, *, model: VesselModel | None = None,
                       max_speed: float | None = None) -> Any:
    """Speed of the steady straight run at a propeller rps (inverse of :func:`self_propulsion_rps`).

    Solves X_H + X_P + X_R = 0 with v = r = δ = 0 for the surge speed u with
    ``scipy.optimize.brentq``, bracketing from u → 0 (the propeller pushes) upwards by doubling
    from the parameter set's approach speed.

    Parameters
    ----------
    model_or_params : Params, Ship or str
        Parameter set, ship, catalog name or ship file path (a model with a
        ``propeller_rps`` input).
    rps : float or array_like
        Propeller rps [1/s], > 0.
    model : VesselModel, optional
        The model (default: the one for the parameter type).
    max_speed : float, optional
        Upper end of the search [m/s] (default 100 × the approach speed).

    Returns
    -------
    float or numpy.ndarray
        Speed [m/s], with the shape of ``rps``.

    Raises
    ------
    ParameterError
        If ``rps`` is not > 0 or the model has no propeller input.
    EquilibriumError
        If no speed in (0, ``max_speed``] balances the surge force.
    """
    from scipy.optimize import brentq

    plant = _propelled_plant(model_or_params, model)
    rates = as_float_array("rps", rps, "1/s")
    check_positive("rps", rates, "1/s")
    u_ref = float(plant.u_ref[0])
    top = 100.0 * u_ref if max_speed is None else max_speed
    check_positive("max_speed", top, "m/s")
    out = np.empty(rates.shape)
    for idx, n_item in np.ndenumerate(rates):
        n = float(n_item)

        def surge_acc(U: float, n: float = n) -> float:
            return float(plant.acceleration(U, 0.0, 0.0, 0.0, n)[0])

        lo = 1e-6 * u_ref
        if surge_acc(lo) <= 0.0:
            raise EquilibriumError(
                f"at `rps` = {n!r} [1/s] the propeller does not push the ship ahead from rest")
        hi = u_ref
        while surge_acc(hi) >= 0.0:
            if hi >= top:
                raise EquilibriumError(
                    f"no speed in (0, {top:g}] [m/s] balances the surge force at `rps` = {n!r} "
                    "[1/s]")
            hi = min(2.0 * hi, float(top))
        out[idx] = brentq(surge_acc, lo, hi, xtol=1e-14, rtol=4 * np.finfo(float).eps)
    return float(out) if out.ndim == 0 else out


def steady_turn_state(params: Any, rudder: float, rps: float | None = None, *,
                      model: VesselModel | None = None, heading: float = 0.0,
                      max_rudder: float = math.radians(35.0)) -> Approach:
    """State vector and inputs of the steady turn at a rudder angle (e.g. to start a pull-out).

    The turn is :func:`steady_turn`'s; the position is the origin and the heading ``heading``.

    Parameters
    ----------
    params : Params, Ship or str
        Parameter set, ship, catalog name or ship file path.
    rudder : float
        Rudder angle δ [rad]; positive turns to starboard.
    rps : float, optional
        Propeller rps [1/s] (required for a model with a propeller input, not allowed
        without one).
    model : VesselModel, optional
        The model (default: the one for the parameter type).
    heading : float, optional
        Heading ψ of the returned state [rad] (default 0).
    max_rudder : float, optional
        Largest admissible |δ| [rad] (default 35°).

    Returns
    -------
    Approach
        ``state`` (model state order) and ``inputs`` by name (``rudder_angle`` [rad], and
        ``propeller_rps`` [1/s] for a model with a propeller).

    Raises
    ------
    ParameterError
        As :func:`steady_turn`; also if ``rudder`` is not a scalar.
    EquilibriumError
        If the steady turn is not found.
    """
    if np.ndim(rudder) != 0:
        raise ParameterError(f"`rudder` must be a scalar [rad], got shape {np.shape(rudder)}")
    check_finite("heading", heading, "rad")
    cs = fallback.constant_speed_plant(params, model, rps)
    if cs is not None:
        states = cs.steady_turns(rudder, max_rudder, math.radians(2.5))[1]
        return Approach(cs.state(states, float(heading)), {"rudder_angle": float(rudder)},
                        cs.speed)
    plant = Plant.of(params, model)
    turn = steady_turn(plant.params[0], rudder, rps, model=plant.model, max_rudder=max_rudder)
    n = _check_rps(plant, rps)
    inputs = {"rudder_angle": float(rudder)}
    if n is not None:
        inputs["propeller_rps"] = n
    return Approach(plant.state(turn.surge_speed, turn.sway_speed, turn.yaw_rate,
                                float(heading), plant.inputs(float(rudder), n)), inputs,
                    turn.speed)


def rudder_for_yaw_rate(params: Any, yaw_rate: Any, rps: float | None = None, *,
                        model: VesselModel | None = None) -> SpiralCurve:
    """The spiral curve δ(r): rudder angle, surge and sway of the steady turn at each yaw rate.

    For each prescribed yaw rate r the three force balances u̇ = v̇ = ṙ = 0 are solved for
    (u, v, δ) by ``scipy.optimize.root``, continued from the straight run (r = 0, the trim
    rudder angle) outwards to each side in steps of at most Δr L/U_0 = 0.01. A prescribed yaw
    rate always has one such equilibrium, also where the ship is course-unstable and a fixed
    rudder angle has three: this is what Bech's reverse spiral test measures with a yaw-rate
    controller, without the transients.

    Parameters
    ----------
    params : Params, Ship or str
        Parameter set, ship, catalog name or ship file path.
    yaw_rate : float or array_like
        Yaw rates r [rad/s] (any order, both signs).
    rps : float, optional
        Propeller rps [1/s] (required for a model with a propeller input, not allowed
        without one).
    model : VesselModel, optional
        The model (default: the one for the parameter type).

    Returns
    -------
    SpiralCurve
        Yaw rate [rad/s], rudder angle [rad], surge speed [m/s], sway speed [m/s], speed [m/s]
        and drift angle [rad]; floats for a scalar ``yaw_rate``, arrays of its shape otherwise.

    Raises
    ------
    ParameterError
        If ``yaw_rate`` is not finite, or ``rps`` is missing/not allowed/not > 0.
    EquilibriumError
        If the continuation fails to converge (e.g. a yaw rate beyond what the hull forces can
        balance).
    """
    rates = as_float_array("yaw_rate", yaw_rate, "rad/s")
    cs = fallback.constant_speed_plant(params, model, rps)
    if cs is not None:
        fields = cs.spiral(rates)
        if rates.ndim == 0:
            return SpiralCurve(*(float(f[0]) for f in fields))
        return SpiralCurve(*(f.reshape(rates.shape) for f in fields))
    plant = Plant.of(params, model)
    n = _check_rps(plant, rps)
    free = ("surge", "v", "rudder")
    u_ref = float(plant.u_ref[0])
    r_step = 0.01 * u_ref / float(plant.length[0])
    trim = fallback.solve(plant, {"r": 0.0}, free, np.array([u_ref, 0.0, 0.0]), n)
    flat = rates.ravel()
    sol = np.full((flat.size, 3), np.nan)
    for i in np.flatnonzero(flat == 0.0):
        sol[i] = trim
    for sign in (1.0, -1.0):
        order = [int(i) for i in np.argsort(np.abs(flat)) if sign * flat[i] > 0.0]
        prev_r, z = 0.0, trim.copy()
        for i in order:
            target = float(flat[i])
            steps = max(1, int(math.ceil(abs(target - prev_r) / r_step)))
            for rr in np.linspace(prev_r, target, steps + 1)[1:]:
                z = fallback.solve(plant, {"r": float(rr)}, free, z, n)
            prev_r = target
            sol[i] = z
    fields = np.full((6, flat.size), np.nan)
    for i in range(flat.size):
        surge, v, delta = sol[i]
        y = plant.model.outputs(0.0, plant.state(surge, v, float(flat[i])),
                                plant.inputs(float(delta), n), plant.params[0])
        fields[:, i] = (flat[i], delta, y[plant.model.output_index("surge_speed")], v,
                        y[plant.model.output_index("speed")],
                        y[plant.model.output_index("drift_angle")])
    if rates.ndim == 0:
        return SpiralCurve(*(float(f[0]) for f in fields))
    return SpiralCurve(*(f.reshape(rates.shape) for f in fields))
