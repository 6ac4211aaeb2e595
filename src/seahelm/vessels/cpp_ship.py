"""Ship with a controllable-pitch propeller (CPP) on a straight course, calm water and waves.

Implements the non-dimensional speed / shaft-speed model used by Platonov & Platonova
(after Nebesnov, Plotnikov & Kuzyushin, 1974):

* calm water, Platonov & Platonova, eq. (6)-(9);
* regular waves, eq. (10)-(12), with the propeller-emergence factors c1(τ), c2(τ).

State ``x = (v̄, ω̄)``: ship speed and shaft speed, both divided by their values on the
initial steady regime (non-dimensional, ``(1, 1)`` is the initial regime). Input
``u = (φ̄,)``: the pitch ratio φ/φ_max ∈ U = [-1, 1] (the only control; the engine regime is
unchanged). Time: in calm water the non-dimensional time τ of eq. (6); in waves the wave
(pitching) phase τ = p t [rad] of eq. (10), so the right-hand side carries the factor
1/A = ε, the small parameter of the averaging (Platonov & Platonova, eq. (1)).

Coefficient cases (Platonov & Platonova, text after eq. (7)) are chosen from the signs of φ̄
and v̄:

==========  ===========  ============  ==========================================
case        φ̄            v̄             meaning
==========  ===========  ============  ==========================================
1           ≥ 0          ≥ 0           ahead pitch, moving ahead
2           < 0          ≥ 0           astern pitch, still moving ahead (crash stop)
3           < 0          < 0           astern pitch, moving astern
uncovered   ≥ 0          < 0           not given by the paper, see below
==========  ===========  ============  ==========================================

The paper's cases overlap on φ̄ = 0 and v̄ = 0; the printed tables are continuous there
(e1, e2 agree between cases 1 and 2, a1, a2 between cases 2 and 3), so the tie-breaking
above does not change the right-hand side. The paper gives no coefficients for ahead pitch
while moving astern; :attr:`CPPShipParams.uncovered_case` selects what happens there:
``1`` (default) extrapolates case 1 (continuous across v̄ = 0, not across φ̄ = 0),
``3`` uses case 3 (continuous across φ̄ = 0, not across v̄ = 0), ``0`` returns NaN so that
the engine records the run as diverged.

The hull-resistance factor switches on the sign of v̄ (eq. (7)): χ = χ1 for v̄ ≥ 0 and
χ = −1.35 χ1 for v̄ < 0, so that the resistance −χ P_e0 v̄² always opposes the motion.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
from numba import njit

from .._validate import as_float_array, check_range
from ..errors import ParameterError, warn_validity
from ..numerics.periodic import period_mean
from ..parameters import Params, as_records, param, signal_indices
from .base import NAV_OUTPUTS, VesselModel

__all__ = [
    "CPPShipParams",
    "CASE_COEFFICIENTS",
    "COEFFICIENT_NAMES",
    "STATE_LABELS",
    "STATE_UNITS",
    "INPUT_LABELS",
    "INPUT_UNITS",
    "coefficient_case",
    "resistance_factor",
    "emergence_alpha",
    "emergence_factors",
    "emergence_kinks",
    "rhs_calm",
    "rhs_waves",
    "calm_water_derivative",
    "waves_derivative",
    "cpp_output",
    "OUTPUT_LABELS",
    "OUTPUT_UNITS",
    "CPP_SHIP_CALM",
    "CPP_SHIP_WAVES",
]

STATE_LABELS: tuple[str, ...] = ("speed", "shaft_speed")
STATE_UNITS: tuple[str, ...] = ("1", "1")
INPUT_LABELS: tuple[str, ...] = ("pitch_ratio",)
INPUT_UNITS: tuple[str, ...] = ("1",)
#: The navigation outputs of a straight course (position and heading not modelled: 0; surge
#: speed v̄, non-dimensional), then the states v̄ and ω̄ under their own names.
OUTPUT_LABELS: tuple[str, ...] = NAV_OUTPUTS + ("speed", "shaft_speed")
OUTPUT_UNITS: tuple[str, ...] = ("m", "m", "rad", "rad/s", "1", "1", "1", "1")

_X = signal_indices(STATE_LABELS)
_U = signal_indices(INPUT_LABELS)
_Y = signal_indices(OUTPUT_LABELS)

#: Names of the columns of :data:`CASE_COEFFICIENTS`.
COEFFICIENT_NAMES: tuple[str, ...] = ("a1", "b1", "c1", "e1", "a2", "b2", "c2", "e2")

#: Coefficients of the thrust (index 1) and torque (index 2) polynomials, one row per case
#: (rows 0, 1, 2 = cases 1, 2, 3), Platonov & Platonova, text after eq. (7).
CASE_COEFFICIENTS = np.array(
    [
        [1.00, -0.60, 1.20, -1.6, 1.00, -0.65, 1.45, -1.8],
        [0.75, -1.40, 2.05, -1.6, 0.90, -1.60, 2.30, -1.8],
        [0.75, 0.32, 1.60, 2.5, 0.90, 0.34, 1.80, 2.7],
    ]
)
CASE_COEFFICIENTS.setflags(write=False)

# Wave means of c1, c2 for the paper's worked case α(τ) = 0.5 − 0.4 sin τ (closed form):
# c1 = 1 − 0.48 sin τ, c2 = 1 − 0.4 sin τ on [0, π], 1 elsewhere.
_C1_MEAN_PAPER = 1.0 - 0.48 / math.pi
_C2_MEAN_PAPER = 1.0 - 0.40 / math.pi


@dataclasses.dataclass(frozen=True, kw_only=True)
class CPPShipParams(Params):
    """Parameters of the CPP ship model (Platonov & Platonova, eq. (6)-(12)); all non-dimensional.

    The paper gives no numbers for χ1, N, A, M⁰, c10, c20, λ0/λmax and φ0/φmax. The defaults
    are chosen so that, with the initial-regime coefficients equal to case 1:

    * (v̄, ω̄) = (1, 1) is the calm-water equilibrium at φ̄ = φ0/φmax: this needs χ1 = 1 and
      M⁰ = 1 (eq. (9) with eq. (8));
    * (1, 1) is also the *averaged* equilibrium in the paper's waves α(τ) = 0.5 − 0.4 sin τ:
      this needs c10 = ⟨c1⟩ = 1 − 0.48/π and c20 = ⟨c2⟩ = 1 − 0.4/π (eq. (13));
      :meth:`balanced` recomputes them for other waves;
    * A = 10 (ε = 1/A = 0.1, the value of the paper's Fig. 1);
    * N = 1: shaft and ship time scales of one order (larger N, a faster shaft, makes the
      O(ε) regime of the averaging start at smaller ε);
    * λ0/λmax = 0.6 for thrust and torque and φ0/φmax = 0.8: a loaded propeller with positive
      initial thrust P_e0 ≈ 0.28 and torque M_C0 ≈ 0.21 (eq. (8)).
    """

    provenance = "Platonov & Platonova, eq. (6)-(12); defaults chosen, see the docstring"

    resistance_coefficient: float = param(
        1.0, unit="1", symbol="χ1", doc="hull resistance factor for v̄ ≥ 0 (eq. (7))", low=0.0,
        low_inclusive=False,
    )
    inertia_ratio: float = param(
        1.0, unit="1", symbol="N", doc="ship-to-shaft inertia ratio (eq. (6))", low=0.0,
        low_inclusive=False,
    )
    wave_ratio: float = param(
        10.0, unit="1", symbol="A",
        doc="wave frequency over ship dynamics rate; ε = 1/A (eq. (10))",
        low=0.0, low_inclusive=False,
    )
    engine_torque: float = param(
        1.0, unit="1", symbol="M⁰", doc="engine torque over its initial value (eq. (9))", low=0.0,
    )
    thrust_emergence_initial: float = param(
        _C1_MEAN_PAPER, unit="1", symbol="c10", doc="thrust emergence factor of the initial regime",
        low=0.0, low_inclusive=False,
    )
    torque_emergence_initial: float = param(
        _C2_MEAN_PAPER, unit="1", symbol="c20", doc="torque emergence factor of the initial regime",
        low=0.0, low_inclusive=False,
    )
    thrust_advance_ratio: float = param(
        0.6, unit="1", symbol="λ0/λ1max", doc="initial advance ratio over the thrust-zero one",
        low=0.0,
    )
    torque_advance_ratio: float = param(
        0.6, unit="1", symbol="λ0/λ2max", doc="initial advance ratio over the torque-zero one",
        low=0.0,
    )
    initial_pitch: float = param(
        0.8, unit="1", symbol="φ0/φmax", doc="pitch ratio of the initial regime", low=0.0,
        high=1.0, low_inclusive=False,
    )
    immersion: float = param(
        1.2, unit="R", symbol="h0/R", doc="propeller immersion at zero pitch angle, in radii",
        low=0.0,
    )
    amplitude: float = param(
        0.96, unit="R", symbol="eψ0/R",
        doc="vertical oscillation amplitude of the propeller, in radii",
        low=0.0,
    )
    uncovered_case: float = param(
        1.0, unit="1", symbol="", doc="coefficients for φ̄ ≥ 0, v̄ < 0: 1 or 3, 0 gives NaN",
        low=0.0, high=3.0,
    )

    def validate(self) -> None:
        if self.uncovered_case not in (0.0, 1.0, 3.0):
            raise ParameterError(
                f"`uncovered_case` must be 0 (NaN), 1 or 3 [1], got {self.uncovered_case!r}"
            )
        alpha_min = (self.immersion - self.amplitude) / 2.4
        if 0.5 + alpha_min <= 0.0:
            raise ParameterError(
                "the torque emergence factor c2(τ) = 0.5 + α(τ) reaches 0: need "
                "immersion − amplitude > −1.2 [R], got "
                f"immersion={self.immersion!r}, amplitude={self.amplitude!r}"
            )
        if 0.4 + 1.2 * alpha_min < 0.0:
            warn_validity(
                "the thrust emergence factor c1(τ) = 0.4 + 1.2 α(τ) becomes negative "
                f"(immersion={self.immersion!r}, amplitude={self.amplitude!r} [R]); "
                "eq. (11) of Platonov & Platonova is an empirical emergence law"
            )
        if self.initial_thrust <= 0.0 or self.initial_torque <= 0.0:
            raise ParameterError(
                "the initial regime must have positive thrust P_e0 and torque M_C0 (eq. (8)); "
                f"got P_e0={self.initial_thrust:.6g}, M_C0={self.initial_torque:.6g} for "
                f"initial_pitch={self.initial_pitch!r}, thrust_advance_ratio="
                f"{self.thrust_advance_ratio!r}, torque_advance_ratio={self.torque_advance_ratio!r}"
            )

    @property
    def epsilon(self) -> float:
        """Small parameter ε = 1/A of the averaging (Platonov & Platonova, eq. (1), (10))."""
        return 1.0 / self.wave_ratio

    @property
    def initial_thrust(self) -> float:
        """P_e0, Platonov & Platonova, eq. (8) (initial-regime coefficients = case 1)."""
        return float(_initial_thrust(self.to_record()))

    @property
    def initial_torque(self) -> float:
        """M_C0, Platonov & Platonova, eq. (8) (initial-regime coefficients = case 1)."""
        return float(_initial_torque(self.to_record()))

    @classmethod
    def balanced(cls, **kwargs: Any) -> "CPPShipParams":
        """Parameters with c10 = ⟨c1⟩ and c20 = ⟨c2⟩ for the given waves.

        With χ1 = 1 and M⁰ = 1 this makes (v̄, ω̄) = (1, 1) the equilibrium of the averaged
        system (Platonov & Platonova, eq. (13)) at the constant pitch φ̄ = φ0/φmax.
        """
        base = cls(**{k: v for k, v in kwargs.items()
                      if k not in ("thrust_emergence_initial", "torque_emergence_initial")})
        kinks = emergence_kinks(base.immersion, base.amplitude)
        c = period_mean(lambda t: emergence_factors(t, base.immersion, base.amplitude),
                        kinks=kinks)
        return base.replace(thrust_emergence_initial=float(c[0]),
                            torque_emergence_initial=float(c[1]))


# ---------------------------------------------------------------------------------------
# compiled kernels
# ---------------------------------------------------------------------------------------
@njit(cache=True)
def _initial_thrust(p):  # pragma: no cover - compiled
    k1 = p.thrust_advance_ratio
    c = CASE_COEFFICIENTS
    return p.initial_pitch * (c[0, 0] + c[0, 1] * k1 + c[0, 2] * k1 * k1) + c[0, 3] * k1 * k1


@njit(cache=True)
def _initial_torque(p):  # pragma: no cover - compiled
    k2 = p.torque_advance_ratio
    c = CASE_COEFFICIENTS
    return p.initial_pitch * (
        p.initial_pitch * (c[0, 4] + c[0, 5] * k2 + c[0, 6] * k2 * k2) + c[0, 7] * k2 * k2
    )


@njit(cache=True)
def _case_row(phi, v, uncovered):  # pragma: no cover - compiled
    """Row of CASE_COEFFICIENTS (0, 1, 2) or -1 for NaN."""
    if phi >= 0.0:
        if v >= 0.0:
            return 0
        if uncovered == 1.0:
            return 0
        if uncovered == 3.0:
            return 2
        return -1
    if v >= 0.0:
        return 1
    return 2


@njit(cache=True)
def _chi(v, chi1):  # pragma: no cover - compiled
    return chi1 if v >= 0.0 else -1.35 * chi1


@njit(cache=True)
def _emergence(tau, h, e):  # pragma: no cover - compiled
    """(c1, c2) of eq. (11) at the wave phase tau [rad], eq. (12)."""
    alpha = h / 2.4 - e / 2.4 * math.sin(tau)
    if alpha > 0.5:
        return 1.0, 1.0
    return 0.4 + 1.2 * alpha, 0.5 + alpha


@njit(cache=True)
def _rhs_core(x, phi, p, c1t, c2t, inv_a, c10, c20, dx):  # pragma: no cover - compiled
    """Eq. (10) for one run; calm water, eq. (9), is c1 = c2 = c10 = c20 = 1 and no 1/A."""
    v = x[_X.speed]
    w = x[_X.shaft_speed]
    row = _case_row(phi, v, p.uncovered_case)
    if row < 0:
        dx[_X.speed] = np.nan
        dx[_X.shaft_speed] = np.nan
        return
    c = CASE_COEFFICIENTS
    k1 = p.thrust_advance_ratio
    k2 = p.torque_advance_ratio
    thrust_poly = c[row, 0] * w * w + c[row, 1] * k1 * v * w + c[row, 2] * k1 * k1 * v * v
    torque_poly = c[row, 4] * w * w + c[row, 5] * k2 * v * w + c[row, 6] * k2 * k2 * v * v
    thrust = (phi * thrust_poly + c[row, 3] * k1 * k1 * v * v) * c1t
    torque = phi * (phi * torque_poly + c[row, 7] * k2 * k2 * v * v) * c2t
    pe0 = _initial_thrust(p)
    mc0 = _initial_torque(p)
    dx[_X.speed] = inv_a * (thrust - _chi(v, p.resistance_coefficient) * pe0 * c10 * v * v)
    dx[_X.shaft_speed] = inv_a * p.inertia_ratio * (mc0 * c20 * p.engine_torque - torque)


@njit(cache=True)
def rhs_waves(t, x, u, d, p, dx):  # pragma: no cover - compiled
    """Right-hand side in regular waves, Platonov & Platonova, eq. (10)-(12).

    ``t`` is the wave phase τ [rad]; ``x = (v̄, ω̄)``; ``u = (φ̄,)``; ``d`` unused (length 0
    allowed); ``p`` a :class:`CPPShipParams` record (``params.to_record()``); ``dx`` is
    written in place.
    """
    c1t, c2t = _emergence(t, p.immersion, p.amplitude)
    _rhs_core(x, u[_U.pitch_ratio], p, c1t, c2t, 1.0 / p.wave_ratio,
              p.thrust_emergence_initial, p.torque_emergence_initial, dx)


@njit(cache=True)
def rhs_calm(t, x, u, d, p, dx):  # pragma: no cover - compiled
    """Right-hand side in calm water, Platonov & Platonova, eq. (9) (= eq. (6) with eq. (8)).

    ``t`` is the non-dimensional time τ of eq. (6) (unused: autonomous); other arguments as
    :func:`rhs_waves`. The wave fields of the parameters are ignored.
    """
    _rhs_core(x, u[_U.pitch_ratio], p, 1.0, 1.0, 1.0, 1.0, 1.0, dx)


@njit(cache=True)
def _batched(kind, t, X, U, P, out):  # pragma: no cover - compiled
    d = np.empty(0)
    for i in range(X.shape[0]):
        if kind == 0:
            rhs_calm(t[i], X[i], U[i], d, P[i], out[i])
        else:
            rhs_waves(t[i], X[i], U[i], d, P[i], out[i])


@njit(cache=True)
def cpp_output(t, x, u, p, y):  # pragma: no cover - compiled
    """Navigation outputs: straight course, position not modelled (0); surge speed = v̄.

    The model is non-dimensional: ``surge_speed`` (and ``speed``) is v̄, the speed in units of
    the initial speed v0 (multiply by v0 [m/s] for SI), ``shaft_speed`` is ω̄, and
    north/east/heading/yaw rate/sway are 0.
    """
    y[_Y.north] = 0.0
    y[_Y.east] = 0.0
    y[_Y.heading] = 0.0
    y[_Y.yaw_rate] = 0.0
    y[_Y.surge_speed] = x[_X.speed]
    y[_Y.sway_speed] = 0.0
    y[_Y.speed] = x[_X.speed]
    y[_Y.shaft_speed] = x[_X.shaft_speed]


CPP_SHIP_CALM = VesselModel(
    name="cpp-ship-calm",
    description="CPP ship speed and shaft speed in calm water, non-dimensional "
    "(Platonov & Platonova, eq. (9))",
    params_type=CPPShipParams,
    state_labels=STATE_LABELS,
    state_units=STATE_UNITS,
    input_labels=INPUT_LABELS,
    input_units=INPUT_UNITS,
    disturbance_labels=(),
    disturbance_units=(),
    rhs=rhs_calm,
    output=cpp_output,
    output_labels=OUTPUT_LABELS,
    output_units=OUTPUT_UNITS,
)

CPP_SHIP_WAVES = VesselModel(
    name="cpp-ship-waves",
    description="CPP ship speed and shaft speed in regular waves, time = wave phase [rad] "
    "(Platonov & Platonova, eq. (10)-(12))",
    params_type=CPPShipParams,
    state_labels=STATE_LABELS,
    state_units=STATE_UNITS,
    input_labels=INPUT_LABELS,
    input_units=INPUT_UNITS,
    disturbance_labels=(),
    disturbance_units=(),
    rhs=rhs_waves,
    output=cpp_output,
    output_labels=OUTPUT_LABELS,
    output_units=OUTPUT_UNITS,
)


# ---------------------------------------------------------------------------------------
# numpy-level public functions
# ---------------------------------------------------------------------------------------
def _params_array(params: CPPShipParams | Any) -> np.ndarray:
    if isinstance(params, CPPShipParams):
        return params.to_array()
    if isinstance(params, (list, tuple)) and params and isinstance(params[0], CPPShipParams):
        return np.stack([q.to_array() for q in params])
    arr = as_float_array("params", params)
    n = len(CPPShipParams.field_names())
    if arr.shape[-1:] != (n,):
        raise ParameterError(f"`params` must end in {n} values (CPPShipParams.to_array()), "
                             f"got shape {arr.shape}")
    return arr


def _derivative(kind: int, t: Any, x: Any, pitch_ratio: Any, params: Any) -> np.ndarray:
    x = as_float_array("x", x)
    if x.shape[-1:] != (2,):
        raise ParameterError(f"`x` must end in 2 states (speed, shaft_speed), got shape {x.shape}")
    u = as_float_array("pitch_ratio", pitch_ratio)
    check_range("pitch_ratio", u, -1.0, 1.0, "1")
    t = as_float_array("t", t)
    p = _params_array(params)
    batch = np.broadcast_shapes(x.shape[:-1], u.shape, t.shape, p.shape[:-1])
    # writable copies: a broadcast that broadcasts nothing is a contiguous read-only view, which
    # np.ascontiguousarray passes through and _batched compiled again for (four signatures)
    X, U, T, P = (np.require(np.broadcast_to(v, shape).reshape(flat), requirements=("C", "W"))
                  for v, shape, flat in ((x, batch + (2,), (-1, 2)),
                                         (u[..., None], batch + (1,), (-1, 1)),
                                         (t, batch, (-1,)),
                                         (p, batch + p.shape[-1:], (-1, p.shape[-1]))))
    out = np.empty_like(X)
    _batched(kind, T, X, U, as_records(P, CPPShipParams), out)
    return out.reshape(batch + (2,))


def calm_water_derivative(x: Any, pitch_ratio: Any, params: CPPShipParams | Any) -> np.ndarray:
    """d(v̄, ω̄)/dτ in calm water over leading batch axes, Platonov & Platonova, eq. (9).

    Parameters
    ----------
    x : array_like, shape (..., 2)
        (v̄, ω̄), speed and shaft speed over their initial values [1].
    pitch_ratio : array_like, shape (...)
        φ̄ = φ/φmax ∈ [-1, 1] [1].
    params : CPPShipParams, sequence of them, or packed array (..., n_params)

    Returns
    -------
    numpy.ndarray, shape (..., 2)

    Raises
    ------
    ParameterError
        If |φ̄| > 1, shapes do not fit or values are not finite.
    """
    return _derivative(0, 0.0, x, pitch_ratio, params)


def waves_derivative(
    t: Any, x: Any, pitch_ratio: Any, params: CPPShipParams | Any
) -> np.ndarray:
    """d(v̄, ω̄)/dτ in regular waves over leading batch axes, Platonov & Platonova, eq. (10)-(12).

    Parameters
    ----------
    t : array_like, shape (...)
        Wave phase τ = p t [rad].
    x, pitch_ratio, params : array_like, array_like, CPPShipParams
        States (v̄, ω̄), pitch ratio φ̄ and ship parameters, as :func:`calm_water_derivative`.

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        Includes the factor 1/A = ε of eq. (10).
    """
    return _derivative(1, t, x, pitch_ratio, params)


def coefficient_case(pitch_ratio: Any, speed: Any, uncovered_case: int = 1) -> np.ndarray:
    """Coefficient case (1, 2, 3) used for the signs of φ̄ and v̄; 0 where the model gives NaN.

    See the module docstring for the table and the uncovered combination φ̄ ≥ 0, v̄ < 0.

    Parameters
    ----------
    pitch_ratio : array_like
        Pitch ratio φ̄ [-].
    speed : array_like
        Non-dimensional speed v̄ [-].
    uncovered_case : {1, 0, 3}, optional
        Case used for φ̄ ≥ 0, v̄ < 0 (default 1; 0 gives NaN).

    Returns
    -------
    numpy.ndarray of int
    """
    phi = as_float_array("pitch_ratio", pitch_ratio)
    v = as_float_array("speed", speed)
    if uncovered_case not in (0, 1, 3):
        raise ParameterError(f"`uncovered_case` must be 0, 1 or 3 [1], got {uncovered_case!r}")
    out = np.where(phi >= 0, np.where(v >= 0, 1, uncovered_case), np.where(v >= 0, 2, 3))
    return out.astype(int)


def resistance_factor(speed: Any, resistance_coefficient: float = 1.0) -> np.ndarray:
    """χ of Platonov & Platonova, eq. (7): χ1 for v̄ ≥ 0 and −1.35 χ1 for v̄ < 0.

    Parameters
    ----------
    speed : array_like
        Non-dimensional speed v̄ [-].
    resistance_coefficient : float, optional
        χ1 [-] (default 1).

    Returns
    -------
    numpy.ndarray
        χ [-].
    """
    v = as_float_array("speed", speed)
    return np.where(v >= 0, 1.0, -1.35) * float(resistance_coefficient)


def emergence_alpha(t: Any, immersion: float = 1.2, amplitude: float = 0.96) -> np.ndarray:
    """α(τ) = h0/(2.4R) − (eψ0/(2.4R)) sin τ, Platonov & Platonova, eq. (12).

    ``immersion`` = h0/R and ``amplitude`` = eψ0/R are in propeller radii; ``t`` in rad.

    Parameters
    ----------
    t : array_like
        Wave phase τ [rad].
    immersion : float, optional
        Shaft immersion h0/R [R] (default 1.2).
    amplitude : float, optional
        Wave amplitude at the propeller eψ0/R [R] (default 0.96).

    Returns
    -------
    numpy.ndarray
        α(τ) [-], shape of ``t``.
    """
    t = np.asarray(t, dtype=float)
    return immersion / 2.4 - amplitude / 2.4 * np.sin(t)


def emergence_factors(t: Any, immersion: float = 1.2, amplitude: float = 0.96) -> np.ndarray:
    """(c1(τ), c2(τ)) stacked on the *first* axis, Platonov & Platonova, eq. (11)-(12).

    Returns an array of shape ``(2,) + np.shape(t)``. Both are continuous with a kink where
    α(τ) = 0.5 (see :func:`emergence_kinks`).

    Parameters
    ----------
    t : array_like
        Wave phase τ [rad].
    immersion : float, optional
        Shaft immersion h0/R [R] (default 1.2).
    amplitude : float, optional
        Wave amplitude at the propeller eψ0/R [R] (default 0.96).
    """
    a = np.minimum(emergence_alpha(t, immersion, amplitude), 0.5)
    return np.stack([0.4 + 1.2 * a, 0.5 + a])


def emergence_kinks(immersion: float = 1.2, amplitude: float = 0.96) -> np.ndarray:
    """Wave phases in [0, 2π) [rad] where α(τ) = 0.5, i.e. where c1, c2 have kinks (0 to 2).

    Parameters
    ----------
    immersion : float, optional
        Shaft immersion h0/R [R] (default 1.2).
    amplitude : float, optional
        Wave amplitude at the propeller eψ0/R [R] (default 0.96).

    Returns
    -------
    numpy.ndarray, shape (0,), (1,) or (2,)
        Sorted kink phases [rad].
    """
    if amplitude == 0.0:
        return np.empty(0)
    s = (immersion / 2.4 - 0.5) / (amplitude / 2.4)
    if abs(s) >= 1.0:
        return np.empty(0)
    a = math.asin(s)
    return np.sort(np.mod([a, math.pi - a], 2 * math.pi))
