"""Criteria over the residuals of a fit, as objects in a registry.

Romanov & Chirkova's eq. (5) searches (a, b, c) for the minimum of a criterion of the residuals
N_i = a ω_i² + b ω_i + α_i (1 + c ω_i) of the steady turns. A criterion must be bounded below
to have a minimum: Σ N_i² (:data:`SQUARED`, what least squares minimises) and Σ|N_i|
(:data:`ABSOLUTE`, robust to one bad turn) are; the plain sum Σ N_i printed in the paper is not
(it is linear in the coefficients) and lives with the paper's reproduction,
:data:`seahelm.studies.romanov_chirkova.PRINTED_EQ5`. Any :class:`Criterion` can be passed to
:func:`seahelm.identification.reduced.fitting.fit_brute_force`.
"""

from __future__ import annotations

import abc
from collections.abc import Mapping
from types import MappingProxyType
from typing import ClassVar

import numpy as np

__all__ = ["Criterion", "SQUARED", "ABSOLUTE", "CRITERIA"]


class Criterion(abc.ABC):
    """A criterion over residuals N_i, to be minimised over the coefficients."""

    #: Registry name.
    name: ClassVar[str]

    @abc.abstractmethod
    def __call__(self, residuals: np.ndarray) -> np.ndarray:
        """The criterion of the residuals N_i (reduced over the last axis)."""

    def __repr__(self) -> str:
        return f"<criterion {self.name!r}>"


class _Squared(Criterion):
    name = "squared"

    def __call__(self, residuals: np.ndarray) -> np.ndarray:
        return np.sum(residuals * residuals, axis=-1)


class _Absolute(Criterion):
    name = "absolute"

    def __call__(self, residuals: np.ndarray) -> np.ndarray:
        return np.sum(np.abs(residuals), axis=-1)


#: Σ N_i²: what least squares minimises (eq. (5) corrected).
SQUARED: Criterion = _Squared()
#: Σ |N_i|: the other correction of eq. (5), less sensitive to one bad turn.
ABSOLUTE: Criterion = _Absolute()

#: The criteria by name: ``"squared"`` and ``"absolute"``.
CRITERIA: Mapping[str, Criterion] = MappingProxyType({c.name: c for c in (SQUARED, ABSOLUTE)})
