"""Scenario files (TOML): schema, validation and the runs or manoeuvre they describe.

A ``[simulation]`` scenario becomes one :class:`~seahelm.simulation.problem.Problem`: the
engine's inputs and the batch's layout (:mod:`.runs`). A ``[maneuver]`` scenario becomes a
:class:`~seahelm.scenario.maneuver.ManeuverJob`: a standard manoeuvre or the IMO check of a
catalog ship (:mod:`.maneuver`). :func:`run_scenario` runs either.

Each check is made once, by whoever owns it. The scenario checks what only it knows: the TOML
structure and types (pydantic, :mod:`.schema`), names (models, catalog entries, integrators,
parameters, state and signal channels), parameter ranges (through the components' parameter
dataclasses) and signal specifications. What the engine runs -- timing (``t_final`` and
``controller.dt`` whole multiples of ``simulation.dt``), the controller/actuator command count,
bounds labels, shapes -- the engine validates, before anything is integrated; its error is
re-raised naming the scenario file and the key it most likely comes from. Every error names
the file, the key path, the bad value and what was expected, and is raised as
:class:`ScenarioError` (a :class:`~seahelm.errors.ParameterError`, so the CLI exits with
code 2).

Layout (see ``examples/*.toml``)::

    title = "..."
    [vessel]            model, catalog (named parameter set; gives the model), params, initial
    [actuator]          model, params
    [controller]        model, dt (sample period [s]), params, reference (per channel)
    [environment]       disturbance (per channel)
    [simulation]        t_final, dt, integrator, record_every, bounds
    [batch]             grid = {"controller.params.kp" = [..]}, [batch.monte_carlo] runs, seed, draws
    [guidance]          law (los | ilos), waypoints = [[north, east], ...], acceptance_radius,
                        lookahead, lookahead_min, lookahead_gamma, kappa: the route steers the
                        heading controller (grid keys "guidance.<name>"); a controller that
                        follows routes itself (lq-cross-track) takes waypoints and
                        acceptance_radius only
    [maneuver]          kind = turning | zigzag | pullout | spiral | imo, and its keys
                        (instead of [simulation], [controller], [environment], [batch])

Angles may be written in degrees with a ``_deg`` suffix on any parameter, initial state,
reference or disturbance channel whose unit is radians; they are converted at this edge.
The grid is a Cartesian product; Monte-Carlo draws are made per grid point with generators
spawned from ``SeedSequence(seed)``, and the seed is stored with the results. Results keep the
shape of the question: a grid over ``controller.params.kp`` and ``controller.params.kd``
comes back with the dimensions ``(kp, kd, time)`` (a dimension is named by the last component
of its key path, or by the whole path where that is ambiguous); Monte-Carlo adds ``sample``,
with the draws stored as variables; a scenario without a batch has one ``run``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from .errors import ScenarioError
from .loading import default_scenario_text, load_scenario, parse_scenario, validate_scenario
from .maneuver import ManeuverJob, prepare_maneuver
from .runs import prepare_runs, run_batch
from .schema import (
    ActuatorSection,
    ControllerSection,
    EnvironmentSection,
    ManeuverSection,
    Scenario,
    SimulationSection,
    VesselSection,
)

__all__ = ["Scenario", "ScenarioError", "ManeuverJob", "load_scenario", "parse_scenario",
           "validate_scenario", "run_scenario", "default_scenario_text", "prepare_runs",
           "prepare_maneuver", "VesselSection", "ActuatorSection", "ControllerSection",
           "EnvironmentSection", "SimulationSection", "ManeuverSection"]


def run_scenario(job: Any, *, progress: Callable[[int, int], None] | None = None,
                 throw: bool = False) -> Any:
    """Run what a scenario describes.

    Parameters
    ----------
    job : Problem or ManeuverJob
        Result of :func:`load_scenario` or :func:`parse_scenario`.
    progress : callable(done_steps, total_steps), optional
        Called between chunks of the simulation loop (a ``[simulation]`` scenario).
    throw : bool, optional
        Raise :class:`~seahelm.errors.SimulationDiverged` on the first diverged run instead of
        recording it (a ``[simulation]`` scenario; default False).

    Returns
    -------
    SimResult, or what :meth:`ManeuverJob.run` returns
        A :class:`~seahelm.results.SimResult` keeping the batch's layout (e.g. dims
        ``(kp, kd, time)``) for a ``[simulation]`` scenario.

    Raises
    ------
    ScenarioError
        If the engine or the manoeuvre rejects a value (naming the file and the key).
    """
    if isinstance(job, ManeuverJob):
        return job.run()
    return run_batch(job, progress=progress, throw=throw)
