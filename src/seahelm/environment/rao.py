"""Response amplitude operators (RAOs): heave, roll and pitch per unit wave amplitude.

An :class:`RAO` is a complex transfer function H_j(ω, ε) per degree of freedom j over the wave
frequency ω [rad/s] and the wave heading ε [rad] relative to the ship (the angle between the
direction the waves travel and the ship's heading, as in :mod:`.encounter`: ε = 0 following,
π head seas, π/2 waves travelling to starboard, i.e. coming from port), at one forward speed U.
In a regular wave whose elevation at the ship's origin is ζ(t) = a cos(ω_e t + ϕ), with the
signed encounter frequency ω_e = ω − ω²U cos ε/g, the response is

    η_j(t) = a |H_j| cos(ω_e t + ϕ + arg H_j)  = Re(a H_j e^{i(ω_e t + ϕ)}),

so ``phase`` is the lead of the response over the wave elevation at the origin. Signs: heave
positive **up** [m/m], roll positive starboard down [rad/m] (as the 4-DOF model's roll angle),
pitch positive bow up [rad/m].

:func:`closed_form_rao` estimates them from the main particulars and the speed
(:class:`~seahelm.vessels.particulars.Particulars`): every ship with particulars has them.
:mod:`.rao_io` reads a documented table (CSV), seahelm's NetCDF and capytaine's NetCDF output.

Heave and pitch: Jensen, Mansour & Olsen (2004)
    A homogeneous box of length L, draught T and breadth B_e = C_b B (their replacement of B
    for the hull form), strip theory with the Smith correction κ = exp(−kT), k = ω²/g,
    effective wave number k_e = |k cos ε|, α = ω_e/ω = 1 − Fn √(kL) cos ε, the sectional
    damping's wave-amplitude ratio A = 2 sin(k B_e α²/2) exp(−k T α²) (their eqs. for the
    heave and pitch transfer functions)::

        f = (1 − kT) + i A²/(k B_e |α|³)          (excitation per unit length, ρgB_e)
        F = κ f sinc(k_e L/2),   G = κ f 24/(k_e² L³) (sin σ − σ cos σ),  σ = k_e L/2
        D = 1 − 2kTα² + i A²/(k B_e α|α|)         (ω_n² = g/(2T); 2ζω_e/ω_n)
        H_heave = F/D,   H_pitch = −i sgn(cos ε) G/D

    |H_heave| = |F|/|D| and |H_pitch| = |G|/|D| are the paper's Φ_w = ηF and Φ_θ = ηG
    (η = 1/|D|, f = |f|); the phases follow from the same one-degree-of-freedom equations in
    complex form (the paper gives amplitudes): in long waves H_heave → 1 (the ship follows
    the surface) and H_pitch → −i k cos ε (the wave slope along the ship).

    The Smith factor: the incident wave's pressure decays with depth as exp(kz) whatever its
    direction (the potential exp(kz + i k (x cos ε + y sin ε)) satisfies Laplace's equation
    only with the full wave number), so the section's bottom at depth T sees exp(−kT): the
    default (``smith="k"``). The transcription in MSS's ``waveresponse345`` (Fossen) has
    κ = exp(−k_e T), which is 1 in beam seas and leaves the short-wave beam-sea heave
    unreduced (0.73 m/m at 1.2-1.6 rad/s on a box whose panel-method heave is 0.04-0.29):
    ``smith="k_e"``. In head and following seas the two coincide.

Roll: a one-degree-of-freedom model with wave-slope excitation
    Not Jensen et al.'s roll (whose empirical sectional roll damping needs hull-shape data);
    the classical linear roll of a ship that in long beam waves follows the wave slope
    (Bhattacharyya 1978, *Dynamics of Marine Vehicles*, ch. 8; Lloyd 1989, *Seakeeping*)::

        H_roll = i r γ k sin ε / (1 − (ω_e/ω_φ)² + 2i ζ_φ ω_e/ω_φ)

    with the effective wave-slope coefficient r (``slope_coefficient``, 1 for a small ship in
    long waves), the natural roll period T_φ, ω_φ = 2π/T_φ (``roll_period``; default the IMO
    estimate T_φ = 2 C B/√GM, C = 0.373 + 0.023 B/T − 0.043 L/100, IMO Res. A.749(18),
    weather criterion, with ``metacentric_height`` GM) and the damping ratio ζ_φ
    (``roll_damping``, default 0.1, including viscous damping). Parametric roll is outside
    every linear RAO.

    γ is the short-wave reduction of the wave-slope moment (``roll_excitation="averaged"``,
    the default): the Froude–Krylov moment of the incident pressure ρga exp(kz) over the
    bottom of a box of length L, breadth B and draught T, relative to its long-wave value
    ρga k sin ε L B³/12 (derived here from the Froude–Krylov hypothesis; the moment of a
    cosine pressure over the beam, as Jensen et al.'s pitch shape function is over the
    length)::

        γ = exp(−kT) · 3 (sin s − s cos s)/s³ · sinc(k cos ε L/2),   s = k sin ε B/2

    — the Smith depth factor, the slope averaged over the breadth and the wave averaged over
    the length (the same factor as the heave's). γ → 1 in long waves and |γ| <= 1. It does not
    depend on KG (the moment of the horizontal force about G, which the sway of a free ship
    mostly relieves, is left out). Against the fraction of the wave slope that a
    one-degree-of-freedom roll needs to reproduce a panel method's roll (capytaine, the
    shipped Wigley I hull, below its roll resonance) γ is 0.01-0.24 low in oblique seas and
    −0.03 to +0.15 off in beam seas, where the full slope is up to 0.48-0.65 too high
    (docs/guide/waves-motions.rst has the rest). ``roll_excitation="slope"`` is the earlier
    γ = 1 (the full wave slope at every frequency and heading), which overstates short-wave and
    quartering-sea roll.

References
----------
Jensen, J. J., Mansour, A. E., Olsen, A. S. (2004). Estimation of ship motions using
closed-form expressions. Ocean Engineering 31, 61–85. doi:10.1016/S0029-8018(03)00108-2.
Bhattacharyya, R. (1978). Dynamics of Marine Vehicles. Wiley.
IMO Resolution A.749(18), Code on Intact Stability, §3.2 (severe wind and rolling criterion).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from .._validate import as_float_array, check_nonnegative, check_positive
from ..constants import GRAVITY
from ..errors import ParameterError, deprecated_method, warn_validity

__all__ = ["RAO", "DOFS", "DOF_UNITS", "closed_form_rao", "imo_roll_period",
           "roll_slope_factor", "SMITH_FACTORS", "ROLL_EXCITATIONS"]

#: Degrees of freedom an RAO may hold, with the unit of their response per metre of wave.
DOFS: tuple[str, ...] = ("surge", "sway", "heave", "roll", "pitch", "yaw")
DOF_UNITS: dict[str, str] = {"surge": "m/m", "sway": "m/m", "heave": "m/m", "roll": "rad/m",
                             "pitch": "rad/m", "yaw": "rad/m"}
#: The closed form's Smith factor: exp(−kT) (``"k"``, default) or exp(−k_e T) (``"k_e"``).
SMITH_FACTORS: tuple[str, ...] = ("k", "k_e")
#: The closed-form roll's excitation: the averaged wave slope γ k sin ε (``"averaged"``,
#: default) or the full wave slope k sin ε (``"slope"``).
ROLL_EXCITATIONS: tuple[str, ...] = ("averaged", "slope")


@dataclasses.dataclass(frozen=True, eq=False)
class RAO:
    """Complex response amplitude operators over wave frequency and heading (module docstring).

    Attributes
    ----------
    frequency : numpy.ndarray, shape (n_freq,)
        Wave frequencies ω [rad/s], strictly increasing, > 0.
    heading : numpy.ndarray, shape (n_head,)
        Wave headings ε relative to the ship [rad], strictly increasing (0 following, π head).
    dofs : tuple of str
        Degrees of freedom (names from :data:`DOFS`).
    values : numpy.ndarray, shape (n_dof, n_freq, n_head), complex
        H_j(ω, ε) per unit wave amplitude (units :data:`DOF_UNITS`).
    speed : float
        Forward speed U [m/s] the RAOs hold for.
    provenance : str
        Where they come from.
    """

    frequency: np.ndarray
    heading: np.ndarray
    dofs: tuple[str, ...]
    values: np.ndarray
    speed: float = 0.0
    provenance: str = ""

    def __post_init__(self) -> None:
        w = as_float_array("frequency", self.frequency, "rad/s")
        h = as_float_array("heading", self.heading, "rad")
        for name, a, unit in (("frequency", w, "rad/s"), ("heading", h, "rad")):
            if a.ndim != 1 or a.size == 0:
                raise ParameterError(f"must be a non-empty 1-D array [{unit}], got shape "
                                     f"{a.shape}", field=name, unit=unit)
            if not np.all(np.isfinite(a)):
                raise ParameterError(f"must be finite [{unit}]", field=name, unit=unit)
            if a.size > 1 and not np.all(np.diff(a) > 0):
                raise ParameterError(f"must be strictly increasing [{unit}]", field=name,
                                     unit=unit)
        check_positive("frequency", w, "rad/s")
        dofs = tuple(self.dofs)
        unknown = [d for d in dofs if d not in DOFS]
        if unknown or not dofs or len(set(dofs)) != len(dofs):
            raise ParameterError(f"must be distinct names of {', '.join(DOFS)}, got {dofs!r}",
                                 field="dofs")
        v = np.asarray(self.values, dtype=complex)
        if v.shape != (len(dofs), w.size, h.size):
            raise ParameterError(f"must have the shape (dofs, frequency, heading) = "
                                 f"{(len(dofs), w.size, h.size)}, got {v.shape}", field="values")
        if not np.all(np.isfinite(v)):
            raise ParameterError("must be finite (no NaN)", field="values")
        check_nonnegative("speed", self.speed, "m/s")
        object.__setattr__(self, "frequency", w)
        object.__setattr__(self, "heading", h)
        object.__setattr__(self, "dofs", dofs)
        object.__setattr__(self, "values", v)
        object.__setattr__(self, "speed", float(self.speed))

    def _index(self, dof: str) -> int:
        if dof not in self.dofs:
            raise ParameterError(f"is not in this RAO; it has {', '.join(self.dofs)}",
                                 field="dof", value=dof)
        return self.dofs.index(dof)

    def amplitude(self, dof: str) -> np.ndarray:
        """|H_j| over (frequency, heading) [m/m or rad/m].

        Parameters
        ----------
        dof : str
            Degree of freedom, e.g. ``"roll"``.

        Returns
        -------
        numpy.ndarray, shape (n_freq, n_head)
        """
        return np.abs(self.values[self._index(dof)])

    def phase(self, dof: str) -> np.ndarray:
        """arg H_j over (frequency, heading) [rad]: the lead over the wave at the origin.

        Parameters
        ----------
        dof : str
            Degree of freedom.

        Returns
        -------
        numpy.ndarray, shape (n_freq, n_head)
        """
        return np.angle(self.values[self._index(dof)])

    def __call__(self, dof: str, frequency: ArrayLike, heading: ArrayLike, *,
                 strict: bool | None = None) -> np.ndarray:
        """H_j at wave frequencies and headings (broadcast), interpolated bilinearly.

        The real and imaginary parts are interpolated linearly in ω and in ε; headings wrap
        to [0, 2π) and a table over [0, π] only is mirrored for ε in (π, 2π) (port-starboard
        symmetry: roll, sway and yaw change sign). A frequency outside the table warns
        (:func:`~seahelm.errors.warn_validity`; an error in strict mode) and takes the end
        value.

        Parameters
        ----------
        dof : str
            Degree of freedom.
        frequency : array_like
            Wave frequencies ω [rad/s].
        heading : array_like
            Wave headings ε [rad].
        strict : bool, optional
            Raise instead of warning on extrapolation (default: the global strict mode).

        Returns
        -------
        numpy.ndarray, complex
        """
        table = self.values[self._index(dof)]
        w = as_float_array("frequency", frequency, "rad/s")
        e = np.mod(as_float_array("heading", heading, "rad"), 2.0 * math.pi)
        w, e = np.broadcast_arrays(w, e)
        if np.any(w < self.frequency[0]) or np.any(w > self.frequency[-1]):
            warn_validity(f"wave frequency outside the RAO table [{self.frequency[0]:.4g}, "
                          f"{self.frequency[-1]:.4g}] rad/s: the end values are used",
                          strict=strict)
        sign = np.ones_like(e)
        h = self.heading
        if h[-1] <= math.pi + 1e-9 and h[0] >= -1e-9:  # a half table: mirror
            mirror = e > math.pi
            e = np.where(mirror, 2.0 * math.pi - e, e)
            if dof in ("roll", "sway", "yaw"):
                sign = np.where(mirror, -1.0, 1.0)
            span = (h[0], h[-1])
        else:
            span = (h[0], h[-1])
        if np.any(e < span[0] - 1e-9) or np.any(e > span[1] + 1e-9):
            raise ParameterError(f"headings outside the RAO table [{span[0]:.4g}, "
                                 f"{span[1]:.4g}] rad", field="heading", unit="rad")
        fi = np.clip(np.searchsorted(self.frequency, w) - 1, 0, max(self.frequency.size - 2, 0))
        hi = np.clip(np.searchsorted(h, e) - 1, 0, max(h.size - 2, 0))
        out = np.empty(w.shape, dtype=complex)
        if self.frequency.size == 1:
            tw, fi1 = np.zeros_like(w), fi
        else:
            fi1 = fi + 1
            tw = np.clip((w - self.frequency[fi]) / (self.frequency[fi1] - self.frequency[fi]),
                         0.0, 1.0)
        if h.size == 1:
            th, hi1 = np.zeros_like(e), hi
        else:
            hi1 = hi + 1
            th = np.clip((e - h[hi]) / (h[hi1] - h[hi]), 0.0, 1.0)
        out[...] = ((1 - tw) * (1 - th) * table[fi, hi] + tw * (1 - th) * table[fi1, hi]
                    + (1 - tw) * th * table[fi, hi1] + tw * th * table[fi1, hi1])
        return out * sign

    def regular_wave_response(self, dof: str, amplitude: float, frequency: float,
                              heading: float, time: ArrayLike, *, phase: float = 0.0,
                              gravity: float = GRAVITY) -> np.ndarray:
        """η_j(t) = a |H_j| cos(ω_e t + ϕ + arg H_j) in one regular wave (module docstring).

        Parameters
        ----------
        dof : str
            Degree of freedom.
        amplitude : float
            Wave amplitude a [m], > 0.
        frequency : float
            Wave frequency ω [rad/s].
        heading : float
            Wave heading ε relative to the ship [rad].
        time : array_like
            Times t [s].
        phase : float, optional
            Phase ϕ of the wave elevation at the origin [rad] (default 0).
        gravity : float, optional
            g [m/s²] of the encounter frequency.

        Returns
        -------
        numpy.ndarray
            The response [m or rad] at ``time``.
        """
        check_positive("amplitude", amplitude, "m")
        t = as_float_array("time", time, "s")
        we = frequency - frequency ** 2 * self.speed * math.cos(heading) / gravity
        H = complex(self(dof, frequency, heading))
        return np.real(amplitude * H * np.exp(1j * (we * t + phase)))

    to_dataset = deprecated_method("to_xarray", "one name for it across seahelm")

    def to_xarray(self) -> Any:
        """The RAOs as an :class:`xarray.Dataset` (seahelm's RAO NetCDF layout, :mod:`.rao_io`).

        Returns
        -------
        xarray.Dataset
            ``amplitude`` and ``phase`` over (dof, frequency, heading), the speed as an
            attribute.
        """
        import xarray as xr

        coords = {"dof": list(self.dofs), "frequency": ("frequency", self.frequency,
                                                        {"units": "rad/s"}),
                  "heading": ("heading", self.heading, {"units": "rad"})}
        units = ", ".join(f"{d}: {DOF_UNITS[d]}" for d in self.dofs)
        return xr.Dataset(
            {"amplitude": (("dof", "frequency", "heading"), np.abs(self.values),
                           {"units": units, "long_name": "RAO amplitude per unit wave amplitude"}),
             "phase": (("dof", "frequency", "heading"), np.angle(self.values),
                       {"units": "rad", "long_name": "lead over the wave elevation at the "
                        "origin, response Re(a H exp(i w_e t))"})},
            coords=coords, attrs={"speed": self.speed, "speed_units": "m/s",
                                  "provenance": self.provenance, "format": "seahelm-rao-1",
                                  "conventions": "heading 0 following, pi head, pi/2 waves to "
                                  "starboard; heave up, roll starboard down, pitch bow up"})


def imo_roll_period(length: float, beam: float, draft: float, metacentric_height: float) -> float:
    """Natural roll period T_φ = 2 C B/√GM, C = 0.373 + 0.023 B/T − 0.043 L/100 [s].

    IMO Res. A.749(18), §3.2.2 (the weather criterion's rolling period; L in metres).

    Parameters
    ----------
    length, beam, draft : float
        L, B, T [m].
    metacentric_height : float
        GM [m], > 0.

    Returns
    -------
    float
        T_φ [s].
    """
    for name, value in (("length", length), ("beam", beam), ("draft", draft),
                        ("metacentric_height", metacentric_height)):
        check_positive(name, value, "m")
    c = 0.373 + 0.023 * beam / draft - 0.043 * length / 100.0
    return 2.0 * c * beam / math.sqrt(metacentric_height)


def _sinc(x: np.ndarray) -> np.ndarray:
    return np.sinc(x / math.pi)


def _beam_shape(s: np.ndarray) -> np.ndarray:
    """3 (sin s − s cos s)/s³ (→ 1 − s²/10 as s → 0)."""
    return 3.0 * _pitch_shape(s)


def roll_slope_factor(k: ArrayLike, heading: ArrayLike, length: float, beam: float,
                      draft: float) -> np.ndarray:
    """γ = exp(−kT) 3 (sin s − s cos s)/s³ sinc(k cos ε L/2), s = k sin ε B/2 (module docstring).

    The Froude–Krylov roll moment of a regular wave over the bottom of a box L × B at depth T
    relative to its long-wave value: the short-wave reduction of the wave-slope roll
    excitation of :func:`closed_form_rao`.

    Parameters
    ----------
    k : array_like
        Wave numbers k = ω²/g [rad/m], >= 0.
    heading : array_like
        Wave headings ε [rad] (broadcast with ``k``).
    length, beam, draft : float
        L, B, T [m], > 0.

    Returns
    -------
    numpy.ndarray
        γ [-], in [−1, 1], 1 at k = 0.
    """
    for name, value in (("length", length), ("beam", beam), ("draft", draft)):
        check_positive(name, value, "m")
    kk = as_float_array("k", k, "rad/m")
    check_nonnegative("k", kk, "rad/m")
    e = as_float_array("heading", heading, "rad")
    s = 0.5 * kk * np.sin(e) * beam
    return np.exp(-kk * draft) * _beam_shape(s) * _sinc(0.5 * kk * np.cos(e) * length)


def _pitch_shape(s: np.ndarray) -> np.ndarray:
    """(sin σ − σ cos σ)/σ³ (→ 1/3 − σ²/30 as σ → 0)."""
    small = np.abs(s) < 1e-3
    safe = np.where(small, 1.0, s)
    return np.where(small, 1.0 / 3.0 - s * s / 30.0,
                    (np.sin(safe) - safe * np.cos(safe)) / safe ** 3)


def closed_form_rao(particulars: Any, speed: float, *, frequency: ArrayLike | None = None,
                    heading: ArrayLike | None = None, metacentric_height: float | None = None,
                    roll_period: float | None = None, roll_damping: float = 0.1,
                    slope_coefficient: float = 1.0, smith: str = "k",
                    roll_excitation: str = "averaged", gravity: float = GRAVITY,
                    strict: bool | None = None) -> RAO:
    """Heave, pitch (Jensen et al. 2004) and roll RAOs from the main particulars and speed.

    Parameters
    ----------
    particulars : Particulars or Ship
        L, B, T and C_b (a :class:`~seahelm.ships.Ship`'s particulars are taken).
    speed : float
        Forward speed U [m/s], >= 0.
    frequency : array_like, optional
        Wave frequencies ω [rad/s] (default 0.1 to 2.0 rad/s, 96 values).
    heading : array_like, optional
        Wave headings ε [rad] (default 0 to π in 5° steps).
    metacentric_height : float, optional
        GM [m]; the roll RAO needs it (or ``roll_period``): without both, only heave and pitch
        (default: the particulars' ``metacentric_height``, if known).
    roll_period : float, optional
        Natural roll period T_φ [s] (default :func:`imo_roll_period` from GM).
    roll_damping : float, optional
        Roll damping ratio ζ_φ [-], in (0, 1] (default 0.1).
    slope_coefficient : float, optional
        Effective wave-slope coefficient r [-], in (0, 1.5] (default 1).
    smith : {"k", "k_e"}, optional
        The Smith factor κ: ``"k"`` exp(−kT) (default, the incident pressure's decay with
        depth) or ``"k_e"`` exp(−k_e T), k_e = |k cos ε| (MSS's transcription of Jensen et al.;
        1 in beam seas).
    roll_excitation : {"averaged", "slope"}, optional
        ``"averaged"`` (default): the wave slope reduced by :func:`roll_slope_factor` (depth,
        breadth and length averaging of the Froude–Krylov moment); ``"slope"``: the full wave
        slope k sin ε at every frequency (the earlier model).
    gravity : float, optional
        g [m/s²].
    strict : bool, optional
        Raise instead of warning outside the formulas' range (default: the global mode).

    Returns
    -------
    RAO
        dofs ``("heave", "pitch")`` or ``("heave", "roll", "pitch")``.

    Raises
    ------
    ParameterError
        On a non-positive dimension, speed < 0, a damping or slope coefficient out of range,
        or an unknown ``smith`` or ``roll_excitation``.

    Notes
    -----
    The module docstring has the equations. Jensen et al. (2004) validate heave and pitch
    against strip theory for Froude numbers up to about 0.3 and block coefficients 0.6 to
    0.8 (C_b outside [0.5, 0.9] or Fn > 0.4 warns).
    """
    p = getattr(particulars, "particulars", particulars)
    if p is None:
        raise ParameterError("the ship has no particulars (L, B, T, C_b): a closed-form RAO "
                             "needs them", field="particulars")
    L, B, T, cb = (float(getattr(p, n)) for n in ("length", "beam", "draft",
                                                   "block_coefficient"))
    if metacentric_height is None and roll_period is None:
        metacentric_height = getattr(p, "metacentric_height", None)
    check_nonnegative("speed", speed, "m/s")
    if smith not in SMITH_FACTORS:
        raise ParameterError(f"must be one of {', '.join(SMITH_FACTORS)}, got {smith!r}",
                             field="smith", value=smith)
    if roll_excitation not in ROLL_EXCITATIONS:
        raise ParameterError(f"must be one of {', '.join(ROLL_EXCITATIONS)}, got "
                             f"{roll_excitation!r}", field="roll_excitation",
                             value=roll_excitation)
    U = float(speed)
    fn = U / math.sqrt(gravity * L)
    if not 0.5 <= cb <= 0.9 or fn > 0.4:
        warn_validity(f"Jensen et al. (2004) closed-form RAOs: C_b = {cb:.3g} (0.5-0.9), "
                      f"Fn = {fn:.3g} (<= 0.4) outside the range they were checked for",
                      strict=strict)
    w = (np.linspace(0.1, 2.0, 96) if frequency is None
         else as_float_array("frequency", frequency, "rad/s"))
    eps = (np.radians(np.arange(0.0, 180.1, 5.0)) if heading is None
           else as_float_array("heading", heading, "rad"))
    check_positive("frequency", w, "rad/s")
    k = (w * w / gravity)[:, None]
    c = np.cos(eps)[None, :]
    Be = cb * B
    alpha = 1.0 - fn * np.sqrt(k * L) * c  # ω_e/ω, signed
    a2 = alpha * alpha
    A = 2.0 * np.sin(0.5 * k * Be * a2) * np.exp(-k * T * a2)
    aa = np.abs(alpha)
    with np.errstate(divide="ignore", invalid="ignore"):
        f_im = np.where(aa > 0, A * A / (k * Be * aa ** 3), 0.0)
        d_im = np.where(aa > 0, A * A / (k * Be * alpha * aa), 0.0)
    f = (1.0 - k * T) + 1j * f_im
    D = (1.0 - 2.0 * k * T * a2) + 1j * d_im
    ke = np.abs(k * c)
    kappa = np.exp(-(ke if smith == "k_e" else k) * T)
    s = 0.5 * ke * L
    F = kappa * f * _sinc(s)
    G = kappa * f * 24.0 / L ** 3 * (s ** 3 / np.where(ke > 0, ke * ke, 1.0)) * _pitch_shape(s)
    G = np.where(ke > 0, G, 0.0)
    heave = F / D
    pitch = -1j * np.sign(c) * G / D
    dofs, values = ["heave", "pitch"], [heave, pitch]
    if metacentric_height is not None or roll_period is not None:
        if roll_period is None:
            roll_period = imo_roll_period(L, B, T, float(metacentric_height))
        check_positive("roll_period", roll_period, "s")
        if not 0.0 < roll_damping <= 1.0:
            raise ParameterError(f"must be in (0, 1] [-], got {roll_damping!r}",
                                 field="roll_damping", unit="-", value=roll_damping)
        if not 0.0 < slope_coefficient <= 1.5:
            raise ParameterError(f"must be in (0, 1.5] [-], got {slope_coefficient!r}",
                                 field="slope_coefficient", unit="-", value=slope_coefficient)
        wr = 2.0 * math.pi / float(roll_period)
        q = (alpha * np.sqrt(k * gravity)) / wr  # ω_e/ω_φ
        gamma = (roll_slope_factor(k, eps[None, :], L, B, T) if roll_excitation == "averaged"
                 else 1.0)
        roll = 1j * slope_coefficient * gamma * k * np.sin(eps)[None, :] / (
            1.0 - q * q + 2j * roll_damping * q)
        dofs.insert(1, "roll")
        values.insert(1, roll)
    text = (f"closed-form estimate from L {L:g} m, B {B:g} m, T {T:g} m, C_b {cb:g} at "
            f"{U:g} m/s: heave and pitch Jensen, Mansour & Olsen (2004), Smith factor "
            f"exp(-{smith} T)")
    if "roll" in dofs:
        text += (f"; roll one-DOF wave-slope model, T_phi {float(roll_period):.4g} s, "
                 f"zeta {roll_damping:g}, r {slope_coefficient:g}, {roll_excitation} wave slope")
    return RAO(w, eps, tuple(dofs), np.stack([np.broadcast_to(v, k.shape[:1] + eps.shape)
                                              for v in values]), U, text)
