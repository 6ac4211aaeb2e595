"""The third-order heading reference model of the craft autopilots (Fossen 2021, §12.1.1):
its start and one step of it, shared by :mod:`.thrust_heading` (Otter USV) and :mod:`.auv_depth_heading`
(REMUS 100).

The desired heading ψ_d follows the commanded ψ_ref through three cascaded first-order
lags (a low-pass filter of relative damping ζ_d and natural frequency ω_d), its rate limited
to ±r_max; per controller sample of period h (forward Euler, as the published autopilots)::

    j_d = ω_d³ wrap(ψ_ref − ψ_d) − (2ζ_d + 1) ω_d² r_d − (2ζ_d + 1) ω_d a_d
    ψ_d ← ψ_d + h r_d,  r_d ← sat(r_d + h a_d, ±r_max),  a_d ← a_d + h j_d

The model's input is wrapped to [−π, π) (the published model takes ψ_ref − ψ_d as it is: the
two agree while it stays below 180°; with LOS guidance, whose ψ_ref jumps by 360° where it
wraps, the unwrapped model would turn the craft a full circle).
"""

from __future__ import annotations

from numba import njit

from .base import wrap_pi

__all__ = ["heading_reference_init", "heading_reference_step"]


@njit(cache=True)
def heading_reference_init(cs, heading, rate, acceleration, psi):  # pragma: no cover - compiled
    """Start the reference model at rest on the craft's heading.

    Parameters
    ----------
    cs : numpy.ndarray
        The controller's states; written in place.
    heading, rate, acceleration : int
        Where ψ_d [rad], r_d [rad/s] and a_d [rad/s²] are in ``cs``.
    psi : float
        The craft's heading ψ [rad]: ψ_d = ψ, r_d = a_d = 0.
    """
    cs[heading] = psi
    cs[rate] = 0.0
    cs[acceleration] = 0.0


@njit(cache=True)
def heading_reference_step(cs, heading, rate, acceleration, target, frequency, damping,
                           max_rate, dt):  # pragma: no cover - compiled
    """Advance the reference model's states ``cs[heading]``, ``cs[rate]``,
    ``cs[acceleration]`` (ψ_d [rad], r_d [rad/s], a_d [rad/s²]) by one sample ``dt`` [s]
    towards ``target`` ψ_ref [rad] (module docstring), with ``frequency`` ω_d [rad/s],
    ``damping`` ζ_d [-] and the rate limit ``max_rate`` r_max [rad/s]."""
    psi_d = cs[heading]
    r_d = cs[rate]
    a_d = cs[acceleration]
    c = 2.0 * damping + 1.0
    jerk = (frequency * frequency * frequency * wrap_pi(target - psi_d)
            - c * frequency * frequency * r_d - c * frequency * a_d)
    cs[heading] = psi_d + dt * r_d
    r_new = r_d + dt * a_d
    cs[rate] = -max_rate if r_new < -max_rate else (max_rate if r_new > max_rate else r_new)
    cs[acceleration] = a_d + dt * jerk
