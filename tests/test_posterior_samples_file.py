"""Posterior samples as Monte-Carlo draws (issue 30, item 4): ``seahelm identify mmg --imo N
--save-posterior FILE.csv`` writes the posterior ships' hull derivatives as a samples file, and
``seahelm imo SHIP.toml --draws FILE.csv`` and a ``kind = "imo"`` scenario with
``[batch.monte_carlo] samples = "FILE.csv"`` check the same ships: the same probabilities, to
the last bit. The samples file itself: written numbers read back exactly, bad files refused by
column and line."""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.analysis.maneuvers import zigzag
from seahelm.identification.samples_file import read_samples, write_samples
from seahelm.cli.main import app
from seahelm.errors import ParameterError
from seahelm.results import open_result_file
from seahelm.scenario import load_scenario
from seahelm.scenario.errors import ScenarioError
from seahelm.ships import get_ship

runner = CliRunner()
KEYS = ("criteria", "probability", "ci_low", "ci_high", "passed", "total", "excluded")


def invoke(args):
    res = runner.invoke(app, [str(a) for a in args])
    assert res.exit_code == 0, (res.stdout, res.stderr)
    return json.loads(res.stdout)


@pytest.fixture(scope="module")
def identified(tmp_path_factory):
    """``identify mmg`` of a 20/20 zig-zag (regression, the derivatives it does not identify
    at the KVLCC2's values), 4 posterior ships checked against IMO, the ship file and the
    samples file written."""
    d = tmp_path_factory.mktemp("posterior")
    log = d / "zz20.nc"
    zigzag(get_ship("kvlcc2-l7"), math.radians(20.0), math.radians(20.0), sides=1,
           record_dt=0.2).runs.to_netcdf(log, engine="h5netcdf")
    payload = invoke(["identify", "mmg", log, "--ship", "kvlcc2-l7", "--regression-only",
                      "--imo", "4", "--seed", "3", "-o", d / "id.toml",
                      "--save-posterior", d / "post.csv", "--json"])
    return d, payload


def test_the_samples_file_holds_the_posterior_ships(identified):
    d, payload = identified
    assert payload["posterior_file"] == str(d / "post.csv")
    table = read_samples(d / "post.csv")
    assert table.n_samples == 4 and len(table.keys) == 17  # every hull derivative
    assert all(k.startswith("vessel.params.") for k in table.keys)
    assert table.units["vessel.params.N_v"] == "-"
    assert any("posterior samples of the MMG hull derivatives" in c for c in table.comments)
    sampled = payload["imo"]["posterior_samples"]
    for name, mean in sampled["mean"].items():  # the posterior's statistics of the same rows
        assert np.mean(table.column(f"vessel.params.{name}")) == pytest.approx(mean, rel=1e-12)
    for name in sampled["fixed_at_base"]:  # not identified: the base ship's value, every row
        col = table.column(f"vessel.params.{name}")
        assert np.all(col == getattr(get_ship("kvlcc2-l7").params, name))


def test_imo_draws_file_and_scenario_give_the_probabilities_of_the_identification(identified):
    d, payload = identified
    direct = payload["imo"]
    cmd = invoke(["imo", d / "id.toml", "--draws", d / "post.csv", "--out", d / "a", "--json"])
    for key in KEYS:
        assert cmd[key] == direct[key], key
    scn = d / "imo.toml"
    scn.write_text('[vessel]\nship = "id.toml"\n[maneuver]\nkind = "imo"\n'
                   '[batch.monte_carlo]\nruns = 4\nseed = 0\nsamples = "post.csv"\n')
    run = invoke(["run", scn, "--out", d / "b", "--json"])
    for key in KEYS:
        assert run[key] == direct[key], key
    a = open_result_file(d / "a" / "imo-probabilities.nc")
    b = open_result_file(d / "b" / "imo-probabilities.nc")
    np.testing.assert_array_equal(a["value"].values, b["value"].values)
    table = read_samples(d / "post.csv")
    for key in table.keys:
        np.testing.assert_array_equal(b[key].values, table.column(key))
        assert b[key].attrs["distribution"] == "samples"
    # fewer samples than the file holds: its first rows
    two = invoke(["imo", d / "id.toml", "--draws", d / "post.csv", "--monte-carlo", "2",
                  "--json"])
    assert two["total"] + two["excluded"] == 2


def test_bad_draws_files_and_scenarios(identified, tmp_path):
    d, _ = identified
    res = runner.invoke(app, ["imo", str(d / "id.toml"), "--draws", str(d / "post.csv"),
                              "--monte-carlo", "5"])
    assert res.exit_code == 2 and "holds only 4 samples" in res.stderr, res.stderr
    bad = tmp_path / "bad.csv"
    bad.write_text("vessel.params.N_v,vessel.params.N_r\n-0.1,-0.05\n-0.1,nan\n")
    res = runner.invoke(app, ["imo", str(d / "id.toml"), "--draws", str(bad)])
    assert res.exit_code == 2 and "`vessel.params.N_r` line 3" in res.stderr, res.stderr
    bad.write_text("vessel.params.length\n7.0\n")
    res = runner.invoke(app, ["imo", str(d / "id.toml"), "--draws", str(bad)])
    assert res.exit_code == 2 and "share the ship's length" in res.stderr, res.stderr
    scn = tmp_path / "s.toml"
    scn.write_text(f'[vessel]\nship = "{d / "id.toml"}"\n[maneuver]\nkind = "imo"\n'
                   f'[batch.monte_carlo]\nruns = 9\nseed = 0\nsamples = "{d / "post.csv"}"\n')
    with pytest.raises(ScenarioError, match=r"batch.monte_carlo.samples.*holds 4 samples"):
        load_scenario(scn)
    scn.write_text(f'[vessel]\nship = "kvlcc2-l7"\n[maneuver]\nkind = "imo"\n'
                   f'[batch.monte_carlo]\nruns = 2\nseed = 0\nsamples = "{d / "post.csv"}"\n'
                   '[batch.monte_carlo.draws]\n'
                   '"vessel.params.N_v" = { distribution = "normal", mean = -0.1, std = 0.01 }\n')
    with pytest.raises(ScenarioError, match="`vessel.params.N_v` is a column of the samples"):
        load_scenario(scn)
    res = runner.invoke(app, ["identify", "mmg", str(d / "zz20.nc"), "--ship", "kvlcc2-l7",
                              "--save-posterior", str(tmp_path / "p.csv")])
    assert res.exit_code == 2 and "needs the number of samples" in res.stderr, res.stderr
    for option in ("--samples", "--imo"):  # 10^12 was a MemoryError (exit 1)
        res = runner.invoke(app, ["identify", "mmg", str(d / "zz20.nc"), "--ship", "kvlcc2-l7",
                                  option, "1000000000000", "--save-posterior",
                                  str(tmp_path / "p.csv")])
        lines = res.stderr.strip().splitlines()
        assert res.exit_code == 2 and len(lines) == 1 and option in lines[0] \
            and "100000" in lines[0], res.stderr
    assert not (tmp_path / "p.csv").exists()


def test_written_numbers_read_back_exactly(tmp_path):
    rng = np.random.default_rng(0)
    cols = {"vessel.params.N_v": rng.normal(-0.137, 0.01, 50),
            "actuator.params.max_rate": rng.uniform(0.1, 0.3, 50)}
    path = write_samples(tmp_path / "s.csv", cols, units={"actuator.params.max_rate": "rad/s"},
                         comments=("two\nlines",))
    table = read_samples(path)
    assert table.keys == tuple(cols) and table.comments == ("two", "lines")
    assert table.units == {"actuator.params.max_rate": "rad/s"}
    for k, v in cols.items():
        np.testing.assert_array_equal(table.column(k), v)
    for text, match in (("", "no header"), ("N_v\n1\n", "not a key path"),
                        ("vessel.params.a,vessel.params.a\n1,2\n", "appears twice"),
                        ("vessel.params.a\n", "no samples"),
                        ("vessel.params.a,vessel.params.b\n1\n", "line 2 has 1 values")):
        (tmp_path / "b.csv").write_text(text)
        with pytest.raises(ParameterError, match=match):
            read_samples(tmp_path / "b.csv")


def test_a_failed_write_leaves_the_old_file(tmp_path, monkeypatch):
    """write_samples is atomic: a disk error while writing keeps the old file whole and leaves
    no temporary file (it wrote in place before)."""
    from pathlib import Path

    path = write_samples(tmp_path / "s.csv", {"vessel.params.N_v": [-0.1, -0.2]})
    before = path.read_bytes()

    def full_disk(self, data):
        raise OSError(28, "No space left on device", str(self))

    monkeypatch.setattr(Path, "write_bytes", full_disk)
    with pytest.raises(OSError):
        write_samples(path, {"vessel.params.N_v": [-0.3]})
    monkeypatch.undo()
    assert path.read_bytes() == before and sorted(p.name for p in tmp_path.iterdir()) == ["s.csv"]


@pytest.mark.parametrize("extra, match", [
    (["--speed", "1.0"], "`--draws FILE.csv` runs every sample at the ship's test speed"),
    (["--check"], "`--check` needs a pass or a fail; `--draws FILE.csv` gives probabilities"),
])
def test_draws_file_alone_names_itself(identified, extra, match):
    """Without --monte-carlo, the refusal named `--monte-carlo`, an option not given."""
    d, _ = identified
    res = runner.invoke(app, ["imo", str(d / "id.toml"), "--draws", str(d / "post.csv"), *extra])
    lines = res.stderr.strip().splitlines()
    assert res.exit_code == 2 and len(lines) == 1 and match in lines[0], res.stderr


@pytest.mark.parametrize("units, ok", [
    ("vessel.params.N_v = deg", False), ("vessel.params.N_v = rad/s, vessel.params.N_r = -",
                                         False),
    ("vessel.params.N_v = -, vessel.params.N_r = 1", True), ("vessel.params.N_r =", True),
])
def test_imo_draws_refuses_a_column_in_other_units(identified, tmp_path, units, ok):
    """N_v and N_r are non-dimensional ('-' in the model's table); a file that says otherwise
    was taken as stored numbers."""
    from seahelm.identification.samples_file import check_units

    d, _ = identified
    path = tmp_path / "u.csv"
    path.write_text(f"# units: {units}\nvessel.params.N_v,vessel.params.N_r\n-0.1,-0.05\n")
    stored = {"vessel.params.N_v": "-", "vessel.params.N_r": "-"}
    if ok:
        check_units(read_samples(path), stored)
        return
    with pytest.raises(ParameterError, match=r"column `vessel.params.N_v` is in '(deg|rad/s)'; "
                                             r"its stored unit is '-'"):
        check_units(read_samples(path), stored)
    res = runner.invoke(app, ["imo", str(d / "id.toml"), "--draws", str(path)])
    lines = res.stderr.strip().splitlines()
    assert res.exit_code == 2 and len(lines) == 1 and "`--draws`" in lines[0] \
        and "stored unit is '-'" in lines[0] and not res.stdout, res.stderr


def test_a_scenario_refuses_a_samples_column_in_other_units(tmp_path):
    """A samples file holds stored units: in a scenario, a column whose `# units:` say
    otherwise (N_v in degrees, the steering gear's rate in deg/s) is refused at
    batch.monte_carlo.samples, naming the column and both units; stored units pass."""
    scn = tmp_path / "s.toml"
    text = ('[vessel]\nship = "kvlcc2-l7"\n[maneuver]\nkind = "turning"\nt_final = 30\n'
            '[batch.monte_carlo]\nruns = 2\nseed = 0\nsamples = "u.csv"\n')
    scn.write_text(text)
    for units, bad in (("vessel.params.N_v = deg", "'deg'; its stored unit is '-'"),
                       ("actuator.params.max_rate = deg/s", "'deg/s'; its stored unit is "
                                                            "'rad/s'")):
        key = units.split(" =")[0]
        (tmp_path / "u.csv").write_text(f"# units: {units}\n{key}\n-0.1\n-0.12\n"
                                        if key.endswith("N_v") else
                                        f"# units: {units}\n{key}\n2.3\n2.4\n")
        with pytest.raises(ScenarioError, match=r"batch\.monte_carlo\.samples.*"
                                                + re.escape(bad)):
            load_scenario(scn)
    (tmp_path / "u.csv").write_text("# units: vessel.params.N_v = -\nvessel.params.N_v\n"
                                    "-0.1\n-0.12\n")
    assert load_scenario(scn).n_samples == 2


def test_a_failed_posterior_writes_no_ship_file(identified, tmp_path, monkeypatch):
    """``-o SHIP.toml --save-posterior F.csv``: the ship file is written after the posterior
    (and its file), so a draw that fails leaves neither behind (it used to leave the ship)."""
    import seahelm.identification.mmg_posterior as mp

    d, _ = identified

    def refuse(*args, **kwargs):
        raise ParameterError("the posterior could not be drawn (test)")

    monkeypatch.setattr(mp, "mmg_posterior", refuse)
    res = runner.invoke(app, ["identify", "mmg", str(d / "zz20.nc"), "--ship", "kvlcc2-l7",
                              "--regression-only", "--imo", "4", "-o", str(tmp_path / "s.toml"),
                              "--save-posterior", str(tmp_path / "p.csv")])
    assert res.exit_code == 2 and "could not be drawn" in res.stderr, res.stderr
    assert not (tmp_path / "s.toml").exists() and not (tmp_path / "p.csv").exists()
