"""The CPP ship's admissible control set, flat approximation and averaged system, Platonov &
Platonova eq. (10)-(24) (seahelm.studies.platonov), printed and corrected."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from seahelm.studies.platonov.averaging import (
    PolynomialControlSet,
    averaged_drift,
    boundary_map,
    sphere_grid,
    support_function,
)
from seahelm.errors import ParameterError
from seahelm.studies.platonov.averaged_system import (
    STUDY_DIRECTION,
    cpp_averaged_rhs,
    cpp_averaging_study,
    cpp_drift_and_matrix,
    rhs_averaged,
    rhs_averaged_printed,
)
from seahelm.studies.platonov.control_set import (
    cpp_betas,
    cpp_boundary_map,
    cpp_control_set,
    cpp_maximiser,
    cpp_support_function,
)
from seahelm.studies.platonov.flat_set import cpp_admissible_set, flat_support_function
from seahelm.vessels.cpp_ship import CPPShipParams, waves_derivative


def c_paper(t):
    """c1, c2 of eq. (11) for α = 0.5 − 0.4 sin τ, written out independently."""
    t = np.asarray(t, dtype=float)
    s = np.sin(t)
    wave = s > 0
    return np.where(wave, 1 - 0.48 * s, 1.0), np.where(wave, 1 - 0.4 * s, 1.0)


@pytest.fixture(scope="module")
def rand_dirs():
    z = np.random.default_rng(7).normal(size=(300, 3))
    return z / np.linalg.norm(z, axis=-1, keepdims=True)


# -- β's ---------------------------------------------------------------------------------
def test_betas_printed_digits():
    b1, b2, b3 = cpp_betas()
    assert round(b1, 5) == 0.82419
    assert round(b2, 4) == 0.8472
    assert round(b3, 4) == 0.8727


def test_betas_closed_form_and_quad():
    b1, b2, b3 = cpp_betas()
    assert b2 == pytest.approx(1 - 0.48 / math.pi, abs=1e-13)
    assert b3 == pytest.approx(1 - 0.40 / math.pi, abs=1e-13)
    wave = quad(lambda t: (1 - 0.48 * math.sin(t)) ** 2 / (1 - 0.4 * math.sin(t)), 0, math.pi,
                epsabs=1e-14)[0]
    assert b1 == pytest.approx((wave + math.pi) / (2 * math.pi), abs=1e-12)


def test_clipped_maximiser_stays_in_U_and_is_optimal(rand_dirs):
    t = np.linspace(0, 2 * math.pi, 64)
    c1, c2 = c_paper(t)
    z = rand_dirs[:, None, :]
    p = cpp_maximiser(c1, c2, z)
    assert np.all(np.abs(p) <= 1.0)
    h = lambda uu: c1 * uu * z[..., 0] + c2 * uu * z[..., 1] + c2 * uu**2 * z[..., 2]  # noqa: E731
    brute = np.full(p.shape, -np.inf)
    for uu in np.linspace(-1, 1, 4001):
        brute = np.maximum(brute, h(uu))
    np.testing.assert_allclose(h(p), brute, atol=1e-6)
    assert np.all(h(p) >= brute - 1e-12)


def test_printed_maximiser_leaves_U(rand_dirs):
    z = rand_dirs[rand_dirs[:, 2] < 0]
    c1, c2 = c_paper(np.linspace(0, 2 * math.pi, 64))
    p = cpp_maximiser(c1, c2, z[:, None, :], variant="printed")
    outside = np.mean(np.any(np.abs(p) > 1, axis=-1))
    assert 0.2 < outside < 0.7  # errata: about 40 % of the z3 < 0 directions
    sig = cpp_boundary_map([1.0, 1.0, -1e-4], variant="printed")
    assert np.max(np.abs(sig)) > 100  # unbounded
    with pytest.raises(ParameterError, match="variant"):
        cpp_maximiser(c1, c2, z[0], variant="paper")


# -- support function and boundary map ------------------------------------------------
def test_support_function_properties(rand_dirs):
    z1, z2 = rand_dirs[:150], rand_dirs[150:]
    h = cpp_support_function
    np.testing.assert_allclose(h(3.5 * z1), 3.5 * h(z1), rtol=1e-12)
    assert np.all(h(z1 + z2) <= h(z1) + h(z2) + 1e-12)
    sig = cpp_boundary_map(z1)
    np.testing.assert_allclose(np.sum(sig * z1, axis=-1), h(z1), atol=1e-14)


def test_boundary_map_generic_and_brute_force(rand_dirs):
    z = rand_dirs[:40]
    cs = cpp_control_set()
    h_generic = support_function(cs, z, pieces=32)
    sig_generic = boundary_map(cs, z, pieces=64)
    sig = cpp_boundary_map(z)
    np.testing.assert_allclose(h_generic, np.sum(sig * z, -1), atol=1e-9)
    # the generic quadrature does not know where a bang-bang maximiser jumps: O(1/pieces)
    np.testing.assert_allclose(sig_generic, sig, atol=5e-4)
    # brute force: midpoint rule in t, argmax over a fine grid in u, one direction at a time
    t = (np.arange(2000) + 0.5) * 2 * math.pi / 2000
    c1, c2 = c_paper(t)
    u = np.linspace(-1, 1, 2001)[:, None]
    for k in range(z.shape[0]):
        H = c1 * u * z[k, 0] + c2 * u * z[k, 1] + c2 * u**2 * z[k, 2]
        assert np.sum(sig[k] * z[k]) == pytest.approx(H.max(axis=0).mean(), abs=2e-6)
        ub = u[np.argmax(H, axis=0), 0]
        brute_sig = [(ub * c1).mean(), (ub * c2).mean(), (ub**2 * c2).mean()]
        np.testing.assert_allclose(sig[k], brute_sig, atol=2e-3)


def test_boundary_points_admissible_bounds():
    z, _, _ = sphere_grid(60, 30)
    sig = cpp_boundary_map(z).reshape(-1, 3)
    b2, b3 = 1 - 0.48 / math.pi, 1 - 0.4 / math.pi
    assert np.all(np.abs(sig[:, 0]) <= b2 + 1e-12)
    assert np.all(np.abs(sig[:, 1]) <= b3 + 1e-12)
    assert np.all((sig[:, 2] >= -1e-15) & (sig[:, 2] <= b3 + 1e-12))
    # z = (0, 0, 1): bang-bang ±1 everywhere, ς3 = β3
    assert cpp_boundary_map([0.0, 0.0, 1.0])[2] == pytest.approx(b3, abs=1e-13)


def test_flat_support_functions():
    b = (0.8, 0.9, 0.7)
    # the arc's hull: direction (0, 0, 1) -> β3 (t = ±1); (0, 0, -1) -> 0 (t = 0)
    assert flat_support_function([0, 0, 1.0], b) == pytest.approx(0.7)
    assert flat_support_function([0, 0, -1.0], b) == pytest.approx(0.0)
    assert flat_support_function([1.0, 0, 0], b) == pytest.approx(0.8)
    # printed: the segment (s, s, β3), s ∈ [-1, 1] sticks out along (1, 1, 0)
    assert flat_support_function([1.0, 1.0, 0], b, "printed") == pytest.approx(2.0)
    with pytest.raises(ParameterError, match="variant"):
        flat_support_function([1.0, 1.0, 0], b, "flat")


def test_admissible_set_distances():
    r = cpp_admissible_set(n_azimuth=80, n_elevation=40)
    b1, b2, b3 = r.betas
    assert r.grid_points == 3200
    # lower bound for the printed Y: its point (1, 1, β3) against h_V((1,1,0)/√2) ≤ (β2+β3)/√2
    assert r.hausdorff_V_Y_printed >= (2 - b2 - b3) / math.sqrt(2) - 1e-9
    assert 0 < r.hausdorff_V_Y < 0.05 < r.hausdorff_V_Y_printed
    # the arc's hull lies within V's bounding box: its support never exceeds V's by more
    # than the distance
    assert np.max(r.support_Y - r.support_V) <= r.hausdorff_V_Y + 1e-12
    assert r.width == pytest.approx(0.036, abs=1e-3)  # errata: V is very thin


# -- averaged system --------------------------------------------------------------------
def test_averaged_drift_generic_equals_cpp():
    p = CPPShipParams()
    x = np.array([[0.9, 1.05], [1.2, 0.8]])
    fbar, _ = cpp_drift_and_matrix(x, p)
    gen = averaged_drift(lambda t, xx: waves_derivative(t, xx, 0.0, p) / p.epsilon, x,
                         kinks=[0.0, math.pi])
    np.testing.assert_allclose(gen, fbar, rtol=1e-12)


@pytest.mark.parametrize("z", [STUDY_DIRECTION, np.array([0.6, 0.5, -1.0]),
                               np.array([1.0, 0.5, 0.2])])
def test_averaged_rhs_equals_brute_force_period_mean(z):
    p = CPPShipParams()
    x = np.array([0.9, 1.05])
    t = (np.arange(4000) + 0.5) * 2 * math.pi / 4000
    c1, c2 = c_paper(t)
    u = np.linspace(-1, 1, 4001)[:, None]
    H = c1 * u * z[0] + c2 * u * z[1] + c2 * u**2 * z[2]
    ubest = u[np.argmax(H, axis=0), 0]
    assert np.all(ubest >= 0)  # stays in case 1 (the case eq. (13) is written for)
    brute = waves_derivative(t, x, ubest, p).mean(axis=0)
    got = cpp_averaged_rhs(x, cpp_boundary_map(z), p)
    np.testing.assert_allclose(got, brute, rtol=2e-4, atol=1e-7)
    sig = cpp_boundary_map(z)
    printed = cpp_averaged_rhs(x, sig, p, assignment="printed")
    if abs(sig[1] - sig[2]) > 0.05:  # the swap is invisible when ς2 = ς3 (p = 1 throughout)
        assert np.max(np.abs(printed - brute)) > 1e-3


@pytest.mark.parametrize("waves", [dict(), dict(immersion=2.0, amplitude=0.0),
                                   dict(immersion=0.5, amplitude=0.2),
                                   dict(immersion=3.0, amplitude=0.5),
                                   dict(immersion=0.9, amplitude=1.4)])
def test_compiled_averaged_rhs_equals_numpy(waves):
    p = CPPShipParams(**waves)
    sig = cpp_boundary_map(STUDY_DIRECTION, p.immersion, p.amplitude)
    for x in ([0.9, 1.05], [1.3, 0.7]):
        for fn, assignment in ((rhs_averaged, "correct"), (rhs_averaged_printed, "printed")):
            dx = np.empty(2)
            fn(0.0, np.array(x), sig, np.empty(0), p.to_record(), dx)
            np.testing.assert_allclose(dx, cpp_averaged_rhs(x, sig, p, assignment=assignment),
                                       rtol=1e-12, atol=1e-15)


def test_equilibrium_of_averaged_system_at_initial_pitch():
    p = CPPShipParams()
    b1, b2, b3 = cpp_betas()
    sigma_const = np.array([0.8 * b2, 0.8 * b3, 0.64 * b3])  # constant φ̄ = 0.8
    np.testing.assert_allclose(cpp_averaged_rhs([1.0, 1.0], sigma_const, p), 0.0, atol=1e-14)


def test_error_order_one_and_printed_does_not_converge():
    eps = (0.05, 0.02, 0.01)
    good = cpp_averaging_study(eps, horizon=1.5, rtol=1e-8, atol=1e-10, n_eval=1501)
    assert 0.85 < good.order < 1.15
    assert np.all(np.diff(good.nfev_original) > 0)  # grows like 1/ε
    assert np.all(good.nfev_averaged * 20 < good.nfev_original)
    bad = cpp_averaging_study(eps, horizon=1.5, rtol=1e-8, atol=1e-10, n_eval=1501,
                              assignment="printed")
    assert bad.errors[-1] > 0.5 * bad.errors[0]
    assert bad.errors[-1] > 3 * good.errors[-1]


def test_plots_return_what_they_drew_on():
    import matplotlib.pyplot as plt

    from seahelm.studies.platonov.figures import (
        plot_averaging_study,
        plot_control_sets,
        plot_set_V,
        plot_set_Y,
    )

    r = cpp_admissible_set(n_azimuth=12, n_elevation=6, refine=False)
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    assert plot_set_V(r, ax=ax) is ax
    assert plot_set_Y(r.betas, variant="printed", ax=ax) is ax
    # the printed reading draws its segment y1 = y2 in [-1, 1], y3 = beta3; the hull nothing more
    seg = [ln for ln in ax.lines if ln.get_label() == "printed segment"]
    assert len(seg) == 1
    xs, ys, zs = seg[0].get_data_3d()
    np.testing.assert_array_equal(xs, [-1.0, 1.0])
    np.testing.assert_array_equal(ys, [-1.0, 1.0])
    np.testing.assert_array_equal(zs, [r.betas[2]] * 2)
    from seahelm.studies.platonov.flat_set import ARC_HULL

    ax_hull = plt.figure().add_subplot(projection="3d")
    plot_set_Y(r.betas, variant=ARC_HULL, ax=ax_hull)
    assert not [ln for ln in ax_hull.lines if "segment" in ln.get_label()]
    with pytest.raises(ValueError, match="variant"):
        plot_set_Y(r.betas, variant="flat", ax=ax)
    fig2 = plt.figure()
    assert plot_control_sets(r, fig=fig2) is fig2
    study = cpp_averaging_study((0.2, 0.1), horizon=0.5, n_eval=101)
    ax2 = plt.figure().add_subplot()
    assert plot_averaging_study(study, ax=ax2) is ax2
    plt.close("all")


def test_bad_input_rejected():
    with pytest.raises(ParameterError, match="epsilons"):
        cpp_averaging_study((0.1, 0.0))
    with pytest.raises(ParameterError, match="epsilons"):
        cpp_averaging_study((-0.1,))
    with pytest.raises(ParameterError, match="c2"):
        cpp_betas(immersion=0.0, amplitude=1.5)
    with pytest.raises(ParameterError, match="c2"):
        cpp_boundary_map([0, 0, 1.0], immersion=0.5, amplitude=1.8)
    with pytest.raises(ParameterError, match="assignment"):
        cpp_averaged_rhs([1.0, 1.0], [0.5, 0.5, 0.3], assignment="swapped")
    with pytest.raises(ParameterError, match="3 components"):
        cpp_boundary_map([1.0, 0.0])
    with pytest.raises(ParameterError, match="low"):
        PolynomialControlSet(lambda t: t, low=1.0, high=-1.0)


def test_hausdorff_distance_of_the_hull_by_independent_brute_force():
    """d_H(V, hull of the arc) = max over directions |h_V − h_Y|, with h_V the period mean of
    the exact maximum of the quadratic H(u) = (c1 z1 + c2 z2) u + c2 z3 u² over u ∈ [−1, 1]
    (vertex clipped) on 4000 midpoints, and h_Y the maximum over 20001 points of the arc
    (β1 t, β2 t, β3 t²). A direction grid only bounds the maximum from below, so the module's
    refined value may exceed the grid value slightly, never fall below it."""
    from seahelm.vessels.cpp_ship import emergence_factors

    n_tau = 4000
    tau = (np.arange(n_tau) + 0.5) * 2 * np.pi / n_tau
    c1, c2 = emergence_factors(tau)
    b1, b2, b3 = np.mean(c1**2 / c2), np.mean(c1), np.mean(c2)
    az, el = np.meshgrid(np.linspace(0, 2 * np.pi, 48, endpoint=False),
                         np.linspace(-np.pi / 2, np.pi / 2, 25))
    z = np.stack([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)], -1).reshape(-1, 3)
    lin = c1[None] * z[:, :1] + c2[None] * z[:, 1:2]          # (dirs, tau)
    quad = c2[None] * z[:, 2:3]
    cand = [lin + quad, -lin + quad]                           # u = ±1
    with np.errstate(divide="ignore", invalid="ignore"):
        u_star = np.clip(-lin / (2 * quad), -1, 1)
    cand.append(np.where(quad < 0, lin * u_star + quad * u_star**2, -np.inf))
    h_v = np.max(cand, axis=0).mean(axis=1)
    t = np.linspace(-1, 1, 20001)
    h_y = np.max(np.outer(z[:, 0], b1 * t) + np.outer(z[:, 1], b2 * t)
                 + np.outer(z[:, 2], b3 * t * t), axis=1)
    grid_value = np.max(np.abs(h_v - h_y))
    r = cpp_admissible_set(n_azimuth=80, n_elevation=40)
    assert r.hausdorff_V_Y >= grid_value - 1e-4
    assert r.hausdorff_V_Y == pytest.approx(grid_value, abs=2e-3)


# -- the printed variants are registry objects --------------------------------------------
def test_printed_variants_are_named_registry_objects():
    from seahelm.studies.platonov import averaged_system as av
    from seahelm.studies.platonov import control_set as cs
    from seahelm.studies.platonov import flat_set as fs

    assert cs.get_maximiser("printed") is cs.PRINTED_EQ15
    assert cs.get_maximiser("clipped") is cs.CLIPPED_MAXIMISER
    assert fs.get_flat_variant("printed") is fs.PRINTED_EQ24
    assert fs.get_flat_variant(fs.ARC_HULL) is fs.ARC_HULL
    assert av.get_assignment("printed") is av.PRINTED_EQ13
    assert av.PRINTED_EQ13.rhs is rhs_averaged_printed and av.CORRECT_ASSIGNMENT.rhs is rhs_averaged
    z = np.array([[1.0, 1.0, -1e-4], [0.3, -0.2, 0.9]])
    np.testing.assert_array_equal(cpp_boundary_map(z, variant=cs.PRINTED_EQ15),
                                  cpp_boundary_map(z, variant="printed"))
    betas = cpp_betas()
    np.testing.assert_array_equal(flat_support_function(z, betas, fs.PRINTED_EQ24),
                                  flat_support_function(z, betas, "printed"))
    x, sig = np.array([0.9, 1.1]), np.array([0.5, 0.4, 0.3])
    np.testing.assert_array_equal(cpp_averaged_rhs(x, sig, assignment=av.PRINTED_EQ13),
                                  cpp_averaged_rhs(x, sig, assignment="printed"))
    with pytest.raises(ParameterError, match="valid: clipped, printed"):
        cs.get_maximiser("paper")
