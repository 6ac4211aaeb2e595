"""Wave spectra: variance, correlation ↔ spectrum, moments, standard spectra, registry.

References are analytic or from scipy.integrate.quad on formulas written out here, never
values produced by the code under test.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate, special

from seahelm.constants import GRAVITY
from seahelm.environment import rational_spectra as rs
from seahelm.environment import spectra as sp
from seahelm.environment import spectrum_base as sb
from seahelm.errors import ParameterError

D, MU, LAM = 0.32175, 0.214, 1.003  # h3% = 3 m, Table 2 means
A2 = MU**2 + LAM**2

RF_CLASSES = {
    "rakhmanin-firsov-1": rs.RakhmaninFirsov1,
    "rakhmanin-firsov-2": rs.RakhmaninFirsov2,
    "rakhmanin-firsov-3": rs.RakhmaninFirsov3,
}


def rf(name: str, d: float = D, mu: float = MU, lam: float = LAM) -> sb.WaveSpectrum:
    return sp.get_spectrum(name, variance=d, decay_rate=mu, resonance_frequency=lam)


def quad_0_inf(f, peak: float = 1.0) -> float:
    pts = [0.0, 0.5 * peak, peak, 2 * peak, 10 * peak]
    total = sum(integrate.quad(f, a, b, limit=400, epsrel=1e-12, epsabs=0)[0] for a, b in zip(pts, pts[1:]))
    return total + integrate.quad(f, pts[-1], np.inf, limit=400, epsrel=1e-12, epsabs=0)[0]


# ---- Rakhmanin–Firsov ----------------------------------------------------------------------


def printed_formula(name: str, w: float, d: float = D, mu: float = MU, lam: float = LAM) -> float:
    """The paper's formulas (3), (4) and the corrected third one, written out independently."""
    den = (mu**2 + lam**2 + w**2) ** 2 - 4 * lam**2 * w**2
    return {
        "rakhmanin-firsov-1": 2 * d * mu / math.pi * (w**2 + mu**2 + lam**2) / den,
        "rakhmanin-firsov-2": 4 * d * mu / math.pi * (mu**2 + lam**2) / den,
        "rakhmanin-firsov-3": 4 * d * mu / math.pi * w**2 / den,
    }[name]


@pytest.mark.parametrize("name", list(RF_CLASSES))
def test_rf_formula_matches_paper(name):
    s = rf(name)
    w = np.linspace(0.0, 6.0, 61)
    expected = np.array([printed_formula(name, x) for x in w])
    np.testing.assert_allclose(s.one_sided(w), expected, rtol=1e-13, atol=0)


@pytest.mark.parametrize("name", list(RF_CLASSES))
@pytest.mark.parametrize("d,mu,lam", [(D, MU, LAM), (2.0, 0.5, 0.3), (0.01, 0.06, 0.4)])
def test_rf_integrates_to_variance(name, d, mu, lam):
    total = quad_0_inf(lambda w: printed_formula(name, w, d, mu, lam), peak=math.hypot(mu, lam))
    assert total == pytest.approx(d, rel=1e-9)
    assert rf(name, d, mu, lam).moment(0) == pytest.approx(d, rel=1e-8)


@pytest.mark.parametrize("name", list(RF_CLASSES))
@pytest.mark.parametrize("tau", [0.0, 0.7, 2.5, 6.0])
def test_correlation_is_cosine_transform_of_one_sided(name, tau):
    """K(τ) = ∫₀^∞ S₁(ω) cos ωτ dω (eq. (1)) for the correlation functions (2), (4), corrected 3rd."""
    s = rf(name)
    f = lambda w: printed_formula(name, w)  # noqa: E731
    if tau == 0.0:
        k = quad_0_inf(f)
    else:
        k = integrate.quad(f, 0, np.inf, weight="cos", wvar=tau, limlst=200)[0]
    closed = {
        "rakhmanin-firsov-1": D * math.exp(-MU * tau) * math.cos(LAM * tau),
        "rakhmanin-firsov-2": D * math.exp(-MU * tau) * (math.cos(LAM * tau) + MU / LAM * math.sin(LAM * tau)),
        "rakhmanin-firsov-3": D * math.exp(-MU * tau) * (math.cos(LAM * tau) - MU / LAM * math.sin(LAM * tau)),
    }[name]
    assert k == pytest.approx(closed, abs=1e-7 * D)
    assert float(s.correlation(tau)) == pytest.approx(closed, rel=1e-13, abs=1e-15)
    assert float(s.correlation(-tau)) == pytest.approx(closed, rel=1e-13, abs=1e-15)


@pytest.mark.parametrize("name", list(RF_CLASSES))
def test_two_sided_is_half_and_even(name):
    s = rf(name)
    w = np.linspace(0, 5, 11)
    np.testing.assert_allclose(s.two_sided(w), 0.5 * s.one_sided(w), rtol=1e-15)
    np.testing.assert_allclose(s.two_sided(-w), s.two_sided(w), rtol=1e-15)
    total = integrate.quad(lambda x: float(s.two_sided(x)), -np.inf, np.inf, limit=400)[0]
    assert total == pytest.approx(D, rel=1e-7)


def test_one_sided_rejects_negative_frequency():
    with pytest.raises(ParameterError, match="`omega` must be >= 0"):
        rf("rakhmanin-firsov-1").one_sided(-1.0)


# ---- slope, rate, acceleration --------------------------------------------------------------


def test_slope_spectrum_eq5_and_variance():
    base = rf("rakhmanin-firsov-2")
    slope = rs.slope_spectrum(base)
    w = np.linspace(0, 4, 9)
    np.testing.assert_allclose(
        slope.one_sided(w), [x**2 / GRAVITY**2 * printed_formula("rakhmanin-firsov-2", x) for x in w], rtol=1e-13
    )
    var = quad_0_inf(lambda x: x**2 / GRAVITY**2 * printed_formula("rakhmanin-firsov-2", x))
    assert var == pytest.approx(A2 * D / GRAVITY**2, rel=1e-9)  # (μ² + λ²) D_r / g²
    assert slope.variance == pytest.approx(A2 * D / GRAVITY**2, rel=1e-8)


def test_ordinate_rate_variance_is_papers_D_alpha():
    """The paper's D_α = (μ² + λ²)D_r is the variance of dζ/dt (erratum: no 1/g²)."""
    assert rs.ordinate_rate_spectrum(rf("rakhmanin-firsov-2")).variance == pytest.approx(A2 * D, rel=1e-8)


@pytest.mark.parametrize("name", ["rakhmanin-firsov-1", "rakhmanin-firsov-3"])
def test_slope_variance_diverges_for_variants_1_and_3(name):
    assert math.isinf(rs.slope_spectrum(rf(name)).variance)


def test_rate_and_acceleration_spectra():
    base = rf("rakhmanin-firsov-2")
    w = np.array([0.1, 0.5, 1.0, 3.0])
    s_alpha = w**2 / GRAVITY**2 * base.one_sided(w)
    np.testing.assert_allclose(rs.slope_rate_spectrum(base).one_sided(w), w**2 * s_alpha, rtol=1e-14)
    np.testing.assert_allclose(rs.slope_acceleration_spectrum(base).one_sided(w), w**4 * s_alpha, rtol=1e-14)
    assert math.isinf(rs.slope_rate_spectrum(base).variance)
    assert math.isinf(rs.slope_acceleration_spectrum(base).variance)


def test_moments_of_variant_2():
    s = rf("rakhmanin-firsov-2")
    # m2 = a² D (spectrum of the derivative is a²·variant 3); m1 by quadrature of the formula
    assert s.moment(2) == pytest.approx(A2 * D, rel=1e-8)
    m1 = quad_0_inf(lambda w: w * printed_formula("rakhmanin-firsov-2", w))
    assert s.moment(1) == pytest.approx(m1, rel=1e-8)
    assert math.isinf(s.moment(3))
    assert math.isinf(rf("rakhmanin-firsov-1").moment(1))
    with pytest.raises(ParameterError, match="`n`"):
        s.moment(-1)


def test_peak_frequency_variant_2():
    s = rf("rakhmanin-firsov-2")
    w = np.linspace(0.5, 1.5, 200001)
    assert s.peak_frequency == pytest.approx(w[np.argmax([printed_formula("rakhmanin-firsov-2", x) for x in w])], abs=1e-5)
    assert s.peak_frequency == pytest.approx(math.sqrt(LAM**2 - MU**2), rel=1e-12)


# ---- standard spectra ----------------------------------------------------------------------


@pytest.mark.parametrize("hs", [0.5, 2.0, 7.5, 14.0])
def test_pierson_moskowitz_m0(hs):
    s = sp.PiersonMoskowitz(significant_height=hs)
    assert abs(s.moment(0) / (hs**2 / 16) - 1) < 1e-6
    alpha, g = 0.0081, GRAVITY
    beta = 4 * alpha * g**2 / hs**2
    f = lambda w: alpha * g**2 / w**5 * math.exp(-beta / w**4) if w > 0 else 0.0  # noqa: E731
    assert abs(quad_0_inf(f, peak=(0.8 * beta) ** 0.25) / (hs**2 / 16) - 1) < 1e-6
    # m_n = (αg²/4) β^((n−4)/4) Γ((4−n)/4)
    for n in (1, 2):
        closed = alpha * g**2 / 4 * beta ** ((n - 4) / 4) * special.gamma((4 - n) / 4)
        assert s.moment(n) == pytest.approx(closed, rel=1e-7)
    assert math.isinf(s.moment(4))
    assert s.peak_frequency == pytest.approx(0.4012 * math.sqrt(g / hs), rel=1e-3)


@pytest.mark.parametrize("name", ["bretschneider", "ittc"])
def test_bretschneider_m0_and_peak(name):
    hs, tp = 3.0, 9.0
    s = sp.get_spectrum(name, significant_height=hs, peak_period=tp)
    assert abs(s.moment(0) / (hs**2 / 16) - 1) < 1e-6
    wp = 2 * math.pi / tp
    w = np.linspace(0.5 * wp, 1.5 * wp, 100001)
    assert w[np.argmax(s.one_sided(w))] == pytest.approx(wp, rel=1e-4)


@pytest.mark.parametrize("gamma", [1.0, 2.0, 3.3, 5.0, 7.0])
def test_jonswap_normalisation(gamma):
    hs, tp = 4.0, 10.0
    s = sp.Jonswap(significant_height=hs, peak_period=tp, gamma=gamma)
    wp = 2 * math.pi / tp

    def ref(w):  # JONSWAP written out (Hasselmann et al. 1973 shape, DNV normalisation)
        if w <= 0:
            return 0.0
        sig = 0.07 if w <= wp else 0.09
        pm = 5 / 16 * hs**2 * wp**4 / w**5 * math.exp(-1.25 * (wp / w) ** 4)
        return (1 - 0.287 * math.log(gamma)) * pm * gamma ** math.exp(-((w - wp) ** 2) / (2 * sig**2 * wp**2))

    m0 = quad_0_inf(ref, wp)
    assert s.moment(0) == pytest.approx(m0, rel=1e-7)
    assert abs(m0 / (hs**2 / 16) - 1) < 0.02  # DNV: C(γ) = 1 − 0.287 ln γ is approximate
    exact = sp.Jonswap(significant_height=hs, peak_period=tp, gamma=gamma, exact_normalization=True)
    assert abs(exact.moment(0) / (hs**2 / 16) - 1) < 1e-6


def test_jonswap_gamma_one_is_bretschneider():
    w = np.linspace(0, 3, 31)
    j = sp.Jonswap(significant_height=2, peak_period=7, gamma=1.0)
    b = sp.Bretschneider(significant_height=2, peak_period=7)
    np.testing.assert_allclose(j.one_sided(w), b.one_sided(w), rtol=1e-14)


# ---- registry and construction ----------------------------------------------------------------


def test_registry_names_and_unknown():
    assert {"rakhmanin-firsov-1", "rakhmanin-firsov-2", "rakhmanin-firsov-3", "pierson-moskowitz",
            "jonswap", "bretschneider", "ittc"} <= set(sp.SPECTRA)
    with pytest.raises(ValueError, match="unknown spectrum 'nope'.*valid:.*jonswap"):
        sp.get_spectrum("nope")
    s = rf("rakhmanin-firsov-1")
    assert sp.get_spectrum(s) is s
    with pytest.raises(ParameterError, match="object"):
        sp.get_spectrum(s, variance=1.0)


@pytest.mark.parametrize("name", list(sp.SPECTRA))
def test_from_wave_height_all_have_m0_equal_to_Dr(name):
    h3 = 5.0
    s = sp.spectrum_from_wave_height(name, h3)
    dr = 0.143 * (h3 / 2) ** 2
    tol = 0.02 if name == "jonswap" else 1e-6
    assert abs(s.moment(0) / dr - 1) < tol


@pytest.mark.parametrize(
    "kwargs,match",
    [
        (dict(variance=D, decay_rate=0.0, resonance_frequency=LAM), "`decay_rate` must be > 0"),
        (dict(variance=D, decay_rate=-0.1, resonance_frequency=LAM), "`decay_rate` must be > 0"),
        (dict(variance=D, decay_rate=float("nan"), resonance_frequency=LAM), "`decay_rate` must be finite"),
        (dict(variance=0.0, decay_rate=MU, resonance_frequency=LAM), "`variance` must be > 0"),
        (dict(variance=D, decay_rate=MU, resonance_frequency=-1.0), "`resonance_frequency` must be > 0"),
    ],
)
def test_rf_bad_parameters(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        rs.RakhmaninFirsov1(**kwargs)


@pytest.mark.parametrize(
    "cls,kwargs,match",
    [
        (sp.PiersonMoskowitz, dict(significant_height=-1.0), "`significant_height` must be > 0"),
        (sp.Bretschneider, dict(significant_height=1.0, peak_period=0.0), "`peak_period` must be > 0"),
        (sp.Jonswap, dict(significant_height=1.0, peak_period=8.0, gamma=0.5), "`gamma` must be >= 1"),
        (sp.Jonswap, dict(significant_height=1.0, peak_period=8.0, sigma_a=float("nan")), "`sigma_a`"),
    ],
)
def test_standard_bad_parameters(cls, kwargs, match):
    with pytest.raises(ParameterError, match=match):
        cls(**kwargs)


def test_from_wave_height_bad_h3():
    with pytest.raises(ParameterError, match="`h3` must be > 0"):
        sp.spectrum_from_wave_height("rakhmanin-firsov-1", -1.0)
    with pytest.raises(ParameterError, match="`h3` must be finite"):
        sp.spectrum_from_wave_height("pierson-moskowitz", float("nan"))
