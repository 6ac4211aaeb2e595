"""The polar seakeeping diagram's colour bar: round level boundaries (matplotlib's locator)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.plotting.seakeeping import contour_levels, plot_polar_diagram


def _round_step(values: np.ndarray) -> float:
    """The common step of equally spaced values, checked to be 1, 2, 2.5 or 5 x 10^k and the
    values its whole multiples."""
    step = float(np.diff(values)[0])
    np.testing.assert_allclose(np.diff(values), step, rtol=1e-9)
    mantissa = step / 10.0 ** math.floor(math.log10(step))
    assert min(abs(mantissa - m) for m in (1.0, 2.0, 2.5, 5.0, 10.0)) < 1e-9, step
    np.testing.assert_allclose(values / step, np.round(values / step), atol=1e-9)
    return step


@pytest.mark.parametrize("low, high", [(0.013, 7.703), (0.64, 15.37), (2e-5, 3.3e-4),
                                       (-1.3, 2.2), (4.0, 4.0)])
def test_levels_are_round_and_cover_the_values(low, high):
    b = contour_levels(low, high, 12)
    _round_step(b)
    assert b[0] <= low and b[-1] >= max(high, low + 1.0 if high == low else high)
    assert len(b) - 1 <= 12


def test_colour_bar_ticks_are_round():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    eps = np.radians(np.arange(0, 360, 30.0))
    z = np.outer([0.1, 3.7, 7.69], np.abs(np.sin(eps))) + 0.013  # linspace gave 0.013, 0.654...
    ax = plot_polar_diagram([0, 4, 8], eps, z, label="RMS roll", unit="deg")
    try:
        ax.figure.canvas.draw()
        bar = ax.figure.axes[1]
        ticks = np.array([t for t in bar.get_yticks() if bar.get_ylim()[0] - 1e-12 <= t
                          <= bar.get_ylim()[1] + 1e-12])
        assert ticks.size >= 3
        assert _round_step(ticks) in (0.5, 1.0, 2.0)
        assert [t.get_text() for t in bar.get_yticklabels()][:2] == ["0", "1"]
    finally:
        plt.close(ax.figure)
