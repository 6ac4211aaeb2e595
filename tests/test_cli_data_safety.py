"""Nothing a user has is overwritten by accident: an output is never an input of the command,
a file it reads beside its input, or a place inside a store (issue 33, part 1)."""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

import pytest
from typer.testing import CliRunner

from seahelm.cli._common import protect_inputs, store_containing
from seahelm.cli.main import app
from seahelm.errors import ParameterError
from seahelm.ships import get_ship, write_ship

runner = CliRunner()


def _digest(path: Path) -> str:
    if path.is_dir():
        return "".join(_digest(p) + str(p.relative_to(path)) for p in sorted(path.rglob("*")))
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _refused(args, *, keep, match):
    before = {p: _digest(p) for p in keep}
    res = runner.invoke(app, args)
    assert res.exit_code == 2, (res.stdout, res.stderr)
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and match in lines[0], lines
    assert {p: _digest(p) for p in keep} == before  # nothing touched


def _fake_store(path: Path) -> Path:
    path.mkdir()
    (path / "zarr.json").write_text('{"zarr_format": 3, "node_type": "group"}')
    (path / "status").mkdir()
    (path / "status" / "zarr.json").write_text("{}")
    return path


def test_report_never_writes_into_the_store_it_reads(tmp_path):
    store = _fake_store(tmp_path / "s.zarr")
    _refused(["report", str(store), "-o", str(store / "zarr.json")], keep=[store],
             match="which this command reads: writing there would corrupt it")
    _refused(["report", str(store), "-o", str(store / "status" / "r.html")], keep=[store],
             match="is inside")


def test_report_never_overwrites_the_companion_files_it_reads(tmp_path):
    runs = tmp_path / "turning-circle-runs.nc"
    metrics = tmp_path / "turning-circle-metrics.nc"
    imo = tmp_path / "imo-report.json"
    for p in (runs, metrics, imo):
        p.write_bytes(os.urandom(64))
    for target in (metrics, imo, runs):
        _refused(["report", str(runs), "-o", str(target)], keep=[runs, metrics, imo],
                 match="is a file this command reads")


def test_a_link_to_an_input_is_the_input(tmp_path):
    result = tmp_path / "result.nc"
    result.write_bytes(b"x" * 10)
    link = tmp_path / "link.html"
    link.symlink_to(result)
    _refused(["report", str(result), "-o", str(link)], keep=[result], match="is a file this command reads")
    _refused(["plot", str(result), "--out", str(link)], keep=[result], match="is a file this command reads")


def test_nothing_is_written_inside_any_store(tmp_path):
    store = _fake_store(tmp_path / "other.zarr")
    _refused(["waves", "sample", "--h3", "3", "--duration", "10", "--dt", "0.5", "--seed", "1",
              "--out", str(store / "w.nc")], keep=[store], match="is inside the store")
    _refused(["maneuver", "turning", "--out", str(store / "turn")], keep=[store],
             match="is inside the store")


def test_run_and_manoeuvres_never_overwrite_their_scenario_or_ship_file(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    scenario = out / "result.nc"  # (a scenario may be called anything)
    scenario.write_text((Path(__file__).parent.parent / "examples" /
                         "mariner_pid_sweep.toml").read_text())
    _refused(["run", str(scenario), "--out", str(out)], keep=[scenario],
             match="is a file this command reads")
    ship = out / "turning-circle-runs.nc"  # a ship file by another name
    write_ship(get_ship("kvlcc2-l7"), ship)
    _refused(["maneuver", "turning", "--ship", str(ship), "--out", str(out)], keep=[ship],
             match="is a file this command reads")
    _refused(["imo", str(ship), "--out", str(out)], keep=[ship], match="is a file this command reads")


def test_a_sweep_store_is_neither_the_scenario_nor_inside_a_store(tmp_path):
    scenario = tmp_path / "s.toml"
    scenario.write_text((Path(__file__).parent.parent / "examples" /
                         "mariner_pid_sweep.toml").read_text())
    _refused(["sweep", str(scenario), "--store", str(scenario)], keep=[scenario],
             match="is the scenario file")
    outer = _fake_store(tmp_path / "outer.zarr")
    _refused(["sweep", str(scenario), "--store", str(outer / "inner.zarr")], keep=[outer],
             match="is inside the store")


def test_the_guard_itself(tmp_path):
    store = _fake_store(tmp_path / "a.zarr")
    assert store_containing(store / "status" / "x") == store.resolve()
    assert store_containing(store) == store.resolve()
    assert store_containing(tmp_path / "b.nc") is None
    protect_inputs("--out", tmp_path / "b.nc", reads=[tmp_path / "c.nc"])  # fine
    with pytest.raises(ParameterError, match=r"`--out` .*c.nc is a file this command reads: "):
        protect_inputs("--out", tmp_path / "c.nc", reads=[tmp_path / "c.nc"])
    with pytest.raises(ParameterError, match="is inside the store"):
        protect_inputs("--out", store / "new.nc")


# ------------------------------------------------------------------------------------------
# resource limits that hold (issue 33, part 4)
# ------------------------------------------------------------------------------------------
def _sweep_scenario(tmp_path):
    scenario = tmp_path / "s.toml"
    scenario.write_text((Path(__file__).parent.parent / "examples" /
                         "mariner_pid_sweep.toml").read_text())
    return scenario


def test_sweep_workers_are_checked_against_the_cores(tmp_path):
    scenario = _sweep_scenario(tmp_path)
    cores = os.cpu_count() or 1
    _refused(["sweep", str(scenario), "--store", str(tmp_path / "s.zarr"), "--workers",
              str(cores * 500)], keep=[scenario],
             match=f"is more than this machine's {cores} core(s)")
    assert not (tmp_path / "s.zarr").exists()


def test_an_explicit_chunk_size_is_checked_against_memory(tmp_path, monkeypatch):
    from seahelm.resources import MemoryLimit
    from seahelm.sweep import chunks

    import seahelm.resources as resources

    scenario = _sweep_scenario(tmp_path)
    _refused(["sweep", str(scenario), "--store", str(tmp_path / "s.zarr"), "--chunk-size",
              str(10 ** 12)], keep=[scenario], match="`--chunk-size` = 1,000,000,000,000 runs "
                                                     "would hold")
    # a small limit (a cgroup's, say) refuses what the machine would take
    monkeypatch.setattr(resources, "memory_limit",
                        lambda: MemoryLimit(1_000_000, "the cgroup's memory limit"))
    with pytest.raises(ParameterError, match=r"more than 80% of the 0.001 GB this process may "
                                             r"use \(the cgroup's memory limit\); give at "
                                             r"most") as err:
        chunks.check_chunk_memory(1000, 10_000.0, workers=2)
    assert err.value.field == "chunk_size"
    chunks.check_chunk_memory(10, 10_000.0, workers=2)  # 0.4 MB: fits


# ------------------------------------------------------------------------------------------
# result files verify themselves (issue 33, part 2, NetCDF)
# ------------------------------------------------------------------------------------------
def _damage(path: Path, variable: str) -> None:
    import h5py

    with h5py.File(path) as f:
        assert f[variable].fletcher32  # written with a checksum
        offset = f[variable].id.get_chunk_info(0).byte_offset
    with open(path, "r+b") as fh:
        fh.seek(offset + 16)
        fh.write(b"\x13" * 64)


def test_a_damaged_result_file_is_one_clear_error(tmp_path):
    import numpy as np

    from seahelm.results import CorruptResultError, load_result
    from seahelm.simulation.engine import simulate
    from seahelm.vessels.nomoto import NOMOTO2

    result = simulate(NOMOTO2, get_ship("mariner-nomoto2").params, np.zeros((3, 5)),
                      t_final=20.0, dt=0.1, reference=[0.1])
    path = result.to_netcdf(tmp_path / "result.nc")
    ds = load_result(path)  # intact: reads back as written
    np.testing.assert_array_equal(ds["heading"].values, result["heading"])
    assert ds.attrs["seahelm_checksums"] == "fletcher32"
    _damage(path, "heading")
    with pytest.raises(CorruptResultError) as err:
        load_result(path)
    assert err.value.field == "heading"
    assert str(err.value) == (f"{path}: variable `heading` is damaged: its data do not match "
                              "their checksum (Fletcher-32); the file was changed after seahelm "
                              "wrote it (write it again from its scenario)")
    for args in (["inspect", str(path)], ["report", str(path), "-o", str(tmp_path / "r.html")],
                 ["plot", str(path), "--out", str(tmp_path / "p.png")]):
        res = runner.invoke(app, args)
        assert res.exit_code == 2, (args, res.stdout, res.stderr)
        assert res.stderr.strip() == f"error: {err.value}", res.stderr
    assert not (tmp_path / "r.html").exists() and not (tmp_path / "p.png").exists()


def test_a_sweep_is_bounded_by_its_chunk_not_by_the_study(tmp_path, monkeypatch):
    # 80 runs of 1,201 records: 14.6 MB of series, a 36 MB peak in memory at once; with 20 MB
    # to use, `run` refuses the study, `sweep` streams it in chunks that fit
    import seahelm.resources as resources
    import seahelm.simulation.memory as memory
    from seahelm.resources import MemoryLimit

    limit = MemoryLimit(20_000_000, "the cgroup's memory limit")
    monkeypatch.setattr(memory, "memory_limit", lambda: limit)
    monkeypatch.setattr(resources, "memory_limit", lambda: limit)
    monkeypatch.setattr(memory, "ASK_ABOVE", 0)
    scenario = _sweep_scenario(tmp_path)
    _refused(["run", str(scenario)], keep=[scenario], match="more than 80% of the 0.02 GB")
    _refused(["sweep", str(scenario), "--store", str(tmp_path / "a.zarr"), "--chunk-size", "80"],
             keep=[scenario], match="`--chunk-size` = 80 runs would hold")
    res = runner.invoke(app, ["sweep", str(scenario), "--store", str(tmp_path / "b.zarr"),
                              "--chunk-size", "10", "--no-series", "--json"])
    assert res.exit_code == 0, res.stderr
    res = runner.invoke(app, ["sweep", str(scenario), "--store", str(tmp_path / "c.zarr"),
                              "--chunk-size", "10", "--json"])
    assert res.exit_code == 0, res.stderr


# ------------------------------------------------------------------------------------------
# every range check wherever the value comes from (issue 33, part 5)
# ------------------------------------------------------------------------------------------
ROUTE = """
title = "r"
[vessel]
ship = "mariner-nonlinear"
[controller]
model = "pid-heading"
[guidance]
law = "los"
waypoints = [[0.0, 0.0], [2000.0, 0.0], [2000.0, 2000.0]]
acceptance_radius = {radius}
[simulation]
t_final = 20.0
dt = 0.1
"""

WIND_GRID = """
title = "w"
[vessel]
ship = "mariner-voitkunsky"
[controller]
model = "pid-heading"
[controller.reference]
heading_deg = 10.0
[simulation]
t_final = 20.0
dt = 0.1
[environment]
loads = "once-per-step"
[environment.wind]
model = "lvov"
speed = 2.0
direction_deg = 90
lateral_area = 1000.0
[batch.grid]
"environment.wind.direction_deg" = [0.0, {direction}]
"""


def _scenario_error(tmp_path, text, match):
    path = tmp_path / "s.toml"
    path.write_text(text)
    _refused(["run", str(path)], keep=[path], match=match)


def test_a_grid_value_is_checked_like_a_single_one(tmp_path):
    _scenario_error(tmp_path, WIND_GRID.format(direction=720.0),
                    "[environment.wind.direction_deg] `direction_deg` must be in [-360, 360] "
                    "[deg], got 720 (run 1: {'environment.wind.direction_deg': 720.0})")


def test_an_acceptance_circle_larger_than_the_route_is_refused(tmp_path):
    from seahelm.control.path_following import LOS, route_params

    _scenario_error(tmp_path, ROUTE.format(radius=1e9),
                    "must be shorter than the route's legs [m]: 1000000000.0 >= the longest "
                    "leg, 2000 m")
    with pytest.raises(ParameterError) as err:
        route_params([[0.0, 0.0], [100.0, 0.0]], law=LOS, acceptance_radius=150.0)
    assert err.value.field == "acceptance_radius"


def test_absurd_currents_and_angles_are_refused(tmp_path):
    import numpy as np

    from seahelm.control.pid import PID_HEADING
    from seahelm.simulation.engine import simulate
    from seahelm.vessels.nomoto import NOMOTO2

    base = ROUTE.split("[guidance]")[0].replace('[controller]\nmodel = "pid-heading"\n', "")
    current = (base + '[simulation]\nt_final = 20.0\ndt = 0.1\n[controller]\n'
               'model = "pid-heading"\n[controller.reference]\nheading_deg = 10.0\n'
               '[environment.current]\nspeed = 1000.0\ndirection_deg = 90\n')
    _scenario_error(tmp_path, current, "[environment.current.speed] must be <= 15 [m/s], "
                                       "got 1000.0")
    with pytest.raises(ParameterError, match=r"channel 'heading' reaches 1e\+300 rad, more "
                                             r"than a thousand turns") as err:
        simulate(NOMOTO2, get_ship("mariner-nomoto2").params, np.zeros(5), t_final=1.0,
                 dt=0.1, controller=PID_HEADING, reference={"heading": 1e300})
    assert err.value.field == "reference"


# ------------------------------------------------------------------------------------------
# messages in the user's words (issue 33, part 6)
# ------------------------------------------------------------------------------------------
def test_an_angle_given_in_degrees_is_refused_in_degrees():
    from seahelm.actuators.servo import ServoParams

    with pytest.raises(ParameterError) as err:
        ServoParams.from_mapping({"max_angle_deg": 200})
    assert str(err.value) == "`max_angle_deg` must be in (0, 180] [deg], got 200"
    assert (err.value.field, err.value.unit, err.value.value) == ("max_angle_deg", "deg", 200.0)
    with pytest.raises(ParameterError, match=r"`max_angle` must be in \(0, 3.14159\] \[rad\]"):
        ServoParams.from_mapping({"max_angle": 3.5})  # (radians written: radians said)


def test_an_empty_list_is_not_called_a_number(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text('title = "t"\n[vessel]\nship = "kvlcc2-l7"\n[maneuver]\nkind = "turning"\n'
                    'rudder_deg = []\n')
    _refused(["run", str(path)], keep=[path], match="[maneuver.rudder_deg] must be a number or "
                                                    "a non-empty list of numbers [deg], got []")


def test_a_turn_log_in_degrees_read_as_radians_is_refused():
    log = Path(__file__).resolve().parent.parent / "examples" / "steady_turn_log.csv"
    _refused(["identify", "steady-turn", str(log), "--angles", "rad"], keep=[log],
             match="column `rudder_angle` reaches 30, read as radians (`--angles rad`) that is "
                   "1719 deg, beyond any rudder; the log is in degrees? (`--angles deg`)")


def test_a_report_or_figure_never_replaces_another_result(tmp_path):
    import numpy as np

    from seahelm.simulation.engine import simulate
    from seahelm.vessels.nomoto import NOMOTO2

    result = simulate(NOMOTO2, get_ship("mariner-nomoto2").params, np.zeros((2, 5)),
                      t_final=5.0, dt=0.1, reference=[0.1])
    a = result.to_netcdf(tmp_path / "a" / "result.nc")
    b = result.to_netcdf(tmp_path / "b" / "result.nc")
    _refused(["report", str(a), "-o", str(b)], keep=[a, b],
             match="exists (a seahelm NetCDF file); this writes an HTML report there: pass "
                   "--force")
    _refused(["plot", str(a), "--out", str(b)], keep=[a, b],
             match="exists (a seahelm NetCDF file); this writes a figure there: pass --force")
