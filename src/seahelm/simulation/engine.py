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

import contextlib
import enum
import functools
import hashlib
import math
import re
import sys
import time as _time
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from types import FunctionType, ModuleType
from typing import TYPE_CHECKING, Any

import numpy as np

from .. import __version__
from .._validate import as_float_array
from ..actuators.base import Actuator
from ..control.base import Controller
from ..errors import ParameterError, SimulationDiverged
from ..parameters import Params, as_records, stack_params
from ..resources import check_work, memory_limit
from ..vessels.base import VesselModel
from .compiled_step import compiled_advance_source, compiled_stage_loop_source
from .composition import compose
from ..environment.first_order_in_loop import HEADING_TOTAL
from ..environment.first_order_kernel import first_order_sample
from .wave_motion_stage import wave_constants
from .environment_stage import (
    environment_stage,
    no_apply_loads,
    no_environment_loads,
    python_environment_stage,
)
from .generated import code_fingerprint, exec_generated, import_generated, kernel_cache_dir
from .inlining import inlined_size
from .problem import Problem, _numba_jit_disabled, jit_enabled
from .integrators import ButcherTableau, get_integrator

if TYPE_CHECKING:  # pragma: no cover
    from ..results import SimResult

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
# kernel generation
# ------------------------------------------------------------------------------------------
def _binding(func: Any, alias: str, inline: bool = True, jit: bool = True) -> tuple[str, bytes]:
    py = getattr(func, "py_func", None)
    if py is None and not jit and isinstance(func, FunctionType):
        py = func  # the pure-Python loop (numba's JIT disabled: njit returned the function)
    if py is None:
        raise TypeError(f"{alias} must be a numba @njit function, got {func!r}")
    module, name = py.__module__, py.__name__
    mod = sys.modules.get(module)
    if mod is None or getattr(mod, name, None) is not func:
        raise TypeError(
            f"{alias} '{module}.{name}' must be importable as a module-level name"
        )
    if not inline and jit:  # called, not inlined (compiled once, with _nrt=False, by its module)
        return f"from {module} import {name} as {alias}\n", code_fingerprint(py)
    # re-jit the component, and every numba function it calls, with inline="always": numba
    # then inlines them at IR level into the loop, which lets LLVM optimise across the
    # component boundaries (a helper left as a call cost the catamaran loop 25 %)
    line = (f"from {module} import {name} as _{alias}\n"
            f"{alias} = inline_always(_{alias})\n")
    return line, code_fingerprint(py)


_TEMPLATE_TEXT = (Path(__file__).with_name("kernel_template.py")).read_text()

#: The first lines of the header of a pure-Python loop (``compile_closed_loop(jit=False)``):
#: after the template's imports, they rebind ``njit``, ``inline_always`` and ``local_record``
#: to their plain-Python stand-ins, so the rest of the module is the compiled loop's text.
PYTHON_HEADER = (
    "# the pure-Python loop (simulate(jit=False)): njit leaves the functions below as they\n"
    "# are, the components are their Python functions, a parameter record is read in place\n"
    "from seahelm.simulation.inlining import no_jit as njit\n"
    "from seahelm.simulation.inlining import python_function as inline_always\n"
    "from seahelm.simulation.inlining import record_in_place as local_record\n\n"
)

_BLOCK = re.compile(r"# <(header|footer)>\n.*?# </\1>\n", re.S)

#: Step code size (bytecode instructions of the model's and the actuator's right-hand sides and
#: what they call, times the number of stages, plus the environment's loads) above which the
#: integrator's stages are looped over rather than written out. Written out, each stage inlines
#: its own copy of the right-hand side: light models run faster that way, heavy ones compile
#: much longer for no speed. Measured with empty caches (2 cores, RK4), written out → looped:
#: KVLCC2 MMG (4 × 837) compile 9.4 → 4.6 s, 1,000 turning circles 0.86 → 0.87 s;
#: nonlinear Mariner (4 × 596) 5.8 → 3.3 s, 0.50 → 0.40 s; Nomoto-2 + PID (4 × 253)
#: 5.9 → 3.7 s but 1.67e7 → 1.44e7 vessel-steps/s; catamaran (4 × 368) 5.7 → 3.7 s but
#: 97 % → 70 % of the hand-fused kernel (2026-11-26); Voitkunsky + compensated PID + Lvov's
#: loads (4 × 421 + 450) 7.8–8.6 → 5.1–5.5 s at the same speed (a single run 5.7 ms). A third
#: form, the stage inputs written out but one right-hand side in a loop (a switch on the
#: stage), compiled like the loop (catamaran 5.4 s, Voitkunsky 5.8 s) but ran Nomoto-2 16–30 %
#: and the catamaran 4–10 % slower than written out; it is not used. Bytecode counts differ a
#: little between Python versions (4-9 % from 3.11 to 3.13), so the threshold sits between
#: the nearest combinations with room both ways: written out, the catamaran (1,552 on 3.11, at
#: most ~1,690 elsewhere) and the CPP ship in waves (1,664, ~1,810); looped, the Voitkunsky
#: model with Lvov's loads (2,134, at least ~1,940).
#: The choice is made when a combination is first compiled in a process: to change it, set
#: this and call ``compile_closed_loop.cache_clear()``, or pass ``stage_loop=`` to
#: :func:`compile_closed_loop`.
STAGE_LOOP_ABOVE = 1850

def _stage_code_size(model: VesselModel, actuator: Actuator, tableau: ButcherTableau,
                     environment: Any, exact_actuator: bool = False, jit: bool = True) -> int:
    """The code a written-out step makes numba compile (see :data:`STAGE_LOOP_ABOVE`): what
    each stage inlines, times the stages, plus the environment's loads (compiled once, as a
    function of their own, but in the same compile the user waits for)."""
    per_stage = (inlined_size(model.rhs) + inlined_size(actuator.output)
                 + inlined_size(actuator.advance if exact_actuator else actuator.rhs))
    once = 0
    if environment is not None:
        loads, apply = (environment_stage if jit else python_environment_stage)(environment,
                                                                                  model)
        per_stage += inlined_size(apply)
        once = inlined_size(loads)
    return tableau.stages * per_stage + once


def _route_source(name: str, args: str, assignments: list[str]) -> str:
    body = "".join(f"    {line}\n" for line in assignments) or "    pass\n"
    return (f"\n\n@njit(inline=\"always\")\ndef {name}({args}):  # pragma: no cover\n"
            + body)


@functools.lru_cache(maxsize=None)
def compile_closed_loop(
    model: VesselModel,
    actuator: Actuator,
    controller: Controller,
    integrator: str | ButcherTableau = "rk4",
    environment: Any = None,
    stage_loop: bool | None = None,
    exact_actuator: bool | None = None,
    jit: bool = True,
    first_order: tuple[tuple[str, ...], bool] | None = None,
) -> ModuleType:
    """The compiled closed-loop module for one combination of components (cached).

    Parameters
    ----------
    model, actuator, controller
        The components; they are wired by signal name
        (:func:`~seahelm.simulation.composition.compose`).
    integrator : str or ButcherTableau
        A name in :data:`~seahelm.simulation.integrators.INTEGRATORS` (default "rk4") or a
        tableau; its step is generated into the module, so the module's name (a hash of its
        text) differs between tableaus.
    environment : Environment, optional
        Wind and wave loads (:mod:`seahelm.environment.loads`), evaluated at every stage
        from the live state (:mod:`seahelm.simulation.environment_stage`).
    stage_loop : bool, optional
        Write the integrator's step as a loop over its stages
        (:func:`~seahelm.simulation.compiled_step.compiled_stage_loop_source`: the stage
        right-hand side inlined once) instead of the stages written out
        (:func:`~seahelm.simulation.compiled_step.compiled_advance_source`: inlined once per
        stage). Default: a loop when the code inlined per stage is larger than
        :data:`STAGE_LOOP_ABOVE` (see there).
    exact_actuator : bool, optional
        Take the actuator states at every stage from its closed-form step
        (``actuator.advance``: exact under the held command, and no stability bound on the
        step from a fast servo) instead of integrating ``actuator.rhs`` with the tableau.
        Default: whenever the actuator has one.
    jit : bool
        ``False``: the same generated module as plain Python (:data:`PYTHON_HEADER`), run in
        memory: ``njit`` leaves its functions as they are and the components are bound as their
        Python functions (:func:`~seahelm.simulation.inlining.python_function`), so nothing is
        compiled, nothing is written to the kernel cache or numba's, and a breakpoint in a
        component's source is hit. The stages are written out or looped over as compiled.
    first_order : (tuple of str, bool), optional
        First-order wave motions in the loop (:mod:`seahelm.environment.first_order_in_loop`):
        the degrees of freedom evaluated, and whether the controller's ``heading``
        measurement is ``heading_total`` (ψ + ψ₁) instead of the model's ``heading``.

    Returns
    -------
    module
        The imported kernel module (``init_runs``, ``run_slice``, ``scratch``).

    Raises
    ------
    ValueError
        If ``exact_actuator`` asks for a closed-form step the actuator lacks, or ``jit`` is
        True while numba's JIT is disabled (``NUMBA_DISABLE_JIT=1``).
    """
    if jit and _numba_jit_disabled():
        raise ValueError("jit: numba's JIT is disabled (NUMBA_DISABLE_JIT=1); pass jit=False")
    tableau = get_integrator(integrator)
    wiring = compose(model, actuator, controller)
    if exact_actuator is None:
        exact_actuator = actuator.advance is not None
    elif exact_actuator and actuator.advance is None:
        raise ValueError(f"exact_actuator: the actuator {actuator.name!r} has no closed-form "
                         "step (advance)")
    parts = [
        _binding(model.rhs, "model_rhs", jit=jit),
        _binding(model.output, "model_output", jit=jit),
        _binding(actuator.rhs, "actuator_rhs", jit=jit),
        _binding(actuator.output, "actuator_output", jit=jit),
        _binding(controller.init, "controller_init", jit=jit),
        _binding(controller.step, "controller_step", jit=jit),
    ]
    if exact_actuator:
        parts.append(_binding(actuator.advance, "actuator_advance", jit=jit))
    loads, apply = ((no_environment_loads, no_apply_loads) if environment is None
                    else (environment_stage if jit else python_environment_stage)(environment,
                                                                                  model))
    # the environment's loads are called, not inlined: inlined at every stage and record site
    # they doubled the loop's compile time (76 s against 31 s for the KVLCC2), and a call
    # costs little beside their transcendental functions
    parts += [_binding(loads, "environment_loads", inline=environment is None, jit=jit),
              _binding(apply, "apply_loads", jit=jit),
              _binding(first_order_sample, "first_order_sample", jit=jit)]
    n_env = 0 if environment is None else len(environment.output_labels)
    waves = wave_constants(model, controller, wiring.measurement_from, n_env, first_order)
    header = ("" if jit else PYTHON_HEADER) + "".join(p[0] for p in parts) + (
        f"\nNX = {model.n_states}\nNA = {actuator.n_states}\nNU = {model.n_inputs}\n"
        f"NYM = {model.n_outputs + n_env + waves['NW_OUT']}\n"
        f"NYA = {len(wiring.actuator_outputs)}\n"
        f"NCA = {len(wiring.actuator_commands)}\nNM = {controller.n_measurements}\n"
        f"NDM = {model.n_disturbances}\nHAS_ENV = {environment is not None}\n"
        f"HOLD_LOADS = {bool(getattr(environment, 'hold_over_step', False))}\n"
        f"EXACT_ACTUATOR = {bool(exact_actuator)}\n"
        + "".join(f"{k} = {v}\n" for k, v in waves.items() if k != "measurement_from") +
        "FASTMATH = {\"arcp\", \"contract\", \"afn\", \"reassoc\"}\n"
    )
    header += _route_source("route_actuator_commands", "cmd, ca", [
        f"ca[{j}] = cmd[{k}]" for j, k in enumerate(wiring.actuator_command_from)])
    header += _route_source("route_inputs", "ya, cmd, u", [
        f"u[{i}] = {'ya' if kind == 'actuator' else 'cmd'}[{j}]"
        for i, (kind, j) in enumerate(wiring.input_from)])
    header += _route_source("route_measurements", "ym, y", [
        f"y[{i}] = ym[{j}]" for i, j in enumerate(waves["measurement_from"])])
    if stage_loop is None:
        stage_loop = _stage_code_size(model, actuator, tableau, environment,
                                      exact_actuator, jit) > STAGE_LOOP_ABOVE
    footer = (compiled_stage_loop_source if stage_loop else compiled_advance_source)(
        tableau, exact_actuator)
    blocks = iter([header, footer])
    text = _BLOCK.sub(lambda m: next(blocks), _TEMPLATE_TEXT)
    digest = hashlib.sha1(
        b"\0".join([text.encode(), __version__.encode(), *(p[1] for p in parts)])
    ).hexdigest()[:16]
    if not jit:
        return exec_generated(f"seahelm_python_loop_{digest}", text)
    return import_generated(f"seahelm_kernel_{digest}", text)


class _Slices:
    """The batch cut into slices of runs, run by the kernel's ``run_slice`` on a thread pool.

    The compiled loop releases the GIL, so threads run slices in parallel; there are up to four
    slices per thread (a slice of runs that stop early does not leave a thread idle) and never
    more threads than runs (a single run stays in the calling thread). ``numba.set_num_threads``
    and ``NUMBA_NUM_THREADS`` set the number of threads, as for any numba parallel code.

    Every slice has its own scratch buffers (the kernel allocates nothing). ``threads`` caps
    the threads (the pure-Python loop runs in the calling thread: ``threads=1``).
    """

    def __init__(self, kernel: ModuleType, arrays: Sequence[np.ndarray],
                 scratch_sizes: tuple[int, ...], threads: int | None = None,
                 wave_sizes: tuple[int, int] = (1, 1)) -> None:
        import numba

        self.kernel = kernel
        n_runs = arrays[0].shape[0]
        # numba types a read-only array apart from a writable one: a kernel called with both
        # (a broadcast view of one run, say) would compile twice, each 15-80 s
        self.arrays = tuple(a if a.flags.writeable else a.copy() for a in arrays)
        self.threads = max(1, min(numba.get_num_threads() if threads is None else threads,
                                  n_runs))
        n_slices = 1 if self.threads == 1 else min(n_runs, 4 * self.threads)
        self.cuts = (np.array([0, n_runs]) if n_slices == 1 else
                     np.linspace(0, n_runs, n_slices + 1).round().astype(np.int64))
        self.scratch = [kernel.scratch(*scratch_sizes) for _ in range(n_slices)]
        self.wave_scratch = [kernel.wave_scratch(*wave_sizes) for _ in range(n_slices)]

    def warm_up(self, n_steps: int, dt: float, ctrl_every: int, rec_every: int) -> None:
        """Compile or load the kernel for these argument types: a zero-step call (once
        compiled, a call costs about 4 µs of argument checks; asking whether these types were
        seen before, from the arrays' flags, cost five times that)."""
        self.run(0, 0, n_steps, dt, ctrl_every, rec_every)

    def run(self, k_start: int, k_stop: int, n_steps: int, dt: float, ctrl_every: int,
            rec_every: int) -> None:
        def one(s: int) -> None:
            self.kernel.run_slice(int(self.cuts[s]), int(self.cuts[s + 1]), k_start, k_stop,
                                  n_steps, dt, ctrl_every, rec_every, *self.arrays,
                                  *self.scratch[s], *self.wave_scratch[s])

        n_slices = len(self.cuts) - 1
        if self.threads == 1 or k_stop == k_start:
            for s in range(n_slices):
                one(s)
            return
        with ThreadPoolExecutor(self.threads, thread_name_prefix="seahelm") as pool:
            # list() re-raises an exception of any slice here
            list(pool.map(one, range(n_slices)))


# ------------------------------------------------------------------------------------------
# input conversion
# ------------------------------------------------------------------------------------------
@functools.lru_cache(maxsize=None)
def _default_params(cls: type[Params]) -> Params:
    """The default parameter set of a class (frozen, so one instance serves every run)."""
    return cls()


def _param_rows(name: str, params: Any, cls: type[Params]) -> tuple[np.ndarray, type[Params]]:
    """Parameter rows (runs, n_fields) and the class they were given as (a subclass of
    ``cls`` carries more fields; compiled code finds its fields by name)."""
    if params is None:
        try:
            params = _default_params(cls)
        except TypeError:
            raise ParameterError(f"is required for {cls.__name__}", field=name) from None
    if isinstance(params, Params) or (
        isinstance(params, Sequence) and len(params) > 0 and isinstance(params[0], Params)
    ):
        first = params if isinstance(params, Params) else params[0]
        return stack_params(params, cls), type(first)
    # a copy: the kernel and the result's ``params`` get rows of their own, never the caller's
    arr = np.array(np.atleast_2d(as_float_array(name, params)), dtype=float, order="C")
    if arr.ndim != 2 or arr.shape[1] != cls.n_values():
        raise ParameterError(
            f"as an array must have shape (runs, {cls.n_values()}) "
            f"({', '.join(cls.value_names())}), got {arr.shape}", field=name)
    for row in arr:  # validate every row through the dataclass
        cls.from_array(row)
    return arr, cls


class _TimeGrid:
    """The grid t_k = k dt, k = 0 … n_steps, built only if a signal is a function of time."""

    def __init__(self, n_steps: int, dt: float) -> None:
        self.size = n_steps + 1
        self.dt = dt
        self._array: np.ndarray | None = None

    def array(self) -> np.ndarray:
        if self._array is None:
            self._array = np.arange(self.size) * self.dt
        return self._array


def _by_name(name: str, value: Mapping[str, Any], labels: tuple[str, ...],
             t_grid: "_TimeGrid", unit: str) -> np.ndarray:
    """A mapping channel name -> specification, assembled into (runs|1, steps+1|1, channels)."""
    unknown = [k for k in value if k not in labels]
    if unknown:
        raise ParameterError(
            f": unknown channel(s) {', '.join(map(repr, unknown))}; channels: "
            f"{', '.join(labels) if labels else 'none'}", field=name)
    cols = [_signal(f"{name}['{lab}']", value.get(lab, 0.0), 1, t_grid, unit) for lab in labels]
    if not cols:
        return np.zeros((1, 1, 1))
    runs = _runs(*((f"{name}['{lab}']", c.shape[0]) for lab, c in zip(labels, cols)))
    steps = max(c.shape[1] for c in cols)
    return np.ascontiguousarray(np.concatenate(
        [np.broadcast_to(c, (runs, steps, 1)) for c in cols], axis=2))


def _signal(
    name: str, value: Any, n_channels: int, t_grid: "_TimeGrid", unit: str,
    labels: tuple[str, ...] = (),
) -> np.ndarray:
    """Convert a reference/disturbance specification to shape (runs|1, steps+1|1, channels)."""
    width = max(n_channels, 1)
    if value is None:
        return np.zeros((1, 1, width))
    if isinstance(value, Mapping):
        return _by_name(name, value, labels, t_grid, unit)
    if callable(value):
        value = value(t_grid.array())
        arr = as_float_array(name, value, unit)
        if arr.ndim == 1 and arr.shape[0] == t_grid.size:
            arr = arr[:, None]
        if arr.ndim == 2:
            arr = arr[None]
        if arr.ndim != 3 or arr.shape[1] != t_grid.size:
            raise ParameterError(
                f"callable must return shape (steps+1,), (steps+1, channels) or "
                f"(runs, steps+1, channels) for {t_grid.size} grid times, got {np.shape(value)}",
                field=name)
    else:
        arr = as_float_array(name, value, unit)
        if arr.ndim == 0:
            arr = arr.reshape(1, 1, 1)
        elif arr.ndim == 1:
            arr = arr.reshape(1, 1, -1)
        elif arr.ndim == 2:
            if arr.shape[0] != t_grid.size:
                raise ParameterError(
                    f"as a 2-D array is a time series on the grid and needs "
                    f"{t_grid.size} rows (steps+1), got {arr.shape}; per-run constants have "
                    "shape (runs, 1, channels)", field=name)
            arr = arr[None]
        elif arr.ndim != 3:
            raise ParameterError(f"must have at most 3 dimensions, got {arr.shape}", field=name)
        if arr.shape[1] not in (1, t_grid.size):
            raise ParameterError(
                f"time axis must have 1 or {t_grid.size} samples, got {arr.shape[1]}", field=name)
    if n_channels == 0:
        if arr.shape[-1] not in (0, 1) or np.any(arr != 0):
            raise ParameterError("given, but the component takes none", field=name)
        return np.zeros(arr.shape[:2] + (1,))
    if arr.shape[-1] != n_channels:
        named = f" ({', '.join(labels)})" if labels else ""
        raise ParameterError(
            f"must have {n_channels} channel(s){named}, got {arr.shape[-1]}", field=name)
    return np.ascontiguousarray(arr, dtype=float)


#: The engine's peak memory per byte of recorded time series: the recordings themselves, the
#: results Dataset made from them and the NetCDF file built in memory before it is written
#: (:func:`seahelm.results.netcdf_bytes`). Measured (tracemalloc, 2,000 and 500 runs of
#: Nomoto-2 + PID, 0.3 GB of recordings, 2026-11-27): simulate 0.74x the estimate below (it
#: counts every channel at 8 B), to_xarray 1.47-1.63x, simulate then to_netcdf 2.33x in all;
#: 2.5 leaves room for HDF5's own buffers.
RECORD_PEAK_FACTOR = 2.5

#: A peak below this [bytes] is not checked against the memory limit (every limit that matters
#: is larger; asking the OS costs more than a short run).
ASK_ABOVE = 1 << 26

#: Wall time a slice of steps of the compiled loop aims at [s]. Between slices Python runs:
#: a progress callback, and a signal handler (the CLI turns SIGTERM and Ctrl-C into
#: exceptions), so a stop request ends a long run within about this time. A slice costs some
#: 5 µs to start (100 µs on the thread pool): 0.25 s keeps that below 0.05 %.
SLICE_SECONDS = 0.25

#: Steps × runs of the first slice, before the loop's speed is known: 0.15 s of a KVLCC2 MMG
#: ship (:data:`seahelm.resources.TYPICAL_RATE`), one slice for a short run.
FIRST_SLICE = 200_000

#: The same for the pure-Python loop (``jit=False``: some 10³ steps/s).
FIRST_SLICE_PYTHON = 200

#: Share of the memory this process may use (:func:`seahelm.resources.memory_limit`) that the
#: engine's peak may take.
RECORD_MEMORY_SHARE = 0.8


def physical_memory() -> int | None:
    """The memory this process may use [bytes]: the smallest of the machine's memory, its
    cgroup's room and its address-space room (:func:`seahelm.resources.memory_limit`; None
    where the OS does not say)."""
    limit = memory_limit()
    return None if limit is None else limit.bytes


class RecordingTooLarge(ParameterError):
    """The recorded time series would not fit in memory (raised before anything is allocated).

    ``need`` and ``total`` [B] are the recording's size and the memory this process may use,
    ``source`` what limits it, so a caller can name its own options in the advice (a
    manoeuvre's approach speed, say).
    """

    def __init__(self, message: str, *, need: int, total: int, source: str = "") -> None:
        super().__init__(message, field="record_every", unit="B", value=need)
        self.need, self.total, self.source = need, total, source

    def size_text(self) -> str:
        """"62.3 GB (a peak of about 2.5x that), more than 80% of the 25.3 GB this process
        may use (this machine's memory)"."""
        return (f"{self.need / 1e9:.3g} GB (a peak of about {RECORD_PEAK_FACTOR:g}x that), "
                f"more than {RECORD_MEMORY_SHARE:.0%} of the {self.total / 1e9:.3g} GB this "
                f"process may use ({self.source})")


def check_record_memory(n_runs: int, n_rec: int, channels: int) -> None:
    """Refuse, before anything is allocated, recordings that cannot fit in memory.

    Parameters
    ----------
    n_runs, n_rec, channels : int
        Runs, records per run and recorded channels (states, outputs, commands, references,
        disturbances).

    Raises
    ------
    RecordingTooLarge
        A :class:`~seahelm.errors.ParameterError`: the engine's peak (:data:`RECORD_PEAK_FACTOR`
        × the recorded arrays at 8 B a value) would take more than :data:`RECORD_MEMORY_SHARE`
        of the memory this process may use — the smallest of the machine's memory, its cgroup's
        limit and its address-space limit (:func:`seahelm.resources.memory_limit`).
    """
    need = 8 * n_runs * n_rec * channels
    if RECORD_PEAK_FACTOR * need <= ASK_ABOVE:  # (asking the OS takes ~60 us)
        return
    limit = memory_limit()
    if limit is None or RECORD_PEAK_FACTOR * need <= RECORD_MEMORY_SHARE * limit.bytes:
        return
    err = RecordingTooLarge("", need=need, total=limit.bytes, source=limit.source)
    raise RecordingTooLarge(
        f": the recorded time series would need {err.size_text()} ({n_runs:,} run(s) x "
        f"{n_rec:,} records x {channels} channels x 8 B); record fewer samples (a larger "
        "record_every), fewer runs or a shorter t_final", need=need, total=limit.bytes,
        source=limit.source)


#: Largest magnitude of an angle signal [rad]: a thousand turns. A heading reference of 1e300
#: (a unit mix-up, a garbage file) is no course: wrapped, it is noise of float precision.
MAX_ANGLE = 2000.0 * math.pi


def _check_angles(name: str, values: np.ndarray, labels: tuple[str, ...],
                  units: tuple[str, ...]) -> None:
    """Angle channels ([rad]) of a signal within ±:data:`MAX_ANGLE`."""
    for j, (label, unit) in enumerate(zip(labels, units)):
        if unit == "rad" and j < values.shape[-1]:
            worst = float(np.max(np.abs(values[..., j])))
            if worst > MAX_ANGLE:
                raise ParameterError(
                    f": channel '{label}' reaches {worst:.6g} rad, more than a thousand turns "
                    f"(±{MAX_ANGLE:.6g} rad); an angle is given in radians here (degrees in a "
                    "scenario as <name>_deg)", field=name, unit="rad", value=worst)


def _runs(*sizes: tuple[str, int]) -> int:
    n = max(s for _, s in sizes)
    for name, s in sizes:
        if s not in (1, n):
            others = ", ".join(f"{k}={v}" for k, v in sizes)
            raise ParameterError(f": batch sizes do not broadcast: `{name}` has {s} runs "
                                 f"({others})", field=name)
    return n


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
    from .problem import Problem

    given = {"params": params, "x0": x0, "t_final": t_final, "dt": dt, "ship": ship,
             "controller": controller, "controller_params": controller_params,
             "actuator": actuator, "actuator_params": actuator_params,
             "actuator_x0": actuator_x0, "reference": reference, "disturbance": disturbance,
             "controller_dt": controller_dt, "integrator": integrator,
             "record_every": record_every, "bounds": bounds, "seed": seed,
             "metadata": metadata, "environment": environment,
             "environment_params": environment_params, "exact_actuator": exact_actuator,
             "jit": jit, "first_order": first_order}
    given = {k: v for k, v in given.items() if v is not None}
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


def _run(problem: "Problem", *, throw: bool,
         progress: Callable[[int, int], None] | None) -> "SimResult":
    """Run a validated problem (:func:`simulate`)."""
    from ..results import SimResult

    model, actuator, controller = problem.model, problem.actuator, problem.controller
    params, x0, actuator_x0 = problem.params, problem.x0, problem.actuator_x0
    actuator_params, controller_params = problem.actuator_params, problem.controller_params
    reference, disturbance = problem.reference, problem.disturbance
    environment, environment_params = problem.environment, problem.environment_params
    bounds, seed, metadata = problem.bounds, problem.seed, problem.metadata
    exact_actuator, dt, t_final = problem.exact_actuator, problem.dt, problem.t_final
    use_jit = problem._derived["jit"]  # (resolved when the problem was made)
    n_steps, ctrl_every = problem.n_steps, problem.controller_every
    ctrl_dt, record_every = problem._derived["controller_dt"], problem.record_every
    tableau, wiring = problem.tableau, problem.wiring
    if environment is None:
        env_signals: tuple[str, ...] = ()
        env_units: tuple[str, ...] = ()
        env_outputs: tuple[str, ...] = ()
        env_output_units: tuple[str, ...] = ()
        ep, e_cls = np.zeros((1, 1)), None
    else:
        # checks the model has what the loads need
        (environment_stage if use_jit else python_environment_stage)(environment, model)
        env_signals, env_units = environment.signal_labels, environment.signal_units
        env_outputs, env_output_units = environment.output_labels, environment.output_units
        ep, e_cls = _param_rows("environment_params", environment_params,
                                environment.params_type)
        mp_check, m_check_cls = _param_rows("params", params, model.params_type)
        for name in model.load_params:
            j = m_check_cls.value_names().index(name)
            bad = ~(mp_check[:, j] > 0)
            if bad.any():
                raise ParameterError(
                    f": model '{model.name}' needs `{name}` > 0 to take the "
                    f"environment's loads, got {mp_check[bad, j][0]!r} (run "
                    f"{int(np.argmax(bad))})", field="params", run=int(np.argmax(bad)))
    dist_labels = model.disturbance_labels + env_signals
    dist_units = model.disturbance_units + env_units
    out_labels = model.output_labels + env_outputs
    out_units = model.output_units + env_output_units
    first_order = problem.first_order
    if first_order is None:
        wave_arrays = (np.zeros((1, 6, 1)), np.zeros((1, 2, 1, 1, 2, 1)), np.zeros(1),
                       np.zeros(1), np.ones(1))
        wave_key = None
    else:
        wave_arrays = first_order.arrays
        wave_key = (first_order.dofs, first_order.autopilot_sees_first_order)
        wave_labels, wave_units = first_order.output_signals("roll_angle" in
                                                             model.output_labels)
        out_labels, out_units = out_labels + wave_labels, out_units + wave_units

    mp, m_cls = _param_rows("params", params, model.params_type)
    ap, a_cls = _param_rows("actuator_params", actuator_params, actuator.params_type)
    cp, c_cls = _param_rows("controller_params", controller_params, controller.params_type)
    x0 = np.atleast_2d(as_float_array("x0", x0))
    if x0.shape[-1] != model.n_states or x0.ndim != 2:
        raise ParameterError(
            f"must have {model.n_states} states ({', '.join(model.state_labels)}), "
            f"got shape {x0.shape}", field="x0")
    xa0 = np.zeros((1, actuator.n_states)) if actuator_x0 is None else np.atleast_2d(
        as_float_array("actuator_x0", actuator_x0)
    )
    if xa0.shape[-1] != actuator.n_states:
        raise ParameterError(
            f"must have {actuator.n_states} states, got shape {xa0.shape}", field="actuator_x0")
    # the recordings must fit before anything of the batch's size is built (the time grid too:
    # a long run with a coarse record needs no array of all its steps)
    n_rec_early = n_steps // record_every + 1 + (n_steps % record_every != 0)
    n_runs_early = max(mp.shape[0], ap.shape[0], cp.shape[0], ep.shape[0], x0.shape[0],
                       1 if first_order is None else first_order.n_runs)
    channels_early = (model.n_states + actuator.n_states + len(out_labels)
                      + len(wiring.commands) + len(controller.output_labels)
                      + len(wiring.references) + len(dist_labels))
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
        ("controller_params", cp.shape[0]), ("environment_params", ep.shape[0]),
        ("x0", x0.shape[0]),
        ("actuator_x0", xa0.shape[0]), ("reference", ref.shape[0]),
        ("disturbance", dist.shape[0]),
        *(() if first_order is None else (("first_order", first_order.n_runs),)),
    )
    if first_order is not None and first_order.n_runs != n_runs:
        raise ParameterError(f": the first-order motions were drawn for {first_order.n_runs} "
                             f"run(s), the batch has {n_runs}", field="first_order")

    def rows(a: np.ndarray) -> np.ndarray:
        if a.shape[0] == n_runs and a.dtype == np.float64 and a.flags.c_contiguous:
            return a  # (as it is: a broadcast and a copy cost µs, a tenth of a short run)
        return np.ascontiguousarray(np.broadcast_to(a, (n_runs,) + a.shape[1:]), dtype=float)

    mp, ap, cp, ep = rows(mp), rows(ap), rows(cp), rows(ep)
    z = np.concatenate([rows(x0), rows(xa0)], axis=1)
    labels = model.state_labels + actuator.state_labels
    lower = np.array(list(model.state_lower) + [-np.inf] * actuator.n_states, dtype=float)
    upper = np.array(list(model.state_upper) + [np.inf] * actuator.n_states, dtype=float)
    for label, (lo, hi) in (bounds or {}).items():  # (labels checked by the Problem)
        j = labels.index(label)
        lower[j], upper[j] = max(lower[j], float(lo)), min(upper[j], float(hi))
    if not (np.isfinite(z).all() and (z >= lower).all() and (z <= upper).all()):
        bad0 = ~np.isfinite(z).all(axis=1) | (z < lower).any(axis=1) | (z > upper).any(axis=1)
        i = int(np.argmax(bad0))
        raise ParameterError(f": the initial state of run {i} is not finite or outside the "
                             f"bounds: {z[i]}", field="x0", run=i)

    if exact_actuator is None:
        exact_actuator = actuator.advance is not None
    kernel = compile_closed_loop(model, actuator, controller, tableau, environment,
                                 exact_actuator=bool(exact_actuator), jit=use_jit,
                                 first_order=wave_key)
    mr = as_records(mp, m_cls)
    ar = as_records(ap, a_cls)
    cr = as_records(cp, c_cls)
    er = ep if e_cls is None else environment.kernel_records(ep)  # + per-run constants
    nz = z.shape[1]
    ncmd = len(wiring.commands) + len(controller.output_labels)  # outputs after commands
    # every record_every-th step and the final one (the last interval may be shorter)
    n_rec = n_steps // record_every + 1 + (n_steps % record_every != 0)
    check_record_memory(n_runs, n_rec, nz + len(out_labels) + ncmd
                         + len(wiring.references) + len(dist_labels))
    cs = np.zeros((n_runs, max(controller.n_states, 1)))
    cmd = np.zeros((n_runs, ncmd))
    ca = np.zeros((n_runs, max(len(wiring.actuator_commands), 1)))
    status = np.zeros(n_runs, dtype=np.int64)
    t_fail = np.full(n_runs, np.nan)
    z_fail = np.full((n_runs, nz), np.nan)
    rec_z = np.full((n_runs, n_rec, nz), np.nan)
    rec_y = np.full((n_runs, n_rec, len(out_labels)), np.nan)
    rec_cmd = np.full((n_runs, n_rec, ncmd), np.nan)

    slices = _Slices(kernel, (z, cs, cmd, ca, mr, ar, cr, er, dist, ref, lower, upper,
                              status, t_fail, z_fail, rec_z, rec_y, rec_cmd, *wave_arrays),
                     (ncmd, ca.shape[1], cs.shape[1], dist.shape[2], ref.shape[2]),
                     threads=None if use_jit else 1,
                     wave_sizes=(wave_arrays[0].shape[2], wave_arrays[1].shape[3]))
    # compile or load the kernel before the clock starts: a zero-step call does it, so the
    # reported simulation time is the simulation's (first use of a combination compiles)
    c0 = _time.perf_counter()
    # the pure-Python loop's numpy scalars warn where the compiled loop silently makes inf/NaN
    # (then recorded as the run's divergence, as compiled)
    def quiet() -> Any:
        return contextlib.nullcontext() if use_jit else np.errstate(all="ignore")

    with quiet():
        slices.warm_up(n_steps, float(dt), ctrl_every, record_every)
        kernel.init_runs(*slices.arrays[:10], *slices.scratch[0], *slices.arrays[18:],
                         *slices.wave_scratch[0])
    compile_time = _time.perf_counter() - c0
    wall0 = _time.perf_counter()
    k = 0
    # the loop runs in slices of steps of about SLICE_SECONDS each: between them Python runs,
    # so a stop signal (Ctrl-C, SIGTERM: the CLI raises it as an exception) ends even a long
    # compiled run within about that time, and a progress bar moves smoothly
    chunk = min(n_steps, max(1, (FIRST_SLICE if use_jit else FIRST_SLICE_PYTHON)
                             // max(n_runs, 1)))
    while k < n_steps:
        k_stop = min(n_steps, k + chunk)
        t0 = _time.perf_counter()
        with quiet():
            slices.run(k, k_stop, n_steps, float(dt), ctrl_every, record_every)
        elapsed = _time.perf_counter() - t0
        done, k = k_stop - k, k_stop
        if progress is not None:
            progress(k, n_steps)
        chunk = int(min(max(done / max(elapsed, 1e-6) * SLICE_SECONDS, 1), n_steps))
        if status.all():
            break
    wall = _time.perf_counter() - wall0

    ref_idx = np.minimum(np.arange(n_rec) * record_every, n_steps)
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
        reference=ref[:, ref_idx] if ref.shape[1] > 1 else np.repeat(ref, n_rec, axis=1),
        reference_labels=wiring.references,
        reference_units=wiring.reference_units,
        disturbance=dist[:, ref_idx] if dist.shape[1] > 1 else np.repeat(dist, n_rec, axis=1),
        disturbance_labels=dist_labels,
        disturbance_units=dist_units,
        status=status,
        failure_time=t_fail,
        failure_state=z_fail,
        params={
            "vessel": (m_cls, mp),
            "actuator": (a_cls, ap),
            "controller": (c_cls, cp),
            **({} if e_cls is None else {"environment": (e_cls, ep)}),
        },
        metadata={
            "model": model.name,
            "actuator": actuator.name,
            "controller": controller.name,
            "integrator": tableau.name,
            "actuator_step": "closed-form" if exact_actuator else "integrated",
            "execution": "compiled" if use_jit else "python",
            **({} if environment is None else {"environment": environment.name}),
            **({} if first_order is None else {
                "first_order_in_loop": ", ".join(first_order.dofs)
                + " (seahelm.environment.first_order_in_loop)",
                "controller_heading": (f"{HEADING_TOTAL} (heading + first-order yaw)"
                                       if first_order.autopilot_sees_first_order
                                       else "heading")}),
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
    if throw and status.any():
        i = int(np.argmax(status != 0))
        raise SimulationDiverged(
            f"run {i} diverged at t = {t_fail[i]:.6g} s "
            f"({RunStatus(int(status[i])).name.lower().replace('_', ' ')}): "
            + ", ".join(f"{lab}={v:.6g}" for lab, v in zip(labels, z_fail[i])),
            time=t_fail[i],
            state=z_fail[i],
            run=i,
        )
    return result
