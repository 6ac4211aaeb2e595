"""``[environment.waves] first_order_motions = true``: the wave motions in a scenario's result."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from seahelm.environment.first_order import first_order_motions
from seahelm.environment.rao import closed_form_rao
from seahelm.environment.spectra import spectrum_from_wave_height
from seahelm.errors import ValidityRangeWarning
from seahelm.scenario import ScenarioError, load_scenario, parse_scenario, run_scenario
from seahelm.ships import get_ship

EXAMPLE = Path(__file__).parents[1] / "examples" / "container_waves_motions.toml"
#: Lvov's mean wave loads warn for the container's C_b 0.56 (< 0.6), as the example says
pytestmark = pytest.mark.filterwarnings("ignore:Lvov:seahelm.errors.ValidityRangeWarning")


def short(text: str, **replace: str) -> str:
    text = text.replace("t_final = 600.0", "t_final = 60.0").replace("runs = 4", "runs = 2")
    for old, new in replace.items():
        text = text.replace(old, new)
    return text


@pytest.fixture(scope="module")
def result():
    return run_scenario(parse_scenario(short(EXAMPLE.read_text()), source="example"))


def test_the_result_has_heave_pitch_and_the_total_roll(result):
    ds = result.to_xarray()
    for name, unit in (("heave", "m"), ("pitch", "rad"), ("roll_wave", "rad"), ("roll", "rad")):
        assert ds[name].attrs["units"] == unit and ds[name].dims == ("sample", "time")
        assert np.all(np.isfinite(ds[name].values))
    np.testing.assert_array_equal(ds["roll"].values, ds["roll_angle"].values
                                  + ds["roll_wave"].values)
    assert 0.05 < float(ds["heave"].std()) < 1.0  # h3% 3 m: σ_ζ = 0.57 m; a 175 m ship heaves less
    assert "closed-form RAOs" in ds.attrs["first_order_motions"]


def test_run_i_draws_from_the_second_child_of_its_sea_stream(result):
    """As documented: SeedSequence([seed, batch seed], spawn_key=(i, 1)), the closed-form RAOs
    at the multiples of 0.25 m/s that bracket run i's own speeds (it spans more than 0.25
    m/s), Table 2's spectrum for h3% = 3 m."""
    ship = get_ship("son-nomoto-container")
    i = 1
    u = result["surge_speed"][i]
    assert u.max() - u.min() > 0.25
    nodes = np.arange(math.floor(u.min() / 0.25), math.ceil(u.max() / 0.25) + 1) * 0.25
    raos = [closed_form_rao(ship, s, metacentric_height=0.3) for s in nodes]
    rec = {"time": result.time, **{n: result[n][i] for n in ("surge_speed", "heading", "north",
                                                              "east")}}
    m = first_order_motions(rec, spectrum_from_wave_height("rakhmanin-firsov-2", 3.0), raos,
                            wave_direction=math.radians(60.0),
                            seed=[np.random.SeedSequence([34, 1], spawn_key=(i, 1))])
    np.testing.assert_array_equal(m["heave"][0], result["heave"][i])
    np.testing.assert_array_equal(m["roll"][0], result["roll_wave"][i])


@pytest.mark.parametrize("change, key, match", [
    ({"irregular = true": "irregular = false", "seed = 34\n": ""},
     "environment.waves", "set `irregular = true`"),
    ({"first_order_motions = true": "first_order_motions = false"},
     "environment.waves", "`components` belongs to the first-order motions"),
    ({"components = 64": "components = 100000000000"},
     "environment.waves.components", "must be <= 100000, got 100000000000"),
    ({"components = 64": 'components = 64\nspreading = "cos-2s"\nspreading_parameter = 1e300'},
     "environment.waves.spreading_parameter", r"must be in \(0, 1000\] \[-\], got 1e\+300"),
    ({'catalog = "son-nomoto-container"': 'model = "container"'},
     "environment.waves.first_order_motions", "particulars"),
])
def test_bad_settings_name_the_key(change, key, match):
    text = short(EXAMPLE.read_text(), **change)
    with pytest.raises(ScenarioError, match=rf"\[{key}.*{match}"):
        run_scenario(parse_scenario(text, source="bad"))


def test_the_example_loads():
    with pytest.warns(ValidityRangeWarning, match="block coefficient"):
        batch = load_scenario(EXAMPLE)
    # the post-pass is the problem's, not settings in its metadata (issue 46)
    assert batch.post_pass is not None and len(batch.post_pass.specs) >= 1
    assert not any(k.startswith("first_order") for k in batch.metadata)


def test_without_the_key_the_particulars_gm_gives_the_roll(result):
    """The container's particulars hold GM 0.3 m, the key's value in the example: without the
    key the same roll (before, the scenario ignored the particulars' GM: heave and pitch only,
    where the closed form, the seakeeping command and the docs take it)."""
    assert get_ship("son-nomoto-container").particulars.metacentric_height == 0.3
    text = short(EXAMPLE.read_text(), **{"metacentric_height = 0.3": ""})
    assert "\nmetacentric_height" not in text
    other = run_scenario(parse_scenario(text, source="no key"))
    np.testing.assert_array_equal(other["roll_wave"], result["roll_wave"])
    np.testing.assert_array_equal(other["heave"], result["heave"])


def test_a_sweep_in_chunks_has_the_motions_of_the_whole_batch(tmp_path):
    """A sweep's chunk is a slice of the runs: its first-order settings are sliced with it and
    its runs seeded by their index in the whole batch (a chunk of one run failed with an
    IndexError, and chunk k's run i took run i's sea)."""
    from seahelm.sweep import open_sweep, run_sweep

    text = short(EXAMPLE.read_text(), **{"runs = 2": "runs = 3"})
    whole = run_scenario(parse_scenario(text, source="example"))
    path = tmp_path / "example.toml"
    path.write_text(text)
    run_sweep(path, tmp_path / "s.zarr", text=text, chunk_size=2)
    with open_sweep(tmp_path / "s.zarr") as ds:
        for name in ("heave", "pitch", "roll_wave", "roll"):
            np.testing.assert_array_equal(ds[name].values, whole[name])


@pytest.mark.parametrize("ranges, groups", [
    # a constant speed: the RAO at that speed; same speeds together
    ([(7.7175, 7.7175), (5.0, 5.0), (7.7175, 7.7175)], [((5.0,), [1]), ((7.7175,), [0, 2])]),
    ([(5.0, 5.2)], [((5.1,), [0])]),                                  # spans < 0.25 m/s
    # the multiples of 0.25 m/s bracketing the speeds; two grid speeds: a group each
    ([(5.0, 5.3), (7.1, 7.4), (5.1, 5.6)], [((5.0, 5.25, 5.5, 5.75), [0, 2]),
                                            ((7.0, 7.25, 7.5), [1])]),
    ([(4.0, 8.0), (7.1, 7.4)], [((4.0, 4.25, 4.5, 4.75, 5.0, 5.25, 5.5, 5.75, 6.0, 6.25, 6.5,
                                  6.75, 7.0, 7.25, 7.5, 7.75, 8.0), [0, 1])]),
])
def test_a_runs_raos_are_at_its_own_speeds(ranges, groups):
    from seahelm.scenario.first_order import SPEED_STEP, _speed_groups

    assert SPEED_STEP == 0.25
    speed = np.array([np.linspace(lo, hi, 5) for lo, hi in ranges])
    got = _speed_groups(speed, list(range(len(ranges))))
    assert [m for _, m in got] == [m for _, m in groups]
    for (s, _), (expected, _) in zip(got, groups):
        np.testing.assert_allclose(s, expected, rtol=1e-15)
    assert _speed_groups(speed, []) == []
