"""Per-run seakeeping statistics of records with first-order wave motions."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from seahelm.analysis.maneuvers import summarize, summary_units
from seahelm.analysis.seakeeping.time_domain import wave_motion_metrics
from seahelm.environment.loads import LvovWaveParams


class _Record:
    """The parts of a SimResult the statistics read."""

    def __init__(self, series, extra, wave_from):
        self.series, self.extra = series, extra
        self.n_runs = len(next(iter(series.values())))
        names = [i.name for i in LvovWaveParams.info()]
        arr = np.zeros((self.n_runs, len(names)))
        arr[:, names.index("wave_direction")] = wave_from
        self.params = {"environment": (LvovWaveParams, arr)}

    def __getitem__(self, name):
        return self.series[name]


def test_rms_speed_and_heading_against_closed_forms():
    t = np.linspace(0.0, 600.0, 6001)  # 60 whole periods of 10 s
    w = 2 * math.pi / 10.0
    heave = np.stack([0.8 * np.sin(w * t), 0.3 * np.cos(w * t)])
    roll = np.radians(2.0) * np.sin(w * t + 0.4)[None].repeat(2, 0)
    heading = np.radians([[30.0] * t.size, [350.0 if k % 2 else 10.0 for k in range(t.size)]])
    rec = _Record({"surge_speed": np.stack([np.full(t.size, 5.0), 6.0 + 0.5 * np.sin(w * t)]),
                   "heading": heading},
                  {"heave": (heave, "m", ""), "pitch": (0.5 * roll, "rad", ""),
                   "roll_wave": (roll, "rad", ""), "roll": (roll + 0.01, "rad", "")},
                  np.radians([60.0, 0.0]))
    m = wave_motion_metrics(rec)
    # a sine over whole periods: RMS = amplitude/sqrt(2) (the trapezoid's end sample aside)
    np.testing.assert_allclose(m["rms_heave_m"], [0.8 / math.sqrt(2), 0.3 / math.sqrt(2)],
                               rtol=2e-4)
    np.testing.assert_allclose(m["rms_roll_wave_deg"], 2.0 / math.sqrt(2), rtol=2e-4)
    np.testing.assert_allclose(m["rms_pitch_deg"], 1.0 / math.sqrt(2), rtol=2e-4)
    np.testing.assert_allclose(m["rms_roll_deg"] ** 2, 2.0 + math.degrees(0.01) ** 2, rtol=1e-3)
    np.testing.assert_allclose(m["mean_surge_speed_mps"], [5.0, 6.0], atol=1e-4)
    # waves from 60 deg, ship heading 30: travelling to 240, 210 deg off the bow; a heading
    # alternating 350/10 deg has the circular mean 0 (its plain mean is 180): head seas (3,001
    # samples of 10 deg and 3,000 of 350: atan(tan(10 deg)/6,001) off)
    off = math.degrees(math.atan(math.tan(math.radians(10.0)) / 6001))
    np.testing.assert_allclose(m["mean_wave_heading_deg"], [210.0, 180.0 - off], rtol=0,
                               atol=1e-9)


def test_a_diverged_run_has_nan_and_a_record_without_motions_nothing():
    t = np.linspace(0.0, 10.0, 11)
    heave = np.stack([np.sin(t), np.full(t.size, np.nan)])
    rec = _Record({"surge_speed": np.ones((2, t.size)), "heading": np.zeros((2, t.size))},
                  {"heave": (heave, "m", "")}, 0.0)
    m = wave_motion_metrics(rec)
    assert set(m) == {"rms_heave_m", "mean_surge_speed_mps", "mean_wave_heading_deg"}
    assert all(np.isfinite(v[0]) and np.isnan(v[1]) for v in m.values())
    rec.extra = {}
    assert wave_motion_metrics(rec) == {}


@pytest.mark.filterwarnings("ignore:Lvov:seahelm.errors.ValidityRangeWarning")
def test_a_scenarios_summary_has_them_with_units():
    from seahelm.scenario import parse_scenario, run_scenario

    text = (Path(__file__).parents[1] / "examples" / "container_waves_motions.toml").read_text()
    text = text.replace("t_final = 600.0", "t_final = 60.0").replace("runs = 4", "runs = 2")
    result = run_scenario(parse_scenario(text, source="example"))
    rows, units = summarize(result), summary_units(result)
    for i, row in enumerate(rows):
        assert row["rms_heave_m"] == pytest.approx(
            float(np.sqrt(np.mean(result["heave"][i] ** 2))), rel=1e-12)
        assert row["rms_roll_deg"] == pytest.approx(
            math.degrees(float(np.sqrt(np.mean(result["roll"][i] ** 2)))), rel=1e-12)
    assert (units["rms_heave_m"], units["rms_pitch_deg"], units["mean_surge_speed_mps"],
            units["mean_wave_heading_deg"]) == ("m", "deg", "m/s", "deg")
