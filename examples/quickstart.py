"""seahelm quick start: the Python API in twenty lines.

Run:  python examples/quickstart.py [OUTDIR]
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

from seahelm.control.pid import PID_HEADING, PIDHeadingParams
from seahelm.simulation.engine import simulate
from seahelm.ships import get_ship
from seahelm.vessels.nomoto import NOMOTO2


def main(out: Path) -> None:
    mariner = get_ship("mariner-nomoto2").params
    # one compiled batch: four course changes at once
    courses = np.radians([10.0, 20.0, 45.0, 90.0])
    result = simulate(
        NOMOTO2, mariner, np.zeros(5),
        t_final=900.0, dt=0.1,
        controller=PID_HEADING, controller_params=PIDHeadingParams(kp=4.0, ki=0.0002, kd=110.0),
        controller_dt=0.5,
        reference=courses.reshape(-1, 1, 1),       # (runs, 1, channels): a constant per run
    )
    ds = result.to_xarray()
    for i, course in enumerate(courses):
        final = math.degrees(float(ds["heading"].isel(run=i, time=-1)))
        peak = math.degrees(float(np.abs(ds["rudder_angle"].isel(run=i)).max()))
        print(f"course {math.degrees(course):5.1f} deg -> final heading {final:6.2f} deg, "
              f"max rudder {peak:4.1f} deg")
    out.mkdir(parents=True, exist_ok=True)
    result.to_netcdf(out / "quickstart.nc")
    fig = result.plot()
    fig.savefig(out / "quickstart.png", dpi=100)
    print(f"wrote {out / 'quickstart.nc'} and {out / 'quickstart.png'}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path("seahelm-out"))
