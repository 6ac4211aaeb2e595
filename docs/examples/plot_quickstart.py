"""
Course changes of the Mariner under a PID autopilot
===================================================

Four course changes in one batch (one compiled run of the engine), the result as an xarray
Dataset with units and run metadata, and the standard figure: heading, rudder, yaw rate and
track.
"""

import numpy as np

from seahelm.control.pid import PID_HEADING, PIDHeadingParams
from seahelm.simulation.engine import simulate
from seahelm.ships import get_ship
from seahelm.vessels.nomoto import NOMOTO2

mariner = get_ship("mariner-nomoto2").params
courses = np.radians([10.0, 20.0, 45.0, 90.0])
result = simulate(NOMOTO2, mariner, np.zeros(5), t_final=900.0, dt=0.1,
                  controller=PID_HEADING,
                  controller_params=PIDHeadingParams(kp=4.0, ki=0.0002, kd=110.0),
                  controller_dt=0.5, reference=courses.reshape(-1, 1, 1))
print(result.messages())

# %%
# The runs as a Dataset: dims (run, time), every channel with its unit.
ds = result.to_xarray()
print(ds["heading"].attrs["units"], np.degrees(ds["heading"][:, -1].values).round(2))

# %%
# The figure.
fig = result.plot()
