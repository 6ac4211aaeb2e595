"""Template of the compiled closed loop (vessel + actuator + controller + integrator).

:func:`seahelm.simulation.engine.compile_closed_loop` writes one module per combination of
components: this file's text with the ``<header>`` block replaced by imports that bind
``model_rhs``, ``model_output``, ``actuator_rhs``, ``actuator_output``, ``controller_init``,
``controller_step``, the sizes, and the routing functions that the composition
(:mod:`seahelm.simulation.composition`) derives from the components' signal names; the
``<footer>`` block holds the integrator's stepper. Each generated module lives in the kernel
cache directory and is compiled by numba with ``cache=True``, so a combination compiles once per
machine, not once per process.

As it stands (the default header), this module is the Nomoto-1 + rudder servo + PID loop with
RK4 and can be imported and run directly.

Parameters reach the components as records (``mp[i]``, read as ``p.gain``); the loop and its
inlined components are compiled with fastmath flags that allow reassociation, contraction
(FMA), reciprocal and approximate-function rewrites, but *not* ``nnan``/``ninf``, and not
``nsz`` either: LLVM folds the finiteness test away once ``nsz`` and ``reassoc`` are both on
(measured; tests/test_simulation_wiring.py guards it), so the NaN/inf detection below stays
exact.

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
NYM = 6
NYA = 1
NCA = 1
NM = 2
NSTAGES = 4
FASTMATH = {"arcp", "contract", "afn", "reassoc"}


@njit(inline="always")
def route_actuator_commands(cmd, ca):  # pragma: no cover - compiled
    ca[0] = cmd[0]


@njit(inline="always")
def route_inputs(ya, cmd, u):  # pragma: no cover - compiled
    u[0] = ya[0]


@njit(inline="always")
def route_measurements(ym, y):  # pragma: no cover - compiled
    y[0] = ym[2]
    y[1] = ym[3]
# </header>

NZ = NX + NA

# The hot loop works on thread-local copies of each run's arrays and never slices arrays per
# step: numba array views touch the parent's reference count atomically, and on an array shared
# by all threads that serialises the cores.


@njit(cache=True, inline="always", fastmath=FASTMATH)
def closed_rhs(t, xv, xa, cmd, ca, d, mp, ap, ya, u, dxv, dxa):  # pragma: no cover - compiled
    actuator_output(xa, ca, ap, ya)
    route_inputs(ya, cmd, u)
    model_rhs(t, xv, u, d, mp, dxv)
    actuator_rhs(t, xa, ca, ap, dxa)


# <footer>
@njit(cache=True, inline="always", fastmath=FASTMATH)
def advance(t, h, xv, xa, cmd, ca, d0, d1, ds, mp, ap, ya, u, kv, ka, fv, fa, tv, ta):  # pragma: no cover
    # classic RK4 (the engine generates this function from the integrator's Butcher tableau)
    nd = d0.shape[0]
    for s in range(NSTAGES):
        c = 0.0 if s == 0 else (0.5 if s < 3 else 1.0)
        a = c
        for j in range(NX):
            tv[j] = xv[j] + (a * h * kv[s - 1, j] if s > 0 else 0.0)
        for j in range(NA):
            ta[j] = xa[j] + (a * h * ka[s - 1, j] if s > 0 else 0.0)
        for j in range(nd):
            ds[j] = d0[j] + c * (d1[j] - d0[j])
        closed_rhs(t + c * h, tv, ta, cmd, ca, ds, mp, ap, ya, u, fv, fa)
        for j in range(NX):
            kv[s, j] = fv[j]
        for j in range(NA):
            ka[s, j] = fa[j]
    for j in range(NX):
        xv[j] += h / 6.0 * (kv[0, j] + 2.0 * kv[1, j] + 2.0 * kv[2, j] + kv[3, j])
    for j in range(NA):
        xa[j] += h / 6.0 * (ka[0, j] + 2.0 * ka[1, j] + 2.0 * ka[2, j] + ka[3, j])
# </footer>


@njit(cache=True, parallel=True, fastmath=FASTMATH)
def init_runs(z, cs, cmd, ca, mp, ap, cp, ref):  # pragma: no cover - compiled
    """Call the controller's init at t = 0 for every run."""
    for ii in prange(z.shape[0]):
        i = np.int64(ii)
        u = np.empty(NU)
        ya = np.empty(max(NYA, 1))
        ym = np.empty(NYM)
        y = np.empty(max(NM, 1))
        ir = i if ref.shape[0] > 1 else 0
        xv = z[i, :NX].copy()
        xa = z[i, NX:].copy()
        cmdi = cmd[i].copy()
        cai = ca[i].copy()
        csi = cs[i].copy()
        actuator_output(xa, cai, ap[i], ya)
        route_inputs(ya, cmdi, u)
        model_output(0.0, xv, u, mp[i], ym)
        route_measurements(ym, y)
        controller_init(z[i].copy(), y, ref[ir, 0].copy(), cp[i], csi)
        cs[i, :] = csi


@njit(cache=True, parallel=True, fastmath=FASTMATH)
def run_chunk(
    k_start, k_stop, n_steps, dt, ctrl_every, rec_every,
    z, cs, cmd, ca, mp, ap, cp, dist, ref, lower, upper,
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
        # thread-local copies of everything the run touches per step (records are read in
        # place: a record is a pointer into the parameter array, without reference counting)
        xv = z[i, :NX].copy()
        xa = z[i, NX:].copy()
        zfull = z[i].copy()
        cmdi = cmd[i].copy()
        cai = ca[i].copy()
        csi = cs[i].copy()
        mpi = mp[i]
        api = ap[i]
        cpi = cp[i]
        lo = lower.copy()
        hi = upper.copy()
        u = np.empty(NU)
        ya = np.empty(max(NYA, 1))
        ym = np.empty(NYM)
        y = np.empty(max(NM, 1))
        kv = np.empty((NSTAGES, NX))
        ka = np.empty((NSTAGES, NA))
        fv = np.empty(NX)
        fa = np.empty(NA)
        tv = np.empty(NX)
        ta = np.empty(NA)
        d0 = np.empty(nd)
        d1 = np.empty(nd)
        ds = np.empty(nd)
        refk = np.empty(nr)
        idist = i if dist.shape[0] > 1 else 0
        iref = i if ref.shape[0] > 1 else 0
        dist_varies = dist.shape[1] > 1
        ref_varies = ref.shape[1] > 1
        if not dist_varies:
            for j in range(nd):
                d0[j] = dist[idist, 0, j]
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
                actuator_output(xa, cai, api, ya)
                route_inputs(ya, cmdi, u)
                model_output(t, xv, u, mpi, ym)
            if control:
                kr = k if ref_varies else 0
                for j in range(nr):
                    refk[j] = ref[iref, kr, j]
                for j in range(NX):
                    zfull[j] = xv[j]
                for j in range(NA):
                    zfull[NX + j] = xa[j]
                route_measurements(ym, y)
                controller_step(t, dt_ctrl, zfull, y, refk, cpi, csi, cmdi)
                route_actuator_commands(cmdi, cai)
            if record:
                m = k // rec_every
                for j in range(NX):
                    rec_z[i, m, j] = xv[j]
                for j in range(NA):
                    rec_z[i, m, NX + j] = xa[j]
                for j in range(NYM):
                    rec_y[i, m, j] = ym[j]
                for j in range(ncmd):
                    rec_cmd[i, m, j] = cmdi[j]
            if dist_varies:
                for j in range(nd):
                    d0[j] = dist[idist, k, j]
                    d1[j] = dist[idist, k + 1, j]
            advance(t, dt, xv, xa, cmdi, cai, d0, d1, ds, mpi, api, ya, u, kv, ka, fv, fa, tv, ta)
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
                actuator_output(xa, cai, api, ya)
                route_inputs(ya, cmdi, u)
                model_output(t + dt, xv, u, mpi, ym)
                for j in range(NX):
                    rec_z[i, m, j] = xv[j]
                for j in range(NA):
                    rec_z[i, m, NX + j] = xa[j]
                for j in range(NYM):
                    rec_y[i, m, j] = ym[j]
                for j in range(ncmd):
                    rec_cmd[i, m, j] = cmdi[j]
        # write the run's state back for the next chunk
        for j in range(NX):
            z[i, j] = xv[j]
        for j in range(NA):
            z[i, NX + j] = xa[j]
        for j in range(ncmd):
            cmd[i, j] = cmdi[j]
        for j in range(cai.shape[0]):
            ca[i, j] = cai[j]
        for j in range(csi.shape[0]):
            cs[i, j] = csi[j]
