"""Sea-state tables (Sushchenko & Lutsko (2010), Tables 1-2) and D_r = 0.143 (h3%/2)²."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.environment import sea_state as ss
from seahelm.errors import ParameterError, ValidityRangeWarning

@pytest.mark.parametrize("h", [0.5, 1.0, 3.0, 10.0, 20.0])
def test_wave_variance(h):
    assert ss.wave_variance(h) == pytest.approx(0.143 * h**2 / 4, rel=1e-15)


def test_rayleigh_coefficient():
    assert ss.RAYLEIGH_VARIANCE_COEFFICIENT == pytest.approx(4 / (8 * math.log(1 / 0.03)), rel=3e-3)


@pytest.mark.parametrize("bad,match", [(0.0, "> 0"), (-1.0, "> 0"), (float("nan"), "finite"), (math.inf, "finite")])
def test_wave_variance_bad(bad, match):
    with pytest.raises(ParameterError, match=f"`h3` must be {match}"):
        ss.wave_variance(bad)


@pytest.mark.parametrize(
    "h,grade",
    [(0.1, 1), (0.25, 2), (0.5, 2), (0.75, 3), (1.0, 3), (1.9, 4), (2.0, 5), (4.0, 6), (7.0, 7), (10.0, 8), (11.0, 9), (30.0, 9)],
)
def test_table1_grade(h, grade):
    assert ss.sea_state_grade(h) == grade


def test_table1_ranges():
    assert ss.wave_height_range(3) == (0.75, 1.25)
    assert ss.wave_height_range("vi") == (3.5, 6.0)
    assert ss.wave_height_range("IX") == (11.0, math.inf)
    np.testing.assert_array_equal(ss.sea_state_grade([0.1, 5.0, 12.0]), [1, 6, 9])
    for bad in (0, 10, "X", 2.5, True):
        with pytest.raises(ParameterError, match="`grade`"):
            ss.wave_height_range(bad)


def test_corrected_table_has_the_corrected_cells():
    c = ss.table2("corrected")
    assert c["lambda_mean"][3] == 0.867  # printed 0.667
    assert c["mu_min"][0] == 0.188  # printed 0.138
    assert ss.table2(ss.CORRECTED_TABLE2)["lambda_mean"][3] == 0.867


def test_corrected_table_is_consistent():
    c = ss.table2("corrected")
    ratio = c["mu_mean"] / c["lambda_mean"]
    assert np.all((ratio > 0.2125) & (ratio < 0.2145))
    assert np.all(np.abs(c["mu_min"] / c["lambda_min"] - 0.150) < 0.003)
    for col in ss.TABLE2_COLUMNS[:-1]:  # every column ∝ h^(-1/2) within 2 %
        v = c[col] * np.sqrt(c["h3"])
        assert np.all(np.abs(v / np.median(v) - 1) < 0.025), col


def test_table_returns_copies_and_unknown_name():
    t = ss.table2()
    t["mu_mean"][0] = -5.0
    assert ss.table2()["mu_mean"][0] == 0.374
    with pytest.raises(ParameterError, match="version 'nope'; valid: 'corrected', 'printed'"):
        ss.table2("nope")
    # "printed" is the study's table, reached by name (tests/test_studies_sushchenko2010.py)
    assert ss.table2("printed")["lambda_mean"][3] == 0.667


def test_exact_rows():
    p = ss.sea_state_parameters(3.0)
    assert (p.decay_rate, p.resonance_frequency, p.grade) == (0.214, 1.003, 5)
    assert p.variance == pytest.approx(0.143 * 2.25)
    assert ss.sea_state_parameters(4.0).resonance_frequency == 0.867


@pytest.mark.parametrize(
    "h,level,mu,lam",
    [
        (1.5, "mean", (0.374 + 0.265) / 2, (1.745 + 1.239) / 2),
        (2.25, "max", 0.394 + 0.25 * (0.316 - 0.394), 1.573 + 0.25 * (1.266 - 1.573)),
        (3.5, "mean", (0.214 + 0.185) / 2, (1.003 + 0.867) / 2),
        (1.2, "min", 0.188 + 0.2 * (0.136 - 0.188), 1.25 + 0.2 * (0.905 - 1.25)),
    ],
)
def test_linear_interpolation(h, level, mu, lam):
    p = ss.sea_state_parameters(h, level=level)
    assert p.decay_rate == pytest.approx(mu, rel=1e-12)
    assert p.resonance_frequency == pytest.approx(lam, rel=1e-12)
    assert p.level == level and not p.extrapolated


def test_a_table_version_object_is_used_as_given():
    rows = np.array(ss.TABLE2["corrected"])
    rows[:, 5] *= 2.0  # λ_mean doubled
    p = ss.sea_state_parameters(3.5, table=ss.Table2Version("doubled", rows))
    assert p.resonance_frequency == pytest.approx(1.003 + 0.867)
    assert p.table == "doubled"
    with pytest.raises(ParameterError, match="increasing"):
        ss.Table2Version("bad", rows[::-1])


@pytest.mark.parametrize("h", [0.5, 0.999, 10.001, 12.0])
def test_outside_table_raises(h):
    with pytest.raises(ParameterError, match=r"`h3` must be in \[1, 10\] \[m\].*Table 2"):
        ss.sea_state_parameters(h)


def test_extrapolation_warns_and_follows_sqrt_law():
    with pytest.warns(ValidityRangeWarning, match="outside Table 2"):
        p = ss.sea_state_parameters(12.0, extrapolate=True)
    assert p.extrapolated
    assert p.decay_rate == pytest.approx(0.119 * math.sqrt(10 / 12))
    assert p.resonance_frequency == pytest.approx(0.555 * math.sqrt(10 / 12))
    with pytest.warns(ValidityRangeWarning):
        q = ss.sea_state_parameters(0.5, extrapolate=True, level="min")
    assert q.decay_rate == pytest.approx(0.188 * math.sqrt(2))


@pytest.mark.parametrize("bad,match", [(0.0, "> 0"), (-2.0, "> 0"), (float("nan"), "finite")])
def test_sea_state_parameters_bad_h3(bad, match):
    with pytest.raises(ParameterError, match=f"`h3` must be {match}"):
        ss.sea_state_parameters(bad)


def test_unknown_level():
    with pytest.raises(ParameterError, match="unknown level 'avg'.*'max', 'mean', 'min'"):
        ss.sea_state_parameters(3.0, level="avg")


@pytest.mark.parametrize("name", ["rakhmanin-firsov-2", "bretschneider", "jonswap"])
def test_spectra_from_wave_height_pass_extrapolate_on(name):
    """The error's hint (pass extrapolate=True) holds for the spectra that read Table 2."""
    from seahelm.environment.spectra import spectrum_from_wave_height

    with pytest.raises(ParameterError, match="pass extrapolate=True"):
        spectrum_from_wave_height(name, 12.0)
    with pytest.warns(ValidityRangeWarning, match="outside Table 2"):
        spec = spectrum_from_wave_height(name, 12.0, extrapolate=True)
    with pytest.warns(ValidityRangeWarning):
        assert spec == spectrum_from_wave_height(name, 12.0, extrapolate=True)


def test_sea_signal_refuses_heights_outside_table2_without_a_python_hint():
    from seahelm.simulation.signals import Sea

    with pytest.raises(ParameterError, match=r"`h3` must be in \[1, 10\] \[m\].*got 12") as err:
        Sea(h3=12.0)
    assert "extrapolate" not in str(err.value)

