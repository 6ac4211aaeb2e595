"""Stepping a batch from outside: :class:`Simulator`, one or more controller intervals a call.

``simulate(problem)`` runs a whole horizon in one go. A :class:`Simulator` built from the same
:class:`~seahelm.simulation.problem.Problem` runs the *same* compiled loop (the kernel of
:func:`~seahelm.simulation.closed_loop.compile_closed_loop`, on the same arrays,
:mod:`seahelm.simulation.kernel_args`) but stops after every ``step``: between two calls the
caller reads the outputs by name, gives the next commands (an external controller: a
reinforcement-learning agent, a co-simulation master, a hardware loop), or moves a run's
state. Nothing of the model or the integrator runs in Python, so stepping one interval at a
time for the whole horizon gives the trajectories of ``simulate(problem)`` bit for bit (the
loop is resumable at any step: it already runs in slices, :mod:`seahelm.simulation.slicing`).

A *coupling hook* (``Simulator(problem, coupling=f)``) is called between controller intervals
with every run's outputs, and may write the next interval's commands and disturbances: ships
that see each other, a sensor with a delay.

Example
-------
>>> import numpy as np
>>> from seahelm import Problem, Simulator
>>> from seahelm.vessels.nomoto import NOMOTO1, Nomoto1Params
>>> problem = Problem(model=NOMOTO1, params=Nomoto1Params(gain=0.1, time_constant=20.0,
...                                                 speed=5.0),
...                   x0=np.zeros(4), t_final=20.0, dt=0.1,
...                   controller_dt=1.0)
>>> sim = Simulator(problem)
>>> obs = sim.reset()
>>> obs = sim.step({"rudder_command": 0.1}, n=5)   # five 1 s intervals, rudder 0.1 rad
>>> float(obs.time[0]), round(float(obs["heading"][0]), 4)
(5.0, 0.0033)
"""

from __future__ import annotations

import copy
import math
import operator
from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import ParameterError, SimulationDiverged
from .engine import Batch, failure_text, prepare
from .problem import Problem
from .slicing import drive, quiet
from .stepping_io import (Observation, _spans, check_commands, restore_rows, run_index,
                          run_indices)

if TYPE_CHECKING:  # pragma: no cover
    from ..results import SimResult

__all__ = ["Simulator", "Observation"]

#: Status a run not stepped this call holds for the call (the kernel skips every run whose
#: status is not 0; the run gets its own status back after the call).
_HELD = 99


class Simulator:
    """A problem's batch, stepped from outside one or more controller intervals at a time.

    Parameters
    ----------
    problem : Problem
        What to simulate: its horizon (``t_final``) bounds the steps, its controller gives the
        commands unless :meth:`step` is given them, its recordings (every ``record_every``-th
        step) fill :meth:`result`.
    coupling : callable, optional
        ``coupling(time, outputs, commands, disturbance)``, called after every controller
        interval of a :meth:`step` (before the next one), with the stepped runs' times (runs,)
        [s], their outputs (runs, outputs) (read-only, by :attr:`output_labels`), the commands
        of the next interval (runs, commands) by :attr:`command_labels` (writable; None when
        the step takes the controller's commands) and the disturbance inputs at the
        interval's start (runs, disturbances) by :attr:`disturbance_labels`, writable: what it
        leaves there is held over the next interval (the recorded ``disturbance`` of
        :meth:`result` stays the problem's). A numba function works as well as a numpy one.
    throw : bool
        Raise :class:`~seahelm.errors.SimulationDiverged` when a run diverges in a step (the
        step is done, the run stays diverged), instead of only marking it in ``status``.

    Notes
    -----
    Bad input (commands of the wrong shape, unknown names, NaN; ``runs`` out of range; a step
    before :meth:`reset`; a hook that raises or writes NaN) raises one
    :class:`~seahelm.errors.ParameterError` and changes no state. A run that diverges stops
    at its time and state as in ``simulate`` (``status``, :meth:`failure`); stepping it
    further is refused for that run only.
    """

    def __init__(self, problem: Problem, *, coupling: Callable[..., Any] | None = None,
                 throw: bool = False) -> None:
        if not isinstance(problem, Problem):
            raise ParameterError(f"must be a Problem, got {type(problem).__name__}",
                                 field="problem")
        if coupling is not None and not callable(coupling):
            raise ParameterError(f"must be callable, got {type(coupling).__name__}",
                                 field="coupling")
        self.problem, self.coupling, self.throw = problem, coupling, throw
        self._batch: Batch = prepare(problem, keep_pool=True)
        b = self._batch
        wiring = problem.wiring
        self.command_labels: tuple[str, ...] = wiring.commands
        self.command_units: tuple[str, ...] = wiring.command_units
        self.output_labels, self.output_units = b.out_labels, b.out_units
        self.state_labels: tuple[str, ...] = b.labels
        self.disturbance_labels: tuple[str, ...] = b.dist_labels
        self._out_index = {name: j for j, name in enumerate(self.output_labels)}
        self._cmd_index = {name: j for j, name in enumerate(self.command_labels)}
        self._state_index = {name: j for j, name in enumerate(self.state_labels)}
        a = b.slices.arrays
        self._z, self._cs, self._cmd, self._ca = a.state
        self._status, self._t_fail, self._z_fail = a.outcome
        self._dist = a.signals[0]
        self._fresh = [x.copy() for x in (*a.state, *a.outcome, *a.record)]
        #: The same copies as the kernel's groups (state, outcome, record): :func:`~seahelm.simulation.stepping_io.restore_rows`.
        ns, no = len(a.state), len(a.outcome)
        self._fresh_groups = (tuple(self._fresh[:ns]), tuple(self._fresh[ns:ns + no]),
                              tuple(self._fresh[ns + no:]))
        self._out = np.zeros((b.n_runs, len(self.output_labels)))
        self._k: np.ndarray | None = None
        self._k0 = 0  # every run's step while they are aligned
        self._aligned = True  # every run at the same step
        self._n_runs = b.n_runs
        self._nc = len(self.command_labels)
        self._all = np.arange(b.n_runs)
        self._seed = problem.seed
        with quiet(b.jit):  # (the outputs come from the same loop: run_slice's ``out``)
            b.slices.warm_up(b.n_steps, b.dt, b.ctrl_every, b.record_every)

    # --------------------------------------------------------------------------------------
    @property
    def n_runs(self) -> int:
        """Runs in the batch."""
        return self._n_runs

    @property
    def n_intervals(self) -> int:
        """Controller intervals in the horizon (the last may be shorter)."""
        b = self._batch
        return -(-b.n_steps // b.ctrl_every)

    @property
    def time(self) -> np.ndarray:
        """Each run's time [s] (runs,)."""
        self._require_reset()
        return self._k * self._batch.dt

    @property
    def status(self) -> np.ndarray:
        """Each run's :class:`~seahelm.simulation.engine.RunStatus` (runs,)."""
        return self._status.copy()

    def reset(self, seed: int | None = None, runs: Any = None) -> Observation:
        """Start runs again from the problem's initial state at t = 0.

        Parameters
        ----------
        seed : int, optional
            Stored as the result's ``seed`` (the problem's inputs were drawn when it was made:
            the engine itself draws nothing).
        runs : int or sequence of int, optional
            The runs to start again (default every run); the others keep their time and state.

        Returns
        -------
        Observation
            The outputs at t = 0.
        """
        sel = self._runs(runs, refuse_diverged=False)
        if seed is not None:
            self._seed = operator.index(seed)
        b = self._batch
        a = b.slices.arrays
        restore_rows(sel, a.state, a.outcome, a.record, *self._fresh_groups)
        if self._k is None:
            self._k = np.zeros(self.n_runs, dtype=np.int64)
        self._k[sel] = 0
        self._aligned = not (self._k != 0).any()
        self._k0 = 0
        with quiet(b.jit):
            b.slices.init_runs(_spans(sel))
        return self._observe()

    def step(self, commands: Any = None, n: int = 1, runs: Any = None) -> Observation:
        """Advance runs by ``n`` controller intervals.

        Parameters
        ----------
        commands : array_like or mapping, optional
            The commands to hold over these intervals instead of the controller's (an external
            controller), by :attr:`command_labels` in their units (radians): an array
            (runs, commands) — or (commands,) for every run — or a mapping name -> value(s)
            (the commands not named keep their last values). Default: the problem's controller.
        n : int
            Controller intervals (``controller_dt`` each; the last of the horizon may be
            shorter), from 1 to :attr:`n_intervals` (more is refused). A run that reaches
            the end of the horizon (``t_final``) stops there: the rest of ``n`` is not
            stepped, and a step of a run already there does nothing (refused when ``runs``
            names it).
        runs : int or sequence of int, optional
            The runs to advance (default every run still going); ``commands`` then has one row
            per selected run.

        Returns
        -------
        Observation
            Every run's outputs after the step.

        Raises
        ------
        ParameterError
            On bad input (nothing is changed): see the class notes.
        SimulationDiverged
            With ``throw=True``, when a run diverged in this step.
        """
        if self._k is None:
            self._require_reset()
        if type(n) is not int and (isinstance(n, bool) or not isinstance(n, np.integer)):
            raise ParameterError(f"must be an integer >= 1 (controller intervals), got {n!r}",
                                 field="n", value=n)
        if n < 1:
            raise ParameterError(f"must be an integer >= 1 (controller intervals), got {n!r}",
                                 field="n", value=n)
        if n > self.n_intervals:  # (10**9 stopped silently at t_final)
            raise ParameterError(
                f"= {int(n)} exceeds the {self.n_intervals} controller intervals of the horizon "
                f"(t_final = {self.problem.t_final:g} s, controller_dt = "
                f"{self.problem.controller_every * self.problem.dt:g} s)", field="n", value=n)
        b = self._batch
        if runs is None and self._aligned and self.coupling is None:
            # every run at the same step, all stepped: one call of the loop, no selection
            return self._step_all(commands, int(n))
        requested = self._runs(runs, refuse_diverged=runs is not None)
        k_req = self._k[requested]
        if runs is not None and (k_req >= b.n_steps).any():
            i = int(requested[np.argmax(k_req >= b.n_steps)])
            raise ParameterError(f": run {i} is at the end of the horizon (t_final = "
                                 f"{self.problem.t_final:g} s)", field="runs", value=i, run=i)
        going = (k_req < b.n_steps) & (self._status[requested] == 0)
        sel = requested[going]
        external = 0
        if commands is not None:
            values = self._commands(commands, requested, runs)[going]
            external = 1
        if sel.size == 0:
            return self._observe()
        if external:
            self._cmd[sel, :len(self.command_labels)] = values
        self._aligned = False
        if self.coupling is None:
            self._advance(sel, n, external)
        else:
            self._advance_coupled(sel, n, external)
        k = self._k
        self._aligned = bool((k == k[0]).all())
        self._k0 = int(k[0])
        return self._finish(sel)

    def _step_all(self, commands: Any, n: int) -> Observation:
        """:meth:`step` of every run, all at the same step (the common case, kept short: a
        single vessel stepped from Python pays this path's overhead at every interval)."""
        b = self._batch
        k0 = self._k0
        if k0 >= b.n_steps:
            return self._observe()
        external = 0
        if commands is not None:
            self._cmd[:, :self._nc] = self._commands(commands, None)
            external = 1
        k1 = min(k0 + n * b.ctrl_every, b.n_steps)
        observed = n == 1 or self._n_runs * (k1 - k0) < 100_000
        if observed:  # (a short step: one call, which also leaves the outputs at k1 in _out)
            with quiet(b.jit):
                b.slices.run(k0, k1, b.n_steps, b.dt, b.ctrl_every, b.record_every, external,
                             self._out)
        else:  # in slices of wall time: a stop signal gets through
            drive(b.slices, b.n_steps, b.dt, b.ctrl_every, b.record_every, jit=b.jit,
                  k_start=k0, k_stop=k1, external=external)
        self._k0 = k1
        self._k.fill(k1)
        if observed and not self._status.any():  # (every run's outputs written by the loop)
            return self._observation()
        return self._finish(None)

    def observe(self) -> Observation:
        """Every run's outputs now, not stepped (after :meth:`set_state`: the state set's)."""
        return self._observe() if self._k is not None else self._require_reset()  # (raises)

    def state(self, run: int) -> dict[str, float]:
        """A run's state (vessel then actuator states) by :attr:`state_labels` [SI].

        Parameters
        ----------
        run : int
            The run's index.

        Returns
        -------
        dict
            State label -> value.
        """
        self._require_reset()
        i = self._run_index(run)
        return dict(zip(self.state_labels, self._z[i].tolist()))  # (Python floats, as float(v))

    def set_state(self, run: int, values: Any) -> None:
        """Set a run's state (the controller's state is kept).

        Parameters
        ----------
        run : int
            The run's index.
        values : mapping or array_like
            State label -> value (the states not named keep theirs), or an array of every
            state (:attr:`state_labels`) [SI]; finite and within the state's bounds.

        Raises
        ------
        ParameterError
            On an unknown label, a wrong shape, a value not finite or outside its bounds.
        """
        self._require_reset()
        i = self._run_index(run)
        z = self._z[i].copy()
        if isinstance(values, Mapping):
            for name, v in values.items():
                if name not in self._state_index:
                    raise ParameterError(f": unknown state {name!r}; states: "
                                         f"{', '.join(self.state_labels)}", field="values",
                                         value=name)
                z[self._state_index[name]] = float(v)
        else:
            arr = np.asarray(values, dtype=float)
            if arr.shape != z.shape:
                raise ParameterError(f"must have shape ({z.size},) "
                                     f"({', '.join(self.state_labels)}), got {arr.shape}",
                                     field="values", value=arr.shape)
            z = arr.copy()
        lower, upper = (self._batch.slices.arrays.get("params", n) for n in ("lower", "upper"))
        bad = ~np.isfinite(z) | (z < lower) | (z > upper)
        if bad.any():
            j = int(np.argmax(bad))
            raise ParameterError(f": state {self.state_labels[j]!r} = {float(z[j])!r} is not "
                                 f"finite or outside its bounds [{lower[j]:g}, {upper[j]:g}]",
                                 field="values", value=z[j], run=i)
        self._z[i] = z

    def failure(self, run: int) -> str | None:
        """How a run diverged (time, status and state, as ``simulate`` reports it).

        Parameters
        ----------
        run : int
            The run's index.

        Returns
        -------
        str or None
            None while the run is going.
        """
        i = self._run_index(run)
        if self._status[i] == 0:
            return None
        return failure_text(i, int(self._status[i]), float(self._t_fail[i]),
                            self.state_labels, self._z_fail[i])

    def result(self) -> "SimResult":
        """The recordings so far as a :class:`~seahelm.results.SimResult` (a copy: stepping
        on does not change it); records not reached yet are NaN."""
        self._require_reset()
        b = self._batch
        metadata = dict(self.problem.metadata or {})
        res = b.result(wall=float("nan"), compile_time=float("nan"), throw=False,
                       metadata=metadata)
        res.metadata["seed"] = -1 if self._seed is None else int(self._seed)
        res.metadata["execution"] += ", stepped (seahelm.simulation.stepping)"
        return copy.deepcopy(res)

    def close(self) -> None:
        """End the thread pool the batch keeps between steps."""
        self._batch.slices.close()

    def __enter__(self) -> "Simulator":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def __repr__(self) -> str:
        t = "not reset" if self._k is None else f"t = {self.time[:3]} s"
        return (f"Simulator({self.problem.model.name}, runs={self.n_runs}, {t}, commands: "
                f"{', '.join(self.command_labels)})")

    # --------------------------------------------------------------------------------------
    def _require_reset(self) -> None:
        if self._k is None:
            raise ParameterError(": call reset() before stepping or reading the state",
                                 field="reset")

    def _run_index(self, run: Any) -> int:
        return run_index(run, self.n_runs)

    def _runs(self, runs: Any, *, refuse_diverged: bool) -> np.ndarray:
        """The selected runs as sorted unique indices (all: every run)."""
        arr = run_indices(runs, self.n_runs)
        if runs is None:
            return arr
        if refuse_diverged and self._k is not None:
            gone = arr[self._status[arr] != 0]
            if gone.size:
                i = int(gone[0])
                raise ParameterError(f": run {i} has stopped: {self.failure(i)}; stepping it "
                                     "further is refused (reset it to start again)",
                                     field="runs", value=i, run=i)
        return arr

    def _commands(self, commands: Any, sel: np.ndarray | None, runs: Any = None) -> np.ndarray:
        """The commands (selected runs, commands) — or (runs|1, commands) for every run
        (``sel`` None) — checked; rows given in the order of ``runs``, returned in ``sel``'s
        (sorted: ``runs=[2, 0]`` gave run 0 the first row)."""
        nc = self._nc
        given = None if runs is None else run_indices(runs, self.n_runs, as_given=True)
        if given is not None and not np.array_equal(given, sel):
            values = check_commands(commands, given, self._cmd[given, :nc], self.command_labels,
                                    self.command_units)
            return values[np.argsort(given)]
        if sel is None and type(commands) is np.ndarray and commands.dtype == np.float64:
            # (the fast path of a stepped single vessel: an array of the right shape)
            if commands.shape == (nc,) or commands.shape == (self._n_runs, nc):
                if not math.isfinite(commands.sum()) and not np.isfinite(commands).all():
                    return self._commands(commands, self._all)
                return commands
        sel = self._all if sel is None else sel
        return check_commands(commands, sel, self._cmd[sel, :nc], self.command_labels,
                              self.command_units)

    def _hold(self, sel: np.ndarray) -> np.ndarray | None:
        """Mark the runs outside ``sel`` that the kernel would step as held (their statuses
        are given back by :meth:`_release`)."""
        if sel.size == self.n_runs:
            return None
        others = np.ones(self.n_runs, dtype=bool)
        others[sel] = False
        others &= self._status == 0
        self._status[others] = _HELD
        return others

    def _release(self, held: np.ndarray | None) -> None:
        if held is not None:
            self._status[held] = 0

    def _groups(self, sel: np.ndarray) -> list[tuple[int, np.ndarray]]:
        """The selected runs by their step (runs reset apart from the others lag behind)."""
        k = self._k[sel]
        if sel.size == 0 or (k == k[0]).all():
            return [(int(k[0]), sel)] if sel.size else []
        return [(int(v), sel[k == v]) for v in np.unique(k)]

    def _advance(self, sel: np.ndarray, n: int, external: int) -> None:
        b = self._batch
        for k0, group in self._groups(sel):
            k1 = min(k0 + n * b.ctrl_every, b.n_steps)
            held = self._hold(group)
            try:
                if n == 1 or b.n_runs * (k1 - k0) < 100_000:  # (a short step: one call)
                    with quiet(b.jit):
                        b.slices.run(k0, k1, b.n_steps, b.dt, b.ctrl_every, b.record_every,
                                     external)
                else:  # in slices of wall time: a stop signal gets through
                    drive(b.slices, b.n_steps, b.dt, b.ctrl_every, b.record_every, jit=b.jit,
                          k_start=k0, k_stop=k1, external=external)
            finally:
                self._release(held)
            self._k[group] = k1

    def _advance_coupled(self, sel: np.ndarray, n: int, external: int) -> None:
        """``n`` intervals one at a time, the coupling hook after each but the last; on a
        failure of the hook every array is put back as it was before the step."""
        b = self._batch
        a = b.slices.arrays
        saved = [x.copy() for x in (*a.state, *a.outcome)] + [self._k.copy(), self._dist.copy()]
        nc = len(self.command_labels)
        first = sel
        try:
            cmds = self._cmd[sel, :nc].copy() if external else None
            for q in range(n):
                if q > 0:
                    if cmds is not None:
                        self._cmd[sel, :nc] = cmds
                    self._advance(sel, 1, external)
                else:
                    self._advance(sel, 1, external)
                self._dist[...] = saved[-1]
                sel = sel[(self._k[sel] < b.n_steps) & (self._status[sel] == 0)]
                if q == n - 1 or sel.size == 0:
                    break
                cmds, dist = self._call_hook(sel, external)
                if dist is not None:
                    self._write_disturbance(sel, dist)
        except BaseException:
            for live, old in zip((*a.state, *a.outcome), saved):
                live[...] = old
            self._k[...], self._dist[...] = saved[-2], saved[-1]
            # the records from the step's start on were not written before it
            for k0 in np.unique(self._k[first]):
                m0 = -(-int(k0) // b.record_every)
                for rec in a.record:
                    rec[first[self._k[first] == k0], m0:] = np.nan
            raise
        self._dist[...] = saved[-1]

    def _call_hook(self, sel: np.ndarray, external: int) -> tuple[Any, Any]:
        b = self._batch
        obs = self._observe()
        outputs = obs.values[sel]
        outputs.flags.writeable = False
        nc = len(self.command_labels)
        cmds = self._cmd[sel, :nc].copy() if external else None
        k = self._k[sel]
        dsrc = self._dist
        d_now = dsrc[np.minimum(sel, dsrc.shape[0] - 1), np.minimum(k, dsrc.shape[1] - 1)]
        dist = np.array(d_now[:, :len(self.disturbance_labels)], dtype=float)
        d_before = dist.copy()
        try:
            self.coupling(k * b.dt, outputs, cmds, dist)
        except ParameterError:
            raise
        except Exception as exc:
            raise ParameterError(f": the coupling hook raised {type(exc).__name__}: {exc}",
                                 field="coupling") from exc
        for what, arr, labels in (("commands", cmds, self.command_labels),
                                  ("disturbance", dist, self.disturbance_labels)):
            if arr is not None and not np.isfinite(arr).all():
                r, j = np.argwhere(~np.isfinite(arr))[0]
                raise ParameterError(f": the coupling hook wrote {float(arr[r, j])!r} to {what} "
                                     f"{labels[j]!r} of run {int(sel[r])} (runs, "
                                     f"{len(labels)}); values must be finite",
                                     field="coupling", value=float(arr[r, j]), run=int(sel[r]))
        return cmds, (None if np.array_equal(dist, d_before) else dist)

    def _write_disturbance(self, sel: np.ndarray, dist: np.ndarray) -> None:
        """The hook's disturbances held over the next interval of the runs ``sel`` (the
        kernel's array is made one row per run and put back after the interval)."""
        b = self._batch
        d = self._dist
        nd = len(self.disturbance_labels)
        if d.shape[0] != self.n_runs:
            raise ParameterError(": the coupling hook writes disturbances per run, but the "
                                 "problem's disturbance is one for every run; give it per "
                                 "run (shape (runs, 1 or steps+1, channels))",
                                 field="coupling")
        if d.shape[1] == 1:
            d[sel, 0, :nd] = dist
            return
        for r, i in enumerate(sel):
            k0 = int(self._k[i])
            d[i, k0:min(k0 + b.ctrl_every, b.n_steps) + 1, :nd] = dist[r]

    def _observe(self) -> Observation:
        with quiet(self._batch.jit):
            self._observe_into()
        return self._observation()

    def _observation(self) -> Observation:
        return Observation(self._k * self._batch.dt, self._out.copy(), self.output_labels,
                           self.output_units, self._status.copy(), self._out_index)

    def _observe_into(self) -> None:
        b = self._batch
        k = self._k
        k0 = int(k[0])
        if self._aligned or (k == k0).all():
            if k0 < b.n_steps and not self._status.any():  # a zero-step call of the loop
                # (observe_runs is a second compiled function: compiled only when needed)
                b.slices.run(k0, k0, b.n_steps, b.dt, b.ctrl_every, b.record_every, 1,
                             self._out)
            else:
                b.slices.observe(k0, b.dt, self._out)
            return
        a = b.slices.arrays
        sc, ssc = b.slices.scratch[0], b.slices.stage_scratch[0]
        for i in range(self.n_runs):
            b.kernel.observe_runs(i, i + 1, int(k[i]), b.dt, a.state, a.params, a.signals,
                                  a.stages, sc, ssc, self._out)

    def _finish(self, sel: np.ndarray | None) -> Observation:
        obs = self._observe()
        if self.throw:
            sel = self._all if sel is None else sel
            gone = sel[self._status[sel] != 0]
            if gone.size:
                i = int(gone[0])
                raise SimulationDiverged(self.failure(i), time=self._t_fail[i],
                                         state=self._z_fail[i].copy(), run=i)
        return obs
