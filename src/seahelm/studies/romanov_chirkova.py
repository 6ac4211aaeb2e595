"""Romanov & Chirkova: identifying the steering model from three steady turns — the paper's
reproduction.

The reusable parts are components: Voitkunsky's steering model (eq. (1)) in
:mod:`seahelm.vessels.voitkunsky`, its exact steady turns and the reduced coefficients a, b, c
(and the α² coefficient d the paper drops) in closed form in
:mod:`seahelm.identification.reduced.turns`, the forms of the reduced equation (eq. (4) is the
form ``"paper"``) in :mod:`seahelm.identification.reduced.forms`, the least-squares, robust and
brute-force fits (eq. (5) with a proper criterion) in :mod:`seahelm.identification.reduced.fitting`, the
steady segments of a log in :mod:`seahelm.identification.reduced.segments`. The paper gives no
coefficient values (no year is printed on it either, hence the module name). This module holds
the paper's procedure on a model ship:

* the criterion of eq. (5) as printed next to the proper ones of
  :mod:`seahelm.identification.reduced.criteria`, as objects: registry :data:`CRITERIA` with
  :data:`PRINTED_EQ5` (``"printed"``, the plain sum Σ N_i), ``"squared"`` (Σ N_i², the default
  of the fits) and ``"absolute"`` (Σ|N_i|); :func:`eq5_criterion` evaluates one, and
  :func:`~seahelm.identification.reduced.fitting.fit_brute_force` takes any of them (with the printed
  one it ends on the search box's boundary);
* :func:`three_turn_study` — three steady turns of a Voitkunsky ship, eq. (4) fitted to them,
  the closed-form coefficients of the branch and the prediction of held-out turns.

Errata (see the seeds guide): the residual of eq. (5) must be squared (or absolute) to be a
criterion — the plain sum is linear in (a, b, c) and unbounded below, so a brute-force search
on it returns a corner of the search box; eq. (4) is linear in (a, b, c), so linear least
squares solves it exactly; the elimination of β is exact only on one branch of β|β| and adds
d α² (d = c²/4a), which eq. (4) drops.

References
----------
Romanov, A. V., Chirkova, M. M. Transforming the mathematical model of ship manoeuvrability to
minimise the time to estimate its coefficients (in Russian), VGAVT. Eq. (1)-(5).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from types import MappingProxyType
from typing import Any, NamedTuple

import numpy as np

from ..errors import ParameterError
from ..identification.reduced.criteria import ABSOLUTE, SQUARED, Criterion
from ..identification.reduced.fitting import fit_lsq
from ..identification.reduced.forms import SteadyTurnFit
from ..identification.reduced.turns import (
    ReducedCoefficients,
    reduced_coefficients,
    stable_steady_turn,
)
from ..registry import lookup
from ..vessels.voitkunsky import MARINER_VOITKUNSKY, VoitkunskyParams

__all__ = [
    "Criterion",
    "PRINTED_EQ5",
    "SQUARED",
    "ABSOLUTE",
    "CRITERIA",
    "eq5_residuals",
    "eq5_criterion",
    "ThreeTurnStudy",
    "three_turn_study",
]


# ---------------------------------------------------------------------------------------------
# The criterion of eq. (5)
# ---------------------------------------------------------------------------------------------
class _PlainSum(Criterion):
    name = "printed"

    def __call__(self, residuals: np.ndarray) -> np.ndarray:
        return np.sum(residuals, axis=-1)


#: Eq. (5) as printed: N = Σ N_i. Not a criterion: linear in (a, b, c), unbounded below.
PRINTED_EQ5: Criterion = _PlainSum()
#: The criteria of eq. (5) by name: ``"printed"``, ``"squared"``, ``"absolute"``.
CRITERIA: Mapping[str, Criterion] = MappingProxyType(
    {c.name: c for c in (PRINTED_EQ5, SQUARED, ABSOLUTE)})


def eq5_residuals(a: Any, b: Any, c: Any, yaw_rate: Any, rudder_angle: Any) -> np.ndarray:
    """N_i = a ω_i² + b ω_i + α_i (1 + c ω_i) of eq. (5).

    Parameters
    ----------
    a, b, c : float or array_like
        Coefficients of eq. (4) [s²/rad], [s], [s/rad]; arrays broadcast against each other
        (a grid of candidates) and get a trailing axis for the turns.
    yaw_rate : array_like, shape (n,)
        Steady yaw rates ω_i [rad/s].
    rudder_angle : array_like, shape (n,)
        Rudder angles α_i [rad].

    Returns
    -------
    numpy.ndarray
        N_i [rad], shape ``broadcast(a, b, c).shape + (n,)``.
    """
    w = np.asarray(yaw_rate, dtype=float)
    al = np.asarray(rudder_angle, dtype=float)
    if w.shape != al.shape or w.ndim != 1:
        raise ParameterError(f"`yaw_rate` and `rudder_angle` must be 1-D of one length, got "
                             f"{w.shape} and {al.shape}")
    a, b, c = (np.asarray(x, dtype=float)[..., None] for x in (a, b, c))
    return a * w**2 + b * w + al * (1.0 + c * w)


def eq5_criterion(a: Any, b: Any, c: Any, yaw_rate: Any, rudder_angle: Any,
                  criterion: str | Criterion = "squared") -> np.ndarray | float:
    """The criterion of eq. (5) for coefficients (a, b, c) and steady turns (ω_i, α_i).

    Parameters
    ----------
    a, b, c : float or array_like
        Coefficients of eq. (4) (see :func:`eq5_residuals`).
    yaw_rate, rudder_angle : array_like, shape (n,)
        Steady turns ω_i [rad/s], α_i [rad].
    criterion : str or Criterion, optional
        A name of :data:`CRITERIA` (default ``"squared"``) or a criterion;
        ``"printed"`` (:data:`PRINTED_EQ5`) is the paper's plain sum.

    Returns
    -------
    float or numpy.ndarray
        The criterion, shape ``broadcast(a, b, c).shape``.

    Raises
    ------
    ParameterError
        For an unknown criterion (the message lists the valid ones) or bad turns.
    """
    crit = lookup("eq. (5) criterion", CRITERIA, criterion, Criterion, error=ParameterError)
    out = crit(eq5_residuals(a, b, c, yaw_rate, rudder_angle))
    return float(out) if np.ndim(out) == 0 else out


# ---------------------------------------------------------------------------------------------
# The paper's procedure on a model ship
# ---------------------------------------------------------------------------------------------
class ThreeTurnStudy(NamedTuple):
    """Eq. (4) identified from three steady turns of a Voitkunsky ship."""

    #: Rudder angles α_i of the three turns [rad].
    rudder_angle: np.ndarray
    #: Their steady yaw rates ω_i [rad/s] (exact, from the model).
    yaw_rate: np.ndarray
    #: Eq. (4) fitted to the three turns (exactly determined).
    fit: SteadyTurnFit
    #: The closed-form a, b, c, d of the branch the turns lie on.
    closed_form: ReducedCoefficients
    #: Held-out rudder angles [rad].
    held_out_rudder_angle: np.ndarray
    #: Their exact steady yaw rates [rad/s].
    held_out_yaw_rate: np.ndarray
    #: The yaw rates eq. (4) predicts for them [rad/s].
    predicted_yaw_rate: np.ndarray

    @property
    def max_relative_error(self) -> float:
        """Largest |predicted/exact − 1| over the held-out turns [-]."""
        return float(np.max(np.abs(self.predicted_yaw_rate / self.held_out_yaw_rate - 1.0)))


def three_turn_study(params: VoitkunskyParams = MARINER_VOITKUNSKY,
                     rudder_angles: Sequence[float] = (math.radians(5.0), math.radians(15.0),
                                                       math.radians(25.0)),
                     held_out: Sequence[float] = (math.radians(10.0), math.radians(20.0),
                                                  math.radians(30.0))) -> ThreeTurnStudy:
    """The paper's procedure: three steady turns, eq. (4) through them, prediction of others.

    The turns are the model's exact stable steady turns (no simulation, no noise); the branch
    of the closed form is the sign of their drift angle.

    Parameters
    ----------
    params : VoitkunskyParams, optional
        The ship (default: the catalog's Mariner set ``mariner-voitkunsky``).
    rudder_angles : sequence of float, optional
        The three rudder angles [rad] (default 5°, 15°, 25°).
    held_out : sequence of float, optional
        Rudder angles [rad] of the turns to predict (default 10°, 20°, 30°).

    Returns
    -------
    ThreeTurnStudy

    Raises
    ------
    ParameterError
        If not exactly three rudder angles are given, a turn has no unique stable steady
        state, or the turns lie on both branches of β|β|.
    """
    al = np.asarray(rudder_angles, dtype=float)
    if al.shape != (3,):
        raise ParameterError(f"`rudder_angles` must be three angles [rad], got {rudder_angles!r}")
    turns = [stable_steady_turn(params, float(a)) for a in al]
    signs = {int(np.sign(t.drift_angle)) for t in turns}
    if len(signs) != 1 or 0 in signs:
        raise ParameterError("the three turns must have drift angles of one sign (one branch "
                             "of β|β|, where eq. (4) holds)")
    w = np.array([t.yaw_rate for t in turns])
    fit = fit_lsq(w, al, form="paper")
    ho = np.asarray(held_out, dtype=float)
    truth = np.array([stable_steady_turn(params, float(a)).yaw_rate for a in ho])
    pred, _ = fit.predict_yaw_rate(ho)
    return ThreeTurnStudy(al, w, fit, reduced_coefficients(params, signs.pop()), ho, truth,
                          np.asarray(pred, dtype=float))
