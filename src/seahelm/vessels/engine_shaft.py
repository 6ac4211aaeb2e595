"""Engine, shaft and reversal sequence of a fixed-pitch propeller: the rps as a state.

The shaft speed n [1/s] follows the torque balance of the shaft line (engine, shafting and
propeller with its entrained water)::

    2π I_s ṅ = Q_E − Q_P                                   (Woodward 1975; Fossen 2021, §9.3)

with Q_P the propeller's hydrodynamic torque and Q_E the engine torque, set by the engine
order e ∈ [−1, 1] (``engine_order``: 1 full ahead, 0 stop, −1 full astern). The commanded rps
is n_c = e n_MCR for e ≥ 0 and n_c = |e| n_astern for e < 0 (n_astern < 0, the full-astern rps).

Governor and limits: Q_E = sat(Q_P + 2π I_s (n_c − n)/T_g, ±Q_lim), Q_lim =
min(Q_MCR, P_MCR/(2π |n|)), Q_MCR = P_MCR/(2π n_MCR): a first-order approach to n_c with the
load fed forward, the engine torque limited to the MCR torque below the rated rps and to the
MCR power above it (the engine's constant-torque / constant-power envelope, MAN Energy
Solutions' load diagram simplified to its two limit lines).

Reversal sequence (a slow-speed two-stroke diesel, which is reversed by stopping it and
restarting it the other way with starting air): while the order is opposite to the rotation
(n n_c < 0) a sequence clock τ runs (dτ/dt = 1; it returns to 0 with the governor's time
constant once the order and the rotation agree again, dτ/dt = −τ/T_g):

1. τ < t_d, the ``reversal_delay``: the fuel is cut, Q_E = 0, and the propeller windmills
   (the water torque alone slows the shaft). This is the time of the bridge order, the
   engine-control sequence and the wait until the engine may be braked: on a crash stop the
   fuel is cut at once and the air brake is applied only once the rpm has fallen to about
   20–40 % of full ahead (the automatic crash-astern sequence of bridge-controlled slow-speed
   engines as mariners describe it, Mariner's Voice 2021), and a motor ship is typically reversed about
   3 minutes after the order (Knowledge of Sea, "Crash stop"). The ship defaults take
   t_d = 60 s at full scale, between an immediate air brake and that cautious practice.
   t_d is honoured as a time: nothing reverses the shaft earlier, whatever the speed.
2. τ ≥ t_d and |n| > n_rev, the ``reversal_rps``: starting air is used as a brake, a constant
   torque Q_B = 2π I_s n_MCR / t_rev (``reversal_time``: the time in which the brake alone
   would stop the shaft from the rated rps), the water torque acting on top.
3. τ ≥ t_d and |n| ≤ n_rev: the engine is started in the new direction and the governor takes
   over.

The time from the order to astern rotation is therefore t_d plus the few seconds the brake
needs from the windmilling rps (``reversal_delay`` = 0 gives the immediate brake of a
reversal without the sequence). The numbers are parameters with units; the defaults per ship
are documented where the ship is (:mod:`seahelm.vessels.mmg_four_quadrant`).

The functions here are compiled kernels that read the fields below from the parameter record
(compiled code reads ``p.shaft_inertia``, never an index); a vessel model that carries the rps
as a state includes :class:`EngineShaftParams`' fields in its own parameters.

References
----------
Woodward, J. B. (1975). Low speed marine diesel. Wiley (shaft dynamics and reversal).
Mariner's Voice (2021). Crash stop. marinersvoice.blogspot.com/2021/02 (fuel cut, air brake
below 20–40 % of full-ahead rpm, then astern).
Knowledge of Sea (n.d.). Emergency stop manoeuvre. knowledgeofsea.com/emergency-stop-manoeuvre
(a motor ship reversed about 3 minutes after the order).
Fossen, T. I. (2021). Handbook of Marine Craft Hydrodynamics and Motion Control, 2nd ed.
Wiley, §9.3 (propeller shaft speed models).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

from ..errors import ParameterError
from ..parameters import Params, param

__all__ = ["EngineShaftParams", "commanded_rps", "engine_torque", "shaft_acceleration",
           "reversal_clock_rate"]

_POS = dict(low=0.0, low_inclusive=False)


@dataclass(frozen=True, kw_only=True)
class EngineShaftParams(Params):
    """Engine, shaft line and reversal sequence (module docstring). No defaults: per ship."""

    shaft_inertia: float = param(unit="kg·m²", symbol="I_s", **_POS,
                                 doc="polar moment of inertia of engine, shafting and propeller "
                                     "including the propeller's entrained water")
    rated_rps: float = param(unit="1/s", symbol="n_MCR", **_POS,
                             doc="shaft speed at the maximum continuous rating (full ahead)")
    max_power: float = param(unit="W", symbol="P_MCR", **_POS,
                             doc="maximum continuous rating (engine power limit)")
    astern_rps: float = param(unit="1/s", symbol="n_astern",
                              doc="full-astern shaft speed (< 0)")
    reversal_time: float = param(unit="s", symbol="t_rev", **_POS,
                                 doc="time in which the brake alone stops the shaft from n_MCR")
    reversal_delay: float = param(unit="s", symbol="t_d", low=0.0,
                                  doc="time from a reversing order to the air start (fuel "
                                      "cut, the propeller windmilling, meanwhile)")
    reversal_rps: float = param(unit="1/s", symbol="n_rev", **_POS,
                                doc="|n| below which the engine is started in the new direction")
    governor_time_constant: float = param(unit="s", symbol="T_g", **_POS,
                                          doc="time constant of the governor's approach to n_c")

    def validate(self) -> None:
        """The astern rps must be < 0 and the reversal rps below the rated rps."""
        check_engine(self)


def check_engine(p: Params) -> None:
    """Cross-field checks of the engine fields (also for a model's parameters that include
    them): astern rps < 0, reversal rps < rated rps."""
    if not p.astern_rps < 0.0:
        raise ParameterError(f"must be < 0 (astern) [1/s], got {p.astern_rps!r}",
                             field="astern_rps", unit="1/s", value=p.astern_rps)
    if not p.reversal_rps < p.rated_rps:
        raise ParameterError(f"must be < rated_rps = {p.rated_rps!r} [1/s], got "
                             f"{p.reversal_rps!r}", field="reversal_rps", unit="1/s",
                             value=p.reversal_rps)


@njit(cache=True)
def commanded_rps(order, p):  # pragma: no cover - compiled
    """n_c of an engine order e (clipped to [−1, 1]): e n_MCR ahead, |e| n_astern astern."""
    e = min(max(order, -1.0), 1.0)
    if e >= 0.0:
        return e * p.rated_rps
    return -e * p.astern_rps


@njit(cache=True)
def reversal_clock_rate(n, order, clock, p):  # pragma: no cover - compiled
    """dτ/dt of the reversal sequence clock: 1 while the order opposes the rotation
    (n n_c < 0), −τ/T_g otherwise (module docstring)."""
    if n * commanded_rps(order, p) < 0.0:
        return 1.0
    return -clock / p.governor_time_constant


@njit(cache=True)
def engine_torque(n, order, propeller_torque, clock, p):  # pragma: no cover - compiled
    """Q_E [N·m] of the governor, limits and reversal sequence at the sequence clock τ =
    ``clock`` [s] (module docstring)."""
    n_c = commanded_rps(order, p)
    two_pi_I = 2.0 * math.pi * p.shaft_inertia
    if n * n_c < 0.0:
        if clock < p.reversal_delay:
            return 0.0  # fuel cut: windmilling
        if abs(n) > p.reversal_rps:
            brake = two_pi_I * p.rated_rps / p.reversal_time
            return -math.copysign(brake, n)
    q_mcr = p.max_power / (2.0 * math.pi * p.rated_rps)
    q_lim = q_mcr
    if abs(n) > p.rated_rps:
        q_lim = p.max_power / (2.0 * math.pi * abs(n))
    q = propeller_torque + two_pi_I * (n_c - n) / p.governor_time_constant
    return min(max(q, -q_lim), q_lim)


@njit(cache=True)
def shaft_acceleration(n, order, propeller_torque, clock, p):  # pragma: no cover - compiled
    """ṅ [1/s²] = (Q_E − Q_P)/(2π I_s) at the sequence clock τ = ``clock`` [s]."""
    q_e = engine_torque(n, order, propeller_torque, clock, p)
    return (q_e - propeller_torque) / (2.0 * math.pi * p.shaft_inertia)
