"""Write ``steady_turn_log.csv``: a simulated multi-step rudder manoeuvre of the Voitkunsky model.

The Mariner-class parameter set ``mariner-voitkunsky`` is run through the compiled engine with
the rudder servo and an open-loop rudder schedule: 5°, 10°, ..., 30° to starboard, each held for
600 s. The log has the columns ``time`` [s], ``rudder_angle`` [deg] and ``yaw_rate`` [deg/s],
sampled every 2 s, with Gaussian yaw-rate sensor noise of 0.002 deg/s (seed 4).

Identify the reduced steady-turn model from it with::

    seahelm identify steady-turn examples/steady_turn_log.csv --angles deg

Run: ``python examples/make_steady_turn_log.py [OUT.csv]``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

RUDDER_STEPS_DEG = (5.0, 10.0, 15.0, 20.0, 25.0, 30.0)
HOLD = 600.0  # [s] per rudder step
DT = 0.5  # [s] integration step
RECORD_EVERY = 4  # -> 2 s samples
NOISE_DEG_S = 0.002  # yaw-rate sensor noise [deg/s]
SEED = 4


def simulate_manoeuvre(rudder_steps_deg=RUDDER_STEPS_DEG, hold=HOLD, dt=DT,
                       record_every=RECORD_EVERY):
    """Simulate the manoeuvre; returns (time [s], rudder_angle [rad], yaw_rate [rad/s], result)."""
    from seahelm.actuators.servo import RUDDER_SERVO, ServoParams
    from seahelm.control.open_loop import OPEN_LOOP
    from seahelm.simulation.engine import simulate
    from seahelm.ships import get_ship
    from seahelm.vessels.voitkunsky import VOITKUNSKY

    params = get_ship("mariner-voitkunsky").params
    steps = np.radians(np.asarray(rudder_steps_deg, dtype=float))
    t_final = hold * len(steps)
    grid = np.arange(int(round(t_final / dt)) + 1) * dt
    schedule = steps[np.minimum((grid // hold).astype(int), len(steps) - 1)]
    res = simulate(VOITKUNSKY, params, VOITKUNSKY.initial_state(), t_final=t_final, dt=dt,
                   controller=OPEN_LOOP, reference=schedule[:, None], actuator=RUDDER_SERVO,
                   actuator_params=ServoParams(), record_every=record_every, throw=True)
    time = grid[::record_every][: res["yaw_rate"].shape[1]]
    return time, res["rudder_angle"][0], res["yaw_rate"][0], res


def write_log(path: Path, noise_deg_s: float = NOISE_DEG_S, seed: int = SEED) -> Path:
    """Simulate and write the CSV (angles in degrees)."""
    time, rudder, yaw_rate, _ = simulate_manoeuvre()
    rng = np.random.default_rng(seed)
    yaw_deg = np.degrees(yaw_rate) + noise_deg_s * rng.standard_normal(yaw_rate.size)
    path = Path(path)
    with path.open("w") as fh:
        fh.write("time,rudder_angle,yaw_rate\n")
        for row in zip(time, np.degrees(rudder), yaw_deg):
            fh.write(f"{row[0]:.1f},{row[1]:.6f},{row[2]:.7f}\n")
    return path


if __name__ == "__main__":
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).with_name(
        "steady_turn_log.csv")
    write_log(out)
    print(f"wrote {out}")
