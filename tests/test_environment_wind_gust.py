"""Wind gusts from the NORSOK spectrum: its published shape, the realisations' statistics and
seeding, and the scenario's gust signal."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import quad

from seahelm.environment.wind_gust import F_MIN, gust_realisation, norsok_spectrum
from seahelm.errors import ParameterError, ValidityRangeWarning
from seahelm.simulation.signals import make_signal


def test_norsok_spectrum_shape():
    # at 10 m and U = 10 m/s the low-frequency plateau is 320 m²/s²/Hz
    assert norsok_spectrum(0.0, 10.0) == pytest.approx(320.0, rel=1e-15)
    # Kolmogorov's inertial range: S ∝ f^(-5/3) as f grows (slowly: x^0.468 >> 1)
    f = np.array([1000.0, 2000.0])
    s = norsok_spectrum(f, 15.0)
    assert math.log(s[1] / s[0]) / math.log(2.0) == pytest.approx(-5.0 / 3.0, abs=0.01)
    f = np.array([2.0, 4.0])
    # stronger wind, more energy at every frequency; the plateau scales with U²
    assert np.all(norsok_spectrum(f, 20.0) > norsok_spectrum(f, 10.0))
    assert norsok_spectrum(0.0, 20.0) == pytest.approx(4.0 * 320.0)
    with pytest.raises(ParameterError, match=r"`mean_speed` must be > 0 \[m/s\]"):
        norsok_spectrum(0.1, 0.0)


def test_realisations_have_the_spectrum_variance_and_zero_mean():
    u0, dt = 15.0, 0.5
    t = np.arange(0.0, 3600.0, dt)
    want = quad(lambda f: float(norsok_spectrum(f, u0)), F_MIN, 1.0, limit=200)[0]
    draws = np.array([gust_realisation(t, u0, seed) for seed in range(40)])
    # the variance of the sum of components is the band's integral: the ensemble of
    # realisations (each hour's own mean removed: the slowest components) matches it
    var = np.mean(np.var(draws, axis=1)) + np.var(draws.mean(axis=1))
    assert var == pytest.approx(want, rel=0.15)
    assert abs(draws.mean()) < 0.2 * math.sqrt(want)
    # reproducible per seed, different across seeds
    np.testing.assert_array_equal(draws[3], gust_realisation(t, u0, 3))
    assert not np.allclose(draws[3], draws[4])


def test_gust_signal_and_scenario_mean_speed_from_the_wind_section():
    sig = make_signal({"kind": "gust", "mean_speed": 12.0, "seed": 2})
    t = np.arange(0.0, 600.0, 0.5)
    np.testing.assert_array_equal(sig(t), gust_realisation(t, 12.0, 2))
    with pytest.raises(ParameterError, match="unknown gust spectrum 'davenport'"):
        make_signal({"kind": "gust", "mean_speed": 12.0, "spectrum": "davenport"})

    from seahelm.scenario import parse_scenario

    text = ('[vessel]\ncatalog = "kvlcc2-l7"\n[actuator]\nmodel = "rudder-servo"\n'
            '[controller]\nmodel = "open-loop"\n[controller.reference]\nrudder_command_deg = 0.0'
            '\npropeller_rps = 10.4\n[environment.wind]\nspeed = 14.0\ndirection_deg = 90\n'
            'gust = {kind = "gust", seed = 5}\n[simulation]\nt_final = 60.0\ndt = 0.5\n'
            '[batch.grid]\n"environment.wind.speed" = [8.0, 14.0]\n')
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityRangeWarning)
        batch = parse_scenario(text)
    tg = np.arange(121) * 0.5
    d = batch.disturbance(tg)
    j = list(batch.model.disturbance_labels + batch.environment.signal_labels).index("wind_gust")
    # each run's gust has its run's mean speed (8 m/s: less energy than 14 m/s)
    assert np.std(d[0, :, j]) < np.std(d[1, :, j])
