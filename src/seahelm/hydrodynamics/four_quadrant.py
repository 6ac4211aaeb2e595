"""Four-quadrant open-water thrust and torque of a Wageningen B-series propeller.

Over all four quadrants of advance speed V_A and rps n the open-water characteristics are
written against the **advance angle** (hydrodynamic pitch angle at 0.7 R)::

    β = atan2(V_A, 0.7 π n D)                                   (−π < β ≤ π)

    C_T*(β) = Σ_{k=0..30} [A_T(k) cos kβ + B_T(k) sin kβ] / 100
    C_Q*(β) = −Σ_{k=0..30} [A_Q(k) cos kβ + B_Q(k) sin kβ] / 1000

    T = ½ ρ C_T*(β) (V_A² + (0.7 π n D)²) (π/4) D²
    Q = ½ ρ C_Q*(β) (V_A² + (0.7 π n D)²) (π/4) D³

(van Lammeren, van Manen & Oosterveld 1969, eqs. for C_T*, C_Q*; Roddy, Hess & Faller 2006,
eq. 1 and Appendix B). Quadrant 1 (0 ≤ β < 90°) is ahead motion with ahead rps, quadrant 2
(90° ≤ β < 180°) ahead motion with astern rps (the crash stop), quadrant 3
(−180° ≤ β < −90°) astern motion with astern rps, quadrant 4 (−90° ≤ β < 0) astern motion
with ahead rps. In the first quadrant, with J = V_A/(n D) = 0.7 π tan β::

    K_T = C_T* (π/8) (J² + (0.7π)²),   K_Q = C_Q* (π/8) (J² + (0.7π)²)

The coefficient table
---------------------
:data:`B4_70_PD10` is the B4-70 propeller with P/D = 1.0, the refit of the four-quadrant
Wageningen data by Roddy, Hess & Faller (2006), Appendix B (31 harmonics, k = 0..30). The
report lists 100 C_T* and −1000 C_Q*. The table was not at hand; the numbers are those of
the transcription in the Modelica library ``BasilioPV/ShipSIM`` (``ShipSIM/Functions.mo``,
function ``WageningenB_4Q_Matrix``, entry ``B4_70_1``, which cites Roddy et al. 2006,
NSWCCD-50-TR-2006/004). Checks of that transcription:

* the same library's B4-70 P/D = 1.4 entry agrees, to the three significant figures given
  there, with a second, independent transcription (``kylemarl/UMFullStop``, ``B470data.csv``,
  which cites Roddy 2006 and is the P/D = 1.4 table although its name does not say so);
* a third, unlabelled 21-term table (``NTNU-MCS/MarPowSim``,
  ``Example/DrillingRigMSStoolbox/Files/thrusterInit.m``: C_T*, C_Q* directly, no scale) is
  close to this one term by term (A_T(0..5): 0.02535, 0.1782, 0.01467, 0.02805, −0.01633,
  −0.05304 against 0.026617, 0.17802, 0.013828, 0.027871, −0.01624, −0.053084; B_T(1):
  −0.74777 against −0.74797): a B4-70 P/D 1.0 fit with 20 harmonics, as in van Lammeren et
  al. (1969), most probably — it is a different fit, not a transcription of the same table,
  and is kept only as a comparison in the tests;
* in the first quadrant, K_T and K_Q from the series agree with the B-series polynomials
  (Oosterveld & van Oossanen 1975; :mod:`seahelm.hydrodynamics.propeller_series`) of the same
  propeller (Z = 4, A_E/A_0 = 0.70, P/D = 1.0) for 0 ≤ J ≤ 1.0 within 0.0116 in K_T and
  0.0037 in K_Q: the largest differences on the grid J = 0, 0.0001, …, 1.0 are 0.01150 in
  K_T (at J = 1.0) and 0.00362 in K_Q (at J = 0.30); 0.4499 against 0.4547 at J = 0 (tested
  on that grid).

Signs: C_T*(0) = 0.2369 > 0 (ahead bollard thrust), C_Q*(0) = 0.0348 > 0 (torque absorbed);
C_T*(180°) = −0.179 (astern bollard thrust, K_T = −0.340, 75 % of the ahead one);
C_T*(90°) = −0.772 (a stopped propeller is a drag), C_Q*(90°) = −0.116 (the flow drives a
stopped shaft ahead: windmilling).

Validity: the B-series models (Z, A_E/A_0, P/D) of the table only; the open-water data
(no hull, no oblique inflow). A ship's own propeller is represented by scaling (see
:mod:`seahelm.vessels.mmg_four_quadrant`).

References
----------
van Lammeren, W. P. A., van Manen, J. D. & Oosterveld, M. W. C. (1969). The Wageningen
B-screw series. Trans. SNAME 77, 269–317.
Roddy, R. F., Hess, D. E. & Faller, W. E. (2006). Neural network predictions of the
4-quadrant Wageningen propeller series. Report NSWCCD-50-TR-2006/004, Naval Surface Warfare
Center Carderock Division. Appendix B.
Oosterveld, M. W. C. & van Oossanen, P. (1975). Further computer-analyzed data of the
Wageningen B-screw series. International Shipbuilding Progress 22(251), 251–262.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numba import njit

__all__ = ["B4_70_PD10", "B4_70_PD10_SOURCE", "fourier_coefficients", "thrust_coefficient_4q",
           "torque_coefficient_4q", "advance_angle", "four_quadrant_kt_kq", "ct_cq",
           "N_HARMONICS"]

#: Number of harmonics of the tables (k = 0..30).
N_HARMONICS = 31

#: B4-70, P/D = 1.0: rows k = 0..30 of (A_T, B_T, A_Q, B_Q) as the report prints them
#: (100 C_T* and −1000 C_Q*): Roddy, Hess & Faller (2006), Appendix B, transcribed in
#: BasilioPV/ShipSIM (ShipSIM/Functions.mo, WageningenB_4Q_Matrix, B4_70_1).
B4_70_PD10 = np.array([
    (2.6617, 0, -2.2945, 0),  # k = 0
    (17.802, -74.797, -26.989, 110.38),  # k = 1
    (1.3828, -1.3632, -1.8758, -0.52852),  # k = 2
    (2.7871, 10.246, -6.3552, -16.544),  # k = 3
    (-1.624, -1.0865, 2.1668, 1.929),  # k = 4
    (-5.3084, 4.7346, 7.653, -8.448),  # k = 5
    (0.1918, 1.1355, -0.56516, -0.90714),  # k = 6
    (3.8318, -0.9318, -6.2654, 3.1042),  # k = 7
    (-0.22892, -0.72471, 1.9211, 0.68648),  # k = 8
    (-1.8656, 2.3747, 3.3456, -4.5196),  # k = 9
    (0.349, 0.86208, -1.2956, -1.0928),  # k = 10
    (2.2321, 0.0070224, -3.1294, -0.044966),  # k = 11
    (-0.35976, -0.36422, 1.2475, 0.72404),  # k = 12
    (0.13606, 0.91758, -1.4351, -1.5284),  # k = 13
    (0.47192, 0.089383, -0.83201, -0.23983),  # k = 14
    (0.87235, -0.59364, 0.034868, 1.6074),  # k = 15
    (-0.35748, -0.070954, 0.89981, -0.66184),  # k = 16
    (0.35955, 0.48825, -1.4247, -1.2084),  # k = 17
    (0.52896, -0.090587, -1.1064, 0.58384),  # k = 18
    (0.21045, -0.81163, 0.27359, 1.3397),  # k = 19
    (-0.27057, -0.056659, 0.6759, -0.29095),  # k = 20
    (0.10509, 0.12011, -0.57328, -0.089605),  # k = 21
    (0.27733, -0.13042, -0.22609, 0.54988),  # k = 22
    (-0.11596, -0.48187, 0.70691, 0.14626),  # k = 23
    (-0.1745, 0.045412, -0.030228, -0.4838),  # k = 24
    (0.040782, -0.019469, -0.46043, 0.38709),  # k = 25
    (0.099247, -0.21858, 0.25629, 0.72114),  # k = 26
    (-0.3465, -0.16314, 0.76092, -0.13767),  # k = 27
    (-0.12357, 0.14865, 0.0026235, -0.45823),  # k = 28
    (0.063929, 0.10185, -0.19316, 0.1052),  # k = 29
    (0.061933, -0.16735, 0.31487, 0.27547),  # k = 30
])
B4_70_PD10.setflags(write=False)

B4_70_PD10_SOURCE = (
    "Wageningen B4-70, P/D 1.0, four-quadrant Fourier series: Roddy, Hess & Faller (2006), "
    "NSWCCD-50-TR-2006/004, Appendix B (31 harmonics), as transcribed in BasilioPV/ShipSIM "
    "(ShipSIM/Functions.mo, WageningenB_4Q_Matrix, B4_70_1)")


def fourier_coefficients(table: Any = None) -> np.ndarray:
    """The table as C_T*, C_Q* coefficients: shape (31, 4) of (a_T, b_T, a_Q, b_Q).

    a_T = A_T/100, b_T = B_T/100, a_Q = −A_Q/1000, b_Q = −B_Q/1000, so that
    C_T* = Σ a_T(k) cos kβ + b_T(k) sin kβ and the same for C_Q*.

    Parameters
    ----------
    table : array_like, shape (K, 4), optional
        A table as printed (100 C_T*, −1000 C_Q*); default :data:`B4_70_PD10`.

    Returns
    -------
    numpy.ndarray, shape (K, 4)
    """
    t = np.asarray(B4_70_PD10 if table is None else table, dtype=float)
    if t.ndim != 2 or t.shape[1] != 4:
        raise ValueError(f"`table` must have shape (K, 4), got {t.shape}")
    return t * np.array([0.01, 0.01, -0.001, -0.001])


@njit(cache=True)
def ct_cq(beta, coeffs):  # pragma: no cover - compiled
    """C_T*(β), C_Q*(β) of the Fourier series (compiled; ``coeffs`` from
    :func:`fourier_coefficients`, shape (K, 4)).

    cos kβ and sin kβ by rotation, (cos kβ + i sin kβ) = (cos (k−4)β + i sin (k−4)β)
    (cos 4β + i sin 4β), in four independent chains (k = 4m, 4m + 1, 4m + 2, 4m + 3) that the
    processor overlaps: one cos and one sin per call instead of 2K (a crash stop's right-hand
    side spent four fifths of its time in them), and a quarter of the dependent steps of one
    chain (1.4-1.7x faster than one chain, measured). A rotation keeps its length, so the
    error grows only linearly in k, to a few 1e-16 at K = 31 (within 1e-14 of the numpy
    series, ``tests/test_hydrodynamics_four_quadrant.py``)."""
    c1 = math.cos(beta)
    s1 = math.sin(beta)
    c2 = c1 * c1 - s1 * s1
    s2 = 2.0 * s1 * c1
    c3 = c2 * c1 - s2 * s1
    s3 = s2 * c1 + c2 * s1
    c4 = c2 * c2 - s2 * s2
    s4 = 2.0 * s2 * c2
    a0, b0, a1, b1, a2, b2, a3, b3 = 1.0, 0.0, c1, s1, c2, s2, c3, s3
    t0 = t1 = t2 = t3 = 0.0
    q0 = q1 = q2 = q3 = 0.0
    n = coeffs.shape[0]
    k = 0
    while k + 3 < n:
        t0 += coeffs[k, 0] * a0 + coeffs[k, 1] * b0
        q0 += coeffs[k, 2] * a0 + coeffs[k, 3] * b0
        t1 += coeffs[k + 1, 0] * a1 + coeffs[k + 1, 1] * b1
        q1 += coeffs[k + 1, 2] * a1 + coeffs[k + 1, 3] * b1
        t2 += coeffs[k + 2, 0] * a2 + coeffs[k + 2, 1] * b2
        q2 += coeffs[k + 2, 2] * a2 + coeffs[k + 2, 3] * b2
        t3 += coeffs[k + 3, 0] * a3 + coeffs[k + 3, 1] * b3
        q3 += coeffs[k + 3, 2] * a3 + coeffs[k + 3, 3] * b3
        a0, b0 = a0 * c4 - b0 * s4, b0 * c4 + a0 * s4
        a1, b1 = a1 * c4 - b1 * s4, b1 * c4 + a1 * s4
        a2, b2 = a2 * c4 - b2 * s4, b2 * c4 + a2 * s4
        a3, b3 = a3 * c4 - b3 * s4, b3 * c4 + a3 * s4
        k += 4
    # the last K mod 4 terms: chains 0, 1, 2 hold the cos and sin of k, k + 1, k + 2
    if k < n:
        t0 += coeffs[k, 0] * a0 + coeffs[k, 1] * b0
        q0 += coeffs[k, 2] * a0 + coeffs[k, 3] * b0
    if k + 1 < n:
        t1 += coeffs[k + 1, 0] * a1 + coeffs[k + 1, 1] * b1
        q1 += coeffs[k + 1, 2] * a1 + coeffs[k + 1, 3] * b1
    if k + 2 < n:
        t2 += coeffs[k + 2, 0] * a2 + coeffs[k + 2, 1] * b2
        q2 += coeffs[k + 2, 2] * a2 + coeffs[k + 2, 3] * b2
    return (t0 + t1) + (t2 + t3), (q0 + q1) + (q2 + q3)


def advance_angle(advance_speed: Any, rps: Any, diameter: float) -> np.ndarray:
    """β = atan2(V_A, 0.7 π n D) [rad] (Roddy et al. 2006, eq. 1).

    Parameters
    ----------
    advance_speed : array_like
        Advance speed V_A [m/s] (any sign).
    rps : array_like
        Propeller rps n [1/s] (any sign).
    diameter : float
        Propeller diameter D [m] (> 0).

    Returns
    -------
    numpy.ndarray
        β in (−π, π] [rad].
    """
    return np.arctan2(np.asarray(advance_speed, dtype=float),
                      0.7 * math.pi * np.asarray(rps, dtype=float) * float(diameter))


def _series(beta: Any, table: Any, cols: slice) -> np.ndarray:
    b = np.asarray(beta, dtype=float)
    c = fourier_coefficients(table)[:, cols]
    k = np.arange(c.shape[0])
    kb = b[..., None] * k
    return np.cos(kb) @ c[:, 0] + np.sin(kb) @ c[:, 1]


def thrust_coefficient_4q(beta: Any, table: Any = None) -> np.ndarray:
    """C_T*(β) of the four-quadrant series (module docstring).

    Parameters
    ----------
    beta : array_like
        Advance angle β [rad].
    table : array_like, shape (K, 4), optional
        Table as printed (default :data:`B4_70_PD10`).

    Returns
    -------
    numpy.ndarray
        C_T* [-] (broadcast over ``beta``).
    """
    return _series(beta, table, slice(0, 2))


def torque_coefficient_4q(beta: Any, table: Any = None) -> np.ndarray:
    """C_Q*(β) of the four-quadrant series (module docstring).

    Parameters
    ----------
    beta : array_like
        Advance angle β [rad].
    table : array_like, shape (K, 4), optional
        Table as printed (default :data:`B4_70_PD10`).

    Returns
    -------
    numpy.ndarray
        C_Q* [-] (broadcast over ``beta``).
    """
    return _series(beta, table, slice(2, 4))


def four_quadrant_kt_kq(J: Any, table: Any = None) -> tuple[np.ndarray, np.ndarray]:
    """First-quadrant K_T(J), K_Q(J) of the series: C* (π/8)(J² + (0.7π)²), β = atan(J/0.7π).

    Parameters
    ----------
    J : array_like
        Advance ratio V_A/(n D) [-], ≥ 0.
    table : array_like, shape (K, 4), optional
        Table as printed (default :data:`B4_70_PD10`).

    Returns
    -------
    tuple of numpy.ndarray
        K_T, K_Q [-].

    Raises
    ------
    ValueError
        If an advance ratio is negative or not finite.
    """
    j = np.asarray(J, dtype=float)
    if not np.all(np.isfinite(j)) or np.any(j < 0.0):
        raise ValueError(f"`J` must be finite and >= 0 [-], got {J!r}")
    beta = np.arctan2(j, 0.7 * math.pi)
    f = math.pi / 8.0 * (j * j + (0.7 * math.pi) ** 2)
    return thrust_coefficient_4q(beta, table) * f, torque_coefficient_4q(beta, table) * f
