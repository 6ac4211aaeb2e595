"""A python-control linear system as a seahelm controller, run compiled in the batched engine.

Design in python-control, simulate batched in seahelm: :func:`state_space_controller` takes a
python-control ``StateSpace`` (or ``TransferFunction``, converted by ``control.ss``) whose
inputs and outputs are *named after seahelm signals* and returns a
:class:`~seahelm.control.base.Controller`. Discrete-time systems run as they are (at their
sample period); continuous-time systems are sampled at the controller period ``dt`` by
python-control's ``StateSpace.sample`` (``method``: zero-order hold by default, or ``foh``,
``tustin``/``bilinear``, ``euler``, ``backward_diff``). At every controller sample t_k the
engine computes, in compiled code::

    w_k     = the system's inputs, read by name (below)
    u_k     = u₀ + C x_k + D (w_k − w₀)             → the commands (the system's outputs)
    x_{k+1} = A x_k + B (w_k − w₀)

with u₀ = ``output_offset`` and w₀ = ``input_offset`` (the operating point of a design in
deviation variables, e.g. the self-propulsion rps on a ``propeller_rps`` output; default zero)
and x₀ = ``initial_state`` (default zero). The command is held until the next sample, as for
every seahelm controller. This is python-control's discrete-time state-space recursion
(``control.forced_response`` of the sampled system), so a closed loop in seahelm equals
python-control's of the plant sampled by zero-order hold (the test: 1e-9 on a Nomoto ship).

Naming the inputs
    Each input of the system is a signal seahelm routes by name:

    * ``<output>``: a model output (a measurement): ``heading``, ``yaw_rate``, ``sway_speed``,
      ``north``, ``east``, ...;
    * ``<output>_error``: reference minus measurement, r − y (python-control's
      ``feedback`` sign), with a reference channel ``<output>``; ``heading_error`` is wrapped
      to [−π, π) (a course through north);
    * ``<output>_reference``: the reference channel ``<output>`` itself (two-degree-of-freedom
      designs).

    Without ``model`` the outputs are the navigation outputs every model declares
    (:data:`~seahelm.vessels.base.NAV_OUTPUTS`); ``model=`` admits that model's other outputs.
    The system's outputs are the controller's commands, connected by name as any controller's
    (``rudder_command`` to a steering gear, ``propeller_rps`` to the model input).
    python-control names unnamed signals ``u[0]``, ``y[0]``: name them with
    ``control.ss(A, B, C, D, inputs=[...], outputs=[...])`` or ``sys.update_names``.

The matrices are parameters (the subset that can be wrapped, and why)
    The compiled step is generated once per *structure* (number of states, the routing of the
    inputs, number of outputs) and cached on disk like the engine's kernels
    (:func:`seahelm._codegen.import_generated`); the matrices, offsets and initial state are
    the controller's parameters (``a``, ``b``, ``c``, ``d`` row-major, ``input_offset``,
    ``output_offset``, ``initial_state``), whose defaults are the given design. So a batch may
    run a different design in every run (:meth:`StateSpaceController.params_for`: a sweep
    over LQ weights, a Monte-Carlo over a plant's coefficients) with one compilation, and a new
    design of the same shape compiles nothing. What can be wrapped is therefore a linear
    time-invariant system: ``StateSpace`` (also ``LinearICSystem``, an interconnection of
    linear systems) and ``TransferFunction``, continuous or discrete, MIMO, static gains
    included. A ``NonlinearIOSystem`` is refused: its update and output functions are Python
    callables (over python-control's ``params``) that numba cannot compile into the batched
    loop; linearise it (``sys.linearize(xeq, ueq)``) and wrap the result, or write the law as
    a seahelm controller (:mod:`seahelm.control.base`). A ``FrequencyResponseData`` has no
    state-space realisation and is refused too. No saturation or anti-windup is added (the
    wrapped system is linear): the steering gear's angle and rate limits act downstream, and
    an integrator of the design winds up while the rudder is saturated.

The sample period is part of the controller (:attr:`Controller.sample_period`): a run at
another ``controller_dt`` is refused when the problem is built. A controller whose sampled
system has a pole outside the unit circle is refused unless ``allow_unstable=True`` (integral
action, a pole on the circle, is accepted).

References
----------
Fossen, T. I. (2021). Handbook of Marine Craft Hydrodynamics and Motion Control, 2nd ed.
Wiley, §15.1 (discrete-time autopilots).
Franklin, G. F., Powell, J. D., Workman, M. L. (1998). Digital Control of Dynamic Systems,
3rd ed., §4.3 (zero-order-hold equivalents), §6.3 (Tustin).
"""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Sequence
from typing import Any

import numpy as np
from numba import njit

from .._optional import optional_import
from ..errors import ParameterError
from ..parameters import Params, param
from ..vessels.base import NAV_OUTPUT_UNITS, NAV_OUTPUTS
from .base import Controller, wrap_pi

__all__ = ["SAMPLING_METHODS", "StateSpaceController", "state_space_controller"]

#: Methods of python-control's ``StateSpace.sample`` accepted for a continuous-time system.
SAMPLING_METHODS = ("zoh", "foh", "tustin", "bilinear", "euler", "backward_diff")

#: Signals whose error (reference − measurement) is wrapped to [−π, π).
WRAPPED = ("heading",)

_MEASUREMENT, _ERROR, _REFERENCE = 0, 1, 2


# ------------------------------------------------------------------------------------------
# compiled: the discrete recursion over the matrices in the parameter record
# ------------------------------------------------------------------------------------------
@njit(cache=True)
def state_space_inputs(y, ref, p, w, kind, meas, refs, wrap):  # pragma: no cover - compiled
    """w_k − w₀: each input read from the measurements or references by its routing."""
    for k in range(w.shape[0]):
        if kind[k] == _MEASUREMENT:
            value = y[meas[k]]
        elif kind[k] == _ERROR:
            value = ref[refs[k]] - y[meas[k]]
            if wrap[k]:
                value = wrap_pi(value)
        else:
            value = ref[refs[k]]
        w[k] = value - p.input_offset[k]


@njit(cache=True)
def state_space_init(p, cs, nx):  # pragma: no cover - compiled
    """x₀ = ``initial_state``."""
    for i in range(nx):
        cs[i] = p.initial_state[i]


@njit(cache=True)
def state_space_step(p, cs, w, cmd, nx, nw, nu):  # pragma: no cover - compiled
    """u = u₀ + C x + D w into ``cmd``; then x ← A x + B w (``cs``: x, then n scratch)."""
    for j in range(nu):
        acc = p.output_offset[j]
        for i in range(nx):
            acc += p.c[j * nx + i] * cs[i]
        for k in range(nw):
            acc += p.d[j * nw + k] * w[k]
        cmd[j] = acc
    for i in range(nx):
        acc = 0.0
        for jj in range(nx):
            acc += p.a[i * nx + jj] * cs[jj]
        for k in range(nw):
            acc += p.b[i * nw + k] * w[k]
        cs[nx + i] = acc
    for i in range(nx):
        cs[i] = cs[nx + i]


@njit(cache=True)
def state_space_static(p, w, cmd, nw, nu):  # pragma: no cover - compiled
    """u = u₀ + D w (a system without states)."""
    for j in range(nu):
        acc = p.output_offset[j]
        for k in range(nw):
            acc += p.d[j * nw + k] * w[k]
        cmd[j] = acc


# ------------------------------------------------------------------------------------------
# the controller
# ------------------------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True, eq=False)
class StateSpaceController(Controller):
    """A :class:`~seahelm.control.base.Controller` made from a linear system (module docstring).

    Attributes
    ----------
    system_inputs, system_outputs : tuple of str
        The system's input and output names (the outputs are the ``command_labels``).
    method : str
        How a continuous-time system was sampled (``""`` for a discrete one).
    n_system_states : int
        States of the sampled system.
    known_outputs : tuple of str
        The model outputs its inputs were checked against.
    """

    system_inputs: tuple[str, ...] = ()
    system_outputs: tuple[str, ...] = ()
    method: str = ""
    n_system_states: int = 0
    known_outputs: tuple[str, ...] = ()

    def params_for(self, sys: Any, *, input_offset: Any = None, output_offset: Any = None,
                   initial_state: Any = None, allow_unstable: bool = False) -> Params:
        """This controller's parameters for another system of the same structure.

        The batch form: ``simulate(..., controller=ctl, controller_params=[ctl.params_for(s)
        for s in designs])`` runs one design per run with one compilation.

        Parameters
        ----------
        sys : control.StateSpace or control.TransferFunction
            A system with the same input and output names and number of states (continuous
            ones are sampled as this controller's were).
        input_offset, output_offset, initial_state : array_like, optional
            As :func:`state_space_controller`.
        allow_unstable : bool, optional
            As :func:`state_space_controller`.

        Returns
        -------
        Params
            An instance of :attr:`params_type`.

        Raises
        ------
        ParameterError
            For a system of another structure (field ``sys``) or a bad offset.
        """
        period = self.sample_period
        spec = _system(sys, period if period else None, self.method or "zoh", allow_unstable)
        if (spec.inputs, spec.outputs, spec.a.shape[0]) != (
                self.system_inputs, self.system_outputs, self.n_system_states):
            raise ParameterError(
                f"must have the structure of controller '{self.name}' (inputs "
                f"{', '.join(self.system_inputs)}; outputs {', '.join(self.system_outputs)}; "
                f"{self.n_system_states} states), got inputs {', '.join(spec.inputs)}; outputs "
                f"{', '.join(spec.outputs)}; {spec.a.shape[0]} states", field="sys")
        if spec.dt and period and abs(spec.dt - period) > 1e-9 * period:
            raise ParameterError(f"has sample period {spec.dt!r} s; controller '{self.name}' "
                                 f"runs at {period!r} s", field="sys", unit="s", value=spec.dt)
        return self.params_type(**_values(spec, input_offset, output_offset, initial_state))


@dataclasses.dataclass(frozen=True)
class _Spec:
    a: np.ndarray
    b: np.ndarray
    c: np.ndarray
    d: np.ndarray
    dt: float  # 0: a static gain (any period)
    inputs: tuple[str, ...]
    outputs: tuple[str, ...]
    states: tuple[str, ...]
    name: str
    sampled: bool  # a continuous-time system, sampled here


def _system(sys: Any, dt: float | None, method: str, allow_unstable: bool) -> _Spec:
    """The sampled matrices and names of ``sys``, checked."""
    ct = optional_import("control", purpose="wrapping a python-control system")
    given_name = str(getattr(sys, "name", "") or "")
    if isinstance(sys, ct.TransferFunction):
        sys = ct.ss(sys)
    if not isinstance(sys, ct.StateSpace):
        if isinstance(sys, ct.NonlinearIOSystem):
            raise ParameterError(
                f"is a python-control {type(sys).__name__}: its update and output functions "
                "are Python callables that numba cannot compile into the batched loop. A "
                "linear time-invariant system (StateSpace, LinearICSystem, TransferFunction) "
                "can be wrapped: linearise it (sys.linearize(xeq, ueq)), or write the law as "
                "a seahelm Controller", field="sys")
        raise ParameterError(
            "must be a python-control StateSpace or TransferFunction (a linear time-invariant "
            f"system with named inputs and outputs), got {type(sys).__name__}", field="sys")
    for key in ("A", "B", "C", "D"):
        m = np.asarray(getattr(sys, key), dtype=float)
        if not np.all(np.isfinite(m)):
            raise ParameterError(f"has non-finite entries in its {key} matrix: {m.tolist()}",
                                 field="sys")
    if method not in SAMPLING_METHODS:
        raise ParameterError(f"must be one of {', '.join(SAMPLING_METHODS)}, got {method!r}",
                             field="method", value=method)
    n = sys.nstates
    if dt is not None and not (isinstance(dt, (int, float)) and not isinstance(dt, bool)
                               and math.isfinite(dt) and dt > 0):
        raise ParameterError(f"must be > 0 [s], got {dt!r}", field="dt", unit="s", value=dt)
    sampled = False
    if n == 0:  # a static gain: the same at any period
        period = 0.0
    elif sys.isctime(strict=True):
        sampled = True
        if dt is None:
            raise ParameterError(
                "is needed to sample a continuous-time system (the controller period [s])",
                field="dt", unit="s")
        sys = sys.sample(float(dt), method=method)
        period = float(dt)
    else:
        if sys.dt is True or sys.dt is None:  # a discrete system of unspecified period
            if dt is None:
                raise ParameterError("is needed: the discrete system does not say its sample "
                                     "period [s]", field="dt", unit="s")
            period = float(dt)
        else:
            period = float(sys.dt)
            if dt is not None and abs(dt - period) > 1e-9 * period:
                raise ParameterError(
                    f"must be the discrete system's sample period {period!r} s, got {dt!r} (a "
                    "discrete system runs at its own period)", field="dt", unit="s", value=dt)
    a, b, c, d = (np.atleast_2d(np.asarray(getattr(sys, k), dtype=float)) for k in "ABCD")
    if n:
        poles = np.linalg.eigvals(a)
        bad = poles[np.abs(poles) > 1.0 + 1e-9]
        if bad.size and not allow_unstable:
            raise ParameterError(
                f"is an unstable controller: sampled at {period:g} s it has poles "
                f"{', '.join(f'{z:.6g}' for z in bad)} outside the unit circle (|z| up to "
                f"{np.abs(bad).max():.6g}); pass allow_unstable=True if that is the design",
                field="sys")
    return _Spec(a=a.reshape(n, n), b=b.reshape(n, sys.ninputs),
                 c=c.reshape(sys.noutputs, n), d=d.reshape(sys.noutputs, sys.ninputs),
                 dt=period, inputs=tuple(sys.input_labels), outputs=tuple(sys.output_labels),
                 states=tuple(sys.state_labels), name=given_name, sampled=sampled)


def _vector(name: str, value: Any, size: int, what: str) -> tuple[float, ...]:
    if value is None:
        return (0.0,) * size
    arr = np.asarray(value, dtype=float).ravel() if not isinstance(value, dict) else None
    if arr is None or arr.shape != (size,):
        raise ParameterError(f"must have {size} values ({what}), got {value!r}", field=name)
    if not np.all(np.isfinite(arr)):
        raise ParameterError(f"must be finite, got {value!r}", field=name)
    return tuple(float(v) for v in arr)


def _values(spec: _Spec, input_offset: Any, output_offset: Any,
            initial_state: Any) -> dict[str, Any]:
    n, m, p = spec.a.shape[0], len(spec.inputs), len(spec.outputs)
    values: dict[str, Any] = {
        "d": tuple(spec.d.ravel()),
        "input_offset": _vector("input_offset", input_offset, m,
                                "one per input: " + ", ".join(spec.inputs)),
        "output_offset": _vector("output_offset", output_offset, p,
                                 "one per output: " + ", ".join(spec.outputs))}
    if n:
        values.update(a=tuple(spec.a.ravel()), b=tuple(spec.b.ravel()),
                      c=tuple(spec.c.ravel()),
                      initial_state=_vector("initial_state", initial_state, n,
                                            "one per state: " + ", ".join(spec.states)))
    elif initial_state is not None and np.size(initial_state):
        raise ParameterError("must be empty: the system has no states", field="initial_state")
    return values


def _identifier(label: str) -> str:
    return re.sub(r"\W+", "_", label).strip("_") or "x"


def _routing(inputs: Sequence[str], known: dict[str, str]) -> tuple[list, tuple, tuple]:
    """(kind, signal) per input, the measurements and the references it reads."""
    routes: list[tuple[int, str]] = []
    for name in inputs:
        if name in known:
            routes.append((_MEASUREMENT, name))
        elif name.endswith("_error") and name[:-6] in known:
            routes.append((_ERROR, name[:-6]))
        elif name.endswith("_reference") and name[:-10] in known:
            routes.append((_REFERENCE, name[:-10]))
        else:
            raise ParameterError(
                f"has input '{name}', which is no signal seahelm can route: an input is a model "
                f"output ({', '.join(known)}), `<output>_error` (reference − output) or "
                "`<output>_reference` (name the inputs: control.ss(..., inputs=[...]); pass "
                "model= for a model's other outputs)", field="sys")
    meas = tuple(dict.fromkeys(s for k, s in routes if k != _REFERENCE))
    refs = tuple(dict.fromkeys(s for k, s in routes if k != _MEASUREMENT))
    return routes, meas, refs


def _params_type(spec: _Spec, defaults: dict[str, Any], title: str) -> type[Params]:
    n, m, p = spec.a.shape[0], len(spec.inputs), len(spec.outputs)
    rows = [("d", p * m, "D (row-major): commands per input"),
            ("input_offset", m, "w₀: inputs at the operating point"),
            ("output_offset", p, "u₀: commands at the operating point")]
    if n:
        rows = [("a", n * n, "A (row-major) of x_{k+1} = A x_k + B w_k"),
                ("b", n * m, "B (row-major)"), ("c", p * n, "C (row-major) of u = C x + D w"),
                *rows, ("initial_state", n, "x₀")]
    fields = [(name, tuple, param(defaults[name], size=size, doc=doc))
              for name, size, doc in rows]
    cls = dataclasses.make_dataclass(f"StateSpaceParams{n}x{m}x{p}", fields, bases=(Params,),
                                     frozen=True, kw_only=True)
    cls.__module__ = __name__
    cls.__doc__ = f"Matrices, offsets and initial state of {title} (sampled, SI units)."
    return cls


def state_space_controller(sys: Any, dt: float | None = None, *, method: str = "zoh",
                           model: Any = None, input_offset: Any = None,
                           output_offset: Any = None, initial_state: Any = None,
                           allow_unstable: bool = False,
                           name: str | None = None) -> StateSpaceController:
    """A python-control linear system as a compiled, batched seahelm controller.

    Parameters
    ----------
    sys : control.StateSpace or control.TransferFunction
        The controller, with inputs named after seahelm signals (``heading_error``,
        ``yaw_rate``, ...; module docstring) and outputs named after commands
        (``rudder_command``, ``propeller_rps``, ...). Continuous or discrete time.
    dt : float, optional
        Controller period [s]: where a continuous-time system is sampled (required for it);
        for a discrete system its own period (if given, it must agree).
    method : str, optional
        Sampling of a continuous-time system, one of :data:`SAMPLING_METHODS` (default
        ``"zoh"``, python-control's default; ``"tustin"`` keeps the frequency response's
        shape and maps stable to stable).
    model : VesselModel, optional
        The vessel model whose outputs the inputs may read (default: the navigation outputs
        :data:`~seahelm.vessels.base.NAV_OUTPUTS`); also gives the references' units.
    input_offset : array_like, optional
        w₀, one value per input (default zeros).
    output_offset : array_like, optional
        u₀, one value per output (default zeros): e.g. the self-propulsion rps.
    initial_state : array_like, optional
        x₀ of the sampled system (default zeros).
    allow_unstable : bool, optional
        Accept a controller with poles outside the unit circle (default False).
    name : str, optional
        The controller's name (default ``state-space:<sys.name>``).

    Returns
    -------
    StateSpaceController
        Its parameters' defaults are this design; its ``sample_period`` is the period.

    Raises
    ------
    ParameterError
        For something other than a linear python-control system (``sys``; a
        ``NonlinearIOSystem`` is named as such), non-finite matrices, an input that is no
        routable signal, outputs that are not distinct identifiers, an unstable controller
        (``sys``), a missing or conflicting ``dt``, an unknown ``method``, offsets or an
        initial state of the wrong length.
    MissingDependencyError
        Without python-control (``pip install 'seahelm[control]'``).
    """
    from .._codegen import code_fingerprint, content_digest, import_generated

    spec = _system(sys, dt, method, allow_unstable)
    if model is not None:
        known = dict(zip(model.output_labels, model.output_units))
    else:
        known = dict(zip(NAV_OUTPUTS, NAV_OUTPUT_UNITS))
    routes, meas, refs = _routing(spec.inputs, known)
    if len(set(spec.inputs)) != len(spec.inputs):
        raise ParameterError(f"has repeated input names: {', '.join(spec.inputs)}", field="sys")
    bad = [o for o in spec.outputs if not o.isidentifier()]
    if bad or len(set(spec.outputs)) != len(spec.outputs):
        raise ParameterError(
            f"must have distinct outputs named after commands (rudder_command, propeller_rps, "
            f"...), got {', '.join(spec.outputs)} (rename: sys.update_names(outputs=[...]))",
            field="sys")
    n, m, p = spec.a.shape[0], len(spec.inputs), len(spec.outputs)
    title = name or (f"state-space:{spec.name}" if spec.name else "state-space")
    defaults = _values(spec, input_offset, output_offset, initial_state)
    params_type = _params_type(spec, defaults, f"controller '{title}'")

    def ints(values: Sequence[int]) -> str:
        return f"np.array([{', '.join(str(v) for v in values)}, 0], dtype=np.int64)[:{m}]"

    kind = [k for k, _ in routes]
    source = (
        '"""Generated by seahelm.control.state_space: a linear system as a controller."""\n'
        "import numpy as np\nfrom numba import njit\n\n"
        "from seahelm.control.state_space import (state_space_init, state_space_inputs,\n"
        "                                         state_space_static, state_space_step)\n\n"
        f"NX = {n}\nNW = {m}\nNU = {p}\nKIND = {ints(kind)}\n"
        f"MEAS = {ints([meas.index(s) if k != _REFERENCE else -1 for k, s in routes])}\n"
        f"REFS = {ints([refs.index(s) if k != _MEASUREMENT else -1 for k, s in routes])}\n"
        f"WRAP = {ints([int(k == _ERROR and s in WRAPPED) for k, s in routes])}\n"
        f"W0 = {2 * n}\n\n\n"
        "@njit(cache=True)\n"
        "def ss_init(z, y, ref, p, cs):  # pragma: no cover - compiled\n"
        + ("    state_space_init(p, cs, NX)\n" if n else "    pass\n") + "\n\n"
        "@njit(cache=True)\n"
        "def ss_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled\n"
        "    w = cs[W0:W0 + NW]\n"
        "    state_space_inputs(y, ref, p, w, KIND, MEAS, REFS, WRAP)\n"
        + ("    state_space_step(p, cs, w, cmd, NX, NW, NU)\n" if n else
           "    state_space_static(p, w, cmd, NW, NU)\n"))
    digest = content_digest(source, *(code_fingerprint(f.py_func) for f in (
        state_space_init, state_space_inputs, state_space_static, state_space_step)))
    module = import_generated(f"seahelm_state_space_{digest}", source)
    states = [_identifier(s) for s in spec.states]
    states = [s if states.count(s) == 1 else f"{s}_{i}" for i, s in enumerate(states)]
    return StateSpaceController(
        name=title,
        description=f"linear {'discrete-time' if spec.dt else 'static'} controller from "
                    f"python-control ({n} states, inputs {', '.join(spec.inputs)}"
                    + (f"; period {spec.dt:g} s" if spec.dt else "")
                    + (f", sampled by {method}" if spec.sampled else "") + ")",
        params_type=params_type,
        state_labels=tuple(f"controller_{s}" for s in states)
        + tuple(f"controller_scratch_{i}" for i in range(n))
        + tuple(f"controller_input_{_identifier(w)}" for w in spec.inputs),
        reference_labels=refs,
        reference_units=tuple(known[r] for r in refs),
        command_labels=spec.outputs,
        init=module.ss_init,
        step=module.ss_step,
        measurement_labels=meas,
        sample_period=spec.dt or None,
        system_inputs=spec.inputs,
        system_outputs=spec.outputs,
        method=method if spec.sampled else "",
        n_system_states=n,
        known_outputs=tuple(known),
    )

