"""The first-order wave motions' stage of the compiled closed loop: which outputs it reads and
writes, and what the controller measures.

The stage (:class:`FirstOrderStage`, :mod:`seahelm.simulation.stage`) evaluates, at every
recorded step and every controller sample, run i's first-order motions
(:mod:`seahelm.environment.first_order_in_loop`) with the post-pass's own per-sample code
(:func:`~seahelm.environment.first_order_kernel.first_order_sample`) from the model's outputs
``north``, ``east``, ``heading`` and ``surge_speed``, and writes them into the outputs after the
model's and the environment's: η_j (``heave``, ``roll_wave``, ``pitch``, ``yaw_wave``, …), then
``heading_total`` = ψ + ψ₁ with yaw, then ``roll`` = the model's ``roll_angle`` + the first-order
roll on a model with roll. :func:`wave_constants` resolves those indices by name, once, as
literals of the generated lines; with ``autopilot_sees_first_order`` the controller's
``heading`` measurement is routed from ``heading_total``. The stage does not act on the
dynamics (it runs outside the integrator's stages), so with the controller reading the model's
heading the states are bit-for-bit those of a loop without it. Its per-run arrays are the
drawn components and the RAO tables (:attr:`FirstOrderInLoop.arrays`), its scratch cos θ_i,
sin θ_i, heading cells and weights over the components and the responses.
"""

from __future__ import annotations

import dataclasses
import json
from typing import Any

import numpy as np

from ..control.base import Controller
from ..environment.first_order_in_loop import HEADING_TOTAL, MOTION_INPUTS, output_signals
from ..environment.first_order_kernel import first_order_sample
from ..errors import ParameterError
from ..vessels.base import VesselModel
from .stage import Stage, StageCode, aligned_buffers, binding

__all__ = ["wave_constants", "FirstOrderStage"]


def wave_constants(model: VesselModel, controller: Controller, measurement_from: tuple[int, ...],
                    n_env: int, first_order: tuple[tuple[str, ...], bool]) -> dict[str, Any]:
    """The kernel's constants of the first-order stage and the controller's measurements.

    Parameters
    ----------
    model : VesselModel
        The model (its outputs ``north``, ``east``, ``heading``, ``surge_speed`` and, if it
        rolls, ``roll_angle``).
    controller : Controller
        The controller.
    measurement_from : tuple of int
        For each of its measurements, the model output it reads (the composition's).
    n_env : int
        Number of the environment's outputs (after the model's in ``ym``).
    first_order : (tuple of str, bool)
        The DOF evaluated and whether the controller sees ψ + ψ₁.

    Returns
    -------
    dict
        ``NWD`` (DOF), ``NW_OUT`` (outputs written), the ``ym`` indices
        ``WAVE_X``, ``WAVE_Y``, ``WAVE_PSI``, ``WAVE_U``, ``WAVE_OUT0``, ``WAVE_ROLL_MODEL``,
        the DOF indices ``WAVE_YAW``, ``WAVE_ROLL`` (−1: none), and ``measurement_from`` (the
        controller's ``heading`` from ``heading_total`` if it sees it).

    Raises
    ------
    ParameterError
        If the model lacks an output the motions are evaluated from, or the controller that
        is to see ψ + ψ₁ measures no ``heading``.
    """
    meas = list(measurement_from)
    dofs, sees = first_order  # (the stage exists only with the motions: no loop without them)
    outs = model.output_labels
    missing = [n for n in MOTION_INPUTS if n not in outs]
    if missing:
        raise ParameterError(
            f": model '{model.name}' does not output {', '.join(missing)}, which the "
            f"first-order motions are evaluated from (outputs: {', '.join(outs)})",
            field="first_order")
    labels, _ = output_signals(dofs, "roll_angle" in outs)
    base = model.n_outputs + n_env
    if sees:
        if "heading" not in controller.measurement_labels:
            raise ParameterError(
                f".autopilot_sees_first_order: controller '{controller.name}' does not measure "
                "`heading`", field="first_order", value=True)
        meas[controller.measurement_labels.index("heading")] = base + labels.index(
            HEADING_TOTAL)
    return {"NWD": len(dofs), "NW_OUT": len(labels),
            "WAVE_X": outs.index("north"), "WAVE_Y": outs.index("east"),
            "WAVE_PSI": outs.index("heading"), "WAVE_U": outs.index("surge_speed"),
            "WAVE_OUT0": base, "WAVE_YAW": dofs.index("yaw") if "yaw" in dofs else -1,
            "WAVE_ROLL": dofs.index("roll") if "roll" in dofs else -1,
            "WAVE_ROLL_MODEL": (outs.index("roll_angle") if "roll" in labels else -1),
            "measurement_from": meas}


@dataclasses.dataclass(frozen=True)
class FirstOrderStage(Stage):
    """The first-order wave motions in the loop as a stage (module docstring).

    Attributes
    ----------
    dofs : tuple of str
        The degrees of freedom evaluated.
    autopilot_sees_first_order : bool
        The controller's ``heading`` is ψ + ψ₁.
    """

    dofs: tuple[str, ...]
    autopilot_sees_first_order: bool
    name = "first_order"
    members = ("components", "tables", "same_speed", "speeds", "speed_step")

    @classmethod
    def from_problem(cls, problem: Any) -> "FirstOrderStage | None":
        """The stage a problem asks for, or None (the loop then runs without it).

        Parameters
        ----------
        problem : Problem
            The problem the loop is built for.
        """
        fo = problem.first_order
        return None if fo is None else cls(tuple(fo.dofs), bool(fo.autopilot_sees_first_order))

    def outputs(self, model: Any) -> tuple[tuple[str, ...], tuple[str, ...]]:
        return output_signals(self.dofs, "roll_angle" in model.output_labels)

    def code(self, model: Any, controller: Any, measurement_from: tuple[int, ...],
             first_output: int, jit: bool) -> StageCode:
        w = wave_constants(model, controller, measurement_from, first_output - model.n_outputs,
                           (self.dofs, self.autopilot_sees_first_order))
        x, y, psi, us, out0 = w["WAVE_X"], w["WAVE_Y"], w["WAVE_PSI"], w["WAVE_U"], w["WAVE_OUT0"]
        lines = [f"first_order_sample(t, ym[{x}], ym[{y}], ym[{psi}], ym[{us}], "
                 + ", ".join(f"g[0][i, {c}]" for c in range(6))
                 + ", g[1][i, 0], g[1][i, 1], g[4][0], g[3], g[2][i] != 0.0, s[0], s[1], s[2], "
                   "s[3], s[4])"]
        lines += [f"ym[{out0 + j}] = s[4][{j}]" for j in range(w["NWD"])]
        o = out0 + w["NWD"]
        if w["WAVE_YAW"] >= 0:  # ψ + ψ₁
            lines.append(f"ym[{o}] = ym[{psi}] + s[4][{w['WAVE_YAW']}]")
            o += 1
        if w["WAVE_ROLL_MODEL"] >= 0:  # the model's roll + the first-order roll
            lines.append(f"ym[{o}] = ym[{w['WAVE_ROLL_MODEL']}] + s[4][{w['WAVE_ROLL']}]")
        return StageCode(bindings=(binding(first_order_sample, "first_order_sample", jit=jit),),
                         lines={"outputs": tuple(lines)},
                         measurement_from=tuple(w["measurement_from"]))

    def inputs(self, problem: Any, model: Any) -> Any:
        return problem.first_order

    def run_counts(self, inputs: Any) -> tuple[tuple[str, int], ...]:
        return (("first_order", inputs.n_runs),)

    def arrays(self, inputs: Any, n_runs: int) -> tuple[np.ndarray, ...]:
        if inputs.n_runs != n_runs:
            raise ParameterError(f": the first-order motions were drawn for {inputs.n_runs} "
                                 f"run(s), the batch has {n_runs}", field="first_order")
        return tuple(inputs.arrays)

    def scratch(self, model: Any, arrays: tuple[np.ndarray, ...],
                n_outputs: int) -> tuple[np.ndarray, ...]:
        # cos θ_i, sin θ_i, heading cells and weights over the m components (exactly m long:
        # the sums run over their length), the responses of the DOF
        m, ndof = arrays[0].shape[2], arrays[1].shape[3]
        return aligned_buffers([(m,), (m,), (m,), (m,), (max(ndof, 1),)],
                               [np.float64, np.float64, np.int64, np.float64, np.float64])

    def metadata(self, problem: Any) -> dict[str, Any]:
        out = {"first_order_in_loop": ", ".join(self.dofs)
               + " (seahelm.environment.first_order_in_loop)",
               "controller_heading": (f"{HEADING_TOTAL} (heading + first-order yaw)"
                                      if self.autopilot_sees_first_order else "heading")}
        settings = getattr(problem.first_order, "settings", ())
        if settings:  # (the typed settings' form in a result file)
            out["first_order_settings"] = json.dumps([s.as_dict() for s in settings])
        return out
