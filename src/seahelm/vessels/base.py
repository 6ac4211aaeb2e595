"""The plug-in interface of a vessel model.

A vessel model is a pure right-hand side plus the declaration of its signals by name, bundled
in a :class:`VesselModel` (the component contract of ARCHITECTURE.md):

``rhs(t, x, u, d, p, dx)``
    numba-compiled; writes ẋ into ``dx`` for one run. ``x`` state (``state_labels`` order),
    ``u`` inputs (``input_labels`` order, e.g. rudder angle [rad], propeller rps [1/s]), ``d``
    external disturbances (``disturbance_labels`` order; zero when not given), ``p`` the run's
    parameters as a record: compiled code reads ``p.gain``, never ``p[0]``
    (:meth:`seahelm.parameters.Params.record_dtype`).
``output(t, x, u, p, y)``
    numba-compiled; writes the model's outputs (``output_labels`` order) into ``y``. A model
    reports whatever it can; the engine records them all and routes those a controller
    declares as measurements (e.g. ``heading``, ``yaw_rate``) to it by name. The usual names
    are :data:`NAV_OUTPUTS`.

Compiled code indexes its vectors through named constants (``S = signal_indices(STATES)``,
then ``x[S.heading]``).

Conventions: north-east-down axes, heading ψ measured clockwise from north, so
ẋ_N = U cos ψ, ẏ_E = U sin ψ; a positive rudder angle gives a positive (starboard) yaw rate.

:meth:`VesselModel.derivative` evaluates the right-hand side over any leading batch axes
(numpy in, numpy out) — for tests, analysis and the adaptive reference path.
"""

from __future__ import annotations

import dataclasses
import functools
from typing import Any

import numpy as np
from numba import njit

from .._validate import lookup_name
from ..errors import ParameterError
from ..parameters import Params, as_records, stack_params

__all__ = ["NAV_OUTPUTS", "NAV_OUTPUT_UNITS", "CAPABILITIES", "VesselModel"]

NAV_OUTPUTS: tuple[str, ...] = ("north", "east", "heading", "yaw_rate", "surge_speed", "sway_speed")
"""The usual output names of a ship model (north, east position; heading; yaw rate; surge and
sway speed). Not a fixed set: each model declares its own ``output_labels``."""
NAV_OUTPUT_UNITS: tuple[str, ...] = ("m", "m", "rad", "rad/s", "m/s", "m/s")

#: What a model may declare it supports (:attr:`VesselModel.capabilities`), beyond running in
#: the engine: the knowledge an analysis needs about a model, declared by the model instead of
#: checked by its name.
CAPABILITIES: dict[str, str] = {
    "shallow-water": "its parameters take the shallow-water corrections of "
                     "seahelm.hydrodynamics.shallow_water (Ship.at_depth, --depth)",
    "hull-identification": "its hull derivatives are what seahelm.identification.mmg_fit "
                           "identifies from records (the base ship of `seahelm identify mmg`)",
    "engine-estimate": "a ship on it with a propeller gets an engine, shaft and reversal "
                       "estimate for the stopping test (seahelm.vessels.mmg_four_quadrant."
                       "from_mmg: the ship on model 'mmg-4q')",
    "record-identification": "its hull, propeller and rudder coefficients are fitted by output "
                             "error to segments of measured records (the multi-record fit: "
                             "`seahelm identify mmg --free` of an mmg-ls ship)",
    "closed-form-self-propulsion": "the propeller rps of its straight run has a closed form "
                                   "(seahelm.vessels.mmg_four_quadrant.self_propulsion_rps), "
                                   "which the equilibrium solvers try first "
                                   "(seahelm.analysis.equilibria.closed_forms)",
}


@dataclasses.dataclass(frozen=True, eq=False)
class VesselModel:
    """A dynamic vessel model usable by the simulation engine.

    Attributes
    ----------
    name : str
        Registry name (``seahelm models`` lists them).
    description : str
        One line: what the model is and where it comes from.
    params_type : type[Params]
        Frozen parameter dataclass.
    state_labels, state_units : tuple of str
        Names and units of the state vector.
    input_labels, input_units : tuple of str
        Names and units of the actuator inputs.
    disturbance_labels, disturbance_units : tuple of str
        Names and units of the external disturbance inputs.
    output_labels, output_units : tuple of str
        Names and units of what ``output`` writes.
    rhs, output : numba dispatchers
        See the module docstring for their signatures.
    state_lower, state_upper : tuple of float, optional
        Declared admissible bounds per state; leaving them marks a run diverged.
    motion : numba dispatcher, optional
        ``motion(x, p) -> (surge_speed, sway_speed, heading)``: the velocity through the water
        [m/s] and the heading [rad] from the state, for the environment's loads (without it
        they are read from the outputs, which costs a full ``output`` per stage).
    load_params : tuple of str, optional
        Parameters the model's load channels (``force_x``, ``force_y``, ``moment_z``) need, which
        must be > 0 when an environment puts loads on them (e.g. the masses that normalise a
        force in a model written in normalised units).
    check_initial_state : callable, optional
        ``check_initial_state(x0)`` with ``x0`` of shape (runs, n_states): raises
        :class:`~seahelm.errors.ParameterError` (field ``x0``) for an initial state the model
        cannot start from (a quaternion that is not of unit length).
    capabilities : frozenset of str, optional
        What the model supports beyond the engine, names of :data:`CAPABILITIES`
        (:meth:`supports`).
    check_result : callable, optional
        ``check_result(result)``, called by :func:`~seahelm.simulation.engine.simulate` on the
        finished result: warns (:func:`~seahelm.errors.warn_validity`) where the runs left the
        model's published range (a low-speed model driven fast).
    """

    name: str
    description: str
    params_type: type[Params]
    state_labels: tuple[str, ...]
    state_units: tuple[str, ...]
    input_labels: tuple[str, ...]
    input_units: tuple[str, ...]
    disturbance_labels: tuple[str, ...]
    disturbance_units: tuple[str, ...]
    rhs: Any
    output: Any
    output_labels: tuple[str, ...] = ()
    output_units: tuple[str, ...] = ()
    state_lower: tuple[float, ...] | None = None
    state_upper: tuple[float, ...] | None = None
    load_params: tuple[str, ...] = ()
    motion: Any = None
    check_initial_state: Any = None
    capabilities: frozenset[str] = frozenset()
    check_result: Any = None

    def __post_init__(self) -> None:
        n = len(self.state_labels)
        object.__setattr__(self, "capabilities", frozenset(self.capabilities))
        unknown = sorted(self.capabilities - set(CAPABILITIES))
        if unknown:
            raise ValueError(f"{self.name}: unknown capabilities {unknown}; valid: "
                             f"{', '.join(CAPABILITIES)}")
        for attr, ref in (
            ("state_units", n),
            ("input_units", len(self.input_labels)),
            ("disturbance_units", len(self.disturbance_labels)),
            ("output_units", len(self.output_labels)),
        ):
            if len(getattr(self, attr)) != ref:
                raise ValueError(f"{self.name}: {attr} has the wrong length")
        if not self.output_labels:
            raise ValueError(f"{self.name}: a model must declare its output_labels")
        for attr in ("state_labels", "input_labels", "disturbance_labels", "output_labels"):
            labels = getattr(self, attr)
            if len(set(labels)) != len(labels):
                raise ValueError(f"{self.name}: duplicate names in {attr}: {labels}")
        if self.state_lower is None:
            object.__setattr__(self, "state_lower", (-np.inf,) * n)
        if self.state_upper is None:
            object.__setattr__(self, "state_upper", (np.inf,) * n)

    @property
    def n_states(self) -> int:
        return len(self.state_labels)

    def supports(self, capability: str) -> bool:
        """Whether the model declares ``capability`` (a name of :data:`CAPABILITIES`).

        Parameters
        ----------
        capability : str

        Returns
        -------
        bool

        Raises
        ------
        ValueError
            For a name that is not a capability (a misspelt check would be False for ever).
        """
        lookup_name("capability", CAPABILITIES, capability)
        return capability in self.capabilities

    @property
    def n_inputs(self) -> int:
        return len(self.input_labels)

    @property
    def n_disturbances(self) -> int:
        return len(self.disturbance_labels)

    @property
    def n_outputs(self) -> int:
        return len(self.output_labels)

    def signals(self) -> list[tuple[str, str, str]]:
        """Every declared signal as ``(kind, name, unit)``: states, inputs, disturbances, outputs.

        Returns
        -------
        list of tuple of str
        """
        return [(kind, n, u) for kind, names, units in (
            ("state", self.state_labels, self.state_units),
            ("input", self.input_labels, self.input_units),
            ("disturbance", self.disturbance_labels, self.disturbance_units),
            ("output", self.output_labels, self.output_units)) for n, u in zip(names, units)]

    def state_index(self, label: str) -> int:
        """Index of a state by label (ValueError listing the labels if unknown).

        Parameters
        ----------
        label : str
            State label, e.g. "yaw_rate".

        Returns
        -------
        int
        """
        try:
            return self.state_labels.index(label)
        except ValueError:
            raise ValueError(
                f"model '{self.name}' has no state '{label}'; states: {', '.join(self.state_labels)}"
            ) from None

    def initial_state(self, **values: float) -> np.ndarray:
        """A state vector with zeros except the given labelled values (SI units)."""
        x = np.zeros(self.n_states)
        for key, value in values.items():
            x[self.state_index(key)] = float(value)
        return x

    def derivative(
        self,
        t: float,
        x: Any,
        u: Any,
        params: Params | Any,
        d: Any | None = None,
    ) -> np.ndarray:
        """ẋ over leading batch axes: ``x`` (..., n_states), ``u`` (..., n_inputs).

        ``params`` is a parameter set, a sequence of them (one per run) or a packed array
        (..., n_params). Shapes broadcast against each other.

        Parameters
        ----------
        t : float
            Time [s].
        x : array_like, shape (..., n_states)
            States (SI units, radians).
        u : array_like, shape (..., n_inputs)
            Inputs (e.g. rudder angle [rad]).
        params : Params, sequence of Params or array_like, shape (..., n_params)
            Model parameters.
        d : array_like, shape (..., n_disturbances), optional
            Disturbance inputs (default zeros).

        Returns
        -------
        numpy.ndarray, shape (..., n_states)
            ẋ.
        """
        x = np.asarray(x, dtype=float)
        u = np.asarray(u, dtype=float)
        p = _param_array(params, self.params_type)
        d = np.zeros(self.n_disturbances) if d is None else np.asarray(d, dtype=float)
        if x.shape[-1:] != (self.n_states,):
            raise ParameterError(
                f"`x` must end in {self.n_states} states ({', '.join(self.state_labels)}), "
                f"got shape {x.shape}"
            )
        if u.shape[-1:] != (self.n_inputs,):
            raise ParameterError(f"`u` must end in {self.n_inputs} inputs, got shape {u.shape}")
        batch = np.broadcast_shapes(x.shape[:-1], u.shape[:-1], p.shape[:-1], d.shape[:-1])
        X, U, D, P = (_rows(a, batch) for a in (x, u, d, p))
        out = np.empty_like(X)
        _batched_rhs(self.rhs, float(t), X, U, D, as_records(P, self.params_type), out)
        return out.reshape(batch + (self.n_states,))

    def outputs(self, t: float, x: Any, u: Any, params: Params | Any) -> np.ndarray:
        """The model's outputs (``output_labels`` order) over leading batch axes.

        Parameters
        ----------
        t : float
            Time [s].
        x : array_like, shape (..., n_states)
            States (SI units, radians).
        u : array_like, shape (..., n_inputs)
            Inputs.
        params : Params or array_like, shape (..., n_params)
            Model parameters.

        Returns
        -------
        numpy.ndarray, shape (..., n_outputs)
        """
        x = np.asarray(x, dtype=float)
        u = np.asarray(u, dtype=float)
        p = _param_array(params, self.params_type)
        batch = np.broadcast_shapes(x.shape[:-1], u.shape[:-1], p.shape[:-1])
        X, U, P = (_rows(a, batch) for a in (x, u, p))
        out = np.empty((X.shape[0], self.n_outputs))
        _batched_output(self.output, float(t), X, U, as_records(P, self.params_type), out)
        return out.reshape(batch + (self.n_outputs,))

    def output_index(self, label: str) -> int:
        """Index of an output by name (ValueError listing the outputs if unknown).

        Parameters
        ----------
        label : str
            Output name, e.g. "heading".

        Returns
        -------
        int
        """
        try:
            return self.output_labels.index(label)
        except ValueError:
            raise ValueError(
                f"model '{self.name}' has no output '{label}'; outputs: "
                f"{', '.join(self.output_labels)}"
            ) from None


def _param_array(params: Any, cls: type[Params]) -> np.ndarray:
    """Parameter set(s) or packed values as a float array (..., n_params)."""
    if isinstance(params, Params) or (
        isinstance(params, (list, tuple)) and params and isinstance(params[0], Params)
    ):
        p = stack_params(params, cls)
        return p[0] if isinstance(params, Params) else p
    return np.asarray(params, dtype=float)


def _rows(a: np.ndarray, batch: tuple[int, ...]) -> np.ndarray:
    """Broadcast ``a`` to ``batch + a.shape[-1:]`` and flatten the batch axes (C order).

    Always writable: a broadcast that broadcasts nothing is a contiguous read-only view, and
    the compiled row loops were compiled a second time for read-only arrays."""
    n = int(np.prod(batch, dtype=np.int64))
    return np.require(np.broadcast_to(a, batch + a.shape[-1:]).reshape(n, a.shape[-1]),
                      requirements=("C", "W"))


@njit
def _generic_rhs(rhs, t, X, U, D, P, out):  # pragma: no cover - compiled
    for i in range(X.shape[0]):
        rhs(t, X[i], U[i], D[i], P[i], out[i])


@njit
def _generic_output(output, t, X, U, P, out):  # pragma: no cover - compiled
    for i in range(X.shape[0]):
        output(t, X[i], U[i], P[i], out[i])


@njit
def _generic_indexed_rhs(rhs, t, X, U, D, P, rows, out):  # pragma: no cover - compiled
    for i in range(X.shape[0]):
        rhs(t, X[i], U[i], D[i], P[rows[i]], out[i])


_ROW_LOOPS = {
    "rhs": ("t, X, U, D, P, out", "fn(t, X[i], U[i], D[i], P[i], out[i])"),
    "output": ("t, X, U, P, out", "fn(t, X[i], U[i], P[i], out[i])"),
    "rhs_indexed": ("t, X, U, D, P, rows, out", "fn(t, X[i], U[i], D[i], P[rows[i]], out[i])"),
    # an actuator's output(x, command, p, out): no time argument
    "output_untimed": ("X, U, P, out", "fn(X[i], U[i], P[i], out[i])"),
}


@functools.lru_cache(maxsize=None)
def _row_loop(fn: Any, kind: str) -> Any:
    """A compiled loop of a model's ``rhs``/``output`` over the rows of a batch, generated
    per function and cached on disk (numba ``cache=True``, :mod:`seahelm._codegen`), or None
    for a function that cannot be imported by its module and name (a closure): the loops
    taking the function as an argument (:func:`_generic_rhs`) cannot be cached, and compiled
    them in every process (0.2-0.6 s each, in every steady approach)."""
    import sys

    from .._codegen import code_fingerprint, content_digest, import_generated

    py = getattr(fn, "py_func", None)
    module, name = getattr(py, "__module__", None), getattr(py, "__name__", None)
    if py is None or getattr(sys.modules.get(str(module)), str(name), None) is not fn:
        return None
    args, call = _ROW_LOOPS[kind]
    source = (f'"""Generated by seahelm.vessels.base: {module}.{name} over a batch\'s rows."""\n'
              f"from numba import njit\n\nfrom {module} import {name} as fn\n\n\n"
              "@njit(cache=True)\n"
              f"def loop({args}):  # pragma: no cover - compiled\n"
              "    for i in range(X.shape[0]):\n"
              f"        {call}\n")
    digest = content_digest(source, code_fingerprint(py))
    return import_generated(f"seahelm_rows_{kind}_{digest}", source).loop


def _batched_rhs(rhs: Any, t: float, X: np.ndarray, U: np.ndarray, D: np.ndarray, P: Any,
                 out: np.ndarray) -> None:
    """``out[i] = rhs(t, X[i], U[i], D[i], P[i])`` for every row i (compiled)."""
    loop = _row_loop(rhs, "rhs")
    if loop is None:
        _generic_rhs(rhs, t, X, U, D, P, out)
    else:
        loop(t, X, U, D, P, out)


def _batched_indexed_rhs(rhs: Any, t: float, X: np.ndarray, U: np.ndarray, D: np.ndarray,
                         P: np.ndarray, rows: np.ndarray, out: np.ndarray) -> None:
    """``out[i] = rhs(t, X[i], U[i], D[i], P[rows[i]])`` for every row i (compiled; the
    parameter records read in place, rows may repeat)."""
    loop = _row_loop(rhs, "rhs_indexed")
    if loop is None:
        _generic_indexed_rhs(rhs, t, X, U, D, P, rows, out)
    else:
        loop(t, X, U, D, P, rows, out)


def _batched_actuator(rhs: Any, output: Any, t: float, X: np.ndarray, C: np.ndarray,
                      P: np.ndarray, dx: np.ndarray, y: np.ndarray) -> None:
    """``dx[i] = rhs(t, X[i], C[i], P[i])`` and ``y[i] = output(X[i], C[i], P[i])`` of an
    actuator for every row i, by loops generated per function and cached on disk (a loop
    taking the functions as arguments compiled again in every process)."""
    rhs_loop, out_loop = _row_loop(rhs, "output"), _row_loop(output, "output_untimed")
    if rhs_loop is None or out_loop is None:
        _generic_actuator(rhs, output, t, X, C, P, dx, y)
    else:
        rhs_loop(t, X, C, P, dx)
        out_loop(X, C, P, y)


@njit
def _generic_actuator(rhs, output, t, X, C, P, dx, y):  # pragma: no cover - compiled
    for i in range(X.shape[0]):
        rhs(t, X[i], C[i], P[i], dx[i])
        output(X[i], C[i], P[i], y[i])


def _batched_output(output: Any, t: float, X: np.ndarray, U: np.ndarray, P: Any,
                    out: np.ndarray) -> None:
    """``out[i] = output(t, X[i], U[i], P[i])`` for every row i (compiled)."""
    loop = _row_loop(output, "output")
    if loop is None:
        _generic_output(output, t, X, U, P, out)
    else:
        loop(t, X, U, P, out)
