"""Template of the compiled closed loop (vessel + actuator + controller + integrator).

:func:`seahelm.simulation.engine.compile_closed_loop` writes one module per combination of
components: this file's text with the ``<header>`` block replaced by imports that bind
``model_rhs``, ``model_output``, ``actuator_rhs``, ``actuator_output``, ``controller_init``,
``controller_step`` (each through :func:`~seahelm.simulation.inlining.inline_always`) and,
for an actuator with a closed-form step (``EXACT_ACTUATOR``), ``actuator_advance``, the
sizes, and the routing functions that the composition
(:mod:`seahelm.simulation.composition`) derives from the components' signal names; the
``<footer>`` block holds the integrator's step, generated from its Butcher tableau by
:func:`seahelm.simulation.compiled_step.compiled_advance_source` (the stages written out) or, for
a heavy model, :func:`~seahelm.simulation.compiled_step.compiled_stage_loop_source` (a loop over
the stages, so the right-hand side is inlined once; see
:data:`seahelm.simulation.engine.STAGE_LOOP_ABOVE`). Each generated module lives in the kernel
cache directory and is compiled by numba with ``cache=True``, so a combination compiles once per
machine, not once per process.

As it stands (the default header and footer), this module is the Nomoto-1 + rudder servo + PID
loop with explicit Euler and can be imported and run directly.

Parameters reach the components as records (``mp[i]``, read as ``p.gain``); the loop and its
inlined components are compiled with fastmath flags that allow reassociation, contraction
(FMA), reciprocal and approximate-function rewrites, but *not* ``nnan``/``ninf``, and not
``nsz`` either: LLVM folds the finiteness test away once ``nsz`` and ``reassoc`` are both on
(measured; tests/test_simulation_wiring.py guards it), so the NaN/inf detection below stays
exact.

Compile time shapes the loop (a new combination of components compiles on first use, and the
user waits): the components are inlined at numba-IR level (``inline="always"``), once per
call site, so the loop has one site that evaluates the outputs and each stage of the step one
site of the right-hand side (a heavy model's step loops over the stages: one site); and
everything is compiled without numba's reference-counted runtime (``_nrt=False``): the
per-run vectors are scratch buffers passed in, one set per slice of runs, so nothing is
allocated and no reference count is touched in the loop. (Marking the array arguments
``noalias``, as numba does for a ``prange`` body, made the Nomoto loop 25 % slower and the
catamaran loop no faster, measured; it is not done.) The loop is serial and
releases the GIL (``nogil=True``); the engine runs slices of the batch on a pool of threads.
A ``parallel=True``/``prange`` loop ran at the same speed but compiled 3× slower (numba's
parfor passes on the inlined loop: 46 s against 14 s for Nomoto-2 + servo + PID with RK4, on
the same machine), and a serial loop *with* the runtime ran 4–5× slower (reference counts of
the inlined array arguments, atomic, at every call site).

Status codes: 0 ok, 1 non-finite state, 2 state outside its declared bounds.
"""

import math

import numpy as np
from numba import njit

from seahelm.simulation.inlining import inline_always, local_record
from seahelm.simulation.stage import aligned_buffers

# <header>
from seahelm.actuators.servo import servo_output as _actuator_output
from seahelm.actuators.servo import servo_rhs as _actuator_rhs
from seahelm.control.pid import pid_heading_init as _controller_init
from seahelm.control.pid import pid_heading_step as _controller_step
from seahelm.vessels.nomoto import nomoto1_output as _model_output
from seahelm.vessels.nomoto import nomoto1_rhs as _model_rhs

actuator_output = inline_always(_actuator_output)
actuator_rhs = inline_always(_actuator_rhs)
controller_init = inline_always(_controller_init)
controller_step = inline_always(_controller_step)
model_output = inline_always(_model_output)
model_rhs = inline_always(_model_rhs)

NX = 4
NA = 1
NU = 1
NYM = 6
NYA = 1
NCA = 1
NM = 2
NDM = 2
EXACT_ACTUATOR = False
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


@njit(inline="always", fastmath=FASTMATH, _nrt=False)
def stages_outputs(t, k, i, xv, u, mp, ym, dist, idist, d0, ds, sg, ss):  # pragma: no cover
    pass


@njit(inline="always", fastmath=FASTMATH, _nrt=False)
def stages_step_start(t, i, xv, u, mp, d0, sg, ss):  # pragma: no cover - compiled
    pass


@njit(inline="always", fastmath=FASTMATH, _nrt=False)
def stages_rhs(t, i, xv, u, mp, d, sg, ss):  # pragma: no cover - compiled
    pass


@njit(inline="always", fastmath=FASTMATH, _nrt=False)
def closed_rhs(t, xv, xa, cmd, ca, d, mp, ap, ir, sg, ss, ya, u, dxv, dxa):  # pragma: no cover
    actuator_output(xa, ca, ap, ya)
    route_inputs(ya, cmd, u)
    stages_rhs(t, ir, xv, u, mp, d, sg, ss)
    model_rhs(t, xv, u, d, mp, dxv)
    if not EXACT_ACTUATOR:  # else the step takes the actuator states from actuator_advance
        actuator_rhs(t, xa, ca, ap, dxa)
# </header>

NZ = NX + NA


# <footer>
# generated by seahelm.simulation.compiled_step.compiled_advance_source from the tableau 'euler'
# c = [0.0]
# b = [1.0]
NSTAGES = 1


@njit(inline="always", fastmath=FASTMATH, _nrt=False)
def advance(t, h, xv, xa, cmd, ca, d0, d1, ds, mp, ap, ir, sg, ss, ya, u, kv, ka, fv, fa, tv, ta):  # pragma: no cover
    closed_rhs(t, xv, xa, cmd, ca, d0, mp, ap, ir, sg, ss, ya, u, fv, fa)
    for j in range(NX):
        xv[j] += h * fv[j]
    for j in range(NA):
        xa[j] += h * fa[j]
# </footer>


def scratch(ncmd, nca, ncs, nd, nr):
    """Fresh per-run buffers, the ``scratch`` group of :func:`run_slice` (one set per slice of
    runs).

    Views of one block, each on cache lines of its own
    (:func:`~seahelm.simulation.stage.aligned_buffers`).
    """
    return aligned_buffers([(NX,), (NA,), (NZ,), (ncmd,), (nca,), (ncs,), (NU,),
                            (max(NYA, 1),), (NYM,), (max(NM, 1),), (NSTAGES, NX),
                            (NSTAGES, NA), (NX,), (NA,), (NX,), (NA,), (nd,), (nd,), (nd,),
                            (nr,)])


@njit(inline="always", _nrt=False)
def load_run(i, z, cmd, ca, cs, xv, xa, cmdi, cai, csi):  # pragma: no cover - compiled
    """Copy run ``i``'s states, commands and controller state into the thread's buffers."""
    for j in range(NX):
        xv[j] = z[i, j]
    for j in range(NA):
        xa[j] = z[i, NX + j]
    for j in range(cmd.shape[1]):
        cmdi[j] = cmd[i, j]
    for j in range(ca.shape[1]):
        cai[j] = ca[i, j]
    for j in range(cs.shape[1]):
        csi[j] = cs[i, j]


#: ``run_slice``'s ``external`` for the controllers' init (:func:`init_runs`).
INIT_RUNS = 2


def init_runs(i_start, i_stop, state, params, signals, outcome, record, stages, scratch,
              stage_scratch, out):
    """Call the controller's init at t = 0 for runs ``i_start`` to ``i_stop`` − 1 (once per
    simulation, and for runs restarted). The arguments are the kernel's groups
    (:mod:`seahelm.simulation.kernel_args`) and ``run_slice``'s (empty) ``out``.

    :func:`run_slice` with ``external`` = :data:`INIT_RUNS`: the model's and the stages'
    outputs at the runs' state from the loop's own code (the code its zero-step observation
    runs), routed to the measurements, then the controller's init instead of its step, and
    nothing else. Not a compiled entry point of its own: that was a second compilation of the
    outputs' inlined code, with a CPython wrapper of its own, 10-15 % of a kernel's compile
    (issue 47 item 7, 2026-12-02). ``outcome`` and ``record`` are passed for their types (the
    compiled loop's signature) and left as they are.
    """
    run_slice(i_start, i_stop, 0, 0, 0, 1.0, 1, 1, INIT_RUNS, state, params, signals, outcome,
              record, stages, scratch, stage_scratch, out)


@njit(cache=True, nogil=True, fastmath=FASTMATH, _nrt=False)
def observe_runs(i_start, i_stop, k, dt, state, params, signals, stages, scratch,
                 stage_scratch, out):  # pragma: no cover - compiled
    """The outputs (the model's, then the stages') of runs ``i_start`` to ``i_stop`` − 1 at
    their state of step ``k`` into ``out[i]``: the code the loop runs before it records or
    measures, so the values are those it records (:mod:`seahelm.simulation.stepping`)."""
    z, cs, cmd, ca = state
    mp, ap, cp, lower, upper = params
    dist, ref = signals
    (xv, xa, zfull, cmdi, cai, csi, u, ya, ym, y, kv, ka, fv, fa, tv, ta, d0, d1, ds,
     refk) = scratch
    t = k * dt
    for i in range(i_start, i_stop):
        load_run(i, z, cmd, ca, cs, xv, xa, cmdi, cai, csi)
        mpi = local_record(mp[i])
        api = local_record(ap[i])
        idist = i if dist.shape[0] > 1 else 0
        for j in range(dist.shape[2]):
            d0[j] = dist[idist, 0, j]
        actuator_output(xa, cai, api, ya)
        route_inputs(ya, cmdi, u)
        model_output(t, xv, u, mpi, ym)
        stages_outputs(t, k, i, xv, u, mpi, ym, dist, idist, d0, ds, stages, stage_scratch)
        for j in range(NYM):
            out[i, j] = ym[j]


@njit(cache=True, nogil=True, fastmath=FASTMATH, _nrt=False)
def run_slice(i_start, i_stop, k_start, k_stop, n_steps, dt, ctrl_every, rec_every, external,
              state, params, signals, outcome, record, stages, scratch, stage_scratch,
              out):  # pragma: no cover - compiled
    """Advance runs ``i_start`` to ``i_stop`` − 1 from step ``k_start`` to ``k_stop`` (the state
    arrays are updated in place, so a simulation goes on chunk by chunk).

    Runs with a non-zero status are skipped; a run that becomes invalid gets status 1 or 2,
    the time and state of the first invalid step, and stops. The arrays come in the kernel's
    groups (:mod:`seahelm.simulation.kernel_args`): ``state``, ``params``, ``signals``,
    ``outcome``, ``record``, the stages' per-run arrays ``stages`` (a tuple of groups, one per
    stage of the loop: :mod:`seahelm.simulation.stage`), and this thread's ``scratch``
    (:func:`scratch`) and ``stage_scratch`` (the stages'). With ``external``
    the controller is not stepped: the commands held in ``state``'s ``cmd`` are applied as
    they are (an external controller, :class:`seahelm.simulation.stepping.Simulator`).
    With ``external`` = :data:`INIT_RUNS` the runs' outputs at ``k_start`` go to the
    controller's init instead, for every run whatever its status (:func:`init_runs`: no step,
    no record, the commands as they are; the reference and disturbance at index 0).
    With a non-empty ``out`` (runs, outputs) each run's outputs at step ``k_stop`` are written
    into ``out[i]``, by the loop's own code (the step is not taken: the next call starts
    there) — a stepped interval's observation without a second call
    (an empty ``out``, shape (0, outputs): nothing is observed).
    """
    z, cs, cmd, ca = state
    mp, ap, cp, lower, upper = params
    dist, ref = signals
    status, t_fail, z_fail = outcome
    rec_z, rec_y, rec_cmd = record
    (xv, xa, zfull, cmdi, cai, csi, u, ya, ym, y, kv, ka, fv, fa, tv, ta, d0, d1, ds,
     refk) = scratch
    nd = dist.shape[2]
    nr = ref.shape[2]
    ncmd = cmd.shape[1]
    dt_ctrl = ctrl_every * dt
    has_bounds = False
    for j in range(NZ):
        if lower[j] > -np.inf or upper[j] < np.inf:
            has_bounds = True
    dist_varies = dist.shape[1] > 1
    ref_varies = ref.shape[1] > 1
    observe = out.shape[0] > 0
    init = external == INIT_RUNS
    for i in range(i_start, i_stop):
        if not init and status[i] != 0:
            continue
        load_run(i, z, cmd, ca, cs, xv, xa, cmdi, cai, csi)
        # stack copies of the run's parameter records: see local_record
        mpi = local_record(mp[i])
        api = local_record(ap[i])
        cpi = local_record(cp[i])
        idist = i if dist.shape[0] > 1 else 0
        iref = i if ref.shape[0] > 1 else 0
        if init or not dist_varies:
            for j in range(nd):
                d0[j] = dist[idist, 0, j]
                d1[j] = d0[j]
        failed = 0
        # countdowns instead of k % n: integer division costs more than the model's algebra
        to_ctrl = (ctrl_every - k_start % ctrl_every) % ctrl_every
        to_rec = (rec_every - k_start % rec_every) % rec_every
        # the record after the last step is one more iteration, that records and stops (the
        # final state is recorded even when the step count is not a multiple of rec_every)
        # (observed: one more iteration that computes the outputs at k_stop and stops)
        k_end = k_stop + 1 if k_stop == n_steps or observe or init else k_stop
        for k in range(k_start, k_end):
            t = k * dt
            last = k == n_steps and not init
            halt = k == k_stop  # (reached only at the last step, observed, or the init)
            on_grid = to_rec == 0
            record = (on_grid and not halt) or last
            control = to_ctrl == 0 and not halt
            to_rec = rec_every - 1 if on_grid else to_rec - 1
            to_ctrl = ctrl_every - 1 if control else to_ctrl - 1
            # the model's outputs only when recorded or measured (NM is a compile-time
            # constant: for a controller that measures nothing the branch is gone)
            if record or (control and NM > 0) or halt:
                actuator_output(xa, cai, api, ya)
                route_inputs(ya, cmdi, u)
                model_output(t, xv, u, mpi, ym)
                # the stages' outputs follow the model's
                stages_outputs(t, k, i, xv, u, mpi, ym, dist, idist, d0, ds, stages,
                               stage_scratch)
            if control:
                kr = k if ref_varies else 0
                for j in range(nr):
                    refk[j] = ref[iref, kr, j]
                for j in range(NX):
                    zfull[j] = xv[j]
                for j in range(NA):
                    zfull[NX + j] = xa[j]
                route_measurements(ym, y)
                if external == 0:
                    controller_step(t, dt_ctrl, zfull, y, refk, cpi, csi, cmdi)
                route_actuator_commands(cmdi, cai)
            if record:
                m = k // rec_every if on_grid else k // rec_every + 1  # (the final record)
                for j in range(NX):
                    rec_z[i, m, j] = xv[j]
                for j in range(NA):
                    rec_z[i, m, NX + j] = xa[j]
                for j in range(NYM):
                    rec_y[i, m, j] = ym[j]
                for j in range(ncmd):
                    rec_cmd[i, m, j] = cmdi[j]
            if halt:
                if observe:
                    for j in range(NYM):
                        out[i, j] = ym[j]
                if init:
                    for j in range(nr):
                        refk[j] = ref[iref, 0, j]
                    for j in range(NX):
                        zfull[j] = xv[j]
                    for j in range(NA):
                        zfull[NX + j] = xa[j]
                    route_measurements(ym, y)
                    controller_init(zfull, y, refk, cpi, csi)
                break
            if dist_varies:
                for j in range(nd):
                    d0[j] = dist[idist, k, j]
                    d1[j] = dist[idist, k + 1, j]
            stages_step_start(t, i, xv, u, mpi, d0, stages, stage_scratch)
            advance(t, dt, xv, xa, cmdi, cai, d0, d1, ds, mpi, api, i, stages, stage_scratch,
                    ya, u, kv, ka, fv, fa, tv, ta)
            # one finiteness test of the sum per step (NaN or ±inf in any state makes it
            # non-finite); only then, or with declared bounds, the state-by-state test
            acc = 0.0
            for j in range(NX):
                acc += xv[j]
            for j in range(NA):
                acc += xa[j]
            if has_bounds or not np.isfinite(acc):
                for j in range(NZ):
                    v = xv[j] if j < NX else xa[j - NX]
                    if not np.isfinite(v):
                        failed = 1
                        break
                    if v < lower[j] or v > upper[j]:
                        failed = 2
            if failed != 0:
                status[i] = failed
                t_fail[i] = (k + 1) * dt
                for j in range(NX):
                    z_fail[i, j] = xv[j]
                for j in range(NA):
                    z_fail[i, NX + j] = xa[j]
                break
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
