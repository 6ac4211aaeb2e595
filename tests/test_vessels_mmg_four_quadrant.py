"""Four-quadrant MMG model (mmg-4q): engine and shaft, equality with mmg ahead, crash stop."""

import math

import numpy as np
import pytest

from seahelm.actuators.servo import RUDDER_SERVO
from seahelm.control.open_loop import OPEN_LOOP
from seahelm.errors import ParameterError
from seahelm.registry import get_model
from seahelm.simulation.engine import simulate
from seahelm.vessels.mmg import KVLCC2_FULL, KVLCC2_FULL_SERVO, MMG
from seahelm.vessels.mmg_four_quadrant import (
    KVLCC2_FULL_4Q,
    KVLCC2_L7_4Q,
    MMG_4Q,
    from_mmg,
    self_propulsion_rps,
)

@pytest.mark.parametrize("field, value", [("reversal_time", 0.0), ("max_power", -1.0),
                                          ("astern_rps", 1.2)])
def test_bad_engine_fields_of_a_ship(field, value):
    with pytest.raises(ParameterError, match=field):
        from_mmg(KVLCC2_FULL, **{field: value})


def test_registry_and_catalog_estimates():
    assert get_model("mmg-4q") is MMG_4Q
    p = KVLCC2_FULL_4Q
    n_sp = self_propulsion_rps(KVLCC2_FULL, KVLCC2_FULL.approach_speed)
    assert p.rated_rps == pytest.approx(n_sp / 0.85 ** (1 / 3))
    assert p.astern_rps < 0.0 < p.reversal_rps < p.rated_rps
    # the L7 is close to the Froude-scaled full-scale ship (same coefficients, fresh water)
    assert KVLCC2_L7_4Q.rated_rps == pytest.approx(p.rated_rps * math.sqrt(45.7), rel=0.01)


def _states(n):
    rng = np.random.default_rng(3)
    u = rng.uniform(2.0, 8.0, 20)
    return np.column_stack([u, rng.uniform(-1, 1, 20), rng.uniform(-0.01, 0.01, 20),
                            np.zeros(20), np.zeros(20), rng.uniform(-3, 3, 20),
                            np.full(20, n), np.zeros(20)])


def test_ahead_derivative_equals_mmg_bit_for_bit():
    n = self_propulsion_rps(KVLCC2_FULL, KVLCC2_FULL.approach_speed)
    x = _states(n)
    delta = np.linspace(-0.6, 0.6, 20)
    d_mmg = MMG.derivative(0.0, x[:, :6], np.column_stack([delta, np.full(20, n)]),
                           KVLCC2_FULL)
    order = n / KVLCC2_FULL_4Q.rated_rps
    d_4q = MMG_4Q.derivative(0.0, x, np.column_stack([delta, np.full(20, order)]),
                             KVLCC2_FULL_4Q)
    np.testing.assert_array_equal(d_4q[:, :6], d_mmg)
    np.testing.assert_allclose(d_4q[:, 6], 0.0, atol=1e-12)  # governor holds the rps
    np.testing.assert_array_equal(d_4q[:, 7], 0.0)  # no reversal: the clock stays at 0


def _run(model, params, x0, ref, t_final=600.0, dt=1.0):
    return simulate(model, params, x0, t_final=t_final, dt=dt, actuator=RUDDER_SERVO,
                    actuator_params=KVLCC2_FULL_SERVO, actuator_x0=[0.0],
                    controller=OPEN_LOOP, reference=ref, record_every=10)


@pytest.mark.parametrize("rudder", [math.radians(35.0), math.radians(-10.0)])
def test_turning_circle_equals_mmg(rudder):
    U0 = KVLCC2_FULL.approach_speed
    n = self_propulsion_rps(KVLCC2_FULL, U0)
    a = _run(MMG, KVLCC2_FULL, [U0, 0, 0, 0, 0, 0],
             {"rudder_command": rudder, "propeller_rps": n})
    b = _run(MMG_4Q, KVLCC2_FULL_4Q, [U0, 0, 0, 0, 0, 0, n, 0],
             {"rudder_command": rudder, "engine_order": n / KVLCC2_FULL_4Q.rated_rps})
    for name in ("north", "east", "heading", "surge_speed"):
        scale = 1.0 + np.abs(a[name]).max()
        np.testing.assert_allclose(b[name], a[name], rtol=0, atol=1e-9 * scale)


def test_crash_stop_comes_to_rest_and_reverses_the_shaft():
    p = KVLCC2_FULL_4Q
    U0 = p.approach_speed
    n = self_propulsion_rps(p, U0)
    r = _run(MMG_4Q, p, [U0, 0, 0, 0, 0, 0, n, 0], {"rudder_command": 0.0,
                                                    "engine_order": -1.0}, t_final=2400.0)
    u = r["surge_speed"][0]
    rps = r["propeller_rps"][0]
    assert rps[-1] == pytest.approx(p.astern_rps, rel=1e-3)
    assert np.any(u <= 0.0)  # dead in the water, then astern
    k = int(np.argmax(u <= 0.0))
    reach = r["north"][0, k]
    assert 0.0 < reach < 20 * p.length


@pytest.mark.parametrize("delay", [0.0, 30.0, 90.0])
def test_reversal_delay_is_honoured_as_a_time(delay):
    """Fuel cut for t_d after the full-astern order (the shaft windmills, still ahead), then
    the air brake reverses it within seconds: astern rotation in (t_d, t_d + 15 s]."""
    p = from_mmg(KVLCC2_FULL, reversal_delay=delay)
    U0 = p.approach_speed
    n = self_propulsion_rps(p, U0)
    r = simulate(MMG_4Q, p, [U0, 0, 0, 0, 0, 0, n, 0], t_final=delay + 60.0, dt=0.05,
                 actuator=RUDDER_SERVO, actuator_params=KVLCC2_FULL_SERVO, actuator_x0=[0.0],
                 controller=OPEN_LOOP, reference={"rudder_command": 0.0, "engine_order": -1.0})
    t = r.time
    rps = r["propeller_rps"][0]
    astern = t[np.argmax(rps < 0.0)]
    assert delay < astern <= delay + 15.0
    assert np.all(rps[t <= delay] > 0.2 * n)  # windmilling: not stopped before t_d
    # the sequence clock counted the time of the reversal, then returned towards 0
    clock = r["reversal_clock"][0]
    assert clock[np.searchsorted(t, astern) - 1] == pytest.approx(astern, abs=0.1)
    assert clock[-1] < 0.1 * astern


# --- the low-speed cross-flow hull (hull_model 0, the default) against the mirror (1) -------

def _hull_forces(p, u, v, r, n=-1.0):
    from seahelm.vessels.mmg_four_quadrant import _forces4q
    out = _forces4q(u, v, r, 0.0, n, p.to_record())
    return np.array(out[:3])


def test_hull_model_must_be_zero_or_one():
    # (the message named the field twice: "`hull_model` `hull_model` = 0.5 must be ...")
    with pytest.raises(ParameterError, match=r"^`hull_model` must be 0 \(cross-flow low-speed "
                       r"hull\) or 1 \(mirrored MMG hull\), got 0\.5"):
        from_mmg(KVLCC2_FULL, hull_model=0.5)


@pytest.mark.parametrize("value, match", [
    (0.0, r"^`cross_flow_drag` must be in \(0, 5\] \[-\], got 0\.0"),
    (-0.5, r"^`cross_flow_drag` must be in \(0, 5\] \[-\], got -0\.5"),
    (math.nan, r"^`cross_flow_drag` must be finite \[-\], got nan"),
])
def test_cross_flow_drag_must_be_positive(value, match):
    """C_D = 0 was taken: a hull with no cross-flow drag, which in pure sway (u = r = 0) feels
    no force at all (Y = -1/2 rho L d C_D v|v|); matching_cross_flow_drag refuses C_D <= 0."""
    with pytest.raises(ParameterError, match=match):
        from_mmg(KVLCC2_FULL, cross_flow_drag=value)


def test_catalog_hull_is_the_cross_flow_model_with_the_matched_drag():
    from seahelm.hydrodynamics.low_speed_hull import matching_cross_flow_drag
    from seahelm.vessels.mmg_four_quadrant import HULL_CROSS_FLOW
    assert KVLCC2_FULL_4Q.hull_model == HULL_CROSS_FLOW
    assert KVLCC2_FULL_4Q.cross_flow_drag == matching_cross_flow_drag(KVLCC2_FULL.Y_v,
                                                                      KVLCC2_FULL.Y_vvv)


@pytest.mark.parametrize("beta_deg", [30.0, 45.0])
@pytest.mark.parametrize("n", [1.5, -1.0])
def test_hull_is_continuous_where_the_models_meet(beta_deg, n):
    """Across the ends of the blend (|β| = 30° and 45°) the hull forces change by O(Δβ)."""
    p, U = KVLCC2_FULL_4Q, 3.0
    unit = 0.5 * p.rho * p.length * p.draft * U ** 2 * np.array([1.0, 1.0, p.length])
    f = [_hull_forces(p, U * math.cos(b), -U * math.sin(b), 0.0, n) / unit
         for b in np.radians(beta_deg) + np.array([-1e-7, 1e-7])]
    assert np.all(np.abs(f[1] - f[0]) < 1e-5)


@pytest.mark.parametrize("v, r", [(0.4, 0.0), (0.2, 0.001), (0.0, -0.002)])
def test_hull_is_continuous_through_zero_surge_speed(v, r):
    p = KVLCC2_FULL_4Q
    unit = 0.5 * p.rho * p.length * p.draft * np.array([1.0, 1.0, p.length])
    a, b = (_hull_forces(p, u, v, r) / unit for u in (-1e-7, 1e-7))
    assert np.all(np.abs(b - a) < 1e-5)


def test_mirror_and_cross_flow_runs_agree_bit_for_bit_while_in_the_mmg_range():
    """Both hull models use the MMG hull while |β| ≤ 30° and |r'| ≤ 1: the crash stop of
    the KVLCC2 is the same run up to the first sample where it leaves that range, then
    differs; both come to rest and the cross-flow one backs without blowing up."""
    from seahelm.vessels.mmg_four_quadrant import HULL_MIRROR
    p = KVLCC2_FULL_4Q
    mirror = from_mmg(KVLCC2_FULL, hull_model=HULL_MIRROR)
    U0 = p.approach_speed
    n = self_propulsion_rps(p, U0)
    ref = {"rudder_command": 0.0, "engine_order": -1.0}
    a = _run(MMG_4Q, p, [U0, 0, 0, 0, 0, 0, n, 0], ref, t_final=2400.0)
    b = _run(MMG_4Q, mirror, [U0, 0, 0, 0, 0, 0, n, 0], ref, t_final=2400.0)
    beta, U = np.abs(a["drift_angle"][0]), a["speed"][0]
    rn = np.abs(a["yaw_rate"][0]) * p.length / np.maximum(U, 1e-9)
    k = int(np.argmax((beta > math.radians(30.0)) | (rn > 1.0)))
    assert 0 < k < beta.size - 1
    # the samples are 10 s apart: the run before the previous sample never left the range
    for name in ("north", "east", "heading", "surge_speed", "sway_speed"):
        np.testing.assert_array_equal(a[name][0, :k - 1], b[name][0, :k - 1])
    assert not np.allclose(a["east"][0, -1], b["east"][0, -1], rtol=1e-3)
    for r in (a, b):
        u = r["surge_speed"][0]
        assert np.all(np.isfinite(u)) and np.any(u <= 0.0)
