"""Open-water thrust and torque of the Wageningen B-screw series (Oosterveld & van Oossanen 1975).

The B-series polynomials give the thrust and torque coefficients of a fixed-pitch propeller of the
series as functions of the advance ratio J, the pitch ratio P/D, the expanded area ratio
A_E/A_0 and the number of blades Z, at a Reynolds number of 2·10⁶::

    K_T = Σ_{n=1..39} C_n^T J^{s_n} (P/D)^{t_n} (A_E/A_0)^{u_n} Z^{v_n}
    K_Q = Σ_{n=1..47} C_n^Q J^{s_n} (P/D)^{t_n} (A_E/A_0)^{u_n} Z^{v_n}

with J = V_A/(n D), K_T = T/(ρ n² D⁴), K_Q = Q/(ρ n² D⁵) and the open-water efficiency
η_0 = J K_T/(2π K_Q). The same paper gives corrections ΔK_T, ΔK_Q for a Reynolds number above
2·10⁶, polynomials in J, P/D, A_E/A_0, Z and (log₁₀ Rn − 0.301), where Rn is the Reynolds number
of the blade section at 0.75 R: Rn = c_0.75 √(V_A² + (0.75 π n D)²)/ν.

:func:`fit_thrust_polynomial` reduces K_T(J) of one propeller to the quadratic
k_0 + k_1 J + k_2 J² that the MMG model takes (:class:`seahelm.vessels.mmg.MMGParams`
``k_0, k_1, k_2``), by least squares over the J range where K_T > 0.

The coefficient table
---------------------
The original paper (Oosterveld & van Oossanen 1975, Tables 1 and 2) was not at hand; the
coefficients here are the table as transcribed in two independent public sources, compared
number by number (86 K_T/K_Q coefficients with their exponents):

* A: ``mr-naval-architect/Resistance-Propulsion-Maneuvering``, files ``KT.csv``, ``KQ.csv``;
* B: ``jonny-dc/BEMT``, file ``Wageningen_KTKQ.m`` (which cites Oosterveld & van Oossanen 1975
  and also carries the Reynolds-number correction).

All 39 K_T terms agree exactly, exponents included. All 47 K_Q exponent sets agree; four K_Q
coefficients differ (term J^s (P/D)^t (A_E/A_0)^u Z^v as (s, t, u, v): A; B → taken):

* (1, 0, 2, 1): +0.00383637; −0.00383637 → −0.00383637 (B);
* (3, 6, 0, 2): −0.0000297; −0.0000297228 → −0.0000297228 (B);
* (3, 3, 2, 2): +0.0000869; +0.0000869243 → +0.0000869243 (B);
* (1, 6, 2, 2): +0.0000554; +0.0000554194 → +0.0000554194 (B).

The last three are A's rounding of the same number (B keeps the six significant figures of the
rest of the table). The sign of the (1,0,2,1) term is taken from B because every other stored
transcription seen agrees with B, among them the same repository as A in its own Python script
(``R&P&M Ship A_WORKING.py``, −0.00383637) and a C++ transcription that cites Bernitsas, Ray &
Kinley (1981); with −0.00383637 the polynomials reproduce Kuiper's (1992) chart readings and
worked example (see the tests).

The ΔK_T, ΔK_Q tables were compared between B and the same repository as A (its script): they
agree term by term except the ΔK_Q term J (P/D) (A_E/A_0) Z (log Rn − 0.301)², −0.00000088538
in A's script and −0.00000088528 in B; B's is taken, as a third transcription seen also has
it (the difference is below 10⁻⁷ in K_Q). A TypeScript transcription squares (log Rn − 0.301)
in the last ΔK_T term to match a spreadsheet (it says so); B's first power is taken, as in
every other transcription seen. With it, ΔK_T and ΔK_Q nearly vanish at Rn = 2·10⁶
(|ΔK_T| < 0.0004, |ΔK_Q| < 0.00003), as a correction to the 2·10⁶ data should.

Validity
--------
The polynomials were fitted to the series' models: 2 ≤ Z ≤ 7, 0.30 ≤ A_E/A_0 ≤ 1.05,
0.5 ≤ P/D ≤ 1.4, J ≥ 0 up to zero thrust (K_T ≥ 0). Outside these a
:class:`~seahelm.errors.ValidityRangeWarning` names the parameter, its value and the range (an
error under :class:`~seahelm.errors.strict_validity`). Not every (Z, A_E/A_0) pair in the box
was built: the polynomials interpolate between the models that were. The Reynolds correction
is for Rn > 2·10⁶ and is not applied below (a lower Rn warns: the series has no data there).

All functions broadcast their arguments together (batch axes lead) and return arrays (0-d for
scalar input).

References
----------
Oosterveld, M. W. C. & van Oossanen, P. (1975). Further computer-analyzed data of the
Wageningen B-screw series. International Shipbuilding Progress 22(251), 251–262. Tables 1, 2.
Bernitsas, M. M., Ray, D. & Kinley, P. (1981). K_T, K_Q and efficiency curves for the
Wageningen B-series propellers. Report 237, Dept. of Naval Architecture and Marine
Engineering, University of Michigan.
Kuiper, G. (1992). The Wageningen propeller series. MARIN Publication 92-001.
"""

from __future__ import annotations

import contextlib
import math
import warnings
from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import brentq

from .._validate import as_float_array
from ..errors import ParameterError, ValidityRangeWarning, warn_validity

__all__ = [
    "FORMULA",
    "VALIDITY_RANGES",
    "REFERENCE_REYNOLDS",
    "KT_TERMS",
    "KQ_TERMS",
    "DELTA_KT_TERMS",
    "DELTA_KQ_TERMS",
    "ThrustFit",
    "thrust_coefficient",
    "torque_coefficient",
    "open_water_efficiency",
    "zero_thrust_advance_ratio",
    "fit_thrust_polynomial",
]

FORMULA = "Wageningen B-series (Oosterveld & van Oossanen 1975)"
"""The formula's name, as validity warnings give it."""

VALIDITY_RANGES: dict[str, tuple[float, float]] = {
    "blades": (2.0, 7.0),
    "area_ratio": (0.30, 1.05),
    "pitch_ratio": (0.5, 1.4),
}
"""Ranges of Z, A_E/A_0 and P/D of the series' models (inclusive)."""

REFERENCE_REYNOLDS = 2.0e6
"""Reynolds number of the polynomials, Rn at 0.75 R [-]."""

# (C, s, t, u, v): C · J^s · (P/D)^t · (A_E/A_0)^u · Z^v  (Oosterveld & van Oossanen 1975, Table 1)
KT_TERMS: tuple[tuple[float, int, int, int, int], ...] = (
    (+0.00880496, 0, 0, 0, 0), (-0.204554, 1, 0, 0, 0), (+0.166351, 0, 1, 0, 0),
    (+0.158114, 0, 2, 0, 0), (-0.147581, 2, 0, 1, 0), (-0.481497, 1, 1, 1, 0),
    (+0.415437, 0, 2, 1, 0), (+0.0144043, 0, 0, 0, 1), (-0.0530054, 2, 0, 0, 1),
    (+0.0143481, 0, 1, 0, 1), (+0.0606826, 1, 1, 0, 1), (-0.0125894, 0, 0, 1, 1),
    (+0.0109689, 1, 0, 1, 1), (-0.133698, 0, 3, 0, 0), (+0.00638407, 0, 6, 0, 0),
    (-0.00132718, 2, 6, 0, 0), (+0.168496, 3, 0, 1, 0), (-0.0507214, 0, 0, 2, 0),
    (+0.0854559, 2, 0, 2, 0), (-0.0504475, 3, 0, 2, 0), (+0.010465, 1, 6, 2, 0),
    (-0.00648272, 2, 6, 2, 0), (-0.00841728, 0, 3, 0, 1), (+0.0168424, 1, 3, 0, 1),
    (-0.00102296, 3, 3, 0, 1), (-0.0317791, 0, 3, 1, 1), (+0.018604, 1, 0, 2, 1),
    (-0.00410798, 0, 2, 2, 1), (-0.000606848, 0, 0, 0, 2), (-0.0049819, 1, 0, 0, 2),
    (+0.0025983, 2, 0, 0, 2), (-0.000560528, 3, 0, 0, 2), (-0.00163652, 1, 2, 0, 2),
    (-0.000328787, 1, 6, 0, 2), (+0.000116502, 2, 6, 0, 2), (+0.000690904, 0, 0, 1, 2),
    (+0.00421749, 0, 3, 1, 2), (+0.0000565229, 3, 6, 1, 2), (-0.00146564, 0, 3, 2, 2),
)
"""The 39 K_T terms (C, s, t, u, v) of Oosterveld & van Oossanen (1975), Table 1."""

KQ_TERMS: tuple[tuple[float, int, int, int, int], ...] = (
    (+0.00379368, 0, 0, 0, 0), (+0.00886523, 2, 0, 0, 0), (-0.032241, 1, 1, 0, 0),
    (+0.00344778, 0, 2, 0, 0), (-0.0408811, 0, 1, 1, 0), (-0.108009, 1, 1, 1, 0),
    (-0.0885381, 2, 1, 1, 0), (+0.188561, 0, 2, 1, 0), (-0.00370871, 1, 0, 0, 1),
    (+0.00513696, 0, 1, 0, 1), (+0.0209449, 1, 1, 0, 1), (+0.00474319, 2, 1, 0, 1),
    (-0.00723408, 2, 0, 1, 1), (+0.00438388, 1, 1, 1, 1), (-0.0269403, 0, 2, 1, 1),
    (+0.0558082, 3, 0, 1, 0), (+0.0161886, 0, 3, 1, 0), (+0.00318086, 1, 3, 1, 0),
    (+0.015896, 0, 0, 2, 0), (+0.0471729, 1, 0, 2, 0), (+0.0196283, 3, 0, 2, 0),
    (-0.0502782, 0, 1, 2, 0), (-0.030055, 3, 1, 2, 0), (+0.0417122, 2, 2, 2, 0),
    (-0.0397722, 0, 3, 2, 0), (-0.00350024, 0, 6, 2, 0), (-0.0106854, 3, 0, 0, 1),
    (+0.00110903, 3, 3, 0, 1), (-0.000313912, 0, 6, 0, 1), (+0.0035985, 3, 0, 1, 1),
    (-0.00142121, 0, 6, 1, 1), (-0.00383637, 1, 0, 2, 1), (+0.0126803, 0, 2, 2, 1),
    (-0.00318278, 2, 3, 2, 1), (+0.00334268, 0, 6, 2, 1), (-0.00183491, 1, 1, 0, 2),
    (+0.000112451, 3, 2, 0, 2), (-0.0000297228, 3, 6, 0, 2), (+0.000269551, 1, 0, 1, 2),
    (+0.00083265, 2, 0, 1, 2), (+0.00155334, 0, 2, 1, 2), (+0.000302683, 0, 6, 1, 2),
    (-0.0001843, 0, 0, 2, 2), (-0.000425399, 0, 3, 2, 2), (+0.0000869243, 3, 3, 2, 2),
    (-0.0004659, 0, 6, 2, 2), (+0.0000554194, 1, 6, 2, 2),
)
"""The 47 K_Q terms (C, s, t, u, v) of Oosterveld & van Oossanen (1975), Table 1."""

# (C, s, t, u, v, w): C · J^s · (P/D)^t · (A_E/A_0)^u · Z^v · (log10 Rn − 0.301)^w  (Table 2)
DELTA_KT_TERMS: tuple[tuple[float, int, int, int, int, int], ...] = (
    (+0.000353485, 0, 0, 0, 0, 0), (-0.00333758, 2, 0, 1, 0, 0),
    (-0.00478125, 1, 1, 1, 0, 0), (+0.000257792, 2, 0, 1, 0, 2),
    (+0.0000643192, 2, 6, 0, 0, 1), (-0.0000110636, 2, 6, 0, 0, 2),
    (-0.0000276305, 2, 0, 1, 1, 2), (+0.0000954, 1, 1, 1, 1, 1),
    (+0.0000032049, 1, 3, 1, 2, 1),
)
"""ΔK_T for Rn > 2·10⁶: terms (C, s, t, u, v, w), Oosterveld & van Oossanen (1975), Table 2."""

DELTA_KQ_TERMS: tuple[tuple[float, int, int, int, int, int], ...] = (
    (-0.000591412, 0, 0, 0, 0, 0), (+0.00696898, 0, 1, 0, 0, 0),
    (-0.0000666654, 0, 6, 0, 1, 0), (+0.0160818, 0, 0, 2, 0, 0),
    (-0.000938091, 0, 1, 0, 0, 1), (-0.00059593, 0, 2, 0, 0, 1),
    (+0.0000782099, 0, 2, 0, 0, 2), (+0.0000052199, 2, 0, 1, 1, 1),
    (-0.00000088528, 1, 1, 1, 1, 2), (+0.0000230171, 0, 6, 0, 1, 1),
    (-0.00000184341, 0, 6, 0, 1, 2), (-0.00400252, 0, 0, 2, 0, 1),
    (+0.000220915, 0, 0, 2, 0, 2),
)
"""ΔK_Q for Rn > 2·10⁶: terms (C, s, t, u, v, w), Oosterveld & van Oossanen (1975), Table 2."""


def _fmt(values: np.ndarray) -> str:
    v = np.unique(np.asarray(values, dtype=float).ravel())
    return ", ".join(f"{x:.4g}" for x in v[:4]) + (" ..." if v.size > 4 else "")


def _propeller(pitch_ratio: ArrayLike, area_ratio: ArrayLike, blades: ArrayLike,
               strict: bool | None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """P/D, A_E/A_0, Z as float arrays: refused if non-physical, warned outside the series."""
    p = as_float_array("pitch_ratio", pitch_ratio, "-")
    a = as_float_array("area_ratio", area_ratio, "-")
    z = as_float_array("blades", blades, "-")
    for name, value in (("pitch_ratio", p), ("area_ratio", a)):
        if np.any(value <= 0):
            raise ParameterError(f"must be > 0 [-], got {_fmt(value[value <= 0])}",
                                 field=name, unit="-", value=value)
    if np.any((z < 2) | (z != np.round(z))):
        bad = z[(z < 2) | (z != np.round(z))]
        raise ParameterError(f"must be an integer number of blades >= 2 [-], got {_fmt(bad)}",
                             field="blades", unit="-", value=blades)
    problems = []
    for name, value in (("blades", z), ("area_ratio", a), ("pitch_ratio", p)):
        low, high = VALIDITY_RANGES[name]
        bad = (value < low) | (value > high)
        if np.any(bad):
            problems.append(f"`{name}` = {_fmt(value[bad])} outside the series' range "
                            f"{low:g} <= {name} <= {high:g} [-]")
    if problems:
        warn_validity(f"{FORMULA} used outside its validity range: " + "; ".join(problems),
                      strict=strict, stacklevel=5)
    return p, a, z


def _advance_ratio(J: ArrayLike) -> np.ndarray:
    j = as_float_array("J", J, "-")
    if np.any(j < 0):
        raise ParameterError(f"must be >= 0 [-] (ahead, positive thrust), got {_fmt(j[j < 0])}",
                             field="J", unit="-", value=J)
    return j


def _log_reynolds(reynolds: ArrayLike | None, strict: bool | None) -> np.ndarray | None:
    """log₁₀ Rn − 0.301 where Rn > 2·10⁶ (NaN elsewhere: no correction), or None."""
    if reynolds is None:
        return None
    rn = as_float_array("reynolds", reynolds, "-")
    if np.any(rn <= 0):
        raise ParameterError(f"must be > 0 [-], got {_fmt(rn[rn <= 0])}", field="reynolds",
                             unit="-", value=reynolds)
    low = rn < REFERENCE_REYNOLDS
    if np.any(low):
        warn_validity(f"{FORMULA}: `reynolds` = {_fmt(rn[low])} below the series' Rn = 2e6; "
                      "the Reynolds correction is for Rn > 2e6 and is not applied",
                      strict=strict, stacklevel=5)
    return np.where(rn > REFERENCE_REYNOLDS, np.log10(rn) - 0.301, np.nan)


def _polynomial(terms: tuple, j: np.ndarray, p: np.ndarray, a: np.ndarray, z: np.ndarray,
                x: np.ndarray | None = None) -> np.ndarray:
    out = np.zeros(np.broadcast_shapes(j.shape, p.shape, a.shape, z.shape,
                                       () if x is None else x.shape))
    for c, s, t, u, v, *w in terms:
        term = c * j**s * p**t * a**u * z**v
        out = out + (term * x ** w[0] if w else term)
    return out


def _evaluate(J: ArrayLike, pitch_ratio: ArrayLike, area_ratio: ArrayLike, blades: ArrayLike,
              reynolds: ArrayLike | None, strict: bool | None, *, torque: bool
              ) -> tuple[np.ndarray, np.ndarray | None]:
    """(K_T, K_Q or None), validated and warned once."""
    j = _advance_ratio(J)
    p, a, z = _propeller(pitch_ratio, area_ratio, blades, strict)
    x = _log_reynolds(reynolds, strict)
    kt = _polynomial(KT_TERMS, j, p, a, z)
    beyond = kt < -1e-9  # (zero thrust itself, to round-off, is inside)
    if np.any(beyond):
        warn_validity(f"{FORMULA} used outside its validity range: `J` = "
                      f"{_fmt(np.broadcast_to(j, kt.shape)[beyond])} beyond zero thrust "
                      "(K_T < 0); the polynomials hold for K_T >= 0", strict=strict,
                      stacklevel=4)
    kq = _polynomial(KQ_TERMS, j, p, a, z) if torque else None
    if x is not None:
        kt = kt + np.nan_to_num(_polynomial(DELTA_KT_TERMS, j, p, a, z, x), nan=0.0)
        if kq is not None:
            kq = kq + np.nan_to_num(_polynomial(DELTA_KQ_TERMS, j, p, a, z, x), nan=0.0)
    return kt, kq


def thrust_coefficient(J: ArrayLike, pitch_ratio: ArrayLike, area_ratio: ArrayLike,
                       blades: ArrayLike, reynolds: ArrayLike | None = None, *,
                       strict: bool | None = None) -> np.ndarray:
    """Thrust coefficient K_T = T/(ρ n² D⁴) of a B-series propeller [-].

    Oosterveld & van Oossanen (1975), Table 1 (39 terms), plus ΔK_T of Table 2 when a
    Reynolds number above 2·10⁶ is given.

    Parameters
    ----------
    J : array_like
        Advance ratio J = V_A/(n D) [-], ≥ 0.
    pitch_ratio : array_like
        Pitch ratio P/D at 0.7 R [-], > 0 (series 0.5 to 1.4).
    area_ratio : array_like
        Expanded blade area ratio A_E/A_0 [-], > 0 (series 0.30 to 1.05).
    blades : array_like
        Number of blades Z [-], an integer ≥ 2 (series 2 to 7).
    reynolds : array_like, optional
        Rn at 0.75 R [-]; above 2·10⁶ the correction ΔK_T is added (default: none, the
        series' Rn = 2·10⁶).
    strict : bool, optional
        Raise instead of warning outside the validity range (default: the global strict
        mode, :class:`~seahelm.errors.strict_validity`).

    Returns
    -------
    numpy.ndarray
        K_T [-], the arguments broadcast together.

    Raises
    ------
    ParameterError
        J < 0, P/D or A_E/A_0 ≤ 0, Z not an integer ≥ 2, Rn ≤ 0, or a NaN/inf anywhere.

    Warns
    -----
    ValidityRangeWarning
        Z, A_E/A_0 or P/D outside the series, K_T < 0 (J beyond zero thrust), Rn < 2·10⁶.
    """
    return _evaluate(J, pitch_ratio, area_ratio, blades, reynolds, strict, torque=False)[0]


def torque_coefficient(J: ArrayLike, pitch_ratio: ArrayLike, area_ratio: ArrayLike,
                       blades: ArrayLike, reynolds: ArrayLike | None = None, *,
                       strict: bool | None = None) -> np.ndarray:
    """Torque coefficient K_Q = Q/(ρ n² D⁵) of a B-series propeller [-].

    Oosterveld & van Oossanen (1975), Table 1 (47 terms), plus ΔK_Q of Table 2 when a
    Reynolds number above 2·10⁶ is given. Arguments, warnings and errors as
    :func:`thrust_coefficient`.

    Parameters
    ----------
    J, pitch_ratio, area_ratio, blades : array_like
        J [-], P/D [-], A_E/A_0 [-], Z [-] (see :func:`thrust_coefficient`).
    reynolds : array_like, optional
        Rn at 0.75 R [-]; above 2·10⁶ the correction ΔK_Q is added.
    strict : bool, optional
        Raise instead of warning outside the validity range.

    Returns
    -------
    numpy.ndarray
        K_Q [-], the arguments broadcast together.
    """
    return _evaluate(J, pitch_ratio, area_ratio, blades, reynolds, strict, torque=True)[1]


def open_water_efficiency(J: ArrayLike, pitch_ratio: ArrayLike, area_ratio: ArrayLike,
                          blades: ArrayLike, reynolds: ArrayLike | None = None, *,
                          strict: bool | None = None) -> np.ndarray:
    """Open-water efficiency η_0 = J K_T/(2π K_Q) of a B-series propeller [-].

    Parameters
    ----------
    J, pitch_ratio, area_ratio, blades : array_like
        J [-], P/D [-], A_E/A_0 [-], Z [-] (see :func:`thrust_coefficient`).
    reynolds : array_like, optional
        Rn at 0.75 R [-] (corrections above 2·10⁶).
    strict : bool, optional
        Raise instead of warning outside the validity range.

    Returns
    -------
    numpy.ndarray
        η_0 [-]; 0 at J = 0.
    """
    kt, kq = _evaluate(J, pitch_ratio, area_ratio, blades, reynolds, strict, torque=True)
    return np.asarray(J, dtype=float) * kt / (2.0 * math.pi * kq)


def zero_thrust_advance_ratio(pitch_ratio: float, area_ratio: float, blades: int,
                              reynolds: float | None = None, *,
                              strict: bool | None = None) -> float:
    """The advance ratio J at which K_T = 0 for one propeller [-].

    Parameters
    ----------
    pitch_ratio, area_ratio : float
        P/D [-], A_E/A_0 [-].
    blades : int
        Z [-].
    reynolds : float, optional
        Rn at 0.75 R [-].
    strict : bool, optional
        Raise instead of warning outside the validity range.

    Returns
    -------
    float
        J at zero thrust [-] (the first root of K_T(J) in (0, 3]).

    Raises
    ------
    ParameterError
        K_T has no root in (0, 3].
    """
    _propeller(pitch_ratio, area_ratio, blades, strict)  # (validated and warned once)

    def kt(j: ArrayLike) -> np.ndarray:
        with _quiet():
            return thrust_coefficient(j, pitch_ratio, area_ratio, blades, reynolds,
                                      strict=False)

    grid = np.linspace(0.0, 3.0, 301)
    values = kt(grid)
    if values[0] <= 0:
        raise ParameterError(f"{FORMULA}: K_T(0) = {values[0]:.4g} <= 0 for P/D = "
                             f"{pitch_ratio}, A_E/A_0 = {area_ratio}, Z = {blades}")
    sign = np.nonzero(values <= 0)[0]
    if sign.size == 0:
        raise ParameterError(f"{FORMULA}: K_T has no zero for J in (0, 3] (P/D = "
                             f"{pitch_ratio}, A_E/A_0 = {area_ratio}, Z = {blades})")
    k = int(sign[0])
    return float(brentq(lambda j: float(kt(j)), grid[k - 1], grid[k], xtol=1e-12))


@contextlib.contextmanager
def _quiet() -> Iterator[None]:
    """Validity warnings silenced inside (the caller has warned once already)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityRangeWarning)
        yield


@dataclass(frozen=True, kw_only=True)
class ThrustFit:
    """The quadratic K_T ≈ k_0 + k_1 J + k_2 J² of one propeller, fitted by least squares.

    Attributes
    ----------
    k_0, k_1, k_2 : float
        Coefficients [-] (the MMG model's ``k_0, k_1, k_2``).
    J_min, J_max : float
        The J range of the fit [-] (``J_max`` at most the zero-thrust J).
    max_error : float
        max |quadratic − polynomial| over the range [-] (absolute, in K_T).
    rms_error : float
        Root-mean-square of the same difference over the fitting grid [-].
    """

    k_0: float
    k_1: float
    k_2: float
    J_min: float
    J_max: float
    max_error: float
    rms_error: float

    def __call__(self, J: ArrayLike) -> np.ndarray:
        """K_T of the quadratic at J [-]."""
        j = np.asarray(J, dtype=float)
        return self.k_0 + self.k_1 * j + self.k_2 * j * j


def fit_thrust_polynomial(pitch_ratio: float, area_ratio: float, blades: int,
                          J_range: tuple[float, float] | None = None, *,
                          reynolds: float | None = None, points: int = 201,
                          strict: bool | None = None) -> ThrustFit:
    """Least-squares quadratic k_0 + k_1 J + k_2 J² to the B-series K_T(J) of one propeller.

    Parameters
    ----------
    pitch_ratio, area_ratio : float
        P/D [-], A_E/A_0 [-].
    blades : int
        Z [-].
    J_range : (float, float), optional
        (J_min, J_max) [-]; the upper end is cut at zero thrust (the polynomials hold for
        K_T ≥ 0). Default (0, J at K_T = 0), see :func:`zero_thrust_advance_ratio`.
    reynolds : float, optional
        Rn at 0.75 R [-] (corrections above 2·10⁶).
    points : int, optional
        Equally spaced J at which the fit is made and its error measured (default 201).
    strict : bool, optional
        Raise instead of warning outside the validity range.

    Returns
    -------
    ThrustFit
        k_0, k_1, k_2, the range and the fit's maximum and rms error.

    Raises
    ------
    ParameterError
        A non-scalar propeller, a J range that is not 0 <= J_min < J_max, fewer than 3 points.
    """
    for name, value in (("pitch_ratio", pitch_ratio), ("area_ratio", area_ratio),
                        ("blades", blades)):
        if np.ndim(value) != 0:
            raise ParameterError(f"must be one number (one propeller per fit), got {value!r}",
                                 field=name, unit="-", value=value)
    if int(points) < 3:
        raise ParameterError(f"must be >= 3, got {points!r}", field="points", value=points)
    j_zero = zero_thrust_advance_ratio(pitch_ratio, area_ratio, blades, reynolds,
                                       strict=strict)
    lo, hi = (0.0, j_zero) if J_range is None else (float(J_range[0]), float(J_range[1]))
    if not (0.0 <= lo < hi and math.isfinite(hi)):
        raise ParameterError(f"must be (J_min, J_max) with 0 <= J_min < J_max [-], got "
                             f"{J_range!r}", field="J_range", unit="-", value=J_range)
    hi = min(hi, j_zero)
    if hi <= lo:
        raise ParameterError(f"starts at or beyond zero thrust J = {j_zero:.4g} [-], got "
                             f"{J_range!r}", field="J_range", unit="-", value=J_range)
    j = np.linspace(lo, hi, int(points))
    with _quiet():
        kt = thrust_coefficient(j, pitch_ratio, area_ratio, blades, reynolds, strict=False)
    k2, k1, k0 = np.polyfit(j, kt, 2)
    err = k0 + k1 * j + k2 * j * j - kt
    return ThrustFit(k_0=float(k0), k_1=float(k1), k_2=float(k2), J_min=lo, J_max=float(hi),
                     max_error=float(np.max(np.abs(err))),
                     rms_error=float(np.sqrt(np.mean(err * err))))
