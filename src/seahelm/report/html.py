"""The report page: the sections as one self-contained HTML file.

plotly.js is inlined once, in the page's head (about 4.8 MB); each figure is a ``<div>`` and
the call that draws it, written by plotly (``plotly.io.to_html`` of the figure's
specification, without the library), so the page opens from ``file://`` with no network. No
MathJax, no fonts or scripts fetched.
"""

from __future__ import annotations

import datetime as _dt
import html
from collections.abc import Sequence
from typing import Any

from ..output_files import REPORT_OF_META
from .sections import Section

__all__ = ["render_html"]

_CSS = """
body { font-family: system-ui, -apple-system, "Segoe UI", sans-serif; margin: 0 auto;
       max-width: 1200px; padding: 0 1.5em 3em; color: #222; }
header { border-bottom: 2px solid #345; margin-bottom: 1em; }
h1 { font-size: 1.5em; margin: .8em 0 .3em; }
h2 { font-size: 1.2em; margin-top: 1.6em; border-bottom: 1px solid #ccc; }
h3 { font-size: 1em; margin: 1.2em 0 .3em; }
nav a { margin-right: 1em; }
div.table { overflow-x: auto; }
table { border-collapse: collapse; margin: .6em 0; font-size: .9em; }
th, td { border: 1px solid #ccc; padding: .2em .5em; vertical-align: top; }
th { background: #eef1f5; text-align: left; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
caption { caption-side: bottom; text-align: left; font-size: .85em; color: #555; }
table.meta td:first-child { font-weight: 600; white-space: nowrap; }
table.summary td, table.diverged td, table.metrics td:first-child { white-space: nowrap; }
tr.pass td:nth-child(8) { color: #176d2c; font-weight: 600; }
tr.fail td:nth-child(8) { color: #b00020; font-weight: 600; }
tr.not-evaluated td:nth-child(8) { color: #8a6d00; }
.good { color: #176d2c; } .bad { color: #b00020; }
p.caption { font-size: .85em; color: #555; }
pre { background: #f6f8fa; padding: .8em; overflow-x: auto; font-size: .85em; }
footer { margin-top: 3em; font-size: .8em; color: #777; }
"""


def _figure_html(fig: dict[str, Any], div_id: str) -> str:
    """A figure specification as a ``<div>`` and plotly's call that draws it."""
    import plotly.io as pio

    return pio.to_html(fig, full_html=False, include_plotlyjs=False, include_mathjax=False,
                       div_id=div_id, validate=False,
                       config={"displaylogo": False, "responsive": True})


def render_html(title: str, sections: Sequence[Section], *, version: str = "",
                report_of: str = "") -> str:
    """The page of ``sections``.

    Parameters
    ----------
    title : str
        Page title.
    sections : sequence of Section
        In page order.
    version : str, optional
        The seahelm version named in the footer.
    report_of : str, optional
        The result files the page is the report of
        (:func:`seahelm.output_files.report_owner`), recorded in a meta element so that a
        report of other files is not replaced without ``--force``.

    Returns
    -------
    str
        A complete HTML document with plotly.js and every figure's data inlined.
    """
    from plotly.offline import get_plotlyjs

    esc = html.escape
    nav = " ".join(f'<a href="#{esc(s.id)}">{esc(s.title)}</a>' for s in sections)
    body = []
    n_fig = 0
    for sec in sections:
        parts = [f'<section id="{esc(sec.id)}"><h2>{esc(sec.title)}</h2>']
        for block in sec.blocks:
            if isinstance(block, str):
                parts.append(block)
            else:
                n_fig += 1
                parts.append(f'<div class="figure">{_figure_html(block, f"fig-{n_fig}")}</div>')
        parts.append("</section>")
        body.append("\n".join(parts))
    created = _dt.datetime.now(_dt.timezone.utc).replace(microsecond=0).isoformat()
    return (
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        f"<meta name=\"generator\" content=\"seahelm {esc(version)}\">\n"
        + (f"<meta name=\"{REPORT_OF_META}\" content=\"{esc(report_of)}\">\n" if report_of
           else "")
        + f"<title>{esc(title)}</title>\n<style>{_CSS}</style>\n"
        f"<script type=\"text/javascript\">{get_plotlyjs()}</script>\n</head>\n<body>\n"
        f"<header><h1>{esc(title)}</h1><nav>{nav}</nav></header>\n"
        + "\n".join(body)
        + f"\n<footer>written by seahelm {esc(version)} on {esc(created)}</footer>\n"
        "</body>\n</html>\n")
