"""Sushchenko & Lutsko (2010): the printed variants are named objects next to the corrected ones.

Expected values are the paper's printed numbers and the errata of the seeds guide, typed in
here or written out as formulas, never values produced by the code under test.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate

from seahelm.constants import GRAVITY
from seahelm.environment import sea_state as ss
from seahelm.environment import spectra as sp
from seahelm.environment.rational_spectra import RakhmaninFirsov3
from seahelm.environment.shaping import shaping_filter
from seahelm.errors import ParameterError
from seahelm.studies import sushchenko2010 as su

D, MU, LAM = 0.32175, 0.214, 1.003  # h3% = 3 m, Table 2 means
A2 = MU**2 + LAM**2

# Table 2 as printed in the paper (h, μmax, μmean, μmin, λmax, λmean, λmin, μ/λ), typed in again.
PAPER_ROWS = {
    1: (0.56, 0.374, 0.138, 2.24, 1.745, 1.25, 0.215),
    2: (0.394, 0.265, 0.136, 1.573, 1.239, 0.905, 0.214),
    3: (0.316, 0.214, 0.111, 1.266, 1.003, 0.74, 0.213),
    4: (0.274, 0.185, 0.096, 1.094, 0.667, 0.64, 0.213),
    5: (0.246, 0.166, 0.086, 0.982, 0.777, 0.572, 0.213),
    10: (0.177, 0.119, 0.061, 0.706, 0.555, 0.404, 0.214),
}


# ---- Table 2 -----------------------------------------------------------------------------
def test_table_versions_are_named_objects():
    assert su.get_table2("printed") is su.PRINTED_TABLE2
    assert su.get_table2("corrected") is ss.CORRECTED_TABLE2
    assert su.get_table2(su.PRINTED_TABLE2) is su.PRINTED_TABLE2
    with pytest.raises(ParameterError, match="unknown Table 2 version 'nope'.*corrected, printed"):
        su.get_table2("nope")


@pytest.mark.parametrize("h,row", PAPER_ROWS.items())
def test_printed_table_reproduces_paper(h, row):
    t = ss.table2(su.PRINTED_TABLE2)
    i = int(np.flatnonzero(t["h3"] == h)[0])
    assert tuple(float(t[c][i]) for c in ss.TABLE2_COLUMNS) == row


def test_the_two_tables_differ_in_exactly_the_two_misprints():
    # errata: λ_mean(4 m) = 0.667 is a misprint for ≈ 0.867, μ_min(1 m) = 0.138 for ≈ 0.188
    p, c = ss.table2(su.PRINTED_TABLE2), ss.table2("corrected")
    diffs = [(col, float(p["h3"][i]), float(p[col][i]), float(c[col][i]))
             for col in ss.TABLE2_COLUMNS for i in range(10) if p[col][i] != c[col][i]]
    assert sorted(diffs) == [("lambda_mean", 4.0, 0.667, 0.867), ("mu_min", 1.0, 0.138, 0.188)]
    # the printed table breaks the ratios μ_mean/λ_mean ≈ 0.2135, μ_min/λ_min ≈ 0.150 there only
    assert np.flatnonzero(np.abs(p["mu_mean"] / p["lambda_mean"] - 0.2135) > 0.002).tolist() == [3]
    assert np.flatnonzero(np.abs(p["mu_min"] / p["lambda_min"] - 0.150) > 0.003).tolist() == [0]


def test_sea_state_parameters_with_the_printed_table():
    assert ss.sea_state_parameters(4.0, table=su.PRINTED_TABLE2).resonance_frequency == 0.667
    assert ss.sea_state_parameters(4.0).resonance_frequency == 0.867
    p = ss.sea_state_parameters(3.5, table=su.get_table2("printed"))
    assert p.resonance_frequency == pytest.approx((1.003 + 0.667) / 2)
    assert p.table == "printed"
    # the name reaches the study's table from the component too (resolved on first use)
    assert ss.sea_state_parameters(4.0, table="printed").resonance_frequency == 0.667
    np.testing.assert_array_equal(ss.table2("printed")["lambda_mean"],
                                  su.PRINTED_TABLE2.rows[:, 5])
    with pytest.raises(ParameterError, match="unknown Table 2 version 'nope'; valid: "
                       "'corrected', 'printed'"):
        ss.table2("nope")


# ---- the third spectrum ------------------------------------------------------------------
def _quad_0_inf(f) -> float:
    pts = [0.0, 0.5, 1.0, 2.0, 10.0]
    total = sum(integrate.quad(f, a, b, limit=400, epsrel=1e-12, epsabs=0)[0]
                for a, b in zip(pts, pts[1:]))
    return total + integrate.quad(f, pts[-1], np.inf, limit=400, epsrel=1e-12, epsabs=0)[0]


def test_printed_third_spectrum_is_reachable_and_differs_from_the_corrected_one():
    assert su.SPECTRA["rakhmanin-firsov-3-printed"] is su.RakhmaninFirsov3Printed
    assert "rakhmanin-firsov-3-printed" not in sp.SPECTRA  # the component registry: correct only
    # ... but the name reaches the study's class wherever a spectrum is named
    assert "rakhmanin-firsov-3-printed" in sp.spectrum_names()
    assert type(sp.get_spectrum("rakhmanin-firsov-3-printed", variance=D, decay_rate=MU,
                                resonance_frequency=LAM)) is su.RakhmaninFirsov3Printed
    assert set(sp.SPECTRA) < set(su.SPECTRA)
    kw = dict(variance=D, decay_rate=MU, resonance_frequency=LAM)
    printed, corrected = su.RakhmaninFirsov3Printed(**kw), RakhmaninFirsov3(**kw)
    w = np.linspace(0.0, 6.0, 61)
    den = (A2 + w**2) ** 2 - 4 * LAM**2 * w**2
    np.testing.assert_allclose(printed.one_sided(w), 2 * D * MU * w**2 / den, rtol=1e-13, atol=0)
    np.testing.assert_allclose(corrected.one_sided(w), 4 * D * MU / math.pi * w**2 / den,
                               rtol=1e-13, atol=0)
    # errata: the printed spectrum integrates to (π/2)·D_r, the corrected one to D_r
    assert _quad_0_inf(lambda x: float(printed.one_sided(x))) == pytest.approx(math.pi / 2 * D,
                                                                               rel=1e-9)
    assert printed.actual_variance == pytest.approx(math.pi / 2 * D)
    assert corrected.moment(0) == pytest.approx(D, rel=1e-8)


def test_spectrum_from_wave_height_by_name_or_class():
    h3 = 5.0
    dr = 0.143 * (h3 / 2) ** 2
    s = su.spectrum_from_wave_height("rakhmanin-firsov-3-printed", h3)
    assert isinstance(s, su.RakhmaninFirsov3Printed)
    assert s.moment(0) == pytest.approx(math.pi / 2 * dr, rel=1e-6)
    assert sp.spectrum_from_wave_height(su.RakhmaninFirsov3Printed, h3) == s
    assert su.spectrum_from_wave_height("rakhmanin-firsov-2", 4.0, table="printed"
                                        ).resonance_frequency == 0.667
    with pytest.raises(ParameterError, match="unknown spectrum 'nope'.*printed"):
        su.spectrum_from_wave_height("nope", h3)


# ---- the shaping filters -----------------------------------------------------------------
def test_printed_filters_are_named_objects():
    assert su.PRINTED_FILTERS == {"ordinate-printed": su.PRINTED_ORDINATE,
                                  "eq6": su.PRINTED_EQ6, "eq7": su.PRINTED_EQ7}


def test_printed_filters_differ_from_the_corrected_ones():
    kw = dict(variance=D, decay_rate=MU, resonance_frequency=LAM)
    spec = RakhmaninFirsov3(**kw)  # any R–F spectrum; the corrected variance of (4) below
    spec2 = sp.get_spectrum("rakhmanin-firsov-2", **kw)
    # factorisation before eq. (6): poles −λ ± jμ, variance (μ/λ)·D_r ≈ 0.21·D_r, not D_r
    printed = su.paper_filter("ordinate-printed", **kw).output_variance()[0]
    assert printed == pytest.approx(MU / LAM * D, rel=1e-10)
    assert shaping_filter(spec2, ("ordinate",)).output_variance()[0] == pytest.approx(D, rel=1e-10)
    assert shaping_filter(spec, ("ordinate",)).output_variance()[0] == pytest.approx(D, rel=1e-10)
    # eq. (6) is biproper: infinite variance
    eq6 = su.paper_filter(su.PRINTED_EQ6, **kw)
    assert eq6.D[0, 0] != 0 and math.isinf(eq6.output_variance()[0])
    # eq. (7): one-sided ∫|W|² = D μ a⁴/(λ g²) instead of the corrected (μ² + λ²) D / g²
    eq7 = su.paper_filter("eq7", **kw).output_variance()[0]
    assert eq7 == pytest.approx(D * MU * A2**2 / (LAM * GRAVITY**2), rel=1e-10)
    slope = shaping_filter(spec2, ("slope",)).output_variance()[0]
    assert slope == pytest.approx(A2 * D / GRAVITY**2, rel=1e-10)
    with pytest.raises(ParameterError, match="unknown paper filter 'eq8'.*eq6"):
        su.paper_filter("eq8", **kw)
    with pytest.raises(ParameterError, match="`decay_rate` must be > 0"):
        su.paper_filter("eq7", variance=D, decay_rate=-1.0, resonance_frequency=LAM)
