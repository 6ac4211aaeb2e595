"""DP with a wave-filtering observer: Fossen & Strand's passive nonlinear observer feeding the
``dp-pid`` control law.

The controller ``dp-pid-observer`` measures position and heading only (``north``, ``east``,
``heading``: with first-order wave motion and noise on them, what a DP system's sensors give)
and controls on the observer's low-frequency estimates η̂, ν̂, so that the thrusters do not
chase the waves; it records ``dp-pid``'s outputs and η̂ (``estimated_north`` [m],
``estimated_east`` [m], ``estimated_heading`` [rad], after the step's update). In a
simulation, the sensor stage (:mod:`seahelm.simulation.sensor_stage`, ``Problem(sensors=...)``)
gives it the measurements with the first-order motions and noise. The observer (Fossen & Strand 1999, "Passive nonlinear observer design for
ships using Lyapunov methods: full-scale experiments with a supply vessel", *Automatica*
35(1), 3–16; Fossen 2021, *Handbook of Marine Craft Hydrodynamics and Motion Control*, 2nd ed.,
§13.4.2), per DOF i of η = (x_N, y_E, ψ)::

    ỹ = y − η̂ − ξ₂                                   (ψ̃ wrapped)
    ξ̇₁ = ξ₂ + K₁ₐ ỹ,   ξ̇₂ = −ω₀² ξ₁ − 2λω₀ ξ₂ + K₁ᵦ ỹ     (wave model, C_w = [0 1])
    η̂̇ = R(y_ψ) ν̂ + K₂ ỹ
    b̂̇ = −b̂/T_b + K₃ ỹ
    M ν̂̇ = −D ν̂ + Rᵀ(y_ψ) b̂ + τ + Rᵀ(y_ψ) K₄ ỹ

with the gains of Fossen (2021) §13.4.2: K₁ₐ = −2(ζ_n − λ) ω_c/ω₀, K₁ᵦ = 2ω₀(ζ_n − λ),
K₂ = ω_c (a notch at ω₀ and a low-pass at ω_c), and K₄ = κ₄ M_d, K₃ = r K₄ within the passivity
ordering 1/T_b ≪ K₃/K₄ < ω₀ < ω_c (Fossen & Strand 1999). M_d, D_d are the design model's
diagonals (as the control law's), τ the thrust the controller applied over the last step.
The observer is integrated by forward Euler in ``observer_substeps`` steps per control step.
The defaults (ω₀ = 0.8 rad/s, a peak period of 7.9 s; λ = 0.1, ζ_n = 1, ω_c = 1.1 ω₀,
κ₄ = 0.1 1/s², r = 0.1 1/s, T_b = 1000 s) are seahelm's choices within that ordering, not
published values.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

from ..parameters import param, signal_indices
from .base import Controller, wrap_pi
from .dp_pid import (_AZ0, COMMANDS, DP_PID, OUTPUTS, REFERENCES, STATES, DpPidParams,
                     dp_control, state_indices)

__all__ = ["DpObserverParams", "DP_PID_OBSERVER", "observer_update"]

MEASUREMENTS: tuple[str, ...] = ("north", "east", "heading")
#: Recorded outputs: ``dp-pid``'s, then the observer's low-frequency estimates η̂.
OBSERVER_OUTPUTS: tuple[str, ...] = OUTPUTS + ("estimated_north", "estimated_east",
                                               "estimated_heading")
_EST0 = len(COMMANDS) + len(OUTPUTS)
_M = signal_indices(MEASUREMENTS)
#: The states the observer reads by name (:func:`~seahelm.control.dp_pid.state_indices`).
_S = state_indices(("desired_north", "desired_east", "desired_heading", "estimated_north",
                    "estimated_east", "estimated_heading", "wave_north", "wave_east",
                    "wave_heading", "bias_x", "bias_y", "bias_n", "estimated_surge_speed",
                    "estimated_sway_speed", "estimated_yaw_rate", "applied_surge",
                    "applied_sway", "applied_yaw"))
_C = signal_indices(COMMANDS)
_XI = STATES.index("wave_state_north")


@dataclass(frozen=True, kw_only=True)
class DpObserverParams(DpPidParams):
    """:class:`DpPidParams` and the passive observer's (see the module)."""

    wave_frequency: float = param(0.8, unit="rad/s", symbol="ω₀", low=0.0, low_inclusive=False,
                                  doc="wave model's peak frequency")
    wave_damping: float = param(0.1, unit="-", symbol="λ", low=0.0, low_inclusive=False,
                                doc="wave model's relative damping")
    notch_damping: float = param(1.0, unit="-", symbol="ζ_n", low=0.0, low_inclusive=False,
                                 doc="notch filter's relative damping (> λ)")
    cutoff_ratio: float = param(1.1, unit="-", symbol="ω_c/ω₀", low=1.0, low_inclusive=False,
                                doc="low-pass cut-off over the wave frequency")
    observer_stiffness: float = param(0.1, unit="1/s²", symbol="κ₄", low=0.0,
                                      low_inclusive=False, doc="K₄ = κ₄ M_d")
    bias_ratio: float = param(0.1, unit="1/s", symbol="r", low=0.0, low_inclusive=False,
                              doc="K₃ = r K₄")
    bias_time_constant: float = param(1000.0, unit="s", symbol="T_b", low=0.0,
                                      low_inclusive=False, doc="bias time constant")
    observer_substeps: float = param(20.0, unit="-", low=1.0, high=1000.0,
                                     doc="Euler steps of the observer per control step")


@njit(cache=True)
def observer_update(dt, yn, ye, ypsi, p, cs):  # pragma: no cover - compiled
    """Integrate the observer over one control step (forward Euler, ``observer_substeps``)
    with the measurement (yn, ye, ypsi) and the thrust applied over the step (held)."""
    w0 = p.wave_frequency
    lam = p.wave_damping
    dz = p.notch_damping - lam
    wc = p.cutoff_ratio * w0
    k1a = -2.0 * dz * wc / w0
    k1b = 2.0 * w0 * dz
    k4x, k4y, k4n = (p.observer_stiffness * p.mass_surge, p.observer_stiffness * p.mass_sway,
                     p.observer_stiffness * p.inertia_yaw)
    r = p.bias_ratio
    tb = p.bias_time_constant
    c, s = math.cos(ypsi), math.sin(ypsi)
    nsub = int(p.observer_substeps)
    h = dt / nsub
    tx, ty, tn = cs[_S.applied_surge], cs[_S.applied_sway], cs[_S.applied_yaw]
    for _ in range(nsub):
        e0 = yn - cs[_S.estimated_north] - cs[_S.wave_north]
        e1 = ye - cs[_S.estimated_east] - cs[_S.wave_east]
        e2 = wrap_pi(ypsi - cs[_S.estimated_heading] - cs[_S.wave_heading])
        u, v, rr = (cs[_S.estimated_surge_speed], cs[_S.estimated_sway_speed],
                    cs[_S.estimated_yaw_rate])
        # wave model (ξ₁, ξ₂) per DOF
        for k, e in ((0, e0), (2, e1), (4, e2)):
            x1 = cs[_XI + k]
            x2 = cs[_XI + k + 1]
            cs[_XI + k] = x1 + h * (x2 + k1a * e)
            cs[_XI + k + 1] = x2 + h * (-w0 * w0 * x1 - 2.0 * lam * w0 * x2 + k1b * e)
        cs[_S.estimated_north] += h * (c * u - s * v + wc * e0)
        cs[_S.estimated_east] += h * (s * u + c * v + wc * e1)
        cs[_S.estimated_heading] += h * (rr + wc * e2)
        bx, by, bn = cs[_S.bias_x], cs[_S.bias_y], cs[_S.bias_n]
        cs[_S.bias_x] = bx + h * (-bx / tb + r * k4x * e0)
        cs[_S.bias_y] = by + h * (-by / tb + r * k4y * e1)
        cs[_S.bias_n] = bn + h * (-bn / tb + r * k4n * e2)
        # M ν̂̇ = −D ν̂ + Rᵀ b̂ + τ + Rᵀ K₄ ỹ (diagonal design model)
        fx = -p.damping_surge * u + c * bx + s * by + tx + c * k4x * e0 + s * k4y * e1
        fy = -p.damping_sway * v - s * bx + c * by + ty - s * k4x * e0 + c * k4y * e1
        fn = -p.damping_yaw * rr + bn + tn + k4n * e2
        cs[_S.estimated_surge_speed] = u + h * fx / p.mass_surge
        cs[_S.estimated_sway_speed] = v + h * fy / p.mass_sway
        cs[_S.estimated_yaw_rate] = rr + h * fn / p.inertia_yaw


@njit(cache=True)
def dp_observer_init(z, y, ref, p, cs):  # pragma: no cover - compiled
    for k in range(cs.shape[0]):
        cs[k] = 0.0
    cs[_S.desired_north] = y[_M.north]
    cs[_S.desired_east] = y[_M.east]
    cs[_S.desired_heading] = y[_M.heading]
    cs[_S.estimated_north] = y[_M.north]
    cs[_S.estimated_east] = y[_M.east]
    cs[_S.estimated_heading] = y[_M.heading]
    for i in range(8):
        cs[_AZ0 + i] = p.thruster_direction[i]


@njit(cache=True)
def dp_observer_step(t, dt, z, y, ref, p, cs, cmd):  # pragma: no cover - compiled
    if t > 0.0:
        observer_update(dt, y[_M.north], y[_M.east], y[_M.heading], p, cs)
    dp_control(dt, cs[_S.estimated_north], cs[_S.estimated_east], cs[_S.estimated_heading],
               cs[_S.estimated_surge_speed], cs[_S.estimated_sway_speed],
               cs[_S.estimated_yaw_rate], ref, p, cs, cmd)
    cs[_S.applied_surge] = cmd[_C.thrust_surge]
    cs[_S.applied_sway] = cmd[_C.thrust_sway]
    cs[_S.applied_yaw] = cmd[_C.thrust_yaw]
    cmd[_EST0] = cs[_S.estimated_north]
    cmd[_EST0 + 1] = cs[_S.estimated_east]
    cmd[_EST0 + 2] = cs[_S.estimated_heading]


DP_PID_OBSERVER = Controller(
    name="dp-pid-observer",
    description="DP: dp-pid on the estimates of Fossen & Strand's (1999) passive wave-filtering "
    "observer, measuring position and heading only",
    params_type=DpObserverParams,
    state_labels=STATES,
    state_units=DP_PID.state_units,
    reference_labels=REFERENCES,
    reference_units=DP_PID.reference_units,
    command_labels=COMMANDS,
    command_units=DP_PID.command_units,
    init=dp_observer_init,
    step=dp_observer_step,
    measurement_labels=MEASUREMENTS,
    output_labels=OBSERVER_OUTPUTS,
    output_units=DP_PID.output_units + ("m", "m", "rad"),
)
