"""Encounter (apparent) frequency and the encounter spectrum of a moving ship.

A ship with speed v meets deep-water waves of frequency ω at the apparent frequency
(Sushchenko & Lutsko (2010), text after eq. (5))

    ω_y = |ω − ω² v cos ε / g|,

ε the angle between the wave velocity and the ship velocity (ε = 0: following seas,
ε = π: head seas). The spectrum transforms as S_y(ω_y) dω_y = S(ω) dω summed over every
wave frequency with the same ω_y, i.e. S_y(ω_y) = Σ S(ω_i)/|1 − 2ω_i v cos ε / g|.

In following seas (v cos ε > 0) the map ω ↦ ω_e = ω − ω²v cos ε/g has a maximum at the
singular frequency ω* = g/(2v cos ε), where dω_e/dω = 0 and the encounter spectrum has an
integrable inverse-square-root singularity at ω_y* = g/(4 v cos ε); three wave frequencies
map onto each ω_y < ω_y*. :class:`EncounterSpectrum` sums all branches and returns ``inf``
exactly at ω_y*, so its integral still equals the wave variance.

The paper's last shaping filter puts |1 − 2ωv cos ε/g| into the gain K: that gain depends on
ω, so the filter is not rational (erratum) and is not offered; sample the encounter process by
the wave-frequency filters and transform frequencies instead.

References
----------
Sushchenko, O. A., & Lutsko, D. O. (2010); Perez, T. (2005), Ship Motion Control, ch. 2.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from numpy.typing import ArrayLike

from .._validate import as_float_array, check_nonnegative, check_positive
from ..constants import GRAVITY
from .spectrum_base import WaveSpectrum

__all__ = [
    "encounter_frequency",
    "apparent_frequency",
    "singular_frequency",
    "EncounterSpectrum",
]


def _speed_heading(speed: ArrayLike, heading: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    v = as_float_array("speed", speed, "m/s")
    check_nonnegative("speed", v, "m/s")
    eps = as_float_array("heading", heading, "rad")
    return v, eps


def encounter_frequency(
    omega: ArrayLike, speed: ArrayLike, heading: ArrayLike, *, gravity: float = GRAVITY
) -> np.ndarray:
    """Signed encounter frequency ω_e = ω − ω² v cos ε / g [rad/s].

    Parameters
    ----------
    omega : array_like
        Wave frequency ω [rad/s], ≥ 0.
    speed : array_like
        Ship speed v [m/s], ≥ 0.
    heading : array_like
        ε [rad], angle between wave and ship velocities (0 following, π head seas).
    gravity : float
        g [m/s²].

    Returns
    -------
    numpy.ndarray
        ω_e, broadcast over the inputs. The apparent frequency is |ω_e|.
    """
    w = as_float_array("omega", omega, "rad/s")
    check_nonnegative("omega", w, "rad/s")
    v, eps = _speed_heading(speed, heading)
    check_positive("gravity", gravity, "m/s^2")
    return w - w**2 * v * np.cos(eps) / gravity


def apparent_frequency(
    omega: ArrayLike, speed: ArrayLike, heading: ArrayLike, *, gravity: float = GRAVITY
) -> np.ndarray:
    """ω_y = |ω − ω² v cos ε / g| (Sushchenko & Lutsko (2010), after eq. (5)).

    Parameters
    ----------
    omega : array_like
        Wave frequency ω [rad/s].
    speed : array_like
        Ship speed v [m/s].
    heading : array_like
        ε [rad], angle between wave and ship velocities (0 following, π head seas).
    gravity : float, optional
        Gravitational acceleration g [m/s²].

    Returns
    -------
    numpy.ndarray
        ω_y [rad/s].
    """
    return np.abs(encounter_frequency(omega, speed, heading, gravity=gravity))


def singular_frequency(speed: float, heading: float, *, gravity: float = GRAVITY) -> float:
    """Wave frequency ω* = g/(2 v cos ε) [rad/s] where dω_e/dω = 0; ``inf`` if v cos ε ≤ 0.

    Parameters
    ----------
    speed : float
        Ship speed v [m/s].
    heading : float
        ε [rad], angle between wave and ship velocities (0 following, π head seas).
    gravity : float, optional
        Gravitational acceleration g [m/s²].

    Returns
    -------
    float
        ω* [rad/s].
    """
    v, eps = _speed_heading(speed, heading)
    check_positive("gravity", gravity, "m/s^2")
    cos_e = float(np.cos(eps))
    c = float(v) * (cos_e if abs(cos_e) >= 1e-12 else 0.0)
    return gravity / (2.0 * c) if c > 0 else math.inf


@dataclasses.dataclass(frozen=True)
class EncounterSpectrum:
    """One-sided spectrum in apparent frequency ω_y of a base wave spectrum.

    S_y(ω_y) = Σ_i S₁(ω_i)/|1 − 2ω_i v cos ε/g| over all ω_i ≥ 0 with |ω_e(ω_i)| = ω_y.

    Parameters
    ----------
    base : WaveSpectrum
        One-sided spectrum in wave frequency (ordinate or slope).
    speed : float
        v [m/s], ≥ 0.
    heading : float
        ε [rad] (0 following, π head seas).
    gravity : float
        g [m/s²].

    Notes
    -----
    At the singular apparent frequency ω_y* = g/(4v cos ε) (following seas) the density is
    ``inf``; the singularity is integrable, so ∫₀^∞ S_y dω_y = ∫₀^∞ S₁ dω.
    """

    base: WaveSpectrum
    speed: float
    heading: float
    gravity: float = GRAVITY

    def __post_init__(self) -> None:
        check_nonnegative("speed", self.speed, "m/s")
        as_float_array("heading", self.heading, "rad")
        check_positive("gravity", self.gravity, "m/s^2")

    @property
    def _c(self) -> float:
        """v cos ε / g [s²/m · m/s = s]; ω_e = ω − c ω²."""
        cos_e = math.cos(self.heading)
        if abs(cos_e) < 1e-12:  # beam seas: cos(π/2) is 6e-17 in floating point
            return 0.0
        return self.speed * cos_e / self.gravity

    @property
    def singular_apparent_frequency(self) -> float:
        """ω_y* = g/(4 v cos ε) [rad/s]; ``inf`` if v cos ε ≤ 0."""
        c = self._c
        return 1.0 / (4.0 * c) if c > 0 else math.inf

    def wave_frequencies(self, omega_y: float) -> np.ndarray:
        """All wave frequencies ω ≥ 0 with |ω − cω²| = ω_y (1, 2 or 3 of them).

        Parameters
        ----------
        omega_y : float
            Apparent frequency ω_y [rad/s] (>= 0).

        Returns
        -------
        numpy.ndarray
            Wave frequencies ω [rad/s], sorted.
        """
        c, wy = self._c, float(omega_y)
        if c == 0.0:
            return np.array([wy])
        roots: list[float] = []
        # ω − cω² = s ω_y, s = ±1  →  cω² − ω + s ω_y = 0; small root in the stable form
        for sign in (1.0, -1.0):
            disc = 1.0 - 4.0 * c * sign * wy
            if disc < 0:
                continue
            sq = math.sqrt(disc)
            for r in (2.0 * sign * wy / (1.0 + sq), (1.0 + sq) / (2.0 * c)):
                if r >= 0 and not any(abs(r - q) <= 1e-12 * max(1.0, r) for q in roots):
                    roots.append(r)
        return np.array(sorted(roots))

    def one_sided(self, omega_y: ArrayLike) -> np.ndarray:
        """S_y(ω_y) [unit²·s/rad], ``inf`` at the singular apparent frequency.

        Parameters
        ----------
        omega_y : array_like
            Apparent frequencies ω_y [rad/s] (>= 0).

        Returns
        -------
        numpy.ndarray
            S_y(ω_y), shape of ``omega_y``.
        """
        wy = as_float_array("omega_y", omega_y, "rad/s")
        check_nonnegative("omega_y", wy, "rad/s")
        flat = np.atleast_1d(wy).ravel()
        out = np.empty_like(flat)
        c = self._c
        ws = self.singular_apparent_frequency
        for i, y in enumerate(flat):
            if y == ws:
                out[i] = math.inf
                continue
            ws_i = self.wave_frequencies(y)
            if ws_i.size == 0:
                out[i] = 0.0
                continue
            jac = np.abs(1.0 - 2.0 * c * ws_i)
            out[i] = float(np.sum(self.base.one_sided(ws_i) / jac))
        return out.reshape(wy.shape)
