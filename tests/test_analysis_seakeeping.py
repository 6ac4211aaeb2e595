"""Seakeeping moments over speed × heading: analytic integrals (|H| = 1 gives Hs²/16; a band of
white noise with ω_e(ω) polynomial, head and following seas; a one-DOF oscillator in white
noise, π ω_n/(4ζ)), the ω-domain integral against the ω_e-domain one of the encounter spectrum
in head seas, port-starboard symmetry, batched = one by one, spreading keeps the variance, the
dataset, bad input."""

from __future__ import annotations

import dataclasses
import math
from typing import ClassVar

import numpy as np
import pytest
from numpy.polynomial import polynomial as P
from scipy import integrate

from seahelm.analysis.seakeeping.frequency_domain import closed_form_moments, response_moments
from seahelm.constants import GRAVITY
from seahelm.environment.encounter import EncounterSpectrum
from seahelm.environment.rao import RAO, closed_form_rao
from seahelm.environment.spectra import Bretschneider, Jonswap
from seahelm.environment.spectrum_base import WaveSpectrum
from seahelm.errors import ParameterError, ValidityRangeWarning
from seahelm.vessels.particulars import Particulars

SHIP = Particulars(length=175.0, beam=25.4, draft=8.5, block_coefficient=0.5617)
SEA = Jonswap(significant_height=4.0, peak_period=10.0)
HALF = np.radians(np.arange(0.0, 180.1, 5.0))


@dataclasses.dataclass(frozen=True)
class Band(WaveSpectrum):
    """White noise S0 on [lo, hi] (S0 everywhere with hi = inf): an analytic test sea."""

    name: ClassVar[str] = "band"
    level: float
    lo: float = 0.0
    hi: float = math.inf

    def one_sided(self, omega):
        w = np.asarray(omega, dtype=float)
        return np.where((w >= self.lo) & (w <= self.hi), self.level, 0.0)


def unit_rao(frequency, speed=0.0, dof="heave", value=1.0 + 0.0j):
    return RAO(frequency, HALF, (dof,), np.full((1, len(frequency), HALF.size), value),
               speed, "constant")


def test_unit_rao_gives_the_wave_variance():
    sea = Bretschneider(significant_height=3.0, peak_period=8.0)
    w = np.linspace(0.01, 40.0, 40001)  # tail beyond 40 rad/s: 5/(4 X^4) ~ 1e-7 of m0
    for U, spreading in ((0.0, None), (6.0, None), (6.0, "cos2"), (3.0, "cos-2s")):
        m = response_moments(unit_rao(w, U), sea, np.radians([0.0, 60.0, 180.0, 300.0]),
                             frequency=w, spreading=spreading)
        np.testing.assert_allclose(m.moment("heave", 0), 3.0 ** 2 / 16.0, rtol=2e-6)
        np.testing.assert_allclose(m.significant_amplitude("heave"), 2 * 3.0 / 4, rtol=1e-6)


@pytest.mark.parametrize("speed, heading_deg", [(0.0, 90.0), (8.0, 180.0), (5.0, 150.0),
                                                (10.0, 0.0), (7.0, 40.0)])
def test_white_noise_band_moments_are_the_polynomial_integrals(speed, heading_deg):
    """m_n = S0 ∫ (ω − cω²)ⁿ dω on the band, c = U cos ε/g: following seas (ε = 0, 40°) put
    the turning point ω* = 1/(2c) inside the band, where ω_e(ω) is not monotonic."""
    lo, hi, s0 = 0.2, 2.0, 0.7
    c = speed * math.cos(math.radians(heading_deg)) / GRAVITY
    if heading_deg in (0.0, 40.0):
        assert lo < 1 / (2 * c) < hi
    w = np.linspace(lo, hi, 40001)
    m = response_moments(unit_rao(w, speed), Band(level=s0, lo=lo, hi=hi),
                         [math.radians(heading_deg)], frequency=w)
    we = np.array([0.0, 1.0, -c])  # ω − cω² as a polynomial in ω
    for n in (0, 2, 4):
        antider = P.polyint(P.polypow(we, n))
        expected = s0 * (P.polyval(hi, antider) - P.polyval(lo, antider))
        assert m.moment("heave", n)[0, 0] == pytest.approx(expected, rel=1e-7)


def test_oscillator_in_white_noise():
    """|H|² of 1/(1 − (ω/ω_n)² + 2iζω/ω_n) in white noise S0: m0 = π S0 ω_n/(4ζ),
    m2 = π S0 ω_n³/(4ζ) (one-sided; the grid leaves out [0, 1e-4] rad/s, S0·1e-4 of m0, and
    beyond W = 500 rad/s S0 ω_n⁴/(3W³) of m0, S0 ω_n⁴/W of m2)."""
    wn, zeta, s0 = 0.5, 0.1, 2.0
    w = np.geomspace(1e-4, 500.0, 400001)
    q = w / wn
    H = 1.0 / (1.0 - q * q + 2j * zeta * q)
    rao = RAO(w, HALF, ("roll",), np.repeat(H[None, :, None], HALF.size, axis=2), 0.0, "sdof")
    m = response_moments(rao, Band(level=s0), np.radians([30.0, 90.0]), frequency=w)
    below = s0 * 1e-4  # the grid starts at 1e-4 rad/s, where |H| = 1
    np.testing.assert_allclose(m.moment("roll", 0), math.pi * s0 * wn / (4 * zeta) - below,
                               rtol=1e-7)
    np.testing.assert_allclose(m.moment("roll", 2), math.pi * s0 * wn ** 3 / (4 * zeta)
                               - s0 * wn ** 4 / 500.0, rtol=1e-6)
    np.testing.assert_allclose(m.zero_crossing_period("roll"), 2 * math.pi / wn, rtol=2e-4)


def test_wave_frequency_integral_equals_encounter_frequency_integral_in_head_seas():
    """∫ ω_eⁿ |H(ω)|² S(ω) dω = ∫ ω_eⁿ |H(ω(ω_e))|² S_e(ω_e) dω_e with the encounter spectrum
    of :class:`EncounterSpectrum` (head seas: ω ↦ ω_e monotonic, ω = (√(1 + 4cω_e) − 1)/(2c)),
    the latter on a dense grid in ω_e (adaptive quadrature misses the narrow roll peak)."""
    U, eps = 6.0, math.radians(160.0)
    c = -U * math.cos(eps) / GRAVITY
    lo, hi = 1e-3, 6.0
    m = closed_form_moments(SHIP, SEA, [U], [eps], metacentric_height=1.2,
                            frequency=np.linspace(lo, hi, 20001))
    we = np.linspace(lo + c * lo ** 2, hi + c * hi ** 2, 120001)
    omega = (np.sqrt(1 + 4 * c * we) - 1) / (2 * c)
    rao = closed_form_rao(SHIP, U, frequency=omega, heading=[eps], metacentric_height=1.2)
    se = EncounterSpectrum(SEA, U, eps).one_sided(we)
    for dof in ("heave", "roll", "pitch"):
        H2 = rao.amplitude(dof)[:, 0] ** 2
        for n in (0, 2, 4):
            ref = integrate.trapezoid(we ** n * H2 * se, we)
            assert m.moment(dof, n)[0, 0] == pytest.approx(ref, rel=3e-7), (dof, n)


@pytest.mark.parametrize("spreading", [None, "cos2"])
def test_port_and_starboard_seas_give_the_same_response(spreading):
    eps = np.radians([20.0, 45.0, 90.0, 120.0, 170.0])
    both = np.concatenate([-eps[::-1], eps])
    m = closed_form_moments(SHIP, SEA, [0.0, 4.0, 8.0], both, metacentric_height=1.0,
                            spreading=spreading, n_directions=18)
    for dof in m.dofs:
        m0 = m.moment(dof, 0)
        np.testing.assert_allclose(m0[:, 4::-1], m0[:, 5:], rtol=1e-12, atol=0)
    assert np.all(m.moment("roll", 0) > 0)
    # ε and 2π − ε too (a heading grid round the circle)
    m2 = closed_form_moments(SHIP, SEA, [4.0], 2 * math.pi - eps, metacentric_height=1.0,
                             spreading=spreading, n_directions=18)
    np.testing.assert_allclose(m2.moment("roll", 0)[0], m.moment("roll", 0)[1, 5:], rtol=1e-12)


def test_batched_equals_one_by_one():
    U = np.array([0.0, 3.0, 7.5])
    eps = np.radians([0.0, 50.0, 90.0, 135.0, 180.0, 250.0])
    grid = closed_form_moments(SHIP, SEA, U, eps, metacentric_height=0.8, spreading="cos2",
                               n_directions=12)
    for i, u in enumerate(U):
        for j, e in enumerate(eps):
            one = closed_form_moments(SHIP, SEA, [u], [e], metacentric_height=0.8,
                                      spreading="cos2", n_directions=12)
            np.testing.assert_allclose(grid.moments[:, :, i, j], one.moments[:, :, 0, 0],
                                       rtol=1e-12, atol=0)
    # several RAO tables at once = each alone
    w = np.linspace(0.05, 3.0, 300)
    raos = [closed_form_rao(SHIP, u, frequency=w, metacentric_height=0.8) for u in U]
    together = response_moments(raos, SEA, eps, frequency=w)
    for i, r in enumerate(raos):
        alone = response_moments(r, SEA, eps, frequency=w)
        np.testing.assert_allclose(together.moments[:, :, i], alone.moments[:, :, 0],
                                   rtol=1e-12, atol=0)
    np.testing.assert_array_equal(together.speed, U)


def test_a_table_at_its_nodes_equals_the_closed_form():
    w = np.linspace(0.05, 4.0, 400)
    rao = closed_form_rao(SHIP, 4.0, frequency=w, heading=HALF, metacentric_height=0.8)
    eps = np.radians([0.0, 45.0, 90.0, 180.0, 225.0])  # 225 deg: the half table mirrored
    a = response_moments(rao, SEA, eps, frequency=w)
    b = closed_form_moments(SHIP, SEA, [4.0], eps, frequency=w, metacentric_height=0.8)
    np.testing.assert_allclose(a.moments, b.moments, rtol=1e-9, atol=1e-20)


def test_dataset_and_statistics():
    m = closed_form_moments(SHIP, SEA, [0.0, 5.0], np.radians([90.0, 180.0]),
                            metacentric_height=0.8)
    ds = m.to_xarray()
    assert dict(ds.sizes) == {"dof": 3, "speed": 2, "heading": 2}
    assert list(ds["dof"].values) == ["heave", "roll", "pitch"]
    assert "roll: rad" in ds["rms"].attrs["units"] and "heave: m^2" in ds["m0"].attrs["units"]
    np.testing.assert_allclose(ds["significant_amplitude"].values, 2 * np.sqrt(ds["m0"].values))
    np.testing.assert_allclose(ds["zero_crossing_period"].sel(dof="heave").values,
                               2 * math.pi * np.sqrt(m.moment("heave", 0) / m.moment("heave", 2)))
    assert ds.attrs["format"] == "seahelm-seakeeping-1" and "Jonswap" in ds.attrs["spectrum"]
    p = m.exceedance_probability("roll", math.radians(2.0), 3600.0)
    assert p.shape == (2, 2) and np.all((p >= 0) & (p <= 1))
    mpm = m.most_probable_maximum("heave", 3 * 3600.0)
    n = 3 * 3600.0 / m.zero_crossing_period("heave")
    np.testing.assert_allclose(mpm, np.sqrt(2 * m.moment("heave", 0) * np.log(n)))


def test_too_narrow_a_table_warns():
    w = np.linspace(0.7, 3.0, 100)  # misses most of a Tp = 10 s sea (ω_p = 0.63 rad/s)
    with pytest.warns(ValidityRangeWarning, match="outside the RAO's frequencies"):
        response_moments(unit_rao(w), SEA, [math.pi])


@pytest.mark.parametrize("call, match", [
    (lambda: closed_form_moments(SHIP, SEA, [5.0], [], dofs="heave"), "`heading`"),
    (lambda: closed_form_moments(SHIP, SEA, [], [1.0], dofs="heave"), "`speed`"),
    (lambda: closed_form_moments(SHIP, SEA, [-1.0], [1.0]), r"`speed` must be >= 0 \[m/s\]"),
    (lambda: closed_form_moments(SHIP, SEA, [1.0], [math.nan]), r"`heading` must be finite \[rad\]"),
    (lambda: closed_form_moments(SHIP, SEA, [1.0], [1.0], dofs="roll"), r"`metacentric_height`.*\[m\]"),
    (lambda: closed_form_moments(SHIP, SEA, [1.0], [1.0], dofs=["sway"]), "`dofs` must be some of heave, pitch"),
    (lambda: closed_form_moments(SHIP, "jonswap", [1.0], [1.0]), "`spectrum` must be a WaveSpectrum"),
    (lambda: closed_form_moments(None, SEA, [1.0], [1.0]), "`particulars`"),
    (lambda: closed_form_moments(SHIP, SEA, [1.0], [1.0], frequency=[0.5, 0.4]), r"`frequency`.*increasing values \[rad/s\]"),
    (lambda: closed_form_moments(SHIP, SEA, [1.0], [1.0], spreading="cos3"), "unknown spreading 'cos3'"),
    (lambda: closed_form_moments(SHIP, SEA, [1.0], [1.0], spreading="cos2", n_directions=0), "`n_directions`"),
    (lambda: closed_form_moments(SHIP, SEA, [1.0], [1.0], metacentric_height=-1.0), r"`metacentric_height` must be > 0 \[m\]"),
    (lambda: response_moments([], SEA, [1.0]), "`raos`"),
    (lambda: response_moments([unit_rao([0.1, 1.0]), unit_rao([0.1, 2.0])], SEA, [1.0]), r"distinct speeds \[m/s\]"),
    (lambda: response_moments(unit_rao([0.1, 1.0]), SEA, [1.0], dofs=["roll"], frequency=[0.1, 1.0]), "`dofs`"),
])
def test_bad_input_names_the_parameter(call, match):
    with pytest.raises(ParameterError, match=match):
        call()


@pytest.mark.parametrize("level, duration, match", [
    (0.0, 3600.0, r"`level` must be > 0 \[rad\]"), (-0.1, 3600.0, r"`level` must be > 0 \[rad\]"),
    (math.nan, 3600.0, r"`level` must be finite \[rad\]"), (0.1, 0.0, r"`duration` must be > 0 \[s\]"),
])
def test_bad_thresholds(level, duration, match):
    m = closed_form_moments(SHIP, SEA, [1.0], [1.0], metacentric_height=1.0)
    with pytest.raises(ParameterError, match=match):
        m.exceedance_probability("roll", level, duration)
    with pytest.raises(ParameterError, match="`dof` is not computed"):
        m.rms("sway")
