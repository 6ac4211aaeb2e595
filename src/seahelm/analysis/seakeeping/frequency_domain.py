"""Seakeeping in the frequency domain: response spectral moments over speed × heading.

A ship at speed U in a sea of one-sided spectrum S(ω) coming at the mean heading ε relative to
the ship (as in :mod:`seahelm.environment.rao`: 0 following, π head, π/2 waves travelling to
starboard) responds in degree of freedom j with the encounter-frequency spectrum
``S_R(ω_e) = |H_j|² S_e(ω_e)``. Its moments are integrated in the **wave** frequency ω, where the
map ω ↦ ω_e = ω − ω²U cos ε/g need not be monotonic (following seas: three wave frequencies
meet the ship at one ω_e below g/(4U cos ε)) — S_e(ω_e) dω_e = S(ω) dω branch by branch, so::

    m_n = ∫₀^∞ ω_e(ω)ⁿ |H_j(ω, ε)|² S(ω) dω        (n = 0, 2, 4),

and with directional spreading D(θ) (:mod:`seahelm.environment.directional_spreading`)::

    m_n = ∫∫ ω_e(ω, ε + θ)ⁿ |H_j(ω, ε + θ)|² S(ω) D(θ) dθ dω

(Lloyd 1989, *Seakeeping*; Price & Bishop 1974). The ω integral is the trapezoidal rule on a
grid (default: 2,000 frequencies from ω_p/200 to 10 ω_p, ω_p the spectrum's peak), the θ
integral the spreading's quadrature. The statistics (RMS, significant amplitude 2√m0, the
zero up-crossing period, the probability of exceeding a level in a time, the most probable
maximum) are :mod:`seahelm.analysis.seakeeping.response_statistics`.

:func:`response_moments` takes RAOs (one per speed: a file's, or any :class:`~seahelm.
environment.rao.RAO`), interpolated as :meth:`RAO.__call__ <seahelm.environment.rao.RAO.
__call__>` does; :func:`closed_form_moments` re-evaluates the closed-form RAOs
(:func:`~seahelm.environment.rao.closed_form_rao`) of a ship's particulars at every speed,
exactly at the quadrature's frequencies and headings. Both return :class:`ResponseMoments`
over (dof, speed, heading), batched: one vectorised pass per speed.

References
----------
Lloyd, A. R. J. M. (1989). Seakeeping: Ship Behaviour in Rough Weather. Ellis Horwood.
Price, W. G., Bishop, R. E. D. (1974). Probabilistic Theory of Ship Dynamics. Chapman & Hall.
St. Denis, M., Pierson, W. J. (1953). On the motions of ships in confused seas. Trans.
SNAME 61, 280–357 (the superposition principle behind ``S_R = |H|² S``).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from scipy.integrate import trapezoid

from ..._validate import as_float_array, check_nonnegative, check_positive
from ...constants import GRAVITY
from ...environment.directional_spreading import get_spreading
from ...environment.rao import DOF_UNITS, RAO, closed_form_rao
from ...environment.spectrum_base import WaveSpectrum
from ...errors import ParameterError, deprecated_method, warn_validity
from . import response_statistics as stats

__all__ = ["ResponseMoments", "response_moments", "closed_form_moments", "response_unit",
           "default_frequencies", "DATASET_FORMAT"]

#: The ``format`` attribute of :meth:`ResponseMoments.to_xarray` (how a report knows it).
DATASET_FORMAT = "seahelm-seakeeping-1"

#: Orders of the moments kept.
ORDERS: tuple[int, ...] = (0, 2, 4)
#: Frequencies × headings evaluated at once (bounds the memory of one pass).
_CHUNK = 250_000
#: Fraction of the wave variance outside an RAO table's frequencies that warns.
_OUTSIDE_TOLERANCE = 0.01


def response_unit(dof: str) -> str:
    """The unit of a response per the RAO's unit: ``"m"`` for heave, ``"rad"`` for roll.

    Parameters
    ----------
    dof : str
        Degree of freedom (:data:`~seahelm.environment.rao.DOFS`).

    Returns
    -------
    str
    """
    return DOF_UNITS[dof].split("/")[0]


def default_frequencies(spectrum: WaveSpectrum, n: int = 2000) -> np.ndarray:
    """The default quadrature grid: ``n`` frequencies from ω_p/200 to 10 ω_p [rad/s].

    Parameters
    ----------
    spectrum : WaveSpectrum
        The sea (its peak frequency ω_p).
    n : int, optional
        Number of frequencies (default 2,000).

    Returns
    -------
    numpy.ndarray
    """
    wp = float(spectrum.peak_frequency)
    return np.linspace(wp / 200.0, 10.0 * wp, n)


@dataclasses.dataclass(frozen=True, eq=False)
class ResponseMoments:
    """Spectral moments m0, m2, m4 of the responses over (dof, speed, heading).

    Attributes
    ----------
    dofs : tuple of str
        Degrees of freedom.
    speed : numpy.ndarray, shape (n_speed,)
        Ship speeds U [m/s].
    heading : numpy.ndarray, shape (n_heading,)
        Mean wave headings ε relative to the ship [rad] (0 following, π head).
    moments : numpy.ndarray, shape (n_dof, 3, n_speed, n_heading)
        m0 [u²], m2 [u²/s²], m4 [u²/s⁴] (u the response's unit, :func:`response_unit`).
    description : dict
        What was computed: the spectrum, the spreading, the RAOs' provenance.
    """

    dofs: tuple[str, ...]
    speed: np.ndarray
    heading: np.ndarray
    moments: np.ndarray
    description: dict = dataclasses.field(default_factory=dict)

    def moment(self, dof: str, n: int) -> np.ndarray:
        """m_n of one degree of freedom over (speed, heading).

        Parameters
        ----------
        dof : str
            Degree of freedom, e.g. ``"roll"``.
        n : int
            Order: 0, 2 or 4.

        Returns
        -------
        numpy.ndarray, shape (n_speed, n_heading)
        """
        if n not in ORDERS:
            raise ParameterError(f"must be one of {ORDERS}, got {n!r}", field="n", value=n)
        return self.moments[self._index(dof), ORDERS.index(n)]

    def _index(self, dof: str) -> int:
        if dof not in self.dofs:
            raise ParameterError(f"is not computed; the moments have {', '.join(self.dofs)}",
                                 field="dof", value=dof)
        return self.dofs.index(dof)

    def rms(self, dof: str) -> np.ndarray:
        """RMS √m0 [u] over (speed, heading).

        Parameters
        ----------
        dof : str
            Degree of freedom.

        Returns
        -------
        numpy.ndarray
        """
        return np.sqrt(self.moment(dof, 0))

    def significant_amplitude(self, dof: str) -> np.ndarray:
        """Significant amplitude 2√m0 [u] (significant height, crest to trough: 4√m0).

        Parameters
        ----------
        dof : str
            Degree of freedom.

        Returns
        -------
        numpy.ndarray
        """
        return stats.significant_amplitude(self.moment(dof, 0))

    def zero_crossing_period(self, dof: str) -> np.ndarray:
        """Mean zero up-crossing period in encounter, T_z = 2π√(m0/m2) [s].

        Parameters
        ----------
        dof : str
            Degree of freedom.

        Returns
        -------
        numpy.ndarray
        """
        return stats.zero_crossing_period(self.moment(dof, 0), self.moment(dof, 2))

    def exceedance_probability(self, dof: str, level: float, duration: float, *,
                               both_sides: bool = False) -> np.ndarray:
        """P(the response exceeds ``level`` at least once in ``duration``) over (speed, heading).

        :func:`~seahelm.analysis.seakeeping.response_statistics.exceedance_probability`.

        Parameters
        ----------
        dof : str
            Degree of freedom.
        level : float
            Threshold [u: m for heave, rad for roll and pitch], > 0.
        duration : float
            Exposure time T [s], > 0.
        both_sides : bool, optional
            Count the crossings of −level too (``|x| > level``; twice the rate) instead of
            those of +level only.

        Returns
        -------
        numpy.ndarray
        """
        check_positive("level", level, response_unit(dof))
        check_positive("duration", duration, "s")
        return stats.exceedance_probability(level, duration, self.moment(dof, 0),
                                            self.moment(dof, 2), both_sides=both_sides)

    def most_probable_maximum(self, dof: str, duration: float) -> np.ndarray:
        """Most probable largest amplitude in ``duration``, √(2 m0 ln N), N = T/T_z [u].

        NaN where fewer than two cycles fit in ``duration`` (or there is no response).

        Parameters
        ----------
        dof : str
            Degree of freedom.
        duration : float
            Exposure time T [s], > 0.

        Returns
        -------
        numpy.ndarray
        """
        check_positive("duration", duration, "s")
        n = duration / self.zero_crossing_period(dof)
        ok = np.isfinite(n) & (n > 1)
        out = np.full(n.shape, np.nan)
        out[ok] = stats.most_probable_maximum(self.moment(dof, 0)[ok], n[ok])
        return out

    to_dataset = deprecated_method("to_xarray", "one name for it across seahelm")

    def to_xarray(self) -> Any:
        """The moments and statistics as an :class:`xarray.Dataset` over (dof, speed, heading).

        Returns
        -------
        xarray.Dataset
            ``m0``, ``m2``, ``m4``, ``rms``, ``significant_amplitude``,
            ``zero_crossing_period``; SI units (roll and pitch in rad), per dof in the
            ``units`` attributes; the description as attributes.
        """
        import xarray as xr

        units = {d: response_unit(d) for d in self.dofs}

        def per_dof(power: str) -> str:
            return ", ".join(f"{d}: {u}{power}" for d, u in units.items())

        dims = ("dof", "speed", "heading")
        m0 = self.moments[:, 0]
        data = {
            "m0": (dims, m0, {"units": per_dof("^2"), "long_name": "zeroth spectral moment "
                              "(variance) of the response"}),
            "m2": (dims, self.moments[:, 1], {"units": per_dof("^2/s^2"),
                                              "long_name": "second spectral moment"}),
            "m4": (dims, self.moments[:, 2], {"units": per_dof("^2/s^4"),
                                              "long_name": "fourth spectral moment"}),
            "rms": (dims, np.sqrt(m0), {"units": per_dof(""), "long_name": "RMS sqrt(m0)"}),
            "significant_amplitude": (dims, 2.0 * np.sqrt(m0), {
                "units": per_dof(""), "long_name": "significant amplitude 2 sqrt(m0) "
                "(significant height, double amplitude: 4 sqrt(m0))"}),
            "zero_crossing_period": (dims, np.stack([self.zero_crossing_period(d)
                                                     for d in self.dofs]), {
                "units": "s", "long_name": "mean zero up-crossing period 2 pi sqrt(m0/m2)"}),
        }
        coords = {"dof": list(self.dofs),
                  "speed": ("speed", self.speed, {"units": "m/s", "long_name": "ship speed"}),
                  "heading": ("heading", self.heading, {
                      "units": "rad", "long_name": "mean wave heading relative to the ship "
                      "(0 following, pi head, pi/2 waves travelling to starboard)"})}
        attrs = {"format": DATASET_FORMAT, **{k: (v if isinstance(v, (int, float))
                                                          else str(v))
                                                       for k, v in self.description.items()}}
        return xr.Dataset(data, coords=coords, attrs=attrs)


# ---------------------------------------------------------------------------------------------
# Inputs
# ---------------------------------------------------------------------------------------------


def _grid(name: str, value: ArrayLike, unit: str) -> np.ndarray:
    a = as_float_array(name, value, unit)
    a = np.atleast_1d(a)
    if a.ndim != 1 or a.size == 0:
        raise ParameterError(f"must be a non-empty 1-D array [{unit}], got shape {a.shape}",
                             field=name, unit=unit)
    return a


def _frequencies(frequency: ArrayLike) -> np.ndarray:
    w = _grid("frequency", frequency, "rad/s")
    check_positive("frequency", w, "rad/s")
    if w.size < 2 or not np.all(np.diff(w) > 0):
        raise ParameterError("must be at least two strictly increasing values [rad/s]",
                             field="frequency", unit="rad/s")
    return w


def _spectrum(spectrum: Any) -> WaveSpectrum:
    if not isinstance(spectrum, WaveSpectrum):
        raise ParameterError(f"must be a WaveSpectrum (seahelm.environment.spectra), got "
                             f"{type(spectrum).__name__}", field="spectrum")
    return spectrum


def _directions(spreading: Any, n_directions: int) -> tuple[np.ndarray, np.ndarray, str]:
    if spreading is None:
        return np.zeros(1), np.ones(1), "none (long-crested)"
    sp = get_spreading(spreading)
    theta, weights = sp.quadrature(n_directions)
    return theta, weights, f"{sp!r}, {theta.size} directions"


def _dofs(dofs: Sequence[str] | None, available: tuple[str, ...], source: str) -> tuple[str, ...]:
    if dofs is None:
        return available
    if isinstance(dofs, str):
        dofs = (dofs,)
    dofs = tuple(dofs)
    missing = [d for d in dofs if d not in available]
    if not dofs or missing:
        raise ParameterError(f"must be some of {', '.join(available)} ({source}), got "
                             f"{dofs!r}", field="dofs", value=dofs)
    return dofs


# ---------------------------------------------------------------------------------------------
# The integral
# ---------------------------------------------------------------------------------------------

Evaluator = Callable[[np.ndarray, np.ndarray], np.ndarray]


def _moments_at_speed(evaluate: Evaluator, n_dof: int, speed: float, omega: np.ndarray,
                      density: np.ndarray, heading: np.ndarray, theta: np.ndarray,
                      weights: np.ndarray, gravity: float) -> np.ndarray:
    """m0, m2, m4 (n_dof, 3, n_heading) at one speed; ``evaluate(ω, ε)`` -> (dof, ω, ε)."""
    eps = (heading[:, None] + theta[None, :]).ravel()
    out = np.empty((n_dof, len(ORDERS), eps.size))
    step = max(1, _CHUNK // omega.size)
    w = omega[:, None]
    for start in range(0, eps.size, step):
        e = eps[start:start + step]
        we2 = (w - w * w * speed * np.cos(e)[None, :] / gravity) ** 2
        H = evaluate(omega, e)
        r = (H.real ** 2 + H.imag ** 2) * density[None, :, None]
        out[:, 0, start:start + step] = trapezoid(r, omega, axis=1)
        r = r * we2
        out[:, 1, start:start + step] = trapezoid(r, omega, axis=1)
        out[:, 2, start:start + step] = trapezoid(r * we2, omega, axis=1)
    return out.reshape(n_dof, len(ORDERS), heading.size, theta.size) @ weights


def _check_common(spectrum: Any, heading: ArrayLike, gravity: float
                  ) -> tuple[WaveSpectrum, np.ndarray]:
    spec = _spectrum(spectrum)
    eps = _grid("heading", heading, "rad")
    check_positive("gravity", gravity, "m/s^2")
    return spec, eps


def response_moments(raos: RAO | Sequence[RAO], spectrum: WaveSpectrum, heading: ArrayLike, *,
                     dofs: Sequence[str] | None = None, spreading: Any = None,
                     n_directions: int = 36, frequency: ArrayLike | None = None,
                     gravity: float = GRAVITY, strict: bool | None = None) -> ResponseMoments:
    """Response moments from RAO tables (one per speed) in a sea over mean wave headings.

    Parameters
    ----------
    raos : RAO or sequence of RAO
        One RAO per speed (each holds its speed, :attr:`RAO.speed`; the speeds distinct).
    spectrum : WaveSpectrum
        The one-sided wave spectrum S(ω) [m²·s/rad] (:mod:`seahelm.environment.spectra`).
    heading : array_like
        Mean wave headings ε relative to the ship [rad] (0 following, π head).
    dofs : sequence of str, optional
        Degrees of freedom (default: all of the first RAO's; every RAO must have them).
    spreading : str or spreading object, optional
        Directional spreading (:func:`~seahelm.environment.directional_spreading.
        get_spreading`: ``"cos2"``, ``"cos-2s"``, or an object); default long-crested.
    n_directions : int, optional
        Directions of the spreading's quadrature (default 36).
    frequency : array_like, optional
        Wave frequencies ω of the quadrature [rad/s], strictly increasing (default
        :func:`default_frequencies` within the RAOs' frequency range).
    gravity : float, optional
        g [m/s²].
    strict : bool, optional
        Raise instead of warning (extrapolated RAOs, wave energy outside their range).

    Returns
    -------
    ResponseMoments

    Raises
    ------
    ParameterError
        Bad input, naming the parameter and its unit.

    Notes
    -----
    The module docstring has the integral. Without ``frequency``, the grid is cut to each
    table's frequency range; more than 1 % of the wave variance outside it warns
    (:func:`~seahelm.errors.warn_validity`): the response there is left out.
    """
    if isinstance(raos, RAO):
        raos = [raos]
    raos = list(raos)
    if not raos or not all(isinstance(r, RAO) for r in raos):
        raise ParameterError("must be one RAO or a non-empty sequence of RAOs", field="raos")
    spec, eps = _check_common(spectrum, heading, gravity)
    speeds = np.array([r.speed for r in raos])
    if np.unique(speeds).size != speeds.size:
        raise ParameterError(f"must hold RAOs at distinct speeds [m/s], got {speeds.tolist()}",
                             field="raos", unit="m/s")
    chosen = _dofs(dofs, raos[0].dofs, "the RAO's dofs")
    for r in raos[1:]:
        _dofs(chosen, r.dofs, f"the RAO at {r.speed:g} m/s")
    theta, weights, spread_text = _directions(spreading, n_directions)
    out = np.empty((len(chosen), len(ORDERS), len(raos), eps.size))
    for i, rao in enumerate(raos):
        if frequency is None:
            full = default_frequencies(spec)
            lo, hi = rao.frequency[0], rao.frequency[-1]
            omega = np.linspace(max(full[0], lo), min(full[-1], hi), full.size)
            total = trapezoid(spec.one_sided(full), full)
            inside = trapezoid(spec.one_sided(omega), omega) if omega[-1] > omega[0] else 0.0
            if total > 0 and 1.0 - inside / total > _OUTSIDE_TOLERANCE:
                warn_validity(f"{100 * (1 - inside / total):.3g} % of the wave variance lies "
                              f"outside the RAO's frequencies [{lo:.4g}, {hi:.4g}] rad/s "
                              f"(at {rao.speed:g} m/s) and is left out", strict=strict)
        else:
            omega = _frequencies(frequency)
        density = spec.one_sided(omega)

        def evaluate(w: np.ndarray, e: np.ndarray, rao: RAO = rao) -> np.ndarray:
            return np.stack([rao(d, w[:, None], e[None, :], strict=strict) for d in chosen])

        out[:, :, i] = _moments_at_speed(evaluate, len(chosen), rao.speed, omega, density,
                                         eps, theta, weights, gravity)
    description = {"spectrum": repr(spec), "spreading": spread_text,
                   "raos": " | ".join(r.provenance or "RAO" for r in raos)}
    return ResponseMoments(chosen, speeds, eps, out, description)


def closed_form_moments(particulars: Any, spectrum: WaveSpectrum, speed: ArrayLike,
                        heading: ArrayLike, *, dofs: Sequence[str] | None = None,
                        spreading: Any = None, n_directions: int = 36,
                        frequency: ArrayLike | None = None,
                        metacentric_height: float | None = None,
                        roll_period: float | None = None, roll_damping: float = 0.1,
                        slope_coefficient: float = 1.0, smith: str = "k",
                        roll_excitation: str = "averaged", gravity: float = GRAVITY,
                        strict: bool | None = None) -> ResponseMoments:
    """Response moments of a ship's closed-form RAOs over speed × mean wave heading.

    The RAOs (:func:`~seahelm.environment.rao.closed_form_rao`) are evaluated at every speed,
    exactly at the quadrature's frequencies and headings (no interpolation).

    Parameters
    ----------
    particulars : Particulars or Ship
        L, B, T, C_b (a ship's particulars are taken).
    spectrum : WaveSpectrum
        The one-sided wave spectrum S(ω) [m²·s/rad].
    speed : array_like
        Ship speeds U [m/s], >= 0.
    heading : array_like
        Mean wave headings ε relative to the ship [rad] (0 following, π head).
    dofs : sequence of str, optional
        Degrees of freedom among heave, roll, pitch (default: all the closed form gives;
        roll needs ``metacentric_height`` or ``roll_period``).
    spreading : str or spreading object, optional
        Directional spreading (``"cos2"``, ``"cos-2s"`` or an object); default long-crested.
    n_directions : int, optional
        Directions of the spreading's quadrature (default 36).
    frequency : array_like, optional
        Wave frequencies ω of the quadrature [rad/s] (default :func:`default_frequencies`).
    metacentric_height : float, optional
        GM [m] for the roll RAO (default: the particulars' ``metacentric_height``, if known).
    roll_period : float, optional
        Natural roll period T_φ [s] (default the IMO estimate from GM).
    roll_damping : float, optional
        Roll damping ratio ζ_φ [-] (default 0.1).
    slope_coefficient : float, optional
        Effective wave-slope coefficient r [-] (default 1).
    smith : {"k", "k_e"}, optional
        The closed form's Smith factor exp(−kT) (default) or exp(−k_e T)
        (:func:`~seahelm.environment.rao.closed_form_rao`).
    roll_excitation : {"averaged", "slope"}, optional
        The roll's wave-slope excitation averaged over the hull (default) or the full slope.
    gravity : float, optional
        g [m/s²].
    strict : bool, optional
        Raise instead of warning outside the closed form's range.

    Returns
    -------
    ResponseMoments

    Raises
    ------
    ParameterError
        Bad input, naming the parameter and its unit; roll asked for without GM or T_φ.
    """
    spec, eps = _check_common(spectrum, heading, gravity)
    speeds = _grid("speed", speed, "m/s")
    check_nonnegative("speed", speeds, "m/s")
    p = getattr(particulars, "particulars", particulars)
    if p is None:
        raise ParameterError("is not known (L, B, T, C_b): a closed-form RAO needs them",
                             field="particulars")
    if metacentric_height is None and roll_period is None:
        metacentric_height = getattr(p, "metacentric_height", None)  # (the particulars' GM)
    has_roll = metacentric_height is not None or roll_period is not None
    available = ("heave", "roll", "pitch") if has_roll else ("heave", "pitch")
    if dofs is not None and "roll" in ((dofs,) if isinstance(dofs, str) else tuple(dofs)) \
            and not has_roll:
        raise ParameterError("is not known [m]: the closed-form roll RAO needs the "
                             "metacentric height GM (or `roll_period` [s])",
                             field="metacentric_height", unit="m")
    chosen = _dofs(dofs, available, "the closed-form RAOs")
    omega = default_frequencies(spec) if frequency is None else _frequencies(frequency)
    density = spec.one_sided(omega)
    theta, weights, spread_text = _directions(spreading, n_directions)
    kwargs = dict(metacentric_height=metacentric_height, roll_period=roll_period,
                  roll_damping=roll_damping, slope_coefficient=slope_coefficient,
                  smith=smith, roll_excitation=roll_excitation, gravity=gravity,
                  strict=strict)
    out = np.empty((len(chosen), len(ORDERS), speeds.size, eps.size))
    provenance = ""
    for i, U in enumerate(speeds):

        def evaluate(w: np.ndarray, e: np.ndarray, U: float = float(U)) -> np.ndarray:
            nonlocal provenance
            unique, inverse = np.unique(e, return_inverse=True)
            rao = closed_form_rao(p, U, frequency=w, heading=unique, **kwargs)
            provenance = rao.provenance
            idx = [rao.dofs.index(d) for d in chosen]
            return rao.values[idx][:, :, inverse.ravel()]

        out[:, :, i] = _moments_at_speed(evaluate, len(chosen), float(U), omega, density, eps,
                                         theta, weights, gravity)
    description = {"spectrum": repr(spec), "spreading": spread_text,
                   "raos": f"closed form re-evaluated at each speed; at the last: {provenance}"}
    return ResponseMoments(chosen, speeds, eps, out, description)
