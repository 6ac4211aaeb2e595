"""The one-run solves by ``scipy.optimize``: the fallback inside the equilibrium solvers.

The public functions of :mod:`seahelm.analysis.equilibria.equilibrium` solve a run as a batch of one
with the batched Newton solvers (:mod:`seahelm.analysis.equilibria.batch_equilibrium`,
:mod:`seahelm.analysis.equilibria.batch_steady_turn`); a run they do not solve, a model with roll
(its heel balanced in every evaluation) and what has no batch form yet (the spiral curve δ(r),
the straight-run speed at an rps) are solved here, one run at a time, by
``scipy.optimize.root`` / ``brentq`` on the model's own derivative, and an equation without a
solution raises :class:`~seahelm.analysis.equilibria.plant.EquilibriumError` with what it
was solving for. The batched solvers' own fallback (``steady_turns(fallback=True)``) is this
module too, so neither imports the public one-run module.

Constant-speed models (no surge equation) are handed to
:class:`~seahelm.analysis.equilibria.constant_speed.ConstantSpeedPlant`
(:func:`constant_speed_plant`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ...errors import ParameterError
from ...registry import model_for_params
from ...vessels.base import VesselModel
from .constant_speed import ConstantSpeedPlant, is_constant_speed
from .plant import EquilibriumError, Plant, resolve_params

# scipy.optimize (0.2 s to import) is imported inside the functions that use it

__all__ = ["solve", "self_propulsion", "turn_fields", "constant_speed_plant"]


def solve(plant: Plant, fixed: dict[str, float], unknowns: tuple[str, ...],
           guess: np.ndarray, rps: float | None) -> np.ndarray:
    """u̇ = v̇ = ṙ = 0 for three of (surge, v, r, rudder) of the plant's one run, the others
    ``fixed`` (``scipy.optimize.root``, scaled: (u, v) by U_ref, r by U_ref/L).

    Parameters
    ----------
    plant : Plant
        A batch of one.
    fixed : dict of str to float
        The given ones of ``surge`` [m/s], ``v`` [m/s], ``r`` [rad/s], ``rudder`` [rad].
    unknowns : tuple of str
        The three solved for.
    guess : numpy.ndarray
        Their start (SI units).
    rps : float or None
        Propeller rps [1/s].

    Returns
    -------
    numpy.ndarray
        The unknowns (SI units).

    Raises
    ------
    EquilibriumError
        If the residual is not below 1e-9 (what was solved for, with what, and scipy's
        message).
    """
    from scipy.optimize import root

    u_ref, length = float(plant.u_ref[0]), float(plant.length[0])
    scale = {"surge": u_ref, "v": u_ref, "r": u_ref / length, "rudder": 1.0}
    acc_scale = np.array([1.0, 1.0, 1.0 / length]) * u_ref ** 2 / length
    s = np.array([scale[k] for k in unknowns])

    def residual(z: np.ndarray) -> np.ndarray:
        values = dict(fixed)
        values.update(zip(unknowns, z * s))
        acc = plant.acceleration(values["surge"], values["v"], values["r"],
                                 values["rudder"], rps)
        return acc / acc_scale

    sol = root(residual, np.asarray(guess, dtype=float) / s, method="hybr",
               options={"xtol": 1e-13})
    res = residual(sol.x)
    if not np.all(np.isfinite(res)) or np.max(np.abs(res)) > 1e-9:
        raise EquilibriumError(
            f"no equilibrium found for {', '.join(unknowns)} with "
            + ", ".join(f"{k} = {v:.6g}" for k, v in fixed.items())
            + (f", rps = {rps:.6g} [1/s]" if rps is not None else "")
            + f" ({sol.message.strip()}; residual {np.max(np.abs(res)):.3g})")
    return sol.x * s


def self_propulsion(plant: Plant, U: float, max_rps: float) -> float:
    """The self-propulsion rps at ``U`` by ``scipy.optimize.brentq`` (bracketed from n = 0
    upwards by doubling), or the EquilibriumError saying why there is none.

    Parameters
    ----------
    plant : Plant
        A batch of one, with a ``propeller_rps`` input.
    U : float
        Straight-run speed [m/s].
    max_rps : float
        Upper end of the search [1/s].

    Returns
    -------
    float
        rps [1/s].
    """
    from scipy.optimize import brentq

    def surge_acc(n: float) -> float:
        return float(plant.acceleration(U, 0.0, 0.0, 0.0, n)[0])

    if surge_acc(0.0) >= 0.0:
        raise EquilibriumError(
            f"at `speed` = {U!r} [m/s] the surge force is not negative with the propeller "
            "stopped: no self-propulsion point")
    hi = 1.0
    while surge_acc(hi) <= 0.0:
        if hi >= max_rps:
            raise EquilibriumError(
                f"no propeller rps in (0, {max_rps:g}] [1/s] gives zero surge force at "
                f"`speed` = {U!r} [m/s]")
        hi = min(2.0 * hi, max_rps)
    return brentq(surge_acc, 0.0, hi, xtol=1e-14, rtol=4 * np.finfo(float).eps)


def turn_fields(plant: Plant, deltas: np.ndarray, n: float | None,
                rudder_step: float) -> np.ndarray:
    """The :class:`~seahelm.analysis.equilibria.equilibrium.SteadyTurn` fields (6, len(deltas))
    of the plant's one run at the rudder angles ``deltas`` by scipy's continuation from the
    straight run, or the EquilibriumError of the first angle without a steady turn.

    Parameters
    ----------
    plant : Plant
        A batch of one.
    deltas : numpy.ndarray
        Rudder angles δ [rad].
    n : float or None
        Propeller rps [1/s].
    rudder_step : float
        Largest rudder change per continuation step [rad].

    Returns
    -------
    numpy.ndarray, shape (6, len(deltas))
    """
    trim = solve(plant, {"r": 0.0}, ("surge", "v", "rudder"),
                 np.array([float(plant.u_ref[0]), 0.0, 0.0]), n)
    fields = np.full((6, len(deltas)), np.nan)
    for i, delta in enumerate(deltas):
        surge, v, r = _turn(plant, trim, float(delta), n, float(rudder_step))
        if not surge > 0.0:
            raise EquilibriumError(
                f"the steady turn at `rudder` = {delta!r} [rad] ({math.degrees(delta):.4g} deg) "
                f"has surge speed {surge:.6g} [m/s] <= 0")
        y = plant.model.outputs(0.0, plant.state(surge, v, r), plant.inputs(float(delta), n),
                                plant.params[0])
        speed = y[plant.model.output_index("speed")]
        fields[:, i] = (
            y[plant.model.output_index("surge_speed")], v, r, speed,
            y[plant.model.output_index("drift_angle")], speed / abs(r) if r != 0.0 else np.inf)
    return fields


def _turn(plant: Plant, trim: np.ndarray, delta: float, n: float | None,
          rudder_step: float) -> tuple[float, float, float]:
    """(surge, v, r) of the steady turn at ``delta`` by continuation (see
    :func:`~seahelm.analysis.equilibria.equilibrium.steady_turn`)."""
    from scipy.optimize import brentq

    u0, v0, d0 = (float(c) for c in trim)
    if delta == d0:
        return u0, v0, 0.0
    sign = 1.0 if delta > d0 else -1.0
    r_step = 0.01 * float(plant.u_ref[0]) / float(plant.length[0])
    free_r = ("surge", "v", "rudder")
    prev_r, prev = 0.0, np.array([u0, v0, d0])
    for k in range(1, 301):
        r = sign * k * r_step
        try:
            z = solve(plant, {"r": r}, free_r, prev, n)
        except EquilibriumError:
            z = None
        if z is None or abs(z[2] - prev[2]) > rudder_step:
            return _turn_in_rudder(plant, prev[2], delta, (prev[0], prev[1], prev_r), n,
                                   rudder_step)
        if sign * (z[2] - delta) >= 0.0:
            start = prev.copy()

            def offset(rr: float) -> float:
                return float(solve(plant, {"r": rr}, free_r, start, n)[2] - delta)

            r_star = brentq(offset, prev_r, r, xtol=1e-13 * r_step, rtol=1e-14)
            zs = solve(plant, {"r": r_star}, free_r, start, n)
            try:
                return tuple(float(c) for c in solve(plant, 
                    {"rudder": delta}, ("surge", "v", "r"), np.array([zs[0], zs[1], r_star]),
                    n))
            except EquilibriumError:  # pragma: no cover - brentq's point is within 1e-13
                return float(zs[0]), float(zs[1]), float(r_star)
        prev_r, prev = r, z
    raise EquilibriumError(
        f"no steady turn found at `rudder` = {delta!r} [rad] ({math.degrees(delta):.4g} deg) "
        "up to r L/U_0 = 3")


def _turn_in_rudder(plant: Plant, d_from: float, d_to: float, guess: tuple[float, ...],
                    n: float | None, rudder_step: float) -> tuple[float, float, float]:
    """Continue (surge, v, r) in the rudder angle from ``d_from`` to ``d_to``."""
    z = np.asarray(guess, dtype=float)
    steps = max(1, int(math.ceil(abs(d_to - d_from) / rudder_step)))
    for d_k in np.linspace(d_from, d_to, steps + 1)[1:]:
        z = solve(plant, {"rudder": float(d_k)}, ("surge", "v", "r"), z, n)
    return float(z[0]), float(z[1]), float(z[2])


def constant_speed_plant(value: Any, model: VesselModel | None,
                    rps: Any = None) -> ConstantSpeedPlant | None:
    """The solver of a constant-speed model
    (:mod:`seahelm.analysis.equilibria.constant_speed`), None for another model (whose
    :class:`~seahelm.analysis.equilibria.plant.Plant` then says what it lacks).

    Parameters
    ----------
    value : Params, Ship, str or path
        Parameter set, ship, catalog name or ship file path.
    model : VesselModel or None
        The model (default: the ship's or the parameter type's).
    rps : float, optional
        Must be None (such a model has no propeller input).

    Returns
    -------
    ConstantSpeedPlant or None

    Raises
    ------
    ParameterError
        If ``rps`` is given for a constant-speed model.
    """
    params, ship_model = resolve_params(value)
    model = model or ship_model or model_for_params(type(params))
    if model is None or not is_constant_speed(model) or not isinstance(params,
                                                                      model.params_type):
        return None
    if rps is not None:
        raise ParameterError(f": model '{model.name}' has no propeller_rps input, got {rps!r}",
                             field="rps", unit="1/s", value=rps)
    return ConstantSpeedPlant(params, model, EquilibriumError)
