"""Propeller and rudder forces in all four quadrants of (u, n): Hachii's propeller, Kitagawa's
reversed rudder inflow (the low-speed MMG model of Miyauchi et al. 2022).

These are the propeller and rudder parts of the low-speed manoeuvring model of the Esso Osaka
3 m model by Miyauchi, Maki, Umeda, Rachman & Akimoto (2022) (:mod:`seahelm.vessels.mmg_low_speed`):
the MMG's first-quadrant forms extended to astern speed (u < 0) and to the propeller turning
astern (n < 0). u is the surge speed, v the sway speed of midship, r the yaw rate,
v' = v/U, r' = r L/U, J_s = u/(n D_P) the ship's advance ratio (without wake).

Wake (ahead speed only)
    w_P = w_P0 − τ |v' + x'_P r'| − C'_P (v' + x'_P r')²; 1 − w_P for u > 0, 1 for u ≤ 0
    (the propeller leads the hull), clipped to (0, 1].

Thrust, propeller model ``"hachii"`` (Hachii et al., as used by Miyauchi et al. 2022)
    n ≥ 0: X_P = (1 − t_P) ρ n² D⁴ K_T(J), K_T = k_0 + k_1 J + k_2 J², J = J_s (1 − w_P) —
    evaluated as ρ D² (1 − t_P)(k_0 n² D² + k_1 n D u_P + k_2 u_P²), u_P = u (1 − w_P), which is
    the same for n ≠ 0 and continuous at n = 0.
    n < 0: X_P = ρ n² D⁴ (C_6 + C_7 J_s) for J_s ≥ C_10, ρ n² D⁴ C_3 otherwise (no thrust
    deduction).
Thrust, propeller model ``"wageningen"``
    The four-quadrant Wageningen B4-70 series (:mod:`seahelm.hydrodynamics.four_quadrant`,
    Roddy, Hess & Faller 2006) scaled to the ship's bollard thrust k_0, with the same wake and
    (1 − t_P) for n ≥ 0: the alternative when no Hachii coefficients are known.

Side force and yaw moment of the propeller (both models: Hachii's fits; Ueno's for u < 0, n > 0)
    n ≥ 0, u ≥ 0: 0. n ≥ 0, u < 0: Y_P = ½ρ L d (n P)² (A_6 J_s² + A_7 J_s + A_8),
    N_P = ½ρ L² d (n P)² (B_6 J_s² + B_7 J_s + B_8), P = D_P p the pitch.
    n < 0: Y_P = ½ρ L d (n D)² × (A_3 + A_4 J_s) for J_s < J_syn = −0.35, A_5 for J_s > J_syn0 =
    −0.06, (A_1 + A_2 J_s) between; N_P the same with ½ρ L² d and B_1 … B_5.

Rudder inflow, ``"kitagawa"`` (the published model's, its switch ``switch_ur = 1``)
    n ≥ 0 with K_T > 0 (K_T the effective thrust coefficient X_P/(ρ n² D⁴ (1 − t_P)), or
    X_P/(ρ n² D⁴) for n < 0): the low-speed MMG form
    u_R = ε √(η (u_P + κ (√(u_P² + 8 K_T n² D²/π) − u_P))² + (1 − η) u_P²), κ = k_x/ε;
    otherwise, u ≥ 0 (Kitagawa's reversed race): u_R² = η sgn(a) a² + (1 − η) b² + C_PR u²
    (signed), a = u ε (1 − w_P) + n D k_x,rev √(8 |K_T|/π), b = u ε (1 − w_P);
    u < 0 with n < 0 or K_T ≤ 0: u_R = u.
Rudder inflow, ``"yasukawa-astern"`` (the published simulator's switch ``switch_ur = 2``)
    As ``"kitagawa"``, but astern with the propeller ahead (u < 0, n ≥ 0, K_T > 0) Yasukawa's
    form: u_R = min(u_R*, u_R**), u_R* = u_P ε (η κ (sgn(u) √(1 + 8 K_T/(π J²)) − 1) + 1)
    (= ε (u + η κ (√(u² + 8 K_T n² D²/π) − u)) for u < 0, written so), u_R** = 0.7 π n D C_uR0.
    v_R = −γ (v + l_R r), γ = γ_P where v + x_R r ≥ 0, γ_N otherwise (x_R the rudder's
    position, l_R = l'_R L); U_R² = u_R² + v_R², α_R = δ − atan2(v_R, u_R).
Rudder force (Fujii's normal force)
    F_N = ½ρ A_R U_R² (6.13 Λ/(2.25 + Λ)) sin α_R; X_R = −(1 − t_R) F_N sin δ,
    Y_R = −(1 + a_H) F_N cos δ, N_R = −(x_R + a_H x_H) F_N cos δ.

The equations are those of Miyauchi et al. (2022) as tabulated with their parameters in the
authors' open simulator (``NAOE-5thLab/mmg-1p1r-simulator``); this module is written from the
equations, not from that code.

References
----------
Miyauchi, Y., Maki, A., Umeda, N., Rachman, D. M. & Akimoto, Y. (2022). System parameter
exploration of ship maneuvering model for automatic docking/berthing using CMA-ES. J. Mar.
Sci. Technol. 27, 1065–1083. doi:10.1007/s00773-022-00889-3.
Hachii's four-quadrant propeller fits and Kitagawa's reversed rudder inflow are taken as
Miyauchi et al. (2022) state and cite them (the originals were not consulted).
Fujii, H. & Tsuda, T. (1961). Experimental researches on rudder performance (2). J. Zosen
Kiokai 110, 31–42.
Roddy, R. F., Hess, D. E. & Faller, W. E. (2006). Neural network predictions of the
4-quadrant Wageningen propeller series. NSWCCD-50-TR-2006/004.
"""

from __future__ import annotations

import math

from numba import njit

from .four_quadrant import ct_cq, fourier_coefficients, thrust_coefficient_4q

__all__ = ["PROPELLER_MODELS", "RUDDER_INFLOW_MODELS", "HACHII", "WAGENINGEN", "KITAGAWA",
           "YASUKAWA_ASTERN",
           "wake_factor", "propeller_forces", "rudder_forces", "fujii_normal_coefficient"]

#: Propeller models by name: the value of the parameter ``propeller_model``.
HACHII = 0.0
WAGENINGEN = 1.0
PROPELLER_MODELS: dict[str, float] = {"hachii": HACHII, "wageningen": WAGENINGEN}

#: Rudder inflow models by name: the value of the parameter ``rudder_inflow_model``.
KITAGAWA = 0.0
YASUKAWA_ASTERN = 1.0
RUDDER_INFLOW_MODELS: dict[str, float] = {"kitagawa": KITAGAWA,
                                          "yasukawa-astern": YASUKAWA_ASTERN}

_COEFFS = fourier_coefficients()
#: K_T at J = 0 of the B4-70 series: C_T*(0) (π/8)(0.7π)².
_KT0_SERIES = float(thrust_coefficient_4q(0.0)) * math.pi / 8.0 * (0.7 * math.pi) ** 2
_EPS = 2.220446049250313e-16


@njit(cache=True)
def wake_factor(u, vn, rn, p):  # pragma: no cover - compiled
    """1 − w_P [-] (module docstring), for the surge speed u [m/s] and v', r' [-]."""
    if u <= 0.0:
        return 1.0
    b = vn + p.x_P * rn
    w = p.w_P0 - p.tau_P * abs(b) - p.C_P * b * b
    f = 1.0 - w
    if f > 1.0:
        return 1.0
    if f <= 0.0:
        return _EPS
    return f


@njit(cache=True)
def propeller_forces(u, vn, rn, n, p):  # pragma: no cover - compiled
    """(X_P, Y_P, N_P, 1 − w_P, K_T) [N, N, N·m, -, -] of the propeller (module docstring).

    ``p`` has ``rho``, ``length``, ``draft``, ``propeller_diameter``, ``pitch_ratio``, the wake
    terms, ``t_P``, ``k_0``–``k_2``, ``C_3``, ``C_6``, ``C_7``, ``C_10``, ``A_1``–``A_8``,
    ``B_1``–``B_8``, ``J_syn``, ``J_syn0`` and ``propeller_model``."""
    rho = p.rho
    D = p.propeller_diameter
    L = p.length
    one_w = wake_factor(u, vn, rn, p)
    u_P = u * one_w
    if p.propeller_model >= 0.5:  # Wageningen B4-70, four quadrants
        w = 0.7 * math.pi * n * D
        ct, _cq = ct_cq(math.atan2(u_P, w), _COEFFS)
        thrust = (p.k_0 / _KT0_SERIES) * ct * 0.5 * rho * (u_P * u_P + w * w) * 0.25 * math.pi \
            * D * D
        X_P = (1.0 - p.t_P) * thrust if n >= 0.0 else thrust
    elif n >= 0.0:
        X_P = (1.0 - p.t_P) * rho * D * D * (p.k_0 * n * n * D * D + p.k_1 * n * D * u_P
                                              + p.k_2 * u_P * u_P)
    elif u / (n * D) >= p.C_10:
        X_P = rho * D * D * (p.C_6 * n * n * D * D + p.C_7 * n * D * u)
    else:
        X_P = rho * D ** 4 * n * n * p.C_3
    Y_P = 0.0
    N_P = 0.0
    qy = 0.5 * rho * L * p.draft
    if n >= 0.0:
        if u < 0.0:
            P = D * p.pitch_ratio
            # (n P)² (a J_s² + b J_s + c) with J_s = u/(n D), written without dividing by n
            ps = P * P
            Y_P = qy * ps * (p.A_6 * u * u / (D * D) + p.A_7 * n * u / D + p.A_8 * n * n)
            N_P = qy * L * ps * (p.B_6 * u * u / (D * D) + p.B_7 * n * u / D + p.B_8 * n * n)
    else:
        J_s = u / (n * D)
        nd2 = n * n * D * D
        if J_s < p.J_syn:
            cy = p.A_3 + p.A_4 * J_s
            cn = p.B_3 + p.B_4 * J_s
        elif J_s > p.J_syn0:
            cy = p.A_5
            cn = p.B_5
        else:
            cy = p.A_1 + p.A_2 * J_s
            cn = p.B_1 + p.B_2 * J_s
        Y_P = qy * nd2 * cy
        N_P = qy * L * nd2 * cn
    # the effective thrust coefficient the rudder inflow uses
    if n > _EPS:
        K_T = X_P / (rho * D ** 4 * n * n * (1.0 - p.t_P))
    elif n < -_EPS:
        K_T = X_P / (rho * D ** 4 * n * n)
    else:
        K_T = 0.0
    return X_P, Y_P, N_P, one_w, K_T


@njit(cache=True)
def fujii_normal_coefficient(aspect_ratio):  # pragma: no cover - compiled
    """Fujii's rudder normal-force gradient f_α = 6.13 Λ/(2.25 + Λ) [-] (Fujii & Tsuda 1961)."""
    return 6.13 * aspect_ratio / (2.25 + aspect_ratio)


@njit(cache=True)
def rudder_forces(u, v, r, delta, n, one_w, K_T, p):  # pragma: no cover - compiled
    """(X_R, Y_R, N_R, F_N, u_R, v_R) [N, N, N·m, N, m/s, m/s] of the rudder (module
    docstring); ``one_w`` and ``K_T`` from :func:`propeller_forces`."""
    D = p.propeller_diameter
    L = p.length
    span = math.sqrt(p.rudder_area * p.rudder_aspect_ratio)
    eta = D / span
    eps = p.epsilon
    u_P = u * one_w
    if n >= 0.0 and K_T > 0.0:
        kappa = p.k_x / eps
        race = math.sqrt(u_P * u_P + 8.0 * K_T * n * n * D * D / math.pi)
        if u < 0.0 and p.rudder_inflow_model >= 0.5:  # Yasukawa's astern inflow
            u_star = eps * (u + eta * kappa * (race - u))
            u_R = min(u_star, 0.7 * math.pi * n * D * p.C_uR0)
        else:
            jet = u_P + kappa * (race - u_P)
            u_R = eps * math.sqrt(eta * jet * jet + (1.0 - eta) * u_P * u_P)
    elif u >= 0.0:
        a = u * eps * one_w + n * D * p.k_x_reverse * math.sqrt(8.0 * abs(K_T) / math.pi)
        b = u * eps * one_w
        sq = eta * math.copysign(a * a, a) + (1.0 - eta) * b * b + p.C_PR * u * u
        u_R = math.copysign(math.sqrt(abs(sq)), sq)
    else:
        u_R = u
    x_R = p.x_R * L
    gamma = p.gamma_P if v + x_R * r >= 0.0 else p.gamma_N
    v_R = -gamma * (v + p.l_R * L * r)
    U2 = u_R * u_R + v_R * v_R
    alpha = delta - math.atan2(v_R, u_R)
    F_N = 0.5 * p.rho * p.rudder_area * U2 * fujii_normal_coefficient(p.rudder_aspect_ratio) \
        * math.sin(alpha)
    sin_d = math.sin(delta)
    cos_d = math.cos(delta)
    X_R = -(1.0 - p.t_R) * F_N * sin_d
    Y_R = -(1.0 + p.a_H) * F_N * cos_d
    N_R = -(x_R + p.a_H * p.x_H * L) * F_N * cos_d
    return X_R, Y_R, N_R, F_N, u_R, v_R
