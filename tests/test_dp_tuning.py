"""DP tuning by pole placement (seahelm.control.dp_tuning, ``seahelm dp tune``): the gains by
hand for the supply vessel, the closed loop on a diagonal M, D has the designed poles, the
written scenario runs with those gains, bad input is refused naming the option."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.cli import app
from seahelm.control.dp_tuning import designed_poles, tune_dp
from seahelm.errors import ParameterError
from seahelm.ships import get_ship

runner = CliRunner()
SUPPLY = get_ship("supply")


def test_the_gains_are_fossens_pole_placement_by_hand():
    """K_p = ω² m, K_d = 2ζω m − d, K_i = ω/10 K_p with the supply vessel's diagonal
    (m11 = 6,764,400 kg, d11 = 77,071.05 kg/s, from its bis-scaled matrices)."""
    t = tune_dp(SUPPLY, bandwidth=0.1, damping=1.0)
    p = SUPPLY.params
    assert p.m11 == pytest.approx(6764400.0) and p.d11 == pytest.approx(77071.0534, rel=1e-8)
    assert t.gains["kp_surge"] == pytest.approx(0.01 * 6764400.0, rel=1e-12)
    assert t.gains["kd_surge"] == pytest.approx(2 * 0.1 * 6764400.0 - p.d11, rel=1e-12)
    assert t.gains["ki_surge"] == pytest.approx(0.1 / 10 * 0.01 * 6764400.0, rel=1e-12)
    assert (t.params.frequency_surge, t.params.frequency_yaw) == (0.1, 0.1)
    assert t.stable and t.warnings == ()


def test_designed_poles_are_the_cubic_roots():
    """ζ = 1: s³ + 2ω s² + ω² s + ω³/10 has the real roots s = −aω with a³ − 2a² + a − 0.1 = 0:
    a = 1.2796, 0.5874, 0.1330 (by hand: 1.2796³ − 2·1.2796² + 1.2796 − 0.1 ≈ 0); checked by
    substitution too."""
    s = designed_poles(0.25, 1.0)
    assert np.all(np.abs(s.imag) < 1e-12)
    for root in s:
        assert abs(root ** 3 + 0.5 * root ** 2 + 0.0625 * root + 0.25 ** 3 / 10) < 1e-12
    np.testing.assert_allclose(np.sort(s.real) / 0.25, [-1.2796, -0.5874, -0.1330], atol=1e-4)


def test_a_diagonal_vessel_has_the_designed_poles_and_the_coupled_one_moves():
    p = SUPPLY.params
    diag = SUPPLY.replace(params=dataclasses.replace(p, m23=0.0, m32=0.0, d23=0.0, d32=0.0))
    t = tune_dp(diag, bandwidth=(0.1, 0.12, 0.2))
    np.testing.assert_allclose(np.sort_complex(t.poles), np.sort_complex(t.designed.ravel()),
                               atol=1e-9)
    coupled = tune_dp(SUPPLY, bandwidth=(0.1, 0.12, 0.2))
    assert coupled.stable
    assert np.abs(np.sort_complex(coupled.poles) - np.sort_complex(t.poles)).max() > 1e-3


def test_bad_requests_are_refused():
    for kw, field in ((dict(bandwidth=0.0), "bandwidth"), (dict(bandwidth=(0.1, 0.2)),
                                                           "bandwidth"),
                      (dict(damping=float("nan")), "damping"), (dict(dt=-1.0), "dt"),
                      (dict(bandwidth=0.001), "bandwidth")):  # K_d < 0
        with pytest.raises(ParameterError) as info:
            tune_dp(SUPPLY, **kw)
        assert info.value.field == field, kw
    with pytest.raises(ParameterError, match="declares no thrusters"):
        tune_dp(get_ship("mariner-nonlinear"))


def test_cli_tune_writes_a_scenario_that_runs_with_the_gains(tmp_path):
    from seahelm.scenario import load_scenario, run_scenario

    path = tmp_path / "dp.toml"
    res = runner.invoke(app, ["dp", "tune", "supply", "--bandwidth", "0.12", "--t-final", "120",
                              "--out", str(path), "--json"])
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    assert out["stable"] and out["gains"]["kp_sway"] == pytest.approx(0.0144 * SUPPLY.params.m22)
    assert len(out["closed_loop_poles"]) == 9
    problem = load_scenario(path)
    row = np.asarray(problem.controller_params)[0]
    names = type(tune_dp(SUPPLY).params).value_names()
    assert row[names.index("frequency_sway")] == 0.12
    result = run_scenario(problem)
    assert result.ok.all()
    assert float(np.asarray(result["north"])[0, -1]) > 5.0  # on its way to the 10 m set-point
    # the text table
    res = runner.invoke(app, ["dp", "tune", "supply", "--bandwidth", "0.5", "--dt", "1"])
    assert res.exit_code == 0 and "warning" in res.output and "stable" in res.output


@pytest.mark.parametrize("args, words", [
    (["--bandwidth", "0.1,x"], ["--bandwidth", "[rad/s]", "0.1,x"]),
    (["--bandwidth", "0.1,0.2"], ["--bandwidth", "[rad/s]", "0.1"]),
    (["--bandwidth", "0.001"], ["--bandwidth", "[rad/s]", "0.001"]),
    (["--damping", "-1"], ["--damping", "[-]", "-1"]),
    (["--dt", "0"], ["--dt", "[s]", "0"]),
    (["--t-final", "-3"], ["--t-final", "[s]", "-3"]),
    (["--north", "nan"], ["--north", "[m]", "nan"]),
])
def test_cli_bad_input_exits_2_in_one_line(args, words):
    res = runner.invoke(app, ["dp", "tune", "supply", *args], terminal_width=400)
    assert res.exit_code == 2, res.output
    line = res.stderr.strip()
    assert "\n" not in line and all(w in line for w in words), line
