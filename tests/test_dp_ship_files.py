"""Thrusters in ship files ([[thrusters]]), the dp-3dof model and the catalog's DP vessels."""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.cli import app
from seahelm.errors import ParameterError
from seahelm.ships import ShipFileError, get_ship, read_ship, ship_to_toml
from seahelm.ships.files import ship_from_mapping
from seahelm.ships.writing import ship_to_mapping

runner = CliRunner()


def _supply_mapping():
    return ship_to_mapping(get_ship("supply"))


def test_supply_vessel_thrusters_are_fossens():
    lay = get_ship("supply").thrusters
    assert lay.names == ("bow-tunnel-1", "bow-tunnel-2", "stern-tunnel-3", "stern-tunnel-4",
                         "main-starboard", "main-port")
    assert lay.kinds == ("tunnel",) * 4 + ("main",) * 2
    # Fossen (2021) §11.2: T_max = K n_max², K = 3.2 (tunnel, 250 rpm), 31.2 (main, 160 rpm)
    assert lay.max_thrust == (3.2 * 250**2,) * 4 + (31.2 * 160**2,) * 2
    assert lay.x[:4] == (30.0, 22.0, -22.0, -30.0) and lay.y[4:] == (8.0, -8.0)
    # the configuration matrix's yaw row is PVS's [30, 22, -22, -30, -8, 8] (per unit thrust)
    yaw = [x * math.sin(a) - y * math.cos(a) for x, y, a in zip(lay.x, lay.y, lay.direction)]
    np.testing.assert_allclose(yaw, [30, 22, -22, -30, -8, 8], atol=1e-12)


def test_a_ship_file_with_thrusters_reads_back_to_the_same_ship(tmp_path):
    ship = get_ship("shushlyapin2017-dp")
    lay = ship.thrusters.__class__(
        names=("az", "tunnel"), x=(-10.0, 8.0), y=(2.0, 0.0), direction=(0.5, 0.5 * math.pi),
        azimuthing=(True, False), max_thrust=(1e4, 5e3), min_thrust=(0.0, -4e3),
        forbidden=(((1.0, 1.5), (3.0, 3.2)), ()), max_thrust_rate=(2e3, math.inf),
        max_azimuth_rate=(0.2, math.inf))
    ship = ship.replace(thrusters=lay, thruster_provenance="a test layout")
    path = tmp_path / "s.toml"
    path.write_text(ship_to_toml(ship))
    back = read_ship(path)
    assert back == ship and back.thrusters == lay
    tab = tomllib.loads(path.read_text())["thrusters"]
    assert tab[0]["kind"] == "azimuth" and tab[0]["forbidden_sectors"] == [[1.0, 1.5], [3.0, 3.2]]


def test_thruster_angles_in_degrees():
    data = _supply_mapping()
    data["thrusters"] = [{"name": "a", "kind": "azimuth", "x": -30.0, "y": 0.0,
                          "max_thrust": 1e5, "direction_deg": 90.0,
                          "max_azimuth_rate_deg": 10.0,
                          "forbidden_sectors_deg": [[170.0, 190.0]]},
                         {"name": "b", "kind": "tunnel", "x": 30.0, "y": 0.0,
                          "max_thrust": 1e5}]
    lay = ship_from_mapping(data).thrusters
    assert lay.direction == (math.radians(90.0), 0.5 * math.pi)
    assert lay.max_azimuth_rate[0] == math.radians(10.0)
    assert lay.forbidden[0] == ((math.radians(170.0), math.radians(190.0)),)
    assert lay.min_thrust == (0.0, -1e5)


_T = {"name": "t", "kind": "tunnel", "x": 1.0, "y": 0.0, "max_thrust": 1e4}
_A = {"name": "a", "kind": "azimuth", "x": -1.0, "y": 0.0, "max_thrust": 1e4}


@pytest.mark.parametrize("tables, field, words", [
    ([{**_T, "kind": "pump"}], "thrusters[0].kind", ["tunnel, azimuth, main", "'pump'"]),
    ([{k: v for k, v in _T.items() if k != "max_thrust"}], "thrusters[0].max_thrust",
     ["is required"]),
    ([{**_T, "max_thrust": -5.0}], "thrusters[0].max_thrust", ["> 0 [N]", "-5.0"]),
    ([{**_T, "min_thrust": 2e4}], "thrusters[0].min_thrust", ["≤ max_thrust", "[N]", "20000"]),
    ([{**_T, "thrust": 1.0}], "thrusters[0].thrust", ["unknown key"]),
    ([{**_T, "forbidden_sectors": [[0.0, 1.0]]}], "thrusters[0].forbidden_sectors",
     ["azimuth thruster only"]),
    ([{**_A, "min_thrust": -1.0}], "thrusters[0].min_thrust", ["not for an azimuth"]),
    ([{**_T, "max_azimuth_rate": 0.1}], "thrusters[0].max_azimuth_rate",
     ["azimuth thruster only", "[rad/s]"]),
    ([{**_A, "forbidden_sectors_deg": [[0.0, 180.0], [170.0, 360.0]]}],
     "thrusters[0].forbidden_sectors_deg", ["cover 360 [deg]"]),
    ([_T, {**_T}], "thrusters.name", ["unique", "'t'"]),
    ([{**_T, "x": "far"}], "thrusters[0].x", ["[m]", "'far'"]),
    ([{**_T, "max_thrust_rate": 0.0}], "thrusters[0].max_thrust_rate", ["> 0 [N/s]"]),
    ([], "thrusters", ["one or more"]),
])
def test_bad_thrusters_name_the_key_unit_and_value(tables, field, words):
    data = _supply_mapping()
    data["thrusters"] = tables
    with pytest.raises(ShipFileError) as info:
        ship_from_mapping(data, source="my.toml")
    assert info.value.field == field
    for w in words:
        assert w in str(info.value), (w, str(info.value))


def test_dp_capability_takes_a_ship_file_and_refuses_bad_ones(tmp_path):
    ship = get_ship("supply")
    path = tmp_path / "supply-copy.toml"
    path.write_text(ship_to_toml(ship.replace(name="supply-copy")))
    ok = runner.invoke(app, ["dp", "capability", str(path), "--headings", "4", "--failures",
                             "none", "--json"])
    ref = runner.invoke(app, ["dp", "capability", "supply", "--headings", "4", "--failures",
                              "none", "--json"])
    assert ok.exit_code == 0 and ref.exit_code == 0
    import json

    a, b = json.loads(ok.stdout), json.loads(ref.stdout)
    assert a["vessel"] == "supply-copy" and a["wind_speed_m_s"] == b["wind_speed_m_s"]
    bad = path.read_text().replace('kind = "main"', 'kind = "propeller"', 1)
    path.write_text(bad)
    res = runner.invoke(app, ["dp", "capability", str(path)])
    assert res.exit_code == 2
    line = res.stderr.strip()
    assert "\n" not in line and "thrusters[4].kind" in line and "'propeller'" in line
    res = runner.invoke(app, ["dp", "capability", "kvlcc2-l7"])
    assert res.exit_code == 2 and "declares no thrusters" in res.stderr
    assert "supply" in res.stderr and "shushlyapin2017-dp" in res.stderr


def test_dp_3dof_right_hand_side_is_m_inverse_of_the_forces():
    """ν̇ = M⁻¹(τ + τ_env − D ν_r), η̇ = R(ψ) ν_r + V_c, against numpy's solve (1e-12)."""
    ship = get_ship("supply")
    p = ship.params
    rng = np.random.default_rng(3)
    x = rng.normal(size=(20, 6)) * [50, 50, 2, 1, 1, 0.05]
    u = rng.normal(size=(20, 3)) * [5e5, 5e5, 2e7]
    d = rng.normal(size=(20, 5)) * [1e5, 1e5, 1e6, 0.5, 0.5]
    got = ship.model.derivative(0.0, x, u, p, d)
    m, dm = p.mass_matrix(), p.damping_matrix()
    for k in range(20):
        nu = x[k, 3:]
        acc = np.linalg.solve(m, u[k] + d[k, :3] - dm @ nu)
        c, s = math.cos(x[k, 2]), math.sin(x[k, 2])
        pos = [c * nu[0] - s * nu[1] + d[k, 3], s * nu[0] + c * nu[1] + d[k, 4], nu[2]]
        np.testing.assert_allclose(got[k], np.concatenate([pos, acc]), rtol=1e-12, atol=1e-15)


def test_a_singular_mass_matrix_is_refused():
    p = get_ship("supply").params
    from seahelm.vessels.dp_three_dof import DpThreeDofParams

    kw = p.as_dict()
    kw.update(m22=1.0, m23=1.0, m32=1.0, m33=1.0)
    with pytest.raises(ParameterError, match="invertible"):
        DpThreeDofParams(**kw)


def test_six_dof_allocation_messages_name_the_field_once():
    from seahelm.vessels.six_dof.otter import otter_params
    from seahelm.vessels.six_dof.thrusters import Allocation

    for kw, field in (({"dofs": ("surge", "warp")}, "`dofs`"),
                      ({"dofs": ("surge",), "weights": [1.0, 0.0]}, "`weights`")):
        with pytest.raises(ParameterError) as info:
            Allocation(otter_params(), **kw)
        assert str(info.value).count(field) == 1, str(info.value)
