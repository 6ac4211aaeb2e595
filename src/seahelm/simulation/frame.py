"""What the engine takes from a combination of components and stages alone.

:func:`~seahelm.simulation.engine.prepare` needs, besides the problem's arrays, the loop's state
labels, the disturbance and output channels (the model's, then each stage's), the state bounds
and a few sizes. They depend on the wiring (model, actuator, controller) and the stages only,
all frozen, so :func:`_frame` makes them once per combination (issue 46: a circle's batch of one
run spent a fifth of ``prepare`` rebuilding them at every call).
"""

from __future__ import annotations

import dataclasses
import functools
from typing import Any

import numpy as np

from .._validate import as_float_array
from ..errors import ParameterError
from ..parameters import as_records
from ..resources import check_work
from .inputs import _check_angles, _param_rows, _runs, _signal, _TimeGrid
from .memory import check_record_memory

__all__: list[str] = []


@dataclasses.dataclass(frozen=True)
class _Frame:
    """What :func:`prepare` takes from a combination of components and stages alone (their
    labels, units, bounds and sizes): :func:`_frame`."""

    labels: tuple[str, ...]
    dist_labels: tuple[str, ...]
    dist_units: tuple[str, ...]
    out_labels: tuple[str, ...]
    out_units: tuple[str, ...]
    stage_names: tuple[str, ...]
    n_states: int
    n_actuator_states: int
    n_commands: int
    controller_width: int
    actuator_command_width: int
    channels: int
    lower: np.ndarray
    upper: np.ndarray


@functools.lru_cache(maxsize=256)
def _frame(wiring: Any, stages: tuple[Any, ...]) -> _Frame:
    """The :class:`_Frame` of a wiring (:class:`~seahelm.simulation.composition.Composition`,
    frozen: its model, actuator and controller) and the loop's stages (frozen dataclasses),
    made once per combination: a batch of one run spent a fifth of :func:`prepare` on them.
    Its ``lower``/``upper`` are read-only (:func:`prepare` copies them)."""
    model, actuator, controller = wiring.model, wiring.actuator, wiring.controller
    dist_labels, dist_units = model.disturbance_labels, model.disturbance_units
    out_labels, out_units = model.output_labels, model.output_units
    for stage in stages:
        (sig, sig_units), (outs, outs_units) = stage.signals(), stage.outputs(model)
        dist_labels, dist_units = dist_labels + sig, dist_units + sig_units
        out_labels, out_units = out_labels + outs, out_units + outs_units
    n_act = actuator.n_states
    lower = np.array(list(model.state_lower) + [-np.inf] * n_act, dtype=float)
    upper = np.array(list(model.state_upper) + [np.inf] * n_act, dtype=float)
    lower.flags.writeable = upper.flags.writeable = False
    n_commands = len(wiring.commands) + len(controller.output_labels)
    return _Frame(
        labels=model.state_labels + actuator.state_labels, dist_labels=dist_labels,
        dist_units=dist_units, out_labels=out_labels, out_units=out_units,
        stage_names=tuple(stage.name for stage in stages), n_states=model.n_states,
        n_actuator_states=n_act, n_commands=n_commands,
        controller_width=max(controller.n_states, 1),
        actuator_command_width=max(len(wiring.actuator_commands), 1),
        channels=(model.n_states + n_act + len(out_labels) + n_commands
                  + len(wiring.references) + len(dist_labels)),
        lower=lower, upper=upper)


#: A problem whose inputs :func:`keep_inputs` did not ask to keep.
_NOT_KEPT = object()


def keep_inputs(problem: Any) -> Any:
    """Let :func:`~seahelm.simulation.engine.prepare` keep ``problem``'s checked inputs on it
    (:class:`_Inputs`, copied into every batch), so that preparing it again skips their
    conversion and checks: for a problem whose arrays no one changes after it was made (a
    manoeuvre's prepared request, :mod:`seahelm.analysis.maneuvers.prepared`, which holds it
    privately). A problem of the caller's is prepared afresh each time (its arrays may have
    been changed in place since). Returns ``problem``."""
    if "_kept_inputs" not in problem.__dict__:
        object.__setattr__(problem, "_kept_inputs", None)
    return problem


@dataclasses.dataclass(frozen=True)
class _Inputs:
    """A problem's inputs as the kernel takes them, checked against each other
    (:func:`problem_inputs`): parameter rows and their classes, the initial state (vessel and
    actuator), its bounds, the signals, the batch size and the recorded samples."""

    mp: np.ndarray
    ap: np.ndarray
    cp: np.ndarray
    m_cls: type
    a_cls: type
    c_cls: type
    z: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    dist: np.ndarray
    ref: np.ndarray
    n_runs: int
    n_runs_early: int
    n_rec: int
    frame: _Frame
    #: the record dtypes of the parameter rows (:func:`~seahelm.parameters.as_records`), kept
    #: with the inputs (None: rows without a field, whose records are made the general way)
    records: tuple[np.dtype | None, ...] = (None, None, None)

    def own(self) -> "_Inputs":
        """The same with a read-only copy of every array (what is kept on the problem; each
        batch prepared from it copies them again, writable, its own)."""
        out = dataclasses.replace(self, records=tuple(
            cls._record_view_dtype() if rows.shape[1] else None
            for rows, cls in ((self.mp, self.m_cls), (self.ap, self.a_cls),
                              (self.cp, self.c_cls))), **{name: getattr(self, name).copy()
                                                          for name in _ARRAYS})
        for name in _ARRAYS:
            getattr(out, name).flags.writeable = False
        return out

    def as_records(self, rows: np.ndarray, which: int, cls: type) -> np.ndarray:
        """``as_records(rows, cls)`` of a batch's copy ``rows`` of this problem's parameter rows
        ``which`` (0 vessel, 1 actuator, 2 controller): the records on its buffer, as
        :func:`~seahelm.parameters.as_records` makes them of such rows (C-contiguous, writable,
        float64, of the class's width), without its checks."""
        dtype = self.records[which]
        if dtype is None:
            return as_records(rows, cls)
        return np.ndarray(shape=(rows.shape[0],), dtype=dtype, buffer=rows)


_ARRAYS = ("mp", "ap", "cp", "z", "lower", "upper", "dist", "ref")


def problem_inputs(problem: Any, frame: _Frame, stages: tuple[Any, ...],
                   stage_inputs: list[Any], stage_runs: list[tuple[str, int]]
                   ) -> tuple[_Inputs, tuple[Any, ...]]:
    """The problem's inputs converted and checked (:class:`_Inputs`) and the stages' arrays,
    in the order :func:`~seahelm.simulation.engine.prepare` has always checked them (the
    recordings' memory and the work before a signal of the run's length is built).

    Raises
    ------
    ParameterError
        On shapes that do not broadcast, an initial state outside the bounds, recordings that
        would not fit in memory, too much work.
    """
    model, actuator, controller = problem.model, problem.actuator, problem.controller
    params, x0, actuator_x0 = problem.params, problem.x0, problem.actuator_x0
    actuator_params, controller_params = problem.actuator_params, problem.controller_params
    reference, disturbance, bounds = problem.reference, problem.disturbance, problem.bounds
    n_steps, record_every, dt = problem.n_steps, problem.record_every, problem.dt
    wiring, dist_labels = problem.wiring, frame.dist_labels
    mp, m_cls = _param_rows("params", params, model.params_type)
    ap, a_cls = _param_rows("actuator_params", actuator_params, actuator.params_type)
    cp, c_cls = _param_rows("controller_params", controller_params, controller.params_type)
    x0 = _rows_2d(as_float_array("x0", x0))
    if x0.shape[-1] != frame.n_states or x0.ndim != 2:
        raise ParameterError(
            f"must have {model.n_states} states ({', '.join(model.state_labels)}), "
            f"got shape {x0.shape}", field="x0")
    xa0 = np.zeros((1, frame.n_actuator_states)) if actuator_x0 is None else _rows_2d(
        as_float_array("actuator_x0", actuator_x0)
    )
    if xa0.shape[-1] != frame.n_actuator_states:
        raise ParameterError(
            f"must have {frame.n_actuator_states} states, got shape {xa0.shape}",
            field="actuator_x0")
    # the recordings must fit before anything of the batch's size is built (the time grid too:
    # a long run with a coarse record needs no array of all its steps)
    n_rec_early = n_steps // record_every + 1 + (n_steps % record_every != 0)
    n_runs_early = max(mp.shape[0], ap.shape[0], cp.shape[0], x0.shape[0],
                       *(n for _, n in stage_runs))
    channels_early = frame.channels
    # the work too, before a reference or disturbance of the run's length is built
    check_record_memory(n_runs_early, n_rec_early, channels_early)
    check_work(n_runs_early, n_steps,
               record_bytes=8.0 * n_runs_early * n_rec_early * channels_early)
    t_grid = _TimeGrid(n_steps, float(dt))
    ref = _signal("reference", reference, len(wiring.references), t_grid, "",
                  wiring.references)
    _check_angles("reference", ref, wiring.references, wiring.reference_units)
    dist = _signal("disturbance", disturbance, len(dist_labels), t_grid, "", dist_labels)
    n_runs = _runs(
        ("params", mp.shape[0]), ("actuator_params", ap.shape[0]),
        ("controller_params", cp.shape[0]), ("x0", x0.shape[0]),
        ("actuator_x0", xa0.shape[0]), ("reference", ref.shape[0]),
        ("disturbance", dist.shape[0]), *stage_runs,
    )
    stage_arrays = tuple(stage.arrays(inp, n_runs) for stage, inp in zip(stages, stage_inputs))

    def rows(a: np.ndarray) -> np.ndarray:
        if a.shape[0] == n_runs and a.dtype == np.float64 and a.flags.c_contiguous:
            return a  # (as it is: a broadcast and a copy cost µs, a tenth of a short run)
        return np.ascontiguousarray(np.broadcast_to(a, (n_runs,) + a.shape[1:]), dtype=float)

    mp, ap, cp = rows(mp), rows(ap), rows(cp)
    z = np.concatenate([rows(x0), rows(xa0)], axis=1)
    labels = frame.labels
    lower, upper = frame.lower.copy(), frame.upper.copy()  # (the kernel's own, as before)
    for label, (lo, hi) in (bounds or {}).items():  # (labels checked by the Problem)
        j = labels.index(label)
        lower[j], upper[j] = max(lower[j], float(lo)), min(upper[j], float(hi))
    within = np.isfinite(z)  # (in place, one reduction: some µs of a short run)
    within &= z >= lower
    within &= z <= upper
    if not within.all():
        i = int(np.argmax(~within.all(axis=1)))
        raise ParameterError(f": the initial state of run {i} is not finite or outside the "
                             f"bounds: {z[i]}", field="x0", run=i)

    n_rec = n_rec_early  # (the channels are the early check's: only more runs need a look)
    if n_runs != n_runs_early:
        check_record_memory(n_runs, n_rec, channels_early)
    return _Inputs(mp=mp, ap=ap, cp=cp, m_cls=m_cls, a_cls=a_cls, c_cls=c_cls, z=z,
                   lower=lower, upper=upper, dist=dist, ref=ref, n_runs=n_runs,
                   n_runs_early=n_runs_early, n_rec=n_rec, frame=frame), stage_arrays


def _rows_2d(a: np.ndarray) -> np.ndarray:
    """``np.atleast_2d(a)``: a 2-D array as it is, a 1-D one as its view ``a[None, :]`` (what
    numpy's function returns, without its µs a call)."""
    if a.ndim == 2:
        return a
    return a[None, :] if a.ndim == 1 else np.atleast_2d(a)
