"""Turning circles: seahelm against shipmmg, KVLCC2 L7, 35° rudder, at equal accuracy.

One 35° starboard turning circle of the KVLCC2 L7 model (MMG standard method, Yasukawa &
Yoshimura 2015) from the straight self-propulsion approach at 1.179 m/s, 90 s (beyond the 180°
heading change), measured end to end: seahelm's :func:`seahelm.analysis.maneuvers.turning_circle`
(approach, compiled batch, metrics Dataset) and shipmmg's ``simulate_mmg_3dof`` (scipy
``solve_ivp``, RK45) with advance and tactical diameter interpolated from its output.

Equal accuracy: each tool runs at the cheapest setting whose advance and tactical diameter
agree to 0.1 % with a much finer run of the same tool — seahelm: the largest RK4 step of
0.5, 0.25, 0.2, 0.1, 0.05 s that agrees with a run at a quarter of that step (0.5 s is the
largest step the library takes without a warning, 10× its default; the servo's states come
from its closed-form solution, so its 0.1 s lag does not bound the step); shipmmg: the loosest
``rtol`` of 1e-3 ... 1e-6 (``atol`` = rtol/1000) that agrees with rtol = 1e-11. (The two
implementations differ slightly in the model — shipmmg's rudder follows an ideal ramp, seahelm's
the rate-limited servo with its 0.1 s lag — so their converged values are printed too but
not compared.)

shipmmg runs in its own interpreter (``--shipmmg-python``, default /tmp/venv-shipmmg/bin/python)
as a subprocess; it is never a seahelm dependency. Without it the comparison is skipped with a
message and seahelm's figures are still printed. Then seahelm runs 1,000 circles in one batch
(500 rudder angles from 20° to 35° × both sides, recorded every second) and the time is set
against shipmmg's for 10 circles. Medians of ``--repeats`` runs; the ratios are within one run.
Last, the one-circle ratio at equal accuracy is measured with the two tools alternating,
``--pairs`` times (shipmmg kept open in its interpreter): its median and quartiles hold on a
machine whose load comes and goes, where figures timed seconds apart do not.

    python benchmarks/bench_maneuvers.py [--repeats 5] [--pairs 51] [--shipmmg-python PATH]
                                         [--quick]

``--quick`` (the test suite's smoke run): steps 0.5 and 0.25 s, 20 circles in the batch,
1 repeat, no shipmmg.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import textwrap
import time

import numpy as np

from seahelm.analysis.equilibria.equilibrium import self_propulsion_rps
from seahelm.analysis.maneuvers import turning_circle
from seahelm.vessels.mmg import KVLCC2_L7

SHIP = "kvlcc2-l7"
U0 = 1.179  # [m/s]
T_FINAL = 90.0  # [s]
RUDDER = math.radians(35.0)
TOLERANCE = 1e-3  # relative, on advance and tactical diameter
SEAHELM_STEPS = (0.5, 0.25, 0.2, 0.1, 0.05)  # [s]; 0.5 s = STEP_VALIDITY x default step
SHIPMMG_RTOLS = (1e-3, 5e-4, 2e-4, 1e-4, 5e-5, 2e-5, 1e-5, 1e-6)

# The shipmmg side, run in shipmmg's interpreter: KVLCC2 L7 in shipmmg's parameter classes
# (the values of seahelm.vessels.mmg.KVLCC2_L7), its simulate_mmg_3dof, advance and tactical
# diameter by linear interpolation of the heading changes in its output.
SHIPMMG_SCRIPT = textwrap.dedent("""
    import json, sys, time
    import numpy as np
    from shipmmg.mmg_3dof import (Mmg3DofBasicParams, Mmg3DofManeuveringParams,
                                  simulate_mmg_3dof)
    job = json.loads(sys.argv[1])
    rho, L, d, nabla = 1000.0, 7.00, 0.46, 3.27
    m = rho * nabla
    nd = 0.5 * rho * L ** 2 * d
    basic = Mmg3DofBasicParams(
        L_pp=L, B=1.27, d=d, x_G=0.25, D_p=0.216, m=m, I_zG=m * (0.25 * L) ** 2, A_R=0.0539,
        η=0.216 / 0.345, m_x=0.022 * nd, m_y=0.223 * nd, J_z=0.011 * nd * L ** 2, f_α=2.747,
        ϵ=1.09, t_R=0.387, x_R=-0.5 * L, a_H=0.312, x_H=-0.464 * L, γ_R_minus=0.395,
        γ_R_plus=0.640, l_R=-0.710, κ=0.50, t_P=0.220, w_P0=0.40, x_P=-0.48)
    man = Mmg3DofManeuveringParams(
        k_0=0.2931, k_1=-0.2753, k_2=-0.1385, R_0_dash=0.022, X_vv_dash=-0.040,
        X_vr_dash=0.002, X_rr_dash=0.011, X_vvvv_dash=0.771, Y_v_dash=-0.315, Y_r_dash=0.083,
        Y_vvv_dash=-1.607, Y_vvr_dash=0.379, Y_vrr_dash=-0.391, Y_rrr_dash=0.008,
        N_v_dash=-0.137, N_r_dash=-0.049, N_vvv_dash=-0.030, N_vvr_dash=-0.294,
        N_vrr_dash=0.055, N_rrr_dash=-0.013)

    def crossing(psi, values, change):
        d = np.abs(psi - psi[0])
        k = int(np.argmax(d >= change))
        w = (change - d[k - 1]) / (d[k] - d[k - 1])
        return values[k - 1] + w * (values[k] - values[k - 1])

    def circle(rtol):
        t = np.arange(0.0, job["t_final"] + 1e-9, 0.05)
        delta = np.minimum(np.radians(15.8) * t, job["rudder"])
        sol = simulate_mmg_3dof(basic, man, t, delta, np.full(t.size, job["rps"]), u0=job["u0"],
                                ρ=rho, t_eval=t, rtol=rtol, atol=rtol * 1e-3)
        x, y, psi = sol.y[3], sol.y[4], sol.y[5]
        return crossing(psi, x, np.pi / 2), abs(crossing(psi, y, np.pi)), int(sol.nfev)

    if job.get("serve"):  # interleaved with seahelm: one line in ("rtol n"), seconds out
        circle(job["serve"])  # (warm)
        for line in sys.stdin:
            rtol, n = float(line.split()[0]), int(line.split()[1])
            t0 = time.perf_counter()
            for _ in range(n):
                circle(rtol)
            print(time.perf_counter() - t0, flush=True)
        sys.exit(0)
    out = {"reference": circle(1e-11)[:2], "rtols": []}
    for rtol in job["rtols"]:
        times = []
        for _ in range(job["repeats"]):
            t0 = time.perf_counter()
            adv, td, nfev = circle(rtol)
            times.append(time.perf_counter() - t0)
        out["rtols"].append({"rtol": rtol, "advance": adv, "tactical_diameter": td,
                             "nfev": nfev, "time": float(np.median(times))})
    if job.get("ten_rtol") is not None:
        times = []
        for _ in range(job["repeats"]):
            t0 = time.perf_counter()
            for _ in range(10):
                circle(job["ten_rtol"])
            times.append(time.perf_counter() - t0)
        out["ten"] = float(np.median(times))
    print(json.dumps(out))
""")


def seahelm_circle(dt: float, record_dt: float | None = None) -> tuple[float, float, float]:
    """(advance, tactical diameter, seconds) of one 35° starboard circle, end to end."""
    t0 = time.perf_counter()
    m = turning_circle(SHIP, RUDDER, sides=1, t_final=T_FINAL, dt=dt, record_dt=record_dt).metrics
    adv, td = float(m["advance"]), float(m["tactical_diameter"])
    return adv, td, time.perf_counter() - t0


def rel(a: float, b: float) -> float:
    return abs(a / b - 1.0)


def run_shipmmg(python: str, job: dict) -> dict | None:
    try:
        proc = subprocess.run([python, "-c", SHIPMMG_SCRIPT, json.dumps(job)],
                              capture_output=True, text=True, timeout=3600)
    except (OSError, subprocess.TimeoutExpired) as exc:
        print(f"shipmmg skipped: cannot run {python}: {exc}")
        return None
    if proc.returncode != 0:
        last = (proc.stderr.strip().splitlines() or ["?"])[-1]
        print(f"shipmmg skipped: {python} could not run it ({last})")
        return None
    return json.loads(proc.stdout.strip().splitlines()[-1])


def interleaved(python: str, job: dict, rtol: float, dt: float, pairs: int) -> list[tuple[float, float]]:
    """(seahelm, shipmmg) seconds of one circle each, ``pairs`` times, alternating: the two
    measured within milliseconds of each other, so a load that comes and goes on a shared
    machine slows both alike (shipmmg in a kept-open interpreter, fed one request a line)."""
    proc = subprocess.Popen([python, "-c", SHIPMMG_SCRIPT, json.dumps({**job, "serve": rtol})],
                            stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    out = []
    try:
        for _ in range(pairs):
            sea = seahelm_circle(dt)[2]
            proc.stdin.write(f"{rtol!r} 1\n")
            proc.stdin.flush()
            out.append((sea, float(proc.stdout.readline())))
    finally:
        proc.stdin.close()
        proc.wait(timeout=60)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--shipmmg-python", default=os.environ.get(
        "SHIPMMG_PYTHON", "/tmp/venv-shipmmg/bin/python"))
    parser.add_argument("--pairs", type=int, default=51,
                        help="seahelm/shipmmg circles timed alternately (default 51)")
    parser.add_argument("--quick", action="store_true",
                        help="smoke run (the test suite's): tiny sizes, 1 repeat")
    args = parser.parse_args()
    steps, n_rudders = SEAHELM_STEPS, 500
    if args.quick:
        args.repeats, steps, n_rudders = 1, (0.5, 0.25), 10
        args.shipmmg_python = "(none: --quick)"
    rps = float(self_propulsion_rps(KVLCC2_L7, U0))
    seahelm_circle(0.2)  # compile (or load) the kernel and the approach outside the timing
    print(f"KVLCC2 L7, 35 deg starboard turning circle, {T_FINAL:g} s, U0 = {U0} m/s, "
          f"n = {rps:.6g} rps; {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f} "
          f"(the batch runs one thread per core; a busy core slows it); medians of "
          f"{args.repeats} runs\n")

    # -- seahelm: step by accuracy -------------------------------------------------------
    print("seahelm (RK4, fixed step): advance / tactical diameter against a run at dt/4")
    chosen = None
    for dt in steps:
        a, td, _ = seahelm_circle(dt)
        a4, td4, _ = seahelm_circle(dt / 4)
        ea, etd = rel(a, a4), rel(td, td4)
        ok = ea <= TOLERANCE and etd <= TOLERANCE
        print(f"  dt = {dt:<5g} s: advance {a:.6f} m ({100 * ea:.4f} %), TD {td:.6f} m "
              f"({100 * etd:.4f} %) {'<= 0.1 %' if ok else '> 0.1 %'}")
        if ok and chosen is None:
            chosen, ref = dt, (a4, td4)
    assert chosen is not None
    times = [seahelm_circle(chosen)[2] for _ in range(args.repeats)]
    t_one = statistics.median(times)
    print(f"  chosen dt = {chosen:g} s: {1e3 * t_one:.2f} ms per circle (end to end: approach, "
          "compiled run, metrics)")

    # -- seahelm: 1,000 circles in one batch ---------------------------------------------
    rudders = np.radians(np.linspace(20.0, 35.0, n_rudders))
    batch_times = []
    for _ in range(max(1, args.repeats // 2)):
        t0 = time.perf_counter()
        res = turning_circle(SHIP, rudders, sides=(1, -1), t_final=T_FINAL, dt=chosen,
                             record_dt=1.0)
        m = res.metrics
        adv35, td35 = float(m["advance"][-1, 0]), float(m["tactical_diameter"][-1, 0])
        batch_times.append(time.perf_counter() - t0)
    t_batch = statistics.median(batch_times)
    assert int(m["complete"].sum()) == 2 * n_rudders
    print(f"  {2 * n_rudders:,} circles ({n_rudders} rudder angles x 2 sides, recorded every 1 s) "
          "in one batch: "
          f"{t_batch:.3f} s ({1e3 * t_batch / (2 * n_rudders):.3f} ms per circle); its 35 deg "
          "starboard "
          f"circle: advance {100 * rel(adv35, ref[0]):.4f} %, TD {100 * rel(td35, ref[1]):.4f} % "
          "from the dt/4 run")

    # -- shipmmg ------------------------------------------------------------------------
    job = {"rps": rps, "u0": U0, "t_final": T_FINAL, "rudder": RUDDER,
           "rtols": list(SHIPMMG_RTOLS), "repeats": args.repeats}
    if not os.path.exists(args.shipmmg_python):
        print(f"\nshipmmg skipped: no interpreter at {args.shipmmg_python} (pass "
              "--shipmmg-python or set SHIPMMG_PYTHON to a Python with shipmmg installed)")
        return
    print(f"\nshipmmg (scipy solve_ivp RK45, {args.shipmmg_python}): advance / TD against "
          "rtol = 1e-11")
    out = run_shipmmg(args.shipmmg_python, job)
    if out is None:
        return
    ref_a, ref_td = out["reference"]
    pick = None
    for row in out["rtols"]:
        ea, etd = rel(row["advance"], ref_a), rel(row["tactical_diameter"], ref_td)
        ok = ea <= TOLERANCE and etd <= TOLERANCE
        print(f"  rtol = {row['rtol']:<6g}: advance {row['advance']:.6f} m ({100 * ea:.4f} %), "
              f"TD {row['tactical_diameter']:.6f} m ({100 * etd:.4f} %), {row['nfev']} rhs "
              f"evaluations, {1e3 * row['time']:.2f} ms {'<= 0.1 %' if ok else '> 0.1 %'}")
        if ok and pick is None:
            pick = row
    assert pick is not None
    job.update(rtols=[], ten_rtol=pick["rtol"], repeats=max(1, args.repeats // 2))
    ten = run_shipmmg(args.shipmmg_python, job)
    t_ten = ten["ten"] if ten else 10 * pick["time"]
    print(f"  chosen rtol = {pick['rtol']:g}: {1e3 * pick['time']:.2f} ms per circle; 10 circles "
          f"{t_ten:.3f} s")
    print(f"\nconverged values (models differ slightly, see the docstring): seahelm advance "
          f"{ref[0]:.4f} m, TD {ref[1]:.4f} m; shipmmg advance {ref_a:.4f} m, TD {ref_td:.4f} m")
    print(f"\nper circle at equal accuracy (<= 0.1 %), measured one after the other: seahelm "
          f"{1e3 * t_one:.2f} ms, shipmmg {1e3 * pick['time']:.2f} ms: "
          f"{pick['time'] / t_one:.1f}x")
    pairs = interleaved(args.shipmmg_python, job, pick["rtol"], chosen, args.pairs)
    ratios = sorted(m / s_ for s_, m in pairs)
    sea_med = statistics.median(s_ for s_, _ in pairs)
    mmg_med = statistics.median(m for _, m in pairs)
    ratio = statistics.median(ratios)
    print(f"interleaved ({len(pairs)} pairs, seahelm and shipmmg alternating): seahelm "
          f"{1e3 * sea_med:.2f} ms (min {1e3 * min(s_ for s_, _ in pairs):.2f}), shipmmg "
          f"{1e3 * mmg_med:.2f} ms (min {1e3 * min(m for _, m in pairs):.2f}); ratio median "
          f"{ratio:.1f}x, quartiles {ratios[len(ratios) // 4]:.1f}-{ratios[3 * len(ratios) // 4]:.1f}x, "
          f"of the minima {min(m for _, m in pairs) / min(s_ for s_, _ in pairs):.1f}x "
          f"({'meets' if ratio >= 10 else 'misses'} the 10x target)")
    print(f"seahelm 1,000 circles {t_batch:.3f} s vs shipmmg 10 circles {t_ten:.3f} s: "
          f"{'less' if t_batch < t_ten else 'MORE'} ({t_ten / t_batch:.2f}x; per circle "
          f"{100 * t_ten / t_batch:.0f}x)")
    print(f"(load average at the end {os.getloadavg()[0]:.2f})")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
