"""Shaping filters: |W(jω)|² = S(ω), Lyapunov variance, exact discretisation, seeded samples.

Statistical bounds: for a zero-mean stationary Gaussian sequence with autocovariance K_m =
K(mΔt), R independent runs of N samples each,

* the variance estimate v̂ = ΣΣ x²/(RN) has Var v̂ = (2/(RN)) Σ_{|m|<N} (1 − |m|/N) K_m²;
* the lag-m estimate ĉ_m = ΣΣ x_k x_{k+m}/(R(N−m)) has (Bartlett, large N)
  Var ĉ_m ≈ (1/(R(N−m))) Σ_l (K_l² + K_{l+m} K_{l−m});
* a Welch estimate (Hann, 50 % overlap) averaged over n segments and R runs has a relative
  standard deviation ≈ √(1.06/(nR)) per frequency bin.

K comes from the closed-form correlation functions written out in this file. Tests assert
|estimate − truth| < 5σ with fixed seeds.
"""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest
from scipy import integrate, linalg, signal

from seahelm.constants import GRAVITY
from seahelm.environment import shaping as sh
from seahelm.environment import spectra as sp
from seahelm.environment import spectrum_base as sb
from seahelm.errors import MissingDependencyError, ParameterError

D, MU, LAM = 0.32175, 0.214, 1.003
A2 = MU**2 + LAM**2


def K(name: str, tau):
    t = np.abs(np.asarray(tau, float))
    e = D * np.exp(-MU * t)
    return {
        "rakhmanin-firsov-1": e * np.cos(LAM * t),
        "rakhmanin-firsov-2": e * (np.cos(LAM * t) + MU / LAM * np.sin(LAM * t)),
        "rakhmanin-firsov-3": e * (np.cos(LAM * t) - MU / LAM * np.sin(LAM * t)),
    }[name]


def spec(name: str) -> sb.WaveSpectrum:
    return sp.get_spectrum(name, variance=D, decay_rate=MU, resonance_frequency=LAM)


def var_of_variance(k: np.ndarray, n: int, runs: int) -> float:
    m = np.arange(1, k.size)
    return 2.0 / (runs * n) * (k[0] ** 2 + 2 * np.sum((1 - m / n) * k[1:] ** 2))


def var_of_lag(kfun, dt: float, m: int, n: int, runs: int, span: int) -> float:
    ell = np.arange(-span, span + 1)
    return float(np.sum(kfun(ell * dt) ** 2 + kfun((ell + m) * dt) * kfun((ell - m) * dt)) / (runs * (n - m)))


RF = ["rakhmanin-firsov-1", "rakhmanin-firsov-2", "rakhmanin-firsov-3"]
W = np.concatenate([[0.0], np.geomspace(1e-3, 1e3, 121)])


# ---- factorisation ---------------------------------------------------------------------------


@pytest.mark.parametrize("name", RF)
def test_magnitude_squared_equals_spectrum(name):
    f = sh.shaping_filter(spec(name))
    np.testing.assert_allclose(f.output_spectrum(W)[0], spec(name).one_sided(W), rtol=1e-10, atol=0)
    assert f.noise_intensity == math.pi


@pytest.mark.parametrize("name", RF)
def test_factor_is_stable_and_minimum_phase(name):
    num, den = spec(name).factor()
    assert np.all(np.roots(den).real < 0)
    assert np.all(np.roots(num).real <= 0) if len(num) > 1 else True
    # the poles are −μ ± jλ (erratum: the paper's factor has −λ ± jμ)
    np.testing.assert_allclose(sorted(np.roots(den).imag), [-LAM, LAM], rtol=1e-12)
    np.testing.assert_allclose(np.roots(den).real, [-MU, -MU], rtol=1e-12)


@pytest.mark.parametrize("name", RF)
def test_lyapunov_variance_is_Dr(name):
    f = sh.shaping_filter(spec(name))
    p = linalg.solve_continuous_lyapunov(f.A, -math.pi * f.B @ f.B.T)
    assert (f.C @ p @ f.C.T).item() == pytest.approx(D, rel=1e-10)
    assert f.output_variance()[0] == pytest.approx(D, rel=1e-10)


def test_slope_filter_eq5():
    f = sh.shaping_filter(spec("rakhmanin-firsov-2"), ("ordinate", "ordinate_rate", "slope"))
    base = spec("rakhmanin-firsov-2").one_sided(W)
    np.testing.assert_allclose(f.output_spectrum(W)[2], W**2 / GRAVITY**2 * base, rtol=1e-10, atol=0)
    np.testing.assert_allclose(f.output_variance(), [D, A2 * D, A2 * D / GRAVITY**2], rtol=1e-10)
    assert f.units == ("m", "m/s", "rad")


@pytest.mark.parametrize("name", RF)
def test_output_covariance_matches_correlation_function(name):
    f = sh.shaping_filter(spec(name))
    tau = np.array([0.0, 0.3, 1.0, 2.7, 8.0])
    np.testing.assert_allclose(f.output_covariance(tau)[0], K(name, tau), rtol=1e-9, atol=1e-12)


def test_biproper_and_improper_outputs():
    f = sh.shaping_filter(spec("rakhmanin-firsov-2"), ("slope_rate",))
    assert f.D[0, 0] != 0 and math.isinf(f.output_variance()[0])
    base = spec("rakhmanin-firsov-2").one_sided(W)
    np.testing.assert_allclose(f.output_spectrum(W)[0], W**4 / GRAVITY**2 * base, rtol=1e-9, atol=0)
    with pytest.raises(ParameterError, match="feedthrough.*rolloff"):
        f.discretize(0.1)
    with pytest.raises(ParameterError, match="improper.*rolloff"):
        sh.shaping_filter(spec("rakhmanin-firsov-2"), ("slope_acceleration",))
    with pytest.raises(ParameterError, match="improper"):
        sh.shaping_filter(spec("rakhmanin-firsov-1"), ("slope_rate",))


@pytest.mark.parametrize("order_out,k", [("slope_rate", 2), ("slope_acceleration", 3)])
def test_rolloff_band_limits(order_out, k):
    wc = 4.0
    f = sh.shaping_filter(spec("rakhmanin-firsov-2"), ("ordinate", order_out), rolloff=wc)
    r = k - 1  # least order making ω^(2k)·ω^(-4)·|L|² integrable with |L|² ~ ω^(-2r)
    lowpass = (wc**2 / (W**2 + wc**2)) ** r
    base = spec("rakhmanin-firsov-2").one_sided(W)
    np.testing.assert_allclose(f.output_spectrum(W)[1], W ** (2 * k) / GRAVITY**2 * base * lowpass, rtol=1e-8, atol=1e-300)

    def integrand(w):
        return w ** (2 * k) / GRAVITY**2 * float(spec("rakhmanin-firsov-2").one_sided(w)) * (wc**2 / (w**2 + wc**2)) ** r

    ref = sum(integrate.quad(integrand, a, b, limit=400)[0] for a, b in [(0, 1), (1, 10), (10, np.inf)])
    assert f.output_variance()[1] == pytest.approx(ref, rel=1e-7)


@pytest.mark.parametrize("dt", [0.05, 1.0, 7.0])
def test_van_loan_against_quadrature(dt):
    f = sh.shaping_filter(spec("rakhmanin-firsov-1"))
    d = f.discretize(dt)
    np.testing.assert_allclose(d.transition, linalg.expm(f.A * dt), rtol=1e-12)
    q = math.pi * f.B @ f.B.T
    x, wts = np.polynomial.legendre.leggauss(40)  # Gauss–Legendre on [0, dt]
    ref = np.zeros_like(q)
    for si, wi in zip(0.5 * dt * (x + 1), wts):
        e = linalg.expm(f.A * si)
        ref += 0.5 * dt * wi * e @ q @ e.T
    np.testing.assert_allclose(d.noise_covariance, ref, rtol=1e-8, atol=1e-14)
    p = d.stationary_covariance
    np.testing.assert_allclose(d.transition @ p @ d.transition.T + d.noise_covariance, p, rtol=1e-10, atol=1e-12)


@pytest.mark.parametrize("dt", [0.05, 1.0])
def test_discrete_autocovariance_is_exact(dt):
    f = sh.shaping_filter(spec("rakhmanin-firsov-2"))
    d = f.discretize(dt)
    m = np.arange(0, int(10 / dt) + 1, max(1, int(0.5 / dt)))
    got = [(d.output @ np.linalg.matrix_power(d.transition, k) @ d.stationary_covariance @ d.output.T).item() for k in m]
    np.testing.assert_allclose(got, K("rakhmanin-firsov-2", m * dt), rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("name", RF)
@pytest.mark.parametrize("dt", [0.05, 1.0, 10.0])
def test_generator_form_autocovariance_is_exact(name, dt):
    """The sampling recursion y_k = C x_k + G_y z_k, x_{k+1} = Φ x_k + G_x z_k, x_0 = F z
    has Cov(y_{k+m}, y_k) = C Φ^m Σ Cᵀ + C Φ^(m−1) G_x G_yᵀ (m ≥ 1), Var = C Σ Cᵀ + G_y G_yᵀ,
    Σ = F Fᵀ; it must equal K(mΔt) whichever form (innovations or state) is used."""
    for outputs, form in ((("ordinate",), "innovations"), (("ordinate", "ordinate_rate"), "state")):
        if name != "rakhmanin-firsov-2" and len(outputs) == 2:
            continue  # the ordinate rate of variants 1 and 3 has white-noise feedthrough
        d = sh.shaping_filter(spec(name), outputs).discretize(dt)
        assert d.form == form
        c, phi, gx, gy, f0 = d.output[:1], d.transition, d.state_noise_gain, d.output_noise_gain[:1], d.initial_factor
        sigma = f0 @ f0.T
        np.testing.assert_allclose(phi @ sigma @ phi.T + gx @ gx.T, sigma, rtol=1e-9, atol=1e-13)
        got = [(c @ sigma @ c.T + gy @ gy.T).item()]
        for m in range(1, 12):
            pm = np.linalg.matrix_power(phi, m)
            got.append((c @ pm @ sigma @ c.T + c @ np.linalg.matrix_power(phi, m - 1) @ gx @ gy.T).item())
        np.testing.assert_allclose(got, K(name, np.arange(12) * dt), rtol=1e-8, atol=1e-12 * D)


@pytest.mark.parametrize("name", ["rakhmanin-firsov-1", "rakhmanin-firsov-2"])
@pytest.mark.parametrize("dt,seed", [(0.05, 11), (1.0, 12)])
def test_sample_variance_and_autocovariance(name, dt, seed):
    runs, duration = 16, 5000.0
    res = sh.shaping_filter(spec(name)).sample(duration=duration, dt=dt, seed=seed, runs=runs)
    x = res["ordinate"]
    n = x.shape[1]
    assert x.shape == (runs, int(round(duration / dt)) + 1)
    kk = K(name, np.arange(n) * dt)
    cut = int(min(n, 80.0 / dt))  # K negligible beyond 80 s (e^{−μ·80} ≈ 4e−8)
    sd_var = math.sqrt(var_of_variance(kk[:cut], n, runs))
    assert abs(np.mean(x**2) - D) < 5 * sd_var
    sd_mean = math.sqrt((kk[0] + 2 * np.sum((1 - np.arange(1, cut) / n) * kk[1:cut])) / (runs * n))
    assert abs(np.mean(x)) < 5 * sd_mean
    for tau in (0.0, 1.0, 2.0, 3.0, 5.0):
        m = int(round(tau / dt))
        c = np.mean(x[:, : n - m] * x[:, m:])
        sd = math.sqrt(var_of_lag(lambda t: K(name, t), dt, m, n, runs, cut))
        assert abs(c - K(name, m * dt)) < 5 * sd, (tau, c, K(name, m * dt), sd)


def test_sample_slope_variance():
    runs = 16
    res = sh.shaping_filter(spec("rakhmanin-firsov-2"), ("ordinate", "slope")).sample(
        duration=4000.0, dt=0.2, seed=5, runs=runs
    )
    np.testing.assert_allclose(res.variance_expected, [D, A2 * D / GRAVITY**2], rtol=1e-10)
    s = res["slope"]
    # slope = ζ̇/g with covariance (a²D/g²) e^{−μτ}(cos λτ − (μ/λ) sin λτ)
    n = s.shape[1]
    tau = np.arange(int(80 / 0.2)) * 0.2
    ks = A2 / GRAVITY**2 * K("rakhmanin-firsov-3", tau)
    sd = math.sqrt(var_of_variance(ks, n, runs))
    assert abs(np.mean(s**2) - A2 * D / GRAVITY**2) < 5 * sd


@pytest.mark.parametrize("name", ["rakhmanin-firsov-1", "rakhmanin-firsov-2"])
def test_welch_matches_aliased_spectrum(name):
    dt, runs, nper = 0.25, 8, 2048
    res = sh.shaping_filter(spec(name)).sample(n_steps=1 << 17, dt=dt, seed=21, runs=runs)
    f_hz, pxx = signal.welch(res["ordinate"], fs=1 / dt, nperseg=nper, axis=-1)
    est = pxx.mean(axis=0) / (2 * math.pi)  # per Hz → one-sided per rad/s
    omega = 2 * math.pi * f_hz
    band = (omega > 0.2) & (omega < 3.0)
    wn = math.pi / dt
    k = np.arange(-200, 201)
    ref = np.array([np.sum(spec(name).one_sided(np.abs(w + 2 * k * wn))) for w in omega[band]])
    nseg = 2 * ((1 << 17) // nper) - 1
    rel_sd = math.sqrt(1.06 / (nseg * runs))
    ratio = est[band] / ref
    assert np.all(np.abs(ratio - 1) < 5 * rel_sd + 0.02)
    assert abs(np.mean(ratio) - 1) < 0.02


# ---- seeding, batching, threads -----------------------------------------------------------------


def test_batch_equals_runs_one_by_one():
    f = sh.shaping_filter(spec("rakhmanin-firsov-2"), ("ordinate", "slope"))
    batch = f.sample(n_steps=3000, dt=0.1, seed=7, runs=4)
    children = np.random.SeedSequence(7).spawn(4)
    for i, child in enumerate(children):
        one = f.sample(n_steps=3000, dt=0.1, seed=[child], runs=1)
        np.testing.assert_array_equal(one.values[0], batch.values[i])
    again = f.sample(n_steps=3000, dt=0.1, seed=7, runs=4, workers=1, chunk=777)
    np.testing.assert_array_equal(again.values, batch.values)
    other = f.sample(n_steps=3000, dt=0.1, seed=8, runs=4)
    assert not np.array_equal(other.values, batch.values)
    assert batch.seed == 7


def test_generator_seed_and_xarray():
    f = sh.shaping_filter(spec("rakhmanin-firsov-2"))
    a = f.sample(duration=10.0, dt=0.5, seed=np.random.default_rng(3), runs=2)
    b = f.sample(duration=10.0, dt=0.5, seed=np.random.default_rng(3), runs=2)
    np.testing.assert_array_equal(a.values, b.values)
    assert a.values.shape == (2, 21, 1)
    ds = a.to_xarray()
    assert ds["ordinate"].dims == ("run", "time")
    assert ds["ordinate"].attrs["units"] == "m"
    np.testing.assert_allclose(ds["time"].values, np.arange(21) * 0.5)
    with pytest.raises(KeyError, match="valid: ordinate"):
        a["slope"]


# ---- python-control export -------------------------------------------------------------------


def test_to_control_frequency_response():
    ct = pytest.importorskip("control")
    f = sh.shaping_filter(spec("rakhmanin-firsov-1"), ("ordinate", "slope"))
    sys_ = f.to_control()
    assert isinstance(sys_, ct.StateSpace)
    w = np.array([0.1, 1.0, 3.0])
    resp = sys_(1j * w)  # shape (outputs, inputs, freqs)
    num, den = spec("rakhmanin-firsov-1").factor()
    ref = np.polyval(num, 1j * w) / np.polyval(den, 1j * w)
    np.testing.assert_allclose(resp[0, 0], ref, rtol=1e-12)
    np.testing.assert_allclose(resp[1, 0], ref * 1j * w / GRAVITY, rtol=1e-12)


def test_to_control_missing(monkeypatch):
    monkeypatch.setitem(sys.modules, "control", None)
    with pytest.raises(MissingDependencyError, match=r"seahelm\[control\]"):
        sh.shaping_filter(spec("rakhmanin-firsov-1")).to_control()


# ---- bad inputs ----------------------------------------------------------------------------


@pytest.mark.parametrize("dt,match", [(0.0, "> 0"), (-0.1, "> 0"), (float("nan"), "finite"), (math.inf, "finite")])
def test_bad_dt(dt, match):
    f = sh.shaping_filter(spec("rakhmanin-firsov-2"))
    with pytest.raises(ParameterError, match=f"`dt` must be {match}"):
        f.sample(n_steps=10, dt=dt, seed=0)
    with pytest.raises(ParameterError, match="`dt`"):
        f.discretize(dt)


def test_bad_sampling_arguments():
    f = sh.shaping_filter(spec("rakhmanin-firsov-2"))
    with pytest.raises(ParameterError, match="`runs`"):
        f.sample(n_steps=10, dt=0.1, runs=0)
    with pytest.raises(ParameterError, match="exactly one of"):
        f.sample(n_steps=10, duration=1.0, dt=0.1)
    with pytest.raises(ParameterError, match="`duration` must be > 0"):
        f.sample(duration=-1.0, dt=0.1)
    with pytest.raises(ParameterError, match="`n_steps`"):
        f.sample(n_steps=0, dt=0.1)
    with pytest.raises(ParameterError, match="per-run seeds"):
        f.sample(n_steps=10, dt=0.1, runs=2, seed=[1])


def test_bad_filter_requests():
    with pytest.raises(ParameterError, match="unknown output 'heave'.*'slope'"):
        sh.shaping_filter(spec("rakhmanin-firsov-2"), ("heave",))
    with pytest.raises(ParameterError, match="no finite-order rational factor"):
        sh.shaping_filter(sp.Jonswap(significant_height=2.0, peak_period=8.0))
    with pytest.raises(ParameterError, match="`rolloff` must be > 0"):
        sh.shaping_filter(spec("rakhmanin-firsov-2"), ("slope_rate",), rolloff=-1.0)
    with pytest.raises(ParameterError, match="`decay_rate` must be > 0"):
        sh.shaping_filter("rakhmanin-firsov-2", variance=D, decay_rate=0.0, resonance_frequency=LAM)
