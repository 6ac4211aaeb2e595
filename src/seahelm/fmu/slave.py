"""The FMI 2.0 co-simulation slave of a seahelm ship: a :class:`pythonfmu.Fmi2Slave` that steps
a :class:`~seahelm.Simulator` (the compiled loop of ``simulate``) with the master's commands.

An FMU built by :func:`seahelm.fmu.build_fmu` holds a subclass of :class:`ShipSlave` naming
its ship file (``ship.toml``, in the FMU's resources). Its variables:

* **inputs** (continuous): the actuator's commands, ``rudder_command`` [rad] and, for a ship
  with a propeller, ``propeller_rps`` [1/s]; start: the straight approach (rudder trim,
  self-propulsion rps); held over each ``doStep``;
* **outputs** (continuous, ``initial="exact"``, start: the approach at the default
  parameters): ``north``, ``east`` [m], ``heading`` [rad], ``surge_speed``, ``sway_speed``,
  ``speed`` [m/s], ``yaw_rate`` [rad/s], ``rudder_angle`` [rad] (the steering gear's);
* **parameters** (fixed): ``initial_north``, ``initial_east`` [m], ``initial_heading`` [rad],
  ``integration_step`` [s] (default 0.1; every communication step must be a whole multiple),
  ``wind_speed`` [m/s] and ``wind_direction`` [rad] (Blendermann's wind loads from the ship's
  windage when ``wind_speed`` > 0).

The simulator is built when the master leaves initialisation mode (its horizon: the
experiment's stop time, default 3,600 s) with the commands as an external controller sampled
every ``integration_step``, so a ``doStep`` of h seconds is one call of the compiled loop over
h / ``integration_step`` steps. A step that fails (a NaN command, a run that diverged, a step
past the horizon, a step not a whole multiple of ``integration_step``) logs the reason and
returns ``fmi2Error``.

The FMU runs Python (pythonfmu's wrapper): the Python that runs it needs seahelm installed.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any
from xml.etree.ElementTree import Element, SubElement

import numpy as np

from .._optional import optional_import
from ..errors import ParameterError

pythonfmu = optional_import("pythonfmu", extra="fmu", purpose="seahelm fmu")
from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Real  # noqa: E402
from pythonfmu.default_experiment import DefaultExperiment  # noqa: E402
from pythonfmu.enums import Fmi2Initial, Fmi2Status  # noqa: E402

__all__ = ["ShipSlave", "OUTPUTS", "PARAMETERS", "UNITS", "hold_namespace"]

#: Outputs: name, unit, description.
OUTPUTS = (("north", "m", "position north (earth frame)"),
           ("east", "m", "position east (earth frame)"),
           ("heading", "rad", "heading ψ, clockwise from north (not wrapped)"),
           ("surge_speed", "m/s", "surge speed u through the water"),
           ("sway_speed", "m/s", "sway speed v through the water (at midship)"),
           ("speed", "m/s", "speed U = sqrt(u² + v²)"),
           ("yaw_rate", "rad/s", "yaw rate r"),
           ("rudder_angle", "rad", "rudder angle δ (the steering gear's state)"))
#: Parameters: name, unit, default, description.
PARAMETERS = (("initial_north", "m", 0.0, "initial position north"),
              ("initial_east", "m", 0.0, "initial position east"),
              ("initial_heading", "rad", 0.0, "initial heading"),
              ("integration_step", "s", 0.1, "fixed integration step (RK4); each "
               "communication step is a whole multiple of it"),
              ("wind_speed", "m/s", 0.0, "true wind speed (Blendermann's loads when > 0)"),
              ("wind_direction", "rad", 0.0, "direction the wind comes from, clockwise from "
               "north"))
#: The SI base-unit exponents of the units used (FMI 2.0 UnitDefinitions).
UNITS = {"m": {"m": 1}, "rad": {"rad": 1}, "s": {"s": 1}, "m/s": {"m": 1, "s": -1},
         "rad/s": {"rad": 1, "s": -1}, "1/s": {"s": -1}}
#: Horizon [s] when the master gives no stop time.
DEFAULT_HORIZON = 3600.0
#: References to the generated slave modules' namespaces, never dropped (:func:`hold_namespace`).
_NAMESPACE_REFS: list[dict[str, Any]] = []


def hold_namespace(namespace: dict[str, Any]) -> None:
    """Keep one more reference to a generated slave module's namespace, for good.

    pythonfmu 0.7's wrapper, when it instantiates a slave, releases the module's ``__dict__``
    once more than it holds it (``findClass``: a ``Py_DECREF`` of the borrowed
    ``PyModule_GetDict``); it also runs the module's code once more in that namespace, so the
    script calling this at import time (:mod:`seahelm.fmu.build`'s template) adds the
    reference it takes away. Without it a master in the same Python process (fmpy) crashed at
    a later garbage collection, the dictionary freed under its module (a segmentation fault
    after the run).

    Parameters
    ----------
    namespace : dict
        The module's ``globals()``.
    """
    _NAMESPACE_REFS.append(namespace)

class ShipSlave(Fmi2Slave):
    """One ship as an FMI 2.0 co-simulation slave (see the module's notes).

    Parameters
    ----------
    **kwargs
        pythonfmu's (``instance_name``, ``resources``).

    Attributes
    ----------
    ship_file : str
        The ship file's name in the FMU's resources (set by the generated subclass).
    """

    ship_file = "ship.toml"
    #: A communication step of 1 s (a whole multiple of the default ``integration_step``): a
    #: master that takes its step from the model description (fmpy's ``simulate_fmu`` without
    #: ``output_interval``) makes steps the FMU can do, not stop_time/500.
    default_experiment = DefaultExperiment(start_time=0.0, step_size=1.0)
    author = "seahelm"
    description = "seahelm ship (MMG/Nomoto manoeuvring model, steering gear, propeller)"

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        from ..analysis.equilibria.equilibrium import approach_state
        from ..ships import get_ship
        from ..simulation.problem import Problem

        ship = get_ship(self._resource(self.ship_file))
        if ship.steering_gear is None:
            raise ParameterError(f": ship {ship.name!r} has no steering gear; an FMU takes "
                                 "the rudder command of a steering gear", field="ship",
                                 value=ship.name)
        self._ship = ship
        self._start = approach_state(ship, trim=True)
        rudder0 = float(self._start.inputs.get("rudder_angle", 0.0))
        labels = Problem(ship=ship, x0=self._start.state, actuator_x0=[rudder0], t_final=1.0,
                         dt=0.1).wiring
        self._command_labels = labels.commands
        self._units: dict[str, str] = {}
        start = {"rudder_command": rudder0, **self._start.inputs}
        for name, unit in zip(labels.commands, labels.command_units):
            setattr(self, name, float(start.get(name, 0.0)))
            self._add(Real(name, causality=Fmi2Causality.input,
                           variability=Fmi2Variability.continuous,
                           description=f"command {name} (held over a step)"), unit)
        for name, unit, default, text in PARAMETERS:
            setattr(self, name, default)
            self._add(Real(name, causality=Fmi2Causality.parameter,
                           variability=Fmi2Variability.fixed, description=text), unit)
        self._state_labels = ship.model.state_labels
        self._set_outputs(self._initial_state(), rudder0)
        for name, unit, text in OUTPUTS:
            self._add(Real(name, causality=Fmi2Causality.output,
                           variability=Fmi2Variability.continuous,
                           initial=Fmi2Initial.exact, description=text), unit)
        self._sim: Any = None
        self._horizon = DEFAULT_HORIZON

    # -- FMI ------------------------------------------------------------------------------
    def setup_experiment(self, start_time: float, stop_time: float | None = None,
                         tolerance: float | None = None) -> None:
        """Note the experiment's stop time (the simulator's horizon).

        Parameters
        ----------
        start_time, stop_time : float
            [s]
        tolerance : float, optional
            Not used (fixed step).
        """
        self._t0 = float(start_time)
        if stop_time is not None and stop_time > start_time:
            self._horizon = float(stop_time) - float(start_time)

    def exit_initialization_mode(self) -> None:
        """Build the simulator from the parameters set and reset it."""
        from ..simulation.problem import Problem
        from ..simulation.stepping import Simulator

        dt = float(self.integration_step)
        if not (math.isfinite(dt) and dt > 0):
            raise ParameterError(f"must be > 0 [s], got {dt!r}", field="integration_step",
                                 unit="s", value=dt)
        for name in ("wind_speed", "wind_direction"):
            v = float(getattr(self, name))
            if not (math.isfinite(v) and (v >= 0 or name == "wind_direction")):
                raise ParameterError(f"must be finite{' and >= 0' * (name == 'wind_speed')} "
                                     f"[{'m/s' if name == 'wind_speed' else 'rad'}], got {v!r}",
                                     field=name, value=v)
        n_steps = max(1, math.ceil(self._horizon / dt - 1e-9))
        env: dict[str, Any] = {}
        if self.wind_speed > 0:
            from ..environment.loads import environment, ship_load_params

            e = environment(wind="blendermann")
            env = {"environment": e, "environment_params": ship_load_params(
                self._ship, e, wind_speed=float(self.wind_speed),
                wind_direction=float(self.wind_direction))}
        rudder0 = float(self._start.inputs.get("rudder_angle", 0.0))
        problem = Problem(ship=self._ship, x0=self._initial_state(), actuator_x0=[rudder0],
                          t_final=n_steps * dt, dt=dt, controller_dt=dt,
                          record_every=n_steps, **env)
        self._sim = Simulator(problem)
        self._sim.reset()
        self._set_outputs(self._initial_state(), rudder0)
        self._dt = dt
        self._steps = 0  # (integration steps done: the simulator's clock is this times dt)
        self._commands = np.zeros((1, len(self._command_labels)))

    def do_step(self, current_time: float, step_size: float) -> bool:
        """Advance by ``step_size`` seconds with the inputs held.

        Parameters
        ----------
        current_time, step_size : float
            [s]

        Returns
        -------
        bool
            False (with a logged reason) if the step failed.
        """
        sim = self._sim
        ratio = step_size / self._dt
        n = int(round(ratio))
        if n < 1 or abs(ratio - n) > 1e-9 * max(1.0, ratio):
            return self._fail(f"step_size {step_size!r} s is not a whole multiple of "
                              f"integration_step = {self._dt:g} s")
        t_before = self._steps * self._dt  # (= sim.time[0]: the run's steps times dt)
        if t_before + n * self._dt > sim.problem.t_final + 1e-9:
            return self._fail(f"a step to t = {t_before + n * self._dt:g} s is past the "
                              f"horizon {sim.problem.t_final:g} s (the experiment's stop time)")
        cmd = self._commands
        for j, name in enumerate(self._command_labels):
            cmd[0, j] = getattr(self, name)
        try:
            obs = sim.step(cmd, n=n)
        except ParameterError as exc:
            return self._fail(str(exc))
        self._steps += n  # (a diverged run's clock moved on too)
        if obs.status[0] != 0:
            return self._fail(sim.failure(0) or "the run diverged")
        values = obs.values[0].tolist()  # (Python floats)
        for name, j in self._out_index(obs).items():
            setattr(self, name, values[j])
        self.rudder_angle = sim.state(0)["rudder_angle"]
        return True

    def terminate(self) -> None:
        """End the simulator's thread pool."""
        if self._sim is not None:
            self._sim.close()
            self._sim = None

    # -- helpers ----------------------------------------------------------------------------
    def to_xml(self, model_options: dict[str, str] | None = None) -> Element:
        """pythonfmu's model description with each variable's unit and the unit definitions.

        Parameters
        ----------
        model_options : dict, optional
            pythonfmu's FMU model options.

        Returns
        -------
        xml.etree.ElementTree.Element
        """
        root = super().to_xml(model_options or {})
        units = SubElement(root, "UnitDefinitions")
        root.remove(units)
        for name in sorted(set(self._units.values())):
            unit = SubElement(units, "Unit", {"name": name})
            SubElement(unit, "BaseUnit", {k: str(v) for k, v in UNITS[name].items()})
        root.insert(list(root).index(root.find("CoSimulation")) + 1, units)
        for var in root.find("ModelVariables"):
            unit = self._units.get(var.get("name"))
            real = var.find("Real")
            if unit is not None and real is not None:
                real.set("unit", unit)
        return root

    def _add(self, var: Real, unit: str) -> None:
        self._units[var.name] = unit
        self.register_variable(var)

    def _resource(self, name: str) -> Path:
        """A file of the FMU's resources (pythonfmu gives their directory, also when it
        builds the model description)."""
        if not self.resources:
            raise ParameterError(": the FMU's resources directory was not given (pythonfmu "
                                 "passes it)", field="resources")
        return Path(self.resources) / name

    def _initial_state(self) -> np.ndarray:
        x0 = np.array(self._start.state, dtype=float)
        for label, name in (("north", "initial_north"), ("east", "initial_east"),
                            ("heading", "initial_heading")):
            if label in self._state_labels:
                x0[self._state_labels.index(label)] = float(getattr(self, name))
        return x0

    def _set_outputs(self, x0: np.ndarray, rudder: float) -> None:
        s = dict(zip(self._state_labels, x0))
        u, v = s.get("surge_speed", 0.0), s.get("sway_speed", 0.0)
        for name in ("north", "east", "heading", "surge_speed", "sway_speed", "yaw_rate"):
            setattr(self, name, float(s.get(name, 0.0)))
        self.speed = float(math.hypot(u, v))
        self.rudder_angle = rudder

    def _out_index(self, obs: Any) -> dict[str, int]:
        if not hasattr(self, "_index"):
            self._index = {name: obs.labels.index(name) for name, _, _ in OUTPUTS
                           if name in obs.labels}
        return self._index

    def _fail(self, message: str) -> bool:
        self.log(message, Fmi2Status.error)
        return False
