"""A file of draws: the ``[draws]`` table of a TOML file as sampling distributions.

``seahelm imo SHIP --monte-carlo N --draws FILE.toml`` draws the ship's parameters from it
(the distributions of a scenario's ``[batch.monte_carlo.draws]``: normal, uniform, lognormal,
truncnormal, validated by the scenario schema); errors name the key path in the file's words.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from ..errors import ParameterError

__all__ = ["read_draws"]


def read_draws(path: str | os.PathLike[str]) -> dict[str, Any]:
    """The ``[draws]`` table of a TOML file as sampling distributions, by parameter name
    (``N_r = {distribution = "normal", mean = -0.049, std = 0.0049}``; the distributions of a
    scenario's ``[batch.monte_carlo.draws]``). The names and units are checked against a ship
    where the draws are used (:func:`seahelm.analysis.imo.probability.monte_carlo_ships`).

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    dict of str to Distribution
        :mod:`seahelm.numerics.sampling` distributions.

    Raises
    ------
    ParameterError
        ``field="draws"``: not a TOML file, no ``[draws]`` table, a draw that is not a
        distribution (naming its key path, what it must be and the value).
    """
    import tomllib

    from pydantic import ValidationError

    from ..numerics.sampling import get_distribution
    from .schema import Distribution

    try:
        data = tomllib.loads(Path(path).read_text(encoding="utf-8-sig"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise ParameterError(f"not a TOML file ({exc})", field="draws") from None
    table = data.get("draws")
    if not isinstance(table, dict) or not table:
        raise ParameterError("needs a table [draws] of parameter = {distribution = ..., ...}",
                             field="draws")
    out = {}
    for key, spec in table.items():
        try:
            d = Distribution.model_validate(spec)
        except ValidationError as exc:
            raise ParameterError(_draws_error(key, exc), field="draws") from None
        params = {k: getattr(d, k) for k in ("mean", "std", "low", "high")
                  if getattr(d, k) is not None}
        out[key] = get_distribution(d.distribution, **params)
    return out


def _draws_error(key: str, exc: Any) -> str:
    """The first error of a ``[draws.KEY]`` table in the file's words: the key path, what it
    must be, the value (not pydantic's "Input should be a valid number")."""
    from .loading import _message
    from .schema import Distribution

    err = exc.errors()[0]
    loc = [str(p) for p in err["loc"]]
    where = ".".join(["draws", key, *loc])
    value = err.get("input")
    got = "" if isinstance(value, dict) else f", got {value!r}"
    kind = err["type"]
    if kind == "extra_forbidden":
        return (f"[{where}] is an unknown key; valid in [draws.{key}]: "
                f"{', '.join(Distribution.model_fields)}")
    if kind == "literal_error":
        return (f"[{where}] must be one of {err.get('ctx', {}).get('expected', '')}"
                .replace("'", "") + got)
    if kind in ("model_type", "model_attributes_type", "dict_type"):
        return (f"[{where}] must be a table {{distribution = ..., mean = ..., std = ...}}"
                f"{got}")
    if kind == "missing":
        return f"[{where}] is missing (a draw needs `distribution`)"
    return f"[{where}] {_message(err, '')}{got if kind != 'value_error' else ''}"
