"""A manoeuvre's validated grid and batch, made once per distinct request.

A manoeuvre call resolves its ship, finds the steady approach, checks the rudder angles and
timing, builds the grid (:class:`~seahelm.analysis.maneuvers.common.Plan`) and validates the
batch's :class:`~seahelm.simulation.problem.Problem` before anything runs: for one KVLCC2 turning
circle that was a third of its Python calls (issue 46). All of it is derived from the request
alone, so a request seen before takes its plan and problem from here and runs them again (the
simulation and the metrics are computed at every call; no result is kept).

A request is kept only when it is made of a ship given as a :class:`~seahelm.ships.Ship` object
or a catalog name (the catalog's object: frozen, and held here, so it cannot be replaced under
the same key) and plain numbers (``int``, ``float``, ``None`` and tuples of them); anything else
(a ship file, arrays, lists, conditions) is prepared afresh at every call. A plan that issued a
:class:`~seahelm.errors.ValidityRangeWarning` is not kept (each call warns as before), nor is one
whose preparation raised. The key holds whether the loop is compiled
(:func:`~seahelm.simulation.problem.jit_enabled`: ``SEAHELM_DISABLE_JIT`` may change between
calls). At most :data:`KEPT` requests are kept, the least recently used dropped first.
"""

from __future__ import annotations

from typing import Any

from ...ships import CATALOG, Ship
from ...simulation.problem import jit_enabled

__all__ = ["KEPT"]

#: Requests kept (the most recently used).
KEPT = 32

_NUMBERS = (int, float, type(None))
#: key -> (the ship object the key's id is of, what was prepared)
_READY: dict[tuple[Any, ...], tuple[Any, Any]] = {}


def request_key(kind: str, ship: Any, *values: Any) -> tuple[tuple[Any, ...], Any] | None:
    """The key of a request of manoeuvre ``kind`` and the ship object it names, or None when
    the request is not one to keep (module docstring)."""
    if type(ship) is Ship:
        source = ship
    elif type(ship) is str:
        try:  # (the catalog's object now: a ship registered again is another one)
            source = CATALOG[ship]
        except KeyError:  # (a ship file's path, or no ship: prepared afresh)
            return None
    else:
        return None
    # (each value's type with it: 1 and 1.0, equal keys, are prepared alike today, but need
    # not be; a tuple's members' types too)
    key: list[Any] = [kind, id(source), jit_enabled()]
    for value in values:
        kind_ = type(value)
        if kind_ is tuple:
            types = tuple([type(v) for v in value])
            for t in types:
                if t not in _NUMBERS:
                    return None
            key.append((kind_, types, value))
        elif kind_ in _NUMBERS:
            key.append((kind_, value))
        else:
            return None
    return tuple(key), source


def ready(key: tuple[tuple[Any, ...], Any] | None) -> Any:
    """What was prepared for ``key`` (:func:`request_key`), or None."""
    if key is None:
        return None
    # (taken out and put back: now the most recently used; another thread asking for it at
    # the same moment finds nothing and prepares it afresh)
    found = _READY.pop(key[0], None)
    if found is None or found[0] is not key[1]:
        return None
    _READY[key[0]] = found
    return found[1]


def keep(key: tuple[tuple[Any, ...], Any] | None, prepared: Any) -> None:
    """Keep what was prepared for ``key`` (nothing without a key), dropping the least
    recently used beyond :data:`KEPT`."""
    if key is None:
        return
    _READY.pop(key[0], None)
    while len(_READY) >= KEPT:
        try:
            _READY.pop(next(iter(_READY)), None)
        except (StopIteration, RuntimeError):  # (emptied or changed by another thread)
            break
    _READY[key[0]] = (key[1], prepared)


def clear() -> None:
    """Forget every prepared request."""
    _READY.clear()
