"""Sea-state tables of Sushchenko & Lutsko (2010): grade ↔ wave height, and μ, λ versus h3%.

Table 1 maps the sea-state grade (I–IX) to the range of the 3 %-exceedance wave height h3%.
Table 2 gives the Rakhmanin–Firsov correlation parameters μ (decay rate, 1/s) and λ
(resonance frequency, rad/s) — maximum, mean and minimum — for h3% = 1 … 10 m.

Table 2 as printed has two misprints (Sushchenko & Lutsko (2010), Table 2; see the seahelm
errata for this paper): every column follows h^(-1/2) within 2 % and μ_mean/λ_mean is
0.213–0.214 in every row except h3% = 4 m, so λ_mean(4 m) = 0.667 is a misprint for 0.867;
μ_min(1 m) = 0.138 breaks μ_min/λ_min = 0.150 of every other row, so it should read 0.188.
This module holds the corrected table (:data:`TABLE2`, :data:`CORRECTED_TABLE2`), the default
everywhere; the table as printed is the paper's reproduction,
:data:`seahelm.studies.sushchenko2010.PRINTED_TABLE2`. Every ``table`` argument takes a name of
:data:`TABLE2`, ``"printed"`` (:data:`PRINTED_TABLE2_VERSIONS`, resolved to that object on
first use) or a :class:`Table2Version` object.

References
----------
Sushchenko, O. A., & Lutsko, D. O. (2010). Modelling of external disturbances in
stabilisation and heading systems of marine vehicles (in Ukrainian). Tables 1 and 2.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from types import MappingProxyType

import numpy as np
from numpy.typing import ArrayLike

from .._validate import as_float_array, check_positive, lookup_name
from ..errors import ParameterError, warn_validity

__all__ = [
    "RAYLEIGH_VARIANCE_COEFFICIENT",
    "TABLE1",
    "TABLE2",
    "TABLE2_COLUMNS",
    "Table2Version",
    "CORRECTED_TABLE2",
    "PRINTED_TABLE2_VERSIONS",
    "LEVELS",
    "SeaStateParameters",
    "wave_variance",
    "sea_state_grade",
    "wave_height_range",
    "table2",
    "sea_state_parameters",
]

#: Coefficient 0.143 of D_r = 0.143 (h3%/2)² (Sushchenko & Lutsko (2010), text after eq. (4)).
#: For Rayleigh-distributed heights it is 4 / (8 ln(1/0.03)) = 0.1426.
RAYLEIGH_VARIANCE_COEFFICIENT: float = 0.143

_ROMAN = ("I", "II", "III", "IV", "V", "VI", "VII", "VIII", "IX")

#: Table 1: sea-state grade (1…9 for I…IX) → (lower, upper) bound of h3% [m]. A height on a
#: boundary belongs to the higher grade (lower bound inclusive); grade IX is open above.
TABLE1: Mapping[int, tuple[float, float]] = MappingProxyType(
    {
        1: (0.0, 0.25),
        2: (0.25, 0.75),
        3: (0.75, 1.25),
        4: (1.25, 2.0),
        5: (2.0, 3.5),
        6: (3.5, 6.0),
        7: (6.0, 8.5),
        8: (8.5, 11.0),
        9: (11.0, math.inf),
    }
)

#: Column names of Table 2 (μ in 1/s, λ in rad/s, μ/λ dimensionless).
TABLE2_COLUMNS: tuple[str, ...] = (
    "mu_max",
    "mu_mean",
    "mu_min",
    "lambda_max",
    "lambda_mean",
    "lambda_min",
    "mu_over_lambda",
)

# h3% [m], then the columns of TABLE2_COLUMNS, with the two misprints of the printed table
# corrected: λ_mean(4 m) = 0.867 (printed 0.667) and μ_min(1 m) = 0.188 (printed 0.138).
_CORRECTED = np.array(
    [
        [1, 0.56, 0.374, 0.188, 2.24, 1.745, 1.25, 0.215],
        [2, 0.394, 0.265, 0.136, 1.573, 1.239, 0.905, 0.214],
        [3, 0.316, 0.214, 0.111, 1.266, 1.003, 0.74, 0.213],
        [4, 0.274, 0.185, 0.096, 1.094, 0.867, 0.64, 0.213],
        [5, 0.246, 0.166, 0.086, 0.982, 0.777, 0.572, 0.213],
        [6, 0.224, 0.151, 0.078, 0.898, 0.709, 0.52, 0.213],
        [7, 0.207, 0.14, 0.072, 0.828, 0.654, 0.48, 0.214],
        [8, 0.194, 0.131, 0.068, 0.774, 0.612, 0.45, 0.214],
        [9, 0.184, 0.123, 0.063, 0.734, 0.578, 0.422, 0.213],
        [10, 0.177, 0.119, 0.061, 0.706, 0.555, 0.404, 0.214],
    ],
    dtype=float,
)
_CORRECTED.setflags(write=False)


@dataclasses.dataclass(frozen=True, eq=False)
class Table2Version:
    """One version of Table 2: its name, its rows and what it is.

    Parameters
    ----------
    name : str
        Name of the version (reported in :attr:`SeaStateParameters.table`).
    rows : numpy.ndarray, shape (n, 8)
        h3% [m] (increasing) followed by the columns :data:`TABLE2_COLUMNS`; stored read-only.
    note : str, optional
        One line on where the version comes from.
    """

    name: str
    rows: np.ndarray
    note: str = ""

    def __post_init__(self) -> None:
        rows = np.array(self.rows, dtype=float)
        if rows.ndim != 2 or rows.shape[1] != 1 + len(TABLE2_COLUMNS) or rows.shape[0] < 2:
            raise ParameterError(f"Table 2 `rows` must have shape (n >= 2, "
                                 f"{1 + len(TABLE2_COLUMNS)}), got {rows.shape}")
        if not np.all(np.isfinite(rows)) or np.any(np.diff(rows[:, 0]) <= 0):
            raise ParameterError("Table 2 `rows` must be finite with increasing h3%")
        rows.setflags(write=False)
        object.__setattr__(self, "rows", rows)


#: Table 2 with its two misprints corrected (the default of every ``table`` argument).
CORRECTED_TABLE2 = Table2Version(
    "corrected", _CORRECTED,
    "corrected: lambda_mean(4 m) 0.667 -> 0.867 and mu_min(1 m) 0.138 -> 0.188 (misprints)")

_VERSIONS: Mapping[str, Table2Version] = MappingProxyType({"corrected": CORRECTED_TABLE2})
#: Table 2 by name: ``"corrected"``, a read-only array of shape (10, 8): h3% [m] followed by
#: :data:`TABLE2_COLUMNS`. The printed table is the study's,
#: :data:`seahelm.studies.sushchenko2010.PRINTED_TABLE2`.
TABLE2: Mapping[str, np.ndarray] = MappingProxyType({k: v.rows for k, v in _VERSIONS.items()})

#: Which Table 2 columns a ``level`` selects: (μ column, λ column).
LEVELS: Mapping[str, tuple[str, str]] = MappingProxyType(
    {
        "max": ("mu_max", "lambda_max"),
        "mean": ("mu_mean", "lambda_mean"),
        "min": ("mu_min", "lambda_min"),
    }
)


def _lookup(registry: Mapping[str, object], name: str, what: str) -> object:
    return lookup_name(what, registry, name, error=ParameterError, quoted=True)


def wave_variance(h3: ArrayLike) -> np.ndarray | float:
    """Variance of the wave ordinate D_r = 0.143 (h3%/2)² [m²].

    Parameters
    ----------
    h3 : array_like
        Height of waves of 3 % exceedance probability h3% [m], > 0.

    Returns
    -------
    float or numpy.ndarray
        D_r [m²], same shape as ``h3``.

    Raises
    ------
    ParameterError
        If ``h3`` is not finite and > 0.

    Notes
    -----
    Sushchenko & Lutsko (2010), formula after eq. (4). For Rayleigh-distributed wave heights
    the exact coefficient is 4 / (8 ln(1/0.03)) = 0.1426; the paper's rounded 0.143 is kept.
    """
    h = as_float_array("h3", h3, "m")
    check_positive("h3", h, "m")
    out = RAYLEIGH_VARIANCE_COEFFICIENT * (h / 2.0) ** 2
    return float(out) if out.ndim == 0 else out


def sea_state_grade(h3: ArrayLike) -> np.ndarray | int:
    """Sea-state grade (1…9 for I…IX) of a 3 %-exceedance wave height, by Table 1.

    Parameters
    ----------
    h3 : array_like
        h3% [m], > 0. A height on a boundary belongs to the higher grade.

    Returns
    -------
    int or numpy.ndarray of int
        Grade 1…9.

    Raises
    ------
    ParameterError
        If ``h3`` is not finite and > 0.
    """
    h = as_float_array("h3", h3, "m")
    check_positive("h3", h, "m")
    lows = np.array([TABLE1[k][0] for k in sorted(TABLE1)][1:])
    grade = np.searchsorted(lows, h, side="right") + 1
    return int(grade) if grade.ndim == 0 else grade


def wave_height_range(grade: int | str) -> tuple[float, float]:
    """Range [lower, upper) of h3% [m] for a sea-state grade (Table 1).

    Parameters
    ----------
    grade : int or str
        1…9 or a Roman numeral "I"…"IX".

    Returns
    -------
    tuple of float
        (lower, upper) [m]; upper is ``inf`` for grade IX.

    Raises
    ------
    ParameterError
        If ``grade`` is not one of the nine grades.
    """
    key = _ROMAN.index(grade.upper()) + 1 if isinstance(grade, str) and grade.upper() in _ROMAN else grade
    if isinstance(key, bool) or not isinstance(key, (int, np.integer)) or int(key) not in TABLE1:
        raise ParameterError(f"`grade` must be 1…9 or I…IX, got {grade!r}")
    return TABLE1[int(key)]


#: Table 2 as printed, by name: reachable wherever a version is named (``table="printed"``)
#: though it lives with the paper's reproduction, as a ``"module:attribute"`` reference
#: resolved on first use (:func:`seahelm.registry.lookup`).
PRINTED_TABLE2_VERSIONS: Mapping[str, str] = MappingProxyType({
    "printed": "seahelm.studies.sushchenko2010:PRINTED_TABLE2",
})


def _table_version(table: str | Table2Version) -> Table2Version:
    """The Table 2 version named ``table`` (or ``table`` itself)."""
    if isinstance(table, Table2Version):
        return table
    if isinstance(table, str) and table in PRINTED_TABLE2_VERSIONS:
        from ..registry import lookup

        return lookup("Table 2 version", PRINTED_TABLE2_VERSIONS, table, Table2Version)
    return lookup_name("Table 2 version", _VERSIONS, table, error=ParameterError, quoted=True,
                       valid=(*_VERSIONS, *PRINTED_TABLE2_VERSIONS), suffix=" or a Table2Version")


def table2(name: str | Table2Version = "corrected") -> dict[str, np.ndarray]:
    """Table 2 as a dict of columns: ``"h3"`` [m] and :data:`TABLE2_COLUMNS`.

    Parameters
    ----------
    name : str or Table2Version
        A name of :data:`TABLE2` (``"corrected"``: the two misprints fixed,
        λ_mean(4 m) = 0.867, μ_min(1 m) = 0.188) or a version object, e.g. the table as
        printed, :data:`seahelm.studies.sushchenko2010.PRINTED_TABLE2`.

    Raises
    ------
    ParameterError
        For an unknown table name (the message lists the valid ones).
    """
    arr = _table_version(name).rows
    cols = ("h3",) + TABLE2_COLUMNS
    return {c: arr[:, i].copy() for i, c in enumerate(cols)}


@dataclasses.dataclass(frozen=True, kw_only=True)
class SeaStateParameters:
    """Rakhmanin–Firsov parameters of a sea state (Sushchenko & Lutsko (2010), Tables 1-2).

    Attributes
    ----------
    h3 : float
        Height of 3 %-exceedance waves h3% [m].
    grade : int
        Sea-state grade 1…9 (Table 1).
    variance : float
        Wave-ordinate variance D_r = 0.143 (h3%/2)² [m²].
    decay_rate : float
        μ [1/s], interpolated in Table 2.
    resonance_frequency : float
        λ [rad/s], interpolated in Table 2.
    level : str
        Table 2 column used: "max", "mean" or "min".
    table : str
        Name of the Table 2 version used (``"corrected"``, or e.g. ``"printed"``).
    extrapolated : bool
        True if h3% lies outside 1…10 m and the h^(-1/2) law was used.
    """

    h3: float
    grade: int
    variance: float
    decay_rate: float
    resonance_frequency: float
    level: str = "mean"
    table: str = "corrected"
    extrapolated: bool = False


def check_table_height(name: str, h3: float, hint: str = "") -> None:
    """Refuse a wave height outside Table 2 (1…10 m) naming the parameter.

    Parameters
    ----------
    name : str
        The parameter as the user wrote it (e.g. ``"h3"``, ``"--h3"``).
    h3 : float
        Height of 3 %-exceedance waves h3% [m].
    hint : str, optional
        What the caller offers instead, appended after a semicolon (e.g. how to extrapolate).

    Raises
    ------
    ParameterError
        If ``h3`` lies outside Table 2.
    """
    hs = table2()["h3"]
    lo, hi = float(hs[0]), float(hs[-1])
    if not lo <= float(h3) <= hi:
        raise ParameterError(
            f"`{name}` must be in [{lo:g}, {hi:g}] [m] (Sushchenko & Lutsko (2010), Table 2), "
            f"got {h3!r}" + (f"; {hint}" if hint else ""))


def sea_state_parameters(
    h3: float,
    *,
    level: str = "mean",
    table: str | Table2Version = "corrected",
    extrapolate: bool = False,
) -> SeaStateParameters:
    """D_r, μ and λ for a wave height h3% by linear interpolation between the rows of Table 2.

    Parameters
    ----------
    h3 : float
        Height of 3 %-exceedance waves h3% [m]; Table 2 covers 1 ≤ h3% ≤ 10 m.
    level : {"max", "mean", "min"}
        Which Table 2 columns to use for μ and λ.
    table : str or Table2Version
        Table 2 version: a name of :data:`TABLE2` or a version object. The default
        ``"corrected"`` fixes the two misprints of the paper (λ_mean(4 m) 0.667 → 0.867,
        μ_min(1 m) 0.138 → 0.188); :data:`seahelm.studies.sushchenko2010.PRINTED_TABLE2`
        reproduces it.
    extrapolate : bool
        Outside 1…10 m, raise (default) or extrapolate with μ, λ ∝ h^(-1/2) fitted to the
        nearest row (every column follows this law within 2 %), warning with
        :class:`~seahelm.errors.ValidityRangeWarning`.

    Returns
    -------
    SeaStateParameters

    Raises
    ------
    ParameterError
        If ``h3`` is not finite and > 0, lies outside Table 2 (1…10 m) without
        ``extrapolate``, or ``level``/``table`` is unknown.

    Notes
    -----
    Sushchenko & Lutsko (2010), Table 2 and D_r = 0.143 (h3%/2)².
    """
    h = float(as_float_array("h3", h3, "m"))
    check_positive("h3", h, "m")
    mu_col, lam_col = _lookup(LEVELS, level, "level")  # type: ignore[misc]
    version = _table_version(table)
    cols = table2(version)
    hs = cols["h3"]
    lo, hi = float(hs[0]), float(hs[-1])
    outside = h < lo or h > hi
    if not extrapolate:
        check_table_height("h3", h, "pass extrapolate=True to use the h^(-1/2) law")
    if outside:
        warn_validity(
            f"h3 = {h:g} m is outside Table 2 (1…10 m); μ and λ extrapolated with h^(-1/2)"
        )
        i = 0 if h < lo else -1
        scale = math.sqrt(float(hs[i]) / h)
        mu = float(cols[mu_col][i]) * scale
        lam = float(cols[lam_col][i]) * scale
    else:
        mu = float(np.interp(h, hs, cols[mu_col]))
        lam = float(np.interp(h, hs, cols[lam_col]))
    return SeaStateParameters(
        h3=h,
        grade=int(sea_state_grade(h)),
        variance=float(wave_variance(h)),
        decay_rate=mu,
        resonance_frequency=lam,
        level=level,
        table=version.name,
        extrapolated=outside,
    )
