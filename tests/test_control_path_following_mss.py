"""seahelm's LOS and ILOS laws against MSS's ``LOSchi.m`` and ``ILOSpsi.m`` (Fossen, Marine Systems
Simulator, GNC/), typed here from those files and replayed on the track seahelm simulates: the
nonlinear Mariner with the PID heading autopilot, starting 200 m off a straight leg due north,
controller sampled every 0.5 s (MSS's ``h``). At every controller sample the heading reference
seahelm recorded equals MSS's

    pi_h = atan2(yk_next - yk, xk_next - xk)
    y_e  = -(x - xk) sin(pi_h) + (y - yk) cos(pi_h)
    psi_ref = pi_h - atan((y_e + kappa y_int) / Delta_h)
    y_int  += h Delta_h y_e / (Delta_h^2 + (y_e + kappa y_int)^2)      (ILOSpsi.m; LOSchi.m: no y_int)

computed from seahelm's recorded north and east. One leg only: the waypoint switching rules
differ (MSS: the remaining along-track distance below R_switch; seahelm: inside the acceptance
circle or past the normal through the next waypoint). Quoted on ``docs/guide/coming-from.rst``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.control.guided import guided
from seahelm.control.path_following import ILOS, LOS, route_params
from seahelm.control.pid import PID_HEADING
from seahelm.simulation.engine import simulate

WAYPOINTS = [[0.0, 0.0], [30000.0, 0.0]]
DELTA, KAPPA, H = 800.0, 7.7 / 4.0, 0.5  # look-ahead [m], ILOS gain [m/s], sample period [s]
DT = 0.1


def mss_law(north, east, kappa):
    """ψ_ref at each sample: ILOSpsi.m (kappa > 0) or LOSchi.m (kappa = 0, no integral)."""
    (xk, yk), (xn, yn) = WAYPOINTS
    pi_h = math.atan2(yn - yk, xn - xk)
    y_int, out = 0.0, []
    for x, y in zip(north, east):
        y_e = -(x - xk) * math.sin(pi_h) + (y - yk) * math.cos(pi_h)
        out.append(pi_h - math.atan((y_e + kappa * y_int) / DELTA))
        y_int = y_int + H * DELTA * y_e / (DELTA**2 + (y_e + kappa * y_int) ** 2)
    return np.array(out)


@pytest.mark.parametrize("law", ["ilos", "los"])
def test_heading_reference_equals_mss_on_the_same_track(law):
    kind, kappa = (ILOS, KAPPA) if law == "ilos" else (LOS, 0.0)
    ctrl = guided(kind, PID_HEADING)
    extra = {"kappa": KAPPA} if law == "ilos" else {}
    route = route_params(WAYPOINTS, law=kind, lookahead=DELTA, acceptance_radius=500.0, **extra)
    params = ctrl.params_type(**route.as_dict(), kp=3.0, ki=0.0, kd=60.0,
                              max_command=math.radians(35.0))
    res = simulate(ship="mariner-nonlinear", controller=ctrl, controller_params=params,
                   x0=[0.0, 0.0, 0.0, 0.0, 200.0, 0.3], t_final=600.0, dt=DT, controller_dt=H)
    assert res.ok.all()
    every = round(H / DT)
    samples = np.arange(0, res.time.size - 1, every)  # the last record is not a new sample
    assert samples.size == 1200 and np.allclose(res.time[samples], H * np.arange(1200))
    want = mss_law(res["north"][0, samples], res["east"][0, samples], kappa)
    got = res["heading_reference"][0, samples]
    np.testing.assert_allclose(got, want, rtol=0.0, atol=1e-12)
    assert np.ptp(got) > 0.2  # it steered: from 200 m off towards the leg
