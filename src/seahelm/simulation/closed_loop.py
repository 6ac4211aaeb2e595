"""Generation of the compiled closed loop: one module per combination of components.

:func:`compile_closed_loop` writes :mod:`seahelm.simulation.kernel_template`'s text with the
components' numba functions bound in (:func:`_binding`), the routing of signals by name from
:func:`~seahelm.simulation.composition.compose` and the integrator's step from its Butcher
tableau, and imports it from the kernel cache (numba compiles it once per machine). The engine
(:mod:`seahelm.simulation.engine`) and the stepping simulator
(:mod:`seahelm.simulation.stepping`) run what it returns.
"""

from __future__ import annotations

import functools
import hashlib
import re
import sys
from pathlib import Path
from types import FunctionType, ModuleType
from typing import Any

from .. import __version__
from ..actuators.base import Actuator
from ..control.base import Controller
from ..environment.first_order_kernel import first_order_sample
from ..vessels.base import VesselModel
from .compiled_step import compiled_advance_source, compiled_stage_loop_source
from .composition import compose
from .environment_stage import (
    environment_stage,
    no_apply_loads,
    no_environment_loads,
    python_environment_stage,
)
from .generated import code_fingerprint, exec_generated, import_generated
from .inlining import inlined_size
from .integrators import ButcherTableau, get_integrator
from .problem import _numba_jit_disabled
from .wave_motion_stage import wave_constants

__all__ = ["compile_closed_loop", "STAGE_LOOP_ABOVE", "PYTHON_HEADER"]


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

