"""Low-speed cross-flow hull (Yoshimura et al. 2009): integrals, limits, continuity, range."""

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import quad

from seahelm.errors import ParameterError, ValidityRangeWarning
from seahelm.hydrodynamics.low_speed_hull import (
    FROUDE_MAX,
    check_range,
    cross_flow_integrals,
    low_speed_hull,
    low_speed_weight,
    matching_cross_flow_drag,
)
from seahelm.vessels.mmg import KVLCC2_FULL

P = KVLCC2_FULL
RHO, L, D = P.rho, P.length, P.draft
COEF = dict(X_0F=-0.022, X_0A=-0.03, X_vr=0.002, Y_v=-0.315, Y_r=0.083, N_v=-0.137,
            N_r=-0.049, C_D=0.9, C_rY=1.0, C_rN=0.7)


def _hull(u, v, r, **kw):
    c = {**COEF, **kw}
    return np.array(low_speed_hull(u, v, r, L, D, RHO, c["X_0F"], c["X_0A"], c["X_vr"],
                                   c["Y_v"], c["Y_r"], c["N_v"], c["N_r"], c["C_D"],
                                   c["C_rY"], c["C_rN"]))


@pytest.mark.parametrize("a, b", [(1.0, 0.0), (-2.0, 0.5), (0.3, 4.0), (-0.1, -3.0),
                                  (0.0, 2.0), (2.0, 4.0), (0.0, 0.0), (1e-9, 1.0)])
def test_cross_flow_integrals_against_quad(a, b):
    iy, i_n = cross_flow_integrals(a, b)
    kink = [-a / b] if b != 0.0 and abs(a / b) < 0.5 else None
    ref_y = quad(lambda x: abs(a + b * x) * (a + b * x), -0.5, 0.5, points=kink,
                 epsabs=1e-14, epsrel=1e-13)[0]
    ref_n = quad(lambda x: x * abs(a + b * x) * (a + b * x), -0.5, 0.5, points=kink,
                 epsabs=1e-14, epsrel=1e-13)[0]
    assert iy == pytest.approx(ref_y, rel=1e-12, abs=1e-14)
    assert i_n == pytest.approx(ref_n, rel=1e-12, abs=1e-14)


def test_pure_sway_is_cross_flow_drag_without_yaw_moment():
    v = 0.7
    X, Y, N = _hull(0.0, v, 0.0)
    assert Y == pytest.approx(-0.5 * RHO * L * D * COEF["C_D"] * v * abs(v), rel=1e-14)
    assert X == 0.0
    assert N == pytest.approx(0.0, abs=1e-9 * abs(Y) * L)


def test_pure_yaw_at_rest():
    """u = v = 0: no sway force (odd integrand); N = −½ρL⁴d C_D (C_rN r)|C_rN r| / 32, since
    ∫ x |x| x² dx over [−½, ½] = 2 ∫₀^½ x³ dx = 1/32."""
    r = -0.004
    X, Y, N = _hull(0.0, 0.0, r)
    c = COEF["C_rN"] * r
    assert X == 0.0 and Y == pytest.approx(0.0, abs=1e-6)
    assert N == pytest.approx(-0.5 * RHO * L ** 4 * D * COEF["C_D"] * c * abs(c) / 32.0,
                              rel=1e-12)


def test_straight_ahead_linear_terms_are_the_mmg_ones():
    """At u = U (v, r → 0 against U) with C_D = 0 the forces are ½ρLdU² (−R'_0, Y'_v v' +
    Y'_r r', L (N'_v v' + N'_r r')) to first order."""
    U, v, r = 8.0, 1e-4, 1e-6
    X, Y, N = _hull(U, v, r, C_D=0.0)
    q = 0.5 * RHO * L * D * U ** 2
    vn, rn = v / U, r * L / U
    assert Y == pytest.approx(q * (COEF["Y_v"] * vn + COEF["Y_r"] * rn), rel=1e-6)
    assert N == pytest.approx(q * L * (COEF["N_v"] * vn + COEF["N_r"] * rn), rel=1e-6)
    assert X == pytest.approx(q * COEF["X_0F"], rel=1e-5)  # |β|/π (X'_0A − X'_0F): 1.4e-6


def test_astern_is_the_fore_aft_mirror_apart_from_the_resistance():
    u, v, r = 2.0, 0.6, 0.003
    X, Y, N = _hull(u, v, r, X_0A=COEF["X_0F"])
    Xm, Ym, Nm = _hull(-u, v, -r, X_0A=COEF["X_0F"])
    assert (Ym, Nm) == pytest.approx((Y, -N), rel=1e-13)
    assert Xm == pytest.approx(-X, rel=1e-13)
    # straight astern: the astern resistance coefficient, resisting the motion
    Xa = _hull(-3.0, 0.0, 0.0)[0]
    assert Xa == pytest.approx(0.5 * RHO * L * D * 9.0 * -COEF["X_0A"], rel=1e-14)


@pytest.mark.parametrize("v, r", [(0.5, 0.0), (0.0, 0.002), (-0.3, 0.001), (0.0, 0.0)])
def test_continuous_through_zero_surge_speed(v, r):
    """|F(ε) − F(0)| = O(ε): non-dimensional (X, Y by ½ρLd, N by ½ρL²d [m²/s²]), the change
    is at most (|coefficients| ≤ 1) × (|v| + |r| L ≤ 1 m/s) × |ε| per term."""
    unit = 0.5 * RHO * L * D * np.array([1.0, 1.0, L])
    at = _hull(0.0, v, r) / unit
    for eps in (1e-3, -1e-3, 1e-7, -1e-7):
        assert np.all(np.abs(_hull(eps, v, r) / unit - at) <= 10.0 * abs(eps))


def test_weight_ramps_and_limits():
    floor = 1e-3 * math.sqrt(9.81 * L)
    U = 4.0

    def w(beta, r=0.0):
        return low_speed_weight(U * math.cos(beta), -U * math.sin(beta), r, L, floor)

    assert w(0.0) == 0.0 and w(math.radians(30.0)) == 0.0
    assert w(math.radians(37.5)) == pytest.approx(0.5)
    assert w(math.radians(45.0)) == 1.0 and w(math.radians(120.0)) == 1.0  # astern
    assert w(0.0, 1.25 * U / L) == pytest.approx(0.5)  # r' = 1.25
    assert low_speed_weight(0.0, 0.0, 1e-3, L, floor) == 1.0  # turning on the spot


def test_matching_cross_flow_drag_equals_the_mmg_sway_force_at_30_deg():
    c_d = matching_cross_flow_drag(P.Y_v, P.Y_vvv)
    b = math.radians(30.0)
    U = 5.0
    u, v = U * math.cos(b), -U * math.sin(b)
    vn = v / U
    mmg = 0.5 * RHO * L * D * U ** 2 * (P.Y_v * vn + P.Y_vvv * vn ** 3)
    Y = _hull(u, v, 0.0, C_D=c_d, Y_v=P.Y_v)[1]
    assert Y == pytest.approx(mmg, rel=1e-12)
    assert c_d == pytest.approx(0.888, abs=5e-4)  # the KVLCC2 (module docstring)
    with pytest.raises(ParameterError, match="Y_vvv"):
        matching_cross_flow_drag(-0.315, 1.0)
    # (the message named the field twice: "`drift` `drift` = nan rad must be ...")
    with pytest.raises(ParameterError, match=r"^`drift` must be in \(0, pi/2\) \[rad\], got nan"):
        matching_cross_flow_drag(P.Y_v, P.Y_vvv, math.nan)


def test_range_warns_above_the_froude_limit_and_raises_in_strict_mode():
    g = 9.81
    fast = 1.5 * FROUDE_MAX * math.sqrt(g * L)
    slow = 0.5 * FROUDE_MAX * math.sqrt(g * L)
    drift = np.array([[0.1, 0.9], [0.1, 0.9]])
    speed = np.array([[fast, fast], [fast, slow]])
    with pytest.warns(ValidityRangeWarning, match="1 of 2 run"):
        out = check_range(speed, drift, np.zeros((2, 2)), L, 0.01)
    assert out.tolist() == [True, False]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert not check_range(np.array([fast, slow]), np.array([0.1, 0.9]), [0.0, 0.0], L,
                               0.01)
    with pytest.raises(ParameterError, match="cross-flow"):
        check_range(speed, drift, np.zeros((2, 2)), L, 0.01, strict=True)
