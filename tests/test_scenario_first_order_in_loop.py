"""Scenario: ``[environment.waves] rao_file`` and ``autopilot_sees_first_order = true`` (the
first-order motions in the loop, the autopilot fed ψ + ψ₁): refused without a yaw RAO, naming
the key; in the loop, run i's motions are the post-pass's of run i's documented seed on its
recorded track; a ``rao_file`` alone replaces the closed form in the post-pass."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from seahelm.environment import rao_io
from seahelm.environment.first_order import first_order_motions
from seahelm.environment.spectra import spectrum_from_wave_height
from seahelm.scenario import ScenarioError, parse_scenario, run_scenario

EXAMPLE = Path(__file__).parents[1] / "examples" / "container_waves_motions.toml"
BARGE = rao_io.box_barge_database()
pytestmark = pytest.mark.filterwarnings("ignore:Lvov:seahelm.errors.ValidityRangeWarning")


def text(*extra: str, **replace: str) -> str:
    out = EXAMPLE.read_text().replace("t_final = 600.0", "t_final = 60.0").replace(
        "runs = 4", "runs = 2")
    out = out.replace("components = 64", "components = 64\n" + "\n".join(extra))
    for old, new in replace.items():
        out = out.replace(old, new)
    return out


def _post_pass(result, i, dofs):
    rec = {"time": result.time, **{n: result[n][i] for n in ("surge_speed", "heading", "north",
                                                              "east")}}
    return first_order_motions(rec, spectrum_from_wave_height("rakhmanin-firsov-2", 3.0),
                               rao_io.read_rao(BARGE), wave_direction=math.radians(60.0),
                               seed=[np.random.SeedSequence([34, 1], spawn_key=(i, 1))],
                               dofs=dofs)


def test_the_closed_form_has_no_yaw_the_key_is_named():
    with pytest.raises(ScenarioError, match=r"\[environment\.waves\.autopilot_sees_first_order\]"
                       r".*closed-form RAOs.*have none.*rao_file"):
        run_scenario(parse_scenario(text("autopilot_sees_first_order = true"), source="bad"))
    with pytest.raises(ScenarioError, match=r"\[environment\.waves\.rao_file\]"):
        run_scenario(parse_scenario(text('rao_file = "no-such-file.nc"'), source="bad"))


@pytest.mark.parametrize("values, loop", [("[2.5]", True), ("[2.5]", False), ("[0]", True),
                                          ("[1000000]", True), ("[0, 32]", True)])
def test_a_grids_components_are_checked_per_run_naming_the_key(values, loop):
    """A grid's ``components`` is a float: 2.5 was taken as 2 without a word; 0 or 10^6 in
    the loop failed with a bare '`n_components` must be...' naming neither the scenario nor the
    key ([0, 32] as 'must be the same in every run'); after the run, only after the runs."""
    extra = (f'rao_file = "{BARGE}"', "autopilot_sees_first_order = true") if loop else ()
    body = text(*extra).replace("[batch.monte_carlo]", "[batch.grid]\n"
                                f'"environment.waves.components" = {values}\n\n'
                                "[batch.monte_carlo]")
    bad = values.strip("[]").split(",")[0]
    with pytest.raises(ScenarioError, match=r"bad: \[environment\.waves\.components\] must be "
                       rf"an integer in \[1, 100000\] \[-\], got {bad}"):
        run_scenario(parse_scenario(body, source="bad"))


def test_in_the_loop_the_autopilot_sees_the_total_heading():
    res = run_scenario(parse_scenario(text(f'rao_file = "{BARGE}"',
                                           "autopilot_sees_first_order = true"), source="in"))
    assert np.all(res.status == 0)
    assert res.metadata["controller_heading"].startswith("heading_total")
    assert "first_order_motions" not in res.metadata  # no post-pass
    dofs = ("heave", "roll", "pitch", "yaw")
    for i in range(2):
        post = _post_pass(res, i, dofs)
        for dof, name in zip(dofs, ("heave", "roll_wave", "pitch", "yaw_wave")):
            np.testing.assert_allclose(res[name][i], post[dof][0], rtol=0, atol=1e-9)
        np.testing.assert_allclose(res["heading_total"][i], res["heading"][i] + post["yaw"][0],
                                   rtol=0, atol=1e-9)
    np.testing.assert_array_equal(res["roll"], res["roll_angle"] + res["roll_wave"])


def test_a_rao_file_alone_replaces_the_closed_form_after_the_run():
    res = run_scenario(parse_scenario(text(f'rao_file = "{BARGE}"'), source="file"))
    assert "controller_heading" not in res.metadata
    post = _post_pass(res, 1, ("heave", "roll", "pitch"))
    np.testing.assert_array_equal(res["heave"][1], post["heave"][0])
    np.testing.assert_array_equal(res["roll_wave"][1], post["roll"][0])


def test_a_sweep_in_chunks_keeps_each_runs_sea_in_the_loop(tmp_path):
    """A sweep's chunk of an in-loop scenario takes its runs' own components (chunk k's run i
    would otherwise take run i's sea, or the chunk fail): chunks of 2 equal the whole batch."""
    from seahelm.sweep import open_sweep, run_sweep

    body = text(f'rao_file = "{BARGE}"', "autopilot_sees_first_order = true").replace(
        "runs = 2", "runs = 3")
    whole = run_scenario(parse_scenario(body, source="in"))
    path = tmp_path / "in.toml"
    path.write_text(body)
    run_sweep(path, tmp_path / "s.zarr", text=body, chunk_size=2)
    with open_sweep(tmp_path / "s.zarr") as ds:
        for name in ("heave", "roll_wave", "yaw_wave", "heading_total", "rudder_angle"):
            np.testing.assert_array_equal(ds[name].values, whole[name])


def test_run_metrics_of_motions_in_the_loop():
    """The in-loop motions are the loop's outputs, not ``extra``: wave_motion_metrics found
    none (no rms_heave_m ... in seahelm run's summary nor in a sweep's store)."""
    from seahelm.analysis.seakeeping.time_domain import wave_motion_metrics

    res = run_scenario(parse_scenario(text(f'rao_file = "{BARGE}"',
                                           "autopilot_sees_first_order = true"), source="in"))
    m = wave_motion_metrics(res)
    for name, metric, factor in (("heave", "rms_heave_m", 1.0),
                                 ("pitch", "rms_pitch_deg", 180 / math.pi),
                                 ("roll_wave", "rms_roll_wave_deg", 180 / math.pi),
                                 ("roll", "rms_roll_deg", 180 / math.pi)):
        np.testing.assert_allclose(m[metric], factor * np.sqrt(np.mean(res[name] ** 2, axis=1)),
                                   rtol=1e-12)
        assert np.all(m[metric] > 0)


@pytest.mark.parametrize("in_loop, relative", [(True, False), (False, False), (False, True)])
def test_the_polar_of_a_sweep_with_a_rao_file_takes_its_frequency_domain_from_the_file(
        tmp_path, in_loop, relative):
    """A sweep whose motions come from ``rao_file`` (after the run or in the loop): the
    frequency-domain cells are those of the file's RAO (they were the closed form's after the
    run, and in the loop the sweep had 'no first-order motions'); a relative ``rao_file`` is
    the scenario file's, wherever the store is (it was looked for beside the store)."""
    import shutil

    from seahelm.analysis.seakeeping.frequency_domain import response_moments
    from seahelm.sweep import run_sweep
    from seahelm.sweep.seakeeping import sweep_seakeeping

    if relative:
        shutil.copy(BARGE, tmp_path / "barge.nc")
    extra = ('rao_file = "barge.nc"' if relative else f'rao_file = "{BARGE}"',) + (
        ("autopilot_sees_first_order = true",) if in_loop else ())
    body = text(*extra).replace("[batch.monte_carlo]", "[batch.grid]\n"
                                '"environment.waves.direction_deg" = [0, 90]\n\n'
                                "[batch.monte_carlo]")
    path = tmp_path / "s.toml"
    path.write_text(body)
    run_sweep(path, tmp_path / "out" / "s.zarr", series=False)
    p = sweep_seakeeping(tmp_path / "out" / "s.zarr")
    rao = rao_io.read_rao(BARGE)
    sea = spectrum_from_wave_height("rakhmanin-firsov-2", 3.0)
    band = np.linspace(rao.frequency[0], rao.frequency[-1], 2000)
    for j in range(2):
        m = response_moments(rao, sea, [float(p.heading[0, j])], dofs=["heave", "roll"],
                             frequency=band)
        for dof in ("heave", "roll"):
            assert p.frequency_domain[p.dofs.index(dof), 0, j] == pytest.approx(
                m.moment(dof, 0)[0, 0], rel=1e-12)
