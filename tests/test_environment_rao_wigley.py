"""The shipped capytaine database of a ship hull (Wigley I, L 3 m, zero speed).

capytaine is not imported: the file was made by tools/capytaine/make_wigley_database.py. The
expected values come from the file, the hull formula (integrated analytically here) and the
long-wave limits of a floating body."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.constants import GRAVITY
from seahelm.environment.rao_io import read_rao, wigley_database

L, B, T, CB = 3.0, 0.3, 0.1875, 0.5607  # C_b by quadrature of the hull formula (Journée 0.561)


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
