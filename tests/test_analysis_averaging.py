"""Full averaging of control-affine periodic systems, the generic part (Platonov & Platonova,
eq. (1)-(4)): period means, polynomial maximisers, the sphere grid, Hausdorff distances. The
CPP ship's control set and averaged system are tests/test_studies_platonov.py."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seahelm.errors import ParameterError
from seahelm.numerics.periodic import period_mean
from seahelm.studies.platonov.averaging import (
    chunk_slices,
    hausdorff_from_support,
    maximise_polynomial,
    sphere_grid,
)


@pytest.mark.parametrize("n, size, expected", [
    (0, 4, []), (3, 4, [(0, 3)]), (8, 4, [(0, 4), (4, 8)]), (9, 4, [(0, 4), (4, 8), (8, 9)])])
def test_chunk_slices_cut_the_rows_in_order(n, size, expected):
    assert [(s.start, s.stop) for s in chunk_slices(n, size)] == expected


def test_period_mean_exact_at_kinks():
    # mean of |sin| = 2/π, kink at π; mean of a smooth trig polynomial
    assert period_mean(lambda t: np.abs(np.sin(t)), kinks=[math.pi], nodes=20) == pytest.approx(
        2 / math.pi, abs=1e-14)
    assert period_mean(lambda t: np.cos(t) ** 2 + np.sin(3 * t)) == pytest.approx(0.5, abs=1e-14)
    with pytest.raises(ParameterError, match="nodes"):
        period_mean(np.sin, nodes=0)


# -- maximisers -------------------------------------------------------------------------
@pytest.mark.parametrize("deg", [1, 2, 3, 4])
def test_maximise_polynomial_matches_brute_force(deg):
    rng = np.random.default_rng(deg)
    q = rng.normal(size=(200, deg + 1))
    q[:5, -1] = 0.0  # degenerate leading coefficients
    lo, hi = -1.0, 0.7
    u, val = maximise_polynomial(q, lo, hi)
    grid = np.linspace(lo, hi, 20001)
    brute = np.polynomial.polynomial.polyval(grid, q.T).max(axis=-1)
    assert np.all((u >= lo) & (u <= hi))
    np.testing.assert_allclose(val, brute, atol=1e-7)
    np.testing.assert_allclose(np.polynomial.polynomial.polyval(u, q.T).diagonal(), val,
                               atol=1e-12)


def test_sphere_grid():
    z, phi1, phi2 = sphere_grid(20, 10)
    assert z.shape == (10, 20, 3)
    np.testing.assert_allclose(np.linalg.norm(z, axis=-1), 1.0)
    assert phi1[0] == 0 and phi1[-1] == pytest.approx(2 * math.pi)
    with pytest.raises(ParameterError, match="n_azimuth"):
        sphere_grid(2, 10)


# -- flat approximation and Hausdorff ---------------------------------------------------
def test_hausdorff_from_support_balls():
    z = sphere_grid(30, 15)[0]
    assert hausdorff_from_support(np.ones(z.shape[:2]), 2 * np.ones(z.shape[:2])) == 1.0
