"""Short-term response statistics against Monte-Carlo and analytic results: the exceedance
probability against the largest of N Rayleigh samples, its Poisson limit, Rice's crossing rates
counted on a synthesised Gaussian record, the significant amplitude against the mean of the
highest third, the most probable maximum against the mode of the largest amplitude's
distribution; directional spreading functions (unit integral, closed forms); bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate, optimize

from seahelm.analysis.seakeeping.response_statistics import (
    crest_period,
    exceedance_probability,
    most_probable_maximum,
    significant_amplitude,
    significant_height,
    spectral_bandwidth,
    upcrossing_rate,
    zero_crossing_period,
)
from seahelm.environment.directional_spreading import (
    Cos2sSpreading,
    CosinePowerSpreading,
    get_spreading,
    spreading_with_parameter,
)
from seahelm.errors import ParameterError


def test_exceedance_against_the_largest_of_n_rayleigh_amplitudes():
    """N = T/T_z cycles, each amplitude Rayleigh(√m0): P(max > x) by Monte-Carlo equals
    1 − exp(−N e^{−x²/2m0}) within the sampling error plus the Poisson approximation's
    |1 − (1 − p)^N − (1 − e^{−Np})|."""
    rng = np.random.default_rng(34)
    m0, m2, n_cycles, x = 0.04, 0.01, 100, 0.6  # T_z = 2π·2 s; x = 3σ
    tz = float(zero_crossing_period(m0, m2))
    assert tz == pytest.approx(4 * math.pi)
    trials = 20_000
    peaks = rng.rayleigh(math.sqrt(m0), size=(trials, n_cycles))
    mc = float(np.mean(peaks.max(axis=1) > x))
    p = float(exceedance_probability(x, n_cycles * tz, m0, m2))
    q = math.exp(-x * x / (2 * m0))
    poisson_gap = abs((1 - (1 - q) ** n_cycles) - p)
    assert poisson_gap < 3e-3
    sigma = math.sqrt(p * (1 - p) / trials)
    assert abs(mc - p) < 4 * sigma + poisson_gap
    # rare: P ≈ N q (the first term of the Poisson series)
    x_high = 1.2
    q = math.exp(-x_high * x_high / (2 * m0))
    assert float(exceedance_probability(x_high, n_cycles * tz, m0, m2)) == pytest.approx(
        n_cycles * q, rel=n_cycles * q)
    # both sides: twice the rate, so P2 = 1 − (1 − P1)²
    p1 = exceedance_probability(0.3, 500.0, m0, m2)
    p2 = exceedance_probability(0.3, 500.0, m0, m2, both_sides=True)
    assert float(p2) == pytest.approx(1 - (1 - float(p1)) ** 2, rel=1e-12)


def test_crossing_rates_on_a_synthesised_gaussian_record():
    """A Gaussian record of a band spectrum S0 on [a, b] (random complex amplitudes, FFT):
    zero up-crossings every T_z = 2π√(m0/m2) and up-crossings of 1.5σ at Rice's rate, with
    m0 = S0 (b − a), m2 = S0 (b³ − a³)/3 computed by hand."""
    rng = np.random.default_rng(7)
    a, b, s0 = 0.5, 1.0, 0.3
    n, dt = 2 ** 21, 0.5
    w = 2 * math.pi * np.fft.rfftfreq(n, dt)
    dw = w[1]
    band = (w >= a) & (w <= b)
    amp = np.zeros(w.size, dtype=complex)
    k = int(band.sum())
    amp[band] = (rng.standard_normal(k) + 1j * rng.standard_normal(k)) * np.sqrt(s0 * dw)
    x = np.fft.irfft(amp * (n / 2), n)  # Re Σ A e^{iωt}, E|A|² = 2 S0 dω: variance Σ S0 dω
    m0, m2 = s0 * (b - a), s0 * (b ** 3 - a ** 3) / 3
    assert np.var(x) == pytest.approx(m0, rel=0.02)
    duration = n * dt
    zero_up = np.count_nonzero((x[:-1] < 0) & (x[1:] >= 0))
    expected = duration / float(zero_crossing_period(m0, m2))
    assert zero_up == pytest.approx(expected, rel=0.01)
    level = 1.5 * math.sqrt(m0)
    up = np.count_nonzero((x[:-1] < level) & (x[1:] >= level))
    assert up == pytest.approx(float(upcrossing_rate(level, m0, m2)) * duration, rel=0.05)


def test_significant_amplitude_is_the_mean_of_the_highest_third():
    """Rayleigh amplitudes: the mean of the highest third is 2.003√m0 (Longuet-Higgins 1952);
    seahelm's significant amplitude is 2√m0, its significant height 4√m0."""
    rng = np.random.default_rng(1)
    m0 = 0.25
    amps = np.sort(rng.rayleigh(math.sqrt(m0), 3_000_000))
    top_third = float(np.mean(amps[-1_000_000:]))
    assert float(significant_amplitude(m0)) == pytest.approx(top_third, rel=3e-3)
    assert float(significant_height(m0)) == pytest.approx(2 * top_third, rel=3e-3)


@pytest.mark.parametrize("n", [100, 1000, 100_000])
def test_most_probable_maximum_is_the_mode_for_many_cycles(n):
    """The mode of N f F^(N−1) (F Rayleigh) lies above √(2 m0 ln N) by about 1/(4 ln²N)."""
    m0 = 2.0

    def minus_log_pdf(x):
        return -(math.log(n * x / m0) - x * x / (2 * m0)
                 + (n - 1) * math.log(-math.expm1(-x * x / (2 * m0))))

    mode = optimize.minimize_scalar(minus_log_pdf, bounds=(0.5, 20.0), method="bounded",
                                    options={"xatol": 1e-12}).x
    mpm = float(most_probable_maximum(m0, n))
    assert 0 < mode / mpm - 1 < 1 / (2 * math.log(n) ** 2)


def test_periods_and_bandwidth_of_a_band():
    a, b, s0 = 0.5, 1.0, 1.0
    m0, m2, m4 = (s0 * (b ** (k + 1) - a ** (k + 1)) / (k + 1) for k in (0, 2, 4))
    assert float(crest_period(m2, m4)) == pytest.approx(2 * math.pi * math.sqrt(m2 / m4))
    assert float(spectral_bandwidth(m0, m2, m4)) == pytest.approx(
        math.sqrt(1 - m2 * m2 / (m0 * m4)))
    assert float(spectral_bandwidth(1.0, 1.0, 1.0)) == 0.0  # a single frequency
    assert math.isnan(float(zero_crossing_period(0.0, 0.0)))
    assert float(exceedance_probability(0.1, 100.0, 0.0, 0.0)) == 0.0


@pytest.mark.parametrize("call, match", [
    (lambda: exceedance_probability(0.0, 10.0, 1.0, 1.0), "`level` must be > 0"),
    (lambda: exceedance_probability(-1.0, 10.0, 1.0, 1.0), "`level` must be > 0"),
    (lambda: exceedance_probability(math.nan, 10.0, 1.0, 1.0), "`level` must be finite"),
    (lambda: exceedance_probability(1.0, 0.0, 1.0, 1.0), r"`duration` must be > 0 \[s\]"),
    (lambda: exceedance_probability(1.0, 10.0, -1.0, 1.0), "`m0` must be >= 0"),
    (lambda: zero_crossing_period(1.0, math.nan), "`m2` must be finite"),
    (lambda: most_probable_maximum(1.0, 1.0), r"`n_cycles` must be > 1 \[-\]"),
])
def test_statistics_bad_input(call, match):
    with pytest.raises(ParameterError, match=match):
        call()


@pytest.mark.parametrize("spreading", [CosinePowerSpreading(), CosinePowerSpreading(power=3.5),
                                       Cos2sSpreading(s=1.0), Cos2sSpreading(s=10.0)])
def test_spreading_integrates_to_one(spreading):
    total = integrate.quad(lambda t: float(spreading.density(t)), -math.pi, math.pi,
                           points=[-math.pi / 2, 0.0, math.pi / 2], epsabs=1e-13)[0]
    assert total == pytest.approx(1.0, abs=1e-10)
    theta, w = spreading.quadrature(24)
    assert w.sum() == pytest.approx(1.0, abs=1e-15) and np.allclose(w, w[::-1])
    assert np.all(np.abs(theta) <= spreading.half_width)


def test_spreading_closed_forms():
    assert float(CosinePowerSpreading().density(0.0)) == pytest.approx(2 / math.pi)  # (2/π)cos²
    assert float(CosinePowerSpreading().density(2.0)) == 0.0
    assert float(Cos2sSpreading(s=1.0).density(0.7)) == pytest.approx(
        (1 + math.cos(0.7)) / (2 * math.pi))  # cos²(θ/2)/π
    assert get_spreading("cos2") == CosinePowerSpreading(power=2.0)
    assert get_spreading("cos-2s", s=4.0) == Cos2sSpreading(s=4.0)
    np.testing.assert_array_equal(CosinePowerSpreading().quadrature(1)[0], [0.0])


@pytest.mark.parametrize("call, match", [
    (lambda: CosinePowerSpreading(power=0.0), r"`power` must be in \(0, 2000\] \[-\]"),
    (lambda: Cos2sSpreading(s=math.nan), r"`s` must be in \(0, 1000\] \[-\]"),
    (lambda: get_spreading("cos4"), "unknown spreading 'cos4'; valid: 'cos-n', 'cos2', 'cos-2s'"),
    (lambda: get_spreading(Cos2sSpreading(), s=2.0), "cannot be given together"),
    (lambda: Cos2sSpreading().quadrature(0),
     r"`n_directions` must be an integer in \[1, 10000\]"),
])
def test_spreading_bad_input(call, match):
    with pytest.raises(ParameterError, match=match):
        call()


@pytest.mark.parametrize("call, match", [
    (lambda: Cos2sSpreading(s=1e6), r"`s` must be in \(0, 1000\] \[-\], got 1000000.0"),
    (lambda: CosinePowerSpreading(power=1e300), r"`power` must be in \(0, 2000\] \[-\]"),
    (lambda: Cos2sSpreading().quadrature(10**11), r"`n_directions` must be an integer in "
                                                  r"\[1, 10000\]"),
])
def test_spreading_too_narrow_or_too_many_directions(call, match):
    """s = 1e6 made every weight of the 36-direction quadrature 0 (the seakeeping moments NaN);
    10^11 directions a MemoryError."""
    with pytest.raises(ParameterError, match=match):
        call()


@pytest.mark.parametrize("spreading", [Cos2sSpreading(s=2.0), Cos2sSpreading(s=25.0),
                                       CosinePowerSpreading(power=2.0),
                                       CosinePowerSpreading(power=7.0)])
def test_drawn_directions_have_the_density(spreading):
    """The directions drawn from evenly spaced uniforms (the quantiles) fall into 40 bins in
    the proportions of D integrated over each bin (scipy's quad of the closed form), within
    the table's 1e-6 and the quantiles' 1/N; the mean is 0 and the second moment is
    ∫θ²D dθ."""
    from scipy.integrate import quad

    n = 400_000
    theta = spreading.draw((np.arange(n) + 0.5) / n)
    h = spreading.half_width
    assert np.all(np.abs(theta) <= h)
    edges = np.linspace(-h, h, 41)
    counts = np.histogram(theta, edges)[0] / n
    expect = [quad(lambda t: float(spreading.density(t)), a, b)[0]
              for a, b in zip(edges[:-1], edges[1:])]
    np.testing.assert_allclose(counts, expect, atol=2e-5)
    assert abs(theta.mean()) < 1e-6
    second = quad(lambda t: t * t * float(spreading.density(t)), -h, h)[0]
    assert (theta ** 2).mean() == pytest.approx(second, rel=1e-4)


def test_spreading_with_parameter():
    assert spreading_with_parameter("cos-2s", 3.0) == Cos2sSpreading(s=3.0)
    assert spreading_with_parameter("cos-n", 4.0) == CosinePowerSpreading(power=4.0)
    with pytest.raises(ParameterError, match="unknown directional spreading 'cos2'"):
        spreading_with_parameter("cos2", 2.0)
    with pytest.raises(ParameterError) as err:
        spreading_with_parameter("cos-2s", -1.0)
    assert err.value.field == "spreading_parameter" and "(0, 1000]" in str(err.value)


@pytest.mark.parametrize("spreading", [Cos2sSpreading(s=1000.0),
                                       CosinePowerSpreading(power=2000.0)])
@pytest.mark.parametrize("n", [2, 36])
def test_the_narrowest_spreading_still_has_weights(spreading, n):
    """At the bounds the midpoint rule's weights are finite and sum to 1 (two directions: the
    nodes at ±90 or ±45 deg, cos^2000 = 2^-1000 > 0)."""
    _, w = spreading.quadrature(n)
    assert np.all(np.isfinite(w)) and w.sum() == pytest.approx(1.0, abs=1e-12)
