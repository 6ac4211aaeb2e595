"""Stages of the compiled closed loop: what one declares, and how the loop is made of them.

A *stage* is a part of the step that is not the vessel, the actuator, the controller or the
integrator: the environment's loads (:mod:`seahelm.simulation.environment_stage`), the
first-order wave motions evaluated in the loop (:mod:`seahelm.simulation.wave_motion_stage`),
and whatever comes next (a thrust allocation, a sensor). Each is one module with a
:class:`Stage` subclass, listed by one line in :data:`seahelm.simulation.stages.STAGES`;
the kernel template (:mod:`seahelm.simulation.kernel_template`) names none of them. A stage
declares

* its **outputs** (recorded after the model's, in the order of the registry) and the
  **disturbance signals** it reads (after the model's channels);
* its **per-run arrays**: one group of the kernel's arguments
  (:mod:`seahelm.simulation.kernel_args`; ``stages[q]`` for the q-th stage of the loop);
* its **scratch**: buffers of one slice of runs (``stage_scratch[q]``), allocated by
  :func:`aligned_buffers`;
* its **place in the step**, as source lines for the positions of :data:`POSITIONS`
  (:class:`StageCode`), which :func:`hooks_source` joins into the generated loop's hook
  functions. A loop without a stage has no line of it, no array, no constant: its hooks are
  empty and numba removes their calls.

The names a stage's lines may use are each position's arguments (:data:`POSITIONS`) and
``g`` (its per-run arrays), ``s`` (its scratch), bound at the top of each hook.
"""

from __future__ import annotations

import dataclasses
import math
import sys
from types import FunctionType
from collections.abc import Hashable
from typing import Any, ClassVar

import numpy as np

from .generated import code_fingerprint

__all__ = ["Stage", "StageCode", "POSITIONS", "hooks_source", "aligned_buffers", "binding"]

#: Where in the step a stage's lines run, and the names they see there:
#:
#: * ``outputs``: after the model's outputs, wherever the loop evaluates them (at a recorded
#:   step, a controller sample, the controllers' init, an observation): ``t`` [s], the step
#:   ``k``, the run ``i``, the vessel state ``xv``, the model's inputs ``u`` and parameter
#:   record ``mp``, the outputs ``ym`` (model's, then every stage's), the run's disturbance
#:   array ``dist`` (runs|1, steps+1|1, channels) and row ``idist``, ``d0`` (its values at
#:   the step's start when they do not vary) and a buffer ``ds``;
#: * ``step_start``: once per step, before the integrator's stages: ``t``, ``i``, ``xv``,
#:   ``u``, ``mp``, ``d0`` (the disturbance at the step's start);
#: * ``rhs``: at every stage of the integrator, before the model's right-hand side: ``t``,
#:   ``i``, ``xv``, ``u``, ``mp``, ``d`` (the disturbance at the stage). A stage that changes
#:   what the model feels writes it into a buffer of its scratch and names that buffer in
#:   :attr:`StageCode.disturbance` (the model reads it).
POSITIONS: dict[str, str] = {
    "outputs": "t, k, i, xv, u, mp, ym, dist, idist, d0, ds, sg, ss",
    "step_start": "t, i, xv, u, mp, d0, sg, ss",
    "rhs": "t, i, xv, u, mp, d, sg, ss",
}


@dataclasses.dataclass(frozen=True)
class StageCode:
    """A stage's part of the generated loop.

    Attributes
    ----------
    bindings : tuple of (str, bytes)
        Import lines binding the numba functions its lines call, with their code
        fingerprints (:func:`seahelm.simulation.closed_loop._binding`).
    lines : dict
        Position (:data:`POSITIONS`) -> source lines (without indentation).
    disturbance : int, optional
        The buffer of its scratch (an index) that the model's right-hand side reads instead
        of ``d``, written by its ``rhs`` lines.
    measurement_from : tuple of int, optional
        The controller's measurements routed anew (index of the output each one reads).
    """

    bindings: tuple[tuple[str, bytes], ...] = ()
    lines: dict[str, tuple[str, ...]] = dataclasses.field(default_factory=dict)
    disturbance: int | None = None
    measurement_from: tuple[int, ...] | None = None


class Stage:
    """One stage of the closed loop (module docstring). Subclasses are frozen dataclasses of
    what their generated code depends on (a stage is part of the compiled loop's cache key),
    and implement the methods below; the defaults are those of a stage without the item."""

    #: The stage's name in :data:`seahelm.simulation.stages.STAGES`.
    name: ClassVar[str] = ""
    #: The names of its per-run arrays, in the order of :meth:`arrays`.
    members: ClassVar[tuple[str, ...]] = ()

    @classmethod
    def from_problem(cls, problem: Any) -> "Stage | None":
        """The stage a problem asks for, or None (the loop then runs without it).

        Parameters
        ----------
        problem : Problem
            The problem the loop is built for.
        """
        raise NotImplementedError

    @property
    def key(self) -> Hashable:
        """What the generated code depends on (the stage itself: a frozen dataclass)."""
        return self

    # ---- declarations ------------------------------------------------------------------
    def signals(self) -> tuple[tuple[str, ...], tuple[str, ...]]:
        """The disturbance signals it reads after the model's channels (names, units)."""
        return (), ()

    def outputs(self, model: Any) -> tuple[tuple[str, ...], tuple[str, ...]]:
        """The outputs it writes after the model's (and earlier stages'): names, units.

        Parameters
        ----------
        model : VesselModel
            The loop's vessel model.
        """
        return (), ()

    def check(self, problem: Any, model: Any) -> None:
        """Raise a :class:`~seahelm.errors.ParameterError` if the problem cannot take it.

        Parameters
        ----------
        problem : Problem
            The problem the loop is built for.
        model : VesselModel
            The loop's vessel model.
        """

    def code_size(self, model: Any, jit: bool) -> tuple[int, int]:
        """Bytecode its ``rhs`` lines inline at each integrator stage, and what it compiles
        once (:data:`seahelm.simulation.closed_loop.STAGE_LOOP_ABOVE`).

        Parameters
        ----------
        model : VesselModel
            The loop's vessel model.
        jit : bool
            The compiled loop (else the pure-Python one).
        """
        return 0, 0

    def code(self, model: Any, controller: Any, measurement_from: tuple[int, ...],
             first_output: int, jit: bool) -> StageCode:
        """Its lines of the generated loop.

        Parameters
        ----------
        model, controller : VesselModel, Controller
            The components.
        measurement_from : tuple of int
            The controller's measurements as routed so far.
        first_output : int
            The index in ``ym`` of its first output.
        jit : bool
            Compiled (else the pure-Python loop's functions are bound).
        """
        return StageCode()

    # ---- per run -----------------------------------------------------------------------
    def inputs(self, problem: Any, model: Any) -> Any:
        """Its per-run inputs from the problem, checked (passed to the methods below).

        Parameters
        ----------
        problem : Problem
            The problem the loop is built for.
        model : VesselModel
            The loop's vessel model.
        """
        return None

    def run_counts(self, inputs: Any) -> tuple[tuple[str, int], ...]:
        """The runs its inputs were made for, by the field that gave them (none: any).

        Parameters
        ----------
        inputs : object
            What :meth:`inputs` gave for the problem.
        """
        return ()

    def arrays(self, inputs: Any, n_runs: int) -> tuple[np.ndarray, ...]:
        """Its per-run arrays (:attr:`members`), for ``n_runs`` runs.

        Parameters
        ----------
        inputs : object
            What :meth:`inputs` gave for the problem.
        n_runs : int
            Runs of the batch.
        """
        return ()

    def scratch(self, model: Any, arrays: tuple[np.ndarray, ...],
                n_outputs: int) -> tuple[np.ndarray, ...]:
        """Fresh buffers for one slice of runs (:func:`aligned_buffers`); ``n_outputs`` is
        the loop's number of outputs.

        Parameters
        ----------
        model : VesselModel
            The loop's vessel model.
        arrays : tuple of ndarray
            Its per-run arrays (:meth:`arrays`).
        n_outputs : int
            The loop's number of outputs.
        """
        return ()

    def metadata(self, problem: Any) -> dict[str, Any]:
        """What the result's metadata says of it.

        Parameters
        ----------
        problem : Problem
            The problem the loop is built for.
        """
        return {}

    def result_params(self, inputs: Any, n_runs: int) -> dict[str, Any]:
        """Parameter records the result keeps (name -> (record class, rows)).

        Parameters
        ----------
        inputs : object
            What :meth:`inputs` gave for the problem.
        n_runs : int
            Runs of the batch.
        """
        return {}


def hooks_source(codes: list[StageCode]) -> tuple[str, str]:
    """The generated hook functions ``stages_<position>`` of :data:`POSITIONS` for the loop's
    stages (in order), and the expression of the disturbance the model's right-hand side
    reads (``d``, or the last ``rhs`` stage's buffer).

    Parameters
    ----------
    codes : list of StageCode
        The loop's stages' parts, in the loop's order.
    """
    disturbance = "d"
    out = []
    for position, args in POSITIONS.items():
        body: list[str] = []
        for q, code in enumerate(codes):
            lines = code.lines.get(position, ())
            if lines:
                body += [f"g = sg[{q}]", f"s = ss[{q}]", *lines]
            if position == "rhs" and code.disturbance is not None:
                disturbance = f"ss[{q}][{code.disturbance}]"
        text = "".join(f"    {line}\n" for line in body) or "    pass\n"
        out.append(f"\n\n@njit(inline=\"always\", fastmath=FASTMATH, _nrt=False)\n"
                   f"def stages_{position}({args}):  # pragma: no cover - compiled\n{text}")
    return "".join(out), disturbance


def aligned_buffers(shapes: list[tuple[int, ...]], dtypes: list[Any] | None = None
                    ) -> tuple[np.ndarray, ...]:
    """Zeroed buffers of these shapes, views of one block, each starting on its own 64-byte
    cache line and the block padded by a line at both ends: buffers of different threads
    never share a cache line (tiny arrays allocated one by one do, and the threads' stores
    then contend for it at every step).

    Parameters
    ----------
    shapes : list of tuple of int
    dtypes : list of dtype, optional
        float64 (default) or int64, per buffer.

    Returns
    -------
    tuple of ndarray
    """
    dtypes = dtypes or [np.float64] * len(shapes)
    line = 8  # 8-byte items per 64-byte cache line
    views: list[tuple[int, np.ndarray]] = []
    for dtype in (np.float64, np.int64):
        mine = [j for j, dt in enumerate(dtypes) if np.dtype(dt) == np.dtype(dtype)]
        counts = [math.prod(shapes[j]) for j in mine]  # (math.prod: np.prod costs µs)
        sizes = [-(-n // line) * line for n in counts]
        block = np.zeros(sum(sizes) + 3 * line, dtype=dtype)
        o = line + (-block.ctypes.data // 8) % line  # first line boundary after the padding
        for j, n, size in zip(mine, counts, sizes):
            views.append((j, block[o:o + n].reshape(shapes[j])))
            o += size
    return tuple(v for _, v in sorted(views, key=lambda jv: jv[0]))


def binding(func: Any, alias: str, inline: bool = True, jit: bool = True) -> tuple[str, bytes]:
    """The import lines that bind a numba function as ``alias`` in the generated loop (inlined
    at numba-IR level, or called), and its code fingerprint.

    Parameters
    ----------
    func : numba dispatcher
        A module-level ``@njit`` function (its Python function when numba's JIT is off).
    alias : str
        Its name in the loop.
    inline : bool
        Inline it at every call site (default) or call it.
    jit : bool
        The compiled loop (else the pure-Python one).

    Returns
    -------
    (str, bytes)

    Raises
    ------
    TypeError
        If ``func`` is not a module-level numba function.
    """
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
