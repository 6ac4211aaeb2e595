"""The first-order wave motions' stage of the compiled closed loop: which outputs it reads and
writes, and what the controller measures.

The kernel (:mod:`seahelm.simulation.kernel_template`, ``wave_stage``) evaluates, at every
recorded step and every controller sample, run i's first-order motions
(:mod:`seahelm.environment.first_order_in_loop`) with the post-pass's own per-sample code
(:func:`~seahelm.environment.first_order_kernel.first_order_sample`) from the model's outputs
``north``, ``east``, ``heading`` and ``surge_speed``, and writes them into the outputs after the
model's and the environment's: η_j (``heave``, ``roll_wave``, ``pitch``, ``yaw_wave``, …), then
``heading_total`` = ψ + ψ₁ with yaw, then ``roll`` = the model's ``roll_angle`` + the first-order
roll on a model with roll. :func:`wave_constants` resolves those indices by name, once, as
compile-time constants of the generated loop; with ``autopilot_sees_first_order`` the
controller's ``heading`` measurement is routed from ``heading_total``. The stage does not act
on the dynamics (it runs outside the integrator's stages), so with the controller reading the
model's heading the states are bit-for-bit those of a loop without it.
"""

from __future__ import annotations

from typing import Any

from ..control.base import Controller
from ..environment.first_order_in_loop import HEADING_TOTAL, MOTION_INPUTS, output_signals
from ..errors import ParameterError
from ..vessels.base import VesselModel

__all__ = ["wave_constants"]


def wave_constants(model: VesselModel, controller: Controller, measurement_from: tuple[int, ...],
                    n_env: int, first_order: tuple[tuple[str, ...], bool] | None
                    ) -> dict[str, Any]:
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
    first_order : (tuple of str, bool) or None
        The DOF evaluated and whether the controller sees ψ + ψ₁.

    Returns
    -------
    dict
        ``HAS_WAVES``, ``NWD`` (DOF), ``NW_OUT`` (outputs written), the ``ym`` indices
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
    if first_order is None:
        return {"HAS_WAVES": False, "NWD": 0, "NW_OUT": 0, "WAVE_X": 0, "WAVE_Y": 0,
                "WAVE_PSI": 0, "WAVE_U": 0, "WAVE_OUT0": 0, "WAVE_YAW": -1, "WAVE_ROLL": -1,
                "WAVE_ROLL_MODEL": -1, "measurement_from": meas}
    dofs, sees = first_order
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
    return {"HAS_WAVES": True, "NWD": len(dofs), "NW_OUT": len(labels),
            "WAVE_X": outs.index("north"), "WAVE_Y": outs.index("east"),
            "WAVE_PSI": outs.index("heading"), "WAVE_U": outs.index("surge_speed"),
            "WAVE_OUT0": base, "WAVE_YAW": dofs.index("yaw") if "yaw" in dofs else -1,
            "WAVE_ROLL": dofs.index("roll") if "roll" in dofs else -1,
            "WAVE_ROLL_MODEL": (outs.index("roll_angle") if "roll" in labels else -1),
            "measurement_from": meas}
