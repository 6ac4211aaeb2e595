"""Course keeping in wind and waves with and without the compensation channels of Lvov (2014).

The Mariner-class ship (Voitkunsky model, catalog ``mariner-voitkunsky``) holds its course
under the PID autopilot in wind and waves. Every case is a hand-written scenario file,
``examples/compensation_<case>_<pid|compensated>.toml``, whose ``[environment.wind]`` and
``[environment.waves]`` sections make the engine compute Lvov's wind loads (eq. (12)) and
mean wave loads (eq. (8)-(10); in the storm an irregular sea modulates them) at every step from
the ship's live heading and speed. Per case:

* ``PID``                 — the compensation channels off (wind_gain = wave_gain = 0);
* ``PID + δ_k``           — channels on, δ_k = the ship model's balancing rudder angle for the
  wind (channel 5) and the extra angle for the waves (channel 6), as written in the file
  (what ``seahelm compensate --ship mariner ...`` prints);
* ``PID + δ_k (12)/(14)`` — the same file with the heading to steer and δ_k of eq. (12) and the
  wave term of eq. (14) as printed (computed here by ``seahelm.studies.lvov2014``).

The weather acts from t = 0: the ship starts on the heading to steer with the rudder amidships.
Metrics over the run: mean and max |heading error|, ∫|e| dt, rudder reversals per minute (moves
under 0.05° ignored), settling time into ±1°, mean |δ − δ_k| (δ_k = the model's steady rudder
of the file), and the loss-of-controllability flag |δ_k| + δ_b > 35° (δ_b = max |δ − δ_k| over
60 s, counted from t = 120 s).

Run:  python examples/compensation_table.py [--t-final 900]
"""

from __future__ import annotations

import argparse
import math
import re
import sys
import warnings
from pathlib import Path

import numpy as np

from seahelm.analysis.maneuvers.course_keeping import heading_metrics
from seahelm.control.compensation import controllability_monitor
from seahelm.errors import ValidityRangeWarning
from seahelm.scenario import parse_scenario, run_batch
from seahelm.studies.lvov2014 import WindWaveCase, wind_wave_scenario

EXAMPLES = Path(__file__).resolve().parent
R = math.radians
#: case key in the file names -> (name in the table, the weather for the paper's δ_k)
CASES = {
    "calm": ("calm", WindWaveCase("calm")),
    "wind": ("wind", WindWaveCase("wind", 15.0, R(60))),
    "windwaves": ("wind + waves", WindWaveCase("wind + waves", 15.0, R(60), 6.75, R(60))),
    "storm": ("storm (irregular)", WindWaveCase("storm", 15.0, R(120), 6.75, R(120))),
}


def _value(text: str, key: str) -> float:
    return float(re.search(rf"^{key} = (\S+)", text, re.M).group(1))


def _paper_text(text: str, case: WindWaveCase) -> str:
    """The compensated file with the paper's heading to steer and δ_k (eq. (12)/(14))."""
    info = wind_wave_scenario(case, t_final=10.0, delta_k_method="paper")["info"]
    values = {"heading_deg": math.degrees(info["heading_to_steer"]),
              "delta_k_wind_deg": math.degrees(info["delta_k_wind"]),
              "delta_k_wave_deg": math.degrees(info["delta_k_wave"])}
    for key, value in values.items():
        text = re.sub(rf"^{key} = \S+", f"{key} = {value:.6f}", text, flags=re.M)
    return text


def _run(text: str, source: str, t_final: float) -> tuple[dict, object]:
    text = re.sub(r"^t_final = \S+", f"t_final = {t_final}", text, flags=re.M)
    with warnings.catch_warnings():
        # the Mariner's block coefficient 0.542 is below eq. (5)-(7)'s range (0.6, 0.8)
        warnings.simplefilter("ignore", ValidityRangeWarning)
        return run_batch(parse_scenario(text, source=source)), text


def run_case(key: str, t_final: float = 900.0) -> list[dict]:
    name, case = CASES[key]
    rows = []
    model_text = (EXAMPLES / f"compensation_{key}_compensated.toml").read_text()
    steady = R(_value(model_text, "delta_k_wind_deg") + _value(model_text, "delta_k_wave_deg"))
    runs = [("PID", f"compensation_{key}_pid.toml", None),
            ("PID + δ_k", f"compensation_{key}_compensated.toml", None)]
    if key != "calm":
        runs.append(("PID + δ_k (12)/(14)", f"compensation_{key}_compensated.toml", case))
    for label, file, paper in runs:
        text = (EXAMPLES / file).read_text()
        if paper is not None:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityRangeWarning)
                text = _paper_text(text, paper)
        res, text = _run(text, file, t_final)
        e = R(_value(text, "heading_deg")) - res["heading"][0]
        dt = float(res.time[1] - res.time[0])
        m = heading_metrics(e, res["rudder_angle"][0], dt=dt, delta_k=steady, start=0.0)
        mon = controllability_monitor(res["rudder_angle"][0], np.full(e.size, steady), dt=dt,
                                         start=120.0)
        dk = _value(text, "delta_k_wind_deg") + _value(text, "delta_k_wave_deg")
        rows.append(dict(
            case=name, controller=label, delta_k=dk if label != "PID" else math.degrees(steady),
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


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--t-final", type=float, default=900.0, help="duration [s] (default 900)")
    args = ap.parse_args(argv)
    rows = [r for key in CASES for r in run_case(key, args.t_final)]
    print_table(rows)


if __name__ == "__main__":
    main()
