"""The wave-frequency yaw of a steered ship in an irregular sea, as a shaping filter.

The model the wave filter (:mod:`seahelm.control.wave_filter`) separates from the ship's
low-frequency motion, built on seahelm's shaping filters (:mod:`seahelm.environment.shaping`).

References
----------
Fossen, T. I. (2021). Handbook of Marine Craft Hydrodynamics and Motion Control, 2nd ed.
Wiley, §10.2.4 (linear wave response models).
"""

from __future__ import annotations

import math

import numpy as np

from .._validate import check_positive
from ..constants import GRAVITY
from .shaping import StateSpaceFilter, from_transfer_functions

__all__ = ["wave_yaw_filter"]


def wave_yaw_filter(ordinate: StateSpaceFilter, *, gain: float, time_constant: float,
                    rudder_per_slope: float, gravity: float = GRAVITY) -> StateSpaceFilter:
    """The WF heading of a Nomoto ship under an equivalent rudder g_δ α(t) (module docstring).

    At wave frequencies ωT ≫ 1 the ship's heading response is inertial, K/(T s²) ≈ −K/(T ω̄²)
    about the sea's mean frequency ω̄ (ω̄² = E[ζ̇²]/E[ζ²]), so ψ_W ≈ −(K g_δ/(T ω̄²)) α with the
    slope α = (s/g) W(s): a narrow-band process with a zero at s = 0 — for the
    Rakhmanin–Firsov variant 2, W(s) ∝ a/(s² + 2μs + a²), Fossen's (2021, eq. (10.118))
    second-order linear wave model K_w s/(s² + 2λω₀s + ω₀²). Without low-frequency content the
    LF and WF headings are separable, and the slow part of the wave-induced drift stays in the
    LF model (as a rudder bias) for the autopilot to correct.

    Parameters
    ----------
    ordinate : StateSpaceFilter
        Shaping filter of the sea's ordinate ζ (first output), W(s).
    gain, time_constant : float
        Nomoto K [1/s], T [s].
    rudder_per_slope : float
        g_δ [rad of equivalent rudder per rad of wave slope].
    gravity : float, optional
        g [m/s²].

    Returns
    -------
    StateSpaceFilter
        One output ``wave_heading`` [rad], the noise intensity of ``ordinate``.
    """
    from scipy import signal

    check_positive("time_constant", time_constant, "s")
    num, den = signal.ss2tf(ordinate.A, ordinate.B, ordinate.C[:1], ordinate.D[:1])
    num = np.trim_zeros(np.atleast_1d(num[0]), "f")
    rate = np.polymul(num, [1.0, 0.0])
    var_z = float(from_transfer_functions([num], den, labels=("z",)).output_variance()[0])
    var_r = float(from_transfer_functions([rate], den, labels=("r",)).output_variance()[0])
    mean_freq2 = var_r / var_z
    k = -gain * rudder_per_slope / (time_constant * mean_freq2 * gravity)
    return from_transfer_functions([rate * k], den, labels=("wave_heading",), units=("rad",),
                                   noise_intensity=ordinate.noise_intensity,
                                   name=f"WF yaw of a Nomoto ship (K = {gain:.4g} 1/s, "
                                        f"T = {time_constant:.4g} s, mean frequency "
                                        f"{math.sqrt(mean_freq2):.3g} rad/s) in {ordinate.name}")
