"""A batch of closed-loop runs described once: what the engine runs, and the shape of the question.

A batch is a :class:`~seahelm.simulation.problem.Problem` (the one typed request of a run
(its old name here, ``RunBatch``, is deprecated): components, per-run parameter rows, initial states, signals, timing, bounds, seed,
metadata, options), whose :class:`BatchLayout` gives the dimensions the runs span. A 3 × 4 grid over ``controller.params.kp`` and
``controller.params.kd`` has the layout ``kp × kd`` (runs in C order: ``kd`` varies fastest);
Monte-Carlo adds a ``sample`` dimension (its drawn values are :class:`BatchValues`); a plain
batch of ``n`` runs has one ``run`` dimension. :func:`simulate_batch` runs it and returns a
:class:`~seahelm.results.SimResult` that keeps the layout, so ``result.to_xarray()`` has the dims
``(kp, kd, time)`` (capytaine's ``fill_dataset`` keeps the problem's coordinates in the same
way).

The layout classes live below the results and the simulation, in :mod:`seahelm.result_layout`
(the results keep a layout without importing the simulation); they are re-exported here.

The :class:`~seahelm.simulation.problem.Problem` validates itself on construction (components,
timing, wiring, bounds labels, options); the engine checks what depends on the per-run inputs'
sizes when it builds its arrays. A :class:`BatchLayout` checks only itself (unique dimension
names, coordinate lengths); its size is checked against the runs the engine made when the
result is built.

Example::

    batch = Problem(model=NOMOTO2, params=mariner, x0=np.zeros(5), t_final=600.0, dt=0.1,
                    controller=PID_HEADING, controller_params=gains,       # 12 rows
                    reference=[math.radians(20.0)],
                    layout=BatchLayout(axes=(BatchAxis(name="kp", values=kps, key="kp"),
                                             BatchAxis(name="kd", values=kds, key="kd"))))
    ds = simulate_batch(batch).to_xarray()     # dims (kp, kd, time)
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping, Sequence
from typing import TYPE_CHECKING

from ..errors import deprecated_names
from ..result_layout import RESERVED_DIMS, BatchAxis, BatchLayout, BatchValues
from .problem import Problem

if TYPE_CHECKING:  # pragma: no cover
    from ..results import SimResult

__all__ = ["BatchAxis", "BatchValues", "BatchLayout", "simulate_batch", "grid_axes"]


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


#: ``RunBatch``, the old name of :class:`Problem`: deprecated (a warning on access).
__getattr__ = deprecated_names(__name__, {
    "RunBatch": ("seahelm.simulation.problem", "Problem", "seahelm.Problem")})


def simulate_batch(
    batch: Problem,
    *,
    throw: bool = False,
    progress: Callable[[int, int], None] | None = None,
) -> "SimResult":
    """Run a :class:`RunBatch` through the engine; the result keeps the batch's layout.

    Parameters
    ----------
    batch : Problem
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

    if not isinstance(batch, Problem):
        raise TypeError(f"`batch` must be a Problem, got {type(batch).__name__}")
    return simulate(batch, throw=throw, progress=progress)
