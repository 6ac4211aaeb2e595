"""The plant of the equilibrium solvers: a model, the parameter sets of its runs and the
signals the solvers need, resolved once.

One :class:`Plant` serves the one-run solvers (:mod:`seahelm.analysis.equilibria.equilibrium`, a
batch of one) and the batched ones (:mod:`seahelm.analysis.equilibria.batch_equilibrium`,
:mod:`seahelm.analysis.equilibria.batch_steady_turn`). It resolves, by name (the module docstring of
:mod:`seahelm.analysis.equilibria.equilibrium` lists the signals):

* the surge state: ``surge_speed`` (MMG), or ``surge_perturbation`` about a parameter
  ``nominal_speed`` (Mariner; :attr:`Plant.u_offset` is then that speed per run);
* the states ``sway_speed``, ``yaw_rate`` and, if there is one, ``heading``;
* the inputs ``rudder_angle`` and, optionally, ``propeller_rps``;
* per run the length L and the reference speed U_ref (``approach_speed``, else
  ``nominal_speed``, else 1 m/s) that scale the unknowns and the accelerations;
* for a model with roll, its heel balance (:func:`~.heel.heel_balance`).

A constant-speed steering model (Nomoto, Voitkunsky: no surge state, the speed a parameter
``speed``; :func:`is_constant_speed`) is the plant's **surge-held** mode
(:attr:`Plant.surge_held`): there is no surge state to resolve, and the plant resolves the
heading, yaw rate and steering states, the speed U, the rate U/L and each steering state's
typical size, which :class:`~seahelm.analysis.equilibria.constant_speed.ConstantSpeedPlant`
solves on.

Before issue 47 this resolution was written twice (``equilibrium._Plant`` for one run,
``batch_equilibrium._Batch`` for a batch); ``tests/test_equilibria_plant.py`` pins it on
every registered model.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ...errors import ParameterError
from ...parameters import Params, as_records, stack_params
from ...registry import model_for_params
from ...vessels.base import VesselModel, _batched_indexed_rhs
from .heel import heel_balance

__all__ = ["EquilibriumError", "Plant", "resolve_params", "is_constant_speed", "SPEED_FIELD",
           "POSITION_STATES"]

#: The parameter holding a constant-speed model's speed U [m/s].
SPEED_FIELD = "speed"
#: States that move freely in an equilibrium (the rest are a constant-speed model's steering
#: states).
POSITION_STATES = ("north", "east", "heading")
_SURGE_STATES = ("surge_speed", "surge_perturbation")


def is_constant_speed(model: VesselModel) -> bool:
    """Whether ``model`` is a constant-speed steering model: no surge state, its speed a
    parameter ``speed`` (the surge held), the states ``north``, ``east``, ``heading`` and
    ``yaw_rate`` and the input ``rudder_angle``
    (:mod:`seahelm.analysis.equilibria.constant_speed`).

    Parameters
    ----------
    model : VesselModel

    Returns
    -------
    bool
    """
    states = set(model.state_labels)
    return (not states & set(_SURGE_STATES)
            and {"north", "east", "heading", "yaw_rate"} <= states
            and "rudder_angle" in model.input_labels
            and SPEED_FIELD in model.params_type.field_names())


def _steering_scale(unit: str, rate: float) -> float:
    """Typical size of a steering state or its derivative of ``unit`` (rate = U/L [1/s])."""
    return {"rad": 1.0, "rad/s": rate, "rad/s²": rate * rate, "m/s": 1.0}.get(unit, 1.0)


class EquilibriumError(ParameterError):
    """The equilibrium equations have no solution for the given arguments (or it was not found).

    A :class:`~seahelm.errors.ParameterError` (so a ``ValueError``): it names the argument it
    concerns in its ``field`` where there is one."""


def resolve_params(value: Any) -> tuple[Params, VesselModel | None]:
    """The parameter set (and the model, for a ship) of a parameter set, ship or ship name.

    Parameters
    ----------
    value : Params, Ship, str or path
        A parameter set, a ship, a catalog name or a ship file path.

    Returns
    -------
    tuple of (Params, VesselModel or None)
        The parameter set, and the ship's model (None for a bare parameter set).

    Raises
    ------
    ParameterError
        If ``value`` is none of these.
    """
    if isinstance(value, Params):
        return value, None
    from ...ships import Ship, get_ship

    if isinstance(value, (Ship, str)) or hasattr(value, "__fspath__"):
        ship = get_ship(value)
        return ship.params, ship.model
    raise ParameterError(
        f"expected a parameter set, a ship or a catalog name, got {type(value).__name__}")


class Plant:
    """A model and the parameter sets of a batch of runs, with the indices of the signals the
    equilibrium solvers need (see the module docstring). One run is a batch of one
    (:meth:`of`).

    Parameters
    ----------
    model : VesselModel
        The model every parameter set belongs to.
    params : Params or sequence of Params
        One parameter set per run (each a ``model.params_type``).

    Raises
    ------
    ParameterError
        If there are no parameter sets, one is not of the model's type, or the model lacks
        the signals named in the module docstring.
    """

    def __init__(self, model: VesselModel, params: Params | Sequence[Params]) -> None:
        plist = [params] if isinstance(params, Params) else list(params)
        if not plist:
            raise ParameterError(": no parameter sets", field="params")
        for p in plist:
            if not isinstance(p, model.params_type):
                raise ParameterError(
                    f"model '{model.name}' takes {model.params_type.__name__}, got "
                    f"{type(p).__name__}")
        self.model = model
        self.params: list[Params] = plist
        first = plist[0]
        states = model.state_labels
        #: the surge held: a constant-speed model (its speed a parameter, no surge equation)
        self.surge_held = is_constant_speed(model)
        if self.surge_held:
            self._surge_held(plist)
            return
        self.steering = None
        if "surge_speed" in states:
            self.i_u = states.index("surge_speed")
            self.u_offset = np.zeros(len(plist))
        elif "surge_perturbation" in states and hasattr(first, "nominal_speed"):
            self.i_u = states.index("surge_perturbation")
            self.u_offset = np.array([float(p.nominal_speed) for p in plist])
        else:
            raise ParameterError(
                f"model '{model.name}' needs a state 'surge_speed' (or 'surge_perturbation' "
                f"with a parameter 'nominal_speed'); states: {', '.join(states)}")
        for name in ("sway_speed", "yaw_rate"):
            if name not in states:
                raise ParameterError(
                    f"model '{model.name}' has no state '{name}'; states: {', '.join(states)}")
        self.i_v = states.index("sway_speed")
        self.i_r = states.index("yaw_rate")
        self.i_psi = states.index("heading") if "heading" in states else None
        if "rudder_angle" not in model.input_labels:
            raise ParameterError(f"model '{model.name}' has no input 'rudder_angle'")
        self.j_delta = model.input_labels.index("rudder_angle")
        self.j_rps = (model.input_labels.index("propeller_rps")
                      if "propeller_rps" in model.input_labels else None)
        self.length = np.array([float(p.length) for p in plist])
        ref = next((n for n in ("approach_speed", "nominal_speed") if hasattr(first, n)), None)
        self.u_ref = (np.array([float(getattr(p, ref)) for p in plist]) if ref is not None
                      else np.ones(len(plist)))
        self.heel = heel_balance(model)  # a model with roll: its steady heel

    def _surge_held(self, plist: list[Params]) -> None:
        """The signals of a constant-speed model: heading, yaw rate and the other steering
        states (all but the position and heading), the rudder; per run the speed U, the
        length L (NaN without one), the rate U/L (1/s when either is missing) and each
        steering state's typical size."""
        m = self.model
        states = m.state_labels
        self.i_u = None
        self.u_offset = np.zeros(len(plist))
        self.i_v = states.index("sway_speed") if "sway_speed" in states else None
        self.i_r = states.index("yaw_rate")
        self.i_psi = states.index("heading")
        self.j_delta = m.input_labels.index("rudder_angle")
        self.j_rps = None
        self.steering = [k for k, s in enumerate(states) if s not in POSITION_STATES]
        self.speed = np.array([float(getattr(p, SPEED_FIELD)) for p in plist])
        self.length = np.array([float(getattr(p, "length", math.nan)) for p in plist])
        self.u_ref = self.speed
        self.rate = np.array([U / L if L > 0 and U > 0 else 1.0
                              for U, L in zip(self.speed.tolist(), self.length.tolist())])
        self.steering_scale = np.array([[_steering_scale(m.state_units[k], rate)
                                         for k in self.steering]
                                        for rate in self.rate.tolist()])
        self.heel = None

    @classmethod
    def of(cls, value: Any, model: VesselModel | None = None) -> Plant:
        """The plant of one run (a batch of one) from a parameter set, ship or ship name.

        Parameters
        ----------
        value : Params, Ship, str or path
            The run's parameter set, ship, catalog name or ship file path.
        model : VesselModel, optional
            The model (default: the ship's, else the one registered model that takes the
            parameter type).

        Returns
        -------
        Plant

        Raises
        ------
        ParameterError
            If no model is given or found, the parameter set is not the model's type, or
            the model lacks a signal.
        """
        params, ship_model = resolve_params(value)
        if model is None:
            model = ship_model or model_for_params(type(params))
            if model is None:
                raise ParameterError(
                    f"no default model for {type(params).__name__}; pass `model=` "
                    "(a default exists for a parameter type only one registered model takes)")
        return cls(model, [params])

    @property
    def n_runs(self) -> int:
        """Number of runs."""
        return len(self.params)

    @functools.cached_property
    def records(self) -> np.ndarray:
        """The parameter records of the runs (what the compiled right-hand side reads)."""
        return as_records(stack_params(self.params, self.model.params_type),
                          type(self.params[0]))

    # -- one run (numpy, the model's own derivative) -------------------------------------
    def state(self, surge: float, v: float, r: float, heading: float = 0.0,
              inputs: np.ndarray | None = None, run: int = 0) -> np.ndarray:
        """The state vector of run ``run`` (heel balanced for a model with roll when the
        ``inputs`` are given).

        Parameters
        ----------
        surge, v, r : float
            Surge speed (total) [m/s], sway speed [m/s], yaw rate [rad/s].
        heading : float, optional
            Heading ψ [rad] (default 0).
        inputs : numpy.ndarray, optional
            The input vector (to balance the heel of a model with roll).
        run : int, optional
            The run (default 0, the one run of :meth:`of`).

        Returns
        -------
        numpy.ndarray
        """
        x = np.zeros(self.model.n_states)
        x[self.i_u] = surge - self.u_offset[run]
        x[self.i_v] = v
        x[self.i_r] = r
        if self.i_psi is not None:
            x[self.i_psi] = heading
        if self.heel is not None and inputs is not None:
            x = self.heel(x, inputs, self.params[run])
        return x

    def inputs(self, rudder: float, rps: float | None) -> np.ndarray:
        """The input vector (rudder angle [rad], propeller rps [1/s] if the model has one).

        Parameters
        ----------
        rudder : float
        rps : float or None

        Returns
        -------
        numpy.ndarray
        """
        u = np.zeros(self.model.n_inputs)
        u[self.j_delta] = rudder
        if self.j_rps is not None:
            u[self.j_rps] = 0.0 if rps is None else rps
        return u

    def acceleration(self, surge: float, v: float, r: float, rudder: float,
                     rps: float | None, run: int = 0) -> np.ndarray:
        """(u̇, v̇, ṙ) of run ``run`` by the model's :meth:`~VesselModel.derivative`.

        Parameters
        ----------
        surge, v, r, rudder : float
            Surge speed [m/s], sway speed [m/s], yaw rate [rad/s], rudder angle [rad].
        rps : float or None
            Propeller rps [1/s].
        run : int, optional
            The run (default 0).

        Returns
        -------
        numpy.ndarray, shape (3,)
        """
        u = self.inputs(rudder, rps)
        dx = self.model.derivative(0.0, self.state(surge, v, r, inputs=u, run=run), u,
                                   self.params[run])
        return dx[[self.i_u, self.i_v, self.i_r]]

    # -- a batch (the compiled right-hand side over rows) --------------------------------
    def accelerations(self, rows: np.ndarray, surge: np.ndarray, v: np.ndarray,
                      rudder: np.ndarray, rps: np.ndarray | None,
                      r: np.ndarray | None = None) -> np.ndarray:
        """(u̇, v̇, ṙ) of runs ``rows`` (a run may repeat) at yaw rate ``r`` (default 0).

        No heel balance (the batched solvers hand a model with roll to the one-run code).

        Parameters
        ----------
        rows : numpy.ndarray of int
            The run of each row.
        surge, v, rudder : numpy.ndarray
            Surge speed [m/s], sway speed [m/s], rudder angle [rad] per row.
        rps : numpy.ndarray or None
            Propeller rps [1/s] per row.
        r : numpy.ndarray, optional
            Yaw rate [rad/s] per row (default 0).

        Returns
        -------
        numpy.ndarray, shape (len(rows), 3)
        """
        m = self.model
        k = rows.size
        x = np.zeros((k, m.n_states))
        x[:, self.i_u] = surge - self.u_offset[rows]
        x[:, self.i_v] = v
        if r is not None:
            x[:, self.i_r] = r
        u = np.zeros((k, m.n_inputs))
        u[:, self.j_delta] = rudder
        if self.j_rps is not None and rps is not None:
            u[:, self.j_rps] = rps
        d = np.zeros((k, m.n_disturbances))
        out = np.empty_like(x)
        with np.errstate(all="ignore"):
            # each run's parameter record read in place (copying the records of the rows
            # would cost several times the right-hand side itself)
            _batched_indexed_rhs(m.rhs, 0.0, x, u, d, self.records,
                                 np.ascontiguousarray(rows, dtype=np.int64), out)
        return out[:, [self.i_u, self.i_v, self.i_r]]
