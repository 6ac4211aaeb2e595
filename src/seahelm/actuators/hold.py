"""First-order hold: recorded inputs replayed as the straight lines between their samples.

A manoeuvre record logs the inputs the ship saw — the rudder angle, the propeller rps — at its
samples. To drive a model with them (the output-error fits of
:mod:`seahelm.identification.nomoto_fit` and :mod:`seahelm.identification.mmg_fit`) the signal between two
samples is taken as the straight line through them (a first-order hold, Franklin, Powell &
Workman, *Digital Control of Dynamic Systems*, 3rd ed., 1998, §6.3.2 "triangle hold").

The engine holds a controller's commands over each step (a zero-order hold, as a digital
controller issues them). A recorded rudder angle fed through the ``direct`` actuator as such a
command is held at δ(t_k) over [t_k, t_k + Δt]: wherever the rudder moves, the model sees it
half a step late (0.05 s at 10 Hz). That lag biased the MMG output-error fit of noiseless
KVLCC2 zig-zags and a turning circle by 1–2 % in Y'_v, Y'_r, N'_v, N'_r
(tests/test_analysis_mmg_fit.py measures it).

Here every input is a state of the actuator whose command is its rate: the slope
(x_{k+1} − x_k)/Δt of the sampled signal, held over [t_k, t_k + Δt], and the closed-form step
x + h ẋ (``advance``) gives every stage of the integrator the interpolated value exactly.
:func:`hold_actuator` makes one for any set of model inputs (the MMG model's rudder angle and
propeller rps, the Nomoto models' rudder angle); :func:`hold_reference` turns samples on the
step grid into its initial state and its reference (the slopes).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
from numba import njit

from ..errors import ParameterError
from ..parameters import Params
from .base import Actuator

__all__ = ["HoldParams", "hold_actuator", "hold_reference"]

#: The unit of a channel's rate, by the channel's unit.
_RATE_UNITS = {"rad": "rad/s", "1/s": "1/s²", "m": "m/s", "m/s": "m/s²"}


@dataclass(frozen=True, kw_only=True)
class HoldParams(Params):
    """The first-order hold has no parameters."""


@njit(cache=True)
def hold_rhs(t, xa, ca, p, dxa):  # pragma: no cover - compiled
    """ẋ_j = the held slope of channel j."""
    for j in range(xa.shape[0]):
        dxa[j] = ca[j]


@njit(cache=True)
def hold_advance(h, xa, ca, p, out):  # pragma: no cover - compiled
    """x_j + h · slope_j: the straight line, exactly."""
    for j in range(xa.shape[0]):
        out[j] = xa[j] + h * ca[j]


@njit(cache=True)
def hold_output(xa, ca, p, ya):  # pragma: no cover - compiled
    for j in range(xa.shape[0]):
        ya[j] = xa[j]


@functools.lru_cache(maxsize=None)
def hold_actuator(labels: tuple[str, ...], units: tuple[str, ...]) -> Actuator:
    """The first-order hold of the model inputs ``labels`` (one object per set of labels).

    Parameters
    ----------
    labels : tuple of str
        The model inputs it feeds (e.g. ``("rudder_angle", "propeller_rps")``); its command
        channels are ``<label>_rate``.
    units : tuple of str
        Their units (e.g. ``("rad", "1/s")``).

    Returns
    -------
    Actuator
        Not registered: it is the record replay of the identification fits, not a piece of
        steering gear.
    """
    labels, units = tuple(labels), tuple(units)
    if not labels or len(units) != len(labels):
        raise ParameterError(f"must be one unit per label, got labels {labels} and units "
                             f"{units}", field="units")
    return Actuator(
        name="hold[" + ",".join(labels) + "]",
        description="first-order hold: recorded inputs replayed as the straight lines "
                    "between their samples",
        params_type=HoldParams,
        state_labels=labels,
        state_units=units,
        command_labels=tuple(f"{lab}_rate" for lab in labels),
        command_units=tuple(_RATE_UNITS.get(u, f"({u})/s") for u in units),
        rhs=hold_rhs,
        output=hold_output,
        advance=hold_advance,
        output_labels=labels,
        output_units=units,
    )


def hold_reference(samples: np.ndarray, dt: float) -> tuple[np.ndarray, np.ndarray]:
    """The initial state and reference of :func:`hold_actuator` for samples on the step grid.

    Parameters
    ----------
    samples : ndarray, shape (steps + 1, channels)
        The inputs at t_k = t_0 + k Δt, k = 0 … steps (e.g. the record interpolated onto the
        grid).
    dt : float
        The step Δt [s].

    Returns
    -------
    x0 : ndarray, shape (channels,)
        The inputs at t_0 (the actuator's initial state).
    reference : ndarray, shape (steps + 1, channels)
        The slopes (x_{k+1} − x_k)/Δt held over each step (the last row, after the last step,
        repeats the one before it).
    """
    x = np.asarray(samples, dtype=float)
    if x.ndim != 2 or x.shape[0] < 2:
        raise ParameterError(f"must have shape (steps + 1 >= 2, channels), got {x.shape}",
                             field="samples")
    if not dt > 0:
        raise ParameterError(f"must be > 0 [s], got {dt!r}", field="dt")
    slopes = np.diff(x, axis=0) / dt
    return x[0].copy(), np.concatenate([slopes, slopes[-1:]], axis=0)
