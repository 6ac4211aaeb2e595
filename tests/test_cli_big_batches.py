"""A big manoeuvre batch (a Monte-Carlo of ships) is summarised, not dumped (issue 32 item 2,
issue 36 items 2-3): statistics per side instead of a column per run, the runs' notes counted
once, figures that draw representatives (a handful of artists) instead of every run."""

from __future__ import annotations

import json
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from typer.testing import CliRunner  # noqa: E402

from seahelm.cli._batch_summary import aggregate_notes, note_lines  # noqa: E402
from seahelm.cli.main import app  # noqa: E402
from seahelm.plotting.maneuver_runs import (  # noqa: E402
    MAX_FAILED_DRAWN,
    REPRESENTATIVE_QUANTILES,
    drawn_groups,
)

RUNS = 24

SCENARIO = f"""
title = "big batch"
[vessel]
catalog = "kvlcc2-l7"
[maneuver]
kind = "{{kind}}"
rudder_deg = {{rudder}}
sides = "both"
t_final = {{t_final}}
[batch.monte_carlo]
runs = {RUNS}
seed = 5
[batch.monte_carlo.draws]
"vessel.params.N_r" = {{{{ distribution = "normal", mean = -0.049, std = 0.0049 }}}}
"vessel.params.Y_v" = {{{{ distribution = "normal", mean = -0.315, std = 0.0315 }}}}
"""


def _scenario(tmp_path, kind="turning", rudder=35, t_final=60.0):
    path = tmp_path / f"{kind}.toml"
    path.write_text(SCENARIO.format(kind=kind, rudder=rudder, t_final=t_final))
    return path


@pytest.fixture(scope="module")
def turning_json(tmp_path_factory):
    path = _scenario(tmp_path_factory.mktemp("big"))
    res = CliRunner().invoke(app, ["run", str(path), "--json"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def test_the_json_keeps_every_run_and_adds_statistics_recomputable_from_them(turning_json):
    runs = turning_json["runs"]
    assert len(runs) == 2 * RUNS
    stats = turning_json["statistics"]
    assert [s["point"]["side"] for s in stats] == ["starboard", "port"]
    for entry in stats:
        mine = [r for r in runs if r["side"] == entry["point"]["side"]]
        assert entry["n_runs"] == len(mine) == RUNS
        values = np.array([r["tactical_diameter_m"] for r in mine])
        s = entry["metrics"]["tactical_diameter_m"]
        assert s["n"] == RUNS
        assert s["mean"] == pytest.approx(values.mean(), rel=1e-12)
        assert s["std"] == pytest.approx(values.std(ddof=1), rel=1e-12)
        assert s["q50"] == pytest.approx(np.median(values), rel=1e-12)
        assert (s["min"], s["max"]) == (values.min(), values.max())
        # the drawn values: each run's ship's draw, so each side's statistics are the same
        assert entry["drawn"]["vessel.params.N_r"]["n"] == RUNS
    assert stats[0]["drawn"] == stats[1]["drawn"]
    # every run knows its ship; the rps of a sample is its own (not the first run's)
    assert sorted({r["ship"] for r in runs}) == list(range(RUNS))
    assert "propeller_rps" not in turning_json or len({r["propeller_rps"] for r in runs}) == 1
    assert "(24 ships)" in turning_json["ship"]


def test_the_terminal_shows_statistics_and_each_note_once(tmp_path):
    path = _scenario(tmp_path)
    res = CliRunner().invoke(app, ["run", str(path)], env={"COLUMNS": "80"})
    assert res.exit_code == 0, res.output
    out = res.stdout
    assert "statistics at side=starboard" in out and "side=port" in out
    assert "tactical diameter [m]" in out
    assert "vessel.params.N_r" in out
    # no column per run: a run's label appears at most in the notes
    assert out.count("kvlcc2-l7 #") <= 4, out
    assert len(out.splitlines()) < 120
    assert f"of {2 * RUNS} runs" in out  # the note said once with its count


def test_notes_that_differ_in_numbers_only_are_one_kind():
    messages = ["ok", "180 deg not reached within t_final = 30 s (final 170.2 deg)",
                "180 deg not reached within t_final = 30 s (final 165.9 deg)", "ok",
                "diverged: state out of bounds at t = 12.5 s"]
    labels = [f"run {i}" for i in range(len(messages))]
    notes = aggregate_notes(labels, messages)
    assert [(n["count"], n["runs"], n["same"]) for n in notes] == [
        (2, ["run 1", "run 2"], False), (1, ["run 4"], True)]
    lines = note_lines(notes, len(messages))
    assert lines[0].startswith("2 of 5 runs (as in run 1): 180 deg not reached")
    assert lines[1] == "run 4: diverged: state out of bounds at t = 12.5 s"
    same = aggregate_notes(labels[:2], ["not steady", "not steady"], skip=())
    assert note_lines(same, 2) == ["2 of 2 runs: not steady"]


@pytest.fixture(scope="module")
def turning_batch():
    from seahelm.scenario import parse_scenario

    job = parse_scenario(SCENARIO.format(kind="turning", rudder=35, t_final=60.0))
    return job.run()


def test_a_big_batch_is_drawn_by_representatives_at_the_quantiles(turning_batch):
    groups = drawn_groups(turning_batch, "tactical_diameter")
    assert [g.size for g in groups] == [RUNS, RUNS]
    td = turning_batch.metrics["tactical_diameter"]
    for group, side in zip(groups, (1, -1)):
        values = np.abs(td.sel(side=side).values)
        want = set(np.quantile(values, REPRESENTATIVE_QUANTILES, method="nearest"))
        got = {abs(float(r.metrics["tactical_diameter"])) for r in group.runs
               if r.role != "failed"}
        assert got == want
        median = [r for r in group.runs if r.role == "median"]
        assert len(median) == 1
        assert abs(float(median[0].metrics["tactical_diameter"])) == float(
            np.quantile(values, 0.5, method="nearest"))
        assert len(group.runs) <= len(REPRESENTATIVE_QUANTILES) + MAX_FAILED_DRAWN


def test_a_small_batch_is_drawn_run_by_run(turning_batch):
    small = turning_batch.metrics.isel(ship=slice(0, 3))
    result = type(turning_batch)(turning_batch.maneuver, small, turning_batch.ships[:3],
                                 None, lambda: turning_batch.runs.isel(ship=slice(0, 3)))
    groups = drawn_groups(result, "tactical_diameter")
    assert len(groups) == 6 and all(len(g.runs) == 1 and g.runs[0].role == "run"
                                    for g in groups)


def test_the_turning_figure_of_a_big_batch_has_few_artists_and_says_what_it_shows(
        turning_batch):
    from seahelm.plotting.maneuvers import plot_turning

    ax = plot_turning(turning_batch)
    fig = ax.figure
    fig.canvas.draw()
    assert len(ax.lines) <= 2 * (len(REPRESENTATIVE_QUANTILES) + MAX_FAILED_DRAWN) + 12
    assert not [t.get_text() for t in ax.texts if t.get_text()]  # (values in the legend)
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert sum("tactical diameter" in text for text in legend) == 2  # the medians only
    assert fig.get_supxlabel().startswith(f"{2 * RUNS} runs; drawn per group")
    assert "(24 ships)" in ax.get_title()
    plt.close(fig)


def test_the_zigzag_figure_of_a_big_batch_has_a_panel_per_side():
    from seahelm.plotting.maneuvers import plot_zigzag
    from seahelm.scenario import parse_scenario

    result = parse_scenario(SCENARIO.format(kind="zigzag", rudder=10, t_final=40.0)).run()
    fig = plot_zigzag(result)
    panels = [ax for ax in fig.axes if ax.get_visible()]
    assert len(panels) == 2
    assert all(f"of {RUNS} runs" in ax.get_title() for ax in panels)
    overshoot_marks = sum(t.get_text().startswith("o1") for ax in panels for t in ax.texts)
    assert overshoot_marks <= 2  # the medians' only
    plt.close(fig)
    assert math.isfinite(float(result.metrics["overshoot"].isel(n=0).mean()))
