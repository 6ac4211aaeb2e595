"""Wind loads of Fujiwara, Ueno & Nimura (1998): regression of the force coefficients on the
ship's windage geometry.

The coefficients of the surge force, the sway force and the yaw moment about midships are
Fourier series in the relative wind angle ψ_A,

    C_X = X_0 + X_1 cos ψ_A + X_3 cos 3ψ_A + X_5 cos 5ψ_A,
    C_Y = Y_1 sin ψ_A + Y_3 sin 3ψ_A + Y_5 sin 5ψ_A,
    C_N = N_1 sin ψ_A + N_2 sin 2ψ_A + N_3 sin 3ψ_A,

X_A = C_X ½ρ_a U_A² A_T, Y_A = C_Y ½ρ_a U_A² A_L, N_A = C_N ½ρ_a U_A² L A_L, and each
coefficient X_k, Y_k, N_k is a linear regression on ratios of the windage geometry
(:func:`fujiwara_coefficients`): L (L_pp), B, A_T, A_L, A_OD (lateral area of the
superstructure), C (centre of A_L forward of midships), C_BR (centre of A_OD), H_BR (height of
the top of the superstructure) and H_C (height of the centre of A_L). The regression
constants are those of Fujiwara et al. (1998) as used with the Esso Osaka model by Miyauchi
et al. (2022).

Angle convention: ψ_A is measured anticlockwise (seen from above) from the bow to the
direction the wind comes from, so in seahelm's bearing q (positive from starboard, clockwise)
ψ_A = −q: a beam wind from starboard (q = 90°) gives Y_A = −Y_1 ½ρ_a U_A² A_L (to port for
Y_1 > 0). Forces in body axes: x forward, y to starboard, N positive turning the bow to
starboard — the signs of the Esso Osaka model of Miyauchi et al. (2022).

Validity: the regression was fitted to wind-tunnel data of merchant ships; outside the
database's ratios it extrapolates (no range check here: the published ranges were not at hand).

References
----------
Fujiwara, T., Ueno, M. & Nimura, T. (1998). Estimation of wind forces and moments acting on
ships. J. Soc. Naval Archit. Japan 183, 77–90.
Miyauchi, Y., Maki, A., Umeda, N., Rachman, D. M. & Akimoto, Y. (2022). System parameter
exploration of ship maneuvering model for automatic docking/berthing using CMA-ES. J. Mar.
Sci. Technol. 27, 1065–1083.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numba import njit

__all__ = ["fujiwara_coefficients", "fujiwara_wind_loads", "COEFFICIENT_NAMES",
           "FUJIWARA_GEOMETRY"]

#: The series coefficients, in the order :func:`fujiwara_coefficients` returns them.
COEFFICIENT_NAMES = ("X_0", "X_1", "X_3", "X_5", "Y_1", "Y_3", "Y_5", "N_1", "N_2", "N_3")

#: The geometry the regression needs: the parameter fields of the wind-load model.
FUJIWARA_GEOMETRY = ("windage_length", "windage_breadth", "windage_frontal_area",
                     "windage_lateral_area", "superstructure_lateral_area", "windage_centre",
                     "superstructure_centre", "superstructure_height", "windage_height")

# Regression constants of Fujiwara et al. (1998): each coefficient is c[0] + Σ c[i] ratio_i,
# the ratios in the order of the functions below.
_X0 = (-0.330, 0.293, 0.0193, 0.6820)
_X1 = (-1.353, 1.700, 2.8700, -0.4630, -0.570, -6.640, -0.0123, 0.0202)
_X3 = (0.830, -0.413, -0.0827, -0.5630, 0.804, -5.670, 0.0401, -0.1320)
_X5 = (0.0372, -0.0075, -0.1030, 0.0921)
_Y1 = (0.684, 0.717, -3.2200, 0.0281, 0.0661, 0.2980)
_Y3 = (-0.400, 0.282, 0.3070, 0.0519, 0.0526, -0.0814, 0.0582)
_Y5 = (0.122, -0.166, -0.0054, -0.0481, -0.0136, 0.0864, -0.0297)
_N1 = (0.2990, 1.710, 0.183, -1.09, -0.0442, -0.289, 4.24, -0.0646, 0.0306)
_N2 = (0.1170, 0.123, -0.323, 0.0041, -0.166, -0.0109, 0.174, 0.214, -1.06)
_N3 = (0.0230, 0.0385, -0.0339, 0.0023)


def _series(c: tuple[float, ...], ratios: tuple[Any, ...]) -> Any:
    out = c[0]
    for k, x in zip(c[1:], ratios, strict=True):
        out = out + k * x
    return out


def fujiwara_coefficients(*, length: Any, breadth: Any, frontal_area: Any, lateral_area: Any,
                          superstructure_area: Any, centre: Any, superstructure_centre: Any,
                          superstructure_height: Any, centre_height: Any) -> dict[str, Any]:
    """The series coefficients X_0 … N_3 of Fujiwara et al. (1998) from the windage geometry.

    Parameters
    ----------
    length : float or array_like
        L_pp [m].
    breadth : float or array_like
        B [m].
    frontal_area, lateral_area : float or array_like
        A_T, A_L [m²].
    superstructure_area : float or array_like
        A_OD [m²].
    centre, superstructure_centre : float or array_like
        C, C_BR: centres of A_L and A_OD forward of midships [m].
    superstructure_height, centre_height : float or array_like
        H_BR, H_C above the waterline [m].

    Returns
    -------
    dict
        :data:`COEFFICIENT_NAMES` -> value [-] (arrays for array input).
    """
    L, B, AT, AL, AOD = length, breadth, frontal_area, lateral_area, superstructure_area
    C, CBR, HBR, HC = centre, superstructure_centre, superstructure_height, centre_height
    return {
        "X_0": _series(_X0, (B * HBR / AT, C / HC, AOD / L / L)),
        "X_1": _series(_X1, (AL / L / B, L * HC / AL, L * HBR / AL, AOD / AL, AT / L / B,
                             L * L / AT, L / HC)),
        "X_3": _series(_X3, (AL / L / HBR, AL / AT, L * HC / AL, AOD / AL, AOD / L / L,
                             C / HC, CBR / L)),
        "X_5": _series(_X5, (AL / AOD, CBR / L, AL / L / B)),
        "Y_1": _series(_Y1, (CBR / L, C / L, AL / AOD, C / HC, AT / (B * HBR))),
        "Y_3": _series(_Y3, (AL / (L * B), L * HC / AL, CBR / L, B / HBR, AOD / AL,
                             AT / (B * HBR))),
        "Y_5": _series(_Y5, (AL / (L * B), L / HBR, CBR / L, B * B / AT, C / L, C * HC / AL)),
        "N_1": _series(_N1, (C / L, L * HC / AL, AT / AL, C / HC, AL / (L * B), AT / L ** 2,
                             B * B / AT, CBR / L)),
        "N_2": _series(_N2, (CBR / L, C / L, AL / AOD, AT / B ** 2, L / HBR, AT / (B * HBR),
                             AL / (L * B), AL / L ** 2)),
        "N_3": _series(_N3, (CBR / L, AT / (B * HBR), AL / AT)),
    }


def fujiwara_constants(r: Any) -> dict[str, np.ndarray]:
    """The per-run constants of the compiled loads: the series coefficients (``fw_X_0`` …)
    and the dynamic-pressure areas, from the parameter fields ``r[...]`` (arrays over runs)."""
    c = fujiwara_coefficients(
        length=r["windage_length"], breadth=r["windage_breadth"],
        frontal_area=r["windage_frontal_area"], lateral_area=r["windage_lateral_area"],
        superstructure_area=r["superstructure_lateral_area"], centre=r["windage_centre"],
        superstructure_centre=r["superstructure_centre"],
        superstructure_height=r["superstructure_height"], centre_height=r["windage_height"])
    out = {f"fw_{k}": np.asarray(v, dtype=float) for k, v in c.items()}
    out["fw_q_frontal"] = 0.5 * r["rho_air"] * r["windage_frontal_area"]
    out["fw_q_lateral"] = 0.5 * r["rho_air"] * r["windage_lateral_area"]
    return out


@njit(cache=True)
def fujiwara_wind_loads(p, speed, angle, cos_angle, sin_angle):  # pragma: no cover - compiled
    """Fujiwara et al. (1998) wind loads (X, Y, N) [N, N, N·m] in body axes for the relative
    wind ``speed`` [m/s] from the bearing ``angle`` [rad] (positive from starboard); the
    per-run constants of :func:`fujiwara_constants`. ψ_A = −angle (module docstring)."""
    u2 = speed * speed
    c3 = math.cos(3.0 * angle)
    c5 = math.cos(5.0 * angle)
    s2 = math.sin(2.0 * angle)
    s3 = math.sin(3.0 * angle)
    s5 = math.sin(5.0 * angle)
    cx = p.fw_X_0 + p.fw_X_1 * cos_angle + p.fw_X_3 * c3 + p.fw_X_5 * c5
    cy = -(p.fw_Y_1 * sin_angle + p.fw_Y_3 * s3 + p.fw_Y_5 * s5)
    cn = -(p.fw_N_1 * sin_angle + p.fw_N_2 * s2 + p.fw_N_3 * s3)
    return (cx * p.fw_q_frontal * u2, cy * p.fw_q_lateral * u2,
            cn * p.fw_q_lateral * p.windage_length * u2)
