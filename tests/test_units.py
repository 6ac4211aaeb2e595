"""One source of truth for units (issue 36, "Meaning and units"): each output's stored unit
(:mod:`seahelm.units`, the summary metrics' by their names) is the one its model, actuator or
name declares, in memory, in ``result.nc``, in a sweep store and in ``seahelm models``; and the
display rule (angles in degrees, fractions in per cent) is one function."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from seahelm.units import (
    display_unit,
    metric_label,
    metric_unit,
    shown_metrics,
    to_display,
)


def test_a_metric_unit_comes_from_its_name_or_its_signal():
    signals = {"heading": "rad", "yaw_rate": "rad/s", "north": "m"}
    assert metric_unit("settling_time_s", signals) == "s"
    assert metric_unit("overshoot_deg", signals) == "deg"
    assert metric_unit("rudder_reversals_per_min", signals) == "1/min"
    assert metric_unit("final_heading", signals) == "rad"
    assert metric_unit("final_heading_rad", signals) == "rad"
    assert metric_unit("yaw_rate_error", signals) == "rad/s"
    assert metric_unit("final_cross_track_error_m", signals) == "m"
    assert metric_unit("something", signals) == ""


def test_the_display_rule():
    assert display_unit("rad") == ("deg", pytest.approx(180 / math.pi))
    assert display_unit("rad/s")[0] == "deg/s"
    assert display_unit("1", "speed_loss") == ("%", 100.0)
    assert display_unit("1", "yaw_rate_nd") == ("1", 1.0)  # a ratio that is not a fraction
    assert display_unit("", "speed_loss") == ("", 1.0)  # no unit: nothing scaled
    assert display_unit("m/s") == ("m/s", 1.0)
    value, unit = to_display(np.array([math.pi, -math.pi / 2]), "rad")
    assert unit == "deg" and value.tolist() == pytest.approx([180.0, -90.0])
    assert to_display(None, "rad") == (None, "deg")
    assert to_display(0.25, "1", "speed_loss") == (25.0, "%")
    assert metric_label("settling_time_s", "s") == "settling time [s]"
    assert metric_label("final_heading", "rad") == "final heading [deg]"
    assert metric_label("final_heading_rad", "rad") == "final heading [deg]"
    assert metric_label("speed_loss", "1") == "speed loss [%]"
    assert metric_label("time_90", "s") == "time 90 [s]"
    assert metric_label("final_yaw_aux", "") == "final yaw aux"
    # a shaft's rotation speed (rad/s of a ..._speed) in rpm, an angle's rate in deg/s: the
    # Otter's propellers at 73.6 rad/s were shown as "4216 deg/s"
    assert display_unit("rad/s", "final_propeller_port_speed") == ("rpm", pytest.approx(
        60 / (2 * math.pi)))
    assert to_display(2 * math.pi, "rad/s", "propeller_speed_command") == (
        pytest.approx(60.0), "rpm")
    assert metric_label("final_propeller_port_speed", "rad/s") == (
        "final propeller port speed [rpm]")
    assert metric_label("final_yaw_rate", "rad/s") == "final yaw rate [deg/s]"
    assert display_unit("m/s", "final_surge_speed") == ("m/s", 1.0)


def test_an_angle_is_shown_once_and_no_filter_state():
    keys = ["final_north", "final_heading", "heading_deg", "max_abs_heading_deg",
            "final_yaw_aux", "final_heading_rad", "settling_time_s", "overshoot_deg"]
    assert shown_metrics(keys) == ["final_north", "final_heading", "max_abs_heading_deg",
                                   "settling_time_s", "overshoot_deg"]
    # an output heading (no state of that name): its final value in radians is shown
    assert shown_metrics(["final_heading_rad", "final_yaw_rate"]) == ["final_heading_rad",
                                                                       "final_yaw_rate"]


@pytest.fixture(scope="module")
def demo_result():
    """The demo's run (its kernel is compiled for the suite anyway)."""
    from seahelm.scenario import default_scenario_text, parse_scenario, run_scenario

    return run_scenario(parse_scenario(default_scenario_text(), source="<demo>"))


def test_every_summary_metric_has_the_declared_unit(demo_result):
    from seahelm.analysis.maneuvers import summarize, summary_units
    from seahelm.registry import get_actuator, get_model

    model = get_model(demo_result.metadata["model"])
    actuator = get_actuator(demo_result.metadata["actuator"])
    declared = dict(zip(model.state_labels + actuator.state_labels,
                        model.state_units + actuator.state_units))
    keys = [k for k in summarize(demo_result)[0] if k not in ("run", "status")]
    units = summary_units(demo_result)
    assert set(units) == set(keys)
    for name, unit in declared.items():
        assert units[f"final_{name}"] == unit, name
    assert units["final_heading_rad"] == declared["heading"] == "rad"
    assert units["final_yaw_rate"] == declared["yaw_rate"]
    assert units["settling_time_s"] == "s" and units["heading_error_deg"] == "deg"
    assert all(units.values()), units  # none blank for the demo


def test_a_controller_command_has_the_unit_of_what_it_feeds(demo_result, tmp_path):
    from seahelm.registry import get_actuator
    from seahelm.results import load_result

    servo = get_actuator(demo_result.metadata["actuator"])
    want = dict(zip(servo.command_labels, servo.command_units))
    assert demo_result.units()["rudder_command"] == want["rudder_command"] == "rad"
    ds = demo_result.to_xarray()
    assert ds["rudder_command"].attrs["units"] == "rad"
    path = demo_result.to_netcdf(tmp_path / "result.nc")
    assert load_result(path)["rudder_command"].attrs["units"] == "rad"  # and in the file


def test_models_lists_controller_command_and_measurement_units():
    from seahelm.cli.main import app
    from seahelm.registry import get_actuator, get_model

    res = CliRunner().invoke(app, ["models", "--json"])
    assert res.exit_code == 0, res.output
    payload = json.loads(res.stdout)
    pid = {(s["kind"], s["name"]): s["unit"]
           for s in payload["controllers"]["pid-heading"]["signals"]}
    servo = get_actuator("rudder-servo")
    assert pid["command", "rudder_command"] == \
        servo.command_units[servo.command_labels.index("rudder_command")] == "rad"
    model = get_model("nomoto2")
    for name in ("heading", "yaw_rate"):
        assert pid["measurement", name] == model.output_units[model.output_labels.index(name)]
    rps = {(s["kind"], s["name"]): s["unit"]
           for s in payload["controllers"]["pid-heading-rps"]["signals"]}
    assert rps["command", "propeller_rps"] == "1/s"
    human = CliRunner().invoke(app, ["models", "pid-heading"], env={"COLUMNS": "120"}).stdout
    line = next(x for x in human.splitlines() if x.startswith("command")
                and "rudder_command" in x)
    assert "[rad]" in line


def test_a_sweep_store_holds_each_metric_unit(report_sweep_dir):
    """The store's metrics carry their units (the sweep report's unit column was empty)."""
    from seahelm.registry import get_model
    from seahelm.sweep.run import summary_statistics
    from seahelm.sweep.store import open_sweep

    ds = open_sweep(report_sweep_dir / "sweep.zarr", flat=True)
    model = get_model(ds.attrs["model"])
    for name, unit in zip(model.state_labels, model.state_units):
        assert ds[f"final_{name}"].attrs["units"] == unit, name
    assert ds["settling_time_s"].attrs["units"] == "s"
    rows = summary_statistics(ds)["metrics"]
    assert rows and all(r["units"] for r in rows), [r for r in rows if not r["units"]]
    # a store written before the units were stored: the same units, from the names
    bare = ds.copy()
    for name, var in bare.data_vars.items():
        if var.attrs.get("kind") == "metric":
            var.attrs.pop("units")
    assert [r["units"] for r in summary_statistics(bare)["metrics"]] == \
        [r["units"] for r in rows]


def test_the_cli_shows_display_units_and_json_the_stored_ones(report_batch_dir):
    """``seahelm inspect`` of a grid × Monte-Carlo result: --json gives each column's stored
    unit; the tables label the same columns with their display units, values in them."""
    from seahelm.cli.main import app

    path = report_batch_dir / "result.nc"
    got = json.loads(CliRunner().invoke(app, ["inspect", str(path), "--json"]).stdout)
    units = got["units"]
    assert units["final_heading"] == "rad" and units["settling_time_s"] == "s"
    assert units["vessel.params.gain"] == "1/s" and units["kp"] == "rad/rad"
    human = CliRunner().invoke(app, ["inspect", str(path)]).stdout
    stats = got["statistics"][0]["metrics"]
    assert "final heading [deg]" in human  # (a table's row, or its key/value line)
    assert f"{math.degrees(stats['final_heading']['mean']):.4g}" in human
    assert f"{stats['final_heading']['mean']:.4g}" not in human  # (not in radians)
    assert "vessel.params.gain [1/s]" in human and "final heading rad" not in human
    assert "heading_deg" not in human  # (the heading once, in degrees)
