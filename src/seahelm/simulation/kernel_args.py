"""The compiled loop's arguments by name: a few groups of arrays, one per concern.

The kernel (:mod:`seahelm.simulation.kernel_template`) takes its arrays as plain tuples, one
per group below, and unpacks them by position at its top; :data:`GROUPS` names the members of
each group in that order (the one place the order is written down on this side). The loop's
stages (:mod:`seahelm.simulation.stage`) bring one group each, named by the stage
(``stages[q]``, members :attr:`~seahelm.simulation.stage.Stage.members`); a loop without
stages gets an empty tuple. Plain tuples,
not namedtuples: numba's dispatcher types a tuple of arrays in C, a namedtuple in Python
(measured on 56 small arrays: 9.4 µs a call as 56 positional arguments, 6.2 µs as 7 tuples,
23 µs as 7 namedtuples).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator

import numpy as np

__all__ = ["GROUPS", "KernelArrays"]

#: The members of each group, in the order the kernel unpacks them.
GROUPS: dict[str, tuple[str, ...]] = {
    # what a run carries from one slice of steps to the next
    "state": ("z", "controller_state", "command", "actuator_command"),
    # per-run parameter records and the state bounds
    "params": ("vessel", "actuator", "controller", "lower", "upper"),
    # signals on the grid, (runs|1, steps+1|1, channels)
    "signals": ("disturbance", "reference"),
    # each run's status, time and state of failure
    "outcome": ("status", "failure_time", "failure_state"),
    # the recordings (runs, records, channels)
    "record": ("state", "output", "command"),
}


@dataclasses.dataclass
class KernelArrays:
    """The batch's arrays in the kernel's groups (:data:`GROUPS`): each a tuple of arrays;
    ``stages`` a tuple of groups, one per stage of the loop, and ``stage_names`` theirs."""

    state: tuple[np.ndarray, ...]
    params: tuple[np.ndarray, ...]
    signals: tuple[np.ndarray, ...]
    outcome: tuple[np.ndarray, ...]
    record: tuple[np.ndarray, ...]
    stages: tuple[tuple[np.ndarray, ...], ...] = ()
    stage_names: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        for name, members in GROUPS.items():
            if len(getattr(self, name)) != len(members):  # pragma: no cover - a bug
                raise AssertionError(f"group {name}: {len(getattr(self, name))} arrays, "
                                     f"expected {members}")

    def __iter__(self) -> Iterator[np.ndarray]:
        """Every array, group by group in the order of :data:`GROUPS`, then the stages'."""
        for name in GROUPS:
            yield from getattr(self, name)
        for group in self.stages:
            yield from group

    @property
    def n_runs(self) -> int:
        """Runs in the batch."""
        return int(self.state[0].shape[0])

    def writable(self) -> "KernelArrays":
        """The same groups with every array writable: numba types a read-only array apart
        from a writable one, and a kernel called with both (a broadcast view of one run, say)
        would compile twice, each 15-80 s."""
        def mine(group: tuple[np.ndarray, ...]) -> tuple[np.ndarray, ...]:
            return tuple(a if a.flags.writeable else a.copy() for a in group)

        # (the engine's own arrays: as they are; a loop, not all() over the generator
        # __iter__, which costs a generator step an array, twice, at every call)
        for group in (self.state, self.params, self.signals, self.outcome, self.record,
                      *self.stages):
            for a in group:
                if not a.flags.writeable:
                    break
            else:
                continue
            break
        else:
            return self
        return KernelArrays(**{name: mine(getattr(self, name)) for name in GROUPS},
                            stages=tuple(mine(g) for g in self.stages),
                            stage_names=self.stage_names)

    def get(self, group: str, member: str) -> np.ndarray:
        """One array by its group's and its own name.

        Parameters
        ----------
        group, member : str
            Names in :data:`GROUPS` (``get("state", "z")``), or a stage's name and one of its
            members (``get("environment", "params")``).

        Returns
        -------
        ndarray
        """
        if group in GROUPS:
            return getattr(self, group)[GROUPS[group].index(member)]
        from .stages import STAGES

        q = self.stage_names.index(group)
        return self.stages[q][STAGES[group].members.index(member)]
