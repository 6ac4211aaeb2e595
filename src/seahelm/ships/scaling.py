"""Froude scaling of a ship to another length, steering gear included.

A ship and its geometrically similar copy λ = L_new/L_old times as long move alike at the same
Froude number Fn = U/√(g L): every non-dimensional coefficient stays, and each dimensional
quantity scales with the power of λ its dimension gives, with lengths L ∝ λ, times
T ∝ √λ and masses M ∝ ρ λ³:

=======================================  =================================================
quantity (unit)                          factor
=======================================  =================================================
length (m), area (m²), volume (m³)       λ, λ², λ³
time (s), e.g. T of Nomoto, a gear lag   √λ
speed (m/s)                              √λ
rate (1/s, rad/s): K, rps, rudder rate   1/√λ
mass (kg), force (N)                     λ³ · ρ_new/ρ_old
moment of inertia (kg·m²)                λ⁵ · ρ_new/ρ_old
density (kg/m³)                          ρ_new/ρ_old (1: same water)
angle (rad), non-dimensional (-, 1)      1
=======================================  =================================================

The rule is applied to every field of the ship's parameter set and of its steering gear from
the unit the field declares (:func:`seahelm.parameters.param`), so it holds for every
registered model: a unit is split into base units (m, s, kg; N = kg·m/s², kN = 10³ N) with
exponents, giving the factor λ^(a + b/2 + 3c) for m^a s^b kg^c. A unit the rule does not
know is an error naming the field and the unit. The main particulars scale as lengths, areas
and volumes.

The water density stays the ship's unless ``rho`` is given: a model tested in fresh water
(1000 kg/m³) scaled to a sea-going ship (1025 kg/m³) keeps its non-dimensional coefficients,
and its masses, forces and moments follow the density. What Froude scaling leaves out — the
Reynolds-number effects on friction, the propeller's open water curve and the wake — is not
corrected: the scaled ship is the model's coefficients at another size.
"""

from __future__ import annotations

import dataclasses
import math
import re
from typing import TYPE_CHECKING, Any

from ..errors import ParameterError
from ..parameters import Params

if TYPE_CHECKING:  # pragma: no cover
    from .ship import Ship

__all__ = ["FROUDE_RULE", "froude_exponents", "froude_factor", "scale_params", "scale_ship"]

#: The rule, as the provenance of a scaled ship states it.
FROUDE_RULE = ("Froude scaling at equal Froude number: lengths x lambda, areas x lambda^2, "
               "volumes x lambda^3, times and speeds x sqrt(lambda), rates and rps / "
               "sqrt(lambda), masses and forces x lambda^3, moments of inertia x lambda^5 "
               "(masses, forces and inertias also x rho_new/rho_old), angles and non-dimensional "
               "coefficients unchanged; each parameter by the unit it declares")

#: Base units and prefixed ones as exponents of (kg, m, s).
_BASE: dict[str, tuple[int, int, int]] = {
    "m": (0, 1, 0), "s": (0, 0, 1), "kg": (1, 0, 0), "N": (1, 1, -2), "kN": (1, 1, -2),
    "rad": (0, 0, 0),
    # "R": a length in propeller radii (the CPP ship's immersion), a ratio
    "R": (0, 0, 0),
}
_DIMENSIONLESS = {"-", "1", "rad", "R"}
_SUPERSCRIPTS = {"²": 2, "³": 3, "⁴": 4, "⁵": 5}
_FACTOR = re.compile(r"^([A-Za-z]+)(?:\^(-?\d+)|([²³⁴⁵]))?$")


def froude_exponents(unit: str, *, field: str = "unit") -> tuple[int, int, int]:
    """Exponents (kg, m, s) of a unit such as ``"kN·s²/m²"``, ``"kg/m³"``, ``"1/s"``.

    Parameters
    ----------
    unit : str
        The unit as a parameter field declares it.
    field : str, optional
        The field it belongs to (for the error message).

    Returns
    -------
    tuple of int

    Raises
    ------
    ParameterError
        For a unit the rule does not know (naming ``field`` and the unit).
    """
    text = unit.strip()
    if text in _DIMENSIONLESS:
        return (0, 0, 0)
    parts = text.split("/")
    if not text or len(parts) > 2:
        raise _unknown(field, unit)
    total = [0, 0, 0]
    for sign, part in zip((1, -1), parts):
        for token in re.split(r"[·*]", part.strip()):
            if token == "1" and sign == 1:
                continue
            match = _FACTOR.match(token.strip())
            if match is None or match.group(1) not in _BASE:
                raise _unknown(field, unit)
            power = int(match.group(2)) if match.group(2) else _SUPERSCRIPTS.get(
                match.group(3) or "", 1)
            for k, e in enumerate(_BASE[match.group(1)]):
                total[k] += sign * power * e
    return (total[0], total[1], total[2])


def _unknown(field: str, unit: str) -> ParameterError:
    return ParameterError(
        f"has the unit {unit!r}, which the Froude scaling rule does not know (it knows "
        f"products and quotients of {', '.join(sorted(_BASE))} with powers, and "
        f"{', '.join(repr(u) for u in sorted(_DIMENSIONLESS))} as non-dimensional)",
        field=field, unit=unit)


def froude_factor(unit: str, scale: float, density_ratio: float = 1.0, *,
                  field: str = "unit") -> float:
    """The factor a quantity of ``unit`` is multiplied by when the ship is ``scale`` = λ times
    as long: λ^(a + b/2 + 3c) (ρ_new/ρ_old)^c for kg^c m^a s^b.

    Parameters
    ----------
    unit : str
    scale : float
        λ = L_new/L_old [-].
    density_ratio : float, optional
        ρ_new/ρ_old [-] (default 1).
    field : str, optional
        For the error message.

    Returns
    -------
    float
    """
    c, a, b = froude_exponents(unit, field=field)
    return scale ** (a + 0.5 * b + 3 * c) * density_ratio ** c


def scale_params(params: Params, scale: float, density_ratio: float = 1.0, *,
                 prefix: str = "params") -> Params:
    """A parameter set Froude-scaled by λ = ``scale`` (each field by its declared unit).

    Parameters
    ----------
    params : Params
    scale : float
        λ = L_new/L_old [-].
    density_ratio : float, optional
        ρ_new/ρ_old [-] (default 1).
    prefix : str, optional
        Path of the parameter set in error messages.

    Returns
    -------
    Params
        Of the same type, validated again.
    """
    changes: dict[str, Any] = {}
    for info in params.info():
        factor = froude_factor(info.unit, scale, density_ratio, field=f"{prefix}.{info.name}")
        if factor == 1.0:
            continue
        value = getattr(params, info.name)
        changes[info.name] = (tuple(_round(v * factor) for v in value)
                              if isinstance(value, tuple) else _round(value * factor))
    return dataclasses.replace(params, **changes) if changes else params


def _densities(params: Params) -> list[str]:
    return [i.name for i in params.info() if froude_exponents(i.unit, field=i.name) == (1, -3, 0)]


#: Lengths a ship may be scaled to [m]: from the smallest free-running models (some 0.1 m)
#: to four times the longest ship built (458 m, the Seawise Giant). 1e9 m or 1 µm was a ship.
LENGTH_RANGE = (0.1, 2000.0)


def scale_ship(ship: "Ship", length: float, *, rho: float | None = None,
               name: str | None = None) -> "Ship":
    """The ship Froude-scaled to the length ``length`` (see the module docstring).

    Parameters
    ----------
    ship : Ship
    length : float
        New length L [m] (the ship's ``length``: its parameters', else its particulars').
    rho : float, optional
        Water density of the scaled ship [kg/m³] (default: the ship's); the model needs a
        density parameter for it.
    name : str, optional
        Name of the scaled ship (default ``"<name>-L<length>"``).

    Returns
    -------
    Ship
        With parameters, steering gear, particulars and test speed scaled, and the scaling
        (λ and the rule) in its provenance.

    Raises
    ------
    ParameterError
        If ``length`` or ``rho`` is not a finite number > 0 (``length`` in
        :data:`LENGTH_RANGE`), the ship has no length, ``rho``
        is given for a model without a density parameter, or a parameter's unit is not one
        the rule knows.
    """
    new_length = _positive("length", length, "m")
    low, high = LENGTH_RANGE
    if not low <= new_length <= high:
        raise ParameterError(f"must be in [{low:g}, {high:g}] [m] (a model basin's smallest "
                             f"models to the longest ships), got {length!r}", field="length",
                             unit="m", value=length)
    if ship.in_shallow_water:  # scale the deep-water ship, then put it in water λ times deeper
        deep = dataclasses.replace(ship, params=ship.deep_water_params or ship.params,
                                   water_depth=math.inf, deep_water_params=None)
        scaled = scale_ship(deep, length, rho=rho, name=name)
        return scaled.at_depth(ship.water_depth * new_length / ship.length)
    old_length = ship.length
    if not (math.isfinite(old_length) and old_length > 0):
        raise ParameterError(
            f": ship '{ship.name}' has no length to scale from (no parameter `length` in "
            f"{type(ship.params).__name__} and no particulars)", field="length", unit="m",
            value=length)
    lam = new_length / old_length
    ratio, density_note = 1.0, ""
    if rho is not None:
        new_rho = _positive("rho", rho, "kg/m³")
        fields = _densities(ship.params)
        if not fields:
            raise ParameterError(
                f": model '{ship.model.name}' has no water density parameter "
                f"({type(ship.params).__name__}), so there is no density to change",
                field="rho", unit="kg/m³", value=rho)
        old_rho = float(getattr(ship.params, fields[0]))
        ratio = new_rho / old_rho
        density_note = (f"; water density {old_rho:g} -> {new_rho:g} kg/m^3 (non-dimensional "
                        "coefficients kept; masses, forces and inertias follow the density)")
    params = scale_params(ship.params, lam, ratio)
    if "length" in params.field_names():  # exactly the length asked for (no rounding)
        params = dataclasses.replace(params, length=new_length)
    for f in _densities(params) if rho is not None else ():
        params = dataclasses.replace(params, **{f: float(rho)})
    what = (f"Froude-scaled from '{ship.name}' by lambda = {lam:.10g} (L = {old_length:g} m "
            f"-> {new_length:g} m){density_note}. {FROUDE_RULE}.")
    changes: dict[str, Any] = {
        "name": name or f"{ship.name}-L{new_length:g}",
        "params": params,
        "description": (f"{ship.description}; " if ship.description else "")
        + f"Froude-scaled to L = {new_length:g} m",
        "provenance": f"{what} Original: {ship.provenance}" if ship.provenance else what,
        "test_speed": (None if ship.design_speed is not None or ship.test_speed is None
                       else ship.test_speed * math.sqrt(lam)),
        "validity": ship.validity + (
            f"Froude-scaled by lambda = {lam:.6g}: Reynolds-number (scale) effects on "
            "friction, wake and propeller are not corrected",),
    }
    gear = ship.steering_gear
    if gear is not None:
        changes["steering_gear"] = dataclasses.replace(
            gear, params=scale_params(gear.params, lam, ratio, prefix="steering_gear.params"),
            provenance=f"{gear.provenance} Froude-scaled by lambda = {lam:.10g} (angles kept, "
            "rates / sqrt(lambda), time constants x sqrt(lambda)).".strip())
    if ship.particulars is not None:
        part = ship.particulars.scaled(lam, f"{ship.particulars.provenance} Froude-scaled by "
                                       f"lambda = {lam:.10g}.".strip())
        changes["particulars"] = dataclasses.replace(part, **{
            f.name: _round(getattr(part, f.name)) for f in dataclasses.fields(part)
            if isinstance(getattr(part, f.name), float)})
    return dataclasses.replace(ship, **changes)


def _round(value: float) -> float:
    """To 15 significant digits: 58 m, not 57.99999999999999 m (a relative change < 1e-15)."""
    return float(f"{value:.15g}")


def _positive(name: str, value: Any, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
            math.isfinite(value) and value > 0):
        raise ParameterError(f"must be a finite number > 0 [{unit}], got {value!r}",
                             field=name, unit=unit, value=value)
    return float(value)
