"""The environment's stage of the compiled closed loop: loads from the live state, by name.

:func:`environment_stage` writes, for one :class:`~seahelm.environment.loads.Environment` and
one vessel model, the compiled function the kernel calls before the model's right-hand side at
every stage (and at every recorded or measured step, for its outputs)::

    environment_loads(t, x, u, p, ym, d, ep, lm)     the loads (X, Y, N) into lm
    apply_loads(d, lm, dm)                           dm = d + the loads on the load channels

(by default both at every stage of the integrator; an environment built with
``hold_over_step=True`` evaluates the loads once per step, at its start, and applies them at
every stage — cheaper, first-order in how the loads follow the state within a step).

``x``, ``u``, ``p`` are the model's state, inputs and parameters; the heading and the velocity
through the water come from the model's ``motion(x, p)`` if it declares one (cheap: a few
states), else from its outputs ``heading``, ``surge_speed``, ``sway_speed`` (``output`` is then
evaluated into ``ym``). ``ym`` holds the model's outputs followed by the environment's outputs
(written here), ``d`` the
run's disturbance inputs (the model's channels, then the environment's signals ``wind_gust``,
``wave_load_fluctuation``), ``ep`` the environment's parameter record, and ``dm`` receives
the model's disturbance channels: what was given plus the loads on ``force_x``, ``force_y``
[N] and ``moment_z`` [N·m] (a constant-speed model without ``force_x`` takes no surge load). The velocity over ground for the relative wind adds the current of
the model's ``current_north``/``current_east`` channels, if it has them.

Wind loads are those **of the true wind**: the loads of the relative wind minus those of the
still air the ship moves through (its own air drag, which a calm-water model identified from
trials contains, and which is small beside the hull's). So zero wind leaves a calm-water run
exactly as it is, and a wind of speed W adds what W adds. The recorded ``apparent_wind_speed``
and ``apparent_wind_angle`` are the full relative wind.

The indices are resolved here, once, by name; a model without the channels or outputs the
environment needs is a :class:`~seahelm.errors.ParameterError` naming what is missing.
:class:`EnvironmentStage` is this stage of the loop (:mod:`seahelm.simulation.stage`): its
outputs, the signals it reads, its per-run arrays (the environment's parameter records), its
scratch and its lines at each place of the step. A loop without an environment has none of it.
"""

from __future__ import annotations

import dataclasses
import functools
from typing import Any

import numpy as np

from ..errors import ParameterError
from .inlining import inlined_size, py_func_of
from .inputs import _param_rows
from .stage import Stage, StageCode, aligned_buffers, binding

__all__ = ["EnvironmentStage", "environment_stage", "python_environment_stage",
           "check_environment", "LOAD_CHANNELS", "MOTION_OUTPUTS"]

#: The model disturbance channels the environment's loads go to, with their units.
LOAD_CHANNELS: dict[str, str] = {"force_x": "N", "force_y": "N", "moment_z": "N·m"}
#: The model outputs the environment reads (velocity through the water, heading).
MOTION_OUTPUTS: dict[str, str] = {"heading": "rad", "surge_speed": "m/s", "sway_speed": "m/s"}


def _module_name(func: Any) -> tuple[str, str]:
    py = py_func_of(func)
    return py.__module__, py.__name__


def check_environment(environment: Any, model: Any) -> None:
    """Raise a :class:`ParameterError` if ``model`` lacks what ``environment`` needs.

    Parameters
    ----------
    environment : Environment
    model : VesselModel
    """
    where = f"environment ({environment.name}) on model '{model.name}'"
    for name, unit in MOTION_OUTPUTS.items():
        if name not in model.output_labels:
            raise ParameterError(
                f"{where}: the model does not output '{name}' [{unit}], which the loads need "
                f"(outputs: {', '.join(model.output_labels)})")
    for name, unit in LOAD_CHANNELS.items():
        if name == "force_x" and name not in model.disturbance_labels:
            continue  # a constant-speed model takes no surge load
        if name not in model.disturbance_labels:
            raise ParameterError(
                f"{where}: the model has no disturbance channel '{name}' [{unit}] for the "
                f"loads (channels: {', '.join(model.disturbance_labels) or 'none'})")
        got = model.disturbance_units[model.disturbance_labels.index(name)]
        if got != unit:
            raise ParameterError(f"{where}: channel '{name}' is in [{got}], the loads in [{unit}]")
    clash = set(environment.signal_labels) & set(model.disturbance_labels)
    clash |= set(environment.output_labels) & set(model.output_labels)
    if clash:
        raise ParameterError(f"{where}: signal names used by both: {', '.join(sorted(clash))}")


@functools.lru_cache(maxsize=None)
def environment_stage(environment: Any, model: Any) -> Any:
    """The compiled stage of ``environment`` acting on ``model`` (module docstring).

    Parameters
    ----------
    environment : Environment
    model : VesselModel

    Returns
    -------
    tuple of numba dispatchers
        ``environment_loads(t, x, u, p, ym, d, ep, lm)`` (the body-axis loads into ``lm[0:3]``,
        the environment's outputs into ``ym``) and ``apply_loads(d, lm, dm)`` (``dm`` = ``d``
        with the loads added on the model's load channels).

    Raises
    ------
    ParameterError
        If the model lacks an output or a channel the loads need.
    """
    from .._codegen import import_generated

    source, digest = _stage_source(environment, model, "from numba import njit")
    module = import_generated(f"seahelm_environment_{digest}", source)
    return module.environment_loads, module.apply_loads


@functools.lru_cache(maxsize=None)
def python_environment_stage(environment: Any, model: Any) -> Any:
    """:func:`environment_stage` as plain Python, for the pure-Python closed loop.

    The same generated source with ``njit`` left out (:func:`~seahelm.simulation.inlining.no_jit`),
    run in memory (:func:`~seahelm.simulation.generated.exec_generated`): nothing is written to
    the kernel cache and nothing is compiled. The functions it returns still name the wind and
    wave loads' numba functions; the closed loop calls them through
    :func:`~seahelm.simulation.inlining.python_function`, which puts the Python ones in their
    place.

    Parameters
    ----------
    environment : Environment
    model : VesselModel

    Returns
    -------
    tuple of functions
        ``environment_loads`` and ``apply_loads``, as :func:`environment_stage`'s.

    Raises
    ------
    ParameterError
        If the model lacks an output or a channel the loads need.
    """
    from .._codegen import exec_generated

    source, digest = _stage_source(
        environment, model, "from seahelm.simulation.inlining import no_jit as njit")
    module = exec_generated(f"seahelm_python_environment_{digest}", source)
    return module.environment_loads, module.apply_loads


def _stage_source(environment: Any, model: Any, njit_import: str) -> tuple[str, str]:
    """The stage's module source (``njit_import`` binds ``njit``) and a digest of it and of
    the code it calls."""
    from .._codegen import code_fingerprint, content_digest

    check_environment(environment, model)
    out, dist = model.output_labels, model.disturbance_labels
    ndm, nym = len(dist), len(out)
    sig = {name: ndm + j for j, name in enumerate(environment.signal_labels)}
    eout = {name: nym + j for j, name in enumerate(environment.output_labels)}
    imports, body = [], []

    funcs = []
    if model.motion is not None:
        mod, name = _module_name(model.motion)
        imports.append(f"from {mod} import {name} as model_motion")
        funcs.append(model.motion)
        body += ["    us, vs, psi = model_motion(x, p)  # through the water"]
    else:
        mod, name = _module_name(model.output)
        imports.append(f"from {mod} import {name} as model_output")
        funcs.append(model.output)
        body += [
            "    model_output(t, x, u, p, ym)",
            f"    psi = ym[{out.index('heading')}]",
            f"    us = ym[{out.index('surge_speed')}]",
            f"    vs = ym[{out.index('sway_speed')}]",
        ]
    cn = f"d[{dist.index('current_north')}]" if "current_north" in dist else ""
    ce = f"d[{dist.index('current_east')}]" if "current_east" in dist else ""
    body += [
        "    c = math.cos(psi)",
        "    s = math.sin(psi)",
        "    fx = 0.0",
        "    fy = 0.0",
        "    mz = 0.0",
    ]
    if environment.wind is not None:
        mod, name = _module_name(environment.wind.loads)
        imports.append(f"from {mod} import {name} as wind_loads")
        funcs.append(environment.wind.loads)
        # the ship's velocity over ground in body axes: through the water plus the current
        over = ["    ub = us", "    vb = vs"] if not (cn or ce) else [
            f"    ub = us + ({cn or '0.0'} * c + {ce or '0.0'} * s)",
            f"    vb = vs + ({ce or '0.0'} * c - {cn or '0.0'} * s)"]
        body += [
            "    # the air's velocity relative to the ship, body axes: the wind's (it blows",
            "    # towards the opposite of where it comes from) minus the ship's over ground",
            f"    w = ep.wind_speed + d[{sig['wind_gust']}]",
            *over,
            "    an = -w * ep.wind_from_cos",
            "    ae = -w * ep.wind_from_sin",
            "    ax = an * c + ae * s - ub",
            "    ay = ae * c - an * s - vb",
            "    speed = math.sqrt(ax * ax + ay * ay)",
            "    angle = math.atan2(-ay, -ax)  # the bearing it comes from, off the bow",
            "    if w != 0.0:",
            "        if speed > 0.0:",
            "            x, y, n = wind_loads(ep, speed, angle, -ax / speed, -ay / speed)",
            "        else:",
            "            x, y, n = wind_loads(ep, speed, angle, 1.0, 0.0)",
            "        # minus the still air the ship moves through: the loads of the true wind",
            "        still = math.sqrt(ub * ub + vb * vb)",
            "        if still > 0.0:",
            "            x0, y0, n0 = wind_loads(ep, still, math.atan2(vb, ub), ub / still,",
            "                                    vb / still)",
            "            x -= x0",
            "            y -= y0",
            "            n -= n0",
            "    else:  # (exactly zero: no round-off of two equal evaluations)",
            "        x = 0.0",
            "        y = 0.0",
            "        n = 0.0",
            f"    ym[{eout['apparent_wind_speed']}] = speed",
            f"    ym[{eout['apparent_wind_angle']}] = angle",
            f"    ym[{eout['wind_force_x']}] = x",
            f"    ym[{eout['wind_force_y']}] = y",
            f"    ym[{eout['wind_moment_z']}] = n",
            "    fx += x",
            "    fy += y",
            "    mz += n",
        ]
    if environment.waves is not None:
        mod, name = _module_name(environment.waves.loads)
        imports.append(f"from {mod} import {name} as wave_loads")
        funcs.append(environment.waves.loads)
        body += [
            "    # the bearing the waves come from, off the bow (q = θ_v − ψ), by its cosine and",
            "    # sine; they run the other way, so the ship's speed along their travel is minus",
            "    # its velocity through the water projected on q",
            "    cq = ep.wave_from_cos * c + ep.wave_from_sin * s",
            "    sq = ep.wave_from_sin * c - ep.wave_from_cos * s",
            "    along = -(us * cq + vs * sq)",
            "    x, y, n = wave_loads(ep, math.atan2(sq, cq), cq, sq, along,",
            f"                         1.0 + d[{sig['wave_load_fluctuation']}])",
            f"    ym[{eout['wave_force_x']}] = x",
            f"    ym[{eout['wave_force_y']}] = y",
            f"    ym[{eout['wave_moment_z']}] = n",
            "    fx += x",
            "    fy += y",
            "    mz += n",
        ]
    body += ["    lm[0] = fx", "    lm[1] = fy", "    lm[2] = mz"]
    apply = [f"    for j in range({ndm}):", "        dm[j] = d[j]"]
    apply += [f"    dm[{dist.index('force_x')}] += lm[0]"] if "force_x" in dist else []
    apply += [f"    dm[{dist.index('force_y')}] += lm[1]",
              f"    dm[{dist.index('moment_z')}] += lm[2]"]
    source = (
        f'"""Generated by seahelm.simulation.environment_stage: {environment.name} on '
        f'{model.name}."""\n'
        f"import math\n\n{njit_import}\n\n" + "\n".join(imports) + "\n\n"
        "\n"
        "@njit(cache=True, _nrt=False, fastmath={'arcp', 'contract', 'afn', 'reassoc'})\n"
        "def environment_loads(t, x, u, p, ym, d, ep, lm):  # pragma: no cover - compiled\n"
        + "\n".join(body) + "\n\n\n"
        "@njit(cache=True)\n"
        "def apply_loads(d, lm, dm):  # pragma: no cover - compiled\n"
        + "\n".join(apply) + "\n")
    digest = content_digest(source, *(code_fingerprint(py_func_of(f)) for f in funcs))
    return source, digest


@dataclasses.dataclass(frozen=True)
class EnvironmentStage(Stage):
    """The environment's loads as a stage of the loop (module docstring).

    Its lines: at every stage of the integrator the loads from the live state
    (``environment_loads``, called: inlined at every site they doubled the loop's compile
    time, 76 s against 31 s for the KVLCC2, and a call costs little beside their
    transcendental functions) added to the model's load channels (``apply_loads``, into its
    buffer ``dm``, which the model's right-hand side reads); with ``hold_over_step`` the loads
    once per step, at its start; after the model's outputs, its own (apparent wind, loads).

    Attributes
    ----------
    environment : Environment
    """

    environment: Any
    name = "environment"
    members = ("params",)

    @classmethod
    def from_problem(cls, problem: Any) -> "EnvironmentStage | None":
        """The stage a problem asks for, or None (the loop then runs without it).

        Parameters
        ----------
        problem : Problem
            The problem the loop is built for.
        """
        return None if problem.environment is None else cls(problem.environment)

    def signals(self) -> tuple[tuple[str, ...], tuple[str, ...]]:
        return self.environment.signal_labels, self.environment.signal_units

    def outputs(self, model: Any) -> tuple[tuple[str, ...], tuple[str, ...]]:
        return self.environment.output_labels, self.environment.output_units

    def _functions(self, model: Any, jit: bool) -> Any:
        return (environment_stage if jit else python_environment_stage)(self.environment, model)

    def code_size(self, model: Any, jit: bool) -> tuple[int, int]:
        loads, apply = self._functions(model, jit)
        return inlined_size(apply), inlined_size(loads)

    def code(self, model: Any, controller: Any, measurement_from: tuple[int, ...],
             first_output: int, jit: bool) -> StageCode:
        loads, apply = self._functions(model, jit)
        live = "environment_loads(t, xv, u, mp, s[0], {d}, g[0][i], s[2])"
        held = bool(getattr(self.environment, "hold_over_step", False))
        return StageCode(
            bindings=(binding(loads, "environment_loads", inline=False, jit=jit),
                      binding(apply, "apply_loads", jit=jit)),
            lines={
                # its outputs (loads, apparent wind) from the disturbance of step k
                "outputs": ("if dist.shape[1] > 1:",
                            "    for j in range(dist.shape[2]):",
                            "        ds[j] = dist[idist, k, j]",
                            "    environment_loads(t, xv, u, mp, ym, ds, g[0][i], s[2])",
                            "else:",
                            "    environment_loads(t, xv, u, mp, ym, d0, g[0][i], s[2])"),
                # the loads of the step's start, held over the step; else at every stage
                **({"step_start": (live.format(d="d0"),)} if held else {}),
                "rhs": (*(() if held else (live.format(d="d"),)), "apply_loads(d, s[2], s[1])"),
            },
            disturbance=1)

    def inputs(self, problem: Any, model: Any) -> Any:
        """The environment's parameter rows and class, checked against the model.

        Parameters
        ----------
        problem : Problem
            The problem the loop is built for.
        model : VesselModel
            The loop's vessel model.
        """
        check_environment(self.environment, model)
        ep, e_cls = _param_rows("environment_params", problem.environment_params,
                                self.environment.params_type)
        mp, m_cls = _param_rows("params", problem.params, model.params_type)
        for name in model.load_params:
            j = m_cls.value_names().index(name)
            bad = ~(mp[:, j] > 0)
            if bad.any():
                raise ParameterError(
                    f": model '{model.name}' needs `{name}` > 0 to take the "
                    f"environment's loads, got {mp[bad, j][0]!r} (run "
                    f"{int(np.argmax(bad))})", field="params", run=int(np.argmax(bad)))
        return ep, e_cls

    def run_counts(self, inputs: Any) -> tuple[tuple[str, int], ...]:
        return (("environment_params", inputs[0].shape[0]),)

    def arrays(self, inputs: Any, n_runs: int) -> tuple[np.ndarray, ...]:
        ep = inputs[0]
        if ep.shape[0] != n_runs:
            ep = np.ascontiguousarray(np.broadcast_to(ep, (n_runs,) + ep.shape[1:]))
        return (self.environment.kernel_records(ep),)  # + per-run constants

    def scratch(self, model: Any, arrays: tuple[np.ndarray, ...],
                n_outputs: int) -> tuple[np.ndarray, ...]:
        # the model's outputs where it has no motion() (then the loads evaluate them), the
        # disturbance with the loads, the loads (X, Y, N)
        return aligned_buffers([(max(n_outputs, 1),), (max(model.n_disturbances, 1),), (3,)])

    def metadata(self, problem: Any) -> dict[str, Any]:
        return {"environment": self.environment.name}

    def result_params(self, inputs: Any, n_runs: int) -> dict[str, Any]:
        ep, e_cls = inputs
        if ep.shape[0] != n_runs:
            ep = np.ascontiguousarray(np.broadcast_to(ep, (n_runs,) + ep.shape[1:]))
        return {"environment": (e_cls, ep)}
