"""Set-points and clocks of a stepped batch: the controller's reference of a
:class:`~seahelm.Simulator`'s runs written between two steps (:func:`set_reference`), the
commands the loop holds now (:func:`held_commands`), every run's clock set back to t = 0
with its state kept (:func:`restart_clock`), and states of many runs set at once
(:func:`set_states`).

With ``commands=None`` :meth:`Simulator.step <seahelm.simulation.stepping.Simulator.step>` lets
the problem's controller (an autopilot) compute the commands inside the compiled loop from its
reference; an outside agent that gives that autopilot its set-point (:mod:`seahelm.gym`'s
set-point actions, a co-simulation master) writes the reference between steps. The loop reads
the reference array of the batch at every controller sample, so a set-point written before a
step is the one the controller sees over that step -- the same numbers as ``simulate`` with
that reference held constant.
"""

from __future__ import annotations

import re

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
from numba import njit

from ..errors import ParameterError
from ..parameters import Params
from .slicing import drive, quiet
from .stepping_io import restore_rows
from .stepping_io import Observation, _spans, check_commands, run_indices

if TYPE_CHECKING:  # pragma: no cover
    from .stepping import Simulator

__all__ = ["set_reference", "set_controller_param", "held_commands", "restart_clock",
           "restart_runs", "set_states", "advance_unobserved"]

#: Restarted runs above this share of the batch are observed with every run (one call of the
#: loop a slice, on the thread pool) rather than span by span.
_SPANS_SHARE = 0.25


def _reference_array(sim: "Simulator") -> np.ndarray:
    return sim._batch.slices.arrays.signals[1]


def set_reference(sim: "Simulator", values: Any, runs: Any = None) -> None:
    """Hold the controller's reference (its set-points) of some runs from the next step on.

    Parameters
    ----------
    sim : Simulator
        Built from a problem whose reference is one constant per run: a ``(runs, 1,
        references)`` array or a mapping of ``(runs, 1, 1)`` arrays (written in place: a time
        series or one reference for every run cannot hold a set-point per run).
    values : array_like or mapping
        By the problem's reference labels (``problem.wiring.references``, e.g. ``heading``
        [rad] for a heading autopilot) in their units: an array (selected runs, references) --
        or (references,) for every selected run -- or a mapping name -> value(s) (the
        references not named keep theirs).
    runs : int or sequence of int, optional
        The runs (default every run).

    Raises
    ------
    ParameterError
        Naming ``reference`` for a problem whose reference is not one per run (or is the
        caller's own array, which the loop would overwrite), else naming ``values`` on a wrong
        shape, an unknown name or a value that is not finite; nothing is written then.
    """
    ref = _reference_array(sim)
    given = sim.problem.reference
    if ref.shape[:2] != (sim.n_runs, 1) or (isinstance(given, np.ndarray)
                                             and np.shares_memory(ref, given)):
        raise ParameterError(
            f": the simulator's reference has shape {ref.shape}; a set-point written between "
            f"steps needs one constant reference per run of its own, shape ({sim.n_runs}, 1, "
            f"references) -- give Problem(reference={{name: array ({sim.n_runs}, 1, 1)}}) or a "
            "copy of an array of that shape", field="reference", value=ref.shape)
    wiring = sim.problem.wiring
    sel = run_indices(runs, sim.n_runs)
    try:
        checked = check_commands(values, sel, ref[sel, 0, :], wiring.references,
                                 wiring.reference_units)
    except ParameterError as exc:
        raise ParameterError(re.sub(r"\bcommand", "reference", exc.reason), field="values",
                             unit=exc.unit, value=exc.value, run=exc.run) from None
    ref[sel, 0, :] = checked


def set_controller_param(sim: "Simulator", name: str, values: Any, runs: Any = None) -> None:
    """Hold a parameter of the controller (a set-point that is a parameter, e.g. the
    ``propeller_rps`` a ``-rps`` autopilot holds) of some runs from the next step on.

    The loop reads each run's controller parameters at the start of every call, so a value
    written before a step is the one the controller uses over that step -- the numbers of
    ``simulate`` with the controller's parameters holding that value.

    Parameters
    ----------
    sim : Simulator
        A simulator whose problem has a controller with the parameter ``name``.
    name : str
        The parameter (a number, not a vector), e.g. ``"propeller_rps"`` [1/s].
    values : float or array_like
        One for every selected run, or (selected runs,), in the parameter's unit; finite and
        within the parameter's range.
    runs : int or sequence of int, optional
        The runs (default every run).

    Raises
    ------
    ParameterError
        Naming ``name`` for a parameter the controller does not have (or a vector one),
        else ``values`` on a wrong shape, a value not finite or outside the parameter's
        range, or one its parameter class refuses otherwise (its ``validate``: a zig-zag's
        ``first_side`` of 0.5); nothing is written then.
    """
    controller = sim.problem.controller
    params_type = getattr(controller, "params_type", None)
    checks = {c[1]: c for c in params_type._field_checks()} if params_type is not None else {}
    if name not in checks or checks[name][2]:
        have = ", ".join(c for c, v in checks.items() if not v[2]) or "none"
        raise ParameterError(f": the controller '{getattr(controller, 'name', controller)}' has "
                             f"no parameter {name!r} (a number); its parameters: {have}",
                             field="name", value=name)
    _, _, _, low, high, low_inclusive = checks[name]
    unit = params_type._fields_by_name()[name].metadata.get("unit", "")
    sel = run_indices(runs, sim.n_runs)
    try:
        v = np.asarray(values, dtype=float)
    except (TypeError, ValueError):  # (text, a ragged list: numpy's words, not the field's)
        raise ParameterError(f"must be a number or numbers (one per run) [{unit}], got "
                             f"{values!r}", field="values", unit=unit, value=values) from None
    if v.ndim > 1 or (v.ndim == 1 and v.shape[0] != sel.size):
        raise ParameterError(f"must be a number or have shape ({sel.size},) (one per run), got "
                             f"{v.shape}", field="values", unit=unit, value=v.shape)
    v = np.broadcast_to(v, sel.shape)
    bad = ~np.isfinite(v) | (v < low) | (v > high) | ((v == low) & (not low_inclusive))
    if bad.any():
        r = int(np.argmax(bad))
        side = "[" if low_inclusive else "("
        raise ParameterError(f": {name} = {float(v[r])!r} [{unit}] of run {int(sel[r])} is not "
                             f"finite or outside {side}{low:g}, {high:g}]", field="values",
                             unit=unit, value=float(v[r]), run=int(sel[r]))
    cp = sim._batch.slices.arrays.get("params", "controller")
    if cp.shape[0] != sim.n_runs:  # (one record for every run: not writable per run)
        raise ParameterError(f": the controller's parameters have {cp.shape[0]} rows for "
                             f"{sim.n_runs} runs", field="controller_params", value=cp.shape)
    _check_whole_sets(sim._batch.info["c_cls"], cp, name, sel, v, unit)
    cp[name][sel] = v


def _check_whole_sets(cls: type[Params], cp: np.ndarray, name: str, sel: np.ndarray,
                      v: np.ndarray, unit: str) -> None:
    """The parameter sets of the runs ``sel`` with ``name`` = ``v`` made as ``cls``, for a
    class whose construction checks more than each field's range (``validate``'s cross-field
    rules: a zig-zag's side is +1 or -1, a route's waypoint count a whole number): what
    :class:`~seahelm.parameters.Params` refuses is refused here too, naming ``values``."""
    if cls.validate is Params.validate and cls.__post_init__ is Params.__post_init__:
        return  # (the field's range, checked by the caller, is all a construction checks)
    rows = cp.view(np.float64).reshape(cp.shape[0], -1)
    j = cls.value_names().index(name)
    for r, value in zip(sel.tolist(), v.tolist()):
        row = rows[r].copy()
        row[j] = value
        try:
            cls.from_array(row)
        except ValueError as exc:  # (ParameterError included)
            raise ParameterError(f": {name} = {value!r} [{unit}] of run {r} makes no "
                                 f"parameter set of {cls.__name__}: {exc}", field="values",
                                 unit=unit, value=value, run=r) from None


def held_commands(sim: "Simulator") -> np.ndarray:
    """The commands every run holds now (runs, commands) by ``sim.command_labels`` [SI]: the
    last ones given to ``step``, or those its controller computed at its last sample.

    Parameters
    ----------
    sim : Simulator
        A reset simulator.

    Returns
    -------
    ndarray (runs, commands)
        A copy.
    """
    sim._require_reset()
    return sim._cmd[:, :len(sim.command_labels)].copy()


def restart_clock(sim: "Simulator", runs: Any = None) -> None:
    """Set every run's time back to t = 0, keeping its state, commands, controller state and
    status -- except ``runs``, started again from the problem's initial state: the runs are at
    the same step again, so the next :meth:`~seahelm.simulation.stepping.Simulator.step` is
    one call of the loop for the whole batch (runs at different steps, as after
    ``Simulator.reset(runs=...)``, are stepped group by group and observed run by run).

    For a time-invariant problem -- no time series among the references and disturbances, a
    model and loads that do not read the time -- the runs kept go on exactly as they would
    have; their recordings are written again from t = 0 on (what
    :meth:`~seahelm.simulation.stepping.Simulator.result` holds later is not one run's past).

    Parameters
    ----------
    sim : Simulator
        A reset simulator.
    runs : int or sequence of int, optional
        The runs to start again (as ``Simulator.reset(runs=...)``; default none).

    Raises
    ------
    ParameterError
        Naming ``reference``/``disturbance`` for a problem whose references or disturbances
        vary in time (their values are read at the run's time), ``first_order`` for
        first-order wave motions in the loop (a function of the time), ``sensors`` for
        position sensors with noise (a function of the step), or ``runs`` out of range.
    """
    _check_time_invariant(sim)
    sel = None if runs is None else run_indices(runs, sim.n_runs)
    # every clock at step 0 (the states, commands, controller states and statuses kept: the
    # loop reads nothing else of a run's past), then the runs to start again reset -- all at
    # one step, so that reset observes them in one call of the loop
    sim._k[:] = 0
    sim._k0 = 0
    sim._aligned = True
    if sel is not None and sel.size:
        sim.reset(runs=sel)


def restart_runs(sim: "Simulator", runs: Any, states: Mapping[str, Any] | None = None, *,
                 observe: bool = True, clock: bool = True) -> Observation | None:
    """:func:`restart_clock` of ``runs`` then :func:`set_states` of them, observing only them:
    the restart of a few sub-environments between two steps of a batch.

    The runs named start again from the problem's initial state (the controller's init at
    t = 0 on it, as :meth:`Simulator.reset <seahelm.simulation.stepping.Simulator.reset>`),
    then get ``states``; every run's clock is set back to t = 0. The observation returned has
    the restarted runs' outputs at their new state and the other runs' outputs as the last
    step left them (the same numbers an observation of every run gives for a time-invariant
    problem, which :func:`restart_clock` requires) -- without the two whole-batch
    observations of ``restart_clock`` + ``set_states`` + ``observe``.

    Parameters
    ----------
    sim : Simulator
        A reset simulator whose outputs now are the other runs' (its last call a ``step``
        of every run, a ``reset`` or a ``restart_runs``: not a ``set_state``).
    runs : int or sequence of int
        The runs to start again.
    states : mapping, optional
        State label -> value or values (one per run) [SI], as :func:`set_states`.
    observe : bool
        Observe the restarted runs and return the observation (default); False: observe
        nothing, return None (a caller that reads the states, :func:`advance_unobserved`).
    clock : bool
        Set every run's clock back to t = 0 (default). False, with every run at one step:
        keep the clocks, the restarted runs start at the batch's time (the same numbers, the
        problem being time-invariant; the next step does not begin on the recording grid's
        t = 0, whose record costs a model evaluation per run).

    Returns
    -------
    Observation or None
        Every run's outputs, all at t = 0 (at the batch's time with ``clock=False``; None
        unless ``observe``).

    Raises
    ------
    ParameterError
        As :func:`restart_clock` and :func:`set_states` (nothing is changed then).
    """
    _check_time_invariant(sim)
    sel = run_indices(runs, sim.n_runs)
    z = _checked_states(sim, sel, states or {}, start=True)
    b = sim._batch
    a = b.slices.arrays
    if clock or not sim._aligned:
        sim._k[:] = 0
        sim._k0 = 0
        sim._aligned = True
    if sel.size:
        restore_rows(sel, a.state, a.outcome, a.record, *sim._fresh_groups)
        spans = _spans(sel)
        with quiet(b.jit):
            _init_runs(sim, sel, spans)  # (the controller's init on the initial state)
            sim._z[sel] = z
            if not observe:
                return None
            if sel.size > _SPANS_SHARE * sim.n_runs:
                sim._observe_into()
            else:
                b.slices.observe_spans(spans, sim._k0, b.n_steps, b.dt, b.ctrl_every,
                                       b.record_every, sim._out)
    return sim._observation() if observe else None


def advance_unobserved(sim: "Simulator", commands: np.ndarray | None, n: int = 1) -> bool:
    """:meth:`Simulator.step <seahelm.simulation.stepping.Simulator.step>` of every run by
    ``n`` controller intervals without the observation: the loop does not compute the outputs
    at the interval's end (one evaluation of the model's outputs per run and step: some 13 %
    of an Euler MMG interval of ten steps); the caller reads the states (``sim._z``, which
    this leaves exactly as ``step`` does) and the statuses (``sim._status``).

    Parameters
    ----------
    sim : Simulator
        A reset simulator; its runs at the same step, without a coupling hook or ``throw``
        (else nothing is done and False returned: the caller steps with ``step``).
    commands : ndarray (runs, commands) or None
        float64, by ``sim.command_labels`` [SI], checked as ``step`` checks them; None: the
        problem's controller.
    n : int
        Controller intervals (>= 1; the horizon's end stops them, as ``step``).

    Returns
    -------
    bool
        Whether the runs were advanced here.
    """
    if sim._k is None or not sim._aligned or sim.coupling is not None or sim.throw \
            or not 1 <= n <= sim.n_intervals:
        return False
    b = sim._batch
    k0 = sim._k0
    if k0 >= b.n_steps:
        return True
    external = 0
    if commands is not None:
        sim._cmd[:, :sim._nc] = sim._commands(commands, None)
        external = 1
    k1 = min(k0 + n * b.ctrl_every, b.n_steps)
    if n == 1 or sim.n_runs * (k1 - k0) < 100_000:  # (a short step: one call, as step)
        with quiet(b.jit):
            b.slices.run(k0, k1, b.n_steps, b.dt, b.ctrl_every, b.record_every, external)
    else:
        drive(b.slices, b.n_steps, b.dt, b.ctrl_every, b.record_every, jit=b.jit,
              k_start=k0, k_stop=k1, external=external)
    sim._k0 = k1
    sim._k.fill(k1)
    return True


#: A call of the kernel's ``init_runs`` costs about this many runs' init (some 1.7 µs against
#: 55-85 ns a run: KVLCC2 MMG, open loop or PID; measured 2026-12-02).
_INIT_CALL_RUNS = 20


def _init_runs(sim: "Simulator", sel: np.ndarray, spans: list[tuple[int, int]]) -> None:
    """The controller's init at t = 0 of the runs ``sel`` (contiguous ``spans``), as
    :meth:`Simulator.reset <seahelm.simulation.stepping.Simulator.reset>`: a call a span, or
    -- many short spans, and no stages (whose outputs the init computes and that might keep a
    run's state) -- one call over the range they cover, the controller states of the other
    runs in it put back (the init writes nothing else of a run: the same numbers)."""
    b = sim._batch
    lo, hi = spans[0][0], spans[-1][1]
    if len(spans) > 2 and not b.slices.arrays.stages and len(spans) * _INIT_CALL_RUNS > hi - lo:
        others = np.ones(hi - lo, dtype=bool)
        others[sel - lo] = False
        cs = sim._cs[lo:hi]
        kept = cs[others]
        b.slices.init_runs([(lo, hi)])
        cs[others] = kept
        return
    b.slices.init_runs(spans)


def _check_time_invariant(sim: "Simulator") -> None:
    """Refuse to set the clock back of a problem that reads the time (see restart_clock)."""
    sim._require_reset()
    a = sim._batch.slices.arrays
    for name, arr in (("disturbance", a.signals[0]), ("reference", a.signals[1])):
        if arr.shape[1] > 1:
            raise ParameterError(f": the {name} is a time series (shape {arr.shape}); the "
                                 "clock of its runs cannot be set back", field=name,
                                 value=arr.shape)
    problem = sim.problem
    if getattr(problem, "first_order", None) is not None:
        raise ParameterError(": the first-order wave motions in the loop are a function of the "
                             "time (their sea would start again from t = 0 for the runs kept); "
                             "the clock of its runs cannot be set back", field="first_order")
    sensors = getattr(problem, "sensors", None)
    if sensors is not None and any(s > 0.0 for s in sensors.noise):
        raise ParameterError(": the position sensors' noise is a function of the step (the runs "
                             "kept would measure their noise from step 0 again); the clock of "
                             "its runs cannot be set back", field="sensors")


def set_states(sim: "Simulator", runs: Any, values: Mapping[str, Any]) -> None:
    """Set some states of some runs at once (:meth:`Simulator.set_state
    <seahelm.simulation.stepping.Simulator.set_state>` for many runs; the controller's state
    is kept).

    Parameters
    ----------
    sim : Simulator
        A reset simulator.
    runs : int or sequence of int
        The runs.
    values : mapping
        State label -> value or values (one per run) [SI]; the states not named keep theirs.
        Finite and within the state's bounds.

    Raises
    ------
    ParameterError
        Naming ``values`` on an unknown label, a wrong shape, a value not finite or outside
        its bounds (nothing is written then).
    """
    sim._require_reset()
    sel = run_indices(runs, sim.n_runs)
    sim._z[sel] = _checked_states(sim, sel, values, start=False)


def _checked_states(sim: "Simulator", sel: np.ndarray, values: Mapping[str, Any], *,
                    start: bool) -> np.ndarray:
    """The states (len(sel), states) of the runs ``sel`` with ``values`` written in, checked:
    from their state now, or (``start``) from the problem's initial state."""
    z = (sim._fresh[0] if start else sim._z)[sel]  # (fancy indexing: a copy)
    labels = sim.state_labels
    for name, v in values.items():
        if name not in labels:
            raise ParameterError(f": unknown state {name!r}; states: {', '.join(labels)}",
                                 field="values", value=name)
        col = np.asarray(v, dtype=float)
        if col.ndim > 1 or (col.ndim == 1 and col.shape[0] != sel.size):
            raise ParameterError(f"[{name!r}] must be a number or have shape ({sel.size},) "
                                 f"(one per run), got {col.shape}", field="values",
                                 value=col.shape)
        z[:, labels.index(name)] = col
    lower, upper = (sim._batch.slices.arrays.get("params", n) for n in ("lower", "upper"))
    first = _first_outside(z, lower, upper)
    if first >= 0:
        r, j = divmod(first, z.shape[1])
        raise ParameterError(f": state {labels[j]!r} = {float(z[r, j])!r} of run {int(sel[r])} is not "
                             f"finite or outside its bounds [{lower[j]:g}, {upper[j]:g}]",
                             field="values", value=float(z[r, j]), run=int(sel[r]))
    return z


@njit(cache=True)
def _first_outside(z, lower, upper):  # pragma: no cover - compiled
    """The flat index (row-major) of the first element of ``z`` (rows, states) that is not
    finite or outside [lower[j], upper[j]] of its column, or -1: ``np.argwhere(~np.isfinite(z)
    | (z < lower) | (z > upper))[0]`` in one compiled pass (the six array calls cost some
    6 µs a restart)."""
    for r in range(z.shape[0]):
        for j in range(z.shape[1]):
            x = z[r, j]
            if not np.isfinite(x) or x < lower[j] or x > upper[j]:
                return r * z.shape[1] + j
    return -1
