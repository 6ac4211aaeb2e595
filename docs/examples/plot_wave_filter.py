"""
Wave filtering: the Mariner's autopilot with and without a Kalman filter
========================================================================

The Mariner (nonlinear model, steering gear 5 °/s) holds its course in an irregular sea of
h3% = 6 m whose first-order wave yaw moment is 3·10⁹ N·m per radian of wave slope. The PID of
bandwidth 0.05 rad/s on the measured heading and yaw rate chases every wave; the PID of
bandwidth 0.07 rad/s fed by the wave filter (:mod:`seahelm.control.wave_filter`) holds the same
low-frequency heading error with a fraction of the rudder motion. The design in the shell::

    seahelm linearize mariner-nonlinear
    seahelm autopilot tune mariner-nonlinear --bandwidth 0.07 --damping 0.8
"""

import math

import matplotlib.pyplot as plt
import numpy as np
from scipy import signal

from seahelm.analysis.equilibria.equilibrium import approach_state
from seahelm.analysis.equilibria.linearisation import linearize
from seahelm.analysis.steering.indices import steering_indices
from seahelm.control.autopilot_design import pid_pole_placement
from seahelm.control.pid import PID_HEADING
from seahelm.control.wave_filter import design_wave_filter, wave_filtered
from seahelm.environment.wave_yaw import wave_yaw_filter
from seahelm.environment.shaping import shaping_filter
from seahelm.environment.spectra import spectrum_from_wave_height
from seahelm.ships import get_ship
from seahelm.simulation.engine import simulate
from seahelm.simulation.signals import Sea

ship = get_ship("mariner-nonlinear")
lin = linearize(ship, actuator=False, disturbances=True)
nomoto = steering_indices(lin).nomoto
K, T = nomoto.gain, nomoto.time_constant
i_r = lin.state_labels.index("yaw_rate")
rudder_per_nm = (lin.B[i_r, lin.input_labels.index("moment_z")]
                 / lin.B[i_r, lin.input_labels.index("rudder_angle")])
print(f"Nomoto K = {K:.4g} 1/s, T = {T:.4g} s; 1 N·m of yaw moment = {rudder_per_nm:.3g} rad")

# %%
# The filter: Nomoto ship + rudder bias + the wave yaw from seahelm's shaping filter.
H3, MOMENT = 6.0, 3e9
ordinate = shaping_filter(spectrum_from_wave_height("rakhmanin-firsov-2", H3))
wave = wave_yaw_filter(ordinate, gain=K, time_constant=T, rudder_per_slope=MOMENT * rudder_per_nm)
design = design_wave_filter(K, T, wave, 0.5, measurement_std=math.radians(0.05))
print("posterior std of the LF heading and yaw rate:",
      np.degrees(np.sqrt(np.diag(design.covariance)[:2])))

# %%
# Four sea realisations (one batch per loop); the figure shows the first.
dt, tf = 0.1, 1500.0
t = np.arange(0.0, tf + dt / 2, dt)
moment = np.stack([MOMENT * Sea(h3=H3, quantity="slope", seed=s)(t) for s in range(4)])
start = approach_state(ship, trim=True)
loops = {"PID (0.05 rad/s) on the measurement": (PID_HEADING, 0.05),
         "PID (0.07 rad/s) + wave filter": (wave_filtered(PID_HEADING, design), 0.07)}
b, a = signal.butter(4, 0.1 / (math.pi / dt))
fig, axes = plt.subplots(3, 1, figsize=(7, 7), sharex=True, layout="constrained")
for label, (controller, bandwidth) in loops.items():
    gains = pid_pole_placement(K, T, bandwidth=bandwidth, max_command=ship.max_rudder).params
    res = simulate(ship=ship, x0=start.state, actuator_x0=[start.inputs["rudder_angle"]],
                   t_final=tf, dt=dt, controller=controller, controller_params=gains,
                   controller_dt=0.5, reference={"heading": 0.0},
                   disturbance={"moment_z": moment[:, :, None]})
    psi, delta = res["heading"], res["rudder_angle"]
    k0 = int(300 / dt)
    rate = np.diff(delta, axis=1)[:, k0:] / dt
    lf = signal.filtfilt(b, a, psi, axis=1)[:, k0:]
    print(f"{label}: RMS rudder rate {np.degrees(np.sqrt(np.mean(rate ** 2))):.3g} deg/s, "
          f"travel {np.degrees(np.abs(np.diff(delta[:, k0:], axis=1)).sum(axis=1).mean()):.4g}"
          f" deg per run, LF heading error RMS {np.degrees(np.sqrt(np.mean(lf ** 2))):.3g} deg")
    psi, delta = psi[0], delta[0]
    axes[0].plot(t, np.degrees(psi), lw=0.8, label=label)
    axes[1].plot(t, np.degrees(signal.filtfilt(b, a, psi)), label=label)
    axes[2].plot(t, np.degrees(delta), lw=0.8, label=label)
axes[0].set_ylabel("heading [deg]")
axes[1].set_ylabel("LF heading [deg]")
axes[2].set_ylabel("rudder [deg]")
axes[2].set_xlabel("time [s]")
axes[0].legend(fontsize=8)
for ax in axes:
    ax.grid(alpha=0.3)
plt.show()
