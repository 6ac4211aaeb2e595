"""Generation of the compiled closed loop: one module per combination of components.

:func:`compile_closed_loop` writes :mod:`seahelm.simulation.kernel_template`'s text with the
components' numba functions bound in (:func:`~seahelm.simulation.stage.binding`), the stages' hooks
(:func:`~seahelm.simulation.stage.hooks_source`), the routing of signals by name from
:func:`~seahelm.simulation.composition.compose` and the integrator's step from its Butcher
tableau, and imports it from the kernel cache (numba compiles it once per machine). The engine
(:mod:`seahelm.simulation.engine`) and the stepping simulator
(:mod:`seahelm.simulation.stepping`) run what it returns.

Where a kernel's compile goes (empty caches, CPU of the first ``simulate``, 2026-12-02): a light
kernel (Nomoto-1 + servo + PID, KVLCC2 MMG + servo + pid-heading-rps, RK4; 7-8 s) spends some
4 s in numba's own passes (``inline_inlinables`` 2 s, SSA, type inference), 1 s turning numba IR
into LLVM IR and 1.5-2 s in LLVM. LLVM's optimisation level is left at numba's default
(``NUMBA_OPT=3``): at 2 and 1 the three kernels measured (with the DP supply vessel) compiled
0-9 % faster, bit for bit the same; at 0, 11-19 % faster (the DP kernel 52 % slower, and not
cacheable) but ran 7-24 times slower, with other numbers (no FMA contraction). numba reads
its level (``numba.core.config.OPT``) when it builds each pass manager; it has no per-function
setting other than ``optnone``.
"""

from __future__ import annotations

import functools
import re
from pathlib import Path
from types import ModuleType
from typing import Any

from .. import __version__
from .._codegen import content_digest
from ..actuators.base import Actuator
from ..control.base import Controller
from ..vessels.base import VesselModel
from .compiled_step import compiled_advance_source, compiled_stage_loop_source
from .composition import compose
from .generated import exec_generated, import_generated
from .inlining import LOOP_FASTMATH, inlined_size
from .integrators import ButcherTableau, get_integrator
from .problem import _numba_jit_disabled
from .stage import Stage, binding, hooks_source

__all__ = ["compile_closed_loop", "STAGE_LOOP_ABOVE", "PYTHON_HEADER"]


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
                     stages: tuple[Stage, ...] = (), exact_actuator: bool = False,
                     jit: bool = True) -> int:
    """The code a written-out step makes numba compile (see :data:`STAGE_LOOP_ABOVE`): what
    each stage inlines, times the stages, plus what the loop's stages compile once (the
    environment's loads: a function of their own, but in the same compile the user waits
    for)."""
    per_stage = (inlined_size(model.rhs) + inlined_size(actuator.output)
                 + inlined_size(actuator.advance if exact_actuator else actuator.rhs))
    once = 0
    for stage in stages:
        each, one = stage.code_size(model, jit)
        per_stage, once = per_stage + each, once + one
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
    stages: tuple[Stage, ...] = (),
    stage_loop: bool | None = None,
    exact_actuator: bool | None = None,
    jit: bool = True,
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
    stages : tuple of Stage
        The loop's stages, in order (:mod:`seahelm.simulation.stage`, the registry
        :data:`seahelm.simulation.stages.STAGES`): e.g. the environment's loads from the live
        state (:class:`~seahelm.simulation.environment_stage.EnvironmentStage`), the
        first-order wave motions (:class:`~seahelm.simulation.wave_motion_stage.FirstOrderStage`).
        Each adds its lines to the loop's hooks; a loop without stages has none.
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
        binding(model.rhs, "model_rhs", jit=jit),
        binding(model.output, "model_output", jit=jit),
        binding(actuator.rhs, "actuator_rhs", jit=jit),
        binding(actuator.output, "actuator_output", jit=jit),
        binding(controller.init, "controller_init", jit=jit),
        binding(controller.step, "controller_step", jit=jit),
    ]
    if exact_actuator:
        parts.append(binding(actuator.advance, "actuator_advance", jit=jit))
    # the stages' lines, each after the outputs of the model and of the stages before it
    measurement_from, n_out, codes = tuple(wiring.measurement_from), model.n_outputs, []
    for stage in stages:
        code = stage.code(model, controller, measurement_from, n_out, jit)
        codes.append(code)
        parts += code.bindings
        measurement_from = code.measurement_from or measurement_from
        n_out += len(stage.outputs(model)[0])
    hooks, disturbance = hooks_source(codes)
    header = ("" if jit else PYTHON_HEADER) + "".join(p[0] for p in parts) + (
        f"\nNX = {model.n_states}\nNA = {actuator.n_states}\nNU = {model.n_inputs}\n"
        f"NYM = {n_out}\n"
        f"NYA = {len(wiring.actuator_outputs)}\n"
        f"NCA = {len(wiring.actuator_commands)}\nNM = {controller.n_measurements}\n"
        f"NDM = {model.n_disturbances}\n"
        f"EXACT_ACTUATOR = {bool(exact_actuator)}\n"
        "FASTMATH = {" + ", ".join(f'"{flag}"' for flag in LOOP_FASTMATH) + "}\n"
    )
    header += _route_source("route_actuator_commands", "cmd, ca", [
        f"ca[{j}] = cmd[{k}]" for j, k in enumerate(wiring.actuator_command_from)])
    header += _route_source("route_inputs", "ya, cmd, u", [
        f"u[{i}] = {'ya' if kind == 'actuator' else 'cmd'}[{j}]"
        for i, (kind, j) in enumerate(wiring.input_from)])
    header += _route_source("route_measurements", "ym, y", [
        f"y[{i}] = ym[{j}]" for i, j in enumerate(measurement_from)])
    header += hooks + _CLOSED_RHS.format(disturbance=disturbance)
    if stage_loop is None:
        stage_loop = _stage_code_size(model, actuator, tableau, stages,
                                      exact_actuator, jit) > STAGE_LOOP_ABOVE
    footer = (compiled_stage_loop_source if stage_loop else compiled_advance_source)(
        tableau, exact_actuator)
    blocks = iter([header, footer])
    text = _BLOCK.sub(lambda m: next(blocks), _TEMPLATE_TEXT)
    digest = content_digest(text, __version__, *(p[1] for p in parts))
    if not jit:
        return exec_generated(f"seahelm_python_loop_{digest}", text)
    return import_generated(f"seahelm_kernel_{digest}", text)


#: The closed loop's right-hand side at one stage of the integrator: the actuator's outputs
#: routed to the model's inputs, the stages' ``rhs`` lines (the environment's loads), the
#: model's right-hand side on the disturbance they leave, the actuator's.
_CLOSED_RHS = """

@njit(inline="always", fastmath=FASTMATH, _nrt=False)
def closed_rhs(t, xv, xa, cmd, ca, d, mp, ap, ir, sg, ss, ya, u, dxv, dxa):  # pragma: no cover
    actuator_output(xa, ca, ap, ya)
    route_inputs(ya, cmd, u)
    stages_rhs(t, ir, xv, u, mp, d, sg, ss)
    model_rhs(t, xv, u, {disturbance}, mp, dxv)
    if not EXACT_ACTUATOR:  # else the step takes the actuator states from actuator_advance
        actuator_rhs(t, xa, ca, ap, dxa)
"""
