"""Template of the compiled closed loop (vessel + actuator + controller + integrator).

:func:`seahelm.simulation.engine.compile_closed_loop` writes one module per combination of
components: this file's text with the ``<header>`` block replaced by imports that bind
``model_rhs``, ``model_output``, ``actuator_rhs``, ``actuator_output``, ``controller_init``,
``controller_step`` and the sizes, and the ``<footer>`` block choosing the integrator. Each
generated module lives in the kernel cache directory and is compiled by numba with
``cache=True``, so a combination compiles once per machine, not once per process.

As it stands (the default header), this module is the Nomoto-1 + rudder servo + PID loop with
RK4 and can be imported and run directly.

Status codes: 0 ok, 1 non-finite state, 2 state outside its declared bounds.
"""

import numpy as np
from numba import njit, prange

# <header>
from seahelm.actuators.servo import servo_output as actuator_output
from seahelm.actuators.servo import servo_rhs as actuator_rhs
from seahelm.control.pid import pid_heading_init as controller_init
from seahelm.control.pid import pid_heading_step as controller_step
from seahelm.vessels.nomoto import nomoto1_output as model_output
from seahelm.vessels.nomoto import nomoto1_rhs as model_rhs

NX = 4
NA = 1
NU = 1
NY = 6
# </header>

NZ = NX + NA


@njit(cache=True)
def closed_rhs(t, z, cmd, d, mp, ap, u, dz):  # pragma: no cover - compiled
    actuator_output(z[NX:], cmd, ap, u)
    model_rhs(t, z[:NX], u, d, mp, dz[:NX])
    actuator_rhs(t, z[NX:], cmd, ap, dz[NX:])


@njit(cache=True)
def euler_advance(t, h, z, cmd, d0, dm, d1, mp, ap, u, k1, k2, k3, k4, tmp):  # pragma: no cover
    closed_rhs(t, z, cmd, d0, mp, ap, u, k1)
    for j in range(NZ):
        z[j] += h * k1[j]


@njit(cache=True)
def heun_advance(t, h, z, cmd, d0, dm, d1, mp, ap, u, k1, k2, k3, k4, tmp):  # pragma: no cover
    closed_rhs(t, z, cmd, d0, mp, ap, u, k1)
    for j in range(NZ):
        tmp[j] = z[j] + h * k1[j]
    closed_rhs(t + h, tmp, cmd, d1, mp, ap, u, k2)
    for j in range(NZ):
        z[j] += 0.5 * h * (k1[j] + k2[j])


@njit(cache=True)
def rk4_advance(t, h, z, cmd, d0, dm, d1, mp, ap, u, k1, k2, k3, k4, tmp):  # pragma: no cover
    hh = 0.5 * h
    closed_rhs(t, z, cmd, d0, mp, ap, u, k1)
    for j in range(NZ):
        tmp[j] = z[j] + hh * k1[j]
    closed_rhs(t + hh, tmp, cmd, dm, mp, ap, u, k2)
    for j in range(NZ):
        tmp[j] = z[j] + hh * k2[j]
    closed_rhs(t + hh, tmp, cmd, dm, mp, ap, u, k3)
    for j in range(NZ):
        tmp[j] = z[j] + h * k3[j]
    closed_rhs(t + h, tmp, cmd, d1, mp, ap, u, k4)
    for j in range(NZ):
        z[j] += h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j])


# <footer>
advance = rk4_advance
# </footer>


@njit(cache=True, parallel=True)
def init_runs(z, cs, cmd, mp, ap, cp, ref):  # pragma: no cover - compiled
    """Call the controller's init at t = 0 for every run."""
    for ii in prange(z.shape[0]):
        i = np.int64(ii)
        u = np.empty(NU)
        y = np.empty(NY)
        ir = i if ref.shape[0] > 1 else 0
        actuator_output(z[i, NX:], cmd[i], ap[i], u)
        model_output(0.0, z[i, :NX], u, mp[i], y)
        controller_init(z[i], y, ref[ir, 0], cp[i], cs[i])


@njit(cache=True, parallel=True)
def run_chunk(
    k_start, k_stop, n_steps, dt, ctrl_every, rec_every,
    z, cs, cmd, mp, ap, cp, dist, ref, lower, upper,
    status, t_fail, z_fail, rec_z, rec_y, rec_cmd,
):  # pragma: no cover - compiled
    """Advance every run from step ``k_start`` to ``k_stop`` (state arrays updated in place).

    Runs with a non-zero status are skipped; a run that becomes invalid gets status 1 or 2,
    the time and state of the first invalid step, and stops.
    """
    n_runs = z.shape[0]
    nd = dist.shape[2]
    for ii in prange(n_runs):
        i = np.int64(ii)
        if status[i] != 0:
            continue
        zi = z[i]
        cmdi = cmd[i]
        u = np.empty(NU)
        y = np.empty(NY)
        k1 = np.empty(NZ)
        k2 = np.empty(NZ)
        k3 = np.empty(NZ)
        k4 = np.empty(NZ)
        tmp = np.empty(NZ)
        dm = np.empty(nd)
        idist = i if dist.shape[0] > 1 else 0
        iref = i if ref.shape[0] > 1 else 0
        dist_varies = dist.shape[1] > 1
        ref_varies = ref.shape[1] > 1
        for k in range(k_start, k_stop):
            t = k * dt
            record = k % rec_every == 0
            if k % ctrl_every == 0 or record:
                actuator_output(zi[NX:], cmdi, ap[i], u)
                model_output(t, zi[:NX], u, mp[i], y)
                if k % ctrl_every == 0:
                    kr = k if ref_varies else 0
                    controller_step(t, ctrl_every * dt, zi, y, ref[iref, kr], cp[i], cs[i], cmdi)
            if record:
                m = k // rec_every
                for j in range(NZ):
                    rec_z[i, m, j] = zi[j]
                for j in range(NY):
                    rec_y[i, m, j] = y[j]
                for j in range(cmdi.shape[0]):
                    rec_cmd[i, m, j] = cmdi[j]
            kd0 = k if dist_varies else 0
            kd1 = k + 1 if dist_varies else 0
            for j in range(nd):
                dm[j] = 0.5 * (dist[idist, kd0, j] + dist[idist, kd1, j])
            advance(t, dt, zi, cmdi, dist[idist, kd0], dm, dist[idist, kd1],
                    mp[i], ap[i], u, k1, k2, k3, k4, tmp)
            failed = 0
            for j in range(NZ):
                v = zi[j]
                if not np.isfinite(v):
                    failed = 1
                    break
                if v < lower[j] or v > upper[j]:
                    failed = 2
            if failed != 0:
                status[i] = failed
                t_fail[i] = (k + 1) * dt
                for j in range(NZ):
                    z_fail[i, j] = zi[j]
                break
            if k + 1 == n_steps and n_steps % rec_every == 0:
                m = n_steps // rec_every
                actuator_output(zi[NX:], cmdi, ap[i], u)
                model_output(t + dt, zi[:NX], u, mp[i], y)
                for j in range(NZ):
                    rec_z[i, m, j] = zi[j]
                for j in range(NY):
                    rec_y[i, m, j] = y[j]
                for j in range(cmdi.shape[0]):
                    rec_cmd[i, m, j] = cmdi[j]
