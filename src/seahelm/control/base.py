"""The plug-in interface of a controller (sampled, zero-order hold).

A controller is stepped by the engine at its own sample period ``dt`` (an integer multiple of
the integration step) and its command is held constant in between. It is a bundle of
numba-compiled functions over one run:

``init(z, y, ref, p, cs)``
    fills the controller's internal state ``cs`` at t = 0.
``step(t, dt, z, y, ref, p, cs, cmd)``
    reads the full closed-loop state ``z`` (vessel states then actuator states), its
    measurements ``y`` — the model outputs it declares in ``measurement_labels``, in that order
    (e.g. ``heading``, ``yaw_rate``), routed to it by name — the reference vector ``ref`` at
    time ``t`` (``reference_labels`` order); updates ``cs`` in place and writes the commands
    ``cmd`` (``command_labels`` order). ``p`` is the run's parameter record (``p.kp``).
    A controller that declares ``output_labels`` (signals worth recording that feed nothing,
    e.g. a guidance law's cross-track error) writes them after its commands, into
    ``cmd[n_commands + j]``; the engine records them with the commands.

Commands are connected by name to an actuator's command channels or, with a pass-through
actuator, to the model inputs they name (``rudder_command`` → ``rudder_angle`` or the input of
the same name). A *pass-through* controller (``OPEN_LOOP``) has no channels of its own: its
references are the commands downstream needs, named after them.

This is the ``init``/``step`` protocol of python-control's sampled systems and of diffrax's
solvers: pure functions with the state passed explicitly.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

from numba import njit

from ..parameters import Params

__all__ = ["Controller", "wrap_pi"]


@njit(cache=True)
def wrap_pi(angle):  # pragma: no cover - compiled
    """Wrap a scalar angle [rad] to [−π, π) inside compiled controllers
    (:func:`seahelm.constants.wrap_angle` is the numpy version)."""
    if -math.pi <= angle < math.pi:  # the common case: no division
        return angle
    wrapped = (angle + math.pi) % (2.0 * math.pi) - math.pi
    return wrapped - 2.0 * math.pi if wrapped >= math.pi else wrapped


@dataclasses.dataclass(frozen=True, eq=False)
class Controller:
    """A controller usable by the simulation engine (see the module docstring).

    Attributes
    ----------
    name, description : str
        Registry name and one line on what it is.
    params_type : type[Params]
        Frozen parameter dataclass.
    state_labels : tuple of str
        Internal states (e.g. an integral).
    reference_labels, reference_units : tuple of str
        Reference channels.
    command_labels : tuple of str
        Commands it writes.
    init, step : numba dispatchers
        See the module docstring.
    measurement_labels : tuple of str
        Model outputs it reads, by name (routed into ``y`` in this order).
    passthrough : bool
        Reference = command, channels named after what they feed (open loop).
    output_labels, output_units : tuple of str
        Recorded signals it writes after its commands (they feed nothing).
    command_units, state_units : tuple of str
        The units of its commands and states, in their order (``""`` or ``"-"``: none; the
        whole tuple empty: not declared, as for a pass-through controller, whose commands are
        what it is wired to, or a copy that relabels its commands or states without giving
        their units).
    sample_period : float or None
        The one controller period [s] it works at (a controller designed or discretised for
        it); None: any. A problem at another ``controller_dt`` is refused.
    """

    name: str
    description: str
    params_type: type[Params]
    state_labels: tuple[str, ...]
    reference_labels: tuple[str, ...]
    reference_units: tuple[str, ...]
    command_labels: tuple[str, ...]
    init: Any
    step: Any
    measurement_labels: tuple[str, ...] = ()
    passthrough: bool = False
    output_labels: tuple[str, ...] = ()
    output_units: tuple[str, ...] = ()
    sample_period: float | None = None
    command_units: tuple[str, ...] = ()
    state_units: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if len(self.reference_units) != len(self.reference_labels):
            raise ValueError(f"{self.name}: reference_units has the wrong length")
        if self.sample_period is not None and not (math.isfinite(self.sample_period)
                                                   and self.sample_period > 0):
            raise ValueError(f"{self.name}: sample_period must be > 0 [s] or None")
        if len(self.output_units) != len(self.output_labels):
            raise ValueError(f"{self.name}: output_units has the wrong length")
        for kind, units, labels in (("command", self.command_units, self.command_labels),
                                    ("state", self.state_units, self.state_labels)):
            if units and len(units) != len(labels):
                # a copy relabelling its commands or states (dataclasses.replace) without
                # their units: undeclared, not wrong
                object.__setattr__(self, f"{kind}_units", ())

    @property
    def n_measurements(self) -> int:
        return len(self.measurement_labels)

    def signals(self) -> list[tuple[str, str, str]]:
        """Every declared signal as ``(kind, name, unit)``: states, references, measurements,
        commands (a pass-through controller's references and commands are named after what it
        is wired to, so it lists none).

        Returns
        -------
        list of tuple of str
        """
        states = self.state_units or ("",) * len(self.state_labels)
        rows = [("state", n, u) for n, u in zip(self.state_labels, states)]
        if not self.passthrough:
            rows += [("reference", n, u) for n, u in zip(self.reference_labels,
                                                          self.reference_units)]
        rows += [("measurement", n, "") for n in self.measurement_labels]
        if not self.passthrough:
            commands = self.command_units or ("",) * len(self.command_labels)
            rows += [("command", n, u) for n, u in zip(self.command_labels, commands)]
        rows += [("output", n, u) for n, u in zip(self.output_labels, self.output_units)]
        return rows

    @property
    def n_states(self) -> int:
        return len(self.state_labels)

    @property
    def n_references(self) -> int:
        return len(self.reference_labels)

    @property
    def n_commands(self) -> int:
        return len(self.command_labels)
