"""Equilibria of constant-speed steering models: Nomoto 1 and 2, Voitkunsky's linear model.

A **constant-speed model** has no surge state: its speed U is a parameter (``speed`` [m/s])
and only the steering states move (yaw rate r, and a drift angle β or an auxiliary state).
It declares, by name:

* states ``north``, ``east``, ``heading``, ``yaw_rate`` and any further *steering states*
  (``yaw_aux`` of Nomoto 2, ``drift_angle`` of Voitkunsky);
* the input ``rudder_angle``;
* a parameter ``speed`` [m/s], and no state ``surge_speed`` or ``surge_perturbation``.

Its equilibria are the zeros of the steering states' derivatives (position and heading move
freely):

straight approach
    heading 0, yaw rate 0, position at the origin, every other steering state at rest; with
    ``trim`` the rudder angle (and the other steering states) solved so that the run is an
    exact equilibrium with r = 0 (0 for a model symmetric at rest, as the Nomoto models);
steady turn at a rudder angle δ
    the steering states with zero derivatives at δ, continued from the straight run in rudder
    steps (Nomoto 1: r = K δ, or r + n3 r³ = K δ with Norrbin's term);
spiral point at a yaw rate r
    the rudder angle (and other steering states) of the steady turn with that yaw rate.

The speed of such a model is the one its coefficients hold at (Nomoto's K and T are
identified at one speed: K ∝ U/L and T ∝ L/U for given non-dimensional K', T'), so an
approach at another speed is refused rather than run with coefficients of the wrong speed.
The speed does not change in a turn: these models have no speed loss.

:mod:`seahelm.analysis.equilibria.equilibrium` hands such a model to this module; the manoeuvre
library then runs on it unchanged.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..._validate import as_float_array, check_finite, check_positive, check_range
from ...errors import ParameterError
from ...parameters import Params
from ...vessels.base import VesselModel
from .plant import POSITION_STATES, SPEED_FIELD, Plant, is_constant_speed

#: (is_constant_speed, SPEED_FIELD and POSITION_STATES are the plant's, re-exported here)
__all__ = ["is_constant_speed", "ConstantSpeedPlant", "SPEED_FIELD", "POSITION_STATES"]

class ConstantSpeedPlant:
    """The equilibria of a constant-speed model and one parameter set: the steering-state
    solves on the surge-held mode of the one :class:`~seahelm.analysis.equilibria.plant.Plant`
    (which resolves the heading, yaw rate and steering states, the speed and their scales).

    Parameters
    ----------
    params : Params
        The model's parameter set.
    model : VesselModel
        A model for which :func:`is_constant_speed` holds.
    error : type, optional
        The exception raised where an equilibrium is not found (a ParameterError subclass;
        :mod:`.equilibrium` passes its ``EquilibriumError``, which this module cannot import
        without a cycle).
    """

    def __init__(self, params: Params, model: VesselModel,
                 error: type[ParameterError] = ParameterError) -> None:
        self.error = error
        if not is_constant_speed(model):  # pragma: no cover - the callers check
            raise ParameterError(f"model '{model.name}' is not a constant-speed model")
        self.params, self.model = params, model
        #: the one plant's surge-held mode resolves the signals (a batch of one)
        self.plant = plant = Plant(model, [params])
        self.i_psi, self.i_r, self.j_delta = plant.i_psi, plant.i_r, plant.j_delta
        self.steering = plant.steering
        self.speed = float(plant.speed[0])
        self.rate = float(plant.rate[0])
        self.scale = plant.steering_scale[0]

    # -- the model's right-hand side -----------------------------------------------------
    def state(self, steering: np.ndarray, heading: float = 0.0) -> np.ndarray:
        """The full state vector at the origin.

        Parameters
        ----------
        steering : numpy.ndarray
            The steering states (model order, SI units).
        heading : float, optional
            Heading ψ [rad] (default 0).

        Returns
        -------
        numpy.ndarray
        """
        x = np.zeros(self.model.n_states)
        x[self.steering] = steering
        x[self.i_psi] = heading
        return x

    def inputs(self, rudder: float) -> np.ndarray:
        """The input vector.

        Parameters
        ----------
        rudder : float
            Rudder angle δ [rad].

        Returns
        -------
        numpy.ndarray
        """
        u = np.zeros(self.model.n_inputs)
        u[self.j_delta] = rudder
        return u

    def residual(self, steering: np.ndarray, rudder: float) -> np.ndarray:
        """The steering states' derivatives, each over its typical size × U/L [-].

        Parameters
        ----------
        steering : numpy.ndarray
            The steering states (SI units).
        rudder : float
            Rudder angle δ [rad].

        Returns
        -------
        numpy.ndarray
        """
        dx = self.model.derivative(0.0, self.state(steering), self.inputs(rudder), self.params)
        return dx[self.steering] / (self.scale * self.rate)

    def _root(self, fun: Any, guess: np.ndarray, what: str) -> np.ndarray:
        from scipy.optimize import root

        sol = root(fun, guess, method="hybr", options={"xtol": 1e-13})
        res = fun(sol.x)
        if not np.all(np.isfinite(res)) or np.max(np.abs(res), initial=0.0) > 1e-9:
            raise self.error(
                f"no equilibrium of model '{self.model.name}' found {what} "
                f"({sol.message.strip()}; residual {np.max(np.abs(res), initial=0.0):.3g})")
        return sol.x

    # -- equilibria ----------------------------------------------------------------------
    def at_rudder(self, rudder: float, start: tuple[float, np.ndarray] | None = None,
                  rudder_step: float = math.radians(2.5)) -> np.ndarray:
        """Steering states with zero derivatives at a rudder angle, by continuation.

        Parameters
        ----------
        rudder : float
            Rudder angle δ [rad].
        start : tuple of (float, numpy.ndarray), optional
            An equilibrium (rudder [rad], steering states) to continue from (default: the
            straight run).
        rudder_step : float, optional
            Largest rudder change per continuation step [rad] (default 2.5°).

        Returns
        -------
        numpy.ndarray
            The steering states [SI].
        """
        d_from, z = start if start is not None else self.trim()
        z = np.asarray(z, dtype=float) / self.scale
        steps = max(1, int(math.ceil(abs(rudder - d_from) / rudder_step)))
        for d_k in np.linspace(d_from, rudder, steps + 1)[1:]:
            z = self._root(lambda w, d=float(d_k): self.residual(w * self.scale, d), z,
                           f"at rudder {math.degrees(d_k):.4g} deg")
        return z * self.scale

    def at_yaw_rate(self, yaw_rate: float, start: tuple[float, np.ndarray] | None = None
                    ) -> tuple[float, np.ndarray]:
        """The equilibrium with a prescribed yaw rate, by continuation in r (steps 0.01 U/L).

        Parameters
        ----------
        yaw_rate : float
            Yaw rate r [rad/s].
        start : tuple of (float, numpy.ndarray), optional
            An equilibrium (rudder [rad], steering states) to continue from (default: the
            straight run).

        Returns
        -------
        tuple of (float, numpy.ndarray)
            Rudder angle [rad] and steering states [SI].
        """
        d, z = start if start is not None else self.trim()
        z = np.asarray(z, dtype=float)
        k_r = self.steering.index(self.i_r)
        free = [k for k in range(len(self.steering)) if k != k_r]
        r0 = float(z[k_r])
        steps = max(1, int(math.ceil(abs(yaw_rate - r0) / (0.01 * self.rate))))
        for r_k in np.linspace(r0, yaw_rate, steps + 1)[1:]:

            def fun(w: np.ndarray, r_k: float = float(r_k)) -> np.ndarray:
                s = np.empty(len(self.steering))
                s[k_r] = r_k
                s[free] = w[:-1] * self.scale[free]
                return self.residual(s, float(w[-1]))

            w = self._root(fun, np.append(z[free] / self.scale[free], d),
                           f"at yaw rate {r_k:.6g} rad/s")
            d = float(w[-1])
            z[k_r], z[free] = r_k, w[:-1] * self.scale[free]
        return d, z

    def trim(self) -> tuple[float, np.ndarray]:
        """(rudder [rad], steering states [SI]) of the straight run: r = 0, others at rest."""
        zero = np.zeros(len(self.steering))
        if np.all(self.residual(zero, 0.0) == 0.0):  # at rest with the rudder amidships
            return 0.0, zero
        return self.at_yaw_rate(0.0, (0.0, zero))

    def lag(self) -> float:
        """The slowest time constant of the steering dynamics about the straight run [s]:
        1/min |Re λ| over the eigenvalues λ of their Jacobian (T of Nomoto 1), at most
        20 L/U. What a manoeuvre's default duration adds for the yaw rate to build up."""
        d, z = self.trim()
        h = 1e-6 * self.scale
        jac = np.empty((len(z), len(z)))
        for k in range(len(z)):
            e = np.zeros(len(z))
            e[k] = h[k]
            jac[:, k] = (self.residual(z + e, d) - self.residual(z - e, d)) / (2 * h[k])
        jac *= self.scale[:, None] * self.rate  # d(ẋ)/dx
        rates = np.abs(np.linalg.eigvals(jac).real)
        rates = rates[rates > 1e-12 * self.rate]
        return float(min(20.0 / self.rate, 1.0 / rates.min())) if rates.size else 0.0

    def outputs(self, steering: np.ndarray, rudder: float) -> dict[str, float]:
        """The model's outputs by name.

        Parameters
        ----------
        steering : numpy.ndarray
            The steering states (SI units).
        rudder : float
            Rudder angle δ [rad].

        Returns
        -------
        dict
        """
        y = self.model.outputs(0.0, self.state(steering), self.inputs(rudder), self.params)
        return dict(zip(self.model.output_labels, (float(v) for v in y)))

    # -- what equilibrium.py hands over ---------------------------------------------------
    def check_speed(self, speed: Any) -> float:
        """The approach speed: the model's own; another one is refused.

        Parameters
        ----------
        speed : float or None
            Requested approach speed [m/s] (None: the model's).

        Returns
        -------
        float
            The model's speed U [m/s].

        Raises
        ------
        ParameterError
            If ``speed`` is not the model's speed (``field="speed"``).
        """
        if speed is None:
            return self.speed
        check_positive("speed", speed, "m/s")
        U = float(speed)
        if not math.isclose(U, self.speed, rel_tol=1e-9):
            raise ParameterError(
                f"must be the constant speed U = {self.speed!r} [m/s] of model "
                f"'{self.model.name}': its steering coefficients hold at that speed only (for "
                "another speed, a ship whose parameters are given at that speed), got "
                f"{U!r}", field="speed", unit="m/s", value=U)
        return U

    def approach(self, speed: Any, *, heading: float, trim: bool) -> tuple[np.ndarray, float]:
        """The straight approach: at the origin, at rest in yaw.

        Parameters
        ----------
        speed : float or None
            Approach speed [m/s] (:meth:`check_speed`).
        heading : float
            Heading ψ [rad].
        trim : bool
            Solve the rudder angle for an exact equilibrium with zero yaw rate.

        Returns
        -------
        tuple of (numpy.ndarray, float)
            State vector and rudder angle [rad].
        """
        self.check_speed(speed)
        check_finite("heading", heading, "rad")
        rudder, steering = self.trim() if trim else (0.0, np.zeros(len(self.steering)))
        return self.state(steering, float(heading)), float(rudder)

    def steady_turns(self, rudder: Any, max_rudder: float, rudder_step: float
                     ) -> tuple[np.ndarray, tuple[int, ...]]:
        """Steady turns at rudder angles.

        Parameters
        ----------
        rudder : float or array_like
            Rudder angles δ [rad].
        max_rudder : float
            Largest admissible |δ| [rad].
        rudder_step : float
            Largest rudder change per continuation step [rad].

        Returns
        -------
        tuple of numpy.ndarray
            The fields of :class:`~seahelm.analysis.equilibria.equilibrium.SteadyTurn`, shape
            (6, *rudder.shape), and the steering states, shape (states, *rudder.shape).
        """
        check_positive("max_rudder", max_rudder, "rad")
        check_positive("rudder_step", rudder_step, "rad")
        deltas = as_float_array("rudder", rudder, "rad")
        check_range("rudder", deltas, -max_rudder, max_rudder, "rad")
        trim = self.trim()
        fields = np.full((6,) + deltas.shape, np.nan)
        states = np.full((len(self.steering),) + deltas.shape, np.nan)
        for idx, delta in np.ndenumerate(deltas):
            z = self.at_rudder(float(delta), trim, rudder_step)
            fields[(slice(None),) + idx] = self._turn_fields(z, float(delta))
            states[(slice(None),) + idx] = z
        return fields, states

    def _turn_fields(self, z: np.ndarray, rudder: float) -> tuple[float, ...]:
        y = self.outputs(z, rudder)
        r = float(z[self.steering.index(self.i_r)])
        U = y.get("speed", self.speed)
        beta = y.get("drift_angle", math.atan2(-y.get("sway_speed", 0.0),
                                               y.get("surge_speed", U)))
        return (y.get("surge_speed", U), y.get("sway_speed", 0.0), r, U, beta,
                U / abs(r) if r != 0.0 else math.inf)

    def spiral(self, rates: np.ndarray) -> np.ndarray:
        """Spiral-curve points at prescribed yaw rates.

        Parameters
        ----------
        rates : numpy.ndarray
            Yaw rates r [rad/s].

        Returns
        -------
        numpy.ndarray
            (yaw rate, rudder, surge, sway, speed, drift angle) of each, shape (6, rates.size).
        """
        flat = rates.ravel()
        out = np.full((6, flat.size), np.nan)
        trim = self.trim()
        for sign in (1.0, -1.0, 0.0):
            order = [int(i) for i in np.argsort(np.abs(flat)) if np.sign(flat[i]) == sign]
            start = trim
            for i in order:
                d, z = self.at_yaw_rate(float(flat[i]), start)
                start = (d, z)
                f = self._turn_fields(z, d)
                out[:, i] = (flat[i], d, f[0], f[1], f[3], f[4])
        return out
