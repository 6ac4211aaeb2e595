"""The cost of wind, waves and current on the KVLCC2 closed loop, against calm water.

The KVLCC2 at full scale (MMG standard model) keeps its course under the PID heading autopilot
(``pid-heading-rps``: rudder by PID, propeller at the self-propulsion rps) through the rudder
servo, RK4, dt = 0.5 s, 1,200 s, for a batch of runs. Measured in the same process, in turn:

* ``calm``        — no environment;
* ``current``     — a uniform current (the model's current channels; no extra stage);
* ``environment`` — Blendermann wind 20 m/s from the beam, Lvov's wave loads in an irregular
  sea (h3% = 3 m, each run its own seeded realisation, the wave-load signal per run and step),
  and a 0.5 m/s current: the environment's stage at every RK4 stage;
* ``env. held``   — the same with ``hold_over_step=True``: the loads evaluated once per step
  and held over its four stages; the script also prints how far the runs end from the
  per-stage ones.

Each figure is the median of ``--repeats`` runs of the whole ``simulate`` call (inputs built
outside the clock; the irregular seas' signal arrays are drawn once, outside the clock, as a
scenario does before the engine runs), after a warm-up that compiles. The target of issue 14
is the environment at ≤ 1.5 × the calm-water cost.

    python benchmarks/bench_environment.py [--runs 1000] [--repeats 5]
"""

from __future__ import annotations

import argparse
import math
import statistics
import time
import warnings

import numpy as np

from seahelm.actuators.servo import RUDDER_SERVO
from seahelm.analysis.equilibria.equilibrium import approach_state
from seahelm.control.pid import PID_HEADING_RPS, PIDHeadingRpsParams
from seahelm.environment.loads import environment, ship_load_params, wave_load_fluctuation
from seahelm.ships import get_ship
from seahelm.errors import ValidityRangeWarning
from seahelm.simulation.engine import simulate
from seahelm.vessels.mmg import KVLCC2_FULL, KVLCC2_FULL_SERVO, MMG

T_FINAL, DT = 1200.0, 0.5


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=1000, help="vessels in the batch (default 1000)")
    ap.add_argument("--repeats", type=int, default=5, help="timed repeats (default 5)")
    ap.add_argument("--quick", action="store_true",
                    help="smoke run (the test suite's): tiny sizes, 1 repeat")
    args = ap.parse_args()
    if args.quick:
        args.runs, args.repeats = 4, 1

    app = approach_state(KVLCC2_FULL, 7.97)
    gains = PIDHeadingRpsParams(kp=4.0, ki=0.004, kd=120.0,
                                propeller_rps=app.inputs["propeller_rps"])
    env = environment(wind="blendermann", waves="lvov")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityRangeWarning)  # C_b 0.81 > 0.8 of eq. (5)-(7)
        ep = ship_load_params(get_ship("kvlcc2-full"), env, wind_speed=20.0,
                              wind_direction=math.radians(90.0), wave_height=3.0,
                              wave_length=120.0, wave_direction=math.radians(45.0))
    n = args.runs
    n_steps = int(round(T_FINAL / DT))
    x0 = np.tile(app.state, (n, 1))
    headings = np.linspace(-0.3, 0.3, n)
    x0[:, MMG.state_index("heading")] = headings
    current = np.zeros((n, 1, MMG.n_disturbances))
    current[:, 0, MMG.disturbance_labels.index("current_north")] = 0.5 * math.cos(1.0)
    current[:, 0, MMG.disturbance_labels.index("current_east")] = 0.5 * math.sin(1.0)
    t0 = time.perf_counter()
    seeds = np.random.SeedSequence(1).spawn(n)
    nd = MMG.n_disturbances + len(env.signal_labels)
    sea = np.zeros((n, n_steps + 1, nd))
    sea[:, 0, :MMG.n_disturbances] = current[:, 0]
    sea[:, :, :MMG.n_disturbances] = current
    j = nd - 1  # wave_load_fluctuation
    sea[:, :, j] = wave_load_fluctuation(3.0, n_steps + 1, DT, seeds, runs=n)
    draw = time.perf_counter() - t0

    common = dict(t_final=T_FINAL, dt=DT, actuator=RUDDER_SERVO, actuator_params=KVLCC2_FULL_SERVO,
                  actuator_x0=[app.inputs["rudder_angle"]], controller=PID_HEADING_RPS,
                  controller_params=gains, reference=np.zeros((n, 1, 1)), record_every=20)
    held = environment(wind="blendermann", waves="lvov", hold_over_step=True)
    cases = {
        "calm": dict(),
        "current": dict(disturbance=current),
        "environment": dict(disturbance=sea, environment=env, environment_params=ep),
        "env. held": dict(disturbance=sea, environment=held, environment_params=held.params(
            **ep.as_dict())),
    }
    times: dict[str, list[float]] = {k: [] for k in cases}
    for name, kw in cases.items():  # warm-up: compile or load every kernel
        res = simulate(MMG, KVLCC2_FULL, x0, **common, **kw)
        assert res.ok.all(), name
    for _ in range(args.repeats):
        for name, kw in cases.items():
            t0 = time.perf_counter()
            simulate(MMG, KVLCC2_FULL, x0, **common, **kw)
            times[name].append(time.perf_counter() - t0)
    med = {k: statistics.median(v) for k, v in times.items()}
    steps = n * n_steps
    print(f"KVLCC2 (MMG) + rudder servo + PID (pid-heading-rps), RK4 dt = {DT:g} s, "
          f"{T_FINAL:g} s, {n} runs ({steps:.3g} vessel-steps); medians of {args.repeats}")
    for name in cases:
        print(f"  {name:12s} {med[name]:7.3f} s  {steps / med[name]:10.3g} vessel-steps/s  "
              f"{med[name] / med['calm']:5.2f} x calm")
    print(f"  (drawing the {n} irregular seas outside the clock: {draw:.2f} s)")
    for name in ("environment", "env. held"):
        ratio = med[name] / med["calm"]
        print(f"{name} / calm = {ratio:.2f} (target <= 1.5): "
              f"{'met' if ratio <= 1.5 else 'NOT met'}")
    # what holding the loads over a step costs in accuracy: the final positions of the runs
    a = simulate(MMG, KVLCC2_FULL, x0, **common, **cases["environment"])
    b = simulate(MMG, KVLCC2_FULL, x0, **common, **cases["env. held"])
    dpos = np.hypot(a["north"][:, -1] - b["north"][:, -1], a["east"][:, -1] - b["east"][:, -1])
    dpsi = np.degrees(np.abs(a["heading"][:, -1] - b["heading"][:, -1]))
    print(f"held vs per stage after {T_FINAL:g} s: position differs by at most {dpos.max():.3g} m "
          f"(of {np.hypot(a['north'][:, -1], a['east'][:, -1]).max():.4g} m travelled), heading "
          f"by {dpsi.max():.3g} deg")


if __name__ == "__main__":
    main()
