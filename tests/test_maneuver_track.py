"""The fast paths of a turning circle's metrics against independent computations.

:func:`seahelm.analysis.maneuvers.track_distance` computes the not-a-knot cubic spline of the
track itself (no interpolant object per call); here it is compared with
``scipy.interpolate.CubicSpline`` and Gauss–Legendre quadrature as the function did it before,
and with the analytic arc of a circle. The cubic event crossings (Newton's method on the
Lagrange cubic through four samples, compiled) are compared with the roots numpy finds for the
same cubic.
"""

from __future__ import annotations

import importlib
import math

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

from seahelm.analysis.maneuvers import track_distance

tc = importlib.import_module("seahelm.analysis.maneuvers.turning_circle")


def _reference(north: np.ndarray, east: np.ndarray, t: np.ndarray) -> np.ndarray:
    """The spline arc by scipy's CubicSpline (not-a-knot) and three-point Gauss quadrature."""
    h = np.diff(t)
    nodes, weights = np.polynomial.legendre.leggauss(3)
    at = t[:-1, None] + 0.5 * h[:, None] * (nodes + 1.0)
    dn = CubicSpline(t, north, axis=1)(at, 1)
    de = CubicSpline(t, east, axis=1)(at, 1)
    pieces = 0.5 * h * (np.hypot(dn, de) @ weights)
    return np.concatenate([np.zeros((north.shape[0], 1)), np.cumsum(pieces, axis=1)], axis=1)


def _tracks(seed: int, runs: int, steps: int, uniform: bool):
    rng = np.random.default_rng(seed)
    t = (np.arange(steps) * 0.37 if uniform
         else np.cumsum(rng.uniform(0.01, 2.0, steps)) - 3.0)  # (ratios to 200: pivoting)
    heading = np.cumsum(rng.normal(0.0, 0.1, (runs, steps)), axis=1)
    speed = rng.uniform(0.1, 10.0, (runs, 1))
    dt = np.gradient(t)
    north = np.cumsum(speed * np.cos(heading) * dt, axis=1) + rng.normal(0, 1e-3, (runs, steps))
    east = np.cumsum(speed * np.sin(heading) * dt, axis=1)
    return t, north, east


@pytest.mark.parametrize("seed, runs, steps, uniform", [
    (0, 1, 181, True), (1, 3, 4, True), (2, 5, 5, False), (3, 7, 60, False),
    (4, 40, 33, True), (5, 2, 400, False)])
def test_track_distance_equals_the_cubic_spline_arc(seed, runs, steps, uniform):
    t, north, east = _tracks(seed, runs, steps, uniform)
    got = track_distance(north, east, t)
    want = _reference(north, east, t)
    np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-12 * float(want.max()))


def test_a_run_with_nan_gets_the_chord_sum_and_the_others_the_spline():
    t, north, east = _tracks(6, 4, 50, False)
    north[2, 30:] = np.nan
    got = track_distance(north, east, t)
    ok = [0, 1, 3]
    np.testing.assert_allclose(got[ok], _reference(north[ok], east[ok], t), rtol=1e-12)
    chords = np.hypot(np.diff(north[2]), np.diff(east[2]))
    np.testing.assert_array_equal(got[2, 1:], np.cumsum(chords))


def test_track_distance_of_a_circle_is_its_arc():
    radius, rate = 8.0, 0.05  # [m], [rad/s]
    t = np.arange(0.0, 120.0, 0.5)
    north, east = radius * np.sin(rate * t), radius * (1.0 - np.cos(rate * t))
    got = track_distance(north, east, t)[0]
    # error of order h^4: (h rate)^4 ~ 4e-7 relative, far below the chords' (h rate)^2 / 24
    np.testing.assert_allclose(got, radius * rate * t, rtol=1e-6, atol=1e-9)
    chords = track_distance(north, east)[0]
    assert abs(chords[-1] / (radius * rate * t[-1]) - 1.0) > 1e-5


def test_track_distance_builds_no_interpolant(monkeypatch):
    import scipy.interpolate

    def refuse(*args, **kwargs):  # pragma: no cover - called only by the old path
        raise AssertionError("CubicSpline constructed")

    monkeypatch.setattr(scipy.interpolate, "CubicSpline", refuse)
    t, north, east = _tracks(7, 2, 30, True)
    assert np.isfinite(track_distance(north, east, t)).all()


@pytest.mark.parametrize("time, why", [
    (np.r_[0.0, 1.0, 1.0, 2.0, 3.0], "strictly increasing"),
    (np.r_[0.0, 1.0, np.nan, 2.0, 3.0], "finite"),
    (np.arange(4.0), "shape"),
    (np.zeros((5, 1)), "shape")])
def test_bad_time_is_refused(time, why):
    north = np.arange(5.0)
    with pytest.raises(ValueError, match=r"`time` \[s\] must be finite, strictly increasing"):
        track_distance(north, north, time)


def test_cubic_crossings_solve_the_lagrange_cubic():
    """The crossing time of each level by the compiled Newton steps equals the root that
    numpy's companion-matrix solver finds for the same cubic through the four samples."""
    rng = np.random.default_rng(8)
    runs, steps = 6, 40
    times = np.broadcast_to(np.cumsum(rng.uniform(0.2, 1.0, steps)), (runs, steps))
    change = np.cumsum(rng.uniform(0.0, 0.2, (runs, steps)), axis=1)
    levels = np.array([0.5 * math.pi, 1.0, 0.17])
    k, w = tc._crossings(change, levels)
    j0, weights = tc._cubic_crossings(np.ascontiguousarray(times), change, levels, k, w)
    got = np.einsum("lrj,lrj->lr", np.take_along_axis(
        np.broadcast_to(times, (3, runs, steps)), j0[..., None] + np.arange(4), axis=2),
        weights)
    checked = 0
    for a, level in enumerate(levels):
        for r in range(runs):
            if k[a, r] <= 0:
                continue
            idx = j0[a, r] + np.arange(4)
            tn, cn = times[r, idx], change[r, idx]
            roots = np.roots(np.polyfit(tn - tn[0], cn - level, 3)) + tn[0]
            lo, hi = times[r, k[a, r] - 1], times[r, k[a, r]]
            real = [z.real for z in roots if abs(z.imag) < 1e-9 and lo - 1e-9 <= z.real <= hi + 1e-9]
            assert real, (a, r)
            assert got[a, r] == pytest.approx(min(real), rel=1e-10, abs=1e-10)
            checked += 1
    assert checked >= 12


@pytest.mark.parametrize("seed, runs, steps", [(9, 1, 181), (10, 6, 50), (11, 3, 5)])
def test_distance_until_equals_the_whole_track_where_wanted(seed, runs, steps):
    """The metrics read the distance at the 10 deg event only: the speeds of the later
    intervals are not evaluated, the distances up to the wanted sample are unchanged."""
    from seahelm.analysis.maneuvers.track import distance_until

    t, north, east = _tracks(seed, runs, steps, seed % 2 == 0)
    if runs > 1:
        north[1, steps // 2:] = np.nan  # (a run without a spline: the chord sum)
    until = np.random.default_rng(seed).integers(0, steps, runs)
    whole = track_distance(north, east, t)
    part = distance_until(north, east, t, until=until)
    for r in range(runs):
        np.testing.assert_array_equal(part[r, :until[r] + 1], whole[r, :until[r] + 1])
