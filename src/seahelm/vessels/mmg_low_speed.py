"""Low-speed MMG model in all four quadrants of (u, n) with the rps as an input (``mmg-ls``).

The manoeuvring model of Miyauchi, Maki, Umeda, Rachman & Akimoto (2022) for berthing: the
3-DOF MMG equations of motion about midship with

* **hull** (``hull_model``, :data:`HULL_MODELS`): ``"cross-flow"`` — Yoshimura's low-speed
  model (Yoshimura, Nakao & Ishibashi 2009;
  :func:`~seahelm.hydrodynamics.low_speed_hull.low_speed_hull`):
  X_H = ½ρLd (X'_0(β) u U + X'_vr v r L), X'_0 = X'_0F + (X'_0A − X'_0F)|β|/π;
  Y_H = ½ρLd (Y'_v v |u| + Y'_r u r L − C_D ∫ |v + C_rY r x|(v + C_rY r x) dx/L);
  N_H = ½ρL²d (N'_v u v + N'_r |u| r L − C_D ∫ |v + C_rN r x|(v + C_rN r x) x dx/L²), the
  integrals over the hull x ∈ [−L/2, L/2] evaluated exactly;
* **propeller** (``propeller_model``,
  :data:`~seahelm.hydrodynamics.low_speed_propulsion.PROPELLER_MODELS`): ``"hachii"`` —
  Hachii's four-quadrant thrust (C_3, C_6, C_7, C_10) and side force and yaw moment
  (A_1 … A_8, B_1 … B_8) — or ``"wageningen"`` (the B4-70 four-quadrant series scaled to
  k_0, with Hachii's side force);
* **rudder** (``rudder_inflow_model``): ``"kitagawa"`` — the low-speed MMG inflow ahead and
  Kitagawa's reversed race for n < 0, u_R = u astern with the propeller astern — or
  ``"yasukawa-astern"`` (Yasukawa's inflow astern with the propeller ahead); Fujii's normal
  force;

(:mod:`seahelm.hydrodynamics.low_speed_propulsion` for the propeller and rudder equations.)
The propeller rps ``propeller_rps`` is an input, as measured in a free-running test (no engine
or shaft model: see ``mmg-4q`` for those). Wind and waves act through the disturbance channels
(``force_x``, ``force_y``, ``moment_z`` about midship): the Esso Osaka's published wind model
is Fujiwara's (``wind_loads="fujiwara"``, :mod:`seahelm.environment.fujiwara`).

Equations of motion (midship origin, x_G forward of midship):
(m + m_x) u̇ − (m + m_y) v r − x_G m r² = X; (m + m_y) v̇ + x_G m ṙ + (m + m_x) u r = Y;
(I_zG + J_z + x_G² m) ṙ + x_G m (v̇ + u r) = N, with m, m_x, m_y made non-dimensional by
½ρL²d and I_zG + J_z by ½ρL⁴d (Miyauchi et al. 2022 give their sum).

Non-dimensional velocities v' = v/U, r' = r L/U (in the wake only); below ``min_speed`` they
are taken as 0 (the published model's guard at U < 10⁻⁵ m/s).

References
----------
Miyauchi, Y., Maki, A., Umeda, N., Rachman, D. M. & Akimoto, Y. (2022). System parameter
exploration of ship maneuvering model for automatic docking/berthing using CMA-ES. J. Mar.
Sci. Technol. 27, 1065–1083. doi:10.1007/s00773-022-00889-3.
Yoshimura, Y., Nakao, I. & Ishibashi, A. (2009). Unified mathematical model for ocean and
harbour manoeuvring. Proc. MARSIM 2009.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np
from numba import njit

from .._validate import lookup_name
from ..errors import ParameterError
from ..hydrodynamics.low_speed_hull import low_speed_hull
from ..hydrodynamics.low_speed_propulsion import (
    PROPELLER_MODELS,
    RUDDER_INFLOW_MODELS,
    propeller_forces,
    rudder_forces,
)
from ..parameters import Params, param, signal_indices
from .base import VesselModel
from .rigid_body import midship_accelerations
from .mmg import (DISTURBANCE_UNITS, DISTURBANCES, OUTPUT_UNITS, OUTPUTS, STATE_UNITS, STATES,
                  mmg_motion, write_mmg_outputs, write_mmg_rates)

__all__ = ["MMGLowSpeedParams", "MMG_LS", "HULL_MODELS", "LowSpeedForces", "force_components",
           "ESSO_OSAKA_3M", "component_code"]

INPUTS = ("rudder_angle", "propeller_rps")
INPUT_UNITS = ("rad", "1/s")

#: Hull models by name: the value of the parameter ``hull_model``.
HULL_MODELS: dict[str, float] = {"cross-flow": 0.0}

S = signal_indices(STATES)
U = signal_indices(INPUTS)
D = signal_indices(DISTURBANCES)
Y = signal_indices(OUTPUTS)

_POS = dict(low=0.0, low_inclusive=False)
_SMALL = dict(low=-0.1, high=0.1)


@dataclass(frozen=True, kw_only=True)
class MMGLowSpeedParams(Params):
    """Parameters of the low-speed four-quadrant MMG model (module docstring); defaults: the
    Esso Osaka 3 m model of Miyauchi et al. (2022) (:data:`ESSO_OSAKA_3M`)."""

    # -- principal particulars ----------------------------------------------------------
    length: float = param(3.0, unit="m", symbol="L_pp", **_POS, doc="length between perpendiculars")
    breadth: float = param(0.48925, unit="m", symbol="B", **_POS, doc="breadth")
    draft: float = param(0.20114, unit="m", symbol="d", **_POS, doc="draught")
    mass: float = param(0.27078, unit="-", symbol="m'", **_POS,
                        doc="mass over ½ρL²d")
    x_G: float = param(0.09357, unit="m", symbol="x_G",
                       doc="centre of gravity forward of midship (dimensional)")
    rho: float = param(998.0, unit="kg/m³", symbol="ρ", **_POS, doc="water density")
    propeller_diameter: float = param(0.084, unit="m", symbol="D_P", **_POS,
                                      doc="propeller diameter")
    pitch_ratio: float = param(0.7151, unit="-", symbol="p", **_POS,
                               doc="propeller pitch over diameter")
    rudder_area: float = param(0.01063, unit="m²", symbol="A_R", **_POS, doc="rudder area")
    rudder_aspect_ratio: float = param(1.539, unit="-", symbol="Λ", **_POS,
                                       doc="rudder aspect ratio; span H_R = √(A_R Λ)")
    approach_speed: float = param(0.3, unit="m/s", symbol="U_0", **_POS,
                                  doc="a typical test speed (not in the equations)")
    min_speed: float = param(1e-5, unit="m/s", symbol="U_min", **_POS,
                             doc="below this speed v' = r' = 0 (U → 0 guard)")
    # -- added masses ---------------------------------------------------------------------
    m_x: float = param(0.0467, unit="-", symbol="m'_x", low=0.0, doc="added mass in surge")
    m_y: float = param(0.2579, unit="-", symbol="m'_y", low=0.0, doc="added mass in sway")
    I_zz_J_zz: float = param(0.0286, unit="-", symbol="I'_zz + J'_zz", **_POS,
                             doc="yaw moment of inertia about G plus added, over ½ρL⁴d")
    # -- hull ---------------------------------------------------------------------------
    hull_model: float = param(0.0, unit="-", symbol="", doc="hull model code (HULL_MODELS)")
    X_0F: float = param(-0.02139, unit="-", symbol="X'_0F", high=0.0,
                        doc="surge resistance coefficient ahead (β = 0)")
    X_0A: float = param(-0.03189, unit="-", symbol="X'_0A", high=0.0,
                        doc="surge resistance coefficient astern (|β| = π)")
    X_vr: float = param(-0.0081, unit="-", symbol="X'_vr", doc="surge force per v r")
    Y_v: float = param(-0.3728, unit="-", symbol="Y'_v", doc="sway force per v |u|")
    Y_r: float = param(0.116, unit="-", symbol="Y'_r", doc="sway force per u r")
    N_v: float = param(-0.1458, unit="-", symbol="N'_v", doc="yaw moment per u v")
    N_r: float = param(-0.04849, unit="-", symbol="N'_r", doc="yaw moment per |u| r")
    C_D: float = param(0.9665, unit="-", symbol="C_D", low=0.0, doc="cross-flow drag coefficient")
    C_rY: float = param(2.217, unit="-", symbol="C_rY",
                        doc="yaw-rate factor of the cross flow in Y")
    C_rN: float = param(0.8097, unit="-", symbol="C_rN",
                        doc="yaw-rate factor of the cross flow in N")
    # -- propeller ----------------------------------------------------------------------
    propeller_model: float = param(0.0, unit="-", symbol="",
                                   doc="propeller model code (PROPELLER_MODELS)")
    t_P: float = param(0.22, unit="-", symbol="t_P", low=0.0, high=0.99, doc="thrust deduction")
    w_P0: float = param(0.614, unit="-", symbol="w_P0", low=0.0, high=0.99,
                        doc="wake fraction in straight motion")
    tau_P: float = param(0.871, unit="-", symbol="τ", doc="wake change per |v' + x'_P r'|")
    C_P: float = param(-0.359, unit="-", symbol="C'_P", doc="wake change per (v' + x'_P r')²")
    x_P: float = param(-0.517, unit="-", symbol="x'_P", low=-1.0, high=1.0,
                       doc="propeller position over L in the wake")
    k_0: float = param(0.3278, unit="-", symbol="k_0", doc="K_T polynomial, constant term")
    k_1: float = param(-0.3323, unit="-", symbol="k_1", doc="K_T polynomial, linear term")
    k_2: float = param(-0.156, unit="-", symbol="k_2", doc="K_T polynomial, quadratic term")
    C_3: float = param(-0.251, unit="-", symbol="C_3", doc="n < 0: X_P/(ρn²D⁴) for J_s < C_10")
    C_6: float = param(-0.175, unit="-", symbol="C_6", doc="n < 0: constant of X_P/(ρn²D⁴)")
    C_7: float = param(0.33, unit="-", symbol="C_7", doc="n < 0: J_s slope of X_P/(ρn²D⁴)")
    C_10: float = param(-0.233, unit="-", symbol="C_10", doc="n < 0: J_s switching the thrust form")
    J_syn: float = param(-0.35, unit="-", symbol="J_syn",
                         doc="n < 0: J_s below which A_3, A_4 hold")
    J_syn0: float = param(-0.06, unit="-", symbol="J_syn0", doc="n < 0: J_s above which A_5 holds")
    A_1: float = param(-7.90e-05, unit="-", symbol="A_1", **_SMALL, doc="Y_P, n < 0: constant")
    A_2: float = param(7.99e-03, unit="-", symbol="A_2", **_SMALL, doc="Y_P, n < 0: per J_s")
    A_3: float = param(-4.93e-03, unit="-", symbol="A_3", **_SMALL, doc="Y_P, n < 0, J_s < J_syn")
    A_4: float = param(-5.87e-03, unit="-", symbol="A_4", **_SMALL, doc="Y_P, J_s < J_syn: per J_s")
    A_5: float = param(-5.58e-04, unit="-", symbol="A_5", **_SMALL, doc="Y_P, n < 0, J_s > J_syn0")
    A_6: float = param(5.08e-03, unit="-", symbol="A_6", **_SMALL, doc="Y_P, u < 0 < n: per J_s²")
    A_7: float = param(1.70e-03, unit="-", symbol="A_7", **_SMALL, doc="Y_P, u < 0 < n: per J_s")
    A_8: float = param(9.16e-04, unit="-", symbol="A_8", **_SMALL, doc="Y_P, u < 0 < n: constant")
    B_1: float = param(3.50e-05, unit="-", symbol="B_1", **_SMALL, doc="N_P, n < 0: constant")
    B_2: float = param(-3.17e-03, unit="-", symbol="B_2", **_SMALL, doc="N_P, n < 0: per J_s")
    B_3: float = param(1.96e-03, unit="-", symbol="B_3", **_SMALL, doc="N_P, n < 0, J_s < J_syn")
    B_4: float = param(2.33e-03, unit="-", symbol="B_4", **_SMALL, doc="N_P, J_s < J_syn: per J_s")
    B_5: float = param(2.25e-04, unit="-", symbol="B_5", **_SMALL, doc="N_P, n < 0, J_s > J_syn0")
    B_6: float = param(-2.16e-03, unit="-", symbol="B_6", **_SMALL, doc="N_P, u < 0 < n: per J_s²")
    B_7: float = param(6.27e-05, unit="-", symbol="B_7", **_SMALL, doc="N_P, u < 0 < n: per J_s")
    B_8: float = param(6.25e-05, unit="-", symbol="B_8", **_SMALL, doc="N_P, u < 0 < n: constant")
    # -- rudder -------------------------------------------------------------------------
    rudder_inflow_model: float = param(0.0, unit="-", symbol="",
                                       doc="rudder inflow model code (RUDDER_INFLOW_MODELS)")
    t_R: float = param(0.19, unit="-", symbol="t_R", low=0.0, high=0.99,
                       doc="steering resistance deduction")
    a_H: float = param(0.393, unit="-", symbol="a_H", low=0.0, doc="rudder force increase factor")
    x_H: float = param(-0.45, unit="-", symbol="x'_H", low=-1.0, high=1.0,
                       doc="position of the additional lateral force over L")
    x_R: float = param(-0.5, unit="-", symbol="x'_R", low=-1.0, high=1.0,
                       doc="rudder position over L")
    l_R: float = param(-1.08, unit="-", symbol="l'_R", low=-2.0, high=2.0,
                       doc="effective rudder position in v_R over L")
    k_x: float = param(0.288, unit="-", symbol="k_x", low=0.0,
                       doc="slipstream factor ahead (κ = k_x/ε)")
    k_x_reverse: float = param(0.144, unit="-", symbol="k_x,rev", low=0.0,
                               doc="slipstream factor of the reversed race (n < 0)")
    epsilon: float = param(1.42, unit="-", symbol="ε", **_POS,
                           doc="(1 − w_R)/(1 − w_P)")
    C_PR: float = param(-0.176, unit="-", symbol="C_PR", doc="reversed race: per u²")
    C_uR0: float = param(0.14, unit="-", symbol="C_uR0",
                         doc="Yasukawa's astern inflow (rudder_inflow_model 1): u_R** factor")
    gamma_N: float = param(0.4406, unit="-", symbol="γ_N", low=0.0,
                           doc="flow straightening where v + x_R r < 0")
    gamma_P: float = param(0.3506, unit="-", symbol="γ_P", low=0.0,
                           doc="flow straightening where v + x_R r ≥ 0")

    def validate(self) -> None:
        """Cross-field checks: component codes known, CoG inside the ship, η ≤ 1."""
        for field, registry in (("hull_model", HULL_MODELS),
                                ("propeller_model", PROPELLER_MODELS),
                                ("rudder_inflow_model", RUDDER_INFLOW_MODELS)):
            value = getattr(self, field)
            if value not in registry.values():
                names = ", ".join(f"{v:g} ({k})" for k, v in registry.items())
                raise ParameterError(f"must be one of {names}, got {value!r}", field=field,
                                     unit="-", value=value)
        if abs(self.x_G) >= 0.5 * self.length:
            raise ParameterError(f"must lie within ±L_pp/2 = ±{0.5 * self.length:g} [m], got "
                                 f"{self.x_G!r}", field="x_G", unit="m", value=self.x_G)
        span = math.sqrt(self.rudder_area * self.rudder_aspect_ratio)
        if self.propeller_diameter > span:
            raise ParameterError(
                f"must not exceed the rudder span √(A_R Λ) = {span:.4g} [m] (η ≤ 1), got "
                f"{self.propeller_diameter!r}", field="propeller_diameter", unit="m",
                value=self.propeller_diameter)


def component_code(kind: str, name: str) -> float:
    """The parameter value of a component by name (``kind``: ``"hull"``, ``"propeller"`` or
    ``"rudder_inflow"``).

    Parameters
    ----------
    kind : str
        Which component.
    name : str
        Its name in :data:`HULL_MODELS`, ``PROPELLER_MODELS`` or ``RUDDER_INFLOW_MODELS``.

    Returns
    -------
    float
        The value of ``hull_model``, ``propeller_model`` or ``rudder_inflow_model``.

    Raises
    ------
    ValueError
        For an unknown kind or name (the message lists the valid ones).
    """
    tables = {"hull": HULL_MODELS, "propeller": PROPELLER_MODELS,
              "rudder_inflow": RUDDER_INFLOW_MODELS}
    return lookup_name(f"{kind} model", lookup_name("component kind", tables, kind), name)


@njit(cache=True)
def _forces_ls(u, v, r, delta, n, p):  # pragma: no cover - compiled
    """(X_H, Y_H, N_H, X_P, Y_P, N_P, X_R, Y_R, N_R, F_N, u_R, v_R, U, β, 1 − w_P)."""
    L = p.length
    speed = math.sqrt(u * u + v * v)
    if speed < p.min_speed:
        vn = 0.0
        rn = 0.0
    else:
        vn = v / speed
        rn = r * L / speed
    X_H, Y_H, N_H = low_speed_hull(u, v, r, L, p.draft, p.rho, p.X_0F, p.X_0A, p.X_vr, p.Y_v,
                                   p.Y_r, p.N_v, p.N_r, p.C_D, p.C_rY, p.C_rN)
    X_P, Y_P, N_P, one_w, K_T = propeller_forces(u, vn, rn, n, p)
    X_R, Y_R, N_R, F_N, u_R, v_R = rudder_forces(u, v, r, delta, n, one_w, K_T, p)
    return (X_H, Y_H, N_H, X_P, Y_P, N_P, X_R, Y_R, N_R, F_N, u_R, v_R, speed,
            math.atan2(-v, u), one_w)


@njit(cache=True)
def mmg_ls_rhs(t, x, u, d, p, dx):  # pragma: no cover - compiled
    """ẋ of the low-speed MMG model for one run (module docstring)."""
    uu = x[S.surge_speed]
    v = x[S.sway_speed]
    r = x[S.yaw_rate]
    (X_H, Y_H, N_H, X_P, Y_P, N_P, X_R, Y_R, N_R, _F_N, _u_R, _v_R, _U, _b,
     _w) = _forces_ls(uu, v, r, u[U.rudder_angle], u[U.propeller_rps], p)
    X = X_H + X_P + X_R + d[D.force_x]
    Yf = Y_H + Y_P + Y_R + d[D.force_y]
    N = N_H + N_P + N_R + d[D.moment_z]
    L = p.length
    scale = 0.5 * p.rho * L * L * p.draft
    m = p.mass * scale
    # the midship equations of motion with I_zG + J_z given as one coefficient (I_zz_J_zz)
    du, dv, dr = midship_accelerations(X, Yf, N, uu, v, r, m, p.m_x * scale, p.m_y * scale,
                                       0.0, p.I_zz_J_zz * scale * L * L, p.x_G)
    write_mmg_rates(x, d, dx, du, dv, dr)


@njit(cache=True)
def mmg_ls_output(t, x, u, p, y):  # pragma: no cover - compiled
    """Outputs (the ``mmg`` model's, ``OUTPUTS`` order) for one run; ``thrust`` is the
    propeller's surge force X_P."""
    delta = u[U.rudder_angle]
    (_X_H, _Y_H, _N_H, X_P, _Y_P, _N_P, _X_R, _Y_R, _N_R, F_N, u_R, v_R, speed, beta,
     _w) = _forces_ls(x[S.surge_speed], x[S.sway_speed], x[S.yaw_rate], delta,
                      u[U.propeller_rps], p)
    write_mmg_outputs(x, y, speed, beta, X_P, F_N, delta - math.atan2(v_R, u_R))


MMG_LS = VesselModel(
    name="mmg-ls",
    description="low-speed MMG model in four quadrants, rps as input: Yoshimura's cross-flow "
    "hull, Hachii's propeller, Kitagawa's reversed rudder inflow (Miyauchi et al. 2022)",
    params_type=MMGLowSpeedParams,
    state_labels=STATES,
    state_units=STATE_UNITS,
    input_labels=INPUTS,
    input_units=INPUT_UNITS,
    disturbance_labels=DISTURBANCES,
    disturbance_units=DISTURBANCE_UNITS,
    rhs=mmg_ls_rhs,
    output=mmg_ls_output,
    output_labels=OUTPUTS,
    output_units=OUTPUT_UNITS,
    motion=mmg_motion,
    capabilities=frozenset({"record-identification"}),
)


class LowSpeedForces(NamedTuple):
    """Force components of ``mmg-ls`` for one state (SI units; moments about midship)."""

    X_H: float
    Y_H: float
    N_H: float
    X_P: float
    Y_P: float
    N_P: float
    X_R: float
    Y_R: float
    N_R: float
    rudder_normal_force: float
    rudder_inflow_u: float
    rudder_inflow_v: float
    speed: float
    drift_angle: float
    wake_factor: float

    @property
    def X(self) -> float:
        """X_H + X_P + X_R [N]."""
        return self.X_H + self.X_P + self.X_R

    @property
    def Y(self) -> float:
        """Y_H + Y_P + Y_R [N]."""
        return self.Y_H + self.Y_P + self.Y_R

    @property
    def N(self) -> float:
        """N_H + N_P + N_R about midship [N·m]."""
        return self.N_H + self.N_P + self.N_R


def force_components(params: MMGLowSpeedParams, state: Any, inputs: Any) -> LowSpeedForces:
    """Hull, propeller and rudder forces of ``mmg-ls`` for one state (diagnostics, checks).

    Parameters
    ----------
    params : MMGLowSpeedParams
        Ship parameters.
    state : array_like, shape (3,) or (6,)
        Surge speed [m/s], midship sway speed [m/s], yaw rate [rad/s] (then position and
        heading, unused).
    inputs : array_like, shape (2,)
        Rudder angle [rad] and propeller rps [1/s].

    Returns
    -------
    LowSpeedForces
    """
    if not isinstance(params, MMGLowSpeedParams):
        raise ParameterError(f"must be MMGLowSpeedParams, got {type(params).__name__}",
                             field="params")
    x = np.asarray(state, dtype=float).ravel()
    w = np.asarray(inputs, dtype=float).ravel()
    if x.size not in (3, 6) or w.size != 2:
        raise ParameterError(f"`state` must have 3 or 6 values and `inputs` 2, got {x.size} "
                             f"and {w.size}", field="state")
    f = _forces_ls(float(x[0]), float(x[1]), float(x[2]), float(w[0]), float(w[1]),
                   params.to_record())
    return LowSpeedForces(*(float(v) for v in f))


#: The Esso Osaka 3 m model, Miyauchi et al. (2022): the defaults.
ESSO_OSAKA_3M = MMGLowSpeedParams()
