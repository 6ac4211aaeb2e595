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
from seahelm.actuators.servo import servo_output as _actuator_output
from seahelm.actuators.servo import servo_rhs as _actuator_rhs
from seahelm.control.pid import pid_heading_init as _controller_init
from seahelm.control.pid import pid_heading_step as _controller_step
from seahelm.vessels.nomoto import nomoto1_output as _model_output
from seahelm.vessels.nomoto import nomoto1_rhs as _model_rhs

actuator_output = njit(inline="always")(_actuator_output.py_func)
actuator_rhs = njit(inline="always")(_actuator_rhs.py_func)
controller_init = njit(inline="always")(_controller_init.py_func)
controller_step = njit(inline="always")(_controller_step.py_func)
model_output = njit(inline="always")(_model_output.py_func)
model_rhs = njit(inline="always")(_model_rhs.py_func)

NX = 4
NA = 1
NU = 1
NY = 6
# </header>

NZ = NX + NA

# The hot loop works on thread-local copies of each run's arrays and never slices shared
# arrays per step: numba array views touch the parent's reference count atomically, and on
# an array shared by all threads that serialises the cores.


@njit(cache=True, inline="always")
def closed_rhs(t, xv, xa, cmd, d, mp, ap, u, dxv, dxa):  # pragma: no cover - compiled
    actuator_output(xa, cmd, ap, u)
    model_rhs(t, xv, u, d, mp, dxv)
    actuator_rhs(t, xa, cmd, ap, dxa)


@njit(cache=True, inline="always")
def euler_advance(t, h, xv, xa, cmd, d0, dm, d1, mp, ap, u, kv0, kv1, kv2, kv3, ka0, ka1, ka2, ka3, tv, ta):  # pragma: no cover
    closed_rhs(t, xv, xa, cmd, d0, mp, ap, u, kv0, ka0)
    for j in range(NX):
        xv[j] += h * kv0[j]
    for j in range(NA):
        xa[j] += h * ka0[j]


@njit(cache=True, inline="always")
def heun_advance(t, h, xv, xa, cmd, d0, dm, d1, mp, ap, u, kv0, kv1, kv2, kv3, ka0, ka1, ka2, ka3, tv, ta):  # pragma: no cover
    closed_rhs(t, xv, xa, cmd, d0, mp, ap, u, kv0, ka0)
    for j in range(NX):
        tv[j] = xv[j] + h * kv0[j]
    for j in range(NA):
        ta[j] = xa[j] + h * ka0[j]
    closed_rhs(t + h, tv, ta, cmd, d1, mp, ap, u, kv1, ka1)
    for j in range(NX):
        xv[j] += 0.5 * h * (kv0[j] + kv1[j])
    for j in range(NA):
        xa[j] += 0.5 * h * (ka0[j] + ka1[j])


@njit(cache=True, inline="always")
def rk4_advance(t, h, xv, xa, cmd, d0, dm, d1, mp, ap, u, kv0, kv1, kv2, kv3, ka0, ka1, ka2, ka3, tv, ta):  # pragma: no cover
    hh = 0.5 * h
    closed_rhs(t, xv, xa, cmd, d0, mp, ap, u, kv0, ka0)
    for j in range(NX):
        tv[j] = xv[j] + hh * kv0[j]
    for j in range(NA):
        ta[j] = xa[j] + hh * ka0[j]
    closed_rhs(t + hh, tv, ta, cmd, dm, mp, ap, u, kv1, ka1)
    for j in range(NX):
        tv[j] = xv[j] + hh * kv1[j]
    for j in range(NA):
        ta[j] = xa[j] + hh * ka1[j]
    closed_rhs(t + hh, tv, ta, cmd, dm, mp, ap, u, kv2, ka2)
    for j in range(NX):
        tv[j] = xv[j] + h * kv2[j]
    for j in range(NA):
        ta[j] = xa[j] + h * ka2[j]
    closed_rhs(t + h, tv, ta, cmd, d1, mp, ap, u, kv3, ka3)
    for j in range(NX):
        xv[j] += h / 6.0 * (kv0[j] + 2.0 * kv1[j] + 2.0 * kv2[j] + kv3[j])
    for j in range(NA):
        xa[j] += h / 6.0 * (ka0[j] + 2.0 * ka1[j] + 2.0 * ka2[j] + ka3[j])


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
        xv = z[i, :NX].copy()
        xa = z[i, NX:].copy()
        cmdi = cmd[i].copy()
        csi = cs[i].copy()
        actuator_output(xa, cmdi, ap[i].copy(), u)
        model_output(0.0, xv, u, mp[i].copy(), y)
        controller_init(z[i].copy(), y, ref[ir, 0].copy(), cp[i].copy(), csi)
        cs[i, :] = csi


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
    nr = ref.shape[2]
    ncmd = cmd.shape[1]
    dt_ctrl = ctrl_every * dt
    for ii in prange(n_runs):
        i = np.int64(ii)
        if status[i] != 0:
            continue
        # thread-local copies of everything the run touches per step
        xv = z[i, :NX].copy()
        xa = z[i, NX:].copy()
        zfull = z[i].copy()
        cmdi = cmd[i].copy()
        csi = cs[i].copy()
        mpi = mp[i].copy()
        api = ap[i].copy()
        cpi = cp[i].copy()
        lo = lower.copy()
        hi = upper.copy()
        u = np.empty(NU)
        y = np.empty(NY)
        kv0 = np.empty(NX)
        kv1 = np.empty(NX)
        kv2 = np.empty(NX)
        kv3 = np.empty(NX)
        ka0 = np.empty(NA)
        ka1 = np.empty(NA)
        ka2 = np.empty(NA)
        ka3 = np.empty(NA)
        tv = np.empty(NX)
        ta = np.empty(NA)
        d0 = np.empty(nd)
        dm = np.empty(nd)
        d1 = np.empty(nd)
        refk = np.empty(nr)
        idist = i if dist.shape[0] > 1 else 0
        iref = i if ref.shape[0] > 1 else 0
        dist_varies = dist.shape[1] > 1
        ref_varies = ref.shape[1] > 1
        if not dist_varies:
            for j in range(nd):
                d0[j] = dist[idist, 0, j]
                dm[j] = d0[j]
                d1[j] = d0[j]
        failed = 0
        # countdowns instead of k % n: integer division costs more than the model's algebra
        to_ctrl = (ctrl_every - k_start % ctrl_every) % ctrl_every
        to_rec = (rec_every - k_start % rec_every) % rec_every
        for k in range(k_start, k_stop):
            t = k * dt
            record = to_rec == 0
            control = to_ctrl == 0
            to_rec = rec_every - 1 if record else to_rec - 1
            to_ctrl = ctrl_every - 1 if control else to_ctrl - 1
            if control or record:
                actuator_output(xa, cmdi, api, u)
                model_output(t, xv, u, mpi, y)
            if control:
                kr = k if ref_varies else 0
                for j in range(nr):
                    refk[j] = ref[iref, kr, j]
                for j in range(NX):
                    zfull[j] = xv[j]
                for j in range(NA):
                    zfull[NX + j] = xa[j]
                controller_step(t, dt_ctrl, zfull, y, refk, cpi, csi, cmdi)
            if record:
                m = k // rec_every
                for j in range(NX):
                    rec_z[i, m, j] = xv[j]
                for j in range(NA):
                    rec_z[i, m, NX + j] = xa[j]
                for j in range(NY):
                    rec_y[i, m, j] = y[j]
                for j in range(ncmd):
                    rec_cmd[i, m, j] = cmdi[j]
            if dist_varies:
                for j in range(nd):
                    d0[j] = dist[idist, k, j]
                    d1[j] = dist[idist, k + 1, j]
                    dm[j] = 0.5 * (d0[j] + d1[j])
            advance(t, dt, xv, xa, cmdi, d0, dm, d1, mpi, api, u, kv0, kv1, kv2, kv3, ka0, ka1, ka2, ka3, tv, ta)
            for j in range(NZ):
                v = xv[j] if j < NX else xa[j - NX]
                if not np.isfinite(v):
                    failed = 1
                    break
                if v < lo[j] or v > hi[j]:
                    failed = 2
            if failed != 0:
                status[i] = failed
                t_fail[i] = (k + 1) * dt
                for j in range(NX):
                    z_fail[i, j] = xv[j]
                for j in range(NA):
                    z_fail[i, NX + j] = xa[j]
                break
            if k + 1 == n_steps and n_steps % rec_every == 0:
                m = n_steps // rec_every
                actuator_output(xa, cmdi, api, u)
                model_output(t + dt, xv, u, mpi, y)
                for j in range(NX):
                    rec_z[i, m, j] = xv[j]
                for j in range(NA):
                    rec_z[i, m, NX + j] = xa[j]
                for j in range(NY):
                    rec_y[i, m, j] = y[j]
                for j in range(ncmd):
                    rec_cmd[i, m, j] = cmdi[j]
        # write the run's state back for the next chunk
        for j in range(NX):
            z[i, j] = xv[j]
        for j in range(NA):
            z[i, NX + j] = xa[j]
        for j in range(ncmd):
            cmd[i, j] = cmdi[j]
        for j in range(csi.shape[0]):
            cs[i, j] = csi[j]
