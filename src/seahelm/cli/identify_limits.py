"""What ``seahelm identify nomoto`` refuses before any work: more records than one fit takes,
and more bootstrap refits than are worth their time (each is a whole output-error fit)."""
from __future__ import annotations

from typing import Any

__all__ = ["MAX_NOMOTO_RECORDS", "check_record_count", "check_bootstrap"]


#: The most records ``identify nomoto`` fits together. The output-error fit estimates the
#: model's parameters and each record's initial state (2 or 3 unknowns a record) with one engine
#: run per record at every evaluation, so its cost grows with the square of the records: 20
#: records of 10 minutes took some 8 s (warm kernel), 200 runs of a Monte-Carlo result over
#: 180 s without a word. One model fitted to many runs of different ships (a Monte-Carlo
#: result's draws) is no identification either.
MAX_NOMOTO_RECORDS = 20


def check_record_count(records: Any, order: int) -> None:
    """Refuse more than :data:`MAX_NOMOTO_RECORDS` records, naming LOG, the count and the
    unknowns.

    Parameters
    ----------
    records : sequence of ManoeuvreRecord
        The records read from LOG.
    order : int
        Nomoto's order (1 or 2).
    """
    from ..errors import ParameterError

    n = len(records)
    if n <= MAX_NOMOTO_RECORDS:
        return
    unknowns = (3 if order == 1 else 5) + (2 if order == 1 else 3) * n
    raise ParameterError(
        f"`LOG`: {n} records (a result file gives one per run) is more than the "
        f"{MAX_NOMOTO_RECORDS} one Nomoto fit takes: {unknowns} unknowns (each record's initial "
        "state) and one engine run per record at every step of the fit, which takes minutes; "
        "one model fitted to the runs of a Monte-Carlo result (different ships) is no "
        f"identification: fit the records of one ship, at most {MAX_NOMOTO_RECORDS} at a time")


def check_bootstrap(bootstrap: int) -> None:
    """``--bootstrap`` at most :data:`~seahelm.identification.nomoto_fit.MAX_BOOTSTRAP`, refused
    before any work with the time it would take.

    Parameters
    ----------
    bootstrap : int
        ``--bootstrap``: the number of refits.
    """
    from ..identification.nomoto_fit import MAX_BOOTSTRAP
    from ..errors import ParameterError

    if bootstrap > MAX_BOOTSTRAP:
        raise ParameterError(
            f"`--bootstrap` must be in [0, {MAX_BOOTSTRAP}], got {bootstrap}: each refit is a "
            f"whole output-error fit (about 0.5 s for a 600-sample record), so {bootstrap} "
            f"would take about {bootstrap * 0.5 / 3600:.3g} h; percentile intervals need about "
            "1000-2000 (Efron & Tibshirani 1993)")
