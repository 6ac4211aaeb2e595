"""The shipped capytaine database of a ship hull (Wigley I, L 3 m, zero speed), the closed form
of Jensen, Mansour & Olsen (2004) against it, its Smith factor and the short-wave reduction of
its roll excitation.

capytaine is not imported: the file was made by tools/capytaine/make_wigley_database.py. The
expected values come from the file (capytaine's RAOs and matrices), from the long-wave limits
of a floating body, or from formulas typed here independently of seahelm's code; the agreement
of the closed form with the panel method is asserted with the measured differences
(docs/guide/waves-motions.rst, "A ship hull: Wigley I") plus a margin, so that a regression of
the closed form fails."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.constants import GRAVITY
from seahelm.environment.rao import closed_form_rao, roll_slope_factor
from seahelm.environment.rao_io import box_barge_database, read_rao, wigley_database
from seahelm.errors import ParameterError, ValidityRangeWarning
from seahelm.vessels.particulars import Particulars

L, B, T, CB = 3.0, 0.3, 0.1875, 0.5607  # C_b by quadrature of the hull formula (Journée 0.561)
WIGLEY = Particulars(length=L, beam=B, draft=T, block_coefficient=CB)


@pytest.fixture(scope="module")
def bem():
    return read_rao(wigley_database())


@pytest.fixture(scope="module")
def dataset():
    import xarray as xr

    return xr.load_dataset(wigley_database())


def column(rao, dof, heading_deg):
    j = int(np.argmin(np.abs(np.degrees(rao.heading) - heading_deg)))
    assert abs(math.degrees(rao.heading[j]) - heading_deg) < 1e-9
    return rao.values[rao.dofs.index(dof), :, j]


def closed(bem, **kw):
    return closed_form_rao(WIGLEY, 0.0, frequency=bem.frequency, heading=bem.heading, **kw)


def test_the_shipped_file_is_wigley_i(bem, dataset):
    path = wigley_database()
    assert path.is_file() and path.stat().st_size < 300_000
    assert bem.dofs == ("surge", "sway", "heave", "roll", "pitch", "yaw")
    np.testing.assert_allclose(bem.frequency, 1.5 + 0.25 * np.arange(27), atol=1e-12)
    np.testing.assert_allclose(np.degrees(bem.heading), np.arange(0.0, 181.0, 15.0), atol=1e-9)
    assert bem.speed == 0.0 and "capytaine 3.0.0" in bem.provenance
    # the heave stiffness is ρ g A_wp of the formula: A_wp = L B ∫0^1 (1 - ξ²)(1 + 0.2 ξ²) dξ
    # = L B (1 - 0.8/3 - 0.04) (analytic)
    c33 = float(dataset["hydrostatic_stiffness"].sel(influenced_dof="Heave",
                                                      radiating_dof="Heave"))
    assert c33 == pytest.approx(1025.0 * GRAVITY * L * B * (1 - 0.8 / 3 - 0.04), rel=1e-9)
    # C_b = ∫∫ η over the unit square: (2/3)(1 - 0.8/3 - 0.04) + (1/3 - 1/11)(128/315)
    assert CB == pytest.approx(2 / 3 * (1 - 0.8 / 3 - 0.04) + (1 / 3 - 1 / 11) * 128 / 315,
                               abs=1e-4)


def test_long_waves_the_hull_follows_the_surface(bem):
    """ω = 1.5 rad/s (λ = 9.1 L): heave ζ, pitch the slope along (within 3 %), roll the slope
    across (within 7 %: measured 5.4 % at 30°, the roll resonance is near), phases within 1°."""
    w = bem.frequency[0]
    k = w * w / GRAVITY
    for deg in range(0, 181, 15):
        eps = math.radians(deg)
        ratios = [(column(bem, "heave", deg)[0], 0.03)]
        if abs(math.cos(eps)) > 0.3:
            ratios.append((column(bem, "pitch", deg)[0] / (-1j * k * math.cos(eps)), 0.03))
        if math.sin(eps) > 0.45:
            ratios.append((column(bem, "roll", deg)[0] / (1j * k * math.sin(eps)), 0.07))
        for r, tol in ratios:
            assert abs(abs(r) - 1.0) < tol, (deg, r)
            assert abs(math.degrees(np.angle(r))) < 1.0, (deg, r)


def test_the_hull_is_symmetric_fore_and_aft(bem):
    """|H(ε)| = |H(π - ε)| at zero speed (measured within 5e-4 relative: capytaine's solver)."""
    for dof in ("heave", "pitch", "roll"):
        a = bem.amplitude(dof)
        np.testing.assert_allclose(a, a[:, ::-1], rtol=2e-3, atol=1e-9 * a.max())


def _half_frequency(w, h):
    """The first frequency at which |H| falls to half its long-wave value (linear)."""
    i = int(np.nonzero(h < 0.5 * h[0])[0][0])
    return float(np.interp(0.5 * h[0], [h[i], h[i - 1]], [w[i], w[i - 1]]))


# heading [deg]: (long waves λ >= 2L: largest relative difference, all ω: largest absolute
# difference, relative shift of the half-amplitude frequency), measured (docs table), default
# Smith factor exp(-kT)
HEAVE = {180.0: (0.088, 0.265, -0.080), 150.0: (0.055, 0.334, -0.067),
         120.0: (0.008, 0.537, -0.136)}
PITCH = {180.0: (0.068, 0.189, -0.042), 150.0: (0.054, 0.233, -0.022),
         120.0: (0.026, 0.496, -0.203)}


@pytest.mark.parametrize("dof, table", [("heave", HEAVE), ("pitch", PITCH)])
def test_closed_form_heave_and_pitch_against_the_panel_method(bem, dof, table):
    """|H| (pitch as |H|/k) against capytaine in head, bow and bow-quartering seas (the same at
    ε and π - ε at zero speed): long waves within the measured relative difference + 2 points,
    the whole range within the measured absolute difference + 25 %, the half-amplitude
    frequency within the measured shift ± 2.5 points."""
    rao = closed(bem)
    w = bem.frequency
    k = w * w / GRAVITY
    long = w <= math.sqrt(math.pi * GRAVITY / L)
    for deg, (rel, ab, shift) in table.items():
        for d in (deg, 180.0 - deg):
            hb, hc = np.abs(column(bem, dof, d)), np.abs(column(rao, dof, d))
            if dof == "pitch":
                hb, hc = hb / k, hc / k
            assert np.max(np.abs(hc[long] - hb[long]) / hb[long]) <= rel + 0.02, d
            assert np.max(np.abs(hc - hb)) <= 1.25 * ab, d
            measured = _half_frequency(w, hc) / _half_frequency(w, hb) - 1.0
            assert abs(measured - shift) <= 0.025, (d, measured)


def test_the_closed_forms_heave_resonance_is_low_for_a_fine_hull(bem, dataset):
    """Jensen et al.'s ω_n² = g/(2T) (5.11 rad/s) takes the stiffness of the breadth C_b B; the
    hull's is C_wp B (C_wp/C_b = 1.24) with an added mass below the displaced mass, so its
    natural frequency √(C33/(m + A33)) (a fixed point, from the file's matrices) is about
    6.6 rad/s, where capytaine's beam-sea heave peaks (within the 0.25 rad/s grid): the
    closed form's is 20-25 % low. Documented, not corrected: it is the published model."""
    sel = dict(influenced_dof="Heave", radiating_dof="Heave")
    a33 = dataset["added_mass"].sel(**sel)
    m = float(dataset["inertia_matrix"].sel(**sel))
    c33 = float(dataset["hydrostatic_stiffness"].sel(**sel))
    wn = 6.0
    for _ in range(50):
        wn = math.sqrt(c33 / (m + float(a33.interp(omega=wn))))
    heave = np.abs(column(bem, "heave", 90.0))
    assert abs(bem.frequency[np.argmax(heave)] - wn) <= 0.25
    jensen = math.sqrt(GRAVITY / (2 * T))
    assert 0.75 <= jensen / wn <= 0.80


# --- the Smith factor -----------------------------------------------------------------------

def _jensen_heave(w, eps, kappa_wavenumber):
    """Jensen et al.'s heave at zero speed typed from the paper's symbols (α = 1)."""
    k = w * w / GRAVITY
    be = CB * B
    a = 2 * np.sin(k * be / 2) * np.exp(-k * T)
    f = (1 - k * T) + 1j * a * a / (k * be)
    d = (1 - 2 * k * T) + 1j * a * a / (k * be)
    ke = abs(k * math.cos(eps))
    sig = ke * L / 2
    sinc = np.where(sig > 0, np.sin(sig) / np.where(sig > 0, sig, 1), 1.0)
    return np.exp(-kappa_wavenumber(k, ke) * T) * f * sinc / d


def test_the_smith_factor_is_exp_minus_kT_by_default_and_exp_minus_keT_selectable():
    w = np.linspace(0.5, 8.0, 31)
    for deg in (90.0, 60.0, 150.0, 180.0):
        eps = math.radians(deg)
        for smith, kw in (("k", lambda k, ke: k), ("k_e", lambda k, ke: ke)):
            rao = closed_form_rao(WIGLEY, 0.0, frequency=w, heading=[eps], smith=smith)
            np.testing.assert_allclose(rao.values[0, :, 0], _jensen_heave(w, eps, kw),
                                       rtol=1e-12, atol=1e-14)
    # head and following seas: the two coincide
    a, b = (closed_form_rao(WIGLEY, 1.5, frequency=w, heading=[0.0, math.pi], smith=s)
            for s in ("k", "k_e"))
    np.testing.assert_allclose(a.values, b.values, rtol=1e-13, atol=1e-15)
    with pytest.raises(ParameterError, match="smith"):
        closed_form_rao(WIGLEY, 0.0, smith="ke")


def test_the_default_smith_factor_brings_the_beam_sea_heave_closer_to_the_panel_method(bem):
    """Beam seas, both shipped hulls: with exp(-kT) the long-wave heave is within 3.1 % (box)
    and 3.8 % (Wigley) of capytaine's, with exp(-k_e T) 11.2 % and 23.3 % above; the RMS
    difference over the file's frequencies falls from 0.240 to 0.187 (box) and from 0.993 to
    0.857 m/m (Wigley); the box's short-wave (>= 1.2 rad/s) heave is at most 0.349 (capytaine
    0.294) instead of 0.727. Measured; asserted with 2 points or 5 % margins."""
    box = read_rao(box_barge_database())
    hull = Particulars(length=100.0, beam=20.0, draft=5.0, block_coefficient=1.0)
    cases = ((box, hull, 0.031, 0.112, 0.187, 0.240), (bem, WIGLEY, 0.038, 0.233, 0.857, 0.993))
    for ref, p, long_k, long_ke, rms_k, rms_ke in cases:
        w = ref.frequency
        long = w <= math.sqrt(math.pi * GRAVITY / p.length)
        hb = np.abs(column(ref, "heave", 90.0))
        with pytest.warns() if p is hull else _nothing():
            got = {s: np.abs(column(closed_form_rao(p, 0.0, frequency=w, heading=ref.heading,
                                                    smith=s), "heave", 90.0))
                   for s in ("k", "k_e")}
        rel = {s: np.max(np.abs(h[long] / hb[long] - 1.0)) for s, h in got.items()}
        rms = {s: math.sqrt(np.mean((h - hb) ** 2)) for s, h in got.items()}
        assert rel["k"] <= long_k + 0.02 and rel["k_e"] >= long_ke - 0.02
        assert rms["k"] <= 1.05 * rms_k and rms["k_e"] >= 0.95 * rms_ke
    hb = np.abs(column(box, "heave", 90.0))
    short = box.frequency >= 1.2
    with pytest.warns(ValidityRangeWarning):
        h = np.abs(column(closed_form_rao(hull, 0.0, frequency=box.frequency,
                                          heading=box.heading), "heave", 90.0))
    assert hb[short].max() == pytest.approx(0.294, abs=0.001)
    assert h[short].max() <= 0.349 * 1.05


class _nothing:
    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False


# --- the roll excitation --------------------------------------------------------------------

def test_roll_slope_factor_is_the_froude_krylov_moment_over_the_bottom():
    """γ against a direct quadrature of the bottom pressure's roll moment, ∫∫ y exp(i k (x cos
    ε + y sin ε)) dx dy over the box L × B, times exp(-kT), over its long-wave value
    i k sin ε L B³/12 (midpoint rule, 400 × 400 cells); γ → 1 as k → 0."""
    nx = ny = 400
    x = (np.arange(nx) + 0.5) / nx * L - L / 2
    y = (np.arange(ny) + 0.5) / ny * B - B / 2
    for k in (0.5, 2.0, 5.0, 9.0):
        for deg in (15.0, 45.0, 90.0, 150.0):
            eps = math.radians(deg)
            phase = np.exp(1j * k * (x[:, None] * math.cos(eps) + y[None, :] * math.sin(eps)))
            moment = np.sum(y[None, :] * phase) * (L / nx) * (B / ny) * math.exp(-k * T)
            ref = moment / (1j * k * math.sin(eps) * L * B ** 3 / 12)
            got = roll_slope_factor(k, eps, L, B, T)
            assert abs(got - ref) < 2e-4, (k, deg, got, ref)
    assert float(roll_slope_factor(1e-9, 1.0, L, B, T)) == pytest.approx(1.0, abs=1e-8)


def test_roll_excitation_averaged_by_default_and_the_full_slope_selectable():
    w = np.linspace(0.5, 8.0, 16)
    eps = np.radians([30.0, 90.0, 135.0])
    new, old = (closed_form_rao(WIGLEY, 0.5, frequency=w, heading=eps, metacentric_height=0.04,
                                roll_excitation=r) for r in ("averaged", "slope"))
    k = (w * w / GRAVITY)[:, None]
    np.testing.assert_allclose(new.values[1], old.values[1] * roll_slope_factor(
        k, eps[None, :], L, B, T), rtol=1e-12, atol=1e-15)
    assert np.all(new.amplitude("roll") <= old.amplitude("roll") * (1 + 1e-12))
    with pytest.raises(ParameterError, match="roll_excitation"):
        closed_form_rao(WIGLEY, 0.0, metacentric_height=0.04, roll_excitation="full")


def _effective_roll_excitation(dataset, deg):
    """|X_roll (C44 − ω²(I44 + A44) − iω B44)| / (C44 k sin ε): the fraction of the wave slope
    a one-degree-of-freedom roll equation needs to give capytaine's roll (capytaine's e^{-iωt}
    convention; independent of the damping)."""
    sel = dict(influenced_dof="Roll", radiating_dof="Roll")
    c44 = float(dataset["hydrostatic_stiffness"].sel(**sel))
    i44 = float(dataset["inertia_matrix"].sel(**sel))
    a44 = dataset["added_mass"].sel(**sel).values
    b44 = dataset["radiation_damping"].sel(**sel).values
    w = dataset.omega.values
    j = int(np.argmin(np.abs(dataset.wave_direction.values - math.radians(deg))))
    rao = dataset["RAO"].sel(complex="re") + 1j * dataset["RAO"].sel(complex="im")
    x = rao.sel(radiating_dof="Roll").transpose("omega", "wave_direction").values[:, j]
    k = w * w / GRAVITY
    return w, np.abs(x * (c44 - w * w * (i44 + a44) - 1j * w * b44)) / (
        c44 * k * math.sin(math.radians(deg)))


# heading [deg]: (lowest and highest γ − r below the roll resonance, ω <= 4.5 rad/s), measured
ROLL = {30.0: (-0.243, -0.010), 45.0: (-0.161, -0.006), 60.0: (-0.081, -0.003),
        90.0: (-0.025, 0.149)}


@pytest.mark.parametrize("deg", sorted(ROLL))
def test_the_averaged_roll_excitation_against_the_panel_method(dataset, deg):
    """Below the Wigley's roll resonance (5.0 rad/s; ω <= 4.5 rad/s, λ >= 1.01 L) γ lies within
    the measured band of capytaine's effective fraction r of the wave slope (± 0.03), where
    the full slope (γ = 1) is up to 0.48-0.65 too high; r → 1 in long waves (within 5 %)."""
    w, r = _effective_roll_excitation(dataset, deg)
    lo, hi = ROLL[deg]
    below = w <= 4.5
    gamma = np.abs(roll_slope_factor(w * w / GRAVITY, math.radians(deg), L, B, T))
    d = (gamma - r)[below]
    assert lo - 0.03 <= d.min() and d.max() <= hi + 0.03, (d.min(), d.max())
    assert np.max(1.0 - r[below]) >= 0.45
    assert abs(r[0] - 1.0) <= 0.05
