"""Linearisation of a vessel model (with its steering gear) at an equilibrium: A, B, C, D.

:func:`linearize` finds the operating point with :mod:`seahelm.analysis.equilibria.equilibrium` (the
trimmed straight run at a speed, or the steady turn at a rudder angle) and
:func:`linearize_at` differentiates the compiled right-hand side there::

    δż = A δz + B δv,    δy = C δz + D δv

with z the model's states followed by the actuator's (the rudder angle of a servo), v the
actuator's command channels (``rudder_command``) followed by the model inputs no actuator
feeds (``propeller_rps`` held by the engine) and, with ``disturbances=True``, the model's
disturbance channels (``force_y`` [N], ``moment_z`` [N·m], a current [m/s], ...): the inputs
an environment acts through. y are the model's outputs. Every row and column carries its name
and unit (:class:`LinearModel`); :meth:`LinearModel.to_control` hands it to python-control
with the names attached, :meth:`LinearModel.to_numpy` gives plain arrays.

Derivatives: Richardson-extrapolated central differences
    The complex-step derivative f'(x) = Im f(x + ih)/h (Squire & Trapp 1998) would be exact to
    rounding, but the right-hand sides are numba functions compiled over float64, and they
    call ``math.sqrt``, ``math.cos``, ``max`` — which numba does not type for complex128
    (compiling ``mariner_rhs`` for complex arrays fails with "No match for registered cases:
    sqrt(complex128)"). So the Jacobian is taken by central differences
    D(h) = (f(x + h) − f(x − h))/(2h) = f' + c₂h² + c₄h⁴ + …, extrapolated over the steps
    h, h/2, h/4, … in Richardson's (1911) tableau T_{k,i} = T_{k,i−1} + (T_{k,i−1} −
    T_{k−1,i−1})/(4^i − 1) (Dahlquist & Björck 2008, §3.4.3; the scheme of Ridders 1982).
    The error estimate of each entry is |T_{L,L} − T_{L,L−1}| (the last correction, a bound
    on the truncation error of the second-best value) plus the rounding error
    ε_mach · max|f| / h_min amplified by the tableau (:attr:`LinearModel.error`). The step of
    each variable is relative to its natural size: U for a speed, U/L for a rate, L for a
    position, 1 rad for an angle (times ``step``, default 10⁻³). For an exactly linear model
    the central difference is already exact and only rounding remains (10⁻¹³ relative).
    Every perturbed point of the tableau is evaluated in one batched call of the model.

Non-smooth points
    A model with a switch (the MMG rudder's γ_R, which changes with the sign of β_R, zero in a
    straight run) has no Jacobian on the switch, and the central difference there is the mean
    of the two one-sided derivatives: a model of neither side (the KVLCC2's straight run gave
    T_1 = −2400 s, between +91 s on one side and −82 s on the other). :func:`linearize_at`
    therefore also takes the one-sided quotients of every column and compares them
    (:mod:`seahelm.numerics.nonsmooth`); where they differ, :attr:`LinearModel.kinks` names
    the variables, :attr:`LinearModel.sides` holds the linear model of each side and
    :attr:`LinearModel.note` says why. At a smooth point the result is the central
    difference, unchanged.

The operating point is an equilibrium of the model's own states: position and heading move
freely (ẋ_N = U, ψ̇ = r in a turn), so they are not zero there; only the velocities (and the
actuator) are at rest. A linear model is exact about any point in its linear states.

References
----------
Richardson, L. F. (1911). The approximate arithmetical solution by finite differences of
physical problems. Phil. Trans. R. Soc. A 210, 307–357.
Ridders, C. J. F. (1982). Accurate computation of F'(x) and F'(x)F''(x). Adv. Eng. Softw. 4(2).
Squire, W., Trapp, G. (1998). Using complex variables to estimate derivatives of real
functions. SIAM Review 40(1), 110–112.
Dahlquist, G., Björck, Å. (2008). Numerical Methods in Scientific Computing, vol. 1. SIAM.
Fossen, T. I. (2021). Handbook of Marine Craft Hydrodynamics and Motion Control, 2nd ed.
Wiley, §7.1 (linear steering models).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from ..._optional import optional_import
from ..._validate import check_positive
from ...errors import ParameterError
from ...parameters import Params, as_records
from ...vessels.base import VesselModel, _batched_actuator, _param_array
from ...numerics.nonsmooth import kinked_columns, one_sided_jacobians, side_jacobians

__all__ = ["LinearModel", "richardson_jacobian", "linearize_at", "linearize"]

_EPS = np.finfo(float).eps


@dataclasses.dataclass(frozen=True, eq=False)
class LinearModel:
    """A linear state-space model with named, unit-carrying signals, about an operating point.

    Attributes
    ----------
    A, B, C, D : numpy.ndarray
        δż = A δz + B δv, δy = C δz + D δv (SI units, radians, seconds).
    state_labels, state_units, input_labels, input_units, output_labels, output_units
        Names and units of z, v and y.
    x0, u0, y0 : numpy.ndarray
        The operating point: states, inputs and outputs there.
    error : dict of str to numpy.ndarray
        Estimated absolute error of each entry of ``A``, ``B``, ``C``, ``D`` (zero where a
        matrix is known exactly).
    name : str
        What was linearised and where (for titles).
    speed : float
        The speed U [m/s] at the operating point (nan if unknown).
    length : float
        The ship's length L [m] (nan if unknown), for non-dimensional indices.
    kinks : tuple of str
        The states and inputs whose Jacobian column jumps at the point (empty: smooth). Where
        not empty, ``A``, ``B``, ``C``, ``D`` are the central difference, the *mean* of the
        two sides, which is a model of neither: use ``sides``.
    sides : tuple of LinearModel
        At a kink, the one-sided linear models (side "+" and side "−", module docstring of
        :mod:`seahelm.numerics.nonsmooth`); empty at a smooth point.
    side : str
        For a one-sided model, its side: ``"sway_speed +, yaw_rate −"`` is the side reached by
        increasing the sway speed or decreasing the yaw rate.
    note : str
        Why the point is not smooth (empty at a smooth point).
    """

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray
    state_labels: tuple[str, ...]
    state_units: tuple[str, ...]
    input_labels: tuple[str, ...]
    input_units: tuple[str, ...]
    output_labels: tuple[str, ...]
    output_units: tuple[str, ...]
    x0: np.ndarray
    u0: np.ndarray
    y0: np.ndarray
    error: dict[str, np.ndarray] = dataclasses.field(default_factory=dict)
    name: str = ""
    speed: float = math.nan
    length: float = math.nan
    kinks: tuple[str, ...] = ()
    sides: tuple["LinearModel", ...] = ()
    side: str = ""
    note: str = ""

    def __post_init__(self) -> None:
        n, m, p = len(self.state_labels), len(self.input_labels), len(self.output_labels)
        for key, shape in (("A", (n, n)), ("B", (n, m)), ("C", (p, n)), ("D", (p, m))):
            value = np.asarray(getattr(self, key), dtype=float)
            if value.shape != shape:
                raise ParameterError(f"must have shape {shape}, got {value.shape}", field=key)
            object.__setattr__(self, key, value)
        for key, ref in (("state_units", n), ("input_units", m), ("output_units", p)):
            if len(getattr(self, key)) != ref:
                raise ParameterError(f"must have {ref} entries", field=key)

    @property
    def smooth(self) -> bool:
        """Whether the model is differentiable at the point (no kinks)."""
        return not self.kinks

    @property
    def poles(self) -> np.ndarray:
        """Eigenvalues of A [1/s]."""
        return np.linalg.eigvals(self.A)

    def _index(self, kind: str, names: Sequence[str] | None) -> list[int]:
        labels = getattr(self, f"{kind}_labels")
        if names is None:
            return list(range(len(labels)))
        missing = [x for x in names if x not in labels]
        if missing:
            raise ParameterError(f"no {kind} {', '.join(missing)}; {kind}s: "
                                 f"{', '.join(labels)}", field=f"{kind}s")
        return [labels.index(x) for x in names]

    def select(self, *, states: Sequence[str] | None = None,
               inputs: Sequence[str] | None = None,
               outputs: Sequence[str] | None = None) -> "LinearModel":
        """The sub-model on some states, inputs and outputs (by name; default all).

        Dropping states drops their coupling: meaningful when the dropped states do not feed
        the kept ones (position and heading of a straight run, say).

        Parameters
        ----------
        states, inputs, outputs : sequence of str, optional
            Names to keep, in the wanted order.

        Returns
        -------
        LinearModel
        """
        i, j, k = (self._index(kind, names) for kind, names in
                   (("state", states), ("input", inputs), ("output", outputs)))
        err = {key: value[np.ix_(*idx)] for key, value in self.error.items()
               for idx in [{"A": (i, i), "B": (i, j), "C": (k, i), "D": (k, j)}[key]]}
        kept = {self.state_labels[a] for a in i} | {self.input_labels[b] for b in j}
        return dataclasses.replace(
            self, kinks=tuple(x for x in self.kinks if x in kept),
            sides=tuple(m.select(states=states, inputs=inputs, outputs=outputs)
                        for m in self.sides),
            A=self.A[np.ix_(i, i)], B=self.B[np.ix_(i, j)], C=self.C[np.ix_(k, i)],
            D=self.D[np.ix_(k, j)], state_labels=tuple(self.state_labels[a] for a in i),
            state_units=tuple(self.state_units[a] for a in i),
            input_labels=tuple(self.input_labels[a] for a in j),
            input_units=tuple(self.input_units[a] for a in j),
            output_labels=tuple(self.output_labels[a] for a in k),
            output_units=tuple(self.output_units[a] for a in k),
            x0=self.x0[i], u0=self.u0[j], y0=self.y0[k], error=err)

    def __repr__(self) -> str:
        from ..._repr import linear_model_summary, summary_text

        return summary_text(*linear_model_summary(self))

    def _repr_html_(self) -> str:
        from ..._repr import linear_model_summary, summary_html

        return summary_html(*linear_model_summary(self))

    def to_numpy(self) -> dict[str, Any]:
        """The matrices and the names and units, as plain numpy arrays and tuples.

        Returns
        -------
        dict
            ``A``, ``B``, ``C``, ``D``, ``x0``, ``u0``, ``y0`` and the ``*_labels``/``*_units``.
        """
        out: dict[str, Any] = {k: np.array(getattr(self, k)) for k in
                               ("A", "B", "C", "D", "x0", "u0", "y0")}
        for kind in ("state", "input", "output"):
            out[f"{kind}_labels"] = getattr(self, f"{kind}_labels")
            out[f"{kind}_units"] = getattr(self, f"{kind}_units")
        return out

    def to_control(self) -> Any:
        """A python-control ``StateSpace`` with the state, input and output names attached.

        Returns
        -------
        control.StateSpace
            Continuous time; ``sys.state_labels`` etc. are this model's labels.

        Raises
        ------
        MissingDependencyError
            Without python-control (``pip install 'seahelm[control]'``).
        """
        ct = optional_import("control", purpose="exporting a linear model")
        return ct.ss(self.A, self.B, self.C, self.D, states=list(self.state_labels),
                     inputs=list(self.input_labels), outputs=list(self.output_labels),
                     name=self.name or None)


# ------------------------------------------------------------------------------------------
# the Jacobian
# ------------------------------------------------------------------------------------------
def richardson_jacobian(f: Callable[[np.ndarray], np.ndarray], x0: Any, step: Any, *,
                        levels: int = 4) -> tuple[np.ndarray, np.ndarray]:
    """∂f/∂x at x0 by Richardson-extrapolated central differences (module docstring).

    Parameters
    ----------
    f : callable
        ``f(X)`` for X of shape (k, n) returns shape (k, m): one batched call evaluates every
        perturbed point.
    x0 : array_like, shape (n,)
        Where to differentiate.
    step : array_like, shape (n,)
        The largest step h_j of each variable (> 0); the tableau halves it ``levels − 1`` times.
    levels : int, optional
        Rows of the tableau (≥ 2; default 4: error O(h⁸) for a smooth f).

    Returns
    -------
    jacobian : numpy.ndarray, shape (m, n)
    error : numpy.ndarray, shape (m, n)
        Estimated absolute error of each entry: the last Richardson correction plus the
        rounding error of the differences.

    Raises
    ------
    ParameterError
        If a step is not positive and finite, or ``levels`` < 2.
    """
    x0 = np.asarray(x0, dtype=float)
    h = np.broadcast_to(np.asarray(step, dtype=float), x0.shape)
    if not np.all(np.isfinite(h) & (h > 0)):
        raise ParameterError(f"must be > 0 and finite, got {h!r}", field="step")
    if levels < 2:
        raise ParameterError(f"must be >= 2, got {levels!r}", field="levels", value=levels)
    n = x0.size
    hk = h[None, :] / 2.0 ** np.arange(levels)[:, None]  # (levels, n)
    eye = np.eye(n)
    plus = x0 + hk[:, :, None] * eye  # (levels, n, n): row j perturbs variable j
    minus = x0 - hk[:, :, None] * eye
    values = np.asarray(f(np.concatenate([plus, minus]).reshape(-1, n)), dtype=float)
    m = values.shape[-1]
    values = values.reshape(2, levels, n, m)
    diff = (values[0] - values[1]) / (2.0 * hk[:, :, None])  # (levels, n, m)
    tableau = [diff]
    for i in range(1, levels):
        prev = tableau[-1]
        tableau.append(prev[1:] + (prev[1:] - prev[:-1]) / (4.0 ** i - 1.0))
    best, second = tableau[-1][0], tableau[-2][-1]
    # rounding: ε max|f| / h, amplified by at most Σ|weights| ≤ 2 per extrapolation level
    scale = np.max(np.abs(values), axis=(0, 1))  # (n, m)
    rounding = 2.0 ** levels * _EPS * scale / hk[-1][:, None]
    return best.T.copy(), (np.abs(best - second) + rounding).T.copy()


# ------------------------------------------------------------------------------------------
# model + actuator as one function of (z, v)
# ------------------------------------------------------------------------------------------
def _natural_size(unit: str, speed: float, length: float, value: float) -> float:
    """The size a perturbation of a signal of ``unit`` is relative to (module docstring)."""
    rate = speed / length if speed > 0 and length > 0 else 1.0
    size = {"m/s": speed if speed > 0 else 1.0, "rad/s": rate, "rad/s²": rate * rate,
            "m": length if length > 0 else 1.0, "rad": 1.0, "deg": 1.0}.get(unit)
    if size is None:  # N, N·m, 1/s, -: relative to the value itself
        size = 1.0
    return max(size, abs(value))


def linearize_at(model: VesselModel, params: Params | Any, x0: Any, u0: Any, *,
                 actuator: Any = None, actuator_params: Params | None = None,
                 disturbances: bool = False, d0: Any = None, step: float = 1e-3,
                 levels: int = 4, name: str = "", speed: float = math.nan,
                 length: float = math.nan) -> LinearModel:
    """Linearise ``model`` (and an actuator feeding it) about the point (x0, u0).

    Parameters
    ----------
    model : VesselModel
        The vessel model.
    params : Params or array_like
        Its parameters.
    x0 : array_like, shape (n_states,)
        The model state at the operating point.
    u0 : array_like, shape (n_inputs,) or mapping of str to float
        The model inputs there (by name: missing inputs are zero).
    actuator : Actuator, optional
        A steering gear between the commands and the model (its states follow the model's, at
        rest with their outputs equal to the model inputs they feed, command = output).
    actuator_params : Params, optional
        Its parameters (required with ``actuator``).
    disturbances : bool, optional
        Add the model's disturbance channels as inputs (default False).
    d0 : array_like, optional
        The disturbances at the operating point (default zero).
    step : float, optional
        Largest relative step of the differences (default 10⁻³ of each signal's natural size).
    levels : int, optional
        Rows of the Richardson tableau (default 4).
    name : str, optional
        A title for the result.
    speed, length : float, optional
        U [m/s] and L [m]: the natural sizes of speeds, rates and positions (default: the
        ``speed`` output at x0 and the parameter ``length`` where they exist).

    Returns
    -------
    LinearModel

    Raises
    ------
    ParameterError
        For a state or input vector of the wrong length, an actuator without parameters, an
        actuator output that is not a model input, or a non-finite model at the point.
    """
    check_positive("step", step, "-")
    p_row = _param_array(params, model.params_type)
    x0 = np.asarray(x0, dtype=float)
    if x0.shape != (model.n_states,):
        raise ParameterError(f"must have {model.n_states} states ({', '.join(model.state_labels)})"
                             f", got shape {x0.shape}", field="x0")
    if isinstance(u0, dict):
        unknown = set(u0) - set(model.input_labels)
        if unknown:
            raise ParameterError(f"no model input {', '.join(sorted(unknown))}; inputs: "
                                 f"{', '.join(model.input_labels)}", field="u0")
        u0 = np.array([float(u0.get(k, 0.0)) for k in model.input_labels])
    u0 = np.asarray(u0, dtype=float)
    if u0.shape != (model.n_inputs,):
        raise ParameterError(f"must have {model.n_inputs} inputs, got shape {u0.shape}",
                             field="u0")
    d0 = np.zeros(model.n_disturbances) if d0 is None else np.asarray(d0, dtype=float)
    if math.isnan(length):
        length = float(getattr(params, "length", math.nan)) if isinstance(params, Params) \
            else math.nan
    if math.isnan(speed) and "speed" in model.output_labels:
        speed = float(model.outputs(0.0, x0, u0, p_row)[model.output_index("speed")])

    # the actuator: which model inputs it feeds, its states at rest there
    if actuator is not None and not actuator.passthrough:
        if actuator_params is None:
            raise ParameterError("is required with an actuator", field="actuator_params")
        missing = [o for o in actuator.output_labels if o not in model.input_labels]
        if missing:
            raise ParameterError(f"actuator output(s) {', '.join(missing)} are not inputs of "
                                 f"model '{model.name}'", field="actuator")
        fed = [model.input_labels.index(o) for o in actuator.output_labels]
        pa_row = _param_array(actuator_params, actuator.params_type)
        xa0 = u0[fed].copy()  # a servo at rest: its state is its output, the command the same
        ca0 = u0[fed].copy()
        act_states, act_units = actuator.state_labels, actuator.state_units
        act_cmds, act_cmd_units = actuator.command_labels, actuator.command_units
    else:
        actuator, fed, xa0, ca0 = None, [], np.zeros(0), np.zeros(0)
        act_states = act_units = act_cmds = act_cmd_units = ()
    direct = [j for j in range(model.n_inputs) if j not in fed]
    n, na = model.n_states, len(xa0)
    nc, nd = len(ca0), len(direct)
    z0 = np.concatenate([x0, xa0])
    v0 = np.concatenate([ca0, u0[direct]] + ([d0] if disturbances else []))

    def split(Z: np.ndarray, V: np.ndarray) -> tuple[np.ndarray, ...]:
        k = Z.shape[0]
        U = np.empty((k, model.n_inputs))
        dxa = np.zeros((k, na))
        if actuator is not None:
            ya = np.empty((k, len(fed)))
            _batched_actuator(actuator.rhs, actuator.output, 0.0,
                              np.ascontiguousarray(Z[:, n:]), np.ascontiguousarray(V[:, :nc]),
                              as_records(np.repeat(pa_row[None], k, 0), actuator.params_type),
                              dxa, ya)
            U[:, fed] = ya
        U[:, direct] = V[:, nc:nc + nd]
        D = V[:, nc + nd:] if disturbances else np.broadcast_to(d0, (k, model.n_disturbances))
        return U, D, dxa

    def f(W: np.ndarray) -> np.ndarray:
        Z, V = W[:, :n + na], W[:, n + na:]
        U, D, dxa = split(Z, V)
        dx = model.derivative(0.0, Z[:, :n], U, p_row, D)
        y = model.outputs(0.0, Z[:, :n], U, p_row)
        return np.concatenate([dx, dxa, y], axis=1)

    w0 = np.concatenate([z0, v0])
    f0 = f(w0[None])[0]
    if not np.all(np.isfinite(f0)):
        raise ParameterError(f"the model is not finite at the operating point ({f0})",
                             field="x0")
    in_labels = act_cmds + tuple(model.input_labels[j] for j in direct) + (
        model.disturbance_labels if disturbances else ())
    in_units = act_cmd_units + tuple(model.input_units[j] for j in direct) + (
        model.disturbance_units if disturbances else ())
    units = model.state_units + act_units + in_units
    sizes = np.array([_natural_size(u, speed, length, w) for u, w in zip(units, w0)])
    J, E = richardson_jacobian(f, w0, step * sizes, levels=levels)
    nz = n + na
    labels = model.state_labels + act_states + in_labels

    def build(J: np.ndarray, E: np.ndarray, **extra: Any) -> LinearModel:
        return LinearModel(
            A=J[:nz, :nz], B=J[:nz, nz:], C=J[nz:, :nz], D=J[nz:, nz:],
            state_labels=model.state_labels + act_states,
            state_units=model.state_units + act_units, input_labels=in_labels,
            input_units=in_units, output_labels=model.output_labels,
            output_units=model.output_units, x0=z0, u0=v0, y0=f0[nz:],
            error={"A": E[:nz, :nz], "B": E[:nz, nz:], "C": E[nz:, :nz], "D": E[nz:, nz:]},
            speed=float(speed), length=float(length), **extra)

    title = name or model.name
    one_sided = one_sided_jacobians(f, w0, step * sizes, levels=levels)
    kink = kinked_columns(*one_sided, step * sizes, f=f, x0=w0, levels=levels)
    if not kink.columns:
        return build(J, E, name=title)
    names = tuple(labels[j] for j in kink.columns)
    refs = sorted({r for r in kink.reference if r >= 0})
    sides = []
    for (Js, Es), sign in zip(side_jacobians(*one_sided, J, E, kink), "+−"):
        side = ", ".join(f"{labels[r]} {sign}" for r in refs)
        sides.append(build(Js, Es, name=f"{title}, side {side}", side=side))
    note = (f"the model has no derivative here: the one-sided derivatives in "
            f"{', '.join(names)} differ (by up to "
            f"{', '.join(f'{100 * x:.3g} %' for x in kink.jump)} of the row scale)")
    if kink.switches > 1:
        note += f"; {kink.switches} switches meet here"
    return build(J, E, name=title, kinks=names, sides=tuple(sides), note=note)


def linearize(ship: Any, *, speed: float | None = None, rudder: float | None = None,
              rps: float | None = None, model: VesselModel | None = None,
              actuator: bool = True, disturbances: bool = False, step: float = 1e-3,
              levels: int = 4) -> LinearModel:
    """Linearise a ship at its trimmed straight run, or at a steady turn.

    Parameters
    ----------
    ship : Ship, str, path or Params
        A ship (catalog name or ship file), or a parameter set (with ``model=`` where its type
        does not name one).
    speed : float, optional
        Approach speed U [m/s] of the straight run (default: the ship's test speed). A
        perturbation or constant-speed model admits its own speed only.
    rudder : float, optional
        Rudder angle δ [rad] of a steady turn (positive to starboard); default: the trimmed
        straight run (:func:`~seahelm.analysis.equilibria.equilibrium.approach_state` with
        ``trim``).
    rps : float, optional
        Propeller rps [1/s] of the turn for a model with a propeller (default: the
        self-propulsion rps of the straight run at ``speed``).
    model : VesselModel, optional
        The model, for a bare parameter set.
    actuator : bool, optional
        Include the ship's steering gear (default True; then the rudder input is the
        ``rudder_command``).
    disturbances : bool, optional
        Add the model's disturbance channels as inputs.
    step, levels : optional
        As :func:`linearize_at`.

    Returns
    -------
    LinearModel

    Raises
    ------
    ParameterError
        For a bad speed (≤ 0, or not the speed of a model that has only one).
    EquilibriumError
        If no equilibrium is found (no straight run at that speed, no turn at that rudder).
    """
    from ...ships import Ship, get_ship
    from .equilibrium import approach_state, steady_turn_state

    if isinstance(ship, Params):
        params, gear, ship_name = ship, None, type(ship).__name__
        base = ship
        if model is None:
            from ...registry import model_for_params
            model = model_for_params(type(ship))
        if model is None:
            raise ParameterError(f"no default model for {type(ship).__name__}; pass `model=`",
                                 field="model")
    else:
        obj = ship if isinstance(ship, Ship) else get_ship(ship)
        params, gear, ship_name, model = obj.params, obj.steering_gear, obj.name, obj.model
        base = obj
        if speed is None and obj.test_speed is not None:
            speed = obj.test_speed
    if speed is not None:
        check_positive("speed", speed, "m/s")
    straight = approach_state(base, speed, model=model, trim=True)
    if rudder is None:
        point, where = straight, "straight run"
    else:
        if rps is None:
            rps = straight.inputs.get("propeller_rps")
        point = steady_turn_state(base, rudder, rps, model=model)
        where = f"steady turn at rudder {math.degrees(rudder):.4g} deg"
    use_gear = actuator and gear is not None
    linear = linearize_at(
        model, params, point.state, dict(point.inputs),
        actuator=gear.actuator if use_gear else None,
        actuator_params=gear.params if use_gear else None, disturbances=disturbances,
        step=step, levels=levels, name=f"{ship_name}, {where}")
    return _with_reason(linear, params)


def _with_reason(linear: LinearModel, params: Any) -> LinearModel:
    """Name the switch of an MMG model's rudder inflow where the point is not smooth."""
    minus, plus = (getattr(params, k, None) for k in ("gamma_R_minus", "gamma_R_plus"))
    if linear.smooth or minus is None or minus == plus:
        return linear
    why = (f"; the rudder's flow-straightening coefficient γ_R switches between {minus:.4g} "
           f"(β_R < 0) and {plus:.4g} (β_R > 0), β_R = β − l'_R r', which is zero in a "
           "straight run (Yasukawa & Yoshimura 2015)")
    # β = atan2(−v, u): more sway speed is less β_R (mmg.py), more yaw rate more if l'_R < 0
    which = {"sway_speed +": "β_R < 0", "sway_speed −": "β_R > 0"}
    sides = []
    for m in linear.sides:
        where = which.get(m.side)
        side = m.side if where is None else (
            f"{m.side} ({where}: γ_R = {minus if where == 'β_R < 0' else plus:.4g})")
        sides.append(dataclasses.replace(m, note=linear.note + why, side=side,
                                         name=m.name.replace(m.side, side)))
    return dataclasses.replace(linear, note=linear.note + why, sides=tuple(sides))
