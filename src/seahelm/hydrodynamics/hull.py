"""The hull's main particulars as the empirical formulas take them, and their validity checks.

:class:`HullParticulars` holds what every regression of this package reads (L, B, T fore and
aft, C_b, ∇, x_G) in SI units, validated once: a value that is not physical (B ≥ L, C_b outside
(0.3, 1), a trim as large as the draft, …) raises :class:`~seahelm.errors.ParameterError`
naming the field, its unit and the value. :func:`check_ranges` is the one place a formula says
that it is used outside the data it was fitted to (a
:class:`~seahelm.errors.ValidityRangeWarning` naming the formula, the parameter and the range;
an error under :class:`~seahelm.errors.strict_validity`). :class:`Coefficient` is an estimated
value with the formula that produced it.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping

import numpy as np

from ..errors import ParameterError, warn_validity

__all__ = ["HullParticulars", "Coefficient", "check_ranges"]


@dataclasses.dataclass(frozen=True)
class Coefficient:
    """An estimated coefficient: its value and where it comes from.

    Attributes
    ----------
    value : float
        The value (the unit of the parameter it estimates).
    source : str
        The formula and its reference, e.g. ``"Kijima et al. (1990): Y'_v = -(π/2 k + 1.4 C_b
        B/L)(1 + 0.67 τ/d)"``.
    """

    value: float
    source: str


def _number(name: str, value: object, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
        raise ParameterError(f"must be a number [{unit}], got {value!r}", field=name, unit=unit,
                             value=value)
    x = float(value)
    if not math.isfinite(x):
        raise ParameterError(f"must be finite [{unit}], got {x!r}", field=name, unit=unit,
                             value=x)
    return x


@dataclasses.dataclass(frozen=True, kw_only=True)
class HullParticulars:
    """Main particulars of a single hull for the empirical estimates (SI units).

    Attributes
    ----------
    length : float
        Length between perpendiculars L_pp [m].
    beam : float
        Moulded breadth B [m] (0 < B < L).
    draft : float
        Mean draught d = (d_a + d_f)/2 [m].
    block_coefficient : float
        C_b = ∇/(L B d) [-], in (0.3, 1).
    trim : float
        Trim τ = d_a − d_f [m], positive by the stern (Kijima et al. 1990); |τ| < d.
    displacement : float or None
        Displacement volume ∇ [m³] (default C_b L B d; given, it must agree with C_b within
        10 %).
    x_G : float
        Centre of gravity forward of midship [m] (|x_G| < L/2).
    """

    length: float
    beam: float
    draft: float
    block_coefficient: float
    trim: float = 0.0
    displacement: float | None = None
    x_G: float = 0.0

    def __post_init__(self) -> None:
        for name, unit in (("length", "m"), ("beam", "m"), ("draft", "m"),
                           ("block_coefficient", "-"), ("trim", "m"), ("x_G", "m")):
            object.__setattr__(self, name, _number(name, getattr(self, name), unit))
        for name in ("length", "beam", "draft"):
            if not getattr(self, name) > 0:
                raise ParameterError(f"must be > 0 [m], got {getattr(self, name)!r}",
                                     field=name, unit="m", value=getattr(self, name))
        if not self.beam < self.length:
            raise ParameterError(
                f"must be less than the length {self.length!r} [m], got {self.beam!r}",
                field="beam", unit="m", value=self.beam)
        if not self.draft < self.length:
            raise ParameterError(
                f"must be less than the length {self.length!r} [m], got {self.draft!r}",
                field="draft", unit="m", value=self.draft)
        if not 0.3 < self.block_coefficient < 1.0:
            raise ParameterError(f"must be in (0.3, 1) [-], got {self.block_coefficient!r}",
                                 field="block_coefficient", unit="-",
                                 value=self.block_coefficient)
        if not abs(self.trim) < self.draft:
            raise ParameterError(
                f"must be smaller in size than the draft {self.draft!r} [m], got {self.trim!r}",
                field="trim", unit="m", value=self.trim)
        if not abs(self.x_G) < 0.5 * self.length:
            raise ParameterError(
                f"must lie within ±L/2 = ±{0.5 * self.length:g} [m], got {self.x_G!r}",
                field="x_G", unit="m", value=self.x_G)
        if self.displacement is not None:
            vol = _number("displacement", self.displacement, "m³")
            if not vol > 0:
                raise ParameterError(f"must be > 0 [m³], got {vol!r}", field="displacement",
                                     unit="m³", value=vol)
            box = self.length * self.beam * self.draft
            if not 0.9 < vol / (box * self.block_coefficient) < 1.1:
                raise ParameterError(
                    f"is {vol!r} [m³] but C_b L B d = {box * self.block_coefficient:.6g} "
                    f"[m³]: the two disagree by more than 10 %; give one of them",
                    field="displacement", unit="m³", value=vol)
            object.__setattr__(self, "displacement", vol)

    @property
    def volume(self) -> float:
        """Displacement volume ∇ [m³] (the given one, else C_b L B d)."""
        if self.displacement is not None:
            return float(self.displacement)
        return self.block_coefficient * self.length * self.beam * self.draft

    @property
    def mass_nd(self) -> float:
        """Non-dimensional mass m' = ∇/(½ L² d) [-] (MMG: m / (½ρ L² d))."""
        return self.volume / (0.5 * self.length ** 2 * self.draft)

    @property
    def k(self) -> float:
        """Aspect ratio of the hull as a wing, k = 2d/L [-] (Kijima et al. 1990)."""
        return 2.0 * self.draft / self.length

    @property
    def trim_ratio(self) -> float:
        """τ' = τ/d [-]."""
        return self.trim / self.draft

    @property
    def cb_b_over_l(self) -> float:
        """C_b B/L [-], the fullness parameter of most regressions."""
        return self.block_coefficient * self.beam / self.length


def check_ranges(formula: str, values: Mapping[str, tuple[float, float, float]], *,
                 strict: bool | None = None, stacklevel: int = 3) -> None:
    """Warn once, naming every parameter outside the data range of ``formula``.

    Parameters
    ----------
    formula : str
        The formula and its reference ("Kijima et al. (1990) hull derivatives").
    values : mapping of str to (value, low, high)
        Each parameter's value and its data range (inclusive).
    strict : bool, optional
        Raise :class:`~seahelm.errors.ParameterError` instead of warning (default: the global
        :class:`~seahelm.errors.strict_validity`).
    stacklevel : int, optional
        Passed on to :func:`warnings.warn`.
    """
    problems = [f"{name} = {value:.4g} outside {low:g}..{high:g}"
                for name, (value, low, high) in values.items()
                if not low <= value <= high]
    if problems:
        warn_validity(f"{formula} used outside the range of its data: " + "; ".join(problems),
                      strict=strict, stacklevel=stacklevel + 1)
