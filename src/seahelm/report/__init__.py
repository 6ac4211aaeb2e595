"""An HTML report of a result: one self-contained file a person opens in a browser.

``write_report(source, target)`` reads a result file and its companions
(:mod:`~seahelm.report.inputs`), builds the sections from their Datasets
(:mod:`~seahelm.report.sections`: scenario and run metadata, per-run status, IMO criteria,
metrics; :mod:`~seahelm.report.batch`: a batch's per-run table, statistics and drawn inputs,
a sweep store; track with hull outlines, time series) and writes them as one HTML page with
plotly.js and all data inlined (:mod:`~seahelm.report.html`), atomically. Every value is
shown by the display rule of :mod:`seahelm.units` (angles in degrees, fractions in per cent),
labelled with its unit. A large batch is summarised (:mod:`~seahelm.report.signals`): at most
20 runs drawn and listed in the per-run table, time series decimated to 2000 samples, the
batch as a 5-95 % band, statistics and histograms; no table is wider than the page at
1,280 px.

plotly is imported only when a report is built.
"""

from __future__ import annotations

import dataclasses
import os
from pathlib import Path
from typing import TYPE_CHECKING

from .inputs import (
    ReportData,
    RunSet,
    combined_report_data,
    load_report_data,
    report_data_from_dataset,
)

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

__all__ = ["ReportData", "RunSet", "ReportSummary", "load_report_data", "combined_report_data",
           "report_data_from_dataset", "report_html", "write_report"]


@dataclasses.dataclass(frozen=True)
class ReportSummary:
    """What :func:`write_report` wrote.

    Attributes
    ----------
    path : pathlib.Path
        The HTML file.
    bytes : int
        Its size.
    title : str
        The page title.
    sections : tuple of str
        The section ids, in page order.
    n_runs : int
        Runs covered (over all batches; a sweep store's runs, not only those plotted; an IMO
        ensemble's samples).
    sources : tuple of str
        The files read.
    counted : str
        What ``n_runs`` counts: ``"run"``, ``"sample"`` for an IMO ensemble (its samples
        are ships, each with its manoeuvres), ``"replay"`` for a replay (one), or
        ``"encounter"`` for an encounter study.
    """

    path: Path
    bytes: int
    title: str
    sections: tuple[str, ...]
    n_runs: int
    sources: tuple[str, ...]
    counted: str = "run"


def report_html(data: ReportData) -> tuple[str, tuple[str, ...]]:
    """The page of ``data`` and its section ids.

    Parameters
    ----------
    data : ReportData
        From :func:`load_report_data` or :func:`report_data_from_dataset`.

    Returns
    -------
    (str, tuple of str)
    """
    from .. import __version__
    from ..output_files import report_owner
    from .html import render_html
    from .sections import build_sections

    sections = build_sections(data)
    return (render_html(data.title, sections, version=__version__,
                        report_of=report_owner(data.sources).removeprefix("report of ")),
            tuple(s.id for s in sections))


def write_report(source: "str | os.PathLike[str] | xr.Dataset | ReportData",
                 target: str | os.PathLike[str], *, force: bool = False,
                 option: str = "target", force_word: str = "force=True") -> ReportSummary:
    """Write the HTML report of a result to ``target`` (atomically: a failure leaves no
    partial file under that name).

    Parameters
    ----------
    source : path, xarray.Dataset or ReportData
        A result file (``result.nc``, ``<manoeuvre>-runs.nc``, ``<manoeuvre>-metrics.nc``), a
        result Dataset, or report data already read.
    target : str or os.PathLike
        The HTML file to write.
    force : bool, optional
        Replace an existing file that is not a seahelm report (default False; the output
        policy, :func:`seahelm.output_files.check_output`), or the report of other result
        files.
    option, force_word : str, optional
        How a refusal names the target and the way to force it (the CLI: ``--out``,
        ``--force``).

    Returns
    -------
    ReportSummary

    Raises
    ------
    FileNotFoundError
        If ``source`` is a path that does not exist.
    ParameterError
        If ``source`` is not a seahelm result file or sweep store, or holds no
        runs.
    """
    from ..output_files import check_output, report_owner, write_output

    named = {"option": option, "force_word": force_word}
    check_output(target, "html", force=force, **named)  # (before the work; again when written)
    if isinstance(source, ReportData):
        data = source
    elif isinstance(source, (str, os.PathLike)):
        data = load_report_data(source)
    else:
        data = report_data_from_dataset(source)
    # a report of other files is not this report's earlier output (before the page is built)
    owner = report_owner(data.sources) if data.sources else None
    check_output(target, "html", force=force, command=owner, **named)
    page, ids = report_html(data)
    encoded = page.encode("utf-8")
    path = write_output(target, lambda tmp: Path(tmp).write_bytes(encoded), "html", force=force,
                        command=owner, **named)
    return ReportSummary(path=path, bytes=len(encoded), title=data.title, sections=ids,
                         n_runs=data.n_runs, sources=data.sources,
                         counted="sample" if data.imo_ensemble is not None else
                         "replay" if data.replay is not None else
                         "encounter" if data.encounters is not None else "run")
