"""The closed-loop simulation engine: vessel + actuator + controller + disturbances, batched.

:func:`simulate` integrates a batch of runs with a fixed-step method. For every combination of
(vessel model, actuator, controller, integrator) :func:`compile_closed_loop` generates a small
module from :mod:`seahelm.simulation.kernel_template` with the components' numba functions
bound in, the routing of signals by name from :func:`~seahelm.simulation.composition.compose`
and the integrator's step from its Butcher tableau (stages written out,
:func:`~seahelm.simulation.compiled_step.compiled_advance_source`, or looped over for a heavy
model, :data:`STAGE_LOOP_ABOVE`), and numba compiles it once
per machine (``cache=True``; the module's name hashes its text, with the generated step, and
the in-memory bytecode of the components and of every numba function they call, so editing
any of them or changing the tableau recompiles it). The compiled loop releases the GIL and
runs slices of the batch on a pool of threads, one per core (``numba.set_num_threads`` sets
how many); nothing in it is Python per step or per run.

Timing: the state is integrated on the grid t_k = k·dt; the controller is stepped every
``controller_dt`` (an integer multiple of dt) and its command held in between (zero-order hold);
disturbances are given on the grid and interpolated linearly inside a step: a stage at
t_k + c_i dt sees d_k + c_i (d_{k+1} − d_k) (for RK4's mid-step stages, the mean of the two).
An actuator with a closed-form step (the rudder servos: a ramp at the rate limit, then an
exponential lag) is not integrated: each stage takes its state at t_k + c_i dt from that
solution under the held command, so a 0.1 s steering-gear lag does not bound the step.

A run whose state turns NaN/inf or leaves its declared bounds stops and is recorded with its
status, time and state; the other runs go on (``throw=True`` raises
:class:`~seahelm.errors.SimulationDiverged` instead).

For debugging, ``simulate(..., jit=False)`` (or ``SEAHELM_DISABLE_JIT=1``, or numba's own
``NUMBA_DISABLE_JIT=1``) runs the same generated module as plain Python, in memory, with the
components' Python functions bound in (:data:`PYTHON_HEADER`): a breakpoint in a model's
``rhs`` is hit, and nothing is compiled or cached.
"""

from __future__ import annotations

import dataclasses
import enum
import functools
import itertools
import operator
import time as _time
from collections.abc import Callable, Mapping, Sequence
from types import ModuleType
from typing import Any

import numpy as np

from ..actuators.base import Actuator
from ..control.base import Controller
from ..errors import ParameterError, SimulationDiverged
from ..parameters import Params, as_records
from ..resources import check_work
from ..results import SimResult
from ..vessels.base import VesselModel
from .closed_loop import (  # noqa: F401 (the engine's names, as before the split)
    PYTHON_HEADER,
    STAGE_LOOP_ABOVE,
    _stage_code_size,
    compile_closed_loop,
)
from .generated import code_fingerprint, import_generated, kernel_cache_dir
from .inputs import (  # noqa: F401
    MAX_ANGLE,
    _check_angles,
    _param_rows,
    _runs,
    _signal,
    _TimeGrid,
)
from .integrators import ButcherTableau
from .kernel_args import KernelArrays
from .memory import (  # noqa: F401
    ASK_ABOVE,
    RECORD_MEMORY_SHARE,
    RECORD_PEAK_FACTOR,
    RecordingTooLarge,
    check_record_memory,
    physical_memory,
)
from .frame import _NOT_KEPT, _frame, _Inputs, _rows_2d, problem_inputs  # noqa: F401
from .problem import Problem, jit_enabled
from .stages import stages_of
from .slicing import FIRST_SLICE, FIRST_SLICE_PYTHON, SLICE_SECONDS, _Slices, drive, quiet  # noqa: F401

__all__ = ["RunStatus", "simulate", "compile_closed_loop", "STAGE_LOOP_ABOVE", "kernel_cache_dir",
           "jit_enabled",
           "import_generated", "code_fingerprint",
           "check_record_memory", "physical_memory", "RecordingTooLarge"]


class RunStatus(enum.IntEnum):
    """Outcome of one run of a batch."""

    OK = 0
    NONFINITE = 1
    OUT_OF_BOUNDS = 2
    NOT_RUN = 3
    """Left out of the batch: its initial state could not be found (a manoeuvre whose steady
    approach failed; the engine itself never sets it)."""


# ------------------------------------------------------------------------------------------
# the public entry point
# ------------------------------------------------------------------------------------------
def simulate(
    model: "VesselModel | Problem | None" = None,
    params: Params | Sequence[Params] | np.ndarray | None = None,
    x0: Any = None,
    *,
    t_final: float | None = None,
    dt: float | None = None,
    ship: Any = None,
    controller: Controller | None = None,
    controller_params: Params | Sequence[Params] | np.ndarray | None = None,
    actuator: Actuator | None = None,
    actuator_params: Params | Sequence[Params] | np.ndarray | None = None,
    actuator_x0: Any = None,
    reference: Any = None,
    disturbance: Any = None,
    controller_dt: float | None = None,
    integrator: str | ButcherTableau | None = None,
    record_every: int | None = None,
    bounds: Mapping[str, tuple[float, float]] | None = None,
    throw: bool = False,
    progress: Callable[[int, int], None] | None = None,
    seed: int | None = None,
    metadata: Mapping[str, Any] | None = None,
    environment: Any = None,
    environment_params: Params | Sequence[Params] | np.ndarray | None = None,
    exact_actuator: bool | None = None,
    jit: bool | None = None,
    first_order: Any = None,
    post_pass: Any = None,
    sensors: Any = None,
) -> "SimResult":
    """Simulate a batch of closed-loop runs: a :class:`~seahelm.simulation.problem.Problem`.

    ``simulate(problem)`` runs a problem (with ``throw`` and ``progress``, nothing else);
    the keyword form ``simulate(model, params, x0, t_final=..., dt=..., ...)`` is a
    convenience that builds the :class:`~seahelm.simulation.problem.Problem` of its arguments
    (the one validation of them) and runs it.

    Parameters
    ----------
    model : VesselModel or Problem
        The vessel model (e.g. :data:`seahelm.vessels.nomoto.NOMOTO2`), or a whole problem.
    ship : Ship, str or path-like, optional
        A ship (catalog name or ship file) instead of ``model`` and ``params``: its steering
        gear is the default actuator.
    params : Params, sequence of Params, or array (runs, n_params)
        Vessel parameters; one set for all runs or one per run.
    x0 : array_like, shape (n_states,) or (runs, n_states)
        Initial vessel state (SI units, radians).
    t_final, dt : float
        Duration [s] and integration step [s]; ``t_final`` must be a multiple of ``dt``.
    controller, controller_params : Controller, Params or array, optional
        Controller (default: open loop, reference = command) and its parameters.
    actuator, actuator_params, actuator_x0 : Actuator, Params or array, array_like, optional
        Actuator (default: rudder servo), its parameters and initial state (default zeros).
    reference : None, scalar, array, callable or mapping
        Controller reference. A 1-D array is a constant vector; a 2-D array
        ``(steps+1, channels)`` a time series on the grid t_k = k dt; a 3-D array
        ``(runs|1, steps+1|1, channels)`` per run; a callable ``f(t_grid)`` returns one of these;
        a mapping gives channels by name (``{"heading": 0.3}``; missing channels are zero).
    disturbance : None, scalar, array, callable or mapping
        External disturbance inputs of the model (same forms as ``reference``; by name, e.g.
        ``{"force_y": ..., "moment_z": ...}``), then the environment's signals
        (``wind_gust``, ``wave_load_fluctuation``) when there is an environment.
    controller_dt : float, optional
        Controller sample period [s], a multiple of ``dt`` (default: the controller's
        ``sample_period`` where it has one, else ``dt``).
    integrator : str or ButcherTableau
        Fixed-step method: a name in :data:`~seahelm.simulation.integrators.INTEGRATORS`
        (default "rk4") or an explicit :class:`~seahelm.simulation.integrators.ButcherTableau`.
    record_every : int
        Record every n-th step, and the final state (``t_final/dt`` need not be a multiple:
        the last recorded interval is then shorter).
    bounds : mapping label -> (low, high), optional
        Admissible state bounds beyond the model's declared ones; leaving them marks a run
        diverged.
    throw : bool
        Raise :class:`SimulationDiverged` (first failed run: time and state) instead of
        recording the failure.
    progress : callable(done_steps, total_steps), optional
        Called between chunks of the loop.
    seed : int, optional
        Stored with the results (for runs whose inputs were drawn at random).
    metadata : mapping, optional
        Extra attributes stored with the results (e.g. the scenario text).
    environment : Environment, optional
        Wind and/or wave loads (:func:`seahelm.environment.loads.environment`), computed at
        every stage from each run's live heading and velocity and added to the model's
        ``force_x``, ``force_y``, ``moment_z`` channels; its outputs (apparent wind, loads) are
        recorded after the model's.
    environment_params : Params, sequence of Params or array, optional
        The environment's parameters (wind speed and direction, wave height, ship data), one
        set or one per run.
    exact_actuator : bool, optional
        Take the actuator's states from its closed-form step (default: when it has one, as the
        rudder servos do) or integrate its rhs with the step (``False``: the behaviour before
        the closed form, to reproduce older results); see :func:`compile_closed_loop`. The
        result's ``metadata["actuator_step"]`` says which (``"closed-form"`` or
        ``"integrated"``).
    jit : bool, optional
        Run the compiled loop (``True``) or the same loop as plain Python (``False``), for
        debugging: the components run as their Python functions, so a breakpoint in a model's
        ``rhs`` (``breakpoint()``, or ``b seahelm/vessels/mmg.py:LINE`` in pdb) stops there,
        an index out of range raises instead of reading memory, and nothing is compiled or
        written to the kernel cache. It runs in the calling thread at some 10³-10⁴ steps/s
        (KVLCC2 MMG 1.1e3, Nomoto-2 + PID 7.6e3): meant for a few runs of some hundred steps.
        The results agree with the compiled loop's to rounding (the compiled loop may fuse
        and reorder floating-point operations; 1e-12 on short runs of every model, tested).
        Default: compiled, unless the environment variable ``SEAHELM_DISABLE_JIT`` is set
        (to anything but empty, ``0``, ``false``, ``no`` or ``off``) or numba's JIT is
        disabled (``NUMBA_DISABLE_JIT=1``); see :func:`jit_enabled`. The result's
        ``metadata["execution"]`` says which loop ran (``"compiled"`` or ``"python"``).
    first_order : FirstOrderInLoop, optional
        First-order wave motions evaluated in the loop at the live state
        (:func:`seahelm.environment.first_order_in_loop.first_order_in_loop`): recorded as
        outputs (``heave``, ``roll_wave``, ``pitch``, ``yaw_wave``, ``heading_total``, and
        ``roll`` on a model with roll); with ``autopilot_sees_first_order`` the controller's
        ``heading`` is ``heading_total``. ``metadata["controller_heading"]`` says which.
    post_pass : object, optional
        Computed from the recordings after the run, into the result's ``extra`` channels and
        metadata (:attr:`Problem.post_pass <seahelm.simulation.problem.Problem>`).
    sensors : PositionSensors, optional
        What the controller's position and heading sensors see: first-order motion and noise
        (:mod:`seahelm.simulation.sensor_stage`).

    Returns
    -------
    SimResult

    Raises
    ------
    ParameterError
        On invalid parameters, shapes or timing (before anything runs).
    SimulationDiverged
        With ``throw=True``, when a run diverges.
    """
    # the keyword form's arguments are Problem's fields, by name (no copy of the list: a
    # field added to Problem and to this signature is passed on; a test checks the two agree)
    arguments = locals()
    if isinstance(model, Problem) and not any(map(operator.is_not, _keyword_values()(arguments),
                                                  itertools.repeat(None))):
        return _run(model, throw=throw, progress=progress)  # (a problem alone: the usual call)
    given = {name: arguments[name] for name in _keyword_fields()
             if arguments[name] is not None}
    if model is not None and not isinstance(model, (Problem, VesselModel)):
        raise ParameterError(
            f"must be a VesselModel or a Problem, got {type(model).__name__} (a ship is given "
            "as `ship=`)", field="model")
    if model is None and "ship" not in given:
        raise ParameterError("is required: give a Problem, or a `model` (or `ship=`) with "
                             "`t_final` and `dt`", field="model")
    if isinstance(model, Problem):
        if given:
            raise ParameterError(
                f"give a Problem or keyword arguments, not both (got {', '.join(given)})",
                field=next(iter(given)))
        problem = model
    else:
        if model is not None:
            given["model"] = model
        for name in ("t_final", "dt"):
            if name not in given:
                raise ParameterError("is required [s]", field=name, unit="s")
        problem = Problem(**given)
    return _run(problem, throw=throw, progress=progress)


@functools.cache
def _keyword_fields() -> tuple[str, ...]:
    """The fields of :class:`Problem` that :func:`simulate` takes as keywords (all but
    ``model``), in the fields' order."""
    import inspect

    taken = inspect.signature(simulate).parameters
    return tuple(f.name for f in dataclasses.fields(Problem)
                 if f.name in taken and f.name != "model")


@functools.cache
def _keyword_values() -> Callable[[Mapping[str, Any]], tuple[Any, ...]]:
    """The values of :func:`_keyword_fields` from :func:`simulate`'s arguments, as a tuple
    (``operator.itemgetter``: one C call, not a dictionary built a name at a time)."""
    return operator.itemgetter(*_keyword_fields())


def _run(problem: "Problem", *, throw: bool,
         progress: Callable[[int, int], None] | None) -> "SimResult":
    """Run a validated problem (:func:`simulate`)."""
    batch = prepare(problem)
    # compile or load the kernel before the clock starts: a zero-step call does it, so the
    # reported simulation time is the simulation's (first use of a combination compiles)
    c0 = _time.perf_counter()
    batch.start()
    compile_time = _time.perf_counter() - c0
    wall = drive(batch.slices, batch.n_steps, batch.dt, batch.ctrl_every, batch.record_every,
                 jit=batch.jit, progress=progress)
    batch.slices.release()  # (run once: its scratch serves the next batch of this kernel)
    return batch.result(wall=wall, compile_time=compile_time, throw=throw)


@dataclasses.dataclass
class Batch:
    """A problem's batch made ready for the compiled loop (:func:`prepare`): the kernel, its
    arrays in slices of runs, and what the result is made of. :func:`simulate` runs it over
    the whole horizon; :class:`~seahelm.simulation.stepping.Simulator` interval by interval."""

    problem: Problem
    kernel: ModuleType
    slices: _Slices
    n_steps: int
    dt: float
    ctrl_every: int
    record_every: int
    jit: bool
    labels: tuple[str, ...]
    out_labels: tuple[str, ...]
    out_units: tuple[str, ...]
    dist_labels: tuple[str, ...]
    dist_units: tuple[str, ...]
    z0: np.ndarray
    info: dict[str, Any]

    @property
    def n_runs(self) -> int:
        """Runs in the batch."""
        return self.slices.arrays.n_runs

    def start(self) -> None:
        """Compile or load the kernel (a zero-step call), then the controllers' init. A batch
        of kept inputs (:func:`~seahelm.simulation.frame.keep_inputs`) has the types of its
        problem's first batch, whose start compiled or loaded the kernel for them: no call."""
        with quiet(self.jit):
            if not self.info["kept"]:
                self.slices.warm_up(self.n_steps, self.dt, self.ctrl_every, self.record_every)
            self.slices.init_runs()

    def result(self, *, wall: float, compile_time: float, throw: bool,
               metadata: Mapping[str, Any] | None = None) -> "SimResult":
        """The :class:`~seahelm.results.SimResult` of the recordings as they are."""
        return _result(self, wall=wall, compile_time=compile_time, throw=throw,
                       metadata=metadata)


def prepare(problem: Problem, *, keep_pool: bool = False) -> Batch:
    """Check a problem's arrays against each other and build the kernel's (:class:`Batch`).

    Raises
    ------
    ParameterError
        On shapes that do not broadcast, an initial state outside the bounds, parameters a
        model's loads need, recordings that would not fit in memory.
    """
    model, actuator, controller = problem.model, problem.actuator, problem.controller
    exact_actuator, dt = problem.exact_actuator, problem.dt
    use_jit = problem._derived["jit"]  # (resolved when the problem was made)
    n_steps, ctrl_every = problem.n_steps, problem.controller_every
    ctrl_dt, record_every = problem._derived["controller_dt"], problem.record_every
    tableau, wiring = problem.tableau, problem.wiring
    kept = problem.__dict__.get("_kept_inputs", _NOT_KEPT)
    # the loop's stages (seahelm.simulation.stages): their inputs checked, their signals after
    # the model's disturbance channels, their outputs after the model's (the labels, bounds and
    # sizes of the combination: :func:`_frame`, made once per combination); a problem's inputs
    # checked once if it let them be kept (frame.keep_inputs: only for a loop without stages)
    if type(kept) is _Inputs:  # (the guards read the machine at every call: memory, threads)
        stages, stage_inputs, stage_arrays, frame = (), [], (), kept.frame
        check_record_memory(kept.n_runs_early, kept.n_rec, frame.channels)
        check_work(kept.n_runs_early, n_steps,
                   record_bytes=8.0 * kept.n_runs_early * kept.n_rec * frame.channels)
        if kept.n_runs != kept.n_runs_early:
            check_record_memory(kept.n_runs, kept.n_rec, frame.channels)
        inputs = kept  # (its arrays copied below: the batch's own)
        mp, ap, cp, z = kept.mp.copy(), kept.ap.copy(), kept.cp.copy(), kept.z.copy()
        lower, upper = kept.lower.copy(), kept.upper.copy()
        dist, ref = kept.dist.copy(), kept.ref.copy()
    else:
        stages = stages_of(problem)
        frame = _frame(wiring, stages)
        stage_inputs = [stage.inputs(problem, model) for stage in stages] if stages else []
        stage_runs = [c for stage, inp in zip(stages, stage_inputs)
                      for c in stage.run_counts(inp)]
        inputs, stage_arrays = problem_inputs(problem, frame, stages, stage_inputs, stage_runs)
        if kept is None and not stages:
            object.__setattr__(problem, "_kept_inputs", inputs.own())
        mp, ap, cp, z = inputs.mp, inputs.ap, inputs.cp, inputs.z
        lower, upper, dist, ref = inputs.lower, inputs.upper, inputs.dist, inputs.ref
    m_cls, a_cls, c_cls = inputs.m_cls, inputs.a_cls, inputs.c_cls
    n_runs, n_rec, labels, out_labels = inputs.n_runs, inputs.n_rec, frame.labels, frame.out_labels

    if exact_actuator is None:
        exact_actuator = actuator.advance is not None
    kernel = compile_closed_loop(model, actuator, controller, tableau, stages,
                                 exact_actuator=bool(exact_actuator), jit=use_jit)
    if inputs is kept:  # (copies of rows checked before: the records without the checks)
        mr, ar, cr = (kept.as_records(mp, 0, m_cls), kept.as_records(ap, 1, a_cls),
                      kept.as_records(cp, 2, c_cls))
    else:
        mr, ar, cr = as_records(mp, m_cls), as_records(ap, a_cls), as_records(cp, c_cls)
    nz = z.shape[1]
    ncmd = frame.n_commands  # (the controller's outputs after the commands)
    cs = np.zeros((n_runs, frame.controller_width))
    cmd = np.zeros((n_runs, ncmd))
    ca = np.zeros((n_runs, frame.actuator_command_width))
    status = np.zeros(n_runs, dtype=np.int64)
    # (NaN until written: np.empty and fill, some µs a call below np.full's)
    t_fail, z_fail = np.empty(n_runs), np.empty((n_runs, nz))
    rec_z, rec_cmd = np.empty((n_runs, n_rec, nz)), np.empty((n_runs, n_rec, ncmd))
    rec_y = np.empty((n_runs, n_rec, len(out_labels)))
    for a in (t_fail, z_fail, rec_z, rec_y, rec_cmd):
        a.fill(np.nan)

    arrays = KernelArrays(
        state=(z, cs, cmd, ca), params=(mr, ar, cr, lower, upper), signals=(dist, ref),
        outcome=(status, t_fail, z_fail), record=(rec_z, rec_y, rec_cmd), stages=stage_arrays,
        stage_names=frame.stage_names)
    n_out = len(out_labels)

    def stage_scratch() -> tuple[tuple[np.ndarray, ...], ...]:
        return tuple(stage.scratch(model, g, n_out) for stage, g in zip(stages, stage_arrays))

    slices = _Slices(kernel, arrays,
                     (ncmd, ca.shape[1], cs.shape[1], dist.shape[2], ref.shape[2]),
                     threads=None if use_jit else 1,
                     stage_scratch=stage_scratch if stages else tuple,
                     keep_pool=keep_pool)
    result_params: dict[str, Any] = {}
    for stage, inp in zip(stages, stage_inputs):
        result_params.update(stage.result_params(inp, n_runs))
    return Batch(problem=problem, kernel=kernel, slices=slices, n_steps=n_steps, dt=float(dt),
                 ctrl_every=ctrl_every, record_every=record_every, jit=use_jit, labels=labels,
                 out_labels=out_labels, out_units=frame.out_units, dist_labels=frame.dist_labels,
                 dist_units=frame.dist_units, z0=slices.arrays.state[0].copy(),
                 info={"mp": mp, "ap": ap, "cp": cp, "m_cls": m_cls, "a_cls": a_cls,
                       "c_cls": c_cls, "n_rec": n_rec, "exact_actuator": exact_actuator,
                       "ctrl_dt": ctrl_dt, "stages": stages, "stage_params": result_params,
                       "kept": inputs is kept})


def _result(batch: Batch, *, wall: float, compile_time: float, throw: bool,
            metadata: Mapping[str, Any] | None = None) -> "SimResult":
    """The result of a batch's recordings (:meth:`Batch.result`)."""
    problem, info = batch.problem, batch.info
    model, actuator, controller = problem.model, problem.actuator, problem.controller
    seed = problem.seed
    tableau, wiring = problem.tableau, problem.wiring
    n_steps, record_every, n_rec = batch.n_steps, batch.record_every, info["n_rec"]
    dt, t_final, ctrl_dt = batch.dt, problem.t_final, info["ctrl_dt"]
    exact_actuator, use_jit = info["exact_actuator"], batch.jit
    (dist, ref), labels = batch.slices.arrays.signals, batch.labels
    m_cls, a_cls, c_cls = info["m_cls"], info["a_cls"], info["c_cls"]
    mp, ap, cp = info["mp"], info["ap"], info["cp"]
    rec_z, rec_y, rec_cmd = batch.slices.arrays.record
    status, t_fail, z_fail = batch.slices.arrays.outcome
    out_labels, out_units = batch.out_labels, batch.out_units
    dist_labels, dist_units = batch.dist_labels, batch.dist_units
    metadata = problem.metadata if metadata is None else metadata
    # the recorded steps: every record_every-th, and the last (np.minimum(k * every, n_steps))
    ref_idx = np.arange(0, n_rec * record_every, record_every)
    ref_idx[-1] = min(int(ref_idx[-1]), n_steps)
    rec_t = ref_idx * float(dt)
    result = SimResult(
        layout=problem.layout,
        time=rec_t,
        state=rec_z,
        state_labels=labels,
        state_units=model.state_units + actuator.state_units,
        output=rec_y,
        output_labels=out_labels,
        output_units=out_units,
        command=rec_cmd,
        command_labels=wiring.commands + controller.output_labels,
        command_units=wiring.command_units + controller.output_units,
        reference=ref[:, ref_idx] if ref.shape[1] > 1 else ref.repeat(n_rec, axis=1),
        reference_labels=wiring.references,
        reference_units=wiring.reference_units,
        disturbance=dist[:, ref_idx] if dist.shape[1] > 1 else dist.repeat(n_rec, axis=1),
        disturbance_labels=dist_labels,
        disturbance_units=dist_units,
        status=status,
        failure_time=t_fail,
        failure_state=z_fail,
        params={
            "vessel": (m_cls, mp),
            "actuator": (a_cls, ap),
            "controller": (c_cls, cp),
            **info["stage_params"],
        },
        metadata={
            "model": model.name,
            **({} if problem.ship is None else {
                "ship": problem.ship.name, "ship_model": problem.ship.model.name,
                "ship_provenance": problem.ship.provenance or "not given"}),
            "actuator": actuator.name,
            "controller": controller.name,
            "integrator": tableau.name,
            "actuator_step": "closed-form" if exact_actuator else "integrated",
            "execution": "compiled" if use_jit else "python",
            **{k: v for stage in info["stages"] for k, v in stage.metadata(problem).items()},
            "dt": float(dt),
            "controller_dt": ctrl_dt,
            "t_final": float(t_final),
            "record_every": record_every,
            "seed": -1 if seed is None else int(seed),
            "wall_time_s": wall,
            "compile_time_s": compile_time,
            **(dict(metadata) if metadata else {}),
        },
    )
    if model.check_result is not None:  # (the model's validity range, on what was run)
        model.check_result(result)
    if problem.post_pass is not None:  # (computed from the recordings, into the result)
        extra, more = problem.post_pass.compute(result)
        result.extra.update(extra)
        result.metadata.update(more)
    if throw and status.any():
        i = int(np.argmax(status != 0))
        raise SimulationDiverged(
            failure_text(i, int(status[i]), float(t_fail[i]), labels, z_fail[i]),
            time=t_fail[i],
            state=z_fail[i],
            run=i,
        )
    return result



def failure_text(i: int, status: int, t_fail: float, labels: tuple[str, ...],
                 z_fail: np.ndarray) -> str:
    """How run ``i`` diverged, in the words of :class:`~seahelm.errors.SimulationDiverged`."""
    return (f"run {i} diverged at t = {t_fail:.6g} s "
            f"({RunStatus(status).name.lower().replace('_', ' ')}): "
            + ", ".join(f"{lab}={v:.6g}" for lab, v in zip(labels, z_fail)))
