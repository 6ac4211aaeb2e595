"""First-order wave motions on a recorded manoeuvre (seahelm.environment.first_order).

Every expected value is computed here independently: the regular-wave response
a|H| cos(ω_e t + ϕ + arg H) and the closed-form phase ∫ω_e dt of a constant-rate turn, the
response variance ∫∫|H|² S D dθ dω by scipy quadrature with D typed from its formula.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate, special

from seahelm.constants import GRAVITY
from seahelm.environment.first_order import (
    WaveComponents,
    draw_wave_components,
    expected_variance,
    first_order_motions,
)
from seahelm.environment.first_order_kernel import sincos
from seahelm.environment.rao import RAO, closed_form_rao
from seahelm.environment.spectra import get_spectrum
from seahelm.errors import ParameterError
from seahelm.ships import get_ship


@pytest.fixture(scope="module")
def rao():
    return closed_form_rao(get_ship("son-nomoto-container"), 7.0, metacentric_height=0.3)


@pytest.fixture(scope="module")
def sea():
    return get_spectrum("jonswap", significant_height=4.0, peak_period=10.0)


def one_component(omega, beta, amplitude=1.3, phase=0.7, runs=1):
    full = lambda v: np.full((runs, 1), float(v))  # noqa: E731
    return WaveComponents(full(omega), full(omega ** 2 / GRAVITY), full(beta), full(amplitude),
                          full(phase), (omega, omega), [])


def test_sincos_matches_numpy():
    from numba import njit

    @njit
    def both(a, s, c):
        for i in range(a.size):
            s[i], c[i] = sincos(a[i])

    a = np.concatenate([np.random.default_rng(1).uniform(-3e4, 3e4, 100_000),
                        np.arange(-8, 9) * math.pi / 4])
    s, c = np.empty_like(a), np.empty_like(a)
    both(a, s, c)
    assert np.max(np.abs(s - np.sin(a))) < 1e-15 * 8
    assert np.max(np.abs(c - np.cos(a))) < 1e-15 * 8


@pytest.mark.parametrize("eps_deg", [180.0, 150.0, 90.0, 47.0, 10.0, 300.0])
@pytest.mark.parametrize("track", ["recorded", "dead-reckoned"])
def test_regular_wave_on_a_straight_run(rao, eps_deg, track):
    t = np.arange(0.0, 600.0, 0.1)
    U, psi0, omega, a, phi = 7.0, math.radians(35.0), 0.6, 1.3, 0.7
    beta = psi0 + math.radians(eps_deg)
    rec = {"time": t, "u": np.full(t.size, U), "psi": np.full(t.size, psi0)}
    if track == "recorded":
        rec.update(x=U * t * math.cos(psi0) + 50.0 * 0, y=U * t * math.sin(psi0))
    m = first_order_motions(rec, None, rao, wave_direction=0.0,
                            components=one_component(omega, beta, a, phi))
    eps = math.radians(eps_deg)
    we = omega - omega ** 2 * U * math.cos(eps) / GRAVITY
    for dof in ("heave", "roll", "pitch"):
        H = complex(rao(dof, omega, eps))
        expect = a * abs(H) * np.cos(we * t + phi + np.angle(H))
        assert np.max(np.abs(m[dof][0] - expect)) < 1e-9, dof


def turn(t, U, r, psi0):
    psi = psi0 + r * t
    x = U / r * (np.sin(psi) - math.sin(psi0))
    y = U / r * (math.cos(psi0) - np.cos(psi))
    return psi, x, y


def test_constant_rate_turn_phase_is_the_integral_of_the_encounter_frequency(rao):
    t = np.arange(0.0, 1200.0, 0.1)
    U, r, psi0, omega, a, phi = 7.0, 0.01, 0.3, 0.8, 1.0, 0.2
    beta = 2.0
    psi, x, y = turn(t, U, r, psi0)
    k = omega ** 2 / GRAVITY
    # ∫0^t (ω − k U cos(β − ψ0 − rτ)) dτ = ωt − (kU/r)(sin(β − ψ0) − sin(β − ψ0 − rt))
    theta = omega * t - k * U / r * (math.sin(beta - psi0) - np.sin(beta - psi))
    comp = one_component(omega, beta, a, phi)
    exact = first_order_motions({"time": t, "u": np.full(t.size, U), "psi": psi, "x": x, "y": y},
                                None, rao, wave_direction=0.0, components=comp)
    reckoned = first_order_motions({"time": t, "u": np.full(t.size, U), "psi": psi}, None, rao,
                                   wave_direction=0.0, components=comp)
    # the trapezoid rule's error on the track: |Δs| ≤ U r² T Δt²/12, times k in the phase
    bound = k * U * r ** 2 * t[-1] * 0.1 ** 2 / 12.0
    for dof in ("heave", "roll", "pitch"):
        H = rao(dof, omega, beta - psi)
        expect = np.real(a * H * np.exp(1j * (theta + phi)))
        assert np.max(np.abs(exact[dof][0] - expect)) < 1e-9
        assert np.max(np.abs(reckoned[dof][0] - expect)) <= np.max(np.abs(a * H)) * bound
    assert np.max(np.abs(reckoned["heave"][0] - exact["heave"][0])) > 1e-9  # it is tested


def straight(runs, U=7.0, psi0=0.0, hours=1.0, dt=0.1):
    t = np.arange(0.0, 3600.0 * hours, dt)
    return {"time": t, "u": np.full((runs, t.size), U), "psi": np.full((runs, t.size), psi0)}


def spectrum_integral(sea, rao, dof, eps, band, spread=None):
    """∫|H|²S dω (long-crested) or ∫∫|H|² S D dθ dω with D = cos-2s typed from its formula."""
    if spread is None:
        w = np.linspace(*band, 20001)
        return integrate.trapezoid(np.abs(rao(dof, w, eps)) ** 2 * sea.one_sided(w), w)
    s = spread
    C = special.gamma(s + 1) / (2 * math.sqrt(math.pi) * special.gamma(s + 0.5))
    w = np.linspace(*band, 1601)
    th = np.linspace(-math.pi, math.pi, 721)
    D = C * np.cos(th / 2) ** (2 * s)
    h2 = np.abs(rao(dof, w[:, None], eps + th[None, :])) ** 2
    inner = integrate.trapezoid(h2 * D, th, axis=1)
    return integrate.trapezoid(inner * sea.one_sided(w), w)


@pytest.mark.parametrize("spread", [None, 2.0])
def test_irregular_sea_variance_within_the_sampling_error(rao, sea, spread):
    """E[η²] over a record = Σ E[a_i²|H_i|²]/2 = ∫|H|²S dω exactly (frequencies uniform in
    their bins, phases uniform): the mean over R independent runs of each run's mean square
    lies within 3 σ̂/√R of it, σ̂ the sample std of the per-run mean squares. (A short-crested
    sea scatters more from run to run, one random direction per component: more components.)
    Sampled every 0.5 s: the expectation holds at any sampling, and the encounter frequencies
    (|ω_e| ≤ ω + ω²U/g < 4.9 rad/s for the band to 2 rad/s at 7 m/s) are below Nyquist's
    6.3 rad/s, so the per-run mean squares are those of the 0.1 s record (measured: the same
    z-scores and bounds to 3 digits, at a fifth of the 7 s CPU the two cases took)."""
    R = 48
    eps = math.radians(60.0)
    m = first_order_motions(straight(R, dt=0.5), sea, rao, wave_direction=math.pi + eps, seed=11,
                            n_components=64 if spread is None else 256,
                            spreading=None if spread is None else "cos-2s",
                            spreading_parameter=spread or 2.0)
    band = m.components.band
    for dof in ("heave", "roll", "pitch"):
        ms = np.mean(m[dof] ** 2, axis=1)
        expect = spectrum_integral(sea, rao, dof, eps, band, spread)
        bound = 3.0 * ms.std(ddof=1) / math.sqrt(R)
        assert abs(ms.mean() - expect) < bound, (dof, ms.mean(), expect, bound)
        assert bound < 0.15 * expect  # a bound that means something
        # (1001 Simpson points in ω and θ: within 1e-4 of this test's integral, as the
        # default 4001 are, at 1/40 of its 12 s CPU in the short-crested case)
        assert expected_variance(sea, rao, dof, eps, band=band,
                                 spreading=None if spread is None else "cos-2s",
                                 spreading_parameter=spread or 2.0,
                                 points=1001) == pytest.approx(expect, rel=1e-2)


def test_spreading_halves_beam_sea_roll_and_brings_it_into_head_seas(sea):
    """At zero speed the full-slope roll RAO is H(ω) sin ε (ω_e = ω), so with cos-2s spreading,
    s = 1 (D = (1 + cos θ)/2π): beam seas keep E[cos²θ] = 1/2 of the long-crested roll variance
    and head seas, long-crested without roll, get E[sin²θ] = 1/2 of it. (The default averaged
    slope is not separable in ε: roll_excitation="slope" keeps the premise.) Sampled every
    0.5 s, as the variance test above (ω_e = ω ≤ 2 rad/s below Nyquist's 6.3 rad/s; measured:
    the z-scores and bounds of the 0.1 s record to 3 digits, at a quarter of its 8.5 s CPU)."""
    rao = closed_form_rao(get_ship("son-nomoto-container"), 0.0, metacentric_height=0.3,
                          roll_excitation="slope")
    band = (0.1, 2.0)
    beam_long = spectrum_integral(sea, rao, "roll", math.pi / 2, band)
    for eps in (math.pi / 2, math.pi):
        spread = spectrum_integral(sea, rao, "roll", eps, band, 1.0)
        assert spread == pytest.approx(0.5 * beam_long, rel=5e-3)
    assert spectrum_integral(sea, rao, "roll", math.pi, band) < 1e-20
    R = 48
    t = np.arange(0.0, 3600.0, 0.5)
    rec = {"time": t, "u": np.zeros((R, t.size)), "psi": np.zeros((R, t.size))}
    for wave_from in (-math.pi / 2, 0.0):  # beam (from port: travelling to starboard), head
        m = first_order_motions(rec, sea, rao, wave_direction=wave_from, seed=3,
                                n_components=256, spreading="cos-2s", spreading_parameter=1.0,
                                band=band)
        ms = np.mean(m["roll"] ** 2, axis=1)
        assert abs(ms.mean() - 0.5 * beam_long) < 3.0 * ms.std(ddof=1) / math.sqrt(R)


def test_batched_run_equals_the_run_alone(rao, sea):
    t = np.arange(0.0, 300.0, 0.1)
    R = 5
    U = np.linspace(5.0, 8.0, R)[:, None] * np.ones(t.size)
    psi = np.stack([turn(t, 7.0, r, 0.1)[0] for r in np.linspace(-0.02, 0.03, R)])
    batch = first_order_motions({"time": t, "u": U, "psi": psi}, sea, rao, wave_direction=1.0,
                                seed=7, spreading="cos-n", spreading_parameter=2.0)
    child = np.random.SeedSequence(7).spawn(R)[3]
    alone = first_order_motions({"time": t, "u": U[3], "psi": psi[3]}, sea, rao,
                                wave_direction=1.0, seed=[child], spreading="cos-n",
                                spreading_parameter=2.0, threads=1)
    for dof in ("heave", "roll", "pitch"):
        np.testing.assert_array_equal(batch[dof][3], alone[dof][0])


def test_raos_at_several_speeds_are_interpolated_in_the_speed(sea):
    ship = get_ship("son-nomoto-container")
    raos = [closed_form_rao(ship, v, metacentric_height=0.3) for v in (4.0, 8.0)]
    t = np.arange(0.0, 60.0, 0.1)
    omega, beta, eps = 0.7, math.pi, math.pi
    rec = {"time": t, "u": np.full(t.size, 5.0), "psi": np.zeros(t.size),
           "x": 5.0 * t, "y": 0.0 * t}
    m = first_order_motions(rec, None, raos, wave_direction=0.0,
                            components=one_component(omega, beta, 1.0, 0.0))
    H = 0.75 * raos[0]("heave", omega, eps) + 0.25 * raos[1]("heave", omega, eps)
    we = omega + omega ** 2 * 5.0 / GRAVITY
    assert np.max(np.abs(m["heave"][0] - np.real(H * np.exp(1j * we * t)))) < 1e-9


def test_dataset_has_units_and_totals(rao, sea):
    m = first_order_motions(straight(2, hours=0.02), sea, rao, wave_direction=0.5, seed=1)
    lf_roll = np.full((2, m.time.size), 0.01)
    ds = m.to_xarray(roll=lf_roll)
    assert ds["heave"].attrs["units"] == "m" and ds["roll_wave"].attrs["units"] == "rad"
    np.testing.assert_allclose(ds["roll"].values, ds["roll_wave"].values + 0.01)
    assert "heading_total" not in ds  # no yaw RAO


def test_yaw_gives_the_total_heading():
    w, h = np.linspace(0.2, 2.0, 10), np.radians(np.arange(0, 181, 15.0))
    vals = np.ones((2, w.size, h.size), complex) * np.array([1.0, 0.01])[:, None, None]
    rao = RAO(w, h, ("heave", "yaw"), vals, 0.0)
    t = np.arange(0.0, 10.0, 0.5)
    m = first_order_motions({"time": t, "u": np.zeros(t.size), "psi": np.full(t.size, 0.4)},
                            None, rao, wave_direction=0.0,
                            components=one_component(1.0, 0.0, 2.0, 0.0))
    # ε = −0.4 rad: the half table is mirrored, and yaw changes sign (port-starboard symmetry)
    np.testing.assert_allclose(m.heading_total[0], 0.4 - 0.02 * np.cos(t), atol=1e-12)
    assert "heading_total" in m.to_xarray()


def test_components_are_seeded_and_cover_the_band(sea):
    c = draw_wave_components(sea, 0.0, runs=3, seed=5, n_components=20, band=(0.3, 1.5))
    assert c.frequency.shape == (3, 20)
    edges = np.linspace(0.3, 1.5, 21)
    assert np.all((c.frequency >= edges[:-1]) & (c.frequency < edges[1:]))
    again = draw_wave_components(sea, 0.0, runs=3, seed=5, n_components=20, band=(0.3, 1.5))
    np.testing.assert_array_equal(c.phase, again.phase)
    np.testing.assert_allclose(c.amplitude, np.sqrt(2 * sea.one_sided(c.frequency) * 0.06))


@pytest.mark.parametrize("change, match", [
    (lambda r: r.update(u=np.where(np.arange(r["time"].size) == 5, np.nan, 7.0)),
     r"motion.u.*not finite.*t = 0.5 s"),
    (lambda r: r.update(psi=np.zeros(7)), r"motion.psi.*shape"),
    (lambda r: r.update(x=np.zeros(20)), r"motion.x.*both x and y"),
    (lambda r: r.pop("u"), r"no `u`.*surge_speed"),
    (lambda r: r.update(time=np.zeros(20)), r"motion.time.*increasing"),
])
def test_bad_records(rao, change, match):
    rec = {"time": np.arange(20) * 0.1, "u": np.full(20, 7.0), "psi": np.zeros(20)}
    change(rec)
    with pytest.raises(ParameterError, match=match):
        first_order_motions(rec, None, rao, wave_direction=0.0,
                            components=one_component(0.7, 0.0))


def test_bad_raos_and_seas(rao, sea):
    rec = {"time": np.arange(20) * 0.1, "u": np.full(20, 7.0), "psi": np.zeros(20)}
    with pytest.raises(ParameterError, match=r"`rao`.*has no 'yaw'"):
        first_order_motions(rec, sea, rao, wave_direction=0.0, dofs=("heave", "yaw"))
    with pytest.raises(ParameterError, match="increasing speeds"):
        first_order_motions(rec, sea, [rao, rao], wave_direction=0.0)
    part = RAO(rao.frequency, rao.heading[18:], rao.dofs, rao.values[:, :, 18:], rao.speed)
    circle = {"time": np.arange(0.0, 700.0, 1.0), "u": np.full(700, 7.0),
              "psi": np.arange(700) * 0.01}  # turns through 400°: meets every heading
    with pytest.raises(ParameterError, match=r"`rao.heading`.*covers wave headings 90 to 180 "
                       r"deg.*run 0"):
        first_order_motions(circle, sea, part, wave_direction=0.0, seed=1)
    with pytest.raises(ParameterError, match="significant_height"):
        get_spectrum("jonswap", significant_height=-1.0, peak_period=10.0)
    with pytest.raises(ParameterError, match="one seed per run"):
        first_order_motions(straight(2, hours=0.01), sea, rao, wave_direction=0.0, seed=[1])
    with pytest.raises(ParameterError, match="unknown directional spreading"):
        first_order_motions(rec, sea, rao, wave_direction=0.0, spreading="cos-3")
    with pytest.raises(ParameterError, match=r"spreading_parameter.*in \(0, 1000\]"):
        first_order_motions(rec, sea, rao, wave_direction=0.0, spreading="cos-2s",
                            spreading_parameter=0.0)


@pytest.mark.parametrize("n", [0, 10**11, math.nan, True])
def test_component_count_is_bounded(rao, sea, n):
    """10^11 components raised a MemoryError (exit 1 from a scenario, after its runs); NaN a
    bare ValueError from int()."""
    rec = {"time": np.arange(20) * 0.1, "u": np.full(20, 7.0), "psi": np.zeros(20)}
    with pytest.raises(ParameterError, match=r"`n_components` must be an integer in "
                                             r"\[1, 100000\] \[-\]"):
        first_order_motions(rec, sea, rao, wave_direction=0.0, n_components=n)
