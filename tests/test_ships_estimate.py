"""A ship from its main particulars: Design, estimate_ship, estimate_nomoto, `seahelm ship
estimate` (issue 29)."""

from __future__ import annotations

import json
import math
import warnings

import pytest
from typer.testing import CliRunner

from seahelm.cli.main import app
from seahelm.errors import ParameterError, ValidityRangeWarning
from seahelm.ships import read_ship
from seahelm.ships.estimate import Design, estimate_coefficients, estimate_nomoto, estimate_ship
from seahelm.vessels.mmg import MMGParams

CARGO = dict(name="cargo120", length=120.0, beam=18.0, draft=7.0, block_coefficient=0.70,
             speed=6.5)


def run(*args: str):
    return CliRunner().invoke(app, list(args), terminal_width=200)


@pytest.fixture(scope="module")
def cargo():
    return estimate_ship(Design(**CARGO))


def test_every_mmg_parameter_is_estimated_and_sourced(cargo):
    fields = set(MMGParams.field_names()) - {"min_froude_number"}
    coefficients = estimate_coefficients(Design(**CARGO))
    assert fields <= set(coefficients)
    sources = dict(cargo.coefficient_sources)
    for name in ("Y_v", "N_r", "X_vvvv", "m_y", "R_0", "k_0", "w_P0", "t_P", "f_alpha", "a_H",
                 "rudder_area", "propeller_diameter"):
        assert sources[name] and sources[name] != "given", name
    assert "Kijima" in sources["Y_v"] and "Holtrop" in sources["R_0"]
    assert "Wageningen" in sources["k_0"] and "Fujii" in sources["f_alpha"]
    assert cargo.params.propeller_diameter == pytest.approx(0.65 * 7.0)
    assert cargo.params.displacement == pytest.approx(0.7 * 120 * 18 * 7)


def test_estimated_ship_file_round_trip(cargo, tmp_path):
    from seahelm.ships import write_ship

    path = write_ship(cargo, tmp_path / "cargo.toml")
    assert read_ship(path) == cargo
    assert "Kijima" in path.read_text()


def test_given_values_are_kept():
    ship = estimate_ship(Design(**CARGO, propeller_diameter=4.0, rudder_area=15.0,
                                rudder_span=5.0, x_G=1.5, displacement=10_000.0))
    p = ship.params
    assert (p.propeller_diameter, p.rudder_area, p.rudder_span, p.x_G, p.displacement) == (
        4.0, 15.0, 5.0, 1.5, 10_000.0)
    assert ship.source_of("rudder_area") == ship.provenance  # given: no formula of its own


def test_fore_and_aft_draughts_give_the_trim():
    design = Design(**{**CARGO, "draft": None}, draft_fore=6.5, draft_aft=7.5)
    assert design.mean_draft == 7.0 and design.trim == 1.0
    trimmed = estimate_ship(design).params
    even = estimate_ship(Design(**CARGO)).params
    assert trimmed.Y_v == pytest.approx(even.Y_v * (1 + 0.67 / 7.0))


def test_shallow_water_estimate(cargo):
    shallow = estimate_ship(Design(**CARGO, water_depth=10.0))
    assert shallow.water_depth == 10.0
    assert shallow.deep_water_params == cargo.params
    assert shallow == cargo.at_depth(10.0)


@pytest.mark.parametrize("change, field, match", [
    ({"beam": 130.0}, "beam", "less than the length"),
    ({"block_coefficient": 1.05}, "block_coefficient", r"\(0.3, 1\)"),
    ({"water_depth": 7.0}, "water_depth", "greater than the draft"),
    ({"propeller_diameter": -4.0}, "propeller_diameter", "> 0"),
    ({"propeller_diameter": 8.0}, "propeller_diameter", "less than the draft"),
    ({"speed": 0.0}, "speed", "> 0"),
    ({"blades": 9}, "blades", "2 to 7"),
    ({"draft": None}, "draft", "required"),
    ({"max_rudder": 2.0}, "max_rudder", "90"),
    ({"rudder_span": 3.0}, "rudder_span", "at least the propeller diameter"),
])
def test_unphysical_design_is_an_error_naming_the_field(change, field, match):
    with pytest.raises(ParameterError, match=match) as info:
        estimate_ship(Design(**{**CARGO, **change}))
    assert info.value.field == field


def test_outside_a_regression_warns_and_strict_raises():
    fast = dict(CARGO, speed=14.0, block_coefficient=0.55, beam=14.0)  # L/B 8.6, Fn 0.41
    with pytest.warns(ValidityRangeWarning) as record:
        estimate_ship(Design(**fast))
    text = " | ".join(str(w.message) for w in record)
    assert "L/B = 8.571 outside 4..8" in text and "Fn = 0.4081 outside 0.05..0.35" in text
    from seahelm.errors import strict_validity

    with strict_validity(), pytest.raises(ParameterError, match="outside"):
        estimate_ship(Design(**fast))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        estimate_ship(Design(**CARGO))  # a conventional cargo ship: inside every range


def test_nomoto_estimate_is_a_stable_steering_model():
    ship = estimate_nomoto(Design(**CARGO))
    p = ship.params
    assert ship.model.name == "nomoto2"
    assert p.gain > 0 and p.t1 > p.t2 > 0 and p.speed == 6.5
    first = estimate_nomoto(Design(**CARGO), order=1).params
    assert first.time_constant == pytest.approx(p.t1 + p.t2 - p.t3)
    assert ship.steering_gear is not None
    with pytest.raises(ParameterError, match="deep water"):
        estimate_nomoto(Design(**CARGO, water_depth=12.0))


def test_the_estimated_ship_turns_like_a_cargo_ship(cargo):
    """35° turning: tactical diameter within the usual 2–5 L of single-screw cargo ships."""
    from seahelm.analysis.maneuvers import turning_circle

    td = float(turning_circle(cargo, math.radians(35.0), sides=1).metrics["tactical_diameter"])
    assert 2.0 < td / 120.0 < 5.0


# -- CLI ------------------------------------------------------------------------------------
def test_cli_estimate_then_imo(tmp_path):
    out = tmp_path / "my.toml"
    res = run("ship", "estimate", "--length", "120", "--beam", "18", "--draft", "7", "--cb",
              "0.7", "--speed", "6.5", "--name", "cargo120", "-o", str(out))
    assert res.exit_code == 0, res.output
    assert read_ship(out) == estimate_ship(Design(**CARGO))
    imo = run("imo", str(out), "--json")
    assert imo.exit_code == 0, imo.output
    report = json.loads(imo.stdout)
    assert report["ship"] == "cargo120"
    shallow = run("imo", str(out), "--depth", "10", "--json")
    assert shallow.exit_code == 0, shallow.output
    assert any("water depth 10 m" in n for n in json.loads(shallow.stdout)["notes"])
    again = run("ship", "estimate", "--length", "120", "--beam", "18", "--draft", "7", "--cb",
                "0.7", "--speed", "6.5", "-o", str(out))
    assert again.exit_code == 2 and "--force" in again.output


def test_cli_estimate_from_a_particulars_file(tmp_path):
    f = tmp_path / "particulars.toml"
    f.write_text('name = "cargo120"\nlength = 120\nbeam = 18\ndraft = 7\nblock_coefficient = '
                 '0.7\nspeed = 6.5\nmax_rudder_deg = 35\n')
    res = run("ship", "estimate", str(f))
    assert res.exit_code == 0, res.output
    assert 'name = "cargo120"' in res.stdout and "[provenance.coefficients]" in res.stdout
    over = run("ship", "estimate", str(f), "--cb", "0.75", "--model", "nomoto2")
    assert over.exit_code == 0 and 'model = "nomoto2"' in over.stdout
    f.write_text("length = 120\nbeam = 18\ndraft = 7\nblock_coeficient = 0.7\nspeed = 6.5\n")
    bad = run("ship", "estimate", str(f))
    assert bad.exit_code == 2
    assert "block_coeficient" in bad.output and "did you mean 'block_coefficient'" in bad.output


@pytest.mark.parametrize("args, message", [
    (["--beam", "130"], "`--beam` must be less than the length 120.0 [m], got 130.0"),
    (["--cb", "1.2"], "`--cb` must be in (0.3, 1) [-], got 1.2"),
    (["--depth", "6"], "`--depth` must be greater than the draft 7.0 [m], got 6.0"),
    (["--propeller-diameter", "-1"], "`--propeller-diameter` must be > 0 [m], got -1.0"),
    (["--max-rudder", "120"], "`--max-rudder` must be in (0, 90] [deg], got 120.0"),
])
def test_cli_estimate_bad_input_is_one_line(args, message):
    base = ["ship", "estimate", "--length", "120", "--beam", "18", "--draft", "7", "--cb",
            "0.7", "--speed", "6.5"]
    res = run(*base, *args)
    assert res.exit_code == 2, res.output
    assert message in res.output, res.output
    assert len(res.output.strip().splitlines()) == 1


def test_cli_estimate_strict(tmp_path):
    args = ["ship", "estimate", "--length", "120", "--beam", "12", "--draft", "5", "--cb",
            "0.55", "--speed", "6.5"]
    warned = run(*args)
    assert warned.exit_code == 0
    assert "warning:" in warned.output and "L/B = 10 outside 4..8" in warned.output
    strict = run(*args, "--strict")
    assert strict.exit_code == 2 and "L/B = 10 outside 4..8" in strict.output


def test_very_full_ship_falls_back_to_taylor_wake_with_a_warning():
    """Holtrop's wake has no value for C_P above about 0.9 (a square root of a negative
    number): Taylor's is used, said in a warning (an error in strict mode)."""
    from seahelm.errors import strict_validity

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")  # (C_b 0.95 is outside several regressions' data)
        ship = estimate_ship(Design(**{**CARGO, "block_coefficient": 0.95}))
    assert any("Taylor's w_P0 = 0.5 C_b - 0.05 = 0.425" in str(w.message) for w in caught)
    assert ship.params.w_P0 == pytest.approx(0.425)
    assert "Taylor" in ship.source_of("w_P0")
    with strict_validity(), pytest.raises(ParameterError):
        estimate_ship(Design(**{**CARGO, "block_coefficient": 0.95}))


def test_absurd_speed_and_sample_counts_are_refused():
    res = run("ship", "estimate", "--length", "120", "--beam", "18", "--draft", "7", "--cb",
              "0.7", "--speed", "1e300")
    assert res.exit_code == 2 and "`--speed` gives a Froude number" in res.output
    res = run("imo", "kvlcc2-l7", "--monte-carlo", "2000000")
    assert res.exit_code == 2 and "--monte-carlo" in res.output


def test_estimate_keeps_the_gm_in_the_particulars(tmp_path):
    runner = CliRunner()
    out = tmp_path / "gm.toml"
    res = runner.invoke(app, ["ship", "estimate", "--length", "120", "--beam", "18", "--draft",
                              "7", "--cb", "0.7", "--speed", "7", "--gm", "1.4", "-o", str(out)])
    assert res.exit_code == 0, res.output
    assert read_ship(out).particulars.metacentric_height == 1.4
    bad = runner.invoke(app, ["ship", "estimate", "--length", "120", "--beam", "18", "--draft",
                              "7", "--cb", "0.7", "--speed", "7", "--gm", "0"])
    assert bad.exit_code == 2 and "`--gm` must be > 0 [m], got 0.0" in bad.output
