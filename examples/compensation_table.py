"""Course keeping in wind and waves with and without the compensation channels of Lvov (2014).

The Mariner-class ship (Voitkunsky steering model, catalog ``mariner-voitkunsky``) holds its
course under the PID autopilot; at t = 30 s wind and waves set in. Each case is run with

* ``PID``            — the compensation channels off (wind_gain = wave_gain = 0);
* ``PID + δ_k``      — channels on, δ_k = the model's steady balancing rudder angle for the
  wind loads (channel 5) and the extra angle for the wave loads (channel 6);
* ``PID + δ_k (12)/(14)`` — channels on, δ_k from eq. (12) and the wave term of eq. (14) as
  printed (with our unit reading, see ``seahelm.control.compensation``).

Loads: wind force and moment as in eq. (12), wave sway force and yaw moment of eq. (9)-(10)
(regular waves), or in the storm case an irregular sea (eq. (9)-(10) modulated by ζ(t)² of a
Rakhmanin–Firsov sea from ``seahelm.environment.shaping``). The course setter steers
ψ* = C + β (drift angle) in every run; the feed-forward passes a 15 s first-order lag.

Metrics over t ≥ 30 s: mean and max |heading error|, ∫|e| dt, rudder reversals per minute
(moves under 0.05° ignored), settling time into ±1°, mean |δ − δ_k| (δ_k = the model's
steady rudder), and the loss-of-controllability flag |δ_k| + δ_b > 35° (δ_b = max |δ − δ_k|
over 60 s, counted from t = 150 s).

Run:  python examples/compensation_table.py [--write-toml DIR]
"""

from __future__ import annotations

import argparse
import math
import sys
import warnings
from pathlib import Path

import numpy as np

from seahelm.control import compensation as cp
from seahelm.control.pid import pid_gains_from_nomoto
from seahelm.errors import ValidityRangeWarning
from seahelm.simulation.engine import simulate

GAINS = pid_gains_from_nomoto(0.185, 107.3, 0.05, 0.8)  # Mariner K, T = T1 + T2 − T3
T_K = 15.0
R = math.radians
CASES = [
    cp.WindWaveCase("calm"),
    cp.WindWaveCase("wind", 15.0, R(60)),
    cp.WindWaveCase("wind + waves", 15.0, R(60), 6.75, R(60)),
    cp.WindWaveCase("storm (irregular)", 15.0, R(120), 6.75, R(120), irregular=True),
]
TOML_CASES = {
    "calm": cp.WindWaveCase("calm"),
    "wind": cp.WindWaveCase("wind", 15.0, R(60)),
    "windwaves": cp.WindWaveCase("wind + waves", 15.0, R(60), 6.75, R(60)),
    "storm": cp.WindWaveCase("storm (regular-wave mean loads)", 15.0, R(120), 6.75, R(120)),
}


def _scenario(case: cp.WindWaveCase, method: str, t_final: float) -> tuple[dict, dict]:
    with warnings.catch_warnings():
        # the Mariner's block coefficient 0.542 is below eq. (5)-(7)'s range (0.6, 0.8)
        warnings.simplefilter("ignore", ValidityRangeWarning)
        sc = cp.wind_wave_scenario(case, t_final=t_final, delta_k_method=method)
    return sc, sc.pop("info")


def run_case(case: cp.WindWaveCase, t_final: float = 900.0) -> list[dict]:
    rows = []
    for label, method, gain in (("PID", "model", 0.0), ("PID + δ_k", "model", 1.0),
                                ("PID + δ_k (12)/(14)", "paper", 1.0)):
        sc, info = _scenario(case, method, t_final)
        _, info_model = _scenario(case, "model", t_final)
        ctrl = cp.CompensatedPIDParams(kp=GAINS.kp, ki=GAINS.ki, kd=GAINS.kd, wind_gain=gain,
                                       wave_gain=gain, feedforward_time_constant=T_K)
        res = simulate(controller_params=ctrl, **sc)
        e = sc["reference"][:, 0] - res["heading"][0]
        m = cp.heading_metrics(e, res["rudder_angle"][0], dt=sc["dt"],
                               delta_k=info_model["steady_rudder"], start=case.onset)
        dk = info_model["steady_rudder"] * (np.arange(e.size) * sc["dt"] >= case.onset)
        mon = cp.controllability_monitor(res["rudder_angle"][0], dk, dt=sc["dt"],
                                         start=case.onset + 120.0)
        rows.append(dict(
            case=case.name, controller=label, delta_k=math.degrees(info["delta_k"]),
            mean=math.degrees(m["mean_abs_error"]), max=math.degrees(m["max_abs_error"]),
            iae=math.degrees(m["iae"]), rev=float(m["reversals_per_min"]),
            settle=float(m["settling_time"]), act=math.degrees(m["mean_activity"]),
            lost=bool(mon.lost), status=int(res.status[0]),
        ))
    return rows


def print_table(rows: list[dict], out=sys.stdout) -> None:
    head = ("| case | controller | δ_k [°] | mean abs e [°] | max abs e [°] | ∫abs e dt [°·s] "
            "| reversals/min | settling [s] | mean abs(δ − δ_k) [°] | lost control |")
    out.write(head + "\n|" + "---|" * 10 + "\n")
    for r in rows:
        settle = "never" if not math.isfinite(r["settle"]) else f"{r['settle']:.0f}"
        out.write(f"| {r['case']} | {r['controller']} | {r['delta_k']:.2f} | {r['mean']:.3f} | "
                  f"{r['max']:.2f} | {r['iae']:.0f} | {r['rev']:.2f} | {settle} | "
                  f"{r['act']:.2f} | {'yes' if r['lost'] else 'no'} |\n")


def write_toml(directory: Path) -> list[Path]:
    """Write the regular-wave cases as scenario files (numbers computed here)."""
    directory.mkdir(parents=True, exist_ok=True)
    written = []
    for key, case in TOML_CASES.items():
        sc, info = _scenario(case, "model", 900.0)
        md, fd = sc["disturbance"][-1, 0], sc["disturbance"][-1, 1]
        for kind, gain in (("pid", 0.0), ("compensated", 1.0)):
            text = f'''# Generated by examples/compensation_table.py --write-toml (do not edit by hand).
# Lvov (2014), Fig. 1: Mariner (Voitkunsky model) course keeping, {case.name}.
# True wind {case.wind_speed:g} m/s from {math.degrees(case.wind_angle):g}° off the bow; waves h3% = {case.wave_height:g} m
# from {math.degrees(case.wave_angle):g}° (regular: the mean loads of eq. (9)-(10)); wind loads as in eq. (12);
# both set in at t = {case.onset:g} s. Disturbances are the model's normalised yaw moment
# N/(I_z − N_ṙ) [rad/s²] and sway force Y/((m − Y_v̇) U) [rad/s].
# Compensation channels {"OFF (PID alone)" if gain == 0 else "ON (δ_k fed forward)"}.
title = "Mariner course keeping, {case.name}, {"PID" if gain == 0 else "PID + wind/wave compensation"}"

[vessel]
model = "voitkunsky"
catalog = "mariner-voitkunsky"

[vessel.initial]
heading_deg = {math.degrees(info["heading_to_steer"]):.6f}

[actuator]
model = "rudder-servo"

[controller]
model = "compensated-pid"
dt = 1.0

[controller.params]
kp = {GAINS.kp:.6g}
ki = {GAINS.ki:.6g}
kd = {GAINS.kd:.6g}
wind_gain = {gain:g}
wave_gain = {gain:g}
feedforward_time_constant = {T_K:g}

[controller.reference]
heading_deg = {math.degrees(info["heading_to_steer"]):.6f}
delta_k_wind_deg = {{ kind = "step", time = {case.onset:g}, after = {math.degrees(info["delta_k_wind"]):.6f} }}
delta_k_wave_deg = {{ kind = "step", time = {case.onset:g}, after = {math.degrees(info["delta_k_wave"]):.6f} }}

[environment.disturbance]
yaw_moment = {{ kind = "step", time = {case.onset:g}, after = {md:.9e} }}
sway_force = {{ kind = "step", time = {case.onset:g}, after = {fd:.9e} }}

[simulation]
t_final = 900.0
dt = 0.1
'''
            path = directory / f"compensation_{key}_{kind}.toml"
            path.write_text(text)
            written.append(path)
    return written


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--write-toml", type=Path, metavar="DIR",
                    help="also write the regular-wave cases as scenario files")
    ap.add_argument("--t-final", type=float, default=900.0)
    args = ap.parse_args(argv)
    rows = [r for case in CASES for r in run_case(case, args.t_final)]
    print_table(rows)
    if args.write_toml:
        for p in write_toml(args.write_toml):
            print(f"wrote {p}", file=sys.stderr)


if __name__ == "__main__":
    main()
