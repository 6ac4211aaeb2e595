"""The building blocks of a report's sections: :class:`Section` and the HTML helpers (every
value escaped)."""

from __future__ import annotations

import dataclasses
import html
import math
import re
from collections.abc import Sequence
from typing import Any

import numpy as np

from .inputs import ReportData, RunSet

__all__ = ["Section", "escape", "fmt", "table", "paragraph", "subheading", "set_title",
           "section_id", "run_attrs"]


@dataclasses.dataclass
class Section:
    """One section of the page.

    Attributes
    ----------
    id : str
        The HTML id (anchor) of the section.
    title : str
        Its heading.
    blocks : list
        HTML strings (already escaped) and plotly figure specifications (dicts), in order.
    """

    id: str
    title: str
    blocks: list[Any] = dataclasses.field(default_factory=list)


# ------------------------------------------------------------------------------------------
# HTML helpers
# ------------------------------------------------------------------------------------------
def escape(value: Any) -> str:
    """``value`` as HTML text.

    Parameters
    ----------
    value : object
        Anything; shown as ``str(value)``.

    Returns
    -------
    str
    """
    return html.escape(str(value), quote=True)


def fmt(value: Any, digits: int = 5) -> str:
    """A number in ``digits`` significant digits (— for NaN and None), a bool as yes/no;
    anything else as text.

    Parameters
    ----------
    value : object
        The value.
    digits : int, optional
        Significant digits of a float.

    Returns
    -------
    str
    """
    if value is None:
        return "—"
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    if isinstance(value, (float, np.floating)):
        return "—" if not math.isfinite(float(value)) else f"{float(value):.{digits}g}"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    return str(value)


def table(header: Sequence[str] | None, rows: Sequence[Sequence[Any]], *, cls: str = "",
          row_classes: Sequence[str] | None = None, caption: str = "", digits: int = 5) -> str:
    """An HTML table, every cell escaped (numbers formatted by :func:`fmt`, right-aligned; a
    heading may break after a dot, so that a key path such as ``vessel.params.gain`` wraps).

    Parameters
    ----------
    header : sequence of str or None
        Column headings (no header row if None).
    rows : sequence of sequences
        The cells.
    cls : str, optional
        The table's CSS class.
    row_classes : sequence of str, optional
        A CSS class per row.
    caption : str, optional
        A caption under the table.
    digits : int, optional
        Significant digits of the numbers (default 5).

    Returns
    -------
    str
    """
    head = "".join(f"<th>{escape(h).replace('.', '.<wbr>')}</th>" for h in header or ())
    body = []
    for i, row in enumerate(rows):
        rc = f' class="{escape(row_classes[i])}"' if row_classes and row_classes[i] else ""
        cells = "".join(
            f'<td class="num">{escape(fmt(v, digits))}</td>'
            if (isinstance(v, (int, float, np.number)) and not isinstance(v, (bool, np.bool_)))
            or v is None else f"<td>{escape(fmt(v, digits))}</td>"
            for v in row)
        body.append(f"<tr{rc}>{cells}</tr>")
    cap = f"<caption>{escape(caption)}</caption>" if caption else ""
    klass = f' class="{escape(cls)}"' if cls else ""
    thead = f"<thead><tr>{head}</tr></thead>" if header is not None else ""
    return (f'<div class="table"><table{klass}>{cap}{thead}'
            f"<tbody>{''.join(body)}</tbody></table></div>")


def paragraph(text: str, cls: str = "") -> str:
    """A paragraph of escaped text.

    Parameters
    ----------
    text : str
        The text.
    cls : str, optional
        Its CSS class.

    Returns
    -------
    str
    """
    klass = f' class="{escape(cls)}"' if cls else ""
    return f"<p{klass}>{escape(text)}</p>"


def subheading(text: str) -> str:
    """A heading within a section.

    Parameters
    ----------
    text : str
        The heading.

    Returns
    -------
    str
    """
    return f"<h3>{escape(text)}</h3>"


def set_title(run_set: RunSet, data: ReportData) -> str:
    """The name of a batch where the report has several ("" for a report of one).

    Parameters
    ----------
    run_set : RunSet
        The batch.
    data : ReportData
        The report's data.

    Returns
    -------
    str
    """
    return run_set.name if len(data.sets) > 1 else ""


def section_id(prefix: str, run_set: RunSet, data: ReportData) -> str:
    """A section's id: ``prefix``, followed by the batch's name where there are several.

    Parameters
    ----------
    prefix : str
        What the section shows (``track``, ``timeseries``, ...).
    run_set : RunSet
        The batch.
    data : ReportData
        The report's data.

    Returns
    -------
    str
    """
    if len(data.sets) == 1:
        return prefix
    return f"{prefix}-" + re.sub(r"[^A-Za-z0-9_-]+", "-", run_set.name).strip("-")


def run_attrs(run_set: RunSet) -> dict[str, Any]:
    """The run metadata of a batch (its runs' attributes, else its metrics'), as plain values.

    Parameters
    ----------
    run_set : RunSet
        The batch.

    Returns
    -------
    dict
    """
    ds = run_set.shaped if run_set.shaped is not None else run_set.metrics
    return {} if ds is None else {str(k): (v.item() if hasattr(v, "item") else v)
                                  for k, v in ds.attrs.items()}
