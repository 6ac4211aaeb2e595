"""``seahelm report RESULT...``: one self-contained HTML report of a result file (or of
several, side by side on one page).

RESULT is ``result.nc`` of ``seahelm run``/``demo``, or a manoeuvre's ``*-runs.nc`` /
``*-metrics.nc`` (``seahelm maneuver``; with ``imo-report.json`` beside them, the files of
``seahelm imo --out`` and the IMO criteria), ``imo-probabilities.nc`` (``seahelm imo
--monte-carlo --out``: the pass probabilities), ``seakeeping.nc`` (``seahelm seakeeping
--out``: the polar diagrams and the largest responses per speed), ``replay.nc`` (``seahelm
replay --out``: the measured and simulated metrics and tracks), ``encounters.nc`` (``seahelm
encounter --out``: outcomes by COLREG situation, tracks, CPA, outcome rose), or a sweep store (``seahelm
sweep``; of an ``imo`` Monte-Carlo scenario, with the pass probabilities). The page
(:mod:`seahelm.report`) holds plotly.js and all the data, so it opens with no network. ``-o``
is checked before anything is read; the file is written atomically; without it the page is
``report.html`` beside RESULT (the name ``seahelm run --report`` and ``demo`` give it). Several result files
(not sweep stores, ``imo-probabilities.nc``, ``seakeeping.nc``, ``replay.nc`` or
``encounters.nc``, which are
reported alone) give one page with
each file's runs named by the file (:func:`seahelm.report.combined_report_data`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer
from rich.markup import escape

from ..errors import ParameterError
from ._common import ForceFlag, JsonFlag, console, handle_errors, input_file, output_file, print_json
from ._outputs import REPORT_NAME

__all__ = ["report", "default_report_path", "REPORT_NAME"]


#: What ``seahelm report`` of several results writes without ``-o`` (beside the first).
COMBINED_NAME = "combined-report.html"


def default_report_path(result: Path) -> Path:
    """Where ``seahelm report RESULT`` writes without ``-o``: :data:`REPORT_NAME` beside
    RESULT (a sweep store: beside the store)."""
    return result.parent / REPORT_NAME


@handle_errors
def report(
    results: Annotated[list[Path], typer.Argument(
        metavar="RESULT...", help=(
            "Result file written by seahelm (NetCDF): result.nc of `seahelm run`/`demo`, a "
            "manoeuvre's *-runs.nc or *-metrics.nc, imo-probabilities.nc of `seahelm imo "
            "--monte-carlo`, seakeeping.nc of `seahelm seakeeping`, replay.nc of `seahelm "
            "replay`, encounters.nc of `seahelm encounter`; or a sweep store of "
            "`seahelm sweep`. Several result files: one "
            "page with each file's runs side by side."))],
    out: Annotated[Path | None, typer.Option(
        "-o", "--out", help=f"HTML file to write (default: {REPORT_NAME} beside RESULT, the "
        f"name `seahelm run --report` gives it; for several, {COMBINED_NAME} beside the "
        "first).")] = None,
    force: ForceFlag = False,
    json_out: JsonFlag = False,
) -> None:
    """Write an HTML report of result files: metadata, status, metrics, interactive plots."""
    reads = []
    for result in results:
        if result.is_dir() or result.suffix == ".zarr":  # a sweep store (a directory)
            if not result.is_dir():
                raise ParameterError(f"`RESULT`: no such sweep store: {result}")
        else:
            input_file("RESULT", result)
        from ..report.inputs import report_inputs

        reads.extend(report_inputs(result))
    # never over what the report reads: the results, their companion files, a store's insides
    default = (default_report_path(results[0]) if len(results) == 1
               else results[0].parent / COMBINED_NAME)
    target = output_file("--out", out or default, "html", reads=reads, force=force)
    if target.suffix.lower() not in (".html", ".htm"):  # (a browser opens it by its suffix)
        raise ParameterError(f"`--out` must name an .html file, got {str(target)!r}"
                             + (f" (suffix {target.suffix!r})" if target.suffix
                                else " (no suffix)"))
    from ..report import combined_report_data, write_report

    summary = write_report(results[0] if len(results) == 1 else combined_report_data(results),
                           target, option="--out", force_word="--force")
    if json_out:
        print_json({"file": str(results[0]), "files": [str(r) for r in results],
                    "report": str(summary.path), "bytes": summary.bytes,
                    "title": summary.title, "n_runs": summary.n_runs,
                    "sections": list(summary.sections), "sources": list(summary.sources)})
        return
    console.print(f"wrote {escape(str(summary.path))} ({summary.bytes / 1e6:.1f} MB, "
                  f"{summary.n_runs} {summary.counted}(s), {len(summary.sections)} sections)",
                  highlight=False)
