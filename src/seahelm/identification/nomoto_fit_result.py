"""The result of a Nomoto identification (:func:`seahelm.identification.nomoto_fit.fit_nomoto`): the
estimates with their Laplace covariance, intervals, the evidence for what is not identified, and
the ship of the identified model (:func:`nomoto_ship`)."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from ..errors import ParameterError
from .fit_result import FitResult, unidentifiable

__all__ = ["NomotoFit", "nomoto_ship"]

_NAMES = {1: ("gain", "time_constant", "rudder_offset"),
          2: ("gain", "t1", "t2", "t3", "rudder_offset")}
_UNITS = {"gain": "1/s", "time_constant": "s", "t1": "s", "t2": "s", "t3": "s",
          "rudder_offset": "rad"}
_SYMBOLS = {"gain": "K", "time_constant": "T", "t1": "T_1", "t2": "T_2", "t3": "T_3",
            "rudder_offset": "δ_0"}



@dataclasses.dataclass(frozen=True)
class NomotoFit(FitResult):
    """A Nomoto model identified from records (see the module docstring).

    Attributes
    ----------
    order : int
        1 or 2.
    names : tuple of str
        Parameter names (``gain``, ``time_constant`` | ``t1``, ``t2``, ``t3``,
        ``rudder_offset``).
    values : ndarray
        Estimates (SI units, radians).
    covariance : ndarray
        Laplace covariance of the estimates.
    dof : int
        Degrees of freedom of the residuals (samples − all fitted parameters).
    residual_std : float
        σ of the output residuals [rad] (or [rad/s] when fitted on the yaw rate).
    output : str
        ``"heading"`` or ``"yaw_rate"``.
    records : tuple of str
        The records fitted.
    initial_states : ndarray
        Each record's fitted initial ψ, r (and ṙ), shape (records, 2 or 3).
    equation_error : ndarray
        The equation-error start (same parameters as ``values``).
    condition_number : float
        Of the scaled normal matrix JᵀJ (columns scaled to unit norm).
    residuals : tuple of ndarray
        The output residuals of each record at its sample times.
    bootstrap : ndarray or None
        Bootstrap estimates, shape (N, parameters), when asked for.
    speed : float or None
        Ship speed U [m/s] the model holds at, where given.
    """

    order: int
    names: tuple[str, ...]
    values: np.ndarray
    covariance: np.ndarray
    dof: int
    residual_std: float
    output: str
    records: tuple[str, ...]
    initial_states: np.ndarray
    equation_error: np.ndarray
    condition_number: float
    residuals: tuple[np.ndarray, ...]
    bootstrap: np.ndarray | None = None
    speed: float | None = None

    @property
    def interval_dof(self) -> int:
        """Student-t intervals (Laplace) with the residuals' degrees of freedom (at least 1):
        :meth:`~seahelm.identification.fit_result.FitResult.confidence_intervals`."""
        return max(self.dof, 1)

    def bootstrap_intervals(self, level: float = 0.95) -> np.ndarray | None:
        """Percentile intervals of the bootstrap refits (None without a bootstrap).

        Parameters
        ----------
        level : float
            Confidence level in (0, 1).

        Returns
        -------
        ndarray or None
        """
        if self.bootstrap is None:
            return None
        q = 50.0 * (1.0 - level)
        return np.percentile(self.bootstrap, [q, 100.0 - q], axis=0).T

    def unidentifiable(self) -> dict[str, str]:
        """The parameters that are not identified, each with the evidence (the rudder offset
        may be near zero: only its correlations count)."""
        return unidentifiable(self.names, self.values, self.covariance, units=_UNITS,
                              value_test_exempt=("rudder_offset",))

    @property
    def residual_autocorrelation(self) -> float:
        """Lag-one autocorrelation of the residuals (pooled over the records): near 1 means
        model mismatch or coloured noise, and Laplace intervals that are too narrow."""
        num = den = 0.0
        for e in self.residuals:
            e = e - e.mean()
            num += float(np.dot(e[1:], e[:-1]))
            den += float(np.dot(e, e))
        return num / den if den > 0 else 0.0

    def as_dict(self, level: float = 0.95) -> dict[str, Any]:
        """Plain data (for JSON): estimates, units, standard errors, intervals, evidence.

        Parameters
        ----------
        level : float
            Confidence level of the intervals.

        Returns
        -------
        dict
        """
        ci = self.confidence_intervals(level)
        bad = self.unidentifiable()
        params = []
        for i, name in enumerate(self.names):
            row = {"name": name, "symbol": _SYMBOLS[name], "unit": _UNITS[name],
                   "identified": name not in bad}
            if name in bad:
                row["evidence"] = bad[name]
            else:
                row.update(value=float(self.values[i]),
                           standard_error=float(self.standard_errors[i]),
                           ci_low=float(ci[i, 0]), ci_high=float(ci[i, 1]))
            row["equation_error_start"] = float(self.equation_error[i])
            params.append(row)
        return {"model": f"nomoto{self.order}", "output": self.output,
                "records": list(self.records), "confidence_level": level,
                "parameters": params, "residual_std": self.residual_std,
                "degrees_of_freedom": self.dof, "condition_number": self.condition_number,
                "residual_autocorrelation": self.residual_autocorrelation,
                "correlation": np.round(self.correlation, 6).tolist()}


def nomoto_ship(fit: NomotoFit, *, name: str, speed: float, length: float,
                max_rudder: float = math.radians(35.0),
                rudder_rate: float = math.radians(65.0 / 28.0), level: float = 0.95) -> Any:
    """A ship of the identified model (``nomoto1`` or ``nomoto2``) with a rudder servo.

    Every parameter's source is the fit (value, standard error, interval); the provenance
    holds the records, the rudder offset δ_0 (not a model parameter: a steady rudder
    disturbance) and the covariance of the estimates.

    Parameters
    ----------
    fit : NomotoFit
    name : str
        The ship's name.
    speed : float
        U [m/s] of the records (the model holds at it).
    length : float
        L [m] (plots, scaling, the IMO check's L/V).
    max_rudder, rudder_rate : float, optional
        Steering gear [rad], [rad/s] (default ±35°, IMO's minimum 2.32°/s).
    level : float, optional
        Confidence level of the intervals written.

    Returns
    -------
    Ship

    Raises
    ------
    ParameterError
        An unidentifiable model parameter (it cannot go into a ship file as a number), a bad
        speed or length.
    """
    from ..actuators.servo import ServoParams
    from ..ships import Ship, SteeringGear
    from ..vessels.nomoto import Nomoto1Params, Nomoto2Params

    bad = {k: v for k, v in fit.unidentifiable().items() if k != "rudder_offset"}
    if bad:
        raise ParameterError(
            "the records do not identify " + "; ".join(f"{_SYMBOLS[k]} ({v})" for k, v in
                                                        bad.items())
            + f": no ship file of nomoto{fit.order} (fit the other order, or records with "
            "more rudder activity)", field="order")
    for field_name, value, unit in (("speed", speed, "m/s"), ("length", length, "m")):
        if not (math.isfinite(value) and value > 0):
            raise ParameterError(f"must be > 0 [{unit}], got {value!r}", field=field_name,
                                 unit=unit, value=value)
    v = dict(zip(fit.names, map(float, fit.values)))
    if fit.order == 1:
        params = Nomoto1Params(gain=v["gain"], time_constant=v["time_constant"], speed=speed,
                               length=length)
    else:
        params = Nomoto2Params(gain=v["gain"], t1=v["t1"], t2=v["t2"], t3=v["t3"],
                               speed=speed, length=length)
    ci = fit.confidence_intervals(level)
    se = fit.standard_errors
    records = ", ".join(fit.records)
    sources = tuple(
        (n, f"output-error fit to {records}: {v[n]:.6g} ± {se[i]:.3g} {_UNITS[n]} (standard "
            f"error; {100 * level:g} % interval {ci[i, 0]:.6g}..{ci[i, 1]:.6g})")
        for i, n in enumerate(fit.names) if n != "rudder_offset")
    i0 = fit.names.index("rudder_offset")
    provenance = (
        f"nomoto{fit.order} identified by seahelm identify nomoto (output error on the "
        f"{fit.output}, Laplace covariance) from {records}; rudder offset δ_0 = "
        f"{math.degrees(v['rudder_offset']):.4g} ± {math.degrees(se[i0]):.3g} deg; residual "
        f"σ = {fit.residual_std:.4g}; covariance of ({', '.join(fit.names)}): "
        f"{np.array2string(fit.covariance, precision=6, separator=', ')}")
    gear = SteeringGear(actuator="rudder-servo",
                        params=ServoParams(max_angle=max_rudder, max_rate=rudder_rate,
                                           time_constant=1.0),
                        provenance="given on the command line (default: ±35°, IMO's minimum "
                                   "rate 2.32°/s; lag 1 s assumed)")
    return Ship(name=name, model=f"nomoto{fit.order}", params=params,
                description=f"Nomoto {fit.order} identified from {len(fit.records)} record(s)",
                steering_gear=gear, provenance=provenance, coefficient_sources=sources,
                validity=(f"linear: the rudder angles and yaw rates of the records; constant "
                          f"speed U = {speed:g} m/s", "deep water"))
