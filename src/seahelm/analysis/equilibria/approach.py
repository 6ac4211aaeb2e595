"""The steady straight approach: one type for one run, and its batch.

:class:`Approach`
    one run's approach: its ``state`` (model order), its constant ``inputs`` by name and its
    ``speed`` U_0; ``rudder`` and ``rps`` read the inputs. What
    :func:`~seahelm.analysis.equilibria.equilibrium.approach_state` returns, what the manoeuvres
    start from (before issue 47 the manoeuvres had their own ``Approach(state, rudder, rps, speed)``
    in ``analysis/maneuvers/ships.py``).
:class:`BatchApproach`
    the approaches of a batch (arrays over runs, with a status and message per run), what
    :func:`~seahelm.analysis.equilibria.batch_equilibrium.approach_states` returns;
    :meth:`BatchApproach.approach` is one run's :class:`Approach`.

:mod:`.approach_cache` keeps solved approaches (``ApproachCache``).
"""

from __future__ import annotations

import dataclasses
import enum
import math
from collections.abc import Mapping
from types import MappingProxyType
from typing import NamedTuple

import numpy as np

from .plant import EquilibriumError

__all__ = ["Approach", "ApproachStatus", "BatchApproach"]


class Approach(NamedTuple):
    """Initial state and constant inputs of a steady straight approach (one run)."""

    state: np.ndarray
    """State vector in the model's ``state_labels`` order (SI units, radians)."""
    inputs: Mapping[str, float]
    """Model inputs by name, e.g. ``{"rudder_angle": 0.0, "propeller_rps": 11.85}``."""
    speed: float = math.nan
    """Approach speed U_0 [m/s] (the speed asked for; a trimmed approach's surge differs from
    it by the trim)."""

    @property
    def rudder(self) -> float:
        """Rudder angle δ [rad] of the approach (the trim angle of a trimmed one)."""
        return float(self.inputs["rudder_angle"])

    @property
    def rps(self) -> float | None:
        """Propeller rps [1/s] (None for a model without a ``propeller_rps`` input)."""
        n = self.inputs.get("propeller_rps")
        return None if n is None else float(n)


class ApproachStatus(enum.IntEnum):
    """Outcome of one run's approach (0 is success)."""

    OK = 0
    NO_SELF_PROPULSION = 1
    """The surge force is not negative with the propeller stopped."""
    RPS_OUT_OF_RANGE = 2
    """No rps up to ``max_rps`` gives zero surge force."""
    NOT_FINITE = 3
    """The right-hand side was NaN or infinite."""
    SINGULAR = 4
    """The Jacobian of the trim equations is singular."""
    LINE_SEARCH = 5
    """The line search found no decrease of the residual."""
    MAX_ITERATIONS = 6
    """Not converged within ``max_iterations``."""
    NO_EQUILIBRIUM = 7
    """A constant-speed model's one-run solve raised (its message is kept)."""


@dataclasses.dataclass(frozen=True)
class BatchApproach:
    """Steady straight approaches of a batch of runs (arrays over ``runs``).

    A failed run keeps NaN in its state, rudder, rps and drift angle; ``status`` and
    ``message`` say why.
    """

    state: np.ndarray
    """States (runs, n_states) in the model's ``state_labels`` order (SI units, radians)."""
    rudder: np.ndarray
    """Trim rudder angle δ [rad] (0 without ``trim``)."""
    rps: np.ndarray
    """Self-propulsion propeller rps [1/s] (NaN for a model without a propeller input)."""
    speed: np.ndarray
    """Approach speed U_0 [m/s]."""
    drift_angle: np.ndarray
    """Drift angle β of the approach [rad] (0 for a ship symmetric at rest)."""
    status: np.ndarray
    """:class:`ApproachStatus` per run (int)."""
    message: tuple[str, ...]
    """'ok' or the reason of the failure, per run."""
    iterations: np.ndarray
    """Newton iterations of the trim (rps iterations for an untrimmed approach)."""
    residual: np.ndarray
    """Final scaled residual ‖F‖∞ of the trim (of the surge equation without trim)."""

    @property
    def ok(self) -> np.ndarray:
        """Boolean mask of the runs whose approach was found."""
        return self.status == ApproachStatus.OK

    @property
    def n_runs(self) -> int:
        """Number of runs."""
        return int(self.status.size)

    def approach(self, run: int, speed: float | None = None, *,
                 has_rps: bool | None = None) -> Approach:
        """Run ``run``'s :class:`Approach` (its state read-only, its inputs a read-only mapping).

        Parameters
        ----------
        run : int
            The run.
        speed : float, optional
            The speed to record (default: the run's ``speed``).
        has_rps : bool, optional
            Whether the model has a ``propeller_rps`` input (default: the run's rps is
            finite).

        Returns
        -------
        Approach

        Raises
        ------
        EquilibriumError
            If the run failed (its message).
        """
        if self.status[run] != ApproachStatus.OK:
            raise EquilibriumError(self.message[run])
        state = self.state[run].copy()
        state.setflags(write=False)
        inputs = {"rudder_angle": float(self.rudder[run])}
        if has_rps if has_rps is not None else math.isfinite(self.rps[run]):
            inputs["propeller_rps"] = float(self.rps[run])
        U = float(self.speed[run]) if speed is None else float(speed)
        return Approach(state, MappingProxyType(inputs), U)
