"""Solved steady approaches kept by (model, parameter set, speed): :class:`ApproachCache`.

An object that owns its entries (a bounded least-recently-used table), not module-level
dictionaries: a manoeuvre or a study may pass its own (``cache=``), and :data:`APPROACHES` is
the one the manoeuvres share by default (a Monte-Carlo study's 10⁴ ships are looked up three
or four times, once per manoeuvre). Not a ``functools.lru_cache``: the approaches a batch
misses are solved together in one vectorised solve
(:func:`~seahelm.analysis.equilibria.batch_equilibrium.approach_states`), which a per-key cache
cannot do. (Before issue 47: ``_MEMO``, ``_KEYS`` and ``MEMO_SIZE`` in
``analysis/maneuvers/ships.py``.)
"""

from __future__ import annotations

import collections
from collections.abc import Sequence
from typing import Any

import numpy as np

from ...errors import ParameterError
from ...parameters import Params
from ...vessels.base import VesselModel
from .batch_equilibrium import approach_states
from .approach import Approach
from .plant import EquilibriumError

__all__ = ["ApproachCache", "APPROACHES", "steady_approaches", "steady_approach",
           "clear_approaches"]


class _Key:
    """A cache key (model, parameter set, speed) hashed once: a parameter set's hash is that of
    the tuple of all its fields (some 10 µs), and a study of 10,000 samples looked each key up
    three times."""

    __slots__ = ("key", "hash")

    def __init__(self, key: tuple[Any, ...]) -> None:
        self.key = key
        self.hash = hash(key)

    def __hash__(self) -> int:
        return self.hash

    def __eq__(self, other: object) -> bool:
        return self is other or (isinstance(other, _Key) and self.hash == other.hash
                                 and self.key == other.key)


class ApproachCache:
    """Trimmed straight approaches by (model, parameter set, speed), least recently used out.

    Parameter sets are frozen, so the equilibrium of a ship at a speed is computed once while
    it is here. A failure is not kept.

    Parameters
    ----------
    size : int, optional
        Most approaches kept (default 512).
    """

    def __init__(self, size: int = 512) -> None:
        if isinstance(size, bool) or not isinstance(size, int) or size < 1:
            raise ParameterError(f"must be a whole number >= 1, got {size!r}", field="size",
                                 value=size)
        self.size = size
        self._entries: collections.OrderedDict[_Key, Approach] = collections.OrderedDict()
        # the keys by the identity of their model and parameter set (and the speed): a ship
        # looked up before finds its key without hashing its parameter set again; each key
        # holds its model and parameter set, so their ids stay theirs while it is here
        self._keys: collections.OrderedDict[tuple[int, int, float], _Key] = \
            collections.OrderedDict()

    def __len__(self) -> int:
        return len(self._entries)

    def clear(self) -> None:
        """Forget every approach (a benchmark times their computation)."""
        self._entries.clear()
        self._keys.clear()

    def _key(self, model: Any, params: Any, speed: float) -> _Key:
        ident = (id(model), id(params), speed)
        key = self._keys.get(ident)
        if key is not None and key.key[0] is model and key.key[1] is params:
            return key
        key = _Key((model, params, speed))
        self._keys[ident] = key
        if len(self._keys) > 4 * self.size:
            self._keys.popitem(last=False)
        return key

    def solve(self, model: VesselModel, params: Sequence[Params],
              speeds: Sequence[float]) -> list[Approach | str]:
        """The trimmed approaches of (parameter set, speed) pairs, those not kept solved in one
        batch (:func:`~seahelm.analysis.equilibria.batch_equilibrium.approach_states`).

        Parameters
        ----------
        model : VesselModel
            The model of every parameter set.
        params : sequence of Params
            One parameter set per pair.
        speeds : sequence of float
            Approach speed U_0 [m/s] per pair.

        Returns
        -------
        list of Approach or str
            Per pair, the approach, or the reason it was not found.
        """
        out: list[Approach | str | None] = [None] * len(params)
        keys = [self._key(model, p, float(U)) for p, U in zip(params, speeds)]
        missing = []
        for k, key in enumerate(keys):
            hit = self._entries.get(key)
            if hit is None:
                missing.append(k)
            else:
                self._entries.move_to_end(key)
                out[k] = hit
        if missing:
            todo: dict[_Key, list[int]] = {}  # (one solve per distinct pair)
            for k in missing:
                todo.setdefault(keys[k], []).append(k)
            solved = approach_states(model, [key.key[1] for key in todo],
                                     np.array([key.key[2] for key in todo]), trim=True)
            has_rps = "propeller_rps" in model.input_labels
            # (only the last `size` found can stay: the others are not put in)
            found = np.flatnonzero(np.asarray(solved.status) == 0)
            kept = int(found[-self.size]) if found.size > self.size else -1
            for m, (key, ks) in enumerate(todo.items()):
                if solved.status[m] != 0:
                    for k in ks:
                        out[k] = solved.message[m]
                    continue
                a = solved.approach(m, key.key[2], has_rps=has_rps)
                if m >= kept:
                    self._entries[key] = a
                for k in ks:
                    out[k] = a
            while len(self._entries) > self.size:
                self._entries.popitem(last=False)
        return out  # type: ignore[return-value]


#: The cache the manoeuvres share by default (512 approaches).
APPROACHES = ApproachCache(512)


def steady_approaches(model: VesselModel, params: Sequence[Params], speeds: Sequence[float],
                      *, cache: ApproachCache | None = None) -> list[Approach | str]:
    """The trimmed straight approaches of many (parameter set, speed) pairs of one model.

    Those not in the cache are solved in one batch
    (:func:`~seahelm.analysis.equilibria.batch_equilibrium.approach_states`, trim rudder included);
    the results equal :func:`~seahelm.analysis.equilibria.equilibrium.approach_state` with
    ``trim=True`` to the solvers' tolerance.

    Parameters
    ----------
    model : VesselModel
        The model of every parameter set.
    params : sequence of Params
        One parameter set per pair.
    speeds : sequence of float
        Approach speed U_0 [m/s] per pair.
    cache : ApproachCache, optional
        Where solved approaches are kept (default :data:`APPROACHES`).

    Returns
    -------
    list of Approach or str
        Per pair, the approach, or the reason it was not found (a failure is not kept).

    Raises
    ------
    ParameterError
        If a speed is not > 0 or differs from a perturbation model's nominal speed.
    """
    return (APPROACHES if cache is None else cache).solve(model, params, speeds)


def steady_approach(model: VesselModel, params: Params, speed: float, *,
                    cache: ApproachCache | None = None) -> Approach:
    """The trimmed straight approach of
    :func:`~seahelm.analysis.equilibria.equilibrium.approach_state`
    (kept in ``cache``, default :data:`APPROACHES`; :func:`steady_approaches`).

    Parameters
    ----------
    model : VesselModel
        The model.
    params : Params
        The parameter set.
    speed : float
        Approach speed U_0 [m/s].
    cache : ApproachCache, optional
        Where solved approaches are kept (default :data:`APPROACHES`).

    Returns
    -------
    Approach

    Raises
    ------
    EquilibriumError
        If the approach is not found (its reason as the message).
    """
    a = steady_approaches(model, [params], [float(speed)], cache=cache)[0]
    if isinstance(a, str):
        raise EquilibriumError(a)
    return a


def clear_approaches() -> None:
    """Forget the approaches of the shared cache :data:`APPROACHES` (a benchmark times their
    computation)."""
    APPROACHES.clear()
