"""A batch of closed-loop runs described once: what the engine runs, and the shape of the question.

:class:`RunBatch` is a frozen, typed description of everything
:func:`seahelm.simulation.engine.simulate` needs (components, per-run parameter rows, initial
states, signals, timing, bounds, seed, metadata) plus the batch's :class:`BatchLayout`: the
dimensions the runs span. A 3 × 4 grid over ``controller.params.kp`` and
``controller.params.kd`` has the layout ``kp × kd`` (runs in C order: ``kd`` varies fastest);
Monte-Carlo adds a ``sample`` dimension (its drawn values are :class:`BatchValues`); a plain
batch of ``n`` runs has one ``run`` dimension. :func:`simulate_batch` runs it and returns a
:class:`~seahelm.results.SimResult` that keeps the layout, so ``result.to_xarray()`` has the dims
``(kp, kd, time)`` (capytaine's ``fill_dataset`` keeps the problem's coordinates in the same
way).

The layout classes live below the results and the simulation, in :mod:`seahelm.result_layout`
(the results keep a layout without importing the simulation); they are re-exported here.

Nothing here validates what the engine runs (timing, command counts, bounds labels, shapes):
the engine is the one validator of its inputs. A :class:`BatchLayout` checks only itself
(unique dimension names, coordinate lengths); its size is checked against the runs the engine
made when the result is built.

Example::

    batch = RunBatch(model=NOMOTO2, params=mariner, x0=np.zeros(5), t_final=600.0, dt=0.1,
                     controller=PID_HEADING, controller_params=gains,       # 12 rows
                     reference=[math.radians(20.0)],
                     layout=BatchLayout(axes=(BatchAxis(name="kp", values=kps, key="kp"),
                                              BatchAxis(name="kd", values=kds, key="kd"))))
    ds = simulate_batch(batch).to_xarray()     # dims (kp, kd, time)
"""

from __future__ import annotations

import dataclasses
import types
from collections.abc import Callable, Collection, Mapping, Sequence
from typing import TYPE_CHECKING, Any

from ..errors import ParameterError
from ..result_layout import RESERVED_DIMS, BatchAxis, BatchLayout, BatchValues

if TYPE_CHECKING:  # pragma: no cover
    from ..actuators.base import Actuator
    from ..control.base import Controller
    from ..results import SimResult
    from ..vessels.base import VesselModel

__all__ = ["BatchAxis", "BatchValues", "BatchLayout", "RunBatch", "simulate_batch", "grid_axes"]


def grid_axes(
    grid: Mapping[str, Sequence[float]],
    *,
    units: Mapping[str, str] | None = None,
    reserved: Collection[str] = (),
) -> tuple[BatchAxis, ...]:
    """Axes of a Cartesian grid over key paths, named by the last path component when unique.

    ``{"controller.params.kp": [...], "controller.params.kd": [...]}`` gives the dimensions
    ``kp`` and ``kd``; a short name shared by two keys, or in ``reserved`` (names the result
    already uses for its variables), falls back to the full key path.

    Parameters
    ----------
    grid : mapping of key path to sequence of float
        The varied keys and their values, outermost dimension first.
    units : mapping of key path to str, optional
        Unit of each key's values (default: none).
    reserved : collection of str, optional
        Names a dimension may not take (default none; ``time`` always).

    Returns
    -------
    tuple of BatchAxis
    """
    units = units or {}
    taken = set(reserved) | set(RESERVED_DIMS)
    short = [key.rsplit(".", 1)[-1] for key in grid]
    axes = []
    for key, name in zip(grid, short):
        if short.count(name) > 1 or name in taken:
            name = key
        axes.append(BatchAxis(name=name, values=grid[key], key=key, units=units.get(key, "")))
    return tuple(axes)


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class RunBatch:
    """Everything :func:`~seahelm.simulation.engine.simulate` needs, and the batch's layout.

    The fields are the engine's arguments (see :func:`~seahelm.simulation.engine.simulate` for
    their forms and units); the engine validates them when the batch runs. ``None`` for a
    component (controller, actuator) means the engine's default.

    Parameters
    ----------
    model : VesselModel
        The vessel model.
    params : Params, sequence of Params or array (runs, n_params)
        Vessel parameters, one set for all runs or one per run.
    x0 : array_like, shape (n_states,) or (runs, n_states)
        Initial vessel state (SI units, radians).
    t_final, dt : float
        Duration [s] and integration step [s].
    controller, controller_params : Controller, Params or array, optional
        Controller (default: the engine's, open loop) and its parameters.
    actuator, actuator_params, actuator_x0 : Actuator, Params or array, array_like, optional
        Actuator (default: the engine's, rudder servo), its parameters and initial state.
    reference, disturbance : None, array or callable, optional
        Controller reference and model disturbances, as :func:`simulate` takes them (a callable
        is evaluated by the engine on its own time grid).
    controller_dt : float, optional
        Controller sample period [s] (default ``dt``).
    integrator : str, optional
        Fixed-step method, a name in :data:`seahelm.simulation.integrators.INTEGRATORS`
        (default "rk4").
    record_every : int, optional
        Record every n-th step (default 1).
    bounds : mapping label -> (low, high), optional
        Admissible state bounds (default none).
    seed : int, optional
        Seed the batch's random inputs came from, stored with the results.
    metadata : mapping, optional
        Extra attributes stored with the results (e.g. the scenario text).
    layout : BatchLayout, optional
        The dimensions the runs span (default: one ``run`` dimension).
    environment, environment_params : Environment, Params or array, optional
        Wind and wave loads (:mod:`seahelm.environment.loads`) and their parameters.
    """

    model: "VesselModel"
    params: Any
    x0: Any
    t_final: float
    dt: float
    controller: "Controller | None" = None
    controller_params: Any = None
    actuator: "Actuator | None" = None
    actuator_params: Any = None
    actuator_x0: Any = None
    reference: Any = None
    disturbance: Any = None
    controller_dt: float | None = None
    integrator: str = "rk4"
    record_every: int = 1
    bounds: Mapping[str, tuple[float, float]] = dataclasses.field(default_factory=dict)
    seed: int | None = None
    metadata: Mapping[str, Any] = dataclasses.field(default_factory=dict)
    layout: BatchLayout | None = None
    environment: Any = None
    environment_params: Any = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "bounds", types.MappingProxyType(dict(self.bounds)))
        object.__setattr__(self, "metadata", types.MappingProxyType(dict(self.metadata)))
        if self.layout is not None and not isinstance(self.layout, BatchLayout):
            raise ParameterError(
                f"`layout` must be a BatchLayout, got {type(self.layout).__name__}")

    @property
    def n_runs(self) -> int | None:
        """Number of runs the layout spans (None without a layout: the engine decides)."""
        return None if self.layout is None else self.layout.size

    def simulate_kwargs(self) -> dict[str, Any]:
        """Keyword arguments of :func:`~seahelm.simulation.engine.simulate` for this batch.

        Returns
        -------
        dict
            The engine's arguments; components given as ``None`` are left out (engine
            defaults).
        """
        kwargs: dict[str, Any] = {
            f.name: getattr(self, f.name) for f in dataclasses.fields(self) if f.name != "layout"
        }
        for name in ("controller", "actuator"):
            if kwargs[name] is None:
                del kwargs[name]
        kwargs["bounds"] = dict(self.bounds)
        kwargs["metadata"] = dict(self.metadata)
        return kwargs

    def replace(self, **changes: Any) -> "RunBatch":
        """A copy with some fields changed (``dataclasses.replace``).

        Parameters
        ----------
        **changes
            New field values.

        Returns
        -------
        RunBatch
        """
        return dataclasses.replace(self, **changes)


def simulate_batch(
    batch: RunBatch,
    *,
    throw: bool = False,
    progress: Callable[[int, int], None] | None = None,
) -> "SimResult":
    """Run a :class:`RunBatch` through the engine; the result keeps the batch's layout.

    Parameters
    ----------
    batch : RunBatch
        The runs and their layout.
    throw : bool, optional
        Raise :class:`~seahelm.errors.SimulationDiverged` on the first diverged run (flat run
        index) instead of recording it (default False).
    progress : callable(done_steps, total_steps), optional
        Called between chunks of the simulation loop.

    Returns
    -------
    SimResult
        With ``layout`` set, so :meth:`~seahelm.results.SimResult.to_xarray` has the batch's
        dimensions.

    Raises
    ------
    ParameterError
        On invalid inputs (raised by the engine before anything runs), or if the layout's size
        differs from the number of runs the inputs broadcast to.
    SimulationDiverged
        With ``throw=True``, when a run diverges.
    """
    from .engine import simulate

    if not isinstance(batch, RunBatch):
        raise TypeError(f"`batch` must be a RunBatch, got {type(batch).__name__}")
    result = simulate(**batch.simulate_kwargs(), throw=throw, progress=progress)
    if batch.layout is None:
        return result
    return dataclasses.replace(result, layout=batch.layout)
