"""`seahelm identify steady-turn` (the typer app of seahelm.cli.identify)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.cli.identify import app
from seahelm.identification.reduced.turns import stable_steady_turn
from seahelm.vessels.voitkunsky import MARINER_VOITKUNSKY

runner = CliRunner()
LOG = Path(__file__).resolve().parents[1] / "examples" / "steady_turn_log.csv"
A, B, C = -320.0, -5.5, 17.0


def _points_csv(path: Path, omega, alpha, header="rudder_angle,yaw_rate") -> Path:
    with path.open("w") as fh:
        fh.write(header + "\n")
        for a, w in zip(alpha, omega):
            fh.write(f"{float(a)!r},{float(w)!r}\n")
    return path


def _exact_points(n=5):
    w = np.linspace(0.006, 0.045, n)
    return w, -(A * w**2 + B * w) / (1 + C * w)


def _run(*args):
    return runner.invoke(app, ["steady-turn", *map(str, args)])


def test_points_in_radians_recover_coefficients(tmp_path):
    w, al = _exact_points()
    r = _run(_points_csv(tmp_path / "p.csv", w, al), "--angles", "rad", "--json")
    assert r.exit_code == 0, r.output
    data = json.loads(r.stdout)
    assert data["input"] == "points" and data["points_used"] == 5
    for key, ref in zip("abc", (A, B, C)):
        assert data[key] == pytest.approx(ref, rel=1e-9)
        assert key in data["stderr"]
    assert data["residual_rms"] < 1e-12


def test_points_in_degrees_give_radian_coefficients(tmp_path):
    w, al = _exact_points()
    r = _run(_points_csv(tmp_path / "p.csv", np.degrees(w), np.degrees(al)), "--json")
    assert r.exit_code == 0, r.output
    data = json.loads(r.stdout)
    assert data["a"] == pytest.approx(A, rel=1e-9) and data["units"]["a"] == "s²/rad"
    assert data["points"][0]["rudder_angle"] == pytest.approx(math.degrees(al[0]))


def test_the_units_block_names_the_unit_of_every_number(tmp_path):
    """The points were printed in degrees under a units block that said rad (issue 36): the
    block names the unit of each field, the points' in --angles, the coefficients' in rad."""
    w, al = _exact_points()
    for angles, scale in (("deg", math.degrees), ("rad", float)):
        path = _points_csv(tmp_path / f"{angles}.csv", np.array([scale(x) for x in w]),
                           np.array([scale(x) for x in al]))
        data = json.loads(_run(path, "--angles", angles, "--json").stdout)
        units = data["units"]
        assert (units["rudder_angle"], units["yaw_rate"]) == (angles, f"{angles}/s")
        assert units["a"] == "s²/rad" and units["residual_rms"] == "rad"
        got = sorted(p["rudder_angle"] for p in data["points"])
        assert got == pytest.approx(sorted(scale(x) for x in al))
        for point in data["points"]:
            assert set(point) <= set(units)
    data = json.loads(_run(LOG, "--angles", "deg", "--json").stdout)
    assert all(set(s) - {"samples"} <= set(data["units"]) for s in data["segments"])
    assert data["units"]["start_time"] == "s"


def test_time_series_log(tmp_path):
    r = _run(LOG, "--angles", "deg", "--json")
    assert r.exit_code == 0, r.output
    data = json.loads(r.stdout)
    assert data["input"] == "time series" and data["points_used"] == 6
    assert [round(s["rudder_angle"], 6) for s in data["segments"]] == [5, 10, 15, 20, 25, 30]
    assert all(np.isfinite(list(data["stderr"].values())))
    # the fitted model reproduces a held-in turn of the full model
    b, a, c = data["b"], data["a"], data["c"]
    alpha = math.radians(15)
    qb = b + c * alpha
    omega = (-qb - math.sqrt(qb * qb - 4 * a * alpha)) / (2 * a)
    assert omega == pytest.approx(stable_steady_turn(MARINER_VOITKUNSKY, alpha).yaw_rate,
                                  rel=2e-3)


@pytest.mark.parametrize("method", ["lsq", "robust", "brute"])
def test_methods_and_human_output(method):
    r = _run(LOG, "--method", method)
    assert r.exit_code == 0, r.output
    text = " ".join(r.stdout.split())
    assert "coefficient" in text and f"method {method}" in text


def test_exact_form_has_d(tmp_path):
    r = _run(LOG, "--form", "exact", "--json")
    assert r.exit_code == 0, r.output
    assert "d" in json.loads(r.stdout)["stderr"]


@pytest.mark.parametrize(
    "content, args, match",
    [
        ("rudder_angle,yaw_rate\n5,0.6\n10,1.1\n", [], "at least 3 distinct steady points"),
        ("rudder_angle,yaw_rate\n5,0.6\n5,1.1\n5,1.5\n", [], "degenerate design"),
        ("rudder_angle,yaw_rate\n5,0.6\n10,nan\n15,1.5\n", [], "NaN/inf"),
        ("rudder_angle,yaw_rate\n5,0.6\n10,\n15,1.5\n", [], "not a number"),
        ("time,rudder\n0,1\n1,1\n2,1\n", [], "missing column"),
        ("rudder_angle,yaw_rate\n5,0.6\n10,1.1\n15,1.5\n", ["--angles", "grad"], "--angles"),
        ("rudder_angle,yaw_rate\n5,0.6\n10,1.1\n15,1.5\n", ["--method", "ols"], "--method"),
        ("time,rudder_angle,yaw_rate\n0,5,0.1\n1,5,0.2\n2,5,0.3\n", [], "steady segment"),
        ("", [], "empty file"),
    ],
)
def test_bad_input_exits_2_with_one_line(tmp_path, content, args, match):
    path = tmp_path / "bad.csv"
    path.write_text(content)
    r = _run(path, *args)
    assert r.exit_code == 2, r.output
    msg = r.stderr if hasattr(r, "stderr") else r.output
    assert match in msg.replace("\n", " ")
    assert r.stdout.strip() == "" or not r.stdout.strip().startswith("{")


def test_missing_file_exits_2(tmp_path):
    r = _run(tmp_path / "nope.csv")
    assert r.exit_code == 2
