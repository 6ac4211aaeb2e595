"""Several vessels in one run: :class:`Encounter`, a batch of encounters stepped together.

An encounter is an own ship (vessel 0) and target ships, each a :class:`Vessel`: any catalog
ship or ship file, its start, its course or route, its own heading autopilot and guidance. A
batch of ``n_encounters`` encounters of ``n_vessels`` vessels is ``n_encounters × n_vessels``
runs of the compiled loop, stepped one controller interval at a time through
:class:`seahelm.Simulator` (one simulator per distinct ship: vessels of the same ship are runs
of one batch). Between two intervals -- where the simulator calls a coupling hook -- every
vessel's controller gets an AIS-like view of the others (:mod:`.sensing`), its guidance and
avoidance (:mod:`.avoidance`) give a desired heading, and the autopilot the rudder command.

The coupling is done in the loop between ``step`` calls rather than in a hook of the simulator
because the vessels of an encounter may be different ships (different simulators), and because
a hook sees the outputs of the runs it steps without their indices; the place in the step and
the arrays read and written are those of the hook.

Every law here acts row by row (one vessel at a time: no sum over the batch), so a vessel's
trajectory does not depend on the batch it is in; with avoidance off, an encounter's vessels
move exactly (bit for bit) as each run alone.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..analysis.equilibria.equilibrium import approach_state
from ..errors import ParameterError
from ..ships import Ship, get_ship
from ..simulation.problem import Problem
from ..simulation.stepping import Simulator
from .avoidance import resolve_avoidance
from .geometry import ColregSectors, FujiiDomain, wrap_pi
from .result import EncounterResult, Recorder, VerdictRules
from .sensing import AIS

__all__ = ["Vessel", "HeadingAutopilot", "Encounter"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class HeadingAutopilot:
    """The vessels' heading autopilot: a PD law on heading, computed between intervals.

    ``δ_c = clip(K_p·wrap(ψ_d - ψ) - K_p·T_d·r, ±δ_max)`` with ``T_d = derivative_time`` times
    the ship's L/U (its time to run one length) and ``δ_max`` the ship's rudder limit (35° for
    a ship without a steering gear).

    Attributes
    ----------
    gain : float
        K_p [rad/rad] (default 1.0).
    derivative_time : float
        T_d in units of L/U [-] (default 1.5).
    """

    gain: float = 1.0
    derivative_time: float = 1.5

    def __post_init__(self) -> None:
        for name in ("gain", "derivative_time"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v >= 0):
                raise ParameterError(f"must be >= 0 [-], got {v!r}", field=f"autopilot.{name}",
                                     value=v)


@dataclasses.dataclass(frozen=True, kw_only=True)
class Vessel:
    """One vessel of an encounter; every number may be an array with one value per encounter.

    Attributes
    ----------
    ship : Ship or str
        A :class:`~seahelm.ships.Ship`, a catalog name or the path of a ship file.
    north, east : float or array (n_encounters,)
        Start position [m].
    course : float or array, optional
        Heading to start on and keep [rad]; required without a ``route``.
    speed : float or array, optional
        Speed through the water [m/s] (the propeller turns at its self-propulsion rate for it,
        held); default the ship's approach speed. Rounded to 0.01 m/s (one self-propulsion
        solve per distinct speed).
    route : array (waypoints, 2) or (n_encounters, waypoints, 2), optional
        Waypoints (north, east) [m] steered for in turn (switched within ``acceptance``); the
        start heading points at the first unless ``course`` is given; after the last, the
        course it was reached on is kept.
    acceptance : float
        Radius of a waypoint [ship lengths] (default 2).
    avoid : bool
        Whether this vessel runs the encounter's avoidance (default False: keeps its course or
        route).
    name : str
        A label for results and plots.
    """

    ship: Any
    north: Any = 0.0
    east: Any = 0.0
    course: Any = None
    speed: Any = None
    route: Any = None
    acceptance: float = 2.0
    avoid: bool = False
    name: str = ""


#: Rudder limit of a ship without a steering gear (a Nomoto ship) [rad].
DEFAULT_MAX_RUDDER = math.radians(35.0)


def _max_rudder(ship: Ship) -> float:
    try:
        return float(ship.max_rudder)
    except ParameterError:
        return DEFAULT_MAX_RUDDER


class _Group:
    """The vessels of one ship: the runs of one simulator."""

    def __init__(self, ship: Ship, index: np.ndarray) -> None:
        self.ship, self.index = ship, index  # index: flat (encounter * n_vessels + vessel)
        self.sim: Simulator | None = None


class Encounter:
    """A batch of encounters, run through the stepping API.

    Parameters
    ----------
    vessels : sequence of Vessel
        Own ship first. Array-valued fields give one encounter each (they broadcast).
    t_final : float
        Duration [s].
    dt, controller_dt : float
        Integration step and controller interval [s] (defaults 0.1 and 1.0).
    sensor : AIS, optional
        What each vessel sees of the others (default: exact, every interval).
    avoidance : str or object, optional
        The collision-avoidance method of the vessels with ``avoid=True`` (a name of
        :data:`~seahelm.encounters.avoidance.AVOIDANCE` or an object with its interface);
        None: nobody avoids.
    autopilot : HeadingAutopilot, optional
    sectors : ColregSectors, optional
        The thresholds of the COLREG situations.
    domain : FujiiDomain, optional
        The ship domain of the near-miss count.
    verdicts : VerdictRules, optional
        The thresholds of the rule verdicts.
    record_every : int
        Record the tracks every n-th controller interval (default 10); CPA, ranges and the
        verdicts' inputs are followed at every interval.
    first_encounter : int
        The index of the first encounter in its study (default 0; a chunk of a study gives
        its start): the sensor's noise of an encounter depends on its index only, so a
        chunk's encounters see the noise they see in the whole batch.

    Raises
    ------
    ParameterError
        On a vessel without course or route, vessels starting within each other's hull
        (circles of half their lengths), a sensor delay as long as the run, or bad numbers.
    """

    def __init__(self, vessels: Sequence[Vessel], *, t_final: float, dt: float = 0.1,
                 controller_dt: float = 1.0, sensor: AIS | None = None,
                 avoidance: Any = None, autopilot: HeadingAutopilot | None = None,
                 sectors: ColregSectors | None = None, domain: FujiiDomain | None = None,
                 verdicts: VerdictRules | None = None, record_every: int = 10,
                 first_encounter: int = 0) -> None:
        if not vessels or not all(isinstance(v, Vessel) for v in vessels):
            raise ParameterError("must be a non-empty sequence of Vessel", field="vessels")
        for name, v in (("t_final", t_final), ("dt", dt), ("controller_dt", controller_dt)):
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise ParameterError(f"must be > 0 [s], got {v!r}", field=name, unit="s",
                                     value=v)
        if not (isinstance(record_every, int) and record_every >= 1):
            raise ParameterError(f"must be an integer >= 1 [intervals], got {record_every!r}",
                                 field="record_every", value=record_every)
        if not (isinstance(first_encounter, (int, np.integer)) and first_encounter >= 0):
            raise ParameterError(f"must be an integer >= 0, got {first_encounter!r}",
                                 field="first_encounter", value=first_encounter)
        self.first_encounter = int(first_encounter)
        self.vessels = tuple(vessels)
        self.t_final, self.dt, self.controller_dt = float(t_final), float(dt), float(controller_dt)
        self.sensor = sensor or AIS()
        self.sensor.start(1, self.controller_dt, self.t_final)  # (validates the delay)
        self.avoidance = resolve_avoidance(avoidance)
        self.autopilot = autopilot or HeadingAutopilot()
        self.sectors = sectors or ColregSectors()
        self.domain = domain or FujiiDomain()
        self.verdict_rules = verdicts or VerdictRules()
        self.record_every = record_every
        self._build()

    # ------------------------------------------------------------------------------------
    def _build(self) -> None:
        nv = len(self.vessels)
        fields = {}
        for i, v in enumerate(self.vessels):
            if v.course is None and v.route is None:
                raise ParameterError(": a vessel needs a course or a route [rad]; got neither",
                                     field=f"vessels[{i}].course", unit="rad", value=None)
            fields[i] = {k: (None if getattr(v, k) is None else np.asarray(getattr(v, k),
                                                                              dtype=float))
                         for k in ("north", "east", "course", "speed")}
        shapes = [a.shape for f in fields.values() for a in f.values() if a is not None]
        routes = [None if v.route is None else np.asarray(v.route, dtype=float)
                  for v in self.vessels]
        for i, r in enumerate(routes):
            if r is not None and (r.ndim not in (2, 3) or r.shape[-1] != 2 or r.shape[-2] < 1
                                  or not np.isfinite(r).all()):
                raise ParameterError(f"must be finite waypoints (waypoints, 2) or "
                                     f"(encounters, waypoints, 2) [m], got shape {r.shape}",
                                     field=f"vessels[{i}].route", unit="m", value=r.shape)
            if r is not None and r.ndim == 3:
                shapes.append(r.shape[:1])
        try:
            (ne,) = np.broadcast_shapes(*shapes, (1,))
        except ValueError:
            raise ParameterError(f"the vessels' arrays must broadcast to one axis of "
                                 f"encounters, got shapes {shapes}", field="vessels") from None
        self.n_encounters, self.n_vessels = ne, nv
        ships = [v.ship if isinstance(v.ship, Ship) else get_ship(v.ship) for v in self.vessels]
        self.ships = ships
        self.lengths = np.array([s.length for s in ships], dtype=float)
        self.names = tuple(v.name or f"{'own' if i == 0 else f'target {i}'} ({s.name})"
                           for i, (v, s) in enumerate(zip(self.vessels, ships)))

        def full(a: np.ndarray | None, default: float) -> np.ndarray:
            return np.broadcast_to(default if a is None else a, (ne,)).astype(float)

        north = np.stack([full(fields[i]["north"], 0.0) for i in range(nv)], axis=1)
        east = np.stack([full(fields[i]["east"], 0.0) for i in range(nv)], axis=1)
        speed = np.stack([full(fields[i]["speed"], ships[i].approach_speed) for i in range(nv)],
                         axis=1)
        speed = np.round(speed, 2)
        if not (np.isfinite(speed).all() and (speed > 0).all()):
            i = int(np.argwhere(~(speed > 0))[0, 1])
            raise ParameterError(f"must be > 0 [m/s], got {speed[:, i].min()!r}",
                                 field=f"vessels[{i}].speed", unit="m/s")
        self.routes = [None if r is None else np.broadcast_to(r, (ne, *r.shape[-2:]))
                       for r in routes]
        course = np.zeros((ne, nv))
        for i in range(nv):
            c = fields[i]["course"]
            if c is not None:
                course[:, i] = full(c, 0.0)
            else:
                first = self.routes[i][:, 0]
                course[:, i] = np.arctan2(first[:, 1] - east[:, i], first[:, 0] - north[:, i])
        for a, name, unit in ((north, "north", "m"), (east, "east", "m"),
                              (course, "course", "rad")):
            if not np.isfinite(a).all():
                i = int(np.argwhere(~np.isfinite(a))[0, 1])
                raise ParameterError(f"must be finite [{unit}]", field=f"vessels[{i}].{name}",
                                     unit=unit)
        self.north0, self.east0, self.course0, self.speed0 = north, east, course, speed
        self._check_apart()
        self.acceptance = np.array([v.acceptance for v in self.vessels]) * self.lengths
        self.avoid = np.array([bool(v.avoid) for v in self.vessels])
        flat = np.arange(ne * nv).reshape(ne, nv)
        groups: dict[int, _Group] = {}
        for i, s in enumerate(ships):
            key = next((j for j in groups if ships[j] is s or ships[j] == s), i)
            if key in groups:
                groups[key].index = np.sort(np.concatenate([groups[key].index, flat[:, i]]))
            else:
                groups[key] = _Group(s, flat[:, i].copy())
        self._groups = list(groups.values())
        self._problems = [self._problem(g) for g in self._groups]

    def _check_apart(self) -> None:
        nv = self.n_vessels
        for i in range(nv):
            for j in range(i + 1, nv):
                d = np.hypot(self.north0[:, j] - self.north0[:, i],
                             self.east0[:, j] - self.east0[:, i])
                touch = 0.5 * (self.lengths[i] + self.lengths[j])
                if (d < touch).any():
                    e = int(np.argmax(d < touch))
                    raise ParameterError(
                        f": vessels {i} and {j} start {d[e]:.1f} m apart in encounter {e}, "
                        f"inside each other's hull (half lengths {touch:.1f} m) [m]",
                        field=f"vessels[{j}].north", unit="m", value=float(d[e]))

    def _problem(self, group: _Group) -> tuple[Problem, np.ndarray]:
        """The group's problem and its propeller rps per run."""
        ship = group.ship
        e, v = np.divmod(group.index, self.n_vessels)
        speeds = self.speed0[e, v]
        starts: dict[float, Any] = {}
        for s in np.unique(speeds):
            at_design = abs(s - ship.approach_speed) < 0.005
            try:
                starts[float(s)] = approach_state(ship, None if at_design else float(s))
            except ParameterError as err:
                i = int(v[np.argmax(speeds == s)])
                raise ParameterError(f": {err.reason.lstrip(': ')}", field=f"vessels[{i}].speed",
                                     unit="m/s", value=float(s)) from None
        model = ship.model
        labels = model.state_labels
        x0 = np.stack([starts[float(s)].state for s in speeds]).astype(float)
        for name, values in (("north", self.north0[e, v]), ("east", self.east0[e, v]),
                             ("heading", self.course0[e, v])):
            if name in labels:
                x0[:, labels.index(name)] = values
        rps = np.array([starts[float(s)].inputs.get("propeller_rps", np.nan) for s in speeds])
        n_steps = int(round(self.t_final / self.dt))
        problem = Problem(ship=ship, x0=x0, t_final=self.t_final, dt=self.dt,
                          controller_dt=self.controller_dt, record_every=n_steps,
                          metadata={"encounter": "seahelm.encounters"})
        return problem, rps

    @property
    def problems(self) -> list[Problem]:
        """One :class:`~seahelm.simulation.problem.Problem` per distinct ship: its vessels'
        runs, from their starts (what is stepped; ``simulate`` of one runs those vessels
        uncoupled over the whole horizon with the rudder held at zero)."""
        return [p for p, _ in self._problems]

    def uncoupled_problems(self) -> list[Problem]:
        """:attr:`problems` with their commands as an open-loop reference: the rudder held at
        zero, the propeller at its self-propulsion rate -- the same ships run uncoupled over
        the whole horizon by ``simulate`` (what the benchmark compares with)."""
        out = []
        for (problem, rps), g in zip(self._problems, self._groups):
            labels = problem.wiring.commands
            ref = np.zeros((g.index.size, 1, len(labels)))
            if "propeller_rps" in labels:
                ref[:, 0, labels.index("propeller_rps")] = rps
            out.append(dataclasses.replace(problem, reference=ref))
        return out

    def autopilot_problems(self) -> list[Problem]:
        """:attr:`problems` steered by the encounter's heading autopilot inside the compiled
        loop, every vessel holding its initial course, the propeller at its self-propulsion
        rate: the same ships, steering as they steer in the encounter, run uncoupled over the
        whole horizon by ``simulate`` (no view of the others, no guidance, no avoidance).

        The law is :class:`HeadingAutopilot`'s as the ``pid-heading`` controller (its
        ``-rps`` variant for a ship with a propeller command): ``K_p`` = ``gain``, ``K_i`` =
        0, ``K_d`` = ``gain`` · T_d, ``δ_max`` the ship's rudder limit, sampled every
        ``controller_dt``. The compiled controller wraps the heading error its own way, so
        its runs equal the encounter's without avoidance to rounding, not bit for bit.

        Returns
        -------
        list of Problem
            One per distinct ship, in the order of :attr:`problems`.
        """
        from ..control.pid import PID_HEADING, PID_HEADING_RPS

        out = []
        kp = float(self.autopilot.gain)
        for (problem, rps), g in zip(self._problems, self._groups):
            ship = g.ship
            kd = kp * (self.autopilot.derivative_time * ship.length / ship.approach_speed)
            gains = dict(kp=kp, ki=0.0, kd=kd, max_command=_max_rudder(ship))
            held = "propeller_rps" in problem.wiring.commands
            controller = PID_HEADING_RPS if held else PID_HEADING
            params = [controller.params_type(**gains, **({"propeller_rps": float(r)}
                                                         if held else {}))
                      for r in rps]
            e, v = np.divmod(g.index, self.n_vessels)
            out.append(dataclasses.replace(problem, controller=controller,
                                           controller_params=params,
                                           reference=self.course0[e, v][:, None, None]))
        return out

    @property
    def run_index(self) -> list[np.ndarray]:
        """For each of :attr:`problems`, its runs' flat index ``encounter * n_vessels +
        vessel``."""
        return [g.index for g in self._groups]

    # ------------------------------------------------------------------------------------
    def run(self) -> EncounterResult:
        """Run every encounter to ``t_final``.

        Returns
        -------
        EncounterResult
            Tracks (encounter, vessel, time), the own ship's pair metrics over time, and the
            per-encounter outcome and verdicts.
        """
        ne, nv = self.n_encounters, self.n_vessels
        n = ne * nv
        sims, cmds, rudder_j, e_lim, td = [], [], [], np.zeros(n), np.zeros(n)
        out_j: list[dict[str, int]] = []
        try:
            for g, (problem, rps) in zip(self._groups, self._problems):
                sim = Simulator(problem)
                g.sim = sim
                sims.append(sim)
                labels = sim.command_labels
                if "rudder_command" not in labels:
                    raise ParameterError(f": ship {g.ship.name!r} takes no rudder_command "
                                         f"(commands: {', '.join(labels)})",
                                         field="vessels.ship", value=g.ship.name)
                c = np.zeros((g.index.size, len(labels)))
                if "propeller_rps" in labels:
                    c[:, labels.index("propeller_rps")] = rps
                cmds.append(c)
                rudder_j.append(labels.index("rudder_command"))
                e_lim[g.index] = _max_rudder(g.ship)
                td[g.index] = (self.autopilot.derivative_time * g.ship.length
                               / g.ship.approach_speed)
                idx = {name: j for j, name in enumerate(sim.output_labels)}
                for need in ("north", "east", "heading"):
                    if need not in idx:
                        raise ParameterError(f": ship {g.ship.name!r} does not output "
                                             f"{need!r}", field="vessels.ship")
                out_j.append(idx)
            return self._loop(sims, cmds, rudder_j, e_lim, td, out_j)
        finally:
            for sim in sims:
                sim.close()

    def _truth(self, obs_list: list[Any], out_j: list[dict[str, int]]) -> np.ndarray:
        """Every vessel's (north, east, course, speed, heading, yaw rate) (runs, 6)."""
        truth = np.empty((self.n_encounters * self.n_vessels, 6))
        for g, obs, idx in zip(self._groups, obs_list, out_j):
            vals = obs.values
            psi = vals[:, idx["heading"]]
            u = vals[:, idx["surge_speed"]] if "surge_speed" in idx else vals[:, idx["speed"]]
            v = vals[:, idx["sway_speed"]] if "sway_speed" in idx else 0.0 * u
            vn = u * np.cos(psi) - v * np.sin(psi)
            ve = u * np.sin(psi) + v * np.cos(psi)
            r = vals[:, idx["yaw_rate"]] if "yaw_rate" in idx else 0.0 * u
            truth[g.index] = np.stack([vals[:, idx["north"]], vals[:, idx["east"]],
                                       np.arctan2(ve, vn), np.hypot(vn, ve), psi, r], axis=1)
        return truth

    def _guidance(self, truth: np.ndarray, wp: np.ndarray) -> np.ndarray:
        """The route's desired heading (encounters, vessels) [rad]: towards the active
        waypoint, and after the last the course it was reached on. ``wp`` (each vessel's
        active waypoint; ``len(route)`` once done) is advanced in place, and so is
        :attr:`_leg` (the course after the route)."""
        ne, nv = self.n_encounters, self.n_vessels
        t = truth.reshape(ne, nv, 6)
        desired = self.course0.copy()
        rows = np.arange(ne)
        for i, route in enumerate(self.routes):
            if route is None:
                continue
            n_wp = route.shape[1]
            for _ in range(n_wp):
                going = wp[:, i] < n_wp
                target = route[rows, np.minimum(wp[:, i], n_wp - 1)]
                bearing = np.arctan2(target[:, 1] - t[:, i, 1], target[:, 0] - t[:, i, 0])
                close = going & (np.hypot(target[:, 0] - t[:, i, 0], target[:, 1] - t[:, i, 1])
                                 < self.acceptance[i])
                if not close.any():
                    break
                last = close & (wp[:, i] == n_wp - 1)
                self._leg[last, i] = bearing[last]
                wp[close, i] += 1
            target = route[rows, np.minimum(wp[:, i], n_wp - 1)]
            bearing = np.arctan2(target[:, 1] - t[:, i, 1], target[:, 0] - t[:, i, 0])
            desired[:, i] = np.where(wp[:, i] < n_wp, bearing, self._leg[:, i])
        return desired

    def _loop(self, sims: list[Simulator], cmds: list[np.ndarray], rudder_j: list[int],
              e_lim: np.ndarray, td: np.ndarray, out_j: list[dict[str, int]]) -> EncounterResult:
        ne, nv = self.n_encounters, self.n_vessels
        n_int = sims[0].n_intervals
        view_state = self.sensor.start(ne * nv, self.controller_dt, self.t_final,
                                       n_vessels=nv, first_encounter=self.first_encounter)
        wp = np.zeros((ne, nv), dtype=np.int64)
        self._leg = np.zeros((ne, nv))
        avoid_state = (self.avoidance.start(ne, nv, self.avoid, self)
                       if self.avoidance is not None and self.avoid.any() else None)
        rec = Recorder(self, n_int)
        kp = self.autopilot.gain
        obs = [sim.reset() for sim in sims]
        for k in range(n_int + 1):
            truth = self._truth(obs, out_j)
            time = float(obs[0].time[0])
            view = view_state.update(k, truth[:, :5])
            desired = self._guidance(truth, wp)
            route_heading = desired
            if avoid_state is not None:
                desired = self.avoidance.desired(time, truth.reshape(ne, nv, 6),
                                                 view.reshape(ne, nv, 5), route_heading,
                                                 avoid_state)
            rudder = np.clip(kp * wrap_pi(desired.reshape(-1) - truth[:, 4])
                             - kp * td * truth[:, 5], -e_lim, e_lim)
            rec.add(k, time, truth, desired, route_heading, rudder)
            if k == n_int:
                break
            for i, (g, sim) in enumerate(zip(self._groups, sims)):
                cmds[i][:, rudder_j[i]] = rudder[g.index]
                obs[i] = sim.step(cmds[i])
        status = np.zeros(ne * nv, dtype=np.int64)
        for g, sim in zip(self._groups, sims):
            status[g.index] = sim.status
        return rec.finish(status.reshape(ne, nv))
