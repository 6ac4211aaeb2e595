"""Autopilot gains from a ship, in one call: linearise, design, check the closed loop, write a
scenario.

:func:`tune_autopilot` linearises the ship at its straight run
(:func:`~seahelm.analysis.equilibria.linearisation.linearize`), takes Nomoto's K and
T = T_1 + T_2 − T_3 (:func:`~seahelm.analysis.steering.indices.steering_indices`) and designs

* ``"pid"``: the ``pid-heading`` gains placing the Nomoto loop's poles
  (:func:`~seahelm.control.autopilot_design.pid_pole_placement`);
* ``"lq"``: the ``lq-heading`` gains of the LQ-integral design on the sway–yaw block
  (:func:`~seahelm.control.autopilot_design.lq_heading`, Bryson weights);
* ``"lq-cross-track"``: the ``lq-cross-track`` gains
  (:func:`~seahelm.control.lq_cross_track.lq_cross_track`); without explicit weights, L/3 and
  20 deg grown together by 2^(1/4) until the nonlinear ship, the candidates simulated in one
  batch, settles from the offset (:func:`cross_track_settles`).

A ship with a propeller is linearised at its self-propelled straight run and the design is
the ``-rps`` variant of the controller, which holds that rps. The result
(:class:`AutopilotTuning`) holds the gains, the designed poles, the poles of the linearised
ship and steering gear under the design (:func:`cross_track_loop_poles`,
:func:`~seahelm.control.autopilot_design.heading_loop_poles`), the margins and the warnings;
:meth:`AutopilotTuning.scenario` is a scenario (a mapping) running the design — a course change,
or the route — and :func:`scenario_toml` its text (tomlkit, the ship files' writer).
``seahelm autopilot tune`` is this call and a rendering.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from ...errors import ParameterError

__all__ = ["DESIGNS", "MAX_PERIOD_SHARE", "AutopilotTuning", "tune_autopilot",
           "cross_track_loop_poles", "cross_track_settles", "scenario_duration",
           "settling_time", "scenario_toml", "poles_text"]

#: The designs of :func:`tune_autopilot` -> the controller they give (``-rps`` added for a ship
#: with a propeller).
DESIGNS = {"pid": "pid-heading", "lq": "lq-heading", "lq-cross-track": "lq-cross-track"}

#: ``dt`` at most |T| / MAX_PERIOD_SHARE (the Nomoto time constant): a controller is sampled
#: some 10-20 times per closed-loop time constant (Franklin, Powell & Workman 1998, ch. 11);
#: 5 per open-loop T is the least that still steers.
MAX_PERIOD_SHARE = 5.0


def poles_text(poles: Any) -> list[str]:
    """Poles as short strings ``-0.1+0.2j``, sorted by real then imaginary part.

    Parameters
    ----------
    poles : array_like of complex

    Returns
    -------
    list of str
    """
    return [f"{p.real:.5g}" + (f"{p.imag:+.5g}j" if abs(p.imag) > 0 else "")
            for p in sorted(np.asarray(poles), key=lambda p: (p.real, p.imag))]


def scenario_duration(poles: Any) -> float:
    """A written scenario's ``t_final`` [s]: five time constants of the slowest stable pole
    of the linearised ship, steering gear and controller, in whole 100 s, at least 300 s.

    It was a hundred (``100 ceil(0.1 · 10 τ)``): a 10° course change of the Mariner under its
    PID ran 15,000 s, where the nonlinear run settles within 2 % in 360–400 s (10° and 30°;
    the slowest pole, about ω_n/10 of the pole-placement PID, 0.0067 1/s, gives 800 s).

    Parameters
    ----------
    poles : array_like of complex
        [1/s].

    Returns
    -------
    float
    """
    rates = [-p.real for p in np.asarray(poles) if p.real < -1e-9]
    settle = 5.0 / min(rates) if rates else 300.0
    return float(max(300.0, 100.0 * math.ceil(0.01 * settle)))


def settling_time(poles: Any) -> float:
    """About ten time constants of the slowest stable pole [s] (300 s with none).

    Parameters
    ----------
    poles : array_like of complex
        [1/s].

    Returns
    -------
    float
    """
    rates = [-p.real for p in np.asarray(poles) if p.real < -1e-9]
    return 10.0 / min(rates) if rates else 300.0


def cross_track_loop_poles(linear: Any, gains: dict[str, float]) -> np.ndarray:
    """Poles of a linearised ship and steering gear under the LQ cross-track law
    δ_c = −k_i ∫y − k_y y − k_ψ ψ − k_r r − k_v v, the integral state appended.

    Parameters
    ----------
    linear : LinearModel
        With the steering gear (input ``rudder_command``), states without ``north``; ``east``
        is the cross-track error of a route due north.
    gains : dict of str to float
        ``k_integral``, ``k_cross_track``, ``k_heading``, ``k_yaw_rate``, ``k_sway``.

    Returns
    -------
    ndarray of complex
        [1/s].
    """
    labels, n = linear.state_labels, len(linear.state_labels)
    row = {s: np.eye(n)[labels.index(s)] for s in ("east", "heading", "yaw_rate", "sway_speed")
           if s in labels}
    k = (gains["k_cross_track"] * row["east"] + gains["k_heading"] * row["heading"]
         + gains["k_yaw_rate"] * row["yaw_rate"]
         + gains["k_sway"] * row.get("sway_speed", np.zeros(n)))
    b = linear.B[:, linear.input_labels.index("rudder_command")]
    acl = np.zeros((n + 1, n + 1))
    acl[:n, :n] = linear.A - np.outer(b, k)
    acl[:n, n] = -b * gains["k_integral"]
    acl[n, :n] = row["east"]
    return np.linalg.eigvals(acl)


def _route_setup(ship: Any, bare: Any, full: Any, offset: float, t_final: float
                 ) -> tuple[dict[str, float], list[list[float]], float | None]:
    """The route scenario's initial state, route and held rps (for the check and the file)."""
    initial = {k: float(v) for k, v in zip(bare.state_labels, bare.x0)
               if k not in ("north", "east", "heading") and v != 0.0}
    leg = max(10.0 * bare.length, 1.2 * bare.speed * t_final)
    rps = (float(full.u0[full.input_labels.index("propeller_rps")]) if ship.has_propeller
           else None)
    return {**initial, "east": float(offset)}, [[0.0, 0.0], [float(f"{leg:.6g}"), 0.0]], rps


def cross_track_settles(ship: Any, bare: Any, full: Any, designs: Sequence[Any], offset: float,
                        dt: float) -> list[bool]:
    """Whether each cross-track design's nonlinear closed loop settles: the ship ``offset``
    off a straight route due north ends within 2 % of max(|offset|, L) of it over the last
    quarter of its run (all designs simulated as one batch; a diverged run does not settle).

    Parameters
    ----------
    ship : Ship
    bare, full : LinearModel
        The ship linearised at its straight run without and with its steering gear (``full``
        without ``north``).
    designs : sequence of LQCrossTrackDesign
    offset : float
        Initial cross-track offset [m].
    dt : float
        Controller sample period [s].

    Returns
    -------
    list of bool
    """
    from ...registry import get_controller
    from ...simulation.engine import simulate

    t_final = float(max(300.0, 100.0 * math.ceil(0.1 * max(
        settling_time(cross_track_loop_poles(full, d.gains)) for d in designs))))
    initial, route, rps = _route_setup(ship, bare, full, offset, t_final)
    x0 = np.zeros(ship.model.n_states)
    for k, v in initial.items():
        x0[ship.model.state_labels.index(k)] = v
    name = "lq-cross-track" + ("-rps" if rps is not None else "")
    res = simulate(ship=ship, x0=x0, t_final=t_final, dt=0.1, controller=get_controller(name),
                   controller_params=[d.params(route, propeller_rps=rps,
                                               acceptance_radius=bare.length) for d in designs],
                   controller_dt=dt, record_every=10)
    xte = res["cross_track_error"]
    tail = np.abs(xte[:, int(0.75 * xte.shape[1]):]).max(axis=1)
    return list((res.status == 0) & (tail <= 0.02 * max(abs(offset), bare.length)))


def _cross_track_design(block: Any, states: tuple[str, ...], surge: float, max_cross_track: float,
                        max_heading_error: float, max_rudder: float, *, explicit: bool,
                        settles: Callable[[list[Any]], list[bool]]) -> tuple[Any, float, float]:
    """The LQ cross-track design at the weights [m], [deg] if they were given (``explicit``);
    else at the smallest of them × 2^(k/4), k = 0 ... 7, whose nonlinear closed loop settles
    (``settles``: candidate designs -> one bool each). Returns the design and its weights."""
    from ...control.lq_cross_track import lq_cross_track

    candidates = []
    for k in range(1 if explicit else 8):
        grow = 2.0 ** (k / 4)
        design = lq_cross_track(block.A, block.B[:, 0], states, surge,
                                max_cross_track=max_cross_track * grow,
                                max_heading_error=math.radians(max_heading_error * grow),
                                max_rudder=max_rudder)
        candidates.append((design, max_cross_track * grow, max_heading_error * grow))
    if explicit:
        return candidates[0]
    for c, good in zip(candidates, settles([c[0] for c in candidates])):
        if good:
            return c
    raise ParameterError(
        f"none of the weights from {candidates[0][1]:.4g} m, {candidates[0][2]:.4g} deg to "
        f"{candidates[-1][1]:.4g} m, {candidates[-1][2]:.4g} deg settles the ship from the "
        "scenario's offset (simulated); give max_cross_track and max_heading_error",
        field="max_cross_track")


@dataclasses.dataclass(frozen=True)
class AutopilotTuning:
    """An autopilot designed for a ship (:func:`tune_autopilot`).

    Attributes
    ----------
    ship : Ship
    design : str
        ``"pid"``, ``"lq"`` or ``"lq-cross-track"``.
    controller : str
        The registry name of the controller the gains are for.
    gains : dict of str to float
        Its parameters (SI, angles in radians; ``propeller_rps`` [1/s] for an ``-rps`` one).
    nomoto : NomotoIndices
        K [1/s], T, T_1, T_2, T_3 [s] at the straight run.
    result : PIDDesign, LQDesign or LQCrossTrackDesign
        The design (designed poles, margins, ...).
    poles : ndarray of complex
        Of the linearised ship and steering gear under the design [1/s].
    warnings : tuple of str
        The design's warnings (margins below the minimums).
    max_heading_error : float or None
        The LQ Bryson weight used [deg].
    max_cross_track : float or None
        The cross-track Bryson weight used [m].
    offset : float or None
        The route scenario's initial offset [m].
    speed : float
        Of the straight run [m/s].
    dt : float
        Controller sample period [s].
    """

    ship: Any
    design: str
    controller: str
    gains: dict[str, float]
    nomoto: Any
    result: Any
    poles: np.ndarray
    warnings: tuple[str, ...]
    max_heading_error: float | None
    max_cross_track: float | None
    offset: float | None
    speed: float
    dt: float
    _bare: Any = dataclasses.field(repr=False, compare=False, default=None)
    _full: Any = dataclasses.field(repr=False, compare=False, default=None)

    def as_dict(self) -> dict[str, Any]:
        """Plain data (for JSON): the gains, Nomoto's indices, the poles, margins, weights.

        Returns
        -------
        dict
        """
        r, K, T = self.result, self.nomoto.gain, self.nomoto.time_constant
        out: dict[str, Any] = {
            "ship": self.ship.name, "design": self.design, "controller": self.controller,
            "nomoto": {"K_per_s": K, "T_s": T, "T1_s": self.nomoto.t1, "T2_s": self.nomoto.t2,
                       "T3_s": self.nomoto.t3},
            "gains": dict(self.gains),
            "designed_poles": [[float(z.real), float(z.imag)] for z in r.poles],
            "poles_with_ship_and_steering_gear": [[float(z.real), float(z.imag)]
                                                  for z in self.poles],
            "gain_margin": r.gain_margin, "phase_margin_deg": math.degrees(r.phase_margin),
            "crossover_rad_per_s": r.crossover,
            "warnings": list(self.warnings),
        }
        if self.design == "pid":
            out.update(natural_frequency=r.natural_frequency, damping=r.damping,
                       integral_time_s=r.integral_time, bandwidth=r.bandwidth)
        else:
            out["max_heading_error_deg"] = self.max_heading_error
        if self.design == "lq-cross-track":
            out.update(max_cross_track_m=self.max_cross_track, surge_speed=r.speed)
        return out

    def scenario(self, *, ship: str | None = None, heading_step: float = 10.0
                 ) -> dict[str, Any]:
        """A scenario (a mapping for :func:`scenario_toml` or
        :func:`~seahelm.scenario.parse_scenario`) running the design from the straight run it
        was designed at: a course change of ``heading_step`` degrees, or (``lq-cross-track``)
        the route due north from the offset, for :func:`scenario_duration` of the poles.

        Parameters
        ----------
        ship : str, optional
            How the scenario names the ship (a catalog name or a ship file's path relative to
            the scenario; default: the ship's name).
        heading_step : float, optional
            The course change [deg], in [-180, 180], not 0 (not for a route).

        Returns
        -------
        dict

        Raises
        ------
        ParameterError
            A ``heading_step`` out of range (``field="heading_step"``).
        """
        if not (math.isfinite(heading_step) and heading_step != 0 and abs(heading_step) <= 180):
            raise ParameterError(f"must be a course change in [-180, 180] [deg], not 0, got "
                                 f"{heading_step!r}", field="heading_step", unit="deg",
                                 value=heading_step)
        bare, name = self._bare, self.ship.name
        t_final = scenario_duration(self.poles)
        params = {("max_command_deg" if k == "max_command" else k):
                  (math.degrees(v) if k == "max_command" else float(v))
                  for k, v in self.gains.items()}
        if self.design == "lq-cross-track":
            start, route, _ = _route_setup(self.ship, bare, self._full, self.offset, t_final)
            return {"title": f"{name}: {self.controller} on a route",
                    "vessel": {"ship": ship or name, "initial": start},
                    "controller": {"model": self.controller, "dt": self.dt, "params": params},
                    "guidance": {"waypoints": [[float(n), float(e)] for n, e in route],
                                 "acceptance_radius": float(bare.length)},
                    "simulation": {"t_final": t_final, "dt": 0.1}}
        initial = {k: float(v) for k, v in zip(bare.state_labels, bare.x0)
                   if k not in ("north", "east", "heading") and v != 0.0}
        vessel: dict[str, Any] = {"ship": ship or name}
        if initial:
            vessel["initial"] = initial
        return {"title": f"{name}: {heading_step:g} deg course change, {self.controller}",
                "vessel": vessel,
                "controller": {"model": self.controller, "dt": self.dt, "params": params,
                               "reference": {"heading_deg": float(heading_step)}},
                "simulation": {"t_final": t_final, "dt": 0.1}}

    def comment(self) -> str:
        """The scenario's first lines: the command's design, Nomoto K, T and the poles.

        Returns
        -------
        str
        """
        return (f"seahelm autopilot tune {self.ship.name} --design {self.design}: Nomoto K = "
                f"{self.nomoto.gain:.4g} 1/s, T = {self.nomoto.time_constant:.4g} s at U = "
                f"{self.speed:.4g} m/s\nclosed-loop poles (ship + steering gear, linear): "
                + ", ".join(poles_text(self.poles)))


def scenario_toml(scenario: dict[str, Any], comment: str = "") -> str:
    """A scenario mapping as TOML text (tomlkit), ``comment`` as its first ``#`` lines.

    Parameters
    ----------
    scenario : dict
        :meth:`AutopilotTuning.scenario`.
    comment : str, optional

    Returns
    -------
    str
    """
    import tomlkit

    doc = tomlkit.document()
    for line in comment.splitlines():
        doc.add(tomlkit.comment(line))
    for key, value in scenario.items():
        doc.add(key, value)
    return tomlkit.dumps(doc)


def tune_autopilot(ship: Any, *, design: str = "pid", bandwidth: float = 0.05,
                   damping: float = 0.8, integral_time: float | None = None,
                   max_heading_error: float | None = None, max_cross_track: float | None = None,
                   offset: float | None = None, speed: float | None = None, dt: float = 0.5
                   ) -> AutopilotTuning:
    """Design a heading or cross-track autopilot for ``ship`` (module docstring).

    Parameters
    ----------
    ship : Ship or str
        A ship or a catalog name / ship-file path; it needs a steering gear.
    design : {"pid", "lq", "lq-cross-track"}, optional
    bandwidth : float, optional
        Closed-loop bandwidth ω_b [rad/s] (PID).
    damping : float, optional
        Relative damping ζ [-] (PID).
    integral_time : float, optional
        T_i [s] (PID; default 10/ω_n).
    max_heading_error : float, optional
        Bryson weight [deg] (LQ: default 5; cross-track: 20).
    max_cross_track : float, optional
        Bryson weight [m] (cross-track; default L/3; with both weights defaulted they grow by
        2^(1/4) until the simulated ship settles).
    offset : float, optional
        The route scenario's initial offset [m] (cross-track; default L).
    speed : float, optional
        Of the straight run [m/s] (default: the test speed).
    dt : float, optional
        Controller sample period [s], at most |T| / :data:`MAX_PERIOD_SHARE`.

    Returns
    -------
    AutopilotTuning

    Raises
    ------
    ParameterError
        Naming the argument: a non-positive or non-finite value, a weight or offset of another
        design, ``dt`` above |T|/5, a ship without steering gear (``field="ship"``), a
        bandwidth above what the rudder rate gives, no cross-track weights that settle.
    """
    from ...control.autopilot_design import (AutopilotDesignWarning, heading_loop_poles,
                                            lq_heading, pid_pole_placement,
                                            state_space_response)
    from ...ships import get_ship
    from ..equilibria.linearisation import linearize
    from .indices import steering_indices

    if design not in DESIGNS:
        raise ParameterError(f"must be one of {', '.join(DESIGNS)}, got {design!r}",
                             field="design", value=design)
    for field, value, unit in (("bandwidth", bandwidth, "rad/s"), ("damping", damping, "-"),
                               ("dt", dt, "s"), ("max_heading_error",
                                                 max_heading_error or 5.0, "deg"),
                               ("max_cross_track", max_cross_track or 1.0, "m")):
        if not (math.isfinite(value) and value > 0):
            raise ParameterError(f"must be > 0 [{unit}], got {value!r}", field=field,
                                 unit=unit, value=value)
    for field, value, designs in (("max_cross_track", max_cross_track, ("lq-cross-track",)),
                                  ("offset", offset, ("lq-cross-track",)),
                                  ("max_heading_error", max_heading_error,
                                   ("lq", "lq-cross-track"))):
        if value is not None and design not in designs:
            raise ParameterError(f"= {value!r} is an option of the design "
                                 f"{' or '.join(designs)}, not of {design}: drop it",
                                 field=field, value=value)
    if integral_time is not None and not integral_time > 0:
        raise ParameterError(f"must be > 0 [s], got {integral_time!r}", field="integral_time",
                             unit="s", value=integral_time)
    the_ship = get_ship(ship) if isinstance(ship, str) else ship
    if the_ship.steering_gear is None:
        raise ParameterError(f"'{the_ship.name}' has no steering gear to design for",
                             field="ship")
    servo = the_ship.servo
    bare = linearize(the_ship, speed=speed, actuator=False)
    full = linearize(the_ship, speed=speed, actuator=True)
    whole = full.select(states=[s for s in full.state_labels if s != "north"])
    indices = steering_indices(bare)
    K, T = indices.nomoto.gain, indices.nomoto.time_constant
    if dt > abs(T) / MAX_PERIOD_SHARE:  # (a sampled loop that slow cannot steer the ship)
        raise ParameterError(
            f"= {dt:g} s is more than 1/{MAX_PERIOD_SHARE:g} of the ship's Nomoto time "
            f"constant |T| = {abs(T):.4g} s: an autopilot sampled that seldom cannot steer it; "
            f"give at most {abs(T) / MAX_PERIOD_SHARE:.3g} s", field="dt", unit="s", value=dt)
    # position does not feed back at the straight run: the loop's poles are those without it
    full = full.select(states=[s for s in full.state_labels if s not in ("north", "east")])
    i_cmd = full.input_labels.index("rudder_command")
    row = {name: np.eye(len(full.state_labels))[full.state_labels.index(name)]
           for name in ("heading", "yaw_rate", "sway_speed") if name in full.state_labels}

    def heading_response(w: np.ndarray) -> np.ndarray:
        return state_space_response(full.A, full.B[:, i_cmd], row["heading"], w)

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", AutopilotDesignWarning)
        if design == "pid":
            result = pid_pole_placement(
                K, T, bandwidth=bandwidth, damping=damping, integral_time=integral_time,
                max_command=float(servo.max_angle), max_rate=float(servo.max_rate),
                heading_response=heading_response)
        elif design == "lq":
            states = tuple(s for s in indices.steering_states)
            block = bare.select(states=states, inputs=["rudder_angle"])
            max_heading_error = 5.0 if max_heading_error is None else max_heading_error
            result = lq_heading(block.A, block.B[:, 0], states,
                                max_heading_error=math.radians(max_heading_error),
                                max_rudder=float(servo.max_angle))
        else:
            states = tuple(s for s in indices.steering_states)
            block = bare.select(states=states, inputs=["rudder_angle"])
            surge = float(bare.A[bare.state_labels.index("east"),
                                 bare.state_labels.index("heading")])  # ∂ė/∂ψ at ψ = 0
            offset = bare.length if offset is None else offset
            start_offset = offset
            result, max_cross_track, max_heading_error = _cross_track_design(
                block, states, surge, max_cross_track or bare.length / 3.0,
                max_heading_error or 20.0, float(servo.max_angle),
                explicit=max_cross_track is not None or max_heading_error is not None,
                settles=lambda designs: cross_track_settles(the_ship, bare, whole, designs,
                                                            start_offset, dt))
    if design == "lq-cross-track":
        gains = {**result.gains, "max_command": result.max_command}
        actual = cross_track_loop_poles(whole, result.gains)
    else:
        gains = dict(result.params.as_dict())
        p = result.params
        if design == "pid":
            k = dict(k_heading=p.kp, k_yaw_rate=p.kd, k_integral=p.ki)
        else:
            k = dict(k_heading=p.k_heading, k_yaw_rate=p.k_yaw_rate, k_integral=p.k_integral,
                     k_sway=p.k_sway)
        actual = heading_loop_poles(full.A, full.B[:, i_cmd], row["heading"], row["yaw_rate"],
                                    c_sway=row.get("sway_speed"), **k)
    controller = DESIGNS[design]
    if the_ship.has_propeller:  # the rps of the self-propelled straight run, held
        controller += "-rps"
        gains["propeller_rps"] = float(full.u0[full.input_labels.index("propeller_rps")])
    return AutopilotTuning(
        ship=the_ship, design=design, controller=controller, gains=gains,
        nomoto=indices.nomoto, result=result, poles=actual,
        warnings=tuple(str(w.message) for w in caught),
        max_heading_error=None if design == "pid" else max_heading_error,
        max_cross_track=max_cross_track if design == "lq-cross-track" else None,
        offset=offset if design == "lq-cross-track" else None, speed=float(bare.speed), dt=dt,
        _bare=bare, _full=full)
