"""Benchmark: original CPP ship in waves (Platonov & Platonova, eq. (10)) against its fully
averaged system (eq. (13)), and the cost of the admissible control set V.

Prints, for several ε:
* the averaging error max |x − x̄| over t ∈ [0, L/ε] and its fitted order;
* right-hand-side evaluations and wall time of both simulations at the same solver tolerance
  (equal accuracy of each solve; the averaged model is itself within C ε of the original);
* the evaluations and time each model needs with a fixed-step RK4 to come within 1e-6 of its
  own converged solution (equal accuracy of the two integrations);
and the time to compute ς(z) and h_V on a 200 × 100 direction grid. Medians of several runs.

Run: ``.venv/bin/python benchmarks/bench_averaging.py [--quick]`` (``--quick``, the test suite's
smoke run: one ε, a 20 × 10 grid, 1 repeat)
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

from seahelm.studies.platonov.averaging import sphere_grid
from seahelm.studies.platonov.averaged_system import (
    STUDY_DIRECTION,
    _original_rhs,
    cpp_averaging_study,
    rhs_averaged,
)
from seahelm.studies.platonov.control_set import cpp_boundary_map
from seahelm.studies.platonov.flat_set import cpp_admissible_set
from seahelm.vessels.cpp_ship import CPPShipParams

REPEATS = 5
EPSILONS = (0.2, 0.1, 0.05, 0.02, 0.01)


def median_time(fn, repeats: int | None = None) -> tuple[float, object]:
    times, out = [], None
    repeats = REPEATS if repeats is None else repeats
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), out


def rk4(f, t_end: float, x0: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Fixed-step classical RK4 (4 rhs evaluations per step); returns times and states."""
    h = t_end / n
    ts = np.linspace(0.0, t_end, n + 1)
    traj = np.empty((n + 1, x0.size))
    x = x0.copy()
    traj[0] = x
    for k in range(n):
        t = ts[k]
        k1 = f(t, x)
        k2 = f(t + h / 2, x + h / 2 * k1)
        k3 = f(t + h / 2, x + h / 2 * k2)
        k4 = f(t + h, x + h * k3)
        x = x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        traj[k + 1] = x
    return ts, traj


def rk4_to_tolerance(f, t_end: float, x0: np.ndarray, reference: np.ndarray,
                     n_out: int, target: float, n_start: int) -> tuple[int, float]:
    """Fewest RK4 steps (n_start · 2^k) within ``target`` of ``reference``.

    ``reference`` (n_states, n_out + 1) holds the converged solution at n_out + 1 equally
    spaced times on [0, t_end]; ``n_start`` must be a multiple of ``n_out`` so that RK4 lands
    on those times (no interpolation error). Returns (rhs evaluations, wall time [s]).
    """
    n = n_start
    while n < 10**7:
        ts, traj = rk4(f, t_end, x0, n)
        err = np.max(np.abs(traj[:: n // n_out].T - reference))
        if err <= target:
            wall, _ = median_time(lambda: rk4(f, t_end, x0, n), repeats=min(3, REPEATS))
            return 4 * n, wall
        n *= 2
    return -1, float("nan")


def main() -> None:
    from scipy.integrate import solve_ivp
    global REPEATS, EPSILONS
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help="smoke run (the test suite's): tiny sizes, 1 repeat")
    grid = (200, 100)
    if parser.parse_args().quick:
        REPEATS, EPSILONS, grid = 1, (0.2,), (20, 10)

    print("CPP ship in waves: original eq. (10) vs averaged eq. (13) "
          f"(DOP853, rtol 1e-9, L = 2, median of {REPEATS})")
    cpp_averaging_study((0.1,))  # compile
    t_study, study = median_time(lambda: cpp_averaging_study(EPSILONS))
    print(f"{'eps':>6} {'error':>10} {'nfev orig':>10} {'nfev avg':>9} "
          f"{'t orig [ms]':>12} {'t avg [ms]':>11}")
    for e, err, no, na, to, ta in zip(study.epsilons, study.errors, study.nfev_original,
                                      study.nfev_averaged, study.time_original,
                                      study.time_averaged):
        print(f"{e:6.3f} {err:10.3e} {no:10d} {na:9d} {1e3 * to:12.2f} {1e3 * ta:11.2f}")
    print(f"fitted error order: {study.order:.3f}   (whole study {t_study:.2f} s)")

    # equal accuracy: each model integrated by fixed-step RK4 to within TARGET of its own
    # converged solution (states sampled on the same slow-time grid)
    target = 1e-6
    print(f"\nFixed-step RK4 to within {target:g} of each model's converged solution:")
    print(f"{'eps':>6} {'evals orig':>11} {'evals avg':>10} {'t orig [ms]':>12} "
          f"{'t avg [ms]':>11}")
    x0 = np.array([0.8, 0.9])
    n_out = 20
    s_eval = np.linspace(0.0, 2.0, n_out + 1)
    sigma = cpp_boundary_map(STUDY_DIRECTION)
    empty = np.empty(0)
    for e in EPSILONS:
        params = CPPShipParams(wave_ratio=1.0 / e)
        p = params.to_record()
        t_end = 2.0 / e

        def f_orig(t, x, p=p):
            dx = np.empty(2)
            _original_rhs(t, x, p, STUDY_DIRECTION, dx)
            return dx

        def f_avg(t, x, p=p):
            dx = np.empty(2)
            rhs_averaged(t, x, sigma, empty, p, dx)
            return dx

        out = []
        periods = int(np.ceil(t_end / (2 * np.pi)))
        for f, n_start in ((f_orig, n_out * int(np.ceil(4 * periods / n_out))), (f_avg, n_out)):
            ref = solve_ivp(f, (0, t_end), x0, method="DOP853", rtol=1e-12, atol=1e-14,
                            t_eval=s_eval / e).y
            out.append(rk4_to_tolerance(f, t_end, x0, ref, n_out, target, n_start))
        (no, to), (na, ta) = out
        print(f"{e:6.3f} {no:11d} {na:10d} {1e3 * to:12.2f} {1e3 * ta:11.2f}")

    print(f"\nAdmissible set V on a {grid[0]} x {grid[1]} direction grid (eq. (17)):")
    z, _, _ = sphere_grid(*grid)
    cpp_boundary_map(z[:2, :2])
    t_v, _ = median_time(lambda: cpp_boundary_map(z))
    print(f"  ς(z) for {grid[0] * grid[1]} directions: {1e3 * t_v:.1f} ms (median of {REPEATS})")
    t_all, res = median_time(lambda: cpp_admissible_set(), repeats=min(3, REPEATS))
    print(f"  V, Y, both Hausdorff distances (refined): {1e3 * t_all:.1f} ms; "
          f"d_H(V, hull) = {res.hausdorff_V_Y:.5f}, d_H(V, printed) = "
          f"{res.hausdorff_V_Y_printed:.5f}")


if __name__ == "__main__":
    main()
