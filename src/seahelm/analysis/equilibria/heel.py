"""The steady heel of a model with a roll state, for the equilibria of :mod:`.equilibrium`.

A 4-DOF model (:mod:`seahelm.vessels.container`) is in a steady motion only when its roll is
too: roll rate p = 0 and the heel angle φ where the roll moment balances, ṗ(φ) = 0 — in a steady
turn the heel at which the restoring moment ρg∇GM φ balances the hydrodynamic, rudder and
centrifugal roll moments. :func:`heel_balance` returns, for a model with the states
``roll_rate`` and ``roll_angle``, the function that sets them so (None for a model without
roll); the equilibrium solvers then solve u̇ = v̇ = ṙ = 0 on the roll-balanced states, which is
the 4-DOF equilibrium with φ eliminated.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ...errors import ParameterError
from ...vessels.base import VesselModel

__all__ = ["heel_balance", "ROLL_STATES"]

#: The state names that mark a model with roll.
ROLL_STATES: tuple[str, str] = ("roll_rate", "roll_angle")


def heel_balance(model: VesselModel) -> Callable[[np.ndarray, np.ndarray, Any], np.ndarray] | None:
    """The roll balance of ``model``: ``balance(x, u, params) -> x`` with p = 0, ṗ(φ) = 0.

    Parameters
    ----------
    model : VesselModel
        A vessel model.

    Returns
    -------
    callable or None
        None for a model without the states ``roll_rate`` and ``roll_angle``; otherwise a
        function of the state vector (its roll entries ignored), the inputs and the
        parameters that returns a copy of the state with p = 0 and the heel angle φ at which
        ṗ = 0 (secant iterations from φ = 0, to |Δφ| < 1e-12 rad).

    Raises
    ------
    ParameterError
        (from the returned function) if no heel within ±90° balances the roll moment.
    """
    if not set(ROLL_STATES) <= set(model.state_labels):
        return None
    i_p, i_phi = (model.state_index(n) for n in ROLL_STATES)

    def balance(x: np.ndarray, u: np.ndarray, params: Any) -> np.ndarray:
        x = np.array(x, dtype=float)
        x[i_p] = 0.0

        def roll_acc(phi: float) -> float:
            x[i_phi] = phi
            return float(model.derivative(0.0, x, u, params)[i_p])

        # ṗ is nearly linear in φ (the restoring moment): secant steps converge in a few
        a, fa = 0.0, roll_acc(0.0)
        b, fb = 1e-3, roll_acc(1e-3)
        for _ in range(50):
            if fb == fa:
                break
            c = b - fb * (b - a) / (fb - fa)
            a, fa = b, fb
            b, fb = c, roll_acc(c)
            if abs(b - a) < 1e-12:
                break
        if not (math.isfinite(b) and abs(b) < 0.5 * math.pi and abs(fb) <= 1e-9 * max(
                1.0, abs(fa))):
            raise ParameterError(
                f"no heel angle within +-90 deg balances the roll moment of model "
                f"'{model.name}' (last {math.degrees(b):.4g} deg)", field="roll_angle",
                unit="rad", value=b)
        x[i_phi] = b
        return x

    return balance


def heel_metrics(result: Any) -> dict[str, tuple[np.ndarray, str, str]]:
    """The heel metrics of a turning circle: maximum and steady heel angle (roll models only).

    Parameters
    ----------
    result : SimResult
        The turning runs (channels ``roll_angle`` over (runs, samples)).

    Returns
    -------
    dict
        ``{}`` for a model without a ``roll_angle`` output; otherwise ``max_heel_angle`` (the
        heel φ of largest magnitude over the run, signed: positive starboard down) and
        ``steady_heel_angle`` (φ at the end of the run), each ``(values, units, long_name)``.
    """
    if "roll_angle" not in result.channel_names():
        return {}
    phi = np.asarray(result["roll_angle"], dtype=float)
    with np.errstate(invalid="ignore"):
        k = np.argmax(np.where(np.isnan(phi), -np.inf, np.abs(phi)), axis=1)
    peak = phi[np.arange(phi.shape[0]), k]
    return {
        "max_heel_angle": (peak, "rad", "heel angle of largest magnitude over the run "
                           "(signed: positive starboard down; outward in a turn is the "
                           "opposite sign of the yaw rate)"),
        "steady_heel_angle": (phi[:, -1], "rad", "heel angle at the end of the run "
                              "(positive starboard down)"),
    }
