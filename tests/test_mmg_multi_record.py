"""Multi-record identification of an ``mmg-ls`` ship (seahelm.analysis.replay.mmg_multi_record) and
``seahelm identify mmg`` with an mmg-ls ship: synthetic records only (no measured data).

The records are simulated by the engine through the replay's path (a ``Problem`` with the
``samples`` signal, not the fit's segments) from a *perturbed* Esso Osaka (N'_r, Y'_v, a_H
changed from the published set), with a steady measured wind, and noise is added; the fit
from the published set must recover the perturbed values within its stated intervals.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.analysis.replay.mmg_multi_record import (
    build_segments,
    fit_mmg_ls,
    laplace_samples,
    simulate_segments,
)
from seahelm.identification.records import RECORD_FORMATS, ManoeuvreRecord, read_records
from seahelm.errors import ParameterError
from seahelm.ships import get_ship

from conftest import one_error

SHIP = "esso-osaka-3m"
TRUTH = {"N_r": -0.07, "Y_v": -0.5, "a_H": 0.8}  # published: -0.04849, -0.3728, 0.393
WIND = (1.5, math.radians(60.0))  # [m/s], from [rad]
DT = 0.05
SAMPLE = 0.1  # [s], the data set's interval
NOISE = {"x": 0.005, "y": 0.005, "heading": 0.002, "surge_speed": 0.002,
         "sway_speed": 0.002, "yaw_rate": 0.0005}


def _ramped(t, period, amplitude):
    """Switches between ±amplitude every ``period`` s, each switch a 1-s ramp."""
    out = np.empty_like(t)
    for i, ti in enumerate(t):
        k = math.floor(ti / period)
        now = amplitude * (1 if k % 2 == 0 else -1)
        before = 0.0 if k == 0 else -now
        out[i] = before + (now - before) * min((ti - k * period) / 1.0, 1.0)
    return out


def _record(name, t_final, period, amplitude, rps, seed):
    from seahelm.environment.loads import environment, ship_load_params
    from seahelm.simulation.engine import simulate
    from seahelm.simulation.problem import Problem
    from seahelm.simulation.signals import Samples

    base = get_ship(SHIP)
    truth = base.replace(params=TRUTH)
    knots = np.arange(0.0, t_final + DT / 2, DT)
    env = environment(wind="fujiwara")
    loads = ship_load_params(truth, env, wind_speed=WIND[0], wind_direction=WIND[1])
    x0 = truth.model.initial_state(surge_speed=0.3, north=1.0, east=-2.0, heading=0.3)
    res = simulate(Problem(
        t_final=t_final, dt=DT, ship=truth, actuator="direct", x0=x0, environment=env,
        environment_params=loads,
        reference={"rudder_angle": Samples(tuple(knots), tuple(_ramped(knots, period,
                                                                       amplitude))),
                   "propeller_rps": Samples(tuple(knots), tuple(rps(knots)))}))
    keep = slice(None, None, int(round(SAMPLE / DT)))
    rng = np.random.default_rng(seed)
    t = res.time[keep]
    ch = {"x": res["north"][0][keep], "y": res["east"][0][keep],
          "surge_speed": res["surge_speed"][0][keep], "sway_speed": res["sway_speed"][0][keep],
          "heading": res["heading"][0][keep], "yaw_rate": res["yaw_rate"][0][keep]}
    ch = {k: v + rng.normal(0.0, NOISE[k], v.size) for k, v in ch.items()}
    heading, yaw = ch.pop("heading"), ch.pop("yaw_rate")
    ch.update(propeller_rps=res["propeller_rps"][0][keep],
              true_wind_speed=np.full(t.size, WIND[0]),
              true_wind_direction=np.full(t.size, WIND[1]))
    return ManoeuvreRecord(name=name, time=t, rudder_angle=res["rudder_angle"][0][keep],
                           heading=heading, yaw_rate=yaw, channels=ch)


@pytest.fixture(scope="module")
def records():
    return [_record("zigzag", 120.0, 15.0, math.radians(20.0), lambda t: 10.0 + 0 * t, 1),
            _record("mixed", 120.0, 25.0, math.radians(30.0),
                    lambda t: 9.0 + 3.0 * np.sin(2 * math.pi * t / 40.0), 2)]


@pytest.fixture(scope="module")
def fit(records):
    return fit_mmg_ls(records, get_ship(SHIP), names=tuple(TRUTH), wind="measured")


def test_the_fit_recovers_the_perturbed_coefficients_within_its_interval(fit):
    base = get_ship(SHIP)
    se = fit.stated_errors
    assert np.all(se > fit.standard_errors)  # the Laplace interval alone is narrower
    for j, name in enumerate(fit.names):
        truth, start = TRUTH[name], getattr(base.params, name)
        assert abs(fit.values[j] - truth) <= 3.0 * se[j], (name, fit.values[j], truth, se[j])
        # the published value (the start) is far outside it: the test can fail
        assert abs(start - truth) > 5.0 * se[j], (name, start, truth, se[j])
    assert fit.rms_fit < 0.2 * fit.rms_start
    assert not fit.fixed


def test_without_the_wind_the_fit_is_biased(records):
    """The measured wind is an input that matters: in still air the same fit misses."""
    still = fit_mmg_ls(records, get_ship(SHIP), names=("N_r",), wind="none", max_nfev=15)
    windy = fit_mmg_ls(records, get_ship(SHIP), names=("N_r",), wind="measured", max_nfev=15)
    assert windy.rms_fit < 0.8 * still.rms_fit


def test_the_ship_carries_the_values_and_their_source(fit):
    ship = fit.ship(get_ship(SHIP))
    assert ship.name == f"{SHIP}-identified"
    for j, name in enumerate(fit.names):
        assert getattr(ship.params, name) == fit.values[j]
        assert "output-error fit" in ship.source_of(name)
    assert ship.params.C_rN == get_ship(SHIP).params.C_rN


def test_segments_start_from_the_measured_state(records):
    base = get_ship(SHIP)
    segs = build_segments(records, base, segment=60.0, wind="none")
    assert len(segs.names) == 4  # 2 records × 120 s / 60 s (the last sample starts none)
    assert segs.sample / segs.dt == pytest.approx(round(segs.sample / segs.dt))
    rec = records[0]
    # the state at the start from the samples within 1 s (the noise of one sample reduced)
    assert segs.x0[1, 3] == pytest.approx(np.interp(60.0, rec.time, rec.channels["x"]),
                                          abs=4 * NOISE["x"])
    assert np.all((segs.x0_std[:, 3] > 0) & (segs.x0_std[:, 3] < NOISE["x"]))
    sim = simulate_segments(base, segs, [base.params])
    # the first sample of each simulated segment is its (smoothed) measured start
    order = (3, 4, 5, 0, 1, 2)  # OUTPUTS (north, east, heading, u, v, r) in the state's order
    assert np.allclose(sim[0, :, order, 0].T, segs.x0, rtol=0, atol=1e-12)


def test_laplace_samples_lie_in_the_ranges(fit):
    draws = laplace_samples(fit, 200, seed=3)
    assert draws.shape == (200, 3)
    assert np.all(draws[:, fit.names.index("a_H")] >= 0.0)
    assert np.allclose(draws.mean(axis=0), fit.values, atol=4 * fit.standard_errors)
    with pytest.raises(ParameterError, match="must be >= 1"):
        laplace_samples(fit, 0)


def test_bad_input_names_the_parameter(records):
    base = get_ship(SHIP)
    with pytest.raises(ParameterError, match="not coefficients of mmg-ls: foo"):
        fit_mmg_ls(records, base, names=("foo",))
    with pytest.raises(ParameterError, match="must be an mmg-ls ship, got model mmg"):
        fit_mmg_ls(records, get_ship("kvlcc2-l7"), names=("N_r",))
    bare = ManoeuvreRecord(name="bare", time=records[0].time,
                           rudder_angle=records[0].rudder_angle, heading=records[0].heading,
                           yaw_rate=records[0].yaw_rate,
                           channels={k: v for k, v in records[0].channels.items()
                                     if not k.startswith("true_wind")})
    with pytest.raises(ParameterError, match="bare: missing column.s. true_wind_speed"):
        build_segments([bare], base, wind="measured")
    with pytest.raises(ParameterError, match="must be > 0"):
        build_segments(records, base, segment=0.0)


# -- the command line ------------------------------------------------------------------
HEADER = list(RECORD_FORMATS["FRT-DS-ESSO"][0])
_COLS = {"t [s]": "time", "x_position_mid [m]": "x", "u_velo [m/s]": "surge_speed",
         "y_position_mid [m]": "y", "vm_velo [m/s]": "sway_speed", "psi_hat [rad]": "heading",
         "r_angvelo [rad/s]": "yaw_rate", "n_prop [rps]": "propeller_rps",
         "delta_rudder [rad]": "rudder_angle", "wind_velo_true [m/s]": "true_wind_speed",
         "wind_dir_true [rad]": "true_wind_direction"}


def _write_csv(path, rec):
    values = {"time": rec.time, "heading": rec.heading, "yaw_rate": rec.yaw_rate,
              "rudder_angle": rec.rudder_angle, **rec.channels}
    head = [h for h in HEADER if h in _COLS]
    with open(path, "w") as fh:
        fh.write(",".join(head) + "\n")
        for i in range(rec.time.size):
            fh.write(",".join(repr(float(values[_COLS[h]][i])) for h in head) + "\n")
    return path


@pytest.fixture(scope="module")
def folder(records, tmp_path_factory):
    root = tmp_path_factory.mktemp("logs")
    for rec in records:
        _write_csv(root / f"{rec.name}.csv", rec)
    return root


def test_cli_fits_a_folder_and_writes_the_ship_and_the_posterior(folder, tmp_path):
    from typer.testing import CliRunner

    from seahelm.identification.samples_file import read_samples
    from seahelm.cli.main import app

    out, post = tmp_path / "ident.toml", tmp_path / "post.csv"
    res = CliRunner().invoke(app, ["identify", "mmg", str(folder), "--ship", SHIP, "--wind",
                                   "measured", "--free", "N_r,Y_v,a_H", "--out", str(out),
                                   "--samples", "20", "--save-posterior", str(post),
                                   "--seed", "1"])
    assert res.exit_code == 0, (res.stdout, res.stderr)
    assert "2 record(s)" in res.stdout and "N_r" in res.stdout and "stated" in res.stdout
    ship = get_ship(str(out))
    assert ship.params.N_r == pytest.approx(TRUTH["N_r"], rel=0.15)
    assert ship.params.a_H == pytest.approx(TRUTH["a_H"], rel=0.15)
    samples = read_samples(post)
    assert samples.keys == ("vessel.params.N_r", "vessel.params.Y_v", "vessel.params.a_H")
    assert samples.values.shape == (20, 3)


@pytest.mark.parametrize("extra, message", [
    (["--free", "foo,N_r"], "`--free`: not coefficients of mmg-ls: foo"),
    (["--imo", "5"], "`--imo` is for an mmg ship"),
    (["--segment", "0"], "`--segment` must be > 0 [s], got 0.0"),
])
def test_cli_bad_input_is_one_line(folder, extra, message):
    line = one_error(["identify", "mmg", str(folder), "--ship", SHIP, *extra])
    assert message in line, line


def test_cli_wind_is_for_mmg_ls_and_an_empty_folder_is_refused(folder, tmp_path):
    line = one_error(["identify", "mmg", str(folder / "zigzag.csv"), "--ship", "kvlcc2-l7",
                      "--wind", "measured"])
    assert "`--wind` is for an mmg-ls ship" in line, line
    (tmp_path / "empty").mkdir()
    line = one_error(["identify", "mmg", str(tmp_path / "empty"), "--ship", SHIP])
    assert "a folder without any *.csv or *.nc record" in line, line


def test_cli_a_record_without_the_wind_names_the_column(folder, tmp_path):
    rec = read_records(folder / "zigzag.csv")[0]
    path = tmp_path / "nowind.csv"
    values = {"time": rec.time, "heading": rec.heading, "yaw_rate": rec.yaw_rate,
              "rudder_angle": rec.rudder_angle, **rec.channels}
    head = [h for h in HEADER if h in _COLS and not _COLS[h].startswith("true_wind")]
    path.write_text(",".join(head) + "\n" + "\n".join(
        ",".join(repr(float(values[_COLS[h]][i])) for h in head) for i in range(rec.time.size))
        + "\n")
    line = one_error(["identify", "mmg", str(path), "--ship", SHIP, "--wind", "measured"])
    assert "nowind.csv: a FRT-DS-ESSO record without column(s) `wind_velo_true [m/s]`" in line

