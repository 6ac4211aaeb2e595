"""Blendermann (1994) wind loads: table, conventions, symmetry, kernel and validation."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from numba import njit

from seahelm.constants import RHO_AIR
from seahelm.environment.blendermann import (
    BLENDERMANN_VESSEL_TYPES,
    BlendermannCoefficients,
    blendermann_coefficients,
    blendermann_loads,
    blendermann_wind_loads,
    get_blendermann_type,
)
from seahelm.errors import ParameterError

# MSS exWindForce.m's research vessel: A_F = 160.7 m², A_L = 434.8 m², L_oa = 55 m
GEOM = dict(frontal_area=160.7, lateral_area=434.8, length_overall=55.0)
TYPES = sorted(BLENDERMANN_VESSEL_TYPES)


def _kernel(speed, angle, p, *, frontal_area, lateral_area, length_overall, lateral_centre=0.0,
            rho_air=RHO_AIR):
    return blendermann_loads(speed, angle, p.cd_transverse, p.cd_longitudinal_head,
                             p.cd_longitudinal_stern, p.delta, p.kappa, frontal_area,
                             lateral_area, length_overall, lateral_centre, rho_air)


# -- the table ---------------------------------------------------------------------------------

# Rows read from MSS LIBRARY/environment/blendermann94.m (BDATA, "Fossen 2021, Ch. 10.1.2"):
# CD_t, CD_l,AF(0), CD_l,AF(pi), delta, kappa. Literals, not computed by the code.
TABLE_ROWS = {
    "car-carrier": (0.95, 0.55, 0.60, 0.80, 1.2),
    "tanker-loaded": (0.70, 0.90, 0.55, 0.40, 3.1),
    "tanker-ballast": (0.70, 0.75, 0.55, 0.40, 2.2),
    "drilling-vessel": (1.00, 0.85, 0.925, 0.10, 1.7),  # mid-points of 0.70-1.00, 0.75-1.10
}


@pytest.mark.parametrize("name", sorted(TABLE_ROWS))
def test_registry_matches_table_rows(name):
    p = BLENDERMANN_VESSEL_TYPES[name]
    got = (p.cd_transverse, p.cd_longitudinal_head, p.cd_longitudinal_stern, p.delta, p.kappa)
    assert got == TABLE_ROWS[name]


def test_registry_lists_every_vessel_type_of_the_table():
    assert len(BLENDERMANN_VESSEL_TYPES) == 17
    assert {p.description for p in BLENDERMANN_VESSEL_TYPES.values()} >= {
        "Car carrier", "Cargo vessel, loaded", "Container ship, loaded", "Tanker, loaded",
        "Tanker, in ballast", "Tender",
    }
    for key in BLENDERMANN_VESSEL_TYPES:
        assert key == key.lower() and " " not in key and "_" not in key


@pytest.mark.parametrize("name", TYPES)
def test_special_angles_give_back_the_table(name):
    p = BLENDERMANN_VESSEL_TYPES[name]
    ratio = GEOM["frontal_area"] / GEOM["lateral_area"]
    c = blendermann_coefficients(np.radians([0.0, 90.0, -90.0, 180.0]), name, **GEOM)
    # beam winds: D = 1, |CY| = CD_t; wind from starboard pushes to port
    assert c.cy[1] == pytest.approx(-p.cd_transverse, rel=1e-14)
    assert c.cy[2] == pytest.approx(p.cd_transverse, rel=1e-14)
    assert abs(c.cx[1]) < 1e-15 and abs(c.cx[2]) < 1e-15
    # head and stern: CX = -/+ CD_l,AF A_F/A_L (referred to A_L)
    assert c.cx[0] == pytest.approx(-p.cd_longitudinal_head * ratio, rel=1e-14)
    assert c.cx[3] == pytest.approx(p.cd_longitudinal_stern * ratio, rel=1e-14)


def test_get_blendermann_type_by_name_and_object():
    p = BLENDERMANN_VESSEL_TYPES["container-loaded"]
    assert get_blendermann_type("container-loaded") is p
    custom = BlendermannCoefficients(cd_transverse=0.8, cd_longitudinal_head=0.5,
                                     cd_longitudinal_stern=0.5, delta=0.5, kappa=1.0)
    assert get_blendermann_type(custom) is custom
    loads = blendermann_wind_loads(10.0, 0.3, custom, **GEOM)
    assert np.isfinite(loads.sway)


def test_unknown_vessel_type_lists_the_valid_ones():
    with pytest.raises(ValueError, match=r"unknown Blendermann vessel type 'bulk-carrier'.*"
                                         r"car-carrier.*tanker-ballast.*tender"):
        get_blendermann_type("bulk-carrier")
    with pytest.raises(ValueError, match="valid: car-carrier"):
        blendermann_coefficients(0.0, 3, **GEOM)


# -- against the source's own formulas -------------------------------------------------------


@pytest.mark.parametrize("gamma_deg", [10.0, 30.0, 60.0, 90.0, 120.0, 150.0, 170.0])
def test_port_side_agrees_with_fossens_formulas(gamma_deg):
    """Fossen's γ_rw is positive from port; on 0..π his (MSS's) expressions hold as written.

    Written out here with the research vessel's literals, CX referred to A_F as MSS does.
    """
    cd_t, head, stern, delta = 0.85, 0.55, 0.65, 0.60
    a_f, a_l, loa, s_l, v, rho = 160.7, 434.8, 55.0, 1.48, 20.0, 1.224
    g = math.radians(gamma_deg)
    cd_l_af = head if g <= math.pi / 2 else stern
    cd_l = cd_l_af * a_f / a_l
    den = 1.0 - 0.5 * delta * (1.0 - cd_l / cd_t) * math.sin(2.0 * g) ** 2
    cx_af = -cd_l_af * math.cos(g) / den
    cy = cd_t * math.sin(g) / den
    cn = (s_l / loa - 0.18 * (g - math.pi / 2.0)) * cy
    q = 0.5 * rho * v**2
    expected = (q * cx_af * a_f, q * cy * a_l, q * cn * a_l * loa)
    got = blendermann_wind_loads(v, -g, "research-vessel", frontal_area=a_f, lateral_area=a_l,
                                 length_overall=loa, lateral_centre=s_l, rho_air=rho)
    scale = q * a_l * loa
    assert float(got.surge) == pytest.approx(expected[0], rel=1e-12, abs=1e-12 * q * a_l)
    assert float(got.sway) == pytest.approx(expected[1], rel=1e-12)
    assert float(got.yaw) == pytest.approx(expected[2], rel=1e-12, abs=1e-12 * scale)


# -- symmetry and signs ----------------------------------------------------------------------


@pytest.mark.parametrize("name", ["car-carrier", "tanker-loaded", "ferry"])
@pytest.mark.parametrize("s_l", [0.0, 4.0, -6.0])
def test_surge_even_sway_and_yaw_odd(name, s_l):
    gamma = np.linspace(-3.0, 3.0, 61)
    plus = blendermann_wind_loads(15.0, gamma, name, lateral_centre=s_l, **GEOM)
    minus = blendermann_wind_loads(15.0, -gamma, name, lateral_centre=s_l, **GEOM)
    np.testing.assert_array_equal(plus.surge, minus.surge)
    np.testing.assert_array_equal(plus.sway, -minus.sway)
    np.testing.assert_array_equal(plus.yaw, -minus.yaw)


@pytest.mark.parametrize("name", TYPES)
@pytest.mark.parametrize("angle", [0.0, math.pi, -math.pi, 2.0 * math.pi, -2.0 * math.pi])
def test_head_and_stern_wind_give_no_side_force_or_moment(name, angle):
    loads = blendermann_wind_loads(25.0, angle, name, lateral_centre=3.0, **GEOM)
    assert loads.sway == 0.0 and loads.yaw == 0.0
    x, y, n = _kernel(25.0, angle, BLENDERMANN_VESSEL_TYPES[name], lateral_centre=3.0, **GEOM)
    assert y == 0.0 and n == 0.0
    head = abs(math.cos(angle)) > 0.5 and math.cos(angle) > 0
    assert (x < 0) if head else (x > 0)


@pytest.mark.parametrize("name", TYPES)
def test_signs_in_seahelm_axes(name):
    deg = np.radians
    loads = blendermann_wind_loads(20.0, deg([0.0, 90.0, 30.0, 150.0, -30.0, -150.0, 180.0]),
                                   name, **GEOM)
    x, y, n = loads
    assert x[0] < 0.0  # head wind slows the ship
    assert x[6] > 0.0  # stern wind pushes it
    assert y[1] < 0.0 and y[2] < 0.0 and y[3] < 0.0  # wind from starboard pushes to port
    assert y[4] > 0.0 and y[5] > 0.0
    assert n[2] < 0.0  # starboard bow: bow turns to port (away from the wind)
    assert n[3] > 0.0  # starboard quarter: bow turns to starboard (into the wind)
    assert n[4] > 0.0 and n[5] < 0.0  # the mirror image from port


def test_centre_ahead_of_midships_turns_bow_away_from_beam_wind():
    p = BLENDERMANN_VESSEL_TYPES["cargo-loaded"]
    c = blendermann_coefficients(math.pi / 2, p, lateral_centre=5.0, **GEOM)
    assert float(c.cn) == pytest.approx(5.0 / GEOM["length_overall"] * -p.cd_transverse)
    assert c.cn < 0.0
    c_aft = blendermann_coefficients(math.pi / 2, p, lateral_centre=-5.0, **GEOM)
    assert c_aft.cn > 0.0


def test_moment_arm_is_blendermanns_line():
    """CN / CY = s_L/L_oa − 0.18 (|γ| − π/2): +0.28 near head wind, −0.28 near stern wind."""
    gamma = np.radians([1.0, 45.0, 135.0, 179.0])
    c = blendermann_coefficients(gamma, "tender", lateral_centre=2.75, **GEOM)
    arm = 2.75 / 55.0 - 0.18 * (gamma - math.pi / 2)
    np.testing.assert_allclose(c.cn / c.cy, arm, rtol=1e-12)


# -- scaling, batching, wrapping -------------------------------------------------------------


def test_loads_scale_with_speed_squared_and_density():
    gamma = np.radians(np.arange(-180.0, 181.0, 15.0))
    one = blendermann_wind_loads(7.0, gamma, "destroyer", **GEOM)
    three = blendermann_wind_loads(21.0, gamma, "destroyer", **GEOM)
    dense = blendermann_wind_loads(7.0, gamma, "destroyer", rho_air=2.0 * RHO_AIR, **GEOM)
    for a, b, d in zip(one, three, dense):
        np.testing.assert_allclose(b, 9.0 * a, rtol=1e-13, atol=1e-9)
        np.testing.assert_allclose(d, 2.0 * a, rtol=1e-13, atol=1e-9)
    calm = blendermann_wind_loads(0.0, gamma, "destroyer", **GEOM)
    for a in calm:
        np.testing.assert_array_equal(np.abs(a), 0.0)


def test_coefficients_times_dynamic_pressure_are_the_loads():
    gamma = np.radians([20.0, 100.0, -140.0])
    c = blendermann_coefficients(gamma, "ferry", lateral_centre=-3.0, **GEOM)
    f = blendermann_wind_loads(12.0, gamma, "ferry", lateral_centre=-3.0, **GEOM)
    q = 0.5 * RHO_AIR * 12.0**2 * GEOM["lateral_area"]
    np.testing.assert_allclose(f.surge, q * c.cx, rtol=1e-14)
    np.testing.assert_allclose(f.sway, q * c.cy, rtol=1e-14)
    np.testing.assert_allclose(f.yaw, q * c.cn * GEOM["length_overall"], rtol=1e-14)


def test_batched_equals_one_by_one():
    rng = np.random.default_rng(7)
    gamma = rng.uniform(-4.0, 4.0, size=(3, 5))
    speed = rng.uniform(0.0, 30.0, size=(3, 1))
    centre = np.array([-4.0, 0.0, 1.0, 2.5, 6.0])  # broadcast along the last axis
    batch = blendermann_wind_loads(speed, gamma, "passenger-liner", lateral_centre=centre,
                                   **GEOM)
    assert batch.surge.shape == (3, 5)
    p = BLENDERMANN_VESSEL_TYPES["passenger-liner"]
    for i in range(3):
        for j in range(5):
            one = blendermann_wind_loads(speed[i, 0], gamma[i, j], p,
                                         lateral_centre=centre[j], **GEOM)
            k = _kernel(speed[i, 0], gamma[i, j], p, lateral_centre=centre[j], **GEOM)
            for b, o, kk in zip(batch, one, k):
                assert b[i, j] == float(o)
                assert b[i, j] == pytest.approx(kk, rel=1e-13, abs=1e-9)


def test_angles_are_wrapped():
    gamma = np.radians([10.0, 95.0, -170.0])
    base = blendermann_wind_loads(9.0, gamma, "speed-boat", **GEOM)
    for turns in (-3, -1, 1, 2):
        shifted = blendermann_wind_loads(9.0, gamma + 2.0 * math.pi * turns, "speed-boat", **GEOM)
        for a, b in zip(base, shifted):
            np.testing.assert_allclose(b, a, rtol=1e-12, atol=1e-9)


# -- the compiled kernel ---------------------------------------------------------------------


@pytest.mark.parametrize("name", TYPES)
def test_kernel_equals_numpy(name):
    p = BLENDERMANN_VESSEL_TYPES[name]
    gamma = np.linspace(-7.0, 7.0, 141)
    ref = blendermann_wind_loads(18.0, gamma, name, lateral_centre=-2.0, rho_air=1.2, **GEOM)
    for i, g in enumerate(gamma):
        x, y, n = _kernel(18.0, float(g), p, lateral_centre=-2.0, rho_air=1.2, **GEOM)
        assert x == pytest.approx(ref.surge[i], rel=1e-13, abs=1e-9)
        assert y == pytest.approx(ref.sway[i], rel=1e-13, abs=1e-9)
        assert n == pytest.approx(ref.yaw[i], rel=1e-13, abs=1e-7)


@njit(_nrt=False)
def _sum_over_angles(angles, out):
    # a caller compiled without the numba runtime: the kernel must not allocate
    sx = sy = sn = 0.0
    for k in range(angles.shape[0]):
        x, y, n = blendermann_loads(20.0, angles[k], 0.95, 0.55, 0.60, 0.80, 1.2,
                                    160.7, 434.8, 55.0, 1.5, 1.225)
        sx += x
        sy += y
        sn += n
    out[0] = sx
    out[1] = sy
    out[2] = sn


def test_kernel_compiles_in_a_caller_without_the_runtime():
    angles = np.linspace(0.1, 2.0, 7)
    out = np.zeros(3)
    _sum_over_angles(angles, out)
    ref = blendermann_wind_loads(20.0, angles, "car-carrier", lateral_centre=1.5, rho_air=1.225,
                                 **GEOM)
    np.testing.assert_allclose(out, [ref.surge.sum(), ref.sway.sum(), ref.yaw.sum()],
                               rtol=1e-12)


# -- validation ------------------------------------------------------------------------------

VALID = dict(cd_transverse=0.9, cd_longitudinal_head=0.55, cd_longitudinal_stern=0.6, delta=0.5,
             kappa=1.2, description="test")


@pytest.mark.parametrize(
    ("field", "value", "match"),
    [
        ("cd_transverse", 0.0, r"`cd_transverse` must be > 0 \[-\], got 0.0"),
        ("cd_transverse", -0.9, r"`cd_transverse` must be > 0 \[-\], got -0.9"),
        ("cd_longitudinal_head", -0.5, r"`cd_longitudinal_head` must be > 0 \[-\], got -0.5"),
        ("cd_longitudinal_stern", 0.0, r"`cd_longitudinal_stern` must be > 0 \[-\], got 0.0"),
        ("kappa", -1.0, r"`kappa` must be > 0 \[-\], got -1.0"),
        ("kappa", math.inf, r"`kappa` must be finite \[-\], got inf"),
        ("delta", 1.5, r"`delta` must be in \[0, 1\] \[-\], got 1.5"),
        ("delta", -0.1, r"`delta` must be in \[0, 1\] \[-\], got -0.1"),
        ("delta", math.nan, r"`delta` must be finite \[-\], got nan"),
        ("cd_transverse", "0.9", r"`cd_transverse` must be a real number \[-\], got '0.9'"),
        ("delta", True, r"`delta` must be a real number \[-\], got True"),
        ("description", 3, r"`description` must be a string, got int"),
    ],
)
def test_coefficients_validation(field, value, match):
    with pytest.raises(ParameterError, match=match):
        BlendermannCoefficients(**{**VALID, field: value})


def test_coefficients_are_frozen_and_keyword_only():
    p = BlendermannCoefficients(**VALID)
    with pytest.raises(dataclasses.FrozenInstanceError):
        p.delta = 0.2  # type: ignore[misc]
    with pytest.raises(TypeError):
        BlendermannCoefficients(0.9, 0.55, 0.6, 0.5, 1.2)  # type: ignore[misc]


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        (dict(frontal_area=0.0), r"`frontal_area` must be > 0 \[m²\], got 0.0"),
        (dict(lateral_area=-4.0), r"`lateral_area` must be > 0 \[m²\], got -4.0"),
        (dict(length_overall=0.0), r"`length_overall` must be > 0 \[m\], got 0.0"),
        (dict(length_overall=math.nan), r"`length_overall` must be finite \[m\], got nan"),
        (dict(lateral_centre=30.0), r"`lateral_centre` must lie within the ship.*\[m\], "
                                    r"got 30.0 with length_overall/2 = 27.5"),
        (dict(lateral_centre=math.inf), r"`lateral_centre` must be finite \[m\], got inf"),
        (dict(angle=math.nan), r"`angle` must be finite \[rad\], got nan"),
        (dict(angle="ahead"), r"`angle` must be real numbers \[rad\], got text: 'ahead'"),
    ],
)
@pytest.mark.parametrize("function", ["coefficients", "loads"])
def test_geometry_and_angle_validation(kwargs, match, function):
    args = {**GEOM, "angle": 0.5, **kwargs}
    angle = args.pop("angle")
    with pytest.raises(ParameterError, match=match):
        if function == "coefficients":
            blendermann_coefficients(angle, "ferry", **args)
        else:
            blendermann_wind_loads(10.0, angle, "ferry", **args)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        (dict(relative_speed=-1.0), r"`relative_speed` must be >= 0 \[m/s\], got -1.0"),
        (dict(relative_speed=math.inf), r"`relative_speed` must be finite \[m/s\], got inf"),
        (dict(rho_air=0.0), r"`rho_air` must be > 0 \[kg/m³\], got 0.0"),
        (dict(rho_air=-1.2), r"`rho_air` must be > 0 \[kg/m³\], got -1.2"),
    ],
)
def test_speed_and_density_validation(kwargs, match):
    speed = kwargs.pop("relative_speed", 10.0)
    with pytest.raises(ParameterError, match=match):
        blendermann_wind_loads(speed, 0.5, "ferry", **GEOM, **kwargs)
