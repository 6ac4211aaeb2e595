"""``[batch.monte_carlo] samples = "FILE.csv"``: Monte-Carlo draws given as a samples file.

A samples file (:mod:`seahelm.identification.samples_file`; e.g. the posterior of an identification,
``seahelm identify mmg --imo N --save-posterior FILE.csv``) holds one row per sample and one
column per drawn key (``vessel.params.<name>``, ``actuator.params.<name>``). In a scenario,
sample *i* takes row *i* of the file — in a grid, every grid point takes the same ``runs``
rows — and the section's ``draws`` and ``correlated`` draw any other keys as usual. The file
is found relative to the scenario file; ``runs`` may not exceed its rows. Its keys are drawn
keys like any other: they are checked, stored with the results (``distribution =
"samples"``) and, in an ``imo`` scenario, may not be what the members share.

:func:`drawn_kinds` lists every drawn key with its kind (the one list the scenario code uses);
:func:`samples_draws` gives the rows of sample indices.
"""

from __future__ import annotations

import functools
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ParameterError
from .errors import at_key

__all__ = ["drawn_kinds", "samples_draws", "samples_file"]

_KEY = "batch.monte_carlo.samples"


@functools.lru_cache(maxsize=8)
def _read(path: str, mtime_ns: int, size: int) -> Any:
    from ..identification.samples_file import read_samples

    return read_samples(path)


def samples_file(mc: Any, source: str) -> Any:
    """The samples file of ``[batch.monte_carlo]`` (read once per version of the file).

    Parameters
    ----------
    mc : MonteCarloSection
        With ``samples`` set.
    source : str
        The scenario file (the samples file is relative to its folder), or ``"<string>"``.

    Returns
    -------
    SamplesFile

    Raises
    ------
    ScenarioError
        At ``batch.monte_carlo.samples``: a missing or invalid file, fewer rows than ``runs``.
    """
    path = Path(mc.samples)
    if not path.is_absolute() and Path(source).is_file():
        path = Path(source).parent / path
    try:
        stat = path.stat()
    except OSError:
        raise at_key(source, _KEY, f"no samples file {str(path)!r}") from None
    try:
        table = _read(str(path), stat.st_mtime_ns, stat.st_size)
    except ParameterError as exc:
        raise at_key(source, _KEY, str(exc)) from None
    if table.n_samples < mc.runs:
        raise at_key(source, _KEY, f"{path} holds {table.n_samples} samples, fewer than "
                                   f"`runs` = {mc.runs}")
    return table


def drawn_kinds(mc: Any, source: str) -> dict[str, str]:
    """Every key ``[batch.monte_carlo]`` draws, with how: a distribution's name,
    ``correlated-normal`` or ``samples``.

    Parameters
    ----------
    mc : MonteCarloSection or None
    source : str
        The scenario file.

    Returns
    -------
    dict of key path to str
        Empty for None.

    Raises
    ------
    ScenarioError
        A key of the samples file that ``draws`` or ``correlated`` draws too.
    """
    if mc is None:
        return {}
    kinds = {key: dist.distribution for key, dist in mc.draws.items()}
    kinds.update({key: "correlated-normal" for block in mc.correlated for key in block.keys})
    if mc.samples is not None:
        for key in samples_file(mc, source).keys:
            if key in kinds:
                raise at_key(source, _KEY, f"`{key}` is a column of the samples file and drawn "
                                           "in `draws`/`correlated` too: draw it once")
            kinds[key] = "samples"
    return kinds


def samples_draws(mc: Any, indices: np.ndarray, source: str) -> dict[str, np.ndarray]:
    """The samples file's values of the flat sample indices (grid point × ``runs`` + sample:
    row = index mod ``runs``).

    Parameters
    ----------
    mc : MonteCarloSection
    indices : ndarray of int
    source : str
        The scenario file.

    Returns
    -------
    dict of key path to ndarray, shape (len(indices),)
        Empty when the section has no samples file.
    """
    if mc.samples is None:
        return {}
    table = samples_file(mc, source)
    rows = np.asarray(indices, dtype=np.int64) % int(mc.runs)
    return {key: table.values[rows, j].copy() for j, key in enumerate(table.keys)}
