"""seahelm's wave spectra against the expressions of MSS's ``waveSpectrum.m`` (Fossen, Marine
Systems Simulator, LIBRARY/environment/waveSpectrum.m), typed here from that file (MSS itself
does not run in this suite). Quoted on ``docs/guide/coming-from.rst``.

* type 7, JONSWAP (H_s, ω₀, γ): S = (1 − 0.287 ln γ) (5/16) H_s² ω₀⁴ ω⁻⁵ exp(−(5/4)(ω₀/ω)⁴)
  γ^exp(−(ω − ω₀)²/(2 σ² ω₀²)), σ = 0.07 below ω₀, 0.09 above (DNV's normalisation);
* type 2, Pierson–Moskowitz (V₂₀): S = A ω⁻⁵ exp(−B ω⁻⁴), A = 8.1·10⁻³ g², B = 0.74 (g/V₂₀)⁴,
  g = 9.81, against seahelm's PM of the same H_s = 4 √(A/(4B));
* type 3, ITTC-modified PM (H_s, T₀): A = 487 H_s²/T₀⁴, B = 1949/T₀⁴ — MSS's constants are
  5(2π)⁴/16 = 487.05 and 5(2π)⁴/4 = 1948.2 rounded, so seahelm's ``ittc`` and ``bretschneider``
  with the peak period T_p = T₀ differ by 8·10⁻⁴ of the peak, and agree to rounding with the
  unrounded constants.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.environment.spectra import get_spectrum

W = np.linspace(0.1, 3.0, 600)  # [rad/s]
G_MSS = 9.81


def _peak_relative(got: np.ndarray, want: np.ndarray) -> float:
    return float(np.max(np.abs(got - want)) / np.max(want))


@pytest.mark.parametrize("hs, w0, gamma", [(4.0, 0.7, 3.3), (2.0, 1.1, 1.0), (6.0, 0.5, 7.0),
                                           (1.0, 0.9, 2.0)])
def test_jonswap_equals_mss_type_7(hs, w0, gamma):
    sigma = np.where(W < w0, 0.07, 0.09)
    want = ((1.0 - 0.287 * math.log(gamma)) * (5.0 / 16.0) * hs**2 * w0**4 * W**-5
            * np.exp(-1.25 * (w0 / W) ** 4)
            * gamma ** np.exp(-((W - w0) ** 2) / (2.0 * (sigma * w0) ** 2)))
    s = get_spectrum("jonswap", significant_height=hs, peak_period=2.0 * math.pi / w0,
                     gamma=gamma)
    assert _peak_relative(s.one_sided(W), want) < 1e-12


@pytest.mark.parametrize("wind", [10.0, 15.0, 25.0])
def test_pierson_moskowitz_equals_mss_type_2(wind):
    a, b = 8.1e-3 * G_MSS**2, 0.74 * (G_MSS / wind) ** 4
    want = a * W**-5 * np.exp(-b / W**4)
    hs = 4.0 * math.sqrt(a / (4.0 * b))  # m0 = A/(4B)
    s = get_spectrum("pierson-moskowitz", significant_height=hs, gravity=G_MSS)
    assert _peak_relative(s.one_sided(W), want) < 1e-12


@pytest.mark.parametrize("name", ["ittc", "bretschneider"])
@pytest.mark.parametrize("hs, t0", [(4.0, 9.0), (2.0, 6.0), (7.0, 13.0)])
def test_ittc_against_mss_type_3(name, hs, t0):
    s = get_spectrum(name, significant_height=hs, peak_period=t0).one_sided(W)
    mss = 487.0 * hs**2 / t0**4 * W**-5 * np.exp(-1949.0 / t0**4 / W**4)
    assert 5e-4 < _peak_relative(s, mss) < 1e-3  # MSS's rounded constants
    c = (2.0 * math.pi) ** 4
    exact = 5.0 * c / 16.0 * hs**2 / t0**4 * W**-5 * np.exp(-1.25 * c / t0**4 / W**4)
    assert _peak_relative(s, exact) < 1e-12
