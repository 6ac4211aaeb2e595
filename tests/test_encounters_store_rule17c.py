"""A study store begun before the Rule 17(c) verdict (``altered_to_port``) existed resumes:
the chunks still to run are written without the variables the store does not hold, and the
study reads as a file of that time (the verdict absent, every other number that of the run)."""

from __future__ import annotations

import numpy as np
import pytest

import seahelm.encounters.chunked as chunked
from seahelm.encounters import Encounter
from seahelm.encounters.monte_carlo import monte_carlo_vessels
from seahelm.encounters.result import EncounterResult
from seahelm.sweep.encounter_store import open_study, run_study

NEW = ["verdict_altered_to_port", "verdict_port_alteration"]


def _encounter():
    vessels, _ = monte_carlo_vessels(4, own_ship="kvlcc2-full", target_ship="kvlcc2-full",
                                     seed=3, detection_range=(3000.0, 3500.0),
                                     tcpa=(100.0, 300.0), overtaking=0.0)
    return Encounter(vessels, t_final=240.0, avoidance="velocity-obstacles", record_every=5)


def test_a_store_without_the_verdict_resumes(tmp_path, monkeypatch):
    store, whole = tmp_path / "s.zarr", _encounter().run()
    real_xr, real_run, ran = EncounterResult.to_xarray, chunked._run_chunk, []

    def old_xarray(self):  # (the files of the code before the verdict)
        return real_xr(self).drop_vars(NEW)

    def interrupted(vessels, settings):
        if ran:
            raise KeyboardInterrupt
        ran.append(1)
        return real_run(vessels, settings)

    monkeypatch.setattr(EncounterResult, "to_xarray", old_xarray)
    monkeypatch.setattr(chunked, "_run_chunk", interrupted)
    with pytest.raises(KeyboardInterrupt):
        run_study(_encounter(), store, "vo", chunk_size=2)
    monkeypatch.setattr(EncounterResult, "to_xarray", real_xr)
    monkeypatch.setattr(chunked, "_run_chunk", real_run)
    res = run_study(_encounter(), store, "vo", chunk_size=2)  # (the second chunk: new code)
    assert "altered_to_port" not in res.verdicts
    for name, arr in res.verdicts.items():
        assert np.array_equal(arr, whole.verdicts[name], equal_nan=True), name
    assert np.array_equal(res.min_range, whole.min_range)
    rows = res.summary()
    assert all(r["own_altered_to_port"] is None for r in rows)
    assert "altered_to_port" not in open_study(store, "vo").verdicts
