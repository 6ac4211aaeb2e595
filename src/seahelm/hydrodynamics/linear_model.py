"""The linear sway–yaw model of Clarke et al. (1983) and the Nomoto constants it implies.

Clarke, Gedling & Hine (1983) regressed the linear derivatives of 36 ships' captive tests on
L, B, T, C_b. In the prime system (forces ÷ ½ρU²L², moments ÷ ½ρU²L³, v' = v/U, r' = rL/U,
masses ÷ ½ρL³, inertias ÷ ½ρL⁵), with c = −π (T/L)²::

    Y'_v̇ = c (1 + 0.16 C_b B/T − 5.1 (B/L)²)        Y'_ṙ = c (0.67 B/L − 0.0033 (B/T)²)
    N'_v̇ = c (1.1 B/L − 0.041 B/T)                   N'_ṙ = c (1/12 + 0.017 C_b B/T − 0.33 B/L)
    Y'_v = c (1 + 0.40 C_b B/T)                      Y'_r = c (−1/2 + 2.2 B/L − 0.080 B/T)
    N'_v = c (1/2 + 2.4 T/L)                         N'_r = c (1/4 + 0.039 B/T − 0.56 B/L)

(the same expressions as Fossen's MSS ``clarke83.m`` and PythonVehicleSimulator's
``clarke83``). With the rudder's force derivatives Y'_δ, N'_δ the linear model

    [m' − Y'_v̇,  m' x'_G − Y'_ṙ] [v̇']   [−Y'_v,  m' − Y'_r     ] [v']   [Y'_δ]
    [m' x'_G − N'_v̇, I'_z − N'_ṙ] [ṙ'] + [−N'_v,  m' x'_G − N'_r] [r'] = [N'_δ] δ

(time in units of L/U) has the transfer function r/δ = K (1 + T_3 s)/((1 + T_1 s)(1 + T_2 s))
(Nomoto 1957; Fossen 2021, §7.1); the first-order approximation has T = T_1 + T_2 − T_3.
:func:`nomoto_constants` solves it for any such model (Clarke's or the MMG model's linear
part), dimensional at a speed U: K [1/s] = K' U/L, T_i [s] = T'_i L/U; it hands the
dimensional system to :func:`nomoto_from_state_space`, which does the same for any one- or
two-state steering system ẋ = A x + b δ (the linearisation of a vessel model at an equilibrium,
:mod:`seahelm.analysis.equilibria.linearisation`).

References
----------
Clarke, D., Gedling, P., Hine, G. (1983). The application of manoeuvring criteria in hull
design using linear theory. Trans. RINA 125, 45–68.
Nomoto, K., Taguchi, T., Honda, K., Hirano, S. (1957). On the steering qualities of ships.
Int. Shipbuilding Progress 4(35), 354–370.
Fossen, T.I. (2021). Handbook of Marine Craft Hydrodynamics and Motion Control, 2nd ed. Wiley.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..errors import ParameterError
from .hull import Coefficient, HullParticulars, check_ranges

__all__ = ["clarke_derivatives", "NomotoConstants", "nomoto_constants",
           "nomoto_from_state_space"]

CLARKE = "Clarke, Gedling & Hine (1983)"


def clarke_derivatives(hull: HullParticulars, *, strict: bool | None = None
                       ) -> dict[str, Coefficient]:
    """Clarke et al.'s (1983) linear derivatives, prime system on L² (module docstring).

    Parameters
    ----------
    hull : HullParticulars
        The hull (L, B, T = mean draught, C_b).
    strict : bool, optional
        Raise instead of warning outside the data of the 36 ships (approximately
        0.5 ≤ C_b ≤ 0.85, 4 ≤ L/B ≤ 8, 2 ≤ B/T ≤ 4.5).

    Returns
    -------
    dict of str to Coefficient
        ``Y_vdot``, ``Y_rdot``, ``N_vdot``, ``N_rdot``, ``Y_v``, ``Y_r``, ``N_v``, ``N_r``.
    """
    L, B, T, cb = hull.length, hull.beam, hull.draft, hull.block_coefficient
    check_ranges(f"{CLARKE} linear derivatives", {"C_b": (cb, 0.5, 0.85),
                                                  "L/B": (L / B, 4.0, 8.0),
                                                  "B/T": (B / T, 2.0, 4.5)}, strict=strict)
    c = -math.pi * (T / L) ** 2
    terms = {
        "Y_vdot": (1 + 0.16 * cb * B / T - 5.1 * (B / L) ** 2,
                   "1 + 0.16 C_b B/T − 5.1 (B/L)²"),
        "Y_rdot": (0.67 * B / L - 0.0033 * (B / T) ** 2, "0.67 B/L − 0.0033 (B/T)²"),
        "N_vdot": (1.1 * B / L - 0.041 * B / T, "1.1 B/L − 0.041 B/T"),
        "N_rdot": (1 / 12 + 0.017 * cb * B / T - 0.33 * B / L,
                   "1/12 + 0.017 C_b B/T − 0.33 B/L"),
        "Y_v": (1 + 0.40 * cb * B / T, "1 + 0.40 C_b B/T"),
        "Y_r": (-0.5 + 2.2 * B / L - 0.080 * B / T, "−1/2 + 2.2 B/L − 0.080 B/T"),
        "N_v": (0.5 + 2.4 * T / L, "1/2 + 2.4 T/L"),
        "N_r": (0.25 + 0.039 * B / T - 0.56 * B / L, "1/4 + 0.039 B/T − 0.56 B/L"),
    }
    return {name: Coefficient(c * value, f"{CLARKE}: {name.replace('dot', '̇')}' = −π (T/L)² "
                                         f"({text}) (prime system on L²)")
            for name, (value, text) in terms.items()}


@dataclasses.dataclass(frozen=True)
class NomotoConstants:
    """Nomoto's second-order steering constants at one speed, and the first-order T.

    Attributes
    ----------
    gain : float
        K [1/s]: steady yaw rate per rudder angle (positive rudder, positive yaw rate).
    t1, t2, t3 : float
        T_1, T_2, T_3 [s].
    speed : float
        The speed U [m/s] they hold at.
    """

    gain: float
    t1: float
    t2: float
    t3: float
    speed: float

    @property
    def time_constant(self) -> float:
        """First-order T = T_1 + T_2 − T_3 [s]."""
        return self.t1 + self.t2 - self.t3


def nomoto_constants(mass: np.ndarray, damping: np.ndarray, rudder: np.ndarray, *,
                     length: float, speed: float, require_stable: bool = True
                     ) -> NomotoConstants:
    """Nomoto K, T_1, T_2, T_3 of a linear sway–yaw model M ẋ' + N x' = b δ (prime units).

    Parameters
    ----------
    mass : array_like, shape (2, 2)
        M (module docstring), non-dimensional.
    damping : array_like, shape (2, 2)
        N, non-dimensional.
    rudder : array_like, shape (2,)
        b = (Y'_δ, N'_δ), non-dimensional, for a positive rudder angle giving a positive yaw
        rate.
    length : float
        L [m].
    speed : float
        U [m/s] (> 0).
    require_stable : bool, optional
        Refuse a course-unstable model (default True); with False its T_1 < 0 and K < 0 are
        returned (Fossen 2021, §7.1).

    Returns
    -------
    NomotoConstants

    Raises
    ------
    ParameterError
        When the model has no two real poles (Nomoto's form needs them), is not straight-line
        stable with ``require_stable``, or the speed or length is not positive.
    """
    if not (speed > 0 and math.isfinite(speed)):
        raise ParameterError(f"must be > 0 [m/s], got {speed!r}", field="speed", unit="m/s",
                             value=speed)
    if not (length > 0 and math.isfinite(length)):
        raise ParameterError(f"must be > 0 [m], got {length!r}", field="length", unit="m",
                             value=length)
    M = np.asarray(mass, dtype=float)
    N = np.asarray(damping, dtype=float)
    b = np.asarray(rudder, dtype=float)
    # time in units of L/U, r' = r L/U: K [1/s] = K' U/L, T_i [s] = T'_i L/U
    prime = nomoto_from_state_space(-np.linalg.solve(M, N), np.linalg.solve(M, b), unit="-",
                                    require_stable=require_stable)
    scale = length / speed
    return NomotoConstants(gain=prime.gain / scale, t1=prime.t1 * scale, t2=prime.t2 * scale,
                           t3=prime.t3 * scale, speed=float(speed))


def nomoto_from_state_space(A: np.ndarray, b: np.ndarray, *, speed: float = math.nan,
                            yaw_rate_index: int = -1, require_stable: bool = True,
                            unit: str = "1/s") -> NomotoConstants:
    """Nomoto K, T_1, T_2, T_3 of the yaw rate of a linear steering system ẋ = A x + b δ.

    The system has one or two states (yaw rate r and, for two, a sway or auxiliary state);
    its transfer function r/δ = c (sI − A)⁻¹ b is put in Nomoto's (1957) form
    K (1 + T_3 s)/((1 + T_1 s)(1 + T_2 s)), with T_1 the slower pole (Fossen 2021, eq. (7.16)).
    With two states, A = [[a_vv, a_vr], [a_rv, a_rr]], b = (b_v, b_r)::

        r/δ = (b_r s + a_rv b_v − a_vv b_r) / (s² − (a_vv + a_rr) s + det A)

    so K = (a_rv b_v − a_vv b_r)/det A, T_3 = b_r/(a_rv b_v − a_vv b_r), T_{1,2} = −1/p_{1,2}.
    With one state r/δ = b/(s − a): K = −b/a, T_1 = −1/a, T_2 = T_3 = 0.

    A course-unstable ship (a positive real pole) has T_1 < 0 (and K < 0): Nomoto's form still
    holds (Fossen 2021, §7.1), and it is returned with ``require_stable=False``.

    Parameters
    ----------
    A : array_like, shape (n, n), n = 1 or 2
        System matrix [1/s] (or non-dimensional, time in units of L/U, with ``unit="-"``).
    b : array_like, shape (n,)
        Rudder column [rad/s² per rad for r], for a positive rudder giving a positive yaw rate.
    speed : float, optional
        The speed U [m/s] the system holds at (recorded in the result only).
    yaw_rate_index : int, optional
        Which state is r (default the last).
    require_stable : bool, optional
        Refuse a model with a pole in the closed right half-plane (default True).
    unit : str, optional
        Unit of the time of A for the messages.

    Returns
    -------
    NomotoConstants

    Raises
    ------
    ParameterError
        When the poles are complex (Nomoto's form needs real poles), or not negative with
        ``require_stable``, or the shapes are wrong.
    """
    A = np.atleast_2d(np.asarray(A, dtype=float))
    b = np.atleast_1d(np.asarray(b, dtype=float))
    n = A.shape[0]
    if A.shape != (n, n) or b.shape != (n,) or n not in (1, 2):
        raise ParameterError(f"must be a 1×1 or 2×2 system with a matching b, got A "
                             f"{A.shape}, b {b.shape}", field="A")
    if n == 1:
        a = A[0, 0]
        if a == 0.0 or (require_stable and a > 0):
            raise ParameterError(
                f"the model has the pole {a:.4g} [{unit}]: Nomoto's form needs a negative "
                "real pole (a straight-line stable ship)", field="model")
        return NomotoConstants(gain=float(-b[0] / a), t1=float(-1.0 / a), t2=0.0, t3=0.0,
                               speed=float(speed))
    ir = yaw_rate_index % 2
    iv = 1 - ir
    poles = np.linalg.eigvals(A)
    bad = np.any(np.abs(poles.imag) > 1e-12 * np.abs(poles).max()) or np.any(poles == 0)
    if bad or (require_stable and np.any(poles.real >= 0)):
        raise ParameterError(
            f"the linear model has poles {', '.join(f'{p:.4g}' for p in poles)} [{unit}]: "
            "Nomoto's form needs two real negative poles (a straight-line stable ship)",
            field="model")
    num1 = b[ir]
    num0 = A[ir, iv] * b[iv] - A[iv, iv] * b[ir]
    p_slow, p_fast = sorted(poles.real, key=abs)  # T_1 the slower pole
    gain = num0 / (p_slow * p_fast)
    t3 = num1 / num0 if num0 != 0 else math.nan
    return NomotoConstants(gain=float(gain), t1=float(-1.0 / p_slow), t2=float(-1.0 / p_fast),
                           t3=float(t3), speed=float(speed))
