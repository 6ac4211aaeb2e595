"""The KVLCC2 (L7 model) as an FMI 2.0 co-simulation FMU, run by fmpy, against ``simulate``.

Builds ``kvlcc2-l7.fmu`` (``seahelm fmu kvlcc2-l7 -o kvlcc2-l7.fmu`` does the same), runs it
with :func:`fmpy.simulate_fmu` for 60 s in communication steps of 1 s with a rudder schedule
(10° to starboard, at 10.5 s 20° to port, at 30.5 s 35° to starboard: fmpy holds the inputs
between the schedule's points and makes a communication point of each change) and the initial heading set through a parameter, then runs
``simulate`` of the same problem (the commands as an open-loop reference on the grid).
Prints the largest difference of each output and writes ``fmu_fmpy.png`` (tracks, heading,
difference) into the directory given.

    python examples/fmu_fmpy.py [OUT_DIR]
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

from seahelm import Problem, get_ship, simulate
from seahelm.analysis.equilibria.equilibrium import approach_state
from seahelm.fmu import build_fmu

DT, STOP, HEADING0 = 0.1, 60.0, math.radians(30.0)
#: (time from which [s], rudder command [rad])
SCHEDULE = ((0.0, math.radians(10.0)), (10.5, math.radians(-20.0)), (30.5, math.radians(35.0)))
OUTPUTS = ("north", "east", "heading", "surge_speed", "sway_speed", "speed", "yaw_rate",
           "rudder_angle")


def rudder_at(t: np.ndarray) -> np.ndarray:
    """The rudder command held at times ``t`` [s]."""
    t = np.asarray(t) + 1e-9
    out = np.full(t.shape, SCHEDULE[0][1])
    for t0, value in SCHEDULE[1:]:
        out[t >= t0] = value
    return out


def run_fmu(path: Path) -> np.ndarray:
    import fmpy

    n0 = approach_state(get_ship("kvlcc2-l7"), trim=True).inputs["propeller_rps"]
    points = [(0.0, SCHEDULE[0][1], n0)]
    for (t0, value), (_, before) in zip(SCHEDULE[1:], SCHEDULE[:-1]):
        points += [(t0, before, n0), (t0, value, n0)]  # (a step: two points at one time)
    points.append((STOP, SCHEDULE[-1][1], n0))
    inputs = np.array(points, dtype=[("time", float), ("rudder_command", float),
                                     ("propeller_rps", float)])
    return fmpy.simulate_fmu(str(path), start_time=0.0, stop_time=STOP, step_size=1.0,
                             output_interval=1.0, input=inputs, output=list(OUTPUTS),
                             start_values={"initial_heading": HEADING0, "integration_step": DT})


def run_simulate() -> dict[str, np.ndarray]:
    ship = get_ship("kvlcc2-l7")
    start = approach_state(ship, trim=True)
    x0 = start.state.copy()
    x0[list(ship.model.state_labels).index("heading")] = HEADING0
    n = int(round(STOP / DT))
    t = np.arange(n + 1) * DT
    reference = np.stack([rudder_at(t), np.full(n + 1, start.inputs["propeller_rps"])], axis=1)
    res = simulate(Problem(ship=ship, x0=x0, actuator_x0=[start.inputs["rudder_angle"]],
                           t_final=STOP, dt=DT, controller_dt=DT, reference=reference,
                           record_every=1))
    out = {name: res.output[0, :, list(res.output_labels).index(name)]
           for name in OUTPUTS if name in res.output_labels}
    out["rudder_angle"] = res.state[0, :, list(res.state_labels).index("rudder_angle")]
    out["time"] = res.time
    return out


def main(out_dir: Path) -> None:
    out_dir.mkdir(parents=True, exist_ok=True)
    fmu = build_fmu("kvlcc2-l7", out_dir / "kvlcc2-l7.fmu", force=True)
    by_fmu, whole = run_fmu(fmu), run_simulate()
    # simulate's records at the FMU's communication points (every second, and the changes)
    k = np.rint(np.asarray(by_fmu["time"]) / DT).astype(int)
    by_simulate = {name: v[k] for name, v in whole.items()}
    np.testing.assert_allclose(by_fmu["time"], by_simulate["time"], rtol=0, atol=1e-9)
    print(f"{'output':14s} {'max |FMU - simulate|':>22s}")
    worst = 0.0
    for name in OUTPUTS:
        d = float(np.max(np.abs(by_fmu[name] - by_simulate[name])))
        worst = max(worst, d)
        print(f"{name:14s} {d:22.3e}")
    print(f"largest difference {worst:.3e} (SI units) over {STOP:g} s, {k.size - 1} doStep "
          "calls")

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    L = get_ship("kvlcc2-l7").length
    fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(11.0, 3.6), layout="constrained")
    ax1.plot(by_simulate["east"] / L, by_simulate["north"] / L, "-", lw=3, alpha=0.4,
             label="simulate")
    ax1.plot(by_fmu["east"] / L, by_fmu["north"] / L, "k.", ms=3, label="FMU (fmpy)")
    ax1.set_xlabel("east / L")
    ax1.set_ylabel("north / L")
    ax1.set_aspect("equal")
    ax1.legend(fontsize=8)
    ax2.plot(by_simulate["time"], np.degrees(by_simulate["heading"]), lw=3, alpha=0.4)
    ax2.plot(by_fmu["time"], np.degrees(by_fmu["heading"]), "k.", ms=3)
    ax2.step(by_fmu["time"], np.degrees(rudder_at(by_fmu["time"])), where="post", color="C1",
             lw=1, label="rudder command [°]")
    ax2.set_xlabel("time [s]")
    ax2.set_ylabel("heading [°]")
    ax2.legend(fontsize=8)
    for name in ("north", "east", "heading", "yaw_rate"):
        ax3.plot(by_fmu["time"], by_fmu[name] - by_simulate[name], label=name)
    ax3.set_ylim(-1e-9, 1e-9)
    ax3.text(0.5, 0.9, f"largest |difference| {worst:.1e}", transform=ax3.transAxes,
             ha="center", fontsize=9)
    ax3.set_xlabel("time [s]")
    ax3.set_ylabel("FMU − simulate (SI), tolerance ±1e-9")
    ax3.legend(fontsize=8, loc="lower left")
    fig.suptitle("KVLCC2 L7 FMU (seahelm fmu, run by fmpy) against simulate()")
    fig.savefig(out_dir / "fmu_fmpy.png", dpi=110)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path("."))
